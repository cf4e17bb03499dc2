// Level of detail by distance (render/TerrainChunks.h): which shells a chunk draws, culling, chunk
// index lists, and frames with and without it: only distant grass differs, and a slow dolly shows
// no popping.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/mat4x4.hpp>
#include <memory>
#include <set>

#include "RenderTestUtil.h"
#include "render/CameraMath.h"
#include "render/GlContext.h"
#include "render/GrassTexture.h"
#include "render/ShellRenderer.h"
#include "render/TerrainChunks.h"

namespace gale::render {
namespace {

TEST(LodShellRange, DropsShellsByTrailingZeroBitsOfTheirIndex) {
    // D1 = 10 m, 17 shells: nearer than 10 m every shell; 10-20 m the even ones (16, 14 .. 0);
    // 20-40 m multiples of 4; ... from 160 m the ground alone.
    const auto at = [](float d) { return detail::shellRange(17, 10.0f, d); };
    EXPECT_EQ(at(0.0f).stride, 1);
    EXPECT_EQ(at(0.0f).top, 17);
    EXPECT_EQ(at(9.99f).count(), 18);
    EXPECT_EQ(at(10.0f).stride, 2);
    EXPECT_EQ(at(10.0f).top, 16);
    EXPECT_EQ(at(10.0f).count(), 9);
    EXPECT_EQ(at(25.0f).stride, 4);
    EXPECT_EQ(at(159.0f).top, 16);  // stride 16: shells 16 and 0
    EXPECT_EQ(at(159.0f).count(), 2);
    EXPECT_EQ(at(160.0f).top, 0);  // the ground alone
    EXPECT_EQ(at(160.0f).count(), 1);
    EXPECT_EQ(at(1e30f).count(), 1);
    // No level of detail: every shell.
    EXPECT_EQ(detail::shellRange(17, 0.0f, 1e6f).count(), 18);
    EXPECT_EQ(detail::shellRange(17, INFINITY, 1e6f).count(), 18);
    // Every shell a chunk leaves out has dropped by the chunk's distance: D(i) <= d.
    for (float d : {0.5f, 12.0f, 33.0f, 90.0f, 200.0f}) {
        const detail::ShellRange r = detail::shellRange(17, 10.0f, d);
        std::set<int> drawn;
        for (int k = 0; k < r.count(); ++k) drawn.insert(r.top - k * r.stride);
        for (int i = 1; i <= 17; ++i) {
            int v = 0;
            while (((i >> v) & 1) == 0) ++v;
            const float drop_m = 10.0f * float(1 << v);
            EXPECT_EQ(drawn.count(i) == 1, drop_m > d) << "shell " << i << " at " << d << " m";
        }
        EXPECT_EQ(drawn.count(0), 1u);
    }
}

TEST(LodShellRange, AChunkDrawnWithoutTheFadeHasNoShellThinningInIt) {
    // The renderer draws a chunk with the plain program when chunkMayFade says no shell of it has
    // started to thin out and the ground does not yet stand in for the grass: check that against
    // the shader's own rules, fade(i, d) = 1 for d <= 0.7 D(i) and the ground's stand-in 0 for
    // d <= 0.7 D(last), last the largest power of two <= N, at every distance up to the chunk's
    // far side, and no shell dropped (the plain program shades every fragment as its own shell).
    const float d1_m = 10.0f;
    for (int shells : {1, 8, 17, 64}) {
        for (float near_m : {0.0f, 3.0f, 9.0f, 14.0f, 30.0f, 75.0f, 400.0f}) {
            const detail::ShellRange r = detail::shellRange(shells, d1_m, near_m);
            for (float far_m = near_m; far_m < near_m + 60.0f; far_m += 0.25f) {
                int last = 1;
                while (last * 2 <= shells) last *= 2;
                bool anyFades = far_m > detail::LOD_FADE_START * d1_m * float(last);
                for (int k = 0; k < r.count(); ++k) {
                    const int i = r.top - k * r.stride;
                    if (i == 0) continue;
                    int v = 0;
                    while (((i >> v) & 1) == 0) ++v;
                    anyFades = anyFades || far_m > detail::LOD_FADE_START * d1_m * float(1 << v);
                }
                // Where shells are dropped, the drawn ones shade the dropped ones' blades
                // (shell.frag's seen shell), which only the fade program does.
                if (anyFades || r.stride > 1) {
                    EXPECT_TRUE(detail::chunkMayFade(r, shells, d1_m, far_m))
                        << shells << " shells, chunk " << near_m << "-" << far_m << " m";
                }
            }
        }
        EXPECT_FALSE(
            detail::chunkMayFade(detail::shellRange(shells, 0.0f, 5.0f), shells, 0.0f, 1e6f));
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
// The frames are a quarter of the viewer's 640 x 480 across: 0.5 pixels here drop shells at the
// distances the default 2 pixels drops them at 640 x 480 (D1 = 15 m for this grass).
constexpr float LOD_PIXELS = 0.5f;

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
