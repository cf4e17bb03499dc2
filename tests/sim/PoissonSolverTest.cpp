// Tests of the reusable MGPCG solver on its own: the discrete operator against analytic answers,
// multigrid's grid-independent iteration counts, warm starts, honest non-convergence.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "SimTestUtil.h"
#include "base/Numbers.h"
#include "sim/PoissonSolver.h"

namespace gale::sim {
namespace {

using gale::PI;
/// A second-order operator quarters its error when h halves: log2 ratio 2, minus slack for the
/// pre-asymptotic range at 16 -> 32 cells.
constexpr double MIN_SECOND_ORDER = 1.8;
/// Solves in these tests go well below the discretisation error so it alone is measured.
constexpr double TIGHT_TOLERANCE = 1e-10;

using test::randomVector;

// Max error of the solve of -Laplace(u) = f on the unit cube, n^3 cells, for
//   u = sin(pi x) sin(pi y) sin(pi z)          (all sides Dirichlet u = 0), or
//   u = sin(pi x) sin(pi y) cos(pi z / 2)      (Neumann du/dz = 0 at z = 0).
double manufacturedError(int n, bool neumannBottom) {
    PoissonSystem sys = PoissonSystem::uniformBox(n, n, n);
    if (neumannBottom) sys.sides[SIDE_ZMIN] = BoundaryKind::Neumann;
    const double h = 1.0 / n;
    const double kz = neumannBottom ? 0.5 * PI : PI;
    auto exact = [&](double x, double y, double z) {
        return std::sin(PI * x) * std::sin(PI * y) *
               (neumannBottom ? std::cos(kz * z) : std::sin(kz * z));
    };
    std::vector<double> rhs(sys.cellCount()), x;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const double X = (i + 0.5) * h, Y = (j + 0.5) * h, Z = (k + 0.5) * h;
                // (A u)_c = h^2 (-Laplace u) for unit weights: A's rows are h * flux balances.
                rhs[sys.cellIndex(i, j, k)] = h * h * (2 * PI * PI + kz * kz) * exact(X, Y, Z);
            }
    PoissonSolver solver(sys);
    SolverSettings set;
    set.relativeTolerance = TIGHT_TOLERANCE;
    const SolveReport rep = solver.solve(rhs, x, set);
    EXPECT_TRUE(rep.converged) << rep.message;
    double err = 0.0;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                err = std::max(err, std::abs(x[sys.cellIndex(i, j, k)] -
                                             exact((i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h)));
    return err;
}

TEST(PoissonSolver, ManufacturedSolutionConvergesAtSecondOrderWithDirichletFaces) {
    const double e16 = manufacturedError(16, false), e32 = manufacturedError(32, false);
    EXPECT_GE(std::log2(e16 / e32), MIN_SECOND_ORDER) << "errors " << e16 << " " << e32;
}

TEST(PoissonSolver, ManufacturedSolutionConvergesAtSecondOrderWithNeumannGround) {
    const double e16 = manufacturedError(16, true), e32 = manufacturedError(32, true);
    EXPECT_GE(std::log2(e16 / e32), MIN_SECOND_ORDER) << "errors " << e16 << " " << e32;
}

TEST(PoissonSolver, OperatorIsTheWeightedSevenPointStencil) {
    PoissonSystem sys = PoissonSystem::uniformBox(3, 3, 3);
    sys.weightX[sys.faceXIndex(2, 1, 1)] = 0.25f;  // between (1,1,1) and (2,1,1)
    PoissonSolver solver(sys);
    std::vector<double> x(sys.cellCount(), 0.0), ax;
    x[sys.cellIndex(1, 1, 1)] = 1.0;
    solver.applyOperator(x, ax);
    constexpr double EXACT = 1e-12;  // small integers and a power-of-two weight: exact arithmetic
    EXPECT_NEAR(ax[sys.cellIndex(1, 1, 1)], 5.25, EXACT);
    EXPECT_NEAR(ax[sys.cellIndex(2, 1, 1)], -0.25, EXACT);
    EXPECT_NEAR(ax[sys.cellIndex(0, 1, 1)], -1.0, EXACT);
    EXPECT_NEAR(ax[sys.cellIndex(1, 1, 0)], -1.0, EXACT);
}

TEST(PoissonSolver, IterationsStayNearlyFlatAsTheGridIsRefined) {
    // McAdams et al. 2010: MGPCG's iteration count barely grows with the grid.
    constexpr int MAX_GROWTH = 3;  // extra iterations allowed from 16^3 to 64x64x32
    int its[3] = {0, 0, 0};
    const int sizes[3][3] = {{16, 16, 16}, {32, 32, 16}, {64, 64, 32}};
    for (int s = 0; s < 3; ++s) {
        PoissonSystem sys = PoissonSystem::uniformBox(sizes[s][0], sizes[s][1], sizes[s][2]);
        sys.sides[SIDE_ZMIN] = BoundaryKind::Neumann;
        PoissonSolver solver(sys);
        std::vector<double> x;
        const SolveReport rep = solver.solve(randomVector(sys.cellCount(), 7), x, SolverSettings{});
        ASSERT_TRUE(rep.converged) << rep.message;
        its[s] = rep.iterations;
    }
    EXPECT_LE(its[2], its[0] + MAX_GROWTH) << its[0] << " " << its[1] << " " << its[2];
}

TEST(PoissonSolver, WarmStartFromTheSolutionConvergesInAtMostOneIteration) {
    PoissonSystem sys = PoissonSystem::uniformBox(24, 24, 12);
    sys.sides[SIDE_ZMIN] = BoundaryKind::Neumann;
    PoissonSolver solver(sys);
    const std::vector<double> b = randomVector(sys.cellCount(), 3);
    std::vector<double> x;
    SolverSettings tight;
    tight.relativeTolerance = TIGHT_TOLERANCE;
    ASSERT_TRUE(solver.solve(b, x, tight).converged);
    SolverSettings normal;  // 1e-6: the warm start is already 1e4 times better
    const SolveReport rep = solver.solve(b, x, normal);
    EXPECT_TRUE(rep.converged);
    EXPECT_LE(rep.iterations, 1);
}

TEST(PoissonSolver, NonConvergenceIsReportedNotThrown) {
    PoissonSystem sys = PoissonSystem::uniformBox(16, 16, 16);
    PoissonSolver solver(sys);
    std::vector<double> x;
    SolverSettings set;
    set.relativeTolerance = 1e-14;
    set.maxIterations = 1;
    SolveReport rep{};
    EXPECT_NO_THROW(rep = solver.solve(randomVector(sys.cellCount(), 5), x, set));
    EXPECT_FALSE(rep.converged);
    EXPECT_EQ(rep.iterations, 1);
    EXPECT_FALSE(rep.message.empty());
}

TEST(PoissonSolver, JacobiPreconditionerReachesTheSameSolution) {
    PoissonSystem sys = PoissonSystem::uniformBox(12, 12, 12);
    sys.sides[SIDE_ZMIN] = BoundaryKind::Neumann;
    PoissonSolver solver(sys);
    const std::vector<double> b = randomVector(sys.cellCount(), 11);
    std::vector<double> xMg, xJac;
    SolverSettings set;
    set.relativeTolerance = TIGHT_TOLERANCE;
    set.maxIterations = 1000;
    ASSERT_TRUE(solver.solve(b, xMg, set).converged);
    set.useMultigrid = false;
    const SolveReport rep = solver.solve(b, xJac, set);
    ASSERT_TRUE(rep.converged) << rep.message;
    constexpr double SAME = 1e-7;  // both to 1e-10 relative residual; conditioning ~1e2
    double diff = 0, norm = 0;
    for (size_t n = 0; n < xMg.size(); ++n)
        diff = std::max(diff, std::abs(xMg[n] - xJac[n])), norm = std::max(norm, std::abs(xMg[n]));
    EXPECT_LE(diff / norm, SAME);
}

TEST(PoissonSolver, InactiveCellsStayZeroAndAreIgnored) {
    // A solid block (all its faces closed) in the middle: its cells are not unknowns.
    PoissonSystem sys = PoissonSystem::uniformBox(8, 8, 8);
    auto closeCell = [&](int i, int j, int k) {
        sys.weightX[sys.faceXIndex(i, j, k)] = sys.weightX[sys.faceXIndex(i + 1, j, k)] = 0.f;
        sys.weightY[sys.faceYIndex(i, j, k)] = sys.weightY[sys.faceYIndex(i, j + 1, k)] = 0.f;
        sys.weightZ[sys.faceZIndex(i, j, k)] = sys.weightZ[sys.faceZIndex(i, j, k + 1)] = 0.f;
    };
    for (int k = 2; k < 5; ++k)
        for (int j = 2; j < 5; ++j)
            for (int i = 2; i < 5; ++i) closeCell(i, j, k);
    PoissonSolver solver(sys);
    EXPECT_EQ(solver.activeCellCount(), size_t(512 - 27));
    std::vector<double> x;
    const SolveReport rep =
        solver.solve(std::vector<double>(sys.cellCount(), 1.0), x, SolverSettings{});
    ASSERT_TRUE(rep.converged) << rep.message;
    EXPECT_EQ(x[sys.cellIndex(3, 3, 3)], 0.0);
    for (double v : x) EXPECT_TRUE(std::isfinite(v));
}

// A malformed system or vector is the caller's bug (std::logic_error); a bad setting is a scene
// value (gale::ParameterError, a std::invalid_argument).
TEST(PoissonSolver, BadSystemThrowsNamingTheField) {
    PoissonSystem sys = PoissonSystem::uniformBox(4, 4, 4);
    sys.weightX[3] = -1.f;
    try {
        PoissonSolver s(sys);
        FAIL() << "expected std::logic_error";
    } catch (const std::logic_error& e) {
        EXPECT_NE(std::string(e.what()).find("weightX"), std::string::npos) << e.what();
    }
    PoissonSystem empty = PoissonSystem::uniformBox(4, 4, 4);
    empty.nz = 0;
    EXPECT_THROW(PoissonSolver{empty}, std::logic_error);
    PoissonSolver ok(PoissonSystem::uniformBox(4, 4, 4));
    std::vector<double> x, shortRhs(3, 1.0);
    EXPECT_THROW((void)ok.solve(shortRhs, x, SolverSettings{}), std::logic_error);
    SolverSettings bad;
    bad.relativeTolerance = 0.0;
    EXPECT_THROW((void)ok.solve(std::vector<double>(64, 1.0), x, bad), std::invalid_argument);
}

}  // namespace
}  // namespace gale::sim
