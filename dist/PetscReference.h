#pragma once
/// \file PetscReference.h
/// The anchor of `gale bench scale` (docs/scale.md): the same sim::PoissonSystem assembled as a
/// PETSc matrix (AIJ, rows split in PETSc's default contiguous blocks) and solved by CG with
/// PETSc's algebraic multigrid (PCGAMG), the standard distributed engine gale is compared with.

#include <mpi.h>

#include <vector>

#include "sim/PoissonSolver.h"

namespace gale::dist {

struct ReferenceSolve {
    double setupSeconds = 0;  ///< assembly and KSPSetUp (GAMG's hierarchy)
    double solveSeconds = 0;  ///< KSPSolve
    int iterations = 0;
    bool converged = false;
};

/// Collective over comm, every rank with the same system and right-hand side (the
/// PoissonSystem layout): CG + GAMG until the unpreconditioned 2-norm residual falls by
/// relativeTolerance (PETSc's criterion; gale's is the max norm). Inactive cells are identity
/// rows with a zero right-hand side. Throws std::runtime_error naming a failed PETSc call.
ReferenceSolve solveWithGamg(const sim::PoissonSystem& system, const std::vector<double>& rhs,
                             double relativeTolerance, MPI_Comm comm);

}  // namespace gale::dist
