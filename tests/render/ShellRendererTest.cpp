// The shell renderer end to end on llvmpipe: a reference image, the bend, shell coverage and input
// validation (Bakay 2003, chapter 3).
//
// Regenerating the reference image: run
//   GALE_UPDATE_REFERENCES=1 ./render_tests --gtest_filter='ShellRenderer.MatchesReferenceImage'
// from the build folder; it rewrites tests/data/render/reference_shells.png in the source tree.
// Look at the new image before committing it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "RenderTestUtil.h"
#include "render/GlContext.h"
#include "render/GrassTexture.h"
#include "render/ImageIO.h"
#include "render/ShellRenderer.h"

namespace gale::render {
namespace {

namespace fs = std::filesystem;

struct ReferenceScene {
    TerrainMesh mesh = test::makeHillMesh();
    GrassParams grass;
    GrassTexture texture;
    Lighting lighting;
    Camera camera;

    ReferenceScene() {
        grass.height_m = 0.3f;
        grass.shells = 9;
        grass.stiffness = 1.0f;
        grass.tile_m = 1.5f;
        grass.lodPixels = 0.0f;  // every shell everywhere: the reference pins the shading
        grass.nearBlades = 0;    // of the shells (NearBladesTest holds the blades)
        GrassTextureSpec spec;
        spec.size = 128;
        spec.seed = 2003;
        texture = generateGrassTexture(spec);
        lighting.ambient = glm::vec3(0.12f);
        lighting.lights.push_back({glm::vec3(-4.0f, -5.0f, 6.0f), glm::vec3(1.0f, 0.92f, 0.8f),
                                   glm::vec3(1.0f, 0.0f, 0.004f)});
        lighting.lights.push_back({glm::vec3(5.0f, 3.0f, 3.0f), glm::vec3(0.35f, 0.4f, 0.6f),
                                   glm::vec3(1.0f, 0.05f, 0.0f)});
        camera.wsPosition_m = glm::vec3(0.0f, -6.5f, 3.2f);
        camera.wsTarget_m = glm::vec3(0.0f, 0.0f, 0.3f);
        camera.fovY_deg = 45.0f;
        camera.near_m = 0.5f;
        camera.far_m = 100.0f;
    }

    GrassWind wind(float west, float east) const {
        return test::makeUniformWind(mesh, glm::vec3(1.0f, 0.4f, 0.0f), west, east);
    }
};

// The reference scene set up in a renderer of its own, frame after frame.
struct ReferenceRig {
    std::unique_ptr<GlContext> context;
    ReferenceScene scene;
    ShellRenderer renderer;

    ReferenceRig(int width, int height)
        : context(createOsMesaContext(width, height)), renderer(*context) {
        renderer.setTerrain(scene.mesh);
        renderer.setGrass(scene.grass, scene.texture);
        renderer.setLighting(scene.lighting);
    }
    Image frame(const GrassWind& wind) {
        renderer.draw(scene.camera, wind);
        Image image;
        context->readPixels(image);
        return image;
    }
};

Image renderReference(const GrassWind& wind) { return ReferenceRig(160, 120).frame(wind); }

TEST(ShellRenderer, MatchesReferenceImage) {
    ReferenceScene scene;
    const Image actual = renderReference(scene.wind(0.35f, 0.9f));
    test::expectMatchesReference(actual, "reference_shells");
}

TEST(ShellRenderer, BendingMovesPixels) {
    // A calm frame and a full-intensity frame of the reference scene differ in many pixels: the
    // tips lean by up to the grass height along the wind.
    constexpr double MIN_MOVED_FRACTION = 0.05;
    constexpr int CHANNEL_NOISE = 8;  // ignore differences below the reference tolerance
    ReferenceScene scene;
    const Image calm = renderReference(scene.wind(0.0f, 0.0f));
    const Image windy = renderReference(scene.wind(1.0f, 1.0f));
    const test::ImageDiff diff = test::compareImages(calm, windy, CHANNEL_NOISE);
    EXPECT_GT(diff.differingFraction, MIN_MOVED_FRACTION);
}

TEST(ShellRenderer, TheNearestSampledBaselineLeavesTheGrassFilteringAlone) {
    // The baseline's nearest sampling is a sampler bound for its draw only: frames drawn after it
    // are those drawn before, and its own frame differs (nearest texels, no bend, no light).
    ReferenceRig rig(160, 120);
    const GrassWind wind = rig.scene.wind(0.35f, 0.9f);
    const Image before = rig.frame(wind);
    rig.renderer.drawFillBaseline(rig.scene.camera, /*nearestSampling=*/true);
    Image nearest;
    rig.context->readPixels(nearest);
    EXPECT_NE(nearest.rgba, before.rgba);
    EXPECT_EQ(rig.frame(wind).rgba, before.rgba);
}

TEST(ShellRenderer, NearestTexelsChangeOnlyTheFilteringOfTheirOwnFrame) {
    // DrawOptions::nearestTexels: the same grass with one texel of the nearest MIP level. Its frame
    // differs from the trilinear one but covers the same ground (the same geometry and alpha
    // test, so nearly the same pixels are sky), and the next default frame is the default again.
    constexpr int CHANNEL_NOISE = 8;               // the reference tolerance
    constexpr double MAX_SKY_CHANGE = 0.01;        // blade edges move by a texel at most
    constexpr double MIN_CHANGED_FRACTION = 0.05;  // the filtering visibly changes the grass
    ReferenceRig rig(160, 120);
    const GrassWind wind = rig.scene.wind(0.35f, 0.9f);
    const Image before = rig.frame(wind);
    DrawOptions nearestTexels;
    nearestTexels.nearestTexels = true;
    rig.renderer.draw(rig.scene.camera, wind, nearestTexels);
    Image nearest;
    rig.context->readPixels(nearest);
    EXPECT_GT(test::compareImages(before, nearest, CHANNEL_NOISE).differingFraction,
              MIN_CHANGED_FRACTION);
    const auto skyShare = [](const Image& image) {
        const auto sky = [](float v) { return static_cast<int>(std::lround(v * 255.0f)); };
        size_t n = 0;
        for (size_t p = 0; p < image.rgba.size(); p += 4)
            n += image.rgba[p] == sky(ShellRenderer::SKY_COLOR[0]) &&
                 image.rgba[p + 1] == sky(ShellRenderer::SKY_COLOR[1]) &&
                 image.rgba[p + 2] == sky(ShellRenderer::SKY_COLOR[2]);
        return static_cast<double>(n) / static_cast<double>(image.rgba.size() / 4);
    };
    EXPECT_NEAR(skyShare(nearest), skyShare(before), MAX_SKY_CHANGE);
    EXPECT_GT(skyShare(before), 0.05);  // the check above has sky to compare
    EXPECT_EQ(rig.frame(wind).rgba, before.rgba);
}

TEST(ShellRenderer, EmptyGroupIntensityMeansNoWind) {
    ReferenceScene scene;
    GrassWind none;  // no per-vertex arrays, no groups
    const Image a = renderReference(none);
    const Image b = renderReference(scene.wind(0.0f, 0.0f));
    EXPECT_EQ(a.rgba, b.rgba);
}

TEST(ShellRenderer, WindArraysAreReuploadedOnlyWhenRevisionChanges) {
    ReferenceRig rig(160, 120);
    auto frame = [&](const GrassWind& wind) { return rig.frame(wind); };
    GrassWind wind = rig.scene.wind(1.0f, 1.0f);
    const Image first = frame(wind);
    auto flipped = std::make_shared<VertexWind>(*wind.vertex);
    for (glm::vec3& d : flipped->wsDirection) d = -d;
    wind.vertex = flipped;  // new directions, same revision: not uploaded
    EXPECT_EQ(frame(wind).rgba, first.rgba);
    ++wind.revision;  // now they are
    EXPECT_NE(frame(wind).rgba, first.rgba);
}

// Top-down view of a flat field larger than the view, lit by one far light near the horizon so
// the Kajiya-Kay diffuse term is ~1 for upright strands and the brightness of a shell is its Banks
// factor S = (i/N)(1 - S_min) + S_min alone: with S_min = 1/2 the ground shows at half brightness,
// the top shell at full.
struct CoverageScene {
    static constexpr int SHELLS = 8;
    static constexpr float SHADOW_MIN = 0.5f;
    std::unique_ptr<GlContext> context = createOsMesaContext(96, 72);
    ShellRenderer renderer{*context};

    explicit CoverageScene(const Image& texture) {
        renderer.setTerrain(test::makeFlatMesh(9, 6.0f, 1.0f));
        GrassParams grass;
        grass.height_m = 0.4f;
        grass.shells = SHELLS;
        grass.nearBlades = 0;  // the shells' coverage alone
        renderer.setGrass(grass, grassTextureFromImage(texture));
        Lighting lighting;
        lighting.ambient = glm::vec3(0.0f);
        lighting.specularStrength = 0.0f;
        lighting.selfShadowMin = SHADOW_MIN;
        lighting.lights.push_back(
            {glm::vec3(1.0e4f, 0.0f, 0.0f), glm::vec3(1.0f), glm::vec3(1.0f, 0.0f, 0.0f)});
        renderer.setLighting(lighting);
    }

    Image draw() {
        Camera camera;
        camera.wsPosition_m = glm::vec3(0.0f, 0.0f, 5.0f);
        camera.wsTarget_m = glm::vec3(0.0f);
        renderer.draw(camera, GrassWind{});
        Image image;
        context->readPixels(image);
        return image;
    }
};

// Rounding of the 8-bit framebuffer and texture plus the light's 1e-4 rad elevation.
constexpr int SHADE_TOLERANCE = 2;

int countPixelsOff(const Image& image, int expected) {
    int off = 0;
    for (size_t p = 0; p < image.rgba.size(); p += 4) {
        for (int c = 0; c < 3; ++c) {
            if (std::abs(int(image.rgba[p + c]) - expected) > SHADE_TOLERANCE) {
                ++off;
                break;
            }
        }
    }
    return off;
}

TEST(ShellRenderer, AllBladeTextureShowsTheTopShellEverywhere) {
    CoverageScene scene(test::makeUniformImage(16, 255, 255, 255, 255));
    const Image image = scene.draw();
    EXPECT_EQ(countPixelsOff(image, 255), 0);
}

TEST(ShellRenderer, AllGroundTextureShowsOnlyShellZero) {
    CoverageScene scene(test::makeUniformImage(16, 255, 255, 255, 0));
    const Image image = scene.draw();
    const int groundShade = static_cast<int>(255.0f * CoverageScene::SHADOW_MIN + 0.5f);
    EXPECT_EQ(countPixelsOff(image, groundShade), 0);
}

// Draws the reference scene with `wind` and expects std::logic_error (the wind comes from
// coupling, so a malformed one is a bug, not bad input) naming `expected`.
void expectDrawRefuses(const GrassWind& wind, const std::string& expected) {
    ReferenceRig rig(32, 24);
    try {
        rig.frame(wind);
        FAIL() << "expected std::logic_error naming " << expected;
    } catch (const std::logic_error& e) {
        EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
}

// A copy of `wind` whose per-vertex arrays `change` edits.
template <class F>
GrassWind withVertexWind(GrassWind wind, F&& change) {
    auto edited = std::make_shared<VertexWind>(*wind.vertex);
    change(*edited);
    wind.vertex = edited;
    ++wind.revision;
    return wind;
}

TEST(ShellRenderer, WrongWindArraySizesThrow) {
    const GrassWind wind = ReferenceScene().wind(0.5f, 0.5f);
    expectDrawRefuses(withVertexWind(wind, [](VertexWind& w) { w.wsDirection.pop_back(); }),
                      "wsDirection");
    expectDrawRefuses(withVertexWind(wind, [](VertexWind& w) { w.group.resize(3); }), "group");
}

TEST(ShellRenderer, GroupOutOfRangeThrows) {
    GrassWind wind = ReferenceScene().wind(0.5f, 0.5f);
    wind.groupIntensity.resize(1);  // vertices east of x = 0 name group 1
    expectDrawRefuses(wind, "group 1");
}

TEST(ShellRenderer, MoreLightsThanTheCapThrow) {
    auto context = createOsMesaContext(32, 24);
    ShellRenderer renderer(*context);
    Lighting lighting;
    lighting.lights.resize(MAX_LIGHTS + 1);
    try {
        renderer.setLighting(lighting);
        FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("at most 16"), std::string::npos) << e.what();
    }
    lighting.lights.resize(MAX_LIGHTS);
    EXPECT_NO_THROW(renderer.setLighting(lighting));
}

TEST(ShellRenderer, DrawBeforeTerrainThrows) {
    auto context = createOsMesaContext(32, 24);
    ShellRenderer renderer(*context);
    EXPECT_THROW(renderer.draw(Camera{}, GrassWind{}), std::logic_error);
}

TEST(ShellRenderer, BadGrassParamsThrow) {
    auto context = createOsMesaContext(32, 24);
    ShellRenderer renderer(*context);
    ReferenceScene scene;
    GrassParams grass = scene.grass;
    grass.shells = MAX_SHELLS + 1;
    EXPECT_THROW(renderer.setGrass(grass, scene.texture), std::invalid_argument);
    grass = scene.grass;
    grass.height_m = 0.0f;
    EXPECT_THROW(renderer.setGrass(grass, scene.texture), std::invalid_argument);
}

}  // namespace
}  // namespace gale::render
