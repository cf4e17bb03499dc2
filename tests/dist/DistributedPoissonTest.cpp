/// \file DistributedPoissonTest.cpp
/// The distributed solve (dist/DistributedPoisson.h) against sim's single-process solver on the
/// same system, run whole under mpirun at 1, 2 and 4 ranks (tests/dist/CMakeLists.txt): every
/// rank solves the single-process reference itself (the oracle), then the distributed solve,
/// and compares. The mass-consistent field of the hemisphere (cubic cells, the exact far field
/// on the open sides) and of a rough fractal terrain on stretched layers (z-line smoothing).

#include <gtest/gtest.h>
#include <petscsys.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <random>
#include <vector>

#include "dist/DistributedPoisson.h"
#include "sim/AirDomain.h"
#include "sim/Heightfield.h"
#include "sim/SteadyWind.h"
#include "validation/ExactSolutions.h"
#include "validation/PoissonTerrains.h"

namespace {

using namespace gale;

/// The agreement: the distributed field equals the single-process one to the solver
/// tolerance, max |du| / U <= 1e-5, with both solved to sim's default 1e-6 relative residual.
constexpr double FIELD_AGREEMENT = 1e-5;
/// Iteration counts within 2 of one process: the processor-block smoother and the interfaces'
/// Neumann-like transfers weaken the V-cycle a little where ranks meet, never by more.
constexpr int ITERATION_SLACK = 2;

int worldSize() {
    int n = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &n);
    return n;
}

bool rankZero() {
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r == 0;
}

struct Comparison {
    double maxDu = 0;  ///< max over all faces |u_dist - u_single| / U
    int iterationsSingle = 0, iterationsDist = 0;
    bool convergedSingle = false, convergedDist = false;
    int px = 0, py = 0;
};

/// Solves the domain's mass-consistent field twice, single-process and distributed.
Comparison compareSolves(const sim::AirDomain& domain, const sim::AmbientWind& ambient,
                         const sim::BoundaryPotential& boundary = {}) {
    sim::SolverSettings set;
    set.maxIterations = 200;
    sim::SteadyWindSolver single(domain);
    const sim::SteadyWindResult a = single.solve(ambient, set, boundary);

    sim::SteadyWindSolver distributed(domain);
    dist::DistributedPoissonSolver solver(distributed.system(), MPI_COMM_WORLD);
    distributed.setPoissonSolve(
        [&](const std::vector<double>& rhs, std::vector<double>& x, const sim::SolverSettings& s) {
            return solver.solve(rhs, x, s);
        });
    const sim::SteadyWindResult b = distributed.solve(ambient, set, boundary);

    Comparison c;
    c.iterationsSingle = a.report.iterations, c.convergedSingle = a.report.converged;
    c.iterationsDist = b.report.iterations, c.convergedDist = b.report.converged;
    c.px = solver.decomposition().px, c.py = solver.decomposition().py;
    const double U = ambient.speed_mps > 0 ? ambient.speed_mps : 1.0;
    auto compare = [&](const std::vector<double>& u, const std::vector<double>& v) {
        EXPECT_EQ(u.size(), v.size());
        for (size_t f = 0; f < std::min(u.size(), v.size()); ++f)
            c.maxDu = std::max(c.maxDu, std::abs(u[f] - v[f]) / U);
    };
    compare(a.field.u_mps(), b.field.u_mps());
    compare(a.field.v_mps(), b.field.v_mps());
    compare(a.field.w_mps(), b.field.w_mps());
    return c;
}

void expectAgreement(const Comparison& c) {
    EXPECT_EQ(c.px * c.py, worldSize());
    EXPECT_TRUE(c.convergedSingle);
    EXPECT_TRUE(c.convergedDist);
    EXPECT_LE(c.maxDu, FIELD_AGREEMENT);
    EXPECT_LE(std::abs(c.iterationsDist - c.iterationsSingle), ITERATION_SLACK)
        << "single " << c.iterationsSingle << ", distributed " << c.iterationsDist;
    if (rankZero())
        std::printf(
            "  %d ranks (%d x %d): iterations %d single, %d distributed; max |du| / U %.3g\n",
            worldSize(), c.px, c.py, c.iterationsSingle, c.iterationsDist, c.maxDu);
}

TEST(DistributedPoisson, HemisphereFieldEqualsSingleProcess) {
    const validation::exact::HemisphereFlow flow{1.0, 1.0, 3.0, 3.0};
    sim::TerrainSpec ts;
    ts.kind = sim::TerrainKind::Hemisphere;
    ts.sizeX_m = ts.sizeY_m = 6.0;
    ts.spacing_m = flow.R_m / 64;
    ts.radius_m = flow.R_m;
    ts.centerX_m = ts.centerY_m = 3.0;
    const sim::Heightfield hf = sim::makeTerrain(ts);
    const sim::AirDomain domain(hf, sim::DomainSpec{flow.R_m / 8, /*top_m=*/3.0});
    sim::AmbientWind ambient;
    ambient.profile = sim::WindProfile::Uniform;
    ambient.speed_mps = flow.U_mps;
    const sim::BoundaryPotential farField = [&](double x, double y, double z) {
        return flow.phi(x, y, z);
    };
    expectAgreement(compareSolves(domain, ambient, farField));
}

TEST(DistributedPoisson, RoughLayeredTerrainFieldEqualsSingleProcess) {
    const sim::Heightfield hf =
        validation::makeRoughTerrain(validation::RoughTerrainKind::Fractal, /*size_m=*/64.0,
                                     /*spacing_m=*/1.0, /*relief_m=*/10.0);
    sim::DomainSpec spec;
    spec.voxelSize_m = 1.0;
    spec.firstCell_m = 0.25;  // thin first layer: z-line smoothing
    const sim::AirDomain domain(hf, spec);
    sim::AmbientWind ambient;  // the default log profile along x
    ambient.speed_mps = 8.0;
    expectAgreement(compareSolves(domain, ambient));
}

/// The Poisson level alone, on a box whose rough weights (cut-cell-like slivers, a rock block
/// across a rank boundary) have no wind behind them: the solution agrees to the tolerance's
/// scale, and a warm start from the answer stops at once on every rank count.
TEST(DistributedPoisson, RoughWeightsSolutionEqualsSingleProcess) {
    sim::PoissonSystem sys = sim::PoissonSystem::uniformBox(40, 36, 20);
    sys.sides[sim::SIDE_ZMIN] = sim::BoundaryKind::Neumann;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> open(0.02f, 1.f);
    for (auto* w : {&sys.weightX, &sys.weightY, &sys.weightZ})
        for (float& v : *w) v = open(rng);
    // Rock: all faces of the cells in a block straddling the planes x = 20 and y = 18.
    for (int k = 0; k < 6; ++k)
        for (int j = 14; j < 22; ++j)
            for (int i = 16; i < 24; ++i) {
                sys.weightX[sys.faceXIndex(i, j, k)] = sys.weightX[sys.faceXIndex(i + 1, j, k)] = 0;
                sys.weightY[sys.faceYIndex(i, j, k)] = sys.weightY[sys.faceYIndex(i, j + 1, k)] = 0;
                sys.weightZ[sys.faceZIndex(i, j, k)] = sys.weightZ[sys.faceZIndex(i, j, k + 1)] = 0;
            }
    std::vector<double> rhs(sys.cellCount());
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    for (double& b : rhs) b = value(rng);
    sim::SolverSettings set;
    set.relativeTolerance = 1e-9;
    set.maxIterations = 200;
    sim::PoissonSolver single(sys);
    std::vector<double> xa;
    const sim::SolveReport ra = single.solve(rhs, xa, set);
    dist::DistributedPoissonSolver solver(sys, MPI_COMM_WORLD);
    std::vector<double> xb;
    const sim::SolveReport rb = solver.solve(rhs, xb, set);
    ASSERT_EQ(xa.size(), xb.size());
    double scale = 0, diff = 0;
    for (size_t c = 0; c < xa.size(); ++c)
        scale = std::max(scale, std::abs(xa[c])), diff = std::max(diff, std::abs(xa[c] - xb[c]));
    // Both at 1e-9 relative residual: the solutions agree far below 1e-6 of their size.
    constexpr double SOLUTION_AGREEMENT = 1e-6;
    EXPECT_TRUE(ra.converged);
    EXPECT_TRUE(rb.converged);
    EXPECT_LE(diff, SOLUTION_AGREEMENT * scale);
    EXPECT_LE(std::abs(rb.iterations - ra.iterations), ITERATION_SLACK)
        << "single " << ra.iterations << ", distributed " << rb.iterations;
    if (rankZero())
        std::printf("  %d ranks: iterations %d single, %d distributed; max |dx| / max |x| %.3g\n",
                    worldSize(), ra.iterations, rb.iterations, scale > 0 ? diff / scale : 0.0);
    // Warm-started from its own answer, the solve is done before its first iteration.
    const sim::SolveReport again = solver.solve(rhs, xb, set);
    EXPECT_EQ(again.iterations, 0);
    EXPECT_TRUE(again.converged);
}

}  // namespace

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0) return 1;
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0) {  // one report, rank 0's; every rank's verdict counts below
        auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
        delete listeners.Release(listeners.default_result_printer());
    }
    std::unique_ptr<tbb::global_control> threads;
    if (const char* t = std::getenv("GALE_THREADS"))
        threads = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, size_t(std::max(1, std::atoi(t))));
    int failed = RUN_ALL_TESTS() != 0 ? 1 : 0, anyFailed = 0;
    MPI_Allreduce(&failed, &anyFailed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    threads.reset();
    PetscFinalize();
    return anyFailed;
}
