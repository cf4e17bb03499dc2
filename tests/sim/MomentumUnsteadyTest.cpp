/// \file MomentumUnsteadyTest.cpp
/// The unsteady solver with the surface layer's stresses (UnsteadySettings::surfaceLayer): air
/// over rough ground slows and takes the log law's shape.
#include <gtest/gtest.h>

#include <cmath>

#include "SimTestUtil.h"
#include "sim/AirDomain.h"
#include "sim/Heightfield.h"
#include "sim/SteadyWind.h"
#include "sim/SurfaceLayer.h"
#include "sim/UnsteadyWind.h"

namespace gale::sim {
namespace {

/// Largest relative gap, over the faces of one column between 1 m and topHeight_m above flat
/// ground at z = 0, between u and the log law through the lowest face's value (the wall
/// function's u*).
double logMisfit(const WindField& f, int i, int j, double z0_m, double topHeight_m) {
    const double h = f.voxelSize_m(), zp = 0.5 * h;
    const double uStar = surface::frictionVelocity_mps(f.u(i, j, 0), zp, z0_m);
    double worst = 0.0;
    for (int k = 1; (k + 0.5) * h <= topHeight_m; ++k) {
        const double z = (k + 0.5) * h;
        worst = std::max(worst,
                         std::abs(f.u(i, j, k) / surface::logLawSpeed_mps(uStar, z, z0_m) - 1.0));
    }
    return worst;
}

TEST(UnsteadyWallStress, UniformWindOverRoughGroundSlowsNearTheGroundAndApproachesTheLogLaw) {
    TerrainSpec t;
    t.kind = TerrainKind::Flat;
    t.sizeX_m = 300, t.sizeY_m = 6, t.spacing_m = 2.0;
    AirDomain domain(makeTerrain(t), {/*voxelSize_m=*/2.0, /*top_m=*/40.0});
    const double U = 5.0, z0 = 0.03;
    const SteadyWindResult mean = solveSteadyWind(domain, test::uniformWind(U), {}, test::tight());
    UnsteadySettings s;
    s.dt_s = 1.0;
    s.surfaceLayer.enabled = true;
    s.surfaceLayer.roughness_m = z0;
    UnsteadyWindSolver solver(domain, mean.field, s, U);
    // 250 m downstream of the inflow, where the boundary layer has grown for 50 s of travel.
    const int i = int(250.0 / domain.voxelSize_m()), j = domain.ny() / 2;
    constexpr double LOG_LAYER_TOP_M = 9.0;  // the lowest five faces: inside the grown layer
    const double misfitStart = logMisfit(solver.field(), i, j, z0, LOG_LAYER_TOP_M);
    const double keStart = solver.kineticEnergy_m5ps2();
    for (const StepReport& r : solver.advanceTo(30.0)) ASSERT_TRUE(r.finite);
    const double misfitEarly = logMisfit(solver.field(), i, j, z0, LOG_LAYER_TOP_M);
    for (const StepReport& r : solver.advanceTo(90.0)) ASSERT_TRUE(r.finite);
    const double misfitLate = logMisfit(solver.field(), i, j, z0, LOG_LAYER_TOP_M);
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

}  // namespace
}  // namespace gale::sim
