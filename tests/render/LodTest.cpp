// Level of detail by distance (render/TerrainChunks.h): which shells a chunk draws, culling, chunk
// index lists, and frames with and without it: only distant grass differs, and a slow dolly shows
// no popping.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/mat4x4.hpp>
#include <memory>

#include "RenderTestUtil.h"
#include "render/CameraMath.h"
#include "render/GlContext.h"
#include "render/GrassTexture.h"
#include "render/ShellRenderer.h"
#include "render/TerrainChunks.h"

namespace gale::render {
namespace {

TEST(LodShellRange, DropsTheWholeStackTogetherAtTheFarDistance) {
    // D = 160 m, 17 shells: nearer than 160 m every shell, from 160 m the ground alone.
    const auto at = [](float d) { return detail::shellRange(17, 160.0f, d); };
    EXPECT_EQ(at(0.0f).stride, 1);
    EXPECT_EQ(at(0.0f).top, 17);
    EXPECT_EQ(at(10.0f).count(), 18);
    EXPECT_EQ(at(159.9f).count(), 18);
    EXPECT_EQ(at(160.0f).top, 0);  // the ground alone
    EXPECT_EQ(at(160.0f).count(), 1);
    EXPECT_EQ(at(1e30f).count(), 1);
    // No level of detail: every shell.
    EXPECT_EQ(detail::shellRange(17, 0.0f, 1e6f).count(), 18);
    EXPECT_EQ(detail::shellRange(17, INFINITY, 1e6f).count(), 18);
}

TEST(LodShellRange, TheFarDistanceIsWhereTheGrassIsHalfTheLodPixelsTall) {
    // A blade of height h standing at distance D, seen face on, spans h f / D pixels; the rule
    // puts that at P / 2.
    const float h_m = 0.5f, focal_px = 579.4f, lodPixels = 3.0f;
    const float far_m = detail::grassFarDistance_m(h_m, focal_px, lodPixels);
    EXPECT_NEAR(h_m * focal_px / far_m, 0.5f * lodPixels, 1e-4f);
    EXPECT_EQ(detail::grassFarDistance_m(h_m, focal_px, 0.0f), 0.0f);
}

TEST(LodShellRange, AChunkDrawnWithoutTheFadeHasNoShellThinningInIt) {
    // The renderer draws a chunk with the plain program when chunkMayFade says no shell of it has
    // started to thin out and the ground does not yet stand in for the grass: check that against
    // the shader's own rule, fade(d) = 1 and stand-in 0 for d <= 0.7 D, at every distance up to the
    // chunk's far side.
    const float grassFar_m = 100.0f;
    for (int shells : {1, 8, 17, 64}) {
        for (float near_m : {0.0f, 3.0f, 30.0f, 75.0f, 400.0f}) {
            for (float far_m = near_m; far_m < near_m + 60.0f; far_m += 0.25f) {
                if (far_m > detail::LOD_FADE_START * grassFar_m) {
                    EXPECT_TRUE(detail::chunkMayFade(shells, grassFar_m, far_m))
                        << shells << " shells, chunk " << near_m << "-" << far_m << " m";
                }
            }
        }
        EXPECT_FALSE(detail::chunkMayFade(shells, 0.0f, 1e6f));
    }
}

TEST(LodChunks, CoverEveryQuadOnceAndBoundTheirVertices) {
    const TerrainMesh mesh =
        test::makeGridMesh(70, 40, 10.0f, 1.0f, [](float x, float y) { return 0.1f * x * y; });
    std::vector<uint32_t> indices;
    const auto chunks = detail::buildChunks(mesh.nx, mesh.ny, mesh.wsPosition_m, indices);
    EXPECT_EQ(chunks.size(), 3u * 2u);  // 69 x 39 quads in chunks of 32
    // The full meshes come first, one after the other: [0, 69 * 39 * 6) is the whole grid once
    // (the fill baseline draws that range in one call); the coarser levels follow.
    size_t fullIndices = 0;
    for (const auto& c : chunks) {
        EXPECT_EQ(c.firstIndex, fullIndices);
        fullIndices += c.indexCount;
    }
    EXPECT_EQ(fullIndices, size_t(69) * 39 * 6);
    for (const auto& c : chunks)
        for (int l = 1; l < c.levelCount; ++l) EXPECT_GE(c.levels[l].first, fullIndices);
    std::multiset<std::array<uint32_t, 3>> triangles;
    for (const auto& c : chunks)
        for (uint32_t t = c.firstIndex; t < c.firstIndex + c.indexCount; t += 3) {
            for (int k = 0; k < 3; ++k) {
                const glm::vec3& p = mesh.wsPosition_m[indices[t + k]];
                EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, c.wsMin_m)) &&
                            glm::all(glm::lessThanEqual(p, c.wsMax_m)));
            }
            std::array<uint32_t, 3> tri{indices[t], indices[t + 1], indices[t + 2]};
            std::sort(tri.begin(), tri.end());
            triangles.insert(tri);
        }
    for (const auto& tri : triangles) EXPECT_EQ(triangles.count(tri), 1u);
}

TEST(LodCulling, BoxesBehindOrBesideTheCameraAreCulled) {
    Camera camera;
    camera.wsPosition_m = glm::vec3(0.0f, 0.0f, 2.0f);
    camera.wsTarget_m = glm::vec3(0.0f, 10.0f, 2.0f);  // looking north
    const glm::mat4 m = clipFromWorld(camera, 4.0f / 3.0f);
    EXPECT_TRUE(detail::boxMayBeVisible(m, glm::vec3(-1, 9, 0), glm::vec3(1, 11, 1)));
    EXPECT_FALSE(detail::boxMayBeVisible(m, glm::vec3(-1, -11, 0), glm::vec3(1, -9, 1)));  // behind
    EXPECT_FALSE(
        detail::boxMayBeVisible(m, glm::vec3(40, 9, 0), glm::vec3(42, 11, 1)));  // far right
    EXPECT_TRUE(
        detail::boxMayBeVisible(m, glm::vec3(-50, -50, -1), glm::vec3(50, 50, 1)));  // around
    EXPECT_FLOAT_EQ(
        detail::distanceToBox(glm::vec3(0, 0, 2), glm::vec3(3, -1, 0), glm::vec3(4, 1, 1)),
        std::hypot(3.0f, 1.0f));
    EXPECT_EQ(detail::distanceToBox(glm::vec3(0.5f), glm::vec3(0), glm::vec3(1)), 0.0f);
}

// A 120 x 120 m rolling meadow seen at human height towards the horizon.
struct Meadow {
    std::unique_ptr<GlContext> context = createOsMesaContext(160, 120);
    ShellRenderer renderer{*context};
    GrassParams grass;
    Meadow() {
        renderer.setTerrain(test::makeGridMesh(121, 121, 60.0f, 2.0f, [](float x, float y) {
            return 1.5f * std::sin(0.07f * x) * std::cos(0.05f * y);
        }));
        grass.height_m = 0.5f;
        grass.shells = 17;
        GrassTextureSpec spec;
        spec.size = 128;
        spec.seed = 5;
        texture = generateGrassTexture(spec);
        Lighting lighting;
        lighting.lights.push_back({glm::vec3(30, -40, 40), glm::vec3(1.0f), glm::vec3(1, 0, 0)});
        renderer.setLighting(lighting);
    }
    Image frame(float lodPixels, float y_m, FrameStats* stats = nullptr) {
        grass.lodPixels = lodPixels;
        renderer.setGrass(grass, texture);
        Camera camera;
        camera.wsPosition_m = glm::vec3(0.0f, y_m, 3.2f);
        camera.wsTarget_m = glm::vec3(0.0f, y_m + 20.0f, 1.5f);
        camera.fovY_deg = 50.0f;
        camera.near_m = 0.1f;
        const FrameStats s = renderer.draw(camera, GrassWind{});
        if (stats) *stats = s;
        Image image;
        context->readPixels(image);
        return image;
    }
    GrassTexture texture;
};

// Fraction of pixels in rows [y0, y1) (top-down) differing by more than `tolerance`.
double differingRows(const Image& a, const Image& b, int y0, int y1, int tolerance) {
    size_t n = 0, off = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < a.width; ++x, ++n) {
            const size_t p = (size_t(y) * a.width + x) * 4;
            for (int c = 0; c < 3; ++c)
                if (std::abs(int(a.rgba[p + c]) - int(b.rgba[p + c])) > tolerance) {
                    ++off;
                    break;
                }
        }
    return double(off) / double(n);
}

constexpr int CHANNEL_TOLERANCE = 8;  // as the reference images
// The frames are a quarter of the viewer's 640 x 480 across; 2 pixels here drop the stack at
// D = 2 h f / P = 64 m for this grass (f = 129 px), inside the meadow, which reaches 110 m.
constexpr float LOD_PIXELS = 2.0f;

TEST(LodFrames, OnlyDistantGrassDiffersAndLessIsDrawn) {
    Meadow meadow;
    FrameStats full, lod;
    const Image off = meadow.frame(0.0f, -50.0f, &full);
    const Image on = meadow.frame(LOD_PIXELS, -50.0f, &lod);
    // The near third of the frame (its bottom rows) is the same grass, pixel for pixel within
    // the reference tolerance; the whole frame differs in a minority of pixels, all farther up.
    EXPECT_LT(differingRows(off, on, 80, 120, CHANNEL_TOLERANCE), 0.002);  // measured 0
    EXPECT_LT(differingRows(off, on, 0, 120, CHANNEL_TOLERANCE), 0.01);    // measured 0.0005
    EXPECT_LT(lod.layers * 2, full.layers);  // measured 87 of 234 chunk layers
    EXPECT_GT(lod.chunksCulled, 0);          // the chunks behind the camera
}

TEST(LodFrames, ASlowDollyShowsNoPopping) {
    // Frame-to-frame change along a 30 cm dolly in 5 cm steps. Shells thin out blade by blade with
    // distance, so a few distant blades may come and go at a step; a shell or a chunk dropped
    // abruptly would show as a burst of changed pixels at one step.
    Meadow meadow;
    constexpr double FLICKER_FACTOR = 1.2;  // measured 1.00 (0.040 of the pixels either way)
    constexpr double BURST_FACTOR = 1.3;    // the largest step against the median step
    Image previousOn = meadow.frame(LOD_PIXELS, -50.0f), previousOff = meadow.frame(0.0f, -50.0f);
    std::vector<double> changes;
    for (int step = 1; step <= 6; ++step) {
        const float y = -50.0f + 0.05f * step;
        const Image on = meadow.frame(LOD_PIXELS, y), off = meadow.frame(0.0f, y);
        const double changeOn = differingRows(previousOn, on, 0, 120, CHANNEL_TOLERANCE);
        const double changeOff = differingRows(previousOff, off, 0, 120, CHANNEL_TOLERANCE);
        EXPECT_LE(changeOn, FLICKER_FACTOR * changeOff) << "step " << step;
        changes.push_back(changeOn);
        previousOn = on;
        previousOff = off;
    }
    std::vector<double> sorted = changes;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_LE(sorted.back(), BURST_FACTOR * sorted[sorted.size() / 2]);
}

}  // namespace
}  // namespace gale::render
