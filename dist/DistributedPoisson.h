#pragma once
/// \file DistributedPoisson.h
/// The Poisson system of sim/PoissonSolver.h solved across MPI ranks: gale's own matrix-free
/// MGPCG (McAdams, Sifakis, Teran 2010) with the horizontal plane split between ranks and PETSc
/// doing what PETSc is for (docs/scale.md):
///
///   - the decomposition: a PETSc DMDA over the (x, y) plane, whole columns on a rank, so the
///     z-line smoother, the wall layer and the stretched layers stay local; each rank's cells
///     start at a multiple of the coarsest level's spacing, so every multigrid level splits the
///     same way and no coarse cell straddles two ranks;
///   - the halos: one ghost layer per level, exchanged through a PetscSF (star forest) built on
///     gale's padded level arrays themselves, no copies into PETSc vectors;
///   - the reductions of CG (MPI_Allreduce);
///   - the coarsest level, assembled as a PETSc matrix and solved by a redundant LU on every rank
///     (PCREDUNDANT), which gathers it.
///
/// Each rank holds its subdomain of every level (sim's multigrid::Level, built by sim's own
/// buildHierarchy from the rank's part of the system) and runs sim's kernels on it: the
/// red-black sweep, the z-line sweep, the residual, the transfers. Across ranks the smoother is
/// processor-block Gauss-Seidel (the ghosts hold the neighbour's values from the exchange before
/// each sweep, as hypre's hybrid Gauss-Seidel does) and the transfers treat a rank's interfaces as
/// Neumann sides, so prolongation and restriction need no communication and stay each other's
/// transpose; pre-sweeps red-black and post-sweeps black-red keep the V-cycle symmetric. On one
/// rank it is sim's solver, to rounding (the coarsest level by PETSc's LU instead of sim's
/// Cholesky).
///
/// @code
///   // Collective: every rank of comm makes the same calls with the same system.
///   gale::dist::DistributedPoissonSolver solver(system, MPI_COMM_WORLD);
///   std::vector<double> x;  // empty: cold start
///   gale::sim::SolveReport rep = solver.solve(rhs, x, gale::sim::SolverSettings{});
///   // x: the whole solution on every rank.
/// @endcode

#include <mpi.h>

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include "sim/PoissonSolver.h"

namespace gale::dist {

/// How the (x, y) plane is split: rank r = rx + px * ry owns cells [xStart[rx], xStart[rx + 1])
/// x [yStart[ry], yStart[ry + 1]) x [0, nz) of level 0.
struct Decomposition {
    int px = 1, py = 1;
    std::vector<int> xStart, yStart;  ///< px + 1 and py + 1 cell indices, 0 first, nx / ny last
    int levels = 1;                   ///< multigrid levels every rank holds
};

/// Where one solve's time went, on this rank (seconds, wall clock) and what it sent.
struct DistributedSolveStats {
    double solveSeconds = 0;   ///< the whole solve()
    double haloSeconds = 0;    ///< ghost exchanges (PetscSF), waiting included
    double coarseSeconds = 0;  ///< the coarsest level's redundant solve (gather included)
    double reduceSeconds = 0;  ///< CG's MPI_Allreduce calls, waiting included
    double haloBytes = 0;      ///< bytes this rank sent in ghost exchanges
    long exchanges = 0;        ///< ghost exchanges
    int iterations = 0;        ///< PCG iterations
    /// solveSeconds minus the three communication parts: the rank's own kernels.
    double computeSeconds() const {
        return solveSeconds - haloSeconds - coarseSeconds - reduceSeconds;
    }
};

/// Distributed MGPCG for a sim::PoissonSystem (same operator, same boundary kinds, same criteria
/// and report as sim::PoissonSolver). Not copyable; every call is collective over the
/// communicator given at construction.
class DistributedPoissonSolver {
  public:
    /// Collective: every rank passes the same whole system; each keeps only its subdomain's
    /// levels. Requires PETSc initialised (PetscInitialize). Throws std::logic_error for a system
    /// sim::PoissonSolver would refuse, and std::runtime_error naming the PETSc call that failed.
    DistributedPoissonSolver(const sim::PoissonSystem& system, MPI_Comm comm);
    ~DistributedPoissonSolver();
    DistributedPoissonSolver(const DistributedPoissonSolver&) = delete;
    DistributedPoissonSolver& operator=(const DistributedPoissonSolver&) = delete;

    /// Solves A x = rhs (collective). rhs: the whole right-hand side (cellCount() entries, the
    /// PoissonSystem layout), the same on every rank; solution: the warm start (empty or
    /// cellCount() entries) on input, on output the whole solution on every rank, 0 in inactive
    /// cells. The same throws as sim::PoissonSolver::solve; numerical trouble is in the report,
    /// which is the same on every rank.
    sim::SolveReport solve(const std::vector<double>& rhs, std::vector<double>& solution,
                           const sim::SolverSettings& settings);

    const Decomposition& decomposition() const;
    /// Of the last solve, on this rank.
    const DistributedSolveStats& stats() const;
    int rank() const;
    int size() const;
    /// Bytes this rank's levels and PCG vectors hold.
    size_t memoryBytes() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

}  // namespace gale::dist
