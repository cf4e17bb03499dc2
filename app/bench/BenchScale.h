#pragma once
/// \file BenchScale.h
/// `gale bench scale` (docs/scale.md): strong scaling of the distributed Poisson solve
/// (dist/DistributedPoisson.h) at 1, 2 and 4 ranks on the 256 x 256 x 64 box of `gale bench
/// solve`, each rank one thread, with the time per iteration split into compute, halo exchange,
/// the coarsest level's solve and CG's reductions, the bytes exchanged, and in the same run two
/// anchors: sim's one-process solver at 1 and 2 threads (shared memory) and PETSc's CG + GAMG at
/// each rank count. Each rank count runs as a child `mpirun --oversubscribe -n N gale bench
/// scale --worker`; the table goes to stdout. Only in builds with gale_dist.

#include <array>
#include <string>
#include <vector>

namespace gale::app {

struct BenchScaleOptions {
    std::string jsonPath;                   ///< if set, the table as JSON (atomically)
    std::array<int, 3> size{256, 256, 64};  ///< the box, cells
    std::vector<int> ranks{1, 2, 4};        ///< rank counts (each a child mpirun)
    double relativeTolerance = 1e-6;        ///< max-norm relative residual (GAMG: 2-norm)
    bool quick = false;                     ///< a 64 x 64 x 32 box (a CI smoke run)
    bool gamg = true;                       ///< also PETSc GAMG at each rank count
    /// Internal: this process is one rank count's child (under mpirun); prints one result line.
    bool worker = false;
    int sharedThreads = 0;  ///< worker: run sim's one-process solver with this many threads only
};

/// Runs the table. Returns 0 when the targets hold (2 ranks x 1 thread at least 0.8 of 1 rank x
/// 2 threads; gale at least 10x faster than GAMG at every rank count), EXIT_UNMET otherwise.
/// Throws std::invalid_argument on bad options, std::runtime_error when a child run fails or an
/// output cannot be written.
int runBenchScale(const BenchScaleOptions& options);

}  // namespace gale::app
