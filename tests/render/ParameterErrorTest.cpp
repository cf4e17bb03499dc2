// A bad scene value given to the renderer throws gale::ParameterError carrying the scene's dotted
// key (docs/scene-format.md) and the value; data the program builds itself (meshes, wind, density
// maps) that break a precondition throw std::logic_error, never a std::invalid_argument
// (docs/architecture.md, "Errors").
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "ParameterErrorCheck.h"
#include "RenderTestUtil.h"
#include "base/ParameterError.h"
#include "render/Animation.h"
#include "render/Bend.h"
#include "render/DensityMap.h"
#include "render/FieldOverlay.h"
#include "render/GlContext.h"
#include "render/GrassTexture.h"
#include "render/RenderLimits.h"
#include "render/ShellRenderer.h"

namespace gale::render {
namespace {

using gale::test::logicErrorOf;
using gale::test::thrownBy;

constexpr float NaNf = std::numeric_limits<float>::quiet_NaN();

TEST(ParameterError, ShellRendererNamesTheGrassAndLightingKeys) {
    auto context = createOsMesaContext(16, 16);
    ShellRenderer renderer(*context);
    const GrassTexture texture = grassTextureFromImage(test::makeUniformImage(4, 0, 200, 0, 255));
    GrassParams grass;
    grass.shells = MAX_SHELLS + 1;
    const ParameterError shells = thrownBy([&] { renderer.setGrass(grass, texture); });
    EXPECT_EQ(shells.key(), "grass.shells");
    EXPECT_EQ(shells.value(), std::to_string(MAX_SHELLS + 1));
    grass = {};
    grass.height_m = 0.0f;
    EXPECT_EQ(thrownBy([&] { renderer.setGrass(grass, texture); }).key(), "grass.height_m");
    grass = {};
    grass.stiffness = NaNf;
    EXPECT_EQ(thrownBy([&] { renderer.setGrass(grass, texture); }).key(), "grass.stiffness");
    grass = {};
    grass.lodPixels = -1.0f;
    EXPECT_EQ(thrownBy([&] { renderer.setGrass(grass, texture); }).key(), "grass.lod_pixels");
    renderer.setGrass(GrassParams{}, texture);
    EXPECT_EQ(thrownBy([&] { renderer.setShellCount(-1); }).key(), "grass.shells");

    Lighting lighting;
    lighting.selfShadowMin = 1.5f;
    EXPECT_EQ(thrownBy([&] { renderer.setLighting(lighting); }).key(), "lighting.self_shadow_min");
    lighting = {};
    lighting.lights.resize(2);
    lighting.lights[1].attenuation = glm::vec3(0.0f);
    EXPECT_EQ(thrownBy([&] { renderer.setLighting(lighting); }).key(),
              "lighting.light[1].attenuation");
    lighting.lights[1] = {};
    lighting.lights[1].color.g = NaNf;
    EXPECT_EQ(thrownBy([&] { renderer.setLighting(lighting); }).key(), "lighting.light[1].color");
    lighting = {};
    lighting.lights.resize(MAX_LIGHTS + 1);
    EXPECT_EQ(thrownBy([&] { renderer.setLighting(lighting); }).key(), "lighting.light");
    lighting = {};
    lighting.specularPower = -1.0f;
    EXPECT_EQ(thrownBy([&] { renderer.setLighting(lighting); }).key(), "lighting.specular_power");

    // The mesh comes from coupling's builder, never straight from a scene.
    TerrainMesh mesh = test::makeFlatMesh(3, 1.0f, 1.0f);
    mesh.wsNormal.pop_back();
    EXPECT_NE(logicErrorOf([&] { renderer.setTerrain(mesh); }).find("wsNormal"), std::string::npos);
}

TEST(ParameterError, OverlayTextureBendAndAnimationNameTheSceneKey) {
    auto context = createOsMesaContext(16, 16);
    FieldOverlay overlay(*context);
    FieldOverlayData data;
    data.speedMax = 0.0f;
    EXPECT_EQ(thrownBy([&] { overlay.draw(Camera{}, data); }).key(), "overlay.speed_max_mps");

    Image wide;
    wide.width = 8, wide.height = 4;
    wide.rgba.assign(8 * 4 * 4, 0);
    const ParameterError texture = thrownBy([&] { (void)grassTextureFromImage(wide); });
    EXPECT_EQ(texture.key(), "grass.texture");
    EXPECT_EQ(texture.value(), "8x4");

    EXPECT_EQ(thrownBy([] { (void)bendBlade(0, 1.0f, 0.5f, 1.0f); }).key(), "grass.shells");
    EXPECT_EQ(thrownBy([] { (void)bendBlade(4, -1.0f, 0.5f, 1.0f); }).key(), "grass.height_m");
    EXPECT_EQ(thrownBy([] { (void)bendBlade(4, 1.0f, 0.5f, 0.0f); }).key(), "grass.stiffness");
    EXPECT_FALSE(logicErrorOf([] { (void)bendBlade(4, 1.0f, NaNf, 1.0f); }).empty());

    AnimationOptions options;  // no files: the checks come first
    EXPECT_EQ(thrownBy([&] { AnimationWriter w(options, 0); }).key(), "output.frames");
    options.fps = 0.0;
    EXPECT_EQ(thrownBy([&] { AnimationWriter w(options, 10); }).key(), "output.fps");
    EXPECT_FALSE(
        logicErrorOf([] { (void)downscale(test::makeUniformImage(4, 0, 0, 0, 0), 8, 8); }).empty());
    EXPECT_FALSE(logicErrorOf([] {
                     (void)loadDensityMap("unused.png", glm::vec2(0.0f), glm::vec2(0.0f));
                 }).empty());
}

}  // namespace
}  // namespace gale::render
