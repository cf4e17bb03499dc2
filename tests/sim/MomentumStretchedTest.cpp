/// \file MomentumStretchedTest.cpp
/// The momentum model and its surface-layer stresses (sim/MomentumTurbulence.h) on vertically
/// stretched layers (DomainSpec::firstCell_m): the log law over flat ground from 1 m up, the
/// same bits as cubic cells when every layer is h thick, a divergence-free finite field over
/// cut cells and stiff input, and a lee slower than the mass-consistent model's. Every verdict
/// is computed here from the fields.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "MomentumTestCases.h"
#include "sim/AirDomain.h"
#include "sim/Heightfield.h"
#include "sim/MomentumTurbulence.h"
#include "sim/MomentumWind.h"
#include "sim/SteadyWind.h"

namespace gale::sim {
namespace {

using testcases::expectLogLawColumn, testcases::flatGround, testcases::logWind, testcases::ridge;

/// Stretched layers: h horizontally, the first layer first_m thick, growing by ratio.
DomainSpec layers(double h_m, double first_m, double ratio = 1.2) {
    DomainSpec s;
    s.voxelSize_m = h_m;
    s.firstCell_m = first_m;
    s.stretchRatio = ratio;
    s.momentumModel = true;
    return s;
}

bool allFinite(const WindField& f) {
    for (const auto* a : {&f.u_mps(), &f.v_mps(), &f.w_mps()})
        for (double x : *a)
            if (!std::isfinite(x)) return false;
    return true;
}

/// Largest |open outflux| over the air cells (m/s x area / h^2: the AirDomain's scaled flux).
double maxDivergence(const AirDomain& d, const WindField& f) {
    double worst = 0.0;
    for (int k = 0; k < d.nz(); ++k)
        for (int j = 0; j < d.ny(); ++j)
            for (int i = 0; i < d.nx(); ++i)
                if (d.isAir(i, j, k))
                    worst = std::max(
                        worst, std::abs(d.openOutflux(f.u_mps(), f.v_mps(), f.w_mps(), i, j, k)));
    return worst;
}

class FlatGroundOnLayers : public ::testing::TestWithParam<double> {};

TEST_P(FlatGroundOnLayers, KeepsTheLogProfileFrom1To50m) {
    const double ground = GetParam(), h = 2.0;
    DomainSpec spec = layers(h, h / 4);
    spec.top_m = 62.0;
    const AirDomain domain(flatGround(ground), spec);
    ASSERT_FALSE(domain.layout().uniformZ());
    const MomentumWindResult res = solveMomentumWind(domain, logWind(5.0), {});
    EXPECT_TRUE(res.report.converged) << res.report.message;
    // Oracle: the neutral log law, 1 m to 50 m above the ground (expectLogLawColumn).
    expectLogLawColumn(domain, res.field, 5.0, ground, "layers");
}

// Ground on a level, and ground cutting the second layer (0.7 m into [0.5, 1.1] m).
INSTANTIATE_TEST_SUITE_P(MomentumStretched, FlatGroundOnLayers, ::testing::Values(0.0, 0.7));

/// The unsteady solver's unknown faces (between two air cells, or on the open box sides and top):
/// the masks TurbulentStress takes.
void faceMasks(const AirDomain& d, std::vector<uint8_t>& okX, std::vector<uint8_t>& okY,
               std::vector<uint8_t>& okZ) {
    const GridIndex& G = d.layout();
    const int nx = d.nx(), ny = d.ny(), nz = d.nz();
    okX.assign(G.count(Placement::FaceX), 0);
    okY.assign(G.count(Placement::FaceY), 0);
    okZ.assign(G.count(Placement::FaceZ), 0);
    auto air = [&](int i, int j, int k) { return d.isAir(i, j, k); };
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i <= nx; ++i)
                okX[G.faceXIndex(i, j, k)] =
                    air(std::max(i - 1, 0), j, k) && air(std::min(i, nx - 1), j, k);
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i < nx; ++i)
                okY[G.faceYIndex(i, j, k)] =
                    air(i, std::max(j - 1, 0), k) && air(i, std::min(j, ny - 1), k);
    for (int k = 1; k <= nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                okZ[G.faceZIndex(i, j, k)] = air(i, j, k - 1) && (k == nz || air(i, j, k));
}

TEST(MomentumStretched, LayersAllHThickGiveTheCubicStressStep) {
    // Stretched layers with ratio 1 and a first layer of h: level heights k h, exact in binary
    // for h = 4 (so the two layouts hold the same numbers), through the stretched code path.
    const double h = 4.0;
    const Heightfield hf = ridge(12, 40, h);
    DomainSpec cubic;
    cubic.voxelSize_m = h;
    cubic.momentumModel = true;
    const AirDomain a(hf, cubic), b(hf, layers(h, h, /*ratio=*/1.0));
    ASSERT_TRUE(a.layout().uniformZ());
    ASSERT_FALSE(b.layout().uniformZ());
    ASSERT_EQ(a.layout().zLevels_m(), b.layout().zLevels_m());
    ASSERT_EQ(a.openFractionsX(), b.openFractionsX());
    ASSERT_EQ(a.openFractionsZ(), b.openFractionsZ());
    // A sheared start: the mass-consistent field of the cubic box, on both.
    const AmbientWind wind = logWind(8.0);
    const SteadyWindResult start = solveSteadyWind(a, wind, {}, {});
    SurfaceLayerSettings s;
    s.enabled = true;
    s.roughness_m = wind.roughness_m;
    s.balanced = wind;
    std::vector<uint8_t> okX, okY, okZ;
    faceMasks(a, okX, okY, okZ);
    TurbulentStress sa(a, s, 1e-5, okX, okY, okZ), sb(b, s, 1e-5, okX, okY, okZ);
    WindField fa = start.field, fb = start.field;
    for (int step = 0; step < 3; ++step) {
        const TurbulenceReport ra = sa.apply(2.0, fa.u_mps(), fa.v_mps(), fa.w_mps());
        const TurbulenceReport rb = sb.apply(2.0, fb.u_mps(), fb.v_mps(), fb.w_mps());
        EXPECT_EQ(ra.maxFrictionVelocity_mps, rb.maxFrictionVelocity_mps);
    }
    // Level heights and spacings come out of the same arithmetic: the same bits.
    EXPECT_EQ(fa.u_mps(), fb.u_mps());
    EXPECT_EQ(fa.v_mps(), fb.v_mps());
    EXPECT_EQ(fa.w_mps(), fb.w_mps());
    EXPECT_EQ(sa.eddyViscosityZ_m2ps(), sb.eddyViscosityZ_m2ps());
}

TEST(MomentumStretched, ConvergedFieldIsDivergenceFreeAndFiniteOnCutCells) {
    // A gentle ridge whose ground cuts the layers everywhere (first layer h/4).
    const double h = 4;
    const AirDomain domain(ridge(12, 40, h), layers(h, h / 4));
    const AmbientWind wind = logWind(8.0);
    MomentumSettings ms;
    ms.maxIterations = 200;
    const MomentumWindResult res = solveMomentumWind(domain, wind, ms);
    ASSERT_TRUE(res.report.finite) << res.report.message;
    EXPECT_TRUE(res.report.converged) << res.report.message;
    EXPECT_TRUE(allFinite(res.field));
    // Oracle: the open-face flux balance of every air cell, recomputed here (bounded by the
    // projection's tolerance times U; a factor for the recurrence residual against the true one).
    constexpr double DIVERGENCE_FACTOR = 10.0;
    EXPECT_LE(maxDivergence(domain, res.field) / wind.speed_mps,
              DIVERGENCE_FACTOR * ms.finalProjection.relativeTolerance);
}

TEST(MomentumStretched, SteepRidgeSlowsTheLeeBelowMassConsistent) {
    const double H = 40, sigma = 24, h = 4;
    const Heightfield hf = ridge(H, sigma, h);
    const AirDomain domain(hf, layers(h, h / 4));
    const AmbientWind wind = logWind(10.0);
    MomentumSettings ms;
    ms.maxIterations = 120;  // the wake crosses the 500 m box twice at the default cfl
    const MomentumWindResult mom = solveMomentumWind(domain, wind, ms);
    const SteadyWindResult mc = solveSteadyWind(domain, wind, {}, {});
    ASSERT_TRUE(mom.report.finite) << mom.report.message;
    // 10 m above the lee slope (crest + sigma, where the slope is steepest).
    const double y = 1.5 * h, x = 150 + sigma, z = hf.sample(x, y) + 10.0;
    const auto vm = mom.field.velocityAt_mps(x, y, z), vc = mc.field.velocityAt_mps(x, y, z);
    EXPECT_LT(std::hypot(vm[0], vm[2]), std::hypot(vc[0], vc[2]));
}

TEST(MomentumStretched, StaysFiniteForHugeWindThinnestLayersAndACliff) {
    // A 20 m cliff, 1 m cells horizontally, layers from h/5, wind of 100 m/s at 10 m.
    Heightfield hf = makeHeightfield(61, 5, 1.0, std::vector<float>(61 * 5, 0.f));
    for (int j = 0; j < 5; ++j)
        for (int i = 25; i < 61; ++i) hf.height_m[size_t(j) * 61 + i] = 20.f;
    DomainSpec spec = layers(1.0, 0.2);
    spec.top_m = 30.0;
    const AirDomain domain(hf, spec);
    MomentumSettings ms;
    ms.maxIterations = 40;
    const MomentumWindResult res = solveMomentumWind(domain, logWind(100.0), ms);
    EXPECT_TRUE(res.report.finite) << res.report.message;
    EXPECT_TRUE(allFinite(res.field));
    for (const MomentumIteration& it : res.report.history)
        EXPECT_TRUE(std::isfinite(it.momentumResidual));
    constexpr double SPEED_BOUND_FACTOR = 5.0;  // generous: a crest speeds the flow up, never by 5x
    const double top = 100.0 * std::log(30.0 / 0.03) / std::log(10.0 / 0.03);
    for (double u : res.field.u_mps()) EXPECT_LE(std::abs(u), SPEED_BOUND_FACTOR * top);
}

}  // namespace
}  // namespace gale::sim
