// Settings that used to give silently wrong output: a default camera whose far plane cut off a
// large terrain (every frame sky, exit 0), and an explicit far plane that shows nothing.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "app/scene/SceneBuilder.h"
#include "app/scene/SceneParser.h"

namespace gale::app {
namespace {

/// A 2 km Gaussian hill at 20 m samples (101 x 101: quick to build), with small grass.
const std::string TWO_KM_TERRAIN =
    "[terrain]\nkind = \"gaussian_hill\"\nsize_m = [2000.0, 2000.0]\nspacing_m = 20.0\n"
    "height_m = 100.0\nradius_m = 300.0\n\n[grass.generated]\nsize = 64\n\n";

/// Distance from `eye` to the farthest corner of the terrain's bounding box, metres: the test's
/// own geometry, not the builder's.
double farthestCorner_m(const sim::Heightfield& f, const glm::vec3& eye) {
    double farthest = 0.0;
    for (double x : {f.originX_m, f.originX_m + f.sizeX_m()})
        for (double y : {f.originY_m, f.originY_m + f.sizeY_m()})
            for (double z : {double(f.minHeight_m()), double(f.maxHeight_m())})
                farthest = std::max(farthest, std::hypot(x - eye.x, y - eye.y, z - eye.z));
    return farthest;
}

TEST(FarPlane, TheDefaultFarPlaneReachesEveryCornerOfATwoKilometreTerrain) {
    const Scene scene = parseSceneString(TWO_KM_TERRAIN, "scene.toml");
    BuildOptions options;
    const BuiltScene built = buildScene(scene, options);
    const double farthest = farthestCorner_m(built.heightfield, built.camera.wsPosition_m);
    ASSERT_GT(farthest, 1000.0) << "the case needs a terrain beyond the old 1000 m far plane";
    EXPECT_GT(double(built.camera.far_m), farthest);
    EXPECT_TRUE(std::isfinite(built.camera.far_m));
    EXPECT_TRUE(built.warnings.empty());
}

TEST(FarPlane, ASmallTerrainKeepsTheDefaultThousandMetres) {
    const Scene scene =
        parseSceneString("[terrain]\nsize_m = [40.0, 40.0]\nspacing_m = 0.5\n", "scene.toml");
    const BuiltScene built = buildScene(scene);
    EXPECT_FLOAT_EQ(built.camera.far_m, 1000.f);
}

TEST(FarPlane, AnExplicitFarPlaneBeforeAllOfTheTerrainIsAWarningAtItsLine) {
    const Scene scene = parseSceneString(TWO_KM_TERRAIN +
                                             "[camera]\nposition_m = [-5000.0, 1000.0, 200.0]\n"
                                             "target_m = [1000.0, 1000.0, 0.0]\nfar_m = 2000.0\n",
                                         "scene.toml");
    const BuiltScene built = buildScene(scene);
    ASSERT_EQ(built.warnings.size(), 1u);
    const std::string& w = built.warnings.front();
    EXPECT_NE(w.find("scene.toml:14: camera.far_m"), std::string::npos) << w;
    EXPECT_NE(w.find("only sky"), std::string::npos) << w;
    EXPECT_FLOAT_EQ(built.camera.far_m, 2000.f) << "an explicit far plane is kept as written";
}

TEST(FarPlane, AnExplicitFarPlaneThatReachesTheTerrainIsNoWarning) {
    const Scene scene = parseSceneString(TWO_KM_TERRAIN +
                                             "[camera]\nposition_m = [-5000.0, 1000.0, 200.0]\n"
                                             "target_m = [1000.0, 1000.0, 0.0]\nfar_m = 9000.0\n",
                                         "scene.toml");
    EXPECT_TRUE(buildScene(scene).warnings.empty());
}

}  // namespace
}  // namespace gale::app
