#pragma once
/// \file ProcessGroup.h
/// `mpirun -n N gale VERB ...` (docs/scale.md): rank 0, the leader, runs the verb as a
/// one-process run does (parses the scene, builds the field through app/scene/SceneField.h,
/// prints, writes every output once, atomically); ranks 1..N-1 serve its Poisson solves: the
/// leader broadcasts each system and right-hand side, and all N ranks solve it together with
/// DistributedPoissonSolver. So every output is the leader's alone and nothing else needs to know
/// about ranks. Started without an MPI launcher (no OMPI_COMM_WORLD_SIZE, PMI_SIZE or
/// PMIX_RANK in the environment) gale does not initialise MPI at all: the same binary is the
/// one-process program, unchanged.
///
/// Failures: an error the leader reports (bad input, exit 2) ends every rank with the leader's
/// exit code and one message, the leader's. A check that fails the same way on every rank
/// (a setting out of range) is the leader's error too. A failure on one follower alone (out of
/// memory, a PETSc error) prints one line naming the rank and ends every rank through
/// MPI_Abort with exit code 2 (the leader may be waiting in a collective call).

#include <functional>
#include <vector>

#include "dist/DistributedPoisson.h"
#include "dist/PetscReference.h"
#include "sim/PoissonSolver.h"

namespace gale::dist {

/// The ranks of this run. One per process, made first thing in main.
class ProcessGroup {
  public:
    /// Initialises PETSc (and MPI) when an MPI launcher started this process, with PETSc's
    /// signal handlers off (gale's own remove its temporaries). Throws std::runtime_error when
    /// PETSc cannot start.
    ProcessGroup();
    /// Leader: tells the followers to stop (exit code 0 unless finish() said otherwise).
    /// Finalises PETSc.
    ~ProcessGroup();
    ProcessGroup(const ProcessGroup&) = delete;
    ProcessGroup& operator=(const ProcessGroup&) = delete;

    bool leader() const { return mRank == 0; }
    int size() const { return mSize; }
    /// Followers: serves the leader's solves until it stops; returns its exit code.
    int serve();
    /// Leader: the exit code the followers end with.
    void finish(int exitCode);

  private:
    int mRank = 0, mSize = 1;
    bool mPetsc = false, mFinished = false;
};

/// The leader's solve of `system` across every rank of the running group, for
/// sim::SteadyWindSolver::setPoissonSolve; empty when there is no group or it has one rank
/// (then the caller's own solver runs). The system is broadcast now and the followers build
/// their levels with the leader's; each call of the returned function broadcasts the
/// right-hand side, warm start and settings and solves collectively (the contract of
/// sim::PoissonSolver::solve). The followers drop their levels when the function is destroyed.
using PoissonSolveFunction = std::function<sim::SolveReport(
    const std::vector<double>& rhs, std::vector<double>& solution, const sim::SolverSettings&)>;
PoissonSolveFunction groupPoissonSolve(const sim::PoissonSystem& system);

/// The leader's view of the last solve groupPoissonSolve's function ran: rank 0's stats and its
/// decomposition (zeros before the first).
struct GroupSolveStats {
    DistributedSolveStats stats;
    Decomposition decomposition;
};
GroupSolveStats lastGroupSolveStats();

/// The anchor of `gale bench scale`: PETSc CG + GAMG on `system` across every rank of the group
/// (solveWithGamg; the followers receive the system and right-hand side first), from the leader.
/// Throws std::runtime_error without a group (gale started without mpirun).
ReferenceSolve groupGamgSolve(const sim::PoissonSystem& system, const std::vector<double>& rhs,
                              double relativeTolerance);

}  // namespace gale::dist
