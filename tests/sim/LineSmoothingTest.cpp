// The z-line smoother of the multigrid preconditioner (sim/PoissonLineSmoothing.cpp): each
// column's z-couplings solved exactly, and the same bits on any number of threads although the
// sweep splits every plane into column chunks.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "SimTestUtil.h"
#include "sim/PoissonSolver.h"

namespace gale::sim {
namespace {

using test::randomVector;

/// Each column is solved by one tridiagonal elimination in double precision: the residual left is
/// round-off, a few ulps of the largest term times the column's condition number (weights spread
/// over 1:16 here).
constexpr double COLUMN_SOLVE_TOLERANCE = 1e-11;

/// nx x ny x nz with z-line smoothing; weights drawn from `seed`: z-faces in [1, 16] (thin layers
/// couple strongly along z), x- and y-faces in [0.25, 1], or all 0 with `decoupled`. The lowest
/// `rockLayers` layers of every third column are rock (all their faces 0). Ground Neumann, other
/// sides Dirichlet.
PoissonSystem lineSystem(int nx, int ny, int nz, bool decoupled, int rockLayers, uint32_t seed) {
    PoissonSystem sys = PoissonSystem::uniformBox(nx, ny, nz);
    sys.zLineSmoothing = true;
    sys.sides[SIDE_ZMIN] = BoundaryKind::Neumann;
    const std::vector<double> r =
        randomVector(sys.weightX.size() + sys.weightY.size() + sys.weightZ.size(), seed);
    size_t n = 0;
    for (float& w : sys.weightX) w = decoupled ? 0.f : float(0.625 + 0.75 * r[n++]);
    for (float& w : sys.weightY) w = decoupled ? 0.f : float(0.625 + 0.75 * r[n++]);
    for (float& w : sys.weightZ) w = float(8.5 + 15.0 * r[n++]);
    auto rock = [&](int i, int j, int k) {
        return i >= 0 && j >= 0 && i < nx && j < ny && (i + nx * j) % 3 == 0 && k < rockLayers;
    };
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (!rock(i, j, k)) continue;
                sys.weightX[sys.faceXIndex(i, j, k)] = sys.weightX[sys.faceXIndex(i + 1, j, k)] =
                    0.f;
                sys.weightY[sys.faceYIndex(i, j, k)] = sys.weightY[sys.faceYIndex(i, j + 1, k)] =
                    0.f;
                sys.weightZ[sys.faceZIndex(i, j, k)] = sys.weightZ[sys.faceZIndex(i, j, k + 1)] =
                    0.f;
            }
    return sys;
}

TEST(ZLineSmoother, OneVCycleSolvesDecoupledColumnsExactly) {
    // 130 columns along x: three column chunks of the plane sweep (64, 64 and 2), threaded.
    const int nx = 130, ny = 20, nz = 14, rockLayers = 3;
    const PoissonSystem sys = lineSystem(nx, ny, nz, /*decoupled=*/true, rockLayers, 7);
    PoissonSolver solver(sys);
    ASSERT_GE(solver.levelCount(), 3);
    const std::vector<double> b = randomVector(sys.cellCount(), 3);
    std::vector<double> z;
    solver.applyPreconditioner(b, z, /*smoothingSweeps=*/1);
    // The test's own operator: with no horizontal couplings, (A z)_k of a column is
    // (lo + up) z_k - lo z_{k-1} - up z_{k+1}; the top face is Dirichlet (weight x 2, value 0
    // beyond it), the ground Neumann (no flux), rock cells are not unknowns.
    double worst = 0.0, bmax = 0.0;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            for (int k = 0; k < nz; ++k) {
                const size_t c = sys.cellIndex(i, j, k);
                const double lo = k > 0 ? sys.weightZ[sys.faceZIndex(i, j, k)] : 0.0;
                const double up =
                    (k + 1 < nz ? 1.0 : 2.0) * sys.weightZ[sys.faceZIndex(i, j, k + 1)];
                if (lo + up == 0.0) {
                    EXPECT_EQ(z[c], 0.0) << "rock cell " << i << "," << j << "," << k;
                    continue;
                }
                const double below = k > 0 ? z[sys.cellIndex(i, j, k - 1)] : 0.0;
                const double above = k + 1 < nz ? z[sys.cellIndex(i, j, k + 1)] : 0.0;
                const double az = (lo + up) * z[c] - lo * below - up * above;
                worst = std::max(worst, std::abs(az - b[c]));
                bmax = std::max(bmax, std::abs(b[c]));
            }
    EXPECT_LE(worst / bmax, COLUMN_SOLVE_TOLERANCE);
}

TEST(ZLineSmoother, SolvesGiveTheSameBitsOnOneThreadAsOnAll) {
    const PoissonSystem sys = lineSystem(150, 24, 16, /*decoupled=*/false, /*rockLayers=*/4, 13);
    const std::vector<double> rhs = randomVector(sys.cellCount(), 17);
    SolverSettings set;
    set.relativeTolerance = 1e-8;
    auto solveWith = [&](size_t threads, std::vector<double>& x) {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        PoissonSolver solver(sys);
        x.clear();
        return solver.solve(rhs, x, set);
    };
    std::vector<double> one, all;
    const SolveReport repOne = solveWith(1, one);
    const SolveReport repAll = solveWith(
        std::max<size_t>(
            2, tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)),
        all);
    ASSERT_TRUE(repOne.converged) << repOne.message;
    EXPECT_EQ(repOne.iterations, repAll.iterations);
    ASSERT_EQ(one.size(), all.size());
    for (size_t c = 0; c < one.size(); ++c) ASSERT_EQ(one[c], all[c]) << "cell " << c;
}

}  // namespace
}  // namespace gale::sim
