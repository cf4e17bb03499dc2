// The viewer's mouse camera: untouched it is the scene's camera exactly (so screenshots match
// `gale render`), orbiting keeps the distance, zooming keeps the direction, reset goes home.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "render/OrbitCamera.h"

namespace gale::render {
namespace {

// float positions of a 10-50 m camera: a few ulps.
constexpr float POSITION_TOL = 1e-4f;

Camera home() {
    Camera c;
    c.wsPosition_m = glm::vec3(-20.0f, -30.0f, 15.0f);
    c.wsTarget_m = glm::vec3(5.0f, 2.0f, 1.0f);
    return c;
}

TEST(OrbitCamera, UntouchedIsTheSceneCameraExactly) {
    const OrbitCamera orbit(home());
    EXPECT_EQ(orbit.camera().wsPosition_m, home().wsPosition_m);
    EXPECT_EQ(orbit.camera().wsTarget_m, home().wsTarget_m);
}

TEST(OrbitCamera, OrbitKeepsDistanceAndTargetAndResetGoesHome) {
    OrbitCamera orbit(home());
    const float d0 = glm::length(home().wsPosition_m - home().wsTarget_m);
    orbit.orbit(120.0, -40.0);
    const Camera c = orbit.camera();
    EXPECT_NEAR(glm::length(c.wsPosition_m - c.wsTarget_m), d0, POSITION_TOL);
    EXPECT_GT(glm::length(c.wsPosition_m - home().wsPosition_m), 1.0f);
    EXPECT_LT(glm::length(c.wsTarget_m - home().wsTarget_m), POSITION_TOL);
    orbit.reset();
    EXPECT_EQ(orbit.camera().wsPosition_m, home().wsPosition_m);
}

TEST(OrbitCamera, ZoomMovesAlongTheViewAndElevationStaysBelowThePole) {
    OrbitCamera orbit(home());
    const glm::vec3 dir0 = glm::normalize(home().wsPosition_m - home().wsTarget_m);
    orbit.zoom(2.0);
    const Camera c = orbit.camera();
    EXPECT_LT(glm::length(c.wsPosition_m - c.wsTarget_m),
              glm::length(home().wsPosition_m - home().wsTarget_m));
    EXPECT_NEAR(glm::dot(glm::normalize(c.wsPosition_m - c.wsTarget_m), dir0), 1.0f, POSITION_TOL);
    orbit.orbit(0.0, 10000.0);
    EXPECT_LT(orbit.elevation_deg(), 89.0 + 1e-9);
    orbit.pan(10.0, 0.0, 480);
    EXPECT_GT(glm::length(orbit.camera().wsTarget_m - home().wsTarget_m), 0.0f);
}

}  // namespace
}  // namespace gale::render
