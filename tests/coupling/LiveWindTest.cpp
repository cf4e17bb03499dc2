// Live wind dropped into the running unsteady flow (coupling/LiveWind.h): each source leaves the
// motion it is named for, divergence-free, and picking finds the terrain under a ray.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <memory>

#include "base/ParameterError.h"
#include "coupling/LiveWind.h"
#include "coupling/TerrainMeshBuilder.h"
#include "sim/SteadyWind.h"
#include "sim/Vortices.h"

namespace gale::coupling {
namespace {

// Still air over flat ground, 32 x 32 m at 1 m cells, 12 m high: the sources alone move it.
struct Calm {
    sim::Heightfield hf;
    std::unique_ptr<sim::AirDomain> domain;
    std::unique_ptr<sim::UnsteadyWindSolver> solver;
    Calm() {
        sim::TerrainSpec ts;
        ts.kind = sim::TerrainKind::Flat;
        ts.sizeX_m = ts.sizeY_m = 32.0;
        ts.spacing_m = 1.0;
        ts.height_m = 0.0;
        hf = sim::makeTerrain(ts);
        sim::DomainSpec spec{1.0, {}, 1e9};
        spec.top_m = 12.0;
        domain = std::make_unique<sim::AirDomain>(hf, spec);
        sim::AmbientWind a;
        a.profile = sim::WindProfile::Uniform;
        a.speed_mps = 0.0;
        const auto steady = sim::solveSteadyWind(*domain, a, {}, {});
        sim::UnsteadySettings s;
        s.dt_s = 0.05;
        solver = std::make_unique<sim::UnsteadyWindSolver>(*domain, steady.field, s, 1.0);
    }
    std::array<double, 3> at(double x, double y, double z) const {
        return solver->field().velocityAt_mps(x, y, z);
    }
};

// The projection's tolerance leaves a residual divergence; the swirl's circulation is
// measured on 64 points and loses a little to the projection near the ground.
constexpr double CIRCULATION_FRACTION = 0.5;

TEST(LiveWind, ADroppedWhirlwindCirclesItsAxisCounterClockwise) {
    Calm c;
    LiveSource s;
    s.kind = LiveSourceKind::Whirlwind;
    s.wsAt_m = {16.0, 16.0};
    s.radius_m = 3.0;
    s.speed_mps = 6.0;
    EXPECT_NEAR(
        sim::circulationAround(c.solver->grid(), c.solver->velocity(), {16.0, 16.0}, 6.0, 4.0), 0.0,
        1e-9);
    const sim::SolveReport rep = addLiveSource(*c.solver, s);
    EXPECT_TRUE(rep.converged);
    sim::Whirlwind ww;
    ww.coreRadius_m = 3.0;
    ww.peakSpeed_mps = 6.0;
    // Independent oracle: the Lamb-Oseen circulation inside 6 m, 2 pi r v(r).
    const double expected = 2.0 * M_PI * 6.0 * ww.tangentialSpeed_mps(6.0);
    const double measured =
        sim::circulationAround(c.solver->grid(), c.solver->velocity(), {16.0, 16.0}, 6.0, 4.0);
    EXPECT_GT(measured, CIRCULATION_FRACTION * expected) << "expected about " << expected;
    EXPECT_TRUE(std::isfinite(c.solver->maxSpeed_mps()));
}

TEST(LiveWind, AGustFrontBlowsAlongTheDrag) {
    Calm c;
    LiveSource s;
    s.kind = LiveSourceKind::GustFront;
    s.wsAt_m = {16.0, 8.0};
    s.wsTo_m = {16.0, 24.0};  // a drag towards +y
    (void)addLiveSource(*c.solver, s);
    const auto u = c.at(16.0, 16.0, 1.5);
    EXPECT_GT(u[1], 1.0) << "along the drag";
    EXPECT_LT(std::abs(u[0]), 0.25 * u[1]) << "mostly along the drag";
}

TEST(LiveWind, ABlastBlowsOutwardAlongTheGroundAndADownwashFalls) {
    {
        Calm c;
        LiveSource s;
        s.kind = LiveSourceKind::Blast;
        s.wsAt_m = {16.0, 16.0};
        (void)addLiveSource(*c.solver, s);
        // Radially outward at r = R on four sides, 0.5 m above the ground.
        EXPECT_GT(c.at(19.0, 16.0, 0.5)[0], 0.5);
        EXPECT_LT(c.at(13.0, 16.0, 0.5)[0], -0.5);
        EXPECT_GT(c.at(16.0, 19.0, 0.5)[1], 0.5);
        EXPECT_LT(c.at(16.0, 13.0, 0.5)[1], -0.5);
    }
    {
        Calm c;
        LiveSource s;
        s.kind = LiveSourceKind::Downwash;
        s.wsAt_m = {16.0, 16.0};
        (void)addLiveSource(*c.solver, s);
        EXPECT_LT(c.at(16.0, 16.0, 5.0)[2], -0.5) << "falling above the point";
        // Near the ground the fall turns outward.
        EXPECT_GT(c.at(20.0, 16.0, 0.5)[0], 0.1);
        EXPECT_LT(c.at(12.0, 16.0, 0.5)[0], -0.1);
    }
}

TEST(LiveWind, BadSourcesAreParameterErrors) {
    Calm c;
    LiveSource s;
    s.speed_mps = std::nan("");
    EXPECT_THROW((void)addLiveSource(*c.solver, s), ParameterError);
    s.speed_mps = 6.0;
    s.radius_m = 0.0;
    EXPECT_THROW((void)addLiveSource(*c.solver, s), ParameterError);
    s.radius_m = 3.0;
    s.wsAt_m[0] = INFINITY;
    EXPECT_THROW((void)addLiveSource(*c.solver, s), ParameterError);
}

// A pick lands within this much of the exact intersection: the bisection's 30 halvings of half a
// mesh cell leave far less; the float positions of a 40 m terrain about 1e-5 m.
constexpr float PICK_TOLERANCE_M = 1e-3f;

TEST(LiveWind, PickingFindsTheTerrainUnderARay) {
    sim::TerrainSpec ts;
    ts.kind = sim::TerrainKind::Flat;
    ts.sizeX_m = ts.sizeY_m = 40.0;
    ts.spacing_m = 0.5;
    ts.height_m = 0.0;
    const render::TerrainMesh mesh = buildTerrainMesh(sim::makeTerrain(ts), 2.0f);
    const float ground = mesh.wsPosition_m.front().z;
    // Straight down.
    auto hit = pickTerrain(mesh, {12.3f, 7.7f, 50.0f}, {0.0f, 0.0f, -1.0f});
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->x, 12.3f, PICK_TOLERANCE_M);
    EXPECT_NEAR(hit->y, 7.7f, PICK_TOLERANCE_M);
    EXPECT_NEAR(hit->z, ground, PICK_TOLERANCE_M);
    // Slanted at 45 degrees from 10 m above (0, 20): lands 10 m further along x.
    const glm::vec3 dir = glm::normalize(glm::vec3(1.0f, 0.0f, -1.0f));
    hit = pickTerrain(mesh, {0.0f, 20.0f, ground + 10.0f}, dir);
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->x, 10.0f, PICK_TOLERANCE_M);
    // Upwards, or off the terrain's plan: nothing.
    EXPECT_FALSE(pickTerrain(mesh, {20.0f, 20.0f, 5.0f}, {0.0f, 0.0f, 1.0f}).has_value());
    EXPECT_FALSE(pickTerrain(mesh, {-30.0f, 20.0f, 5.0f}, {0.0f, 0.0f, -1.0f}).has_value());
}

}  // namespace
}  // namespace gale::coupling
