// Tests of the steady mass-consistent wind: invariants (uniform stays uniform, divergence, no flow
// into terrain), the exact hemisphere (potential flow past a sphere), warm start, extreme terrain,
// bad input, and the .vdb output.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "SimTestUtil.h"
#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/AirDomain.h"
#include "sim/SteadyWind.h"
#include "sim/VdbIO.h"
#include "validation/ExactSolutions.h"

namespace gale::sim {
namespace {

namespace exact = gale::validation::exact;

using test::tight;
using test::uniformWind;

using gale::PI;

Heightfield flat(double size_m, double spacing_m, double height_m = 0.0) {
    TerrainSpec s;
    s.kind = TerrainKind::Flat;
    s.sizeX_m = s.sizeY_m = size_m;
    s.spacing_m = spacing_m;
    Heightfield hf = makeTerrain(s);
    for (float& z : hf.height_m) z = float(height_m);
    return hf;
}

template <class F>
void expectThrowsNaming(F&& f, const std::string& fragment) {
    try {
        f();
        ADD_FAILURE() << "expected std::invalid_argument naming " << fragment;
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
}

bool allFinite(const WindField& f) {
    for (const auto* a : {&f.u_mps(), &f.v_mps(), &f.w_mps()})
        for (double v : *a)
            if (!std::isfinite(v)) return false;
    return true;
}

// --- invariants -----------------------------------------------------------------------------

TEST(SteadyWind, UniformWindOverFlatGroundStaysUniform) {
    constexpr double REL_TOL = 1e-6;  // the bound; the exact answer is u0 itself
    AirDomain domain(flat(40.0, 1.0, 3.3),
                     DomainSpec{/*voxelSize_m=*/2.0, /*top_m=*/{}, /*memoryLimit_bytes=*/1e9});
    const AmbientWind a = uniformWind(7.0, 30.0);
    const SteadyWindResult res = solveSteadyWind(domain, a, {}, SolverSettings{});
    ASSERT_TRUE(res.report.converged) << res.report.message;
    const auto u0 = a.velocityAt_mps(10.0);
    double err = 0.0;
    for (double x = 1.0; x < 40.0; x += 3.7)
        for (double y = 1.0; y < 40.0; y += 4.1)
            for (double z = 3.4; z < domain.wsTop_m(); z += 2.3) {
                const auto u = res.field.velocityAt_mps(x, y, z);
                for (int c = 0; c < 3; ++c)
                    err = std::max(err, std::abs(u[c] - u0[c]) / a.speed_mps);
            }
    EXPECT_LT(err, REL_TOL);
}

TEST(SteadyWind, LogProfileOverFlatGroundIsAlreadyDivergenceFree) {
    // A horizontal wind varying only with height has no divergence: the solve must not change it.
    constexpr double REL_TOL = 1e-6;
    AirDomain domain(flat(32.0, 1.0),
                     DomainSpec{/*voxelSize_m=*/1.0, /*top_m=*/20.0, /*memoryLimit_bytes=*/1e9});
    AmbientWind a;  // log law, 5 m/s at 10 m, z0 = 0.03 m
    a.direction_deg = 90.0;
    const SteadyWindResult res = solveSteadyWind(domain, a, {}, SolverSettings{});
    ASSERT_TRUE(res.report.converged) << res.report.message;
    for (double z : {0.5, 1.5, 5.5, 10.0, 19.5}) {
        const auto u = res.field.velocityAt_mps(16.3, 15.2, z);
        // The field samples the profile at face centres and interpolates linearly between them.
        const double zLo = std::max(0.5, std::floor(z - 0.5) + 0.5),
                     zHi = std::min(19.5, zLo + 1.0);
        const double t = std::clamp(z - zLo, 0.0, 1.0);
        const double expect = (1 - t) * a.speedAt_mps(zLo) + t * a.speedAt_mps(zHi);
        EXPECT_NEAR(u[1], expect, REL_TOL * a.speed_mps) << "z " << z;
        EXPECT_NEAR(u[0], 0.0, REL_TOL * a.speed_mps);
        EXPECT_NEAR(u[2], 0.0, REL_TOL * a.speed_mps);
    }
}

Heightfield gaussianHill(double spacing_m) {
    TerrainSpec s;
    s.kind = TerrainKind::GaussianHill;
    s.sizeX_m = s.sizeY_m = 100.0;
    s.spacing_m = spacing_m;
    s.height_m = 15.0;
    s.radius_m = 12.0;
    s.centerX_m = s.centerY_m = 50.0;
    return makeTerrain(s);
}

TEST(SteadyWind, SolvedFieldIsDivergenceFreeAndDoesNotCrossTheTerrain) {
    // Divergence: the solve's relative residual 1e-9 bounds the flux imbalance per cell.
    constexpr double MAX_DIVERGENCE = 1e-6;
    AirDomain domain(gaussianHill(0.5),
                     DomainSpec{/*voxelSize_m=*/2.0, /*top_m=*/{}, /*memoryLimit_bytes=*/1e9});
    AmbientWind a;
    a.direction_deg = 20.0;
    const SteadyWindResult res = solveSteadyWind(domain, a, {}, tight());
    ASSERT_TRUE(res.report.converged) << res.report.message;
    EXPECT_LT(res.report.maxDivergenceScaled, MAX_DIVERGENCE);
    EXPECT_TRUE(allFinite(res.field));
}

// Largest n.u / U sampled half a cell above the hill's surface (uniform 5 m/s wind).
double maxNormalSpeedNearTerrain(double voxel_m) {
    AirDomain domain(gaussianHill(0.25),
                     DomainSpec{voxel_m, /*top_m=*/{}, /*memoryLimit_bytes=*/1e9});
    const AmbientWind a = uniformWind(5.0, 20.0);
    const SteadyWindResult res = solveSteadyWind(domain, a, {}, SolverSettings{});
    EXPECT_TRUE(res.report.converged) << res.report.message;
    const Heightfield& T = domain.terrain();
    double worst = 0.0;
    for (double x = 30.0; x <= 70.0; x += 2.5)
        for (double y = 30.0; y <= 70.0; y += 2.5) {
            const double e = 0.01;
            const double dhdx = (T.sample(x + e, y) - T.sample(x - e, y)) / (2 * e);
            const double dhdy = (T.sample(x, y + e) - T.sample(x, y - e)) / (2 * e);
            const double len = std::sqrt(dhdx * dhdx + dhdy * dhdy + 1.0);
            const auto u = res.field.velocityAt_mps(x, y, T.sample(x, y) + 0.5 * voxel_m);
            worst =
                std::max(worst, std::abs((-dhdx * u[0] - dhdy * u[1] + u[2]) / len) / a.speed_mps);
        }
    return worst;
}

TEST(SteadyWind, NormalVelocityAtTheTerrainIsSmallAndVanishesWithTheCellSize) {
    // No flux crosses the closed part of any face, by construction. What the sampler returns at
    // the surface is interpolation near a cut boundary: first order in h, measured 0.137 at
    // h = 2 m and 0.075 at h = 1 m on this 15 m hill of slope up to 0.76.
    constexpr double MAX_NORMAL_SPEED_REL_AT_1M = 0.1;
    constexpr double MIN_RATIO_WHEN_H_HALVES = 1.5;  // first order would be 2
    const double e2 = maxNormalSpeedNearTerrain(2.0), e1 = maxNormalSpeedNearTerrain(1.0);
    EXPECT_LT(e1, MAX_NORMAL_SPEED_REL_AT_1M);
    EXPECT_GT(e2 / e1, MIN_RATIO_WHEN_H_HALVES) << e2 << " -> " << e1;
}

// --- the hemisphere: potential flow past a sphere, exact ------------------------------------

struct HemisphereError {
    double nearL2 = 0, nearMax = 0;
    int iterations = 0;
};

// Hemisphere of radius R = 1 m at the centre of a [0, 6]^2 x [0, 3] m box, uniform U = 1 m/s,
// a_h = a_v; the exact far field phi = U R^3 cos(theta) / (2 r^2) carried on the open faces.
HemisphereError hemisphereError(int cellsPerRadius) {
    const double R = 1.0, c = 3.0;
    AirDomain domain(test::centredHemisphere(R, c),
                     DomainSpec{R / cellsPerRadius, /*top_m=*/3.0 * R, /*memoryLimit_bytes=*/2e9});
    const gale::validation::exact::HemisphereFlow flow{R, /*U_mps=*/1.0, c, c};
    auto phi = [&](double x, double y, double z) { return flow.phi(x, y, z); };
    const SteadyWindResult res = solveSteadyWind(domain, uniformWind(1.0, 0.0), {}, tight(), phi);
    EXPECT_TRUE(res.report.converged) << res.report.message;
    HemisphereError e;
    e.iterations = res.report.iterations;
    double e2 = 0, n2 = 0;
    for (const auto& p : flow.nearPoints()) {
        const auto ue = flow.velocity(p[0], p[1], p[2]);
        const auto u = res.field.velocityAt_mps(p[0], p[1], p[2]);
        double d = 0;
        for (int q = 0; q < 3; ++q) d += (u[q] - ue[q]) * (u[q] - ue[q]), n2 += ue[q] * ue[q];
        e2 += d;
        e.nearMax = std::max(e.nearMax, std::sqrt(d));
    }
    e.nearL2 = std::sqrt(e2 / n2);
    return e;
}

TEST(SteadyWind, HemisphereNearSurfaceErrorIsSmallAndConvergesAtLeastAtOrderOnePointFive) {
    // Measured 5.5e-3 at 8 and 9.1e-4 at 16 cells per radius (docs/solver.md).
    constexpr double MAX_NEAR_L2_AT_16 = 2e-3;  // the target is 1e-2
    constexpr double MIN_ORDER = 1.5;           // the target
    const HemisphereError e8 = hemisphereError(8), e16 = hemisphereError(16);
    EXPECT_LT(e16.nearL2, MAX_NEAR_L2_AT_16);
    EXPECT_GE(std::log2(e8.nearL2 / e16.nearL2), MIN_ORDER) << e8.nearL2 << " -> " << e16.nearL2;
    EXPECT_GE(std::log2(e8.nearMax / e16.nearMax), MIN_ORDER)
        << e8.nearMax << " -> " << e16.nearMax;
}

// --- warm start -----------------------------------------------------------------------------

TEST(SteadyWind, WarmStartFromTheExactSolutionConvergesInAtMostOneIteration) {
    AirDomain domain(gaussianHill(1.0),
                     DomainSpec{/*voxelSize_m=*/2.5, /*top_m=*/{}, /*memoryLimit_bytes=*/1e9});
    SteadyWindSolver solver(domain);
    AmbientWind a;
    const SteadyWindResult first = solver.solve(a, tight());
    ASSERT_TRUE(first.report.converged);
    const SteadyWindResult again = solver.solve(a, SolverSettings{});
    EXPECT_TRUE(again.report.converged);
    EXPECT_LE(again.report.iterations, 1);
    solver.setWarmStart({});
    const SteadyWindResult cold = solver.solve(a, SolverSettings{});
    EXPECT_GT(cold.report.iterations, 1);
}

TEST(SteadyWind, IterationsOnCutCellTerrainStayNearlyFlatAsTheCellSizeHalves) {
    // MGPCG on cut cells: 8 and 9 iterations measured at h = 4 and 2 m (docs/solver.md).
    constexpr int MAX_GROWTH = 3;
    const Heightfield hill = test::centredGaussianHill(200.0, 1.0, 30.0, 25.0);
    int its[2] = {0, 0};
    const double voxels[2] = {4.0, 2.0};
    for (int n = 0; n < 2; ++n) {
        AirDomain domain(hill, DomainSpec{voxels[n], /*top_m=*/{}, /*memoryLimit_bytes=*/1e9});
        const SteadyWindResult res = solveSteadyWind(domain, AmbientWind{}, {}, SolverSettings{});
        ASSERT_TRUE(res.report.converged) << res.report.message;
        its[n] = res.report.iterations;
    }
    EXPECT_LE(its[1], its[0] + MAX_GROWTH) << its[0] << " -> " << its[1];
}

TEST(SteadyWind, AnisotropicWeightsConvergeWithinTheSupportedRange) {
    constexpr int MAX_ITERATIONS =
        40;  // r = 0.1 and 10: 15 and 13 iterations measured (docs/solver.md)
    AirDomain domain(gaussianHill(1.0),
                     DomainSpec{/*voxelSize_m=*/2.0, /*top_m=*/{}, /*memoryLimit_bytes=*/1e9});
    for (const MassConsistentWeights w : {MassConsistentWeights{1.0, std::sqrt(10.0)},
                                          MassConsistentWeights{std::sqrt(10.0), 1.0}}) {
        SolverSettings s;
        s.maxIterations = MAX_ITERATIONS;
        const SteadyWindResult res = solveSteadyWind(domain, AmbientWind{}, w, s);
        EXPECT_TRUE(res.report.converged)
            << "alphaH " << w.alphaH << " alphaV " << w.alphaV << ": " << res.report.message;
    }
    expectThrowsNaming([&] { SteadyWindSolver s(domain, {1.0, 10.0}); }, "(alpha_h / alpha_v)^2");
    expectThrowsNaming([&] { SteadyWindSolver s(domain, {0.0, 1.0}); }, "solver.alpha_h");
}

// --- extreme terrain ------------------------------------------------------------------------

void expectExtremeCaseSolves(const Heightfield& hf, double voxel_m) {
    constexpr double MAX_DIVERGENCE = 1e-4;  // relative residual 1e-6 with margin for cut cells
    AirDomain domain(hf, DomainSpec{voxel_m, /*top_m=*/{}, /*memoryLimit_bytes=*/1e9});
    AmbientWind a;
    a.speed_mps = 100.0;
    const SteadyWindResult res = solveSteadyWind(domain, a, {}, SolverSettings{});
    EXPECT_TRUE(res.report.converged) << res.report.message;
    EXPECT_TRUE(allFinite(res.field));
    EXPECT_LT(res.report.maxDivergenceScaled, MAX_DIVERGENCE);
}

TEST(SteadyWind, VerticalCliffConvergesWithFiniteValues) {
    Heightfield hf = flat(40.0, 0.25);
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i)
            if (i * hf.spacing_m > 20.3)
                hf.height_m[size_t(j) * hf.nx + i] = 12.0f;  // 12 m wall in one sample
    expectExtremeCaseSolves(hf, 1.0);
}

TEST(SteadyWind, OneVoxelSpikeConvergesWithFiniteValues) {
    Heightfield hf = flat(32.0, 0.25);
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i)
            if (std::abs(i * 0.25 - 16.0) <= 0.5 && std::abs(j * 0.25 - 16.0) <= 0.5)
                hf.height_m[size_t(j) * hf.nx + i] = 10.0f;  // 1 m wide, 10 m tall
    expectExtremeCaseSolves(hf, 1.0);
}

TEST(SteadyWind, ClosedValleyConvergesWithFiniteValues) {
    // A deep bowl enclosed on all sides: its air connects to the rest only through the top.
    Heightfield hf = flat(40.0, 0.5, 10.0);
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            const double r = std::hypot(i * 0.5 - 20.0, j * 0.5 - 20.0);
            if (r < 8.0)
                hf.height_m[size_t(j) * hf.nx + i] =
                    float(10.0 - 9.0 * (1.0 - (r / 8.0) * (r / 8.0)));
        }
    expectExtremeCaseSolves(hf, 1.0);
}

TEST(SteadyWind, CalmWindGivesAZeroField) {
    AirDomain domain(gaussianHill(2.0),
                     DomainSpec{/*voxelSize_m=*/4.0, /*top_m=*/{}, /*memoryLimit_bytes=*/1e9});
    const SteadyWindResult res =
        solveSteadyWind(domain, uniformWind(0.0, 0.0), {}, SolverSettings{});
    EXPECT_TRUE(res.report.converged);
    for (double v : res.field.u_mps()) ASSERT_EQ(v, 0.0);
}

// --- domain ---------------------------------------------------------------------------------

TEST(AirDomain, ActivatesAirOnlyAboveTheTerrain) {
    TerrainSpec ts;
    ts.kind = TerrainKind::Hemisphere;
    ts.sizeX_m = ts.sizeY_m = 8.0;
    ts.spacing_m = 0.05;
    ts.radius_m = 2.0;
    ts.centerX_m = ts.centerY_m = 4.0;
    AirDomain domain(makeTerrain(ts),
                     DomainSpec{/*voxelSize_m=*/0.5, /*top_m=*/4.0, /*memoryLimit_bytes=*/1e9});
    EXPECT_EQ(domain.nx(), 16);
    EXPECT_EQ(domain.nz(), 8);
    EXPECT_EQ(size_t(airMaskGrid(domain)->activeVoxelCount()), domain.activeCellCount());
    EXPECT_GT(domain.vdbMemory_bytes(), 0u);
    EXPECT_GT(domain.memoryEstimate_bytes(), 0u);
    // Under the dome's centre the first cells are rock; far from it all cells are air.
    EXPECT_FALSE(domain.isAir(8, 8, 2));
    EXPECT_TRUE(domain.isAir(8, 8, 4));
    EXPECT_TRUE(domain.isAir(0, 0, 0));
    for (float f : domain.openFractionsZ()) ASSERT_TRUE(f >= 0.f && f <= 1.f);
    // Cut faces: at z = 0.5 the dome's edge (r = 1.94 m) crosses the footprint [5.5, 6] x [4, 4.5]
    // of column (11, 8); over the crown (column (8, 8)) the face at z = 1.5 is wholly in rock.
    EXPECT_GT(domain.openFractionZ(11, 8, 1), 0.f);
    EXPECT_LT(domain.openFractionZ(11, 8, 1), 1.f);
    EXPECT_EQ(domain.openFractionZ(8, 8, 3), 0.f);
}

TEST(AirDomain, BadInputThrowsNamingTheParameter) {
    const Heightfield hf = flat(20.0, 1.0);
    expectThrowsNaming([&] { AirDomain d(hf, DomainSpec{0.0, {}, 1e9}); }, "solver.voxel_size_m");
    expectThrowsNaming([&] { AirDomain d(hf, DomainSpec{-1.0, {}, 1e9}); }, "solver.voxel_size_m");
    expectThrowsNaming(
        [&] {
            AirDomain d(hf, DomainSpec{std::nan(""), {}, 1e9});
        },
        "solver.voxel_size_m");
    expectThrowsNaming([&] { AirDomain d(hf, DomainSpec{100.0, {}, 1e9}); }, "solver.voxel_size_m");
    expectThrowsNaming([&] { AirDomain d(hf, DomainSpec{1.0, /*top_m=*/-1.0, 1e9}); }, "top_m");
    expectThrowsNaming([&] { AirDomain d(hf, DomainSpec{1.0, /*top_m=*/0.0, 1e9}); }, "no air");
    expectThrowsNaming(
        [&] {
            AirDomain d(hf, DomainSpec{0.01, /*top_m=*/50.0, 1e9});
        },
        "solver.memory_limit_mb");
    expectThrowsNaming(
        [&] {
            AirDomain d(hf, DomainSpec{1.0, {}, 0.0});
        },
        "solver.memory_limit_mb");
    // The typed error carries the scene's key and the value in the key's unit (MiB).
    try {
        AirDomain d(hf, DomainSpec{0.01, /*top_m=*/50.0, /*memoryLimit_bytes=*/64.0 * 1024 * 1024});
        ADD_FAILURE() << "a domain over its memory limit was built";
    } catch (const ParameterError& e) {
        EXPECT_EQ(e.key(), "solver.memory_limit_mb");
        EXPECT_EQ(e.value(), "64");
        EXPECT_NE(e.expected().find("MiB"), std::string::npos) << e.what();
    }
    Heightfield bad = hf;
    bad.height_m[5] = std::nanf("");
    expectThrowsNaming([&] { AirDomain d(bad, DomainSpec{1.0, {}, 1e9}); }, "height is not finite");
    AmbientWind a;
    a.speed_mps = -1.0;
    AirDomain d(hf, DomainSpec{2.0, {}, 1e9});
    expectThrowsNaming([&] { (void)solveSteadyWind(d, a, {}, SolverSettings{}); }, "speed_mps");
    a = AmbientWind{};
    a.roughness_m = 0.0;
    expectThrowsNaming([&] { (void)solveSteadyWind(d, a, {}, SolverSettings{}); }, "roughness_m");
}

// --- field sampling and output --------------------------------------------------------------

TEST(WindField, SamplingIsZeroBelowTheTerrainAndOutsideTheBox) {
    AirDomain domain(gaussianHill(2.0),
                     DomainSpec{/*voxelSize_m=*/4.0, /*top_m=*/{}, /*memoryLimit_bytes=*/1e9});
    const SteadyWindResult res =
        solveSteadyWind(domain, uniformWind(5.0, 0.0), {}, SolverSettings{});
    const auto below = res.field.velocityAt_mps(50.0, 50.0, 10.0);  // inside the 15 m hill
    const auto outside = res.field.velocityAt_mps(-5.0, 50.0, 20.0);
    const auto above = res.field.velocityAt_mps(50.0, 50.0, 30.0);
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(below[c], 0.0);
        EXPECT_EQ(outside[c], 0.0);
    }
    EXPECT_GT(above[0], 5.0);  // speed-up over the crest
}

TEST(WindField, ConcurrentSamplingMatchesSerialSampling) {
    AirDomain domain(gaussianHill(2.0),
                     DomainSpec{/*voxelSize_m=*/4.0, /*top_m=*/{}, /*memoryLimit_bytes=*/1e9});
    const SteadyWindResult res = solveSteadyWind(domain, AmbientWind{}, {}, SolverSettings{});
    std::vector<std::array<double, 3>> pts, serial, parallel(4000);
    for (int n = 0; n < 4000; ++n)
        pts.push_back({(n * 37) % 100 + 0.3, (n * 53) % 100 + 0.7, 5.0 + (n % 40)});
    for (const auto& p : pts) serial.push_back(res.field.velocityAt_mps(p[0], p[1], p[2]));
    tbb::parallel_for(0, 4000, [&](int n) {
        parallel[n] = res.field.velocityAt_mps(pts[n][0], pts[n][1], pts[n][2]);
    });
    EXPECT_EQ(serial, parallel);  // bit-identical: sampling is a pure function of the field
}

TEST(SteadyWind, DirectionIsWhereTheWindBlowsTowardsCounterClockwiseFromX) {
    AirDomain domain(flat(40.0, 2.0),
                     DomainSpec{/*voxelSize_m=*/4.0, /*top_m=*/{}, /*memoryLimit_bytes=*/1e9});
    const SteadyWindResult res =
        solveSteadyWind(domain, uniformWind(5.0, 90.0), {}, SolverSettings{});
    const auto u = res.field.velocityAt_mps(20.0, 20.0, 10.0);
    constexpr double REL_TOL = 1e-6;  // as for uniform flow: the solve leaves u0 unchanged
    EXPECT_NEAR(u[0], 0.0, REL_TOL * 5.0);
    EXPECT_NEAR(u[1], 5.0, REL_TOL * 5.0);
}

TEST(WindField, WritesAVdbWithVelocitySpeedAndStaggeredFaceGrids) {
    AirDomain domain(gaussianHill(2.0),
                     DomainSpec{/*voxelSize_m=*/4.0, /*top_m=*/{}, /*memoryLimit_bytes=*/1e9});
    const SteadyWindResult res =
        solveSteadyWind(domain, uniformWind(5.0, 0.0), {}, SolverSettings{});
    const std::string path = std::string(GALE_BINARY_DIR) + "/steady_wind_test.vdb";
    res.field.writeVdb(
        path, VdbMetadata{{{"case", "test"}}, {{"iterations", double(res.report.iterations)}}});
    openvdb::initialize();
    openvdb::io::File file(path);
    file.open();
    auto vel = openvdb::gridPtrCast<openvdb::Vec3SGrid>(file.readGrid("velocity"));
    auto speed = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("speed"));
    auto faces = openvdb::gridPtrCast<openvdb::Vec3SGrid>(file.readGrid("velocity_faces"));
    file.close();
    ASSERT_TRUE(vel && speed && faces);
    EXPECT_EQ(vel->getGridClass(), openvdb::GRID_UNKNOWN);
    EXPECT_EQ(vel->getVectorType(), openvdb::VEC_CONTRAVARIANT_RELATIVE);
    EXPECT_EQ(size_t(vel->activeVoxelCount()), domain.activeCellCount());
    EXPECT_DOUBLE_EQ(vel->voxelSize()[0], 4.0);
    // Voxel (0, 0, k) centre is at world (2, 2, zMin + 4k + 2).
    const auto ws = vel->indexToWorld(openvdb::Coord(0, 0, 0));
    EXPECT_DOUBLE_EQ(ws[0], 2.0);
    constexpr double FLOAT_TOL = 1e-5;  // grids store float32
    const auto c = res.field.cellVelocity_mps(3, 4, 5);
    const openvdb::Vec3s v = vel->tree().getValue(openvdb::Coord(3, 4, 5));
    EXPECT_NEAR(v[0], c[0], FLOAT_TOL * 5.0);
    EXPECT_NEAR(speed->tree().getValue(openvdb::Coord(3, 4, 5)),
                std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), FLOAT_TOL * 5.0);
    // The staggered faces: OpenVDB's staggered sampler reads the wind the grass reads, down to
    // half a cell above the hill (where closed faces hold extrapolated values), and the grid's
    // active voxels are the air's (every air cell's own voxel at least; no voxel without air).
    EXPECT_EQ(faces->getGridClass(), openvdb::GRID_STAGGERED);
    EXPECT_GE(size_t(faces->activeVoxelCount()), domain.activeCellCount());
    EXPECT_LT(size_t(faces->activeVoxelCount()),
              size_t(domain.nx() + 1) * (domain.ny() + 1) * (domain.nz() + 1));
    openvdb::tools::GridSampler<openvdb::Vec3SGrid, openvdb::tools::StaggeredBoxSampler> sampler(
        *faces);
    const Heightfield& ground = domain.terrain();
    int compared = 0;
    for (double x = 6.0; x < domain.nx() * 4.0 - 6.0; x += 3.7)
        for (double y = 6.0; y < domain.ny() * 4.0 - 6.0; y += 4.3) {
            const double z = ground.sample(x, y) + 2.0;
            const auto ours = res.field.velocityAt_mps(x, y, z);
            const openvdb::Vec3s theirs = sampler.wsSample(openvdb::Vec3d(x, y, z));
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(theirs[k], ours[k], FLOAT_TOL * 5.0) << x << ", " << y;
            ++compared;
        }
    EXPECT_GT(compared, 50);
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace gale::sim
