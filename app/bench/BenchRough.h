#pragma once
/// \file BenchRough.h
/// `gale bench rough`: the steady solve's iterations on rough, real-like terrains as the cells
/// halve (docs/solver.md, "Rough terrain"): the fractal and the sharp-feature heightmap of
/// validation/PoissonTerrains.h, 1280 m square with 10 m pixels, at 20, 10 and 5 m cells (quick: a
/// 320 m square). Table to stdout, progress lines to stderr.

#include <string>

namespace gale::app {

struct BenchRoughOptions {
    std::string jsonPath;  ///< if set, the table as JSON (atomically)
    bool quick = false;    ///< a 320 m square (16 to 64 cells per side): a CI smoke run
};

/// Runs the study. Returns EXIT_OK when every solve converged in at most 20 iterations (the
/// target of issue 12), EXIT_UNMET otherwise (the table is written either way). Throws
/// std::runtime_error if the JSON cannot be written.
int runBenchRough(const BenchRoughOptions& options);

}  // namespace gale::app
