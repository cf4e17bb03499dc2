#pragma once
/// \file BenchSolve.h
/// The steady solver's benchmarks (docs/solver.md has the method and the measured tables):
///  - `gale bench accuracy`: error against run time on the exact hemisphere (potential flow past
///    a sphere), over resolutions and solver tolerances, with the observed convergence order;
///  - `gale bench solve`: our MGPCG and OpenVDB's PCG side by side on the same elliptic problem,
///    with iterations, time, peak memory and the memory-bandwidth floor.
/// Tables go to stdout, progress lines to stderr.

#include <array>
#include <string>
#include <vector>

#include "sim/PoissonSolver.h"

namespace gale::app {

struct BenchAccuracyOptions {
    std::string outputFolder = "out/bench";  ///< gets accuracy.csv and accuracy.svg (atomically)
    std::string jsonPath;                    ///< if set, the table as JSON (atomically)
    /// CI smoke run: 4, 8, 16 cells per radius and one tolerance (1e-6); the full run adds 32
    /// cells per radius and the tolerances 1e-1 (WindNinja's stopping rule) and 1e-3.
    bool quick = false;
};

/// Runs the hemisphere study. Returns 0 when the targets hold (near-surface relative L2 <= 1% at
/// 16 cells per radius, observed order >= 1.5), 1 otherwise (the table is written either way).
/// Throws std::runtime_error if an output cannot be written.
int runBenchAccuracy(const BenchAccuracyOptions& options);

struct BenchSolveOptions {
    std::string jsonPath;  ///< if set, the table as JSON (atomically)
    /// Boxes nx, ny, nz; empty: 64x64x32, 128x128x64, 256x256x64.
    std::vector<std::array<int, 3>> sizes;
    bool quick = false;               ///< only the first size (CI smoke run)
    bool openVdb = true;              ///< also run openvdb::tools::poisson (Jacobi-PCG and IC-PCG)
    double relativeTolerance = 1e-6;  ///< max-norm relative residual, both solvers
};

/// Runs the side-by-side comparison; each solver runs in a forked child so its peak memory is
/// its own. Returns 0 when ours converged at every size (targets are reported, not enforced).
/// Throws std::invalid_argument on bad options, std::runtime_error on I/O failure.
int runBenchSolve(const BenchSolveOptions& options);

/// The problem of `gale bench solve` (and `gale bench scale`): a box of unit cells, the 7-point
/// Laplacian, Dirichlet 0 on the sides and top, Neumann on the ground ...
sim::PoissonSystem benchSystem(int nx, int ny, int nz);
/// ... and a deterministic pseudo-random right-hand side in [-0.5, 0.5] (every frequency
/// present: the hard case for any preconditioner), n entries.
std::vector<double> benchRhs(size_t n);

}  // namespace gale::app
