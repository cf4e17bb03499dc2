/// \file PoissonBitsTest.cpp
/// The single-process solver's results to the last bit: a hash of every solution bit and the
/// iteration count of three systems (point smoothing with cut-cell-like weights and rock, z-line
/// smoothing on thin layers, a pure-Neumann box the coarse Cholesky pins), against the values
/// the solver gave before sim's multigrid learned subdomains (SubdomainShape, coarseningPlan;
/// gale_dist). A change to the kernels that moves one rounding anywhere fails here; a deliberate
/// one updates the constants and says why in its commit.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "sim/PoissonDetail.h"
#include "sim/PoissonSolver.h"

namespace {

using namespace gale::sim;

/// FNV-1a over the bytes of the solution and the iteration count.
uint64_t solutionHash(const std::vector<double>& x, int iterations) {
    uint64_t h = 1469598103934665603ull;
    auto add = [&](const void* data, size_t n) {
        const auto* b = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
    };
    add(x.data(), x.size() * sizeof(double));
    add(&iterations, sizeof iterations);
    return h;
}

/// A box with weights drawn from `seed` in [0.02, 1] (z-faces x zScale), a rock block and a
/// random right-hand side; solved to 1e-9.
uint64_t solveHash(int nx, int ny, int nz, bool zLines, float zScale, bool neumannAll,
                   uint32_t seed) {
    PoissonSystem sys = PoissonSystem::uniformBox(nx, ny, nz);
    sys.zLineSmoothing = zLines;
    sys.sides[SIDE_ZMIN] = BoundaryKind::Neumann;
    if (neumannAll)
        for (auto& s : sys.sides) s = BoundaryKind::Neumann;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> open(0.02f, 1.f);
    for (float& v : sys.weightX) v = open(rng);
    for (float& v : sys.weightY) v = open(rng);
    for (float& v : sys.weightZ) v = zScale * open(rng);
    for (int k = 0; k < nz / 3; ++k)
        for (int j = ny / 3; j < ny / 2; ++j)
            for (int i = nx / 3; i < nx / 2; ++i) {
                sys.weightX[sys.faceXIndex(i, j, k)] = sys.weightX[sys.faceXIndex(i + 1, j, k)] = 0;
                sys.weightY[sys.faceYIndex(i, j, k)] = sys.weightY[sys.faceYIndex(i, j + 1, k)] = 0;
                sys.weightZ[sys.faceZIndex(i, j, k)] = sys.weightZ[sys.faceZIndex(i, j, k + 1)] = 0;
            }
    std::vector<double> rhs(sys.cellCount());
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    double mean = 0;
    for (double& b : rhs) b = value(rng), mean += b;
    if (neumannAll)  // a compatible right-hand side for the singular system
        for (double& b : rhs) b -= mean / double(rhs.size());
    SolverSettings set;
    set.relativeTolerance = 1e-9;
    set.maxIterations = 100;
    PoissonSolver solver(sys);
    std::vector<double> x;
    const SolveReport rep = solver.solve(rhs, x, set);
    return solutionHash(x, rep.iterations);
}

/// The constants are of the row kernels' x86-64-v3 clones (AVX2, FMA; PoissonDetail.h), which a
/// machine without them does not run: there the test has nothing to compare with.
#define SKIP_WITHOUT_AVX2_FMA()                                             \
    if (!(__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))) \
        GTEST_SKIP() << "the hashes are of the AVX2/FMA kernels";

TEST(PoissonBits, PointSmoothingUnchangedToTheLastBit) {
    SKIP_WITHOUT_AVX2_FMA();
    const uint64_t h = solveHash(70, 52, 30, /*zLines=*/false, 1.f, false, 3);
    std::printf("  hash %016llx\n", static_cast<unsigned long long>(h));
    EXPECT_EQ(h, 0x65bc24d1c038c866ull);
}

TEST(PoissonBits, LineSmoothingUnchangedToTheLastBit) {
    SKIP_WITHOUT_AVX2_FMA();
    const uint64_t h = solveHash(66, 40, 24, /*zLines=*/true, 16.f, false, 4);
    std::printf("  hash %016llx\n", static_cast<unsigned long long>(h));
    EXPECT_EQ(h, 0xb344a02ab5d768ebull);
}

TEST(PoissonBits, PureNeumannUnchangedToTheLastBit) {
    SKIP_WITHOUT_AVX2_FMA();
    const uint64_t h = solveHash(30, 20, 12, /*zLines=*/false, 1.f, true, 5);
    std::printf("  hash %016llx\n", static_cast<unsigned long long>(h));
    EXPECT_EQ(h, 0xb932a634dd46c4f0ull);
}

/// Small levels smooth phase by phase, big ones slab by slab (PoissonSmoothing.cpp); both orders
/// must give the same solution to the last bit, on any machine. The same three systems with every
/// level pipelined and with every level phased.
TEST(PoissonBits, PhasedAndPipelinedSweepsGiveTheSameBits) {
    struct Case {
        int nx, ny, nz;
        bool zLines;
        float zScale;
        bool neumann;
        uint32_t seed;
    };
    for (const Case& c :
         {Case{70, 52, 30, false, 1.f, false, 3}, Case{30, 20, 12, false, 1.f, true, 5},
          Case{96, 80, 40, false, 1.f, false, 7}}) {
        multigrid::setPhasedMaxCells(0);
        const uint64_t pipelined =
            solveHash(c.nx, c.ny, c.nz, c.zLines, c.zScale, c.neumann, c.seed);
        multigrid::setPhasedMaxCells(SIZE_MAX);
        const uint64_t phased = solveHash(c.nx, c.ny, c.nz, c.zLines, c.zScale, c.neumann, c.seed);
        multigrid::setPhasedMaxCells(multigrid::PHASED_MAX_CELLS);
        EXPECT_EQ(pipelined, phased) << c.nx << " x " << c.ny << " x " << c.nz;
    }
}

}  // namespace
