#pragma once
/// \file LambOseenStudy.h
/// The translating inviscid Lamb-Oseen vortex against its exact Galilean solution
/// (UnsteadyStability.h, runTranslatingVortex; the error of TranslatingVortex.h): a sequence of
/// runs, each at its cells per core and CFL, with the observed order between neighbours
/// (docs/unsteady.md, "Translating Lamb-Oseen vortex").

#include <cmath>
#include <utility>
#include <vector>

namespace gale::validation {

struct LambOseenOptions {
    /// (cells per core, CFL) of each run, in order; the quick size is 4 and 8 cells at CFL 1.
    std::vector<std::pair<int, double>> runs = {{4, 1.0}, {8, 1.0}};
};

struct LambOseenStudy {
    struct Row {
        int cellsPerCore = 0;
        double courant = 0;
        int steps = 0;
        double error = NAN;  ///< RMS |u - u_exact| / v_peak within 2 r_c at the final time
        double order = NAN;  ///< log2(previous error / error); NaN on the first row
        double keStart_m5ps2 = 0, keEnd_m5ps2 = 0, wall_s = 0;
    };
    std::vector<Row> rows;
    /// The last row's order (NaN with one row).
    double lastOrder() const { return rows.empty() ? NAN : rows.back().order; }
};

/// Runs each (cells, CFL) of the options. Throws what runTranslatingVortex throws.
LambOseenStudy runLambOseen(const LambOseenOptions& options);

}  // namespace gale::validation
