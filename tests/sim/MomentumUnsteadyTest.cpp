/// \file MomentumUnsteadyTest.cpp
/// The unsteady solver with the surface layer's stresses (UnsteadySettings::surfaceLayer): air
/// over rough ground slows and takes the log law's shape.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "SimTestUtil.h"
#include "sim/AirDomain.h"
#include "sim/Heightfield.h"
#include "sim/SteadyWind.h"
#include "sim/SurfaceLayer.h"
#include "sim/UnsteadyWind.h"

namespace gale::sim {
namespace {

/// Largest relative gap, over the faces of one column between the second layer and topHeight_m
/// above flat ground at z = 0, between u and the log law through the lowest face's value (the
/// wall function's u*, at the first layer's centre), on cubic cells or stretched layers.
double logMisfit(const WindField& f, int i, int j, double z0_m, double topHeight_m) {
    const GridLayout& L = f.layout();
    const double zp = L.zCentre_m(0);
    const double uStar = surface::frictionVelocity_mps(f.u(i, j, 0), zp, z0_m);
    double worst = 0.0;
    for (int k = 1; k < L.nz && L.zCentre_m(k) <= topHeight_m; ++k) {
        const double z = L.zCentre_m(k);
        worst = std::max(worst,
                         std::abs(f.u(i, j, k) / surface::logLawSpeed_mps(uStar, z, z0_m) - 1.0));
    }
    return worst;
}

/// Uniform wind U over flat rough ground (z0 0.03 m) in a 300 m x 6 m box with 2 m cells
/// horizontally (first_m: the first layer's thickness, stretched by 1.2; unset: cubic): slows
/// near the ground and approaches the log law 250 m downstream (logTop_m: the highest centre
/// checked).
void expectLogLayerGrows(std::optional<double> first_m, double logTop_m) {
    TerrainSpec t;
    t.kind = TerrainKind::Flat;
    t.sizeX_m = 300, t.sizeY_m = 6, t.spacing_m = 2.0;
    DomainSpec spec{/*voxelSize_m=*/2.0, /*top_m=*/40.0};
    spec.firstCell_m = first_m;
    AirDomain domain(makeTerrain(t), spec);
    ASSERT_EQ(domain.layout().uniformZ(), !first_m.has_value());
    const double U = 5.0, z0 = 0.03;
    const SteadyWindResult mean = solveSteadyWind(domain, test::uniformWind(U), {}, test::tight());
    UnsteadySettings s;
    s.dt_s = 1.0;
    s.surfaceLayer.enabled = true;
    s.surfaceLayer.roughness_m = z0;
    UnsteadyWindSolver solver(domain, mean.field, s, U);
    // 250 m downstream of the inflow, where the boundary layer has grown for 50 s of travel.
    const int i = int(250.0 / domain.voxelSize_m()), j = domain.ny() / 2;
    const double misfitStart = logMisfit(solver.field(), i, j, z0, logTop_m);
    const double keStart = solver.kineticEnergy_m5ps2();
    for (const StepReport& r : solver.advanceTo(30.0)) ASSERT_TRUE(r.finite);
    const double misfitEarly = logMisfit(solver.field(), i, j, z0, logTop_m);
    for (const StepReport& r : solver.advanceTo(90.0)) ASSERT_TRUE(r.finite);
    const double misfitLate = logMisfit(solver.field(), i, j, z0, logTop_m);
    for (const auto* a :
         {&solver.field().u_mps(), &solver.field().v_mps(), &solver.field().w_mps()})
        for (double x : *a) ASSERT_TRUE(std::isfinite(x));
    // Slows near the ground: the wall stress takes momentum out of the lowest face.
    constexpr double SLOWED_FRACTION = 0.8;  // the log law puts 1 m at 0.6 U when 17 m is at U
    EXPECT_LT(solver.field().u(i, j, 0), SLOWED_FRACTION * U);
    // Approaches the log law: the misfit falls as the layer develops and ends small.
    constexpr double LOG_SHAPE_TOLERANCE =
        0.05;  // mixing length below kappa z aloft bends the profile a little
    EXPECT_LT(misfitEarly, misfitStart);
    EXPECT_LE(misfitLate, misfitEarly);
    EXPECT_LE(misfitLate, LOG_SHAPE_TOLERANCE);
    // The ground only takes energy out: no gain over the run (the inflow replaces what it takes).
    EXPECT_LE(solver.kineticEnergy_m5ps2(), keStart);
}

TEST(UnsteadyWallStress, UniformWindOverRoughGroundSlowsNearTheGroundAndApproachesTheLogLaw) {
    constexpr double LOG_LAYER_TOP_M = 9.0;  // the lowest five faces: inside the grown layer
    expectLogLayerGrows(std::nullopt, LOG_LAYER_TOP_M);
}

TEST(UnsteadyWallStress, OnStretchedLayersTheGroundSlowsTheWindIntoTheLogLaw) {
    // Layers from h/4 = 0.5 m, growing by 1.2: the same heights checked as on cubic cells.
    constexpr double LOG_LAYER_TOP_M = 9.0;
    expectLogLayerGrows(0.5, LOG_LAYER_TOP_M);
}

}  // namespace
}  // namespace gale::sim
