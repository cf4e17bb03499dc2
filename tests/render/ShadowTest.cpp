/// \file ShadowTest.cpp
/// The key light's shadow of the terrain (render/ShadowMap.h, shaders/shell.vert): a steep ridge
/// under a low sun darkens exactly the ground its shadow covers, computed here by marching the ray
/// to the sun over the analytic ridge; a flat meadow does not shadow itself (no acne); a light
/// inside the terrain's box or below the horizon behaves as stated.

#include <gtest/gtest.h>

#include <cmath>
#include <glm/vec4.hpp>
#include <memory>
#include <vector>

#include "RenderTestUtil.h"
#include "base/Numbers.h"
#include "render/CameraMath.h"
#include "render/GlContext.h"
#include "render/ShadowMap.h"
#include "render/ShellRenderer.h"

namespace gale::render {
namespace {

constexpr int SIZE_PX = 320;
// The ridge along y: 12 m high, sigma 3 m (flanks up to 67 degrees), on a 120 m meadow.
constexpr float RIDGE_M = 12.0f, SIGMA_M = 3.0f, HALF_M = 60.0f;
float ridge(float x) { return RIDGE_M * std::exp(-x * x / (2.0f * SIGMA_M * SIGMA_M)); }

// A sun far to the east at `elevation_deg` (a direction for this terrain), light 0.
Lighting sunFromEast(float elevation_deg, bool shadows) {
    Lighting lighting;
    const float el = static_cast<float>(radiansFromDegrees(elevation_deg));
    lighting.lights.push_back(
        {glm::vec3(1e6f * std::cos(el), 0.0f, 1e6f * std::sin(el)), glm::vec3(1.0f), {1, 0, 0}});
    lighting.ambient = glm::vec3(0.2f);
    lighting.specularStrength = 0.0f;
    lighting.shadows = shadows;
    return lighting;
}

struct ShadowScene {
    std::unique_ptr<GlContext> context = createOsMesaContext(SIZE_PX, SIZE_PX);
    ShellRenderer renderer{*context};
    Camera camera;
    GrassTexture texture = generateGrassTexture(GrassTextureSpec{});
    explicit ShadowScene(const TerrainMesh& mesh, float lodPixels = GrassParams{}.lodPixels) {
        renderer.setTerrain(mesh);
        setLod(lodPixels);
        // Straight down from 150 m, a little off the vertical so lookAt has an up direction.
        camera.wsPosition_m = glm::vec3(0.0f, -1.0f, 150.0f);
        camera.wsTarget_m = glm::vec3(0.0f);
        camera.far_m = 400.0f;
    }
    // lodPixels 0: every shell on the full mesh, where a vertex's visibility is its own.
    void setLod(float lodPixels) {
        GrassParams grass;
        grass.height_m = 0.3f;
        grass.shells = 8;
        grass.lodPixels = lodPixels;
        renderer.setGrass(grass, texture);
    }
    Image frame(const Lighting& lighting) {
        renderer.setLighting(lighting);
        (void)renderer.draw(camera, GrassWind{});
        Image image;
        context->readPixels(image);
        return image;
    }
    // The pixel (column, row from the top) where ground point p lands.
    glm::ivec2 pixelOf(const glm::vec3& p) const {
        const glm::vec4 c = clipFromWorld(camera, 1.0f) * glm::vec4(p, 1.0f);
        const float x = (c.x / c.w * 0.5f + 0.5f) * SIZE_PX;
        const float y = (1.0f - (c.y / c.w * 0.5f + 0.5f)) * SIZE_PX;
        return {static_cast<int>(x), static_cast<int>(y)};
    }
};

double luminance(const Image& image, glm::ivec2 px) {
    const size_t p = (static_cast<size_t>(px.y) * image.width + px.x) * 4;
    return 0.2126 * image.rgba[p] + 0.7152 * image.rgba[p + 1] + 0.0722 * image.rgba[p + 2];
}

// The oracle: does the ray from ground point (x, ridge(x)) towards the sun pass below the ridge
// somewhere? Marched in 1 cm steps over the analytic profile.
bool inShadow(float x, float elevation_deg) {
    const double el = radiansFromDegrees(elevation_deg);
    for (double t = 0.01; t < 200.0; t += 0.01) {
        const double px = x + t * std::cos(el), pz = ridge(x) + t * std::sin(el);
        if (pz < ridge(static_cast<float>(px))) return true;
        if (pz > RIDGE_M) return false;
    }
    return false;
}

TEST(Shadows, TheMapLookupBlendsFourDepthComparisonsLikeGlsLinearShadowSampler) {
    // 2 x 2 texels, row 0 first: depths 0.2 (occluder) on the left column, 1 on the right.
    const std::vector<float> depth = {0.2f, 1.0f, 0.2f, 1.0f};
    // Texel centres are at (k + 0.5) / 2: at a left centre the occluder, at a right one none.
    EXPECT_FLOAT_EQ(detail::mapVisibility(depth, 2, {0.25f, 0.25f, 0.5f}), 0.0f);
    EXPECT_FLOAT_EQ(detail::mapVisibility(depth, 2, {0.75f, 0.75f, 0.5f}), 1.0f);
    // Half way between the columns, half the light; a quarter of the way, a quarter.
    EXPECT_FLOAT_EQ(detail::mapVisibility(depth, 2, {0.5f, 0.5f, 0.5f}), 0.5f);
    EXPECT_FLOAT_EQ(detail::mapVisibility(depth, 2, {0.375f, 0.5f, 0.5f}), 0.25f);
    // In front of the occluder (t.z <= depth): lit everywhere; beyond the map: lit.
    EXPECT_FLOAT_EQ(detail::mapVisibility(depth, 2, {0.25f, 0.25f, 0.1f}), 1.0f);
    EXPECT_FLOAT_EQ(detail::mapVisibility(depth, 2, {-3.0f, 0.5f, 0.9f}), 1.0f);
    EXPECT_FLOAT_EQ(detail::mapVisibility(depth, 2, {0.5f, NAN, 0.9f}), 1.0f);
}

TEST(Shadows, ACoarseLevelShowsTheMeanVisibilityOfTheGroundItsCellsStandFor) {
    // A 65 x 65 grid lit for i < 40, shadowed from column 40 on; chunks of 32 quads.
    constexpr int N = 65;
    std::vector<float> visible(N * N);
    for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i) visible[j * N + i] = i < 40 ? 1.0f : 0.0f;
    const std::vector<float> levels = detail::levelVisibility(visible, N, N, 6, 32);
    ASSERT_EQ(levels.size(), visible.size() * 6);
    const auto at = [&](int i, int j, int l) { return levels[size_t(j * N + i) * 6 + l]; };
    // Level 0 is the vertex's own; level 2 at column 38 averages columns 36..40: 4 of 5 lit.
    EXPECT_FLOAT_EQ(at(38, 10, 0), 1.0f);
    EXPECT_FLOAT_EQ(at(38, 10, 2), 0.8f);
    // Level 3 at column 44 averages 40..48: all shadowed; at column 36, 32..40: 8 of 9 lit.
    EXPECT_FLOAT_EQ(at(44, 10, 3), 0.0f);
    EXPECT_FLOAT_EQ(at(36, 10, 3), 8.0f / 9.0f);
    // Chunk borders (row 32, column 32, the grid's edges) keep their own value at every level.
    for (int l = 0; l < 6; ++l) {
        EXPECT_FLOAT_EQ(at(39, 32, l), 1.0f);
        EXPECT_FLOAT_EQ(at(32, 10, l), 1.0f);
        EXPECT_FLOAT_EQ(at(64, 10, l), 0.0f);
    }
    // The mean over the grid is kept at every level away from the step (no light made or lost).
    EXPECT_FLOAT_EQ(at(10, 10, 5), 1.0f);
}

TEST(Shadows, ARidgeUnderALowSunDarkensTheGroundItsShadowCovers) {
    // The full mesh: the shadow's edge as sharp as the vertices (coarse levels average it over
    // their cells; checked below).
    ShadowScene scene(
        test::makeGridMesh(241, 241, HALF_M, 3.0f, [](float x, float) { return ridge(x); }), 0.0f);
    constexpr float ELEVATION_DEG = 20.0f;
    const Image on = scene.frame(sunFromEast(ELEVATION_DEG, true));
    const Image off = scene.frame(sunFromEast(ELEVATION_DEG, false));
    // The shadow's far edge, from the oracle: west of the ridge, the last shadowed x.
    float edge_m = 0.0f;
    for (float x = 0.0f; x > -HALF_M; x -= 0.05f)
        if (inShadow(x, ELEVATION_DEG)) edge_m = x;
    // 12 m / tan(20 deg) = 33 m, less the flank below the tangent point.
    EXPECT_LT(edge_m, -25.0f);
    EXPECT_GT(edge_m, -34.0f);
    // Classify ground points along y in [-20, 20] m, 1.5 m (three mesh cells; the light is per
    // vertex) clear of every boundary the oracle finds.
    double shadowedOn = 0, shadowedOff = 0, litOn = 0, litOff = 0;
    int shadowed = 0, lit = 0;
    for (float x = -50.0f; x <= 50.0f; x += 0.5f) {
        const bool s = inShadow(x, ELEVATION_DEG);
        if (s != inShadow(x - 1.5f, ELEVATION_DEG) || s != inShadow(x + 1.5f, ELEVATION_DEG))
            continue;
        for (float y = -20.0f; y <= 20.0f; y += 2.0f) {
            const glm::ivec2 px = scene.pixelOf(glm::vec3(x, y, ridge(x)));
            ASSERT_TRUE(px.x >= 0 && px.y >= 0 && px.x < SIZE_PX && px.y < SIZE_PX);
            if (s) {
                shadowedOn += luminance(on, px), shadowedOff += luminance(off, px), ++shadowed;
            } else {
                litOn += luminance(on, px), litOff += luminance(off, px), ++lit;
            }
        }
    }
    ASSERT_GT(shadowed, 200);
    ASSERT_GT(lit, 400);
    std::printf("shadowed ground %.3f of its unshadowed luminance (%d points), lit %.4f (%d)\n",
                shadowedOn / shadowedOff, shadowed, litOn / litOff, lit);
    // Shadowed: the sun gone, ambient 0.2 left against about 1 + 0.2 (Banks scales both alike).
    EXPECT_LT(shadowedOn / shadowedOff, 0.5);
    // Lit: unchanged but for the odd texel at a shadow's soft edge.
    EXPECT_NEAR(litOn / litOff, 1.0, 0.01);

    // With the level of detail the far chunks take coarse meshes, whose vertices show the mean
    // visibility of the ground their cells stand for: the edge blurs over a cell, the light on
    // the whole shadowed strip and its surroundings stays (the mean over x in [-45, 10] m).
    const auto stripMean = [&](const Image& image) {
        double sum = 0;
        int n = 0;
        for (float x = -45.0f; x <= 10.0f; x += 0.5f)
            for (float y = -20.0f; y <= 20.0f; y += 2.0f, ++n)
                sum += luminance(image, scene.pixelOf(glm::vec3(x, y, ridge(x))));
        return sum / n;
    };
    const double full = stripMean(on);
    scene.setLod(GrassParams{}.lodPixels);
    const double lod = stripMean(scene.frame(sunFromEast(ELEVATION_DEG, true)));
    const double lodUnshadowed = stripMean(scene.frame(sunFromEast(ELEVATION_DEG, false)));
    std::printf("strip mean: every shell %.2f, level of detail %.2f (unshadowed %.2f)\n", full, lod,
                lodUnshadowed);
    EXPECT_NEAR(lod / full, 1.0, 0.03);
}

TEST(Shadows, AFlatMeadowDoesNotShadowItself) {
    ShadowScene scene(test::makeFlatMesh(121, HALF_M, 3.0f));
    for (float elevation : {5.0f, 20.0f, 60.0f, 90.0f}) {
        const test::ImageDiff d =
            test::compareImages(scene.frame(sunFromEast(elevation, true)),
                                scene.frame(sunFromEast(elevation, false)), 2);
        EXPECT_EQ(d.differingFraction, 0.0) << elevation << " deg";
    }
}

TEST(Shadows, ALightInsideTheBoxCastsNoMapAndASetSunShadowsEverything) {
    const glm::vec3 lo(-10.0f, -10.0f, 0.0f), hi(10.0f, 10.0f, 2.0f);
    EXPECT_FALSE(detail::keyLightView(glm::vec3(0.0f, 0.0f, 1.0f), lo, hi, 64).has_value());
    EXPECT_FALSE(detail::keyLightView(glm::vec3(NAN), lo, hi, 64).has_value());
    EXPECT_TRUE(detail::keyLightView(glm::vec3(30.0f, 0.0f, 5.0f), lo, hi, 64).has_value());
    EXPECT_TRUE(detail::keyLightView(glm::vec3(0.0f, 0.0f, 1e6f), lo, hi, 64).has_value());
    // A lamp among the grass lights it as before (no map, no shadow).
    ShadowScene scene(test::makeFlatMesh(41, 20.0f, 3.0f));
    Lighting lamp = sunFromEast(45.0f, true);
    lamp.lights[0].wsPosition_m = glm::vec3(2.0f, 3.0f, 1.0f);
    lamp.lights[0].attenuation = glm::vec3(1.0f, 0.1f, 0.0f);
    const Image withShadows = scene.frame(lamp);
    lamp.shadows = false;
    EXPECT_EQ(test::compareImages(withShadows, scene.frame(lamp), 0).differingFraction, 0.0);
    // A sun 5 degrees below the horizon reaches no blade: ambient alone, darker than unshadowed.
    const Image set = scene.frame(sunFromEast(-5.0f, true));
    const Image unshadowed = scene.frame(sunFromEast(-5.0f, false));
    const glm::ivec2 middle(SIZE_PX / 2, SIZE_PX / 2);
    double a = 0, b = 0;
    for (int dy = -20; dy <= 20; ++dy)
        for (int dx = -20; dx <= 20; ++dx) {
            a += luminance(set, middle + glm::ivec2(dx, dy));
            b += luminance(unshadowed, middle + glm::ivec2(dx, dy));
        }
    EXPECT_LT(a, 0.5 * b);
}

}  // namespace
}  // namespace gale::render
