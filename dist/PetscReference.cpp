/// \file PetscReference.cpp
/// PETSc GAMG on a sim::PoissonSystem (PetscReference.h).

#include "dist/PetscReference.h"

#include <petscksp.h>

#include <chrono>
#include <stdexcept>
#include <string>

namespace gale::dist {

namespace {
void check(PetscErrorCode code, const char* call) {
    if (code != 0)
        throw std::runtime_error(std::string("PETSc: ") + call + " failed with error " +
                                 std::to_string(int(code)));
}
double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

ReferenceSolve solveWithGamg(const sim::PoissonSystem& s, const std::vector<double>& rhs,
                             double relativeTolerance, MPI_Comm comm) {
    ReferenceSolve out;
    const auto t0 = std::chrono::steady_clock::now();
    const PetscInt n = PetscInt(s.cellCount());
    Mat A = nullptr;
    check(MatCreateAIJ(comm, PETSC_DECIDE, PETSC_DECIDE, n, n, 7, nullptr, 6, nullptr, &A),
          "MatCreateAIJ");
    PetscInt begin = 0, end = 0;
    check(MatGetOwnershipRange(A, &begin, &end), "MatGetOwnershipRange");
    // The operator of sim/PoissonSolver.h: boundary faces x 2 (Dirichlet) or 0 (Neumann).
    auto side = [&](int which) {
        return s.sides[size_t(which)] == sim::BoundaryKind::Dirichlet ? 2.0 : 0.0;
    };
    for (PetscInt row = begin; row < end; ++row) {
        const int i = int(row % s.nx), j = int((row / s.nx) % s.ny),
                  k = int(row / (PetscInt(s.nx) * s.ny));
        const double w[6] = {
            s.weightX[s.faceXIndex(i, j, k)] * (i == 0 ? side(sim::SIDE_XMIN) : 1.0),
            s.weightX[s.faceXIndex(i + 1, j, k)] * (i + 1 == s.nx ? side(sim::SIDE_XMAX) : 1.0),
            s.weightY[s.faceYIndex(i, j, k)] * (j == 0 ? side(sim::SIDE_YMIN) : 1.0),
            s.weightY[s.faceYIndex(i, j + 1, k)] * (j + 1 == s.ny ? side(sim::SIDE_YMAX) : 1.0),
            s.weightZ[s.faceZIndex(i, j, k)] * (k == 0 ? side(sim::SIDE_ZMIN) : 1.0),
            s.weightZ[s.faceZIndex(i, j, k + 1)] * (k + 1 == s.nz ? side(sim::SIDE_ZMAX) : 1.0)};
        double d = 0;
        for (double v : w) d += v;
        if (!(d > 0)) {
            check(MatSetValue(A, row, row, 1.0, INSERT_VALUES), "MatSetValue");
            continue;
        }
        check(MatSetValue(A, row, row, d, INSERT_VALUES), "MatSetValue");
        const PetscInt nb[6] = {i > 0 ? row - 1 : -1,
                                i + 1 < s.nx ? row + 1 : -1,
                                j > 0 ? row - s.nx : -1,
                                j + 1 < s.ny ? row + s.nx : -1,
                                k > 0 ? row - PetscInt(s.nx) * s.ny : -1,
                                k + 1 < s.nz ? row + PetscInt(s.nx) * s.ny : -1};
        for (int f = 0; f < 6; ++f)
            if (nb[f] >= 0 && w[f] != 0.0)
                check(MatSetValue(A, row, nb[f], -w[f], INSERT_VALUES), "MatSetValue");
    }
    check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    Vec b = nullptr, x = nullptr;
    check(MatCreateVecs(A, &x, &b), "MatCreateVecs");
    PetscScalar* a = nullptr;
    check(VecGetArray(b, &a), "VecGetArray");
    for (PetscInt row = begin; row < end; ++row) a[row - begin] = rhs[size_t(row)];
    check(VecRestoreArray(b, &a), "VecRestoreArray");
    KSP ksp = nullptr;
    check(KSPCreate(comm, &ksp), "KSPCreate");
    check(KSPSetOperators(ksp, A, A), "KSPSetOperators");
    check(KSPSetType(ksp, KSPCG), "KSPSetType");
    check(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
    check(KSPSetTolerances(ksp, relativeTolerance, 0.0, PETSC_DEFAULT, 500), "KSPSetTolerances");
    PC pc = nullptr;
    check(KSPGetPC(ksp, &pc), "KSPGetPC");
    check(PCSetType(pc, PCGAMG), "PCSetType(PCGAMG)");
    check(KSPSetUp(ksp), "KSPSetUp");
    out.setupSeconds = since(t0);
    const auto t1 = std::chrono::steady_clock::now();
    check(KSPSolve(ksp, b, x), "KSPSolve");
    out.solveSeconds = since(t1);
    PetscInt its = 0;
    KSPConvergedReason reason;
    check(KSPGetIterationNumber(ksp, &its), "KSPGetIterationNumber");
    check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
    out.iterations = int(its);
    out.converged = reason > 0;
    KSPDestroy(&ksp);
    VecDestroy(&b);
    VecDestroy(&x);
    MatDestroy(&A);
    return out;
}

}  // namespace gale::dist
