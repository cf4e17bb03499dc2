#pragma once
/// \file BenchUnsteady.h
/// The unsteady wind's benchmarks (docs/unsteady.md has the method and the measured tables):
///  - `gale bench stability`: the named extreme cases of validation/UnsteadyStability.h as a table
///    (case, steps, dt, CFL, kinetic energy budget, deviation from the steady start, divergence,
///    finiteness), the translating Lamb-Oseen vortex's errors and orders (h at fixed CFL, dt at
///    fixed h) and Burgers' vortex core, judged by the bench's own rules;
///  - `gale bench unsteady`: error against wall time on the exact viscous Lamb-Oseen vortex for
///    each advection scheme over resolutions and time steps (CSV + SVG via app/bench/SvgPlot,
///    observed orders), and the time per step and its parts over a hill at 128x128x48 (and
///    256x256x48).
/// Tables go to stdout, progress lines to stderr.

#include <string>

namespace gale::app {

struct BenchStabilityOptions {
    bool quick = false;    ///< only the fast subset (what sim_tests runs)
    std::string jsonPath;  ///< if set, the table as JSON (atomically)
};

/// Returns EXIT_OK when every rule holds, EXIT_UNMET otherwise. Throws std::runtime_error if the
/// JSON cannot be written.
int runBenchStability(const BenchStabilityOptions& options);

struct BenchUnsteadyOptions {
    std::string outputFolder = "out/bench";  ///< gets unsteady_accuracy.csv and .svg (atomically)
    std::string jsonPath;                    ///< if set, both tables as JSON (atomically)
    /// CI smoke run: 2, 4 cells per core radius and a 48x48x16 timing box; the full run adds 8
    /// and 16 cells per core, a larger step at the finest, and 128x128x48 and 256x256x48 boxes.
    bool quick = false;
};

/// Returns 0 when every run stayed finite, the error falls with resolution for every scheme
/// (order > 0.5) and (full run) the finest semi-Lagrangian error is below 5 % of the peak speed;
/// 1 otherwise (tables written either way).
int runBenchUnsteady(const BenchUnsteadyOptions& options);

}  // namespace gale::app
