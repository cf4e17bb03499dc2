// Views of the field (coupling/FieldOverlayBuilder): uniform wind gives identical arrows, the RK2
// streamline integrator moves a point by u dt in uniform flow and stays on circles in rotation,
// and the Q-criterion (Hunt, Wray, Moin 1988) separates rotation from strain.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <memory>

#include "coupling/FieldOverlayBuilder.h"
#include "coupling/TerrainMeshBuilder.h"
#include "sim/Heightfield.h"
#include "sim/WindField.h"

using namespace gale;

namespace {

// Float storage of positions and vectors: a few ulps of 1-10 m values.
constexpr float VECTOR_TOL = 1e-5f;
// The midpoint rule grows the radius in solid-body rotation by (w dt)^4 / 8 per step (about 3e-9
// here): 500 steps stay far inside this relative error.
constexpr double ROTATION_RADIUS_TOL = 1e-4;

struct Uniform {
    std::shared_ptr<sim::Heightfield> terrain;
    render::TerrainMesh mesh;
    sim::WindField field;
    static constexpr double U = 3.0, V = 1.0;

    Uniform() {
        sim::TerrainSpec spec;
        spec.kind = sim::TerrainKind::Flat;
        spec.sizeX_m = spec.sizeY_m = 16.0;
        spec.spacing_m = 1.0;
        terrain = std::make_shared<sim::Heightfield>(sim::makeTerrain(spec));
        mesh = coupling::buildTerrainMesh(*terrain, /*tile_m=*/2.0, /*stride=*/1);
        const int n = 16, nz = 8;
        field = sim::WindField(n, n, nz, 1.0, {0.0, 0.0, 0.0}, terrain,
                               std::vector<uint8_t>(size_t(n) * n * nz, 1));
        std::fill(field.u_mps().begin(), field.u_mps().end(), U);
        std::fill(field.v_mps().begin(), field.v_mps().end(), V);
    }
};

TEST(FieldOverlayBuilder, UniformWindOverFlatGroundGivesIdenticalArrows) {
    Uniform s;
    coupling::OverlaySpec spec;
    spec.arrows = true;
    spec.arrowSpacing_m = 2.0;
    const render::FieldOverlayData data = coupling::buildFieldOverlay(s.field, s.mesh, spec, 0.5);
    ASSERT_EQ(data.arrows.size(), 64u);  // 16 m / 2 m = 8 a side
    const float speed = float(std::hypot(Uniform::U, Uniform::V));
    for (const render::OverlayArrow& a : data.arrows) {
        EXPECT_NEAR(a.speed, speed, VECTOR_TOL);
        EXPECT_NEAR(a.wsVector_m.x, data.arrows[0].wsVector_m.x, VECTOR_TOL);
        EXPECT_NEAR(a.wsVector_m.y, data.arrows[0].wsVector_m.y, VECTOR_TOL);
        EXPECT_NEAR(a.wsVector_m.z, 0.0f, VECTOR_TOL);
        EXPECT_NEAR(a.wsBase_m.z, 1.25f * 0.5f, VECTOR_TOL);  // default: just above the tips
    }
    // Along the wind, and 0.85 spacing long at the top of the colour map.
    const glm::vec3 d = glm::normalize(data.arrows[0].wsVector_m);
    EXPECT_NEAR(d.x, Uniform::U / speed, VECTOR_TOL);
    EXPECT_NEAR(glm::length(data.arrows[0].wsVector_m), 0.85f * 2.0f * speed / data.speedMax,
                VECTOR_TOL);
    EXPECT_GE(data.speedMax, speed);
}

// The automatic colour scale of a run only grows: a calmer frame after a windy one keeps the
// windy top (and the arrows shrink with it); a fixed speed_max_mps is never touched.
TEST(FieldOverlayBuilder, TheLegendNamesTheQuantityAndItsHeightsAboveTheGround) {
    Uniform s;
    coupling::OverlaySpec spec;
    spec.arrows = true;
    spec.slice = true;
    spec.sliceHeight_m = 2.0;
    // Arrows at their default, 1.25 x the grass height of 0.5 m.
    render::FieldOverlayData data = coupling::buildFieldOverlay(s.field, s.mesh, spec, 0.5);
    EXPECT_EQ(data.quantity, "wind speed");
    EXPECT_EQ(data.where, "slice 2 m, arrows 0.625 m above ground");
    spec.arrows = false;
    EXPECT_EQ(coupling::buildFieldOverlay(s.field, s.mesh, spec, 0.5).where, "2 m above ground");
    spec.arrows = true;
    spec.slice = false;
    spec.arrowHeight_m = 1.5;
    EXPECT_EQ(coupling::buildFieldOverlay(s.field, s.mesh, spec, 0.5).where, "1.5 m above ground");
}

TEST(FieldOverlayBuilder, AutomaticScaleHoldsItsLargestTopOverARun) {
    Uniform windy, calm;
    for (double& u : calm.field.u_mps()) u *= 0.25;
    for (double& v : calm.field.v_mps()) v *= 0.25;
    coupling::OverlaySpec spec;
    spec.arrows = true;
    spec.arrowSpacing_m = 2.0;
    const float calmAlone = coupling::buildFieldOverlay(calm.field, calm.mesh, spec, 0.5).speedMax;
    coupling::OverlayScaleKeeper keeper;
    const render::FieldOverlayData first =
        coupling::buildFieldOverlay(windy.field, windy.mesh, keeper.frame(spec), 0.5);
    keeper.seen(first);
    const render::FieldOverlayData second =
        coupling::buildFieldOverlay(calm.field, calm.mesh, keeper.frame(spec), 0.5);
    keeper.seen(second);
    EXPECT_LT(calmAlone, first.speedMax);        // on its own the calm frame would rescale...
    EXPECT_EQ(second.speedMax, first.speedMax);  // ...within the run it keeps the windy top
    EXPECT_NEAR(glm::length(second.arrows[0].wsVector_m),
                0.25f * glm::length(first.arrows[0].wsVector_m), VECTOR_TOL);
    spec.speedMax_mps = 2.0;
    EXPECT_EQ(
        coupling::buildFieldOverlay(windy.field, windy.mesh, keeper.frame(spec), 0.5).speedMax,
        2.0f);
}

TEST(FieldOverlayBuilder, StreamlinesInUniformWindAreStraightAndCrossTheTerrain) {
    Uniform s;
    coupling::OverlaySpec spec;
    spec.streamlines = true;
    spec.streamlineCount = 4;
    spec.sliceHeight_m = 2.0;
    const render::FieldOverlayData data = coupling::buildFieldOverlay(s.field, s.mesh, spec, 0.5);
    ASSERT_EQ(data.streamlines.size(), 4u);
    for (const render::OverlayPolyline& line : data.streamlines) {
        const glm::vec3 a = line.wsPoint_m.front(), b = line.wsPoint_m.back();
        EXPECT_NEAR(a.x, 0.25f, VECTOR_TOL);  // seeded on the upstream (west) edge
        // Carried until it leaves the 16 m box, through the east or the north side.
        EXPECT_TRUE(b.x > 15.0f || b.y > 15.0f) << b.x << ", " << b.y;
        // Straight along (U, V): the cross product with the wind vanishes.
        const glm::vec2 along(b.x - a.x, b.y - a.y);
        EXPECT_NEAR(along.x * Uniform::V - along.y * Uniform::U, 0.0, 1e-3);
    }
}

TEST(FieldOverlayBuilder, Rk2StepMovesByUDtInUniformFlow) {
    const glm::dvec3 u(2.0, -1.0, 0.5);
    const coupling::VelocityFn uniform = [&](const glm::dvec3&) { return u; };
    const glm::dvec3 x0(1.0, 2.0, 3.0);
    const glm::dvec3 x1 = coupling::rk2Step(uniform, x0, 0.25);
    EXPECT_DOUBLE_EQ(x1.x, x0.x + 0.25 * u.x);
    EXPECT_DOUBLE_EQ(x1.y, x0.y + 0.25 * u.y);
    EXPECT_DOUBLE_EQ(x1.z, x0.z + 0.25 * u.z);
}

TEST(FieldOverlayBuilder, StreamlineInSolidBodyRotationStaysOnItsCircle) {
    const double w = 0.5;  // rad/s
    const coupling::VelocityFn rotation = [&](const glm::dvec3& p) {
        return glm::dvec3(-w * p.y, w * p.x, 0.0);
    };
    const auto line = coupling::traceStreamline(rotation, glm::dvec3(4.0, 0.0, 1.0), 0.05, 500);
    ASSERT_EQ(line.size(), 500u);
    for (const glm::dvec3& p : line)
        EXPECT_NEAR(std::hypot(p.x, p.y), 4.0, ROTATION_RADIUS_TOL * 4.0);
}

TEST(FieldOverlayBuilder, QCriterionIsRotationSquaredForSolidBodyAndNegativeForStrain) {
    const double w = 2.0;
    // u = (-w y, w x, 0): du/dy = -w, dv/dx = w.
    EXPECT_DOUBLE_EQ(coupling::qCriterion({{{0, -w, 0}, {w, 0, 0}, {0, 0, 0}}}), w * w);
    // Pure strain u = (a x, -a y, 0).
    EXPECT_LT(coupling::qCriterion({{{1.0, 0, 0}, {0, -1.0, 0}, {0, 0, 0}}}), 0.0);
    // Simple shear u = (g y, 0, 0) has as much rotation as strain: Q = 0.
    EXPECT_NEAR(coupling::qCriterion({{{0, 3.0, 0}, {0, 0, 0}, {0, 0, 0}}}), 0.0, 1e-12);
}

TEST(FieldOverlayBuilder, IrrotationalUniformWindMarksNoVortexCores) {
    Uniform s;
    coupling::OverlaySpec spec;
    spec.vortexCores = true;
    EXPECT_TRUE(coupling::buildFieldOverlay(s.field, s.mesh, spec, 0.5).vortexCores.empty());
}

TEST(FieldOverlayBuilder, BadSpecNamesTheKey) {
    coupling::OverlaySpec spec;
    spec.sliceHeight_m = 0.0;
    try {
        coupling::validate(spec);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("overlay.slice_height_m"), std::string::npos);
    }
}

}  // namespace
