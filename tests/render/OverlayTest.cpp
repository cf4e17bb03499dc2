// Field overlays (render/FieldOverlay): the colour map, the legend's numbers, the font, and a
// reference image of arrows and a slice for uniform wind over flat ground.
//
// Regenerating the reference image: run
//   GALE_UPDATE_REFERENCES=1 ./render_tests
//   --gtest_filter='Overlay.UniformWindArrowsAndSliceMatchReferenceImage'
// from the build folder; it rewrites tests/data/render/overlay_uniform.png in the source tree.
// Look at the new image before committing it.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include "RenderTestUtil.h"
#include "render/BitmapFont.h"
#include "render/CameraMath.h"
#include "render/ColorMap.h"
#include "render/FieldOverlay.h"
#include "render/GlContext.h"
#include "render/ImageIO.h"
#include "render/ShellRenderer.h"

namespace gale::render {
namespace {

namespace fs = std::filesystem;

// The ten viridis stops are given as 8-bit hex codes: half a level of rounding.
constexpr float STOP_TOLERANCE = 0.5f / 255.0f;
// L* steps between neighbouring samples of a 1000-sample sweep must not fall by more than this
// (float rounding), and the whole map must rise by at least this much (viridis: about 16 -> 92).
constexpr float LIGHTNESS_NOISE = 1e-3f;
constexpr float MIN_LIGHTNESS_RISE = 70.0f;

TEST(ColorMap, EndpointsAreViridisDarkPurpleAndYellow) {
    const glm::vec3 lo = viridis(0.0f), hi = viridis(1.0f);
    EXPECT_NEAR(lo.r, 0x44 / 255.0f, STOP_TOLERANCE);
    EXPECT_NEAR(lo.g, 0x01 / 255.0f, STOP_TOLERANCE);
    EXPECT_NEAR(lo.b, 0x54 / 255.0f, STOP_TOLERANCE);
    EXPECT_NEAR(hi.r, 0xfd / 255.0f, STOP_TOLERANCE);
    EXPECT_NEAR(hi.g, 0xe7 / 255.0f, STOP_TOLERANCE);
    EXPECT_NEAR(hi.b, 0x25 / 255.0f, STOP_TOLERANCE);
    // The middle is matplotlib's teal (#21918c at t = 0.5, between stops 4 and 5).
    const glm::vec3 mid = viridis(0.5f);
    EXPECT_NEAR(mid.g, 0x90 / 255.0f, 3.0f / 255.0f);
}

TEST(ColorMap, LightnessRisesMonotonically) {
    float previous = cieLightness(viridis(0.0f));
    const float first = previous;
    for (int k = 1; k <= 1000; ++k) {
        const float l = cieLightness(viridis(float(k) / 1000.0f));
        ASSERT_GE(l, previous - LIGHTNESS_NOISE) << "at t = " << float(k) / 1000.0f;
        previous = l;
    }
    EXPECT_GT(previous - first, MIN_LIGHTNESS_RISE);
}

TEST(ColorMap, ClampsOutOfRangeAndNaN) {
    EXPECT_EQ(viridis(-3.0f), viridis(0.0f));
    EXPECT_EQ(viridis(7.0f), viridis(1.0f));
    EXPECT_EQ(viridis(std::nanf("")), viridis(0.0f));
}

TEST(Overlay, LegendTicksAreRoundNumbersFromZeroToTheTop) {
    EXPECT_EQ(FieldOverlay::legendTicks(6.0f), (std::vector<float>{0, 2, 4, 6}));
    EXPECT_EQ(FieldOverlay::legendTicks(10.0f), (std::vector<float>{0, 2, 4, 6, 8, 10}));
    const std::vector<float> small = FieldOverlay::legendTicks(1.0f);
    ASSERT_EQ(small.size(), 6u);
    EXPECT_FLOAT_EQ(small[1], 0.2f);
    EXPECT_EQ(FieldOverlay::tickLabel(0.2f, 0.2f), "0.2");
    EXPECT_EQ(FieldOverlay::tickLabel(4.0f, 2.0f), "4");
    EXPECT_EQ(FieldOverlay::tickLabel(0.25f, 0.25f), "0.25");
}

TEST(BitmapFont, HasTheLegendAndHeadsUpCharacters) {
    for (char c : std::string("0123456789.-/:% ms") + "abcdefghijklmnopqrstuvwxyz")
        EXPECT_TRUE(hasGlyph(c)) << "'" << c << "'";
    // Every glyph but space lights something, and no two digits look alike.
    std::map<std::string, char> seen;
    for (char c : std::string("0123456789.-/ms")) {
        std::string bits;
        for (int y = 0; y < GLYPH_HEIGHT_PX; ++y)
            for (int x = 0; x < GLYPH_WIDTH_PX; ++x) bits += glyphPixel(c, x, y) ? '#' : '.';
        EXPECT_NE(bits.find('#'), std::string::npos) << c;
        EXPECT_EQ(seen.count(bits), 0u) << c << " looks like " << seen[bits];
        seen[bits] = c;
    }
    EXPECT_EQ(textWidth_px("m/s", 2), 2 * (3 * GLYPH_ADVANCE_PX - 1));
}

/// Uniform wind along +x at 3 m/s over flat ground, shown against a 6 m/s colour map.
struct UniformScene {
    static constexpr float SPEED_MPS = 3.0f;
    static constexpr float SPEED_MAX_MPS = 6.0f;
    Camera camera;
    FieldOverlayData data;

    explicit UniformScene(bool withSlice) {
        camera.wsPosition_m = glm::vec3(0.0f, -7.0f, 6.0f);
        camera.wsTarget_m = glm::vec3(0.0f, 0.0f, 0.0f);
        camera.near_m = 0.5f;
        camera.far_m = 100.0f;
        for (int j = -2; j <= 2; ++j)
            for (int i = -2; i <= 2; ++i)
                data.arrows.push_back({glm::vec3(i * 1.2f - 0.4f, j * 1.2f, 0.4f),
                                       glm::vec3(0.8f, 0.0f, 0.0f), SPEED_MPS});
        if (withSlice) {
            data.slice.nx = data.slice.ny = 9;
            for (int j = 0; j < 9; ++j)
                for (int i = 0; i < 9; ++i) {
                    data.slice.wsPosition_m.emplace_back(-3.0f + 0.75f * i, -3.0f + 0.75f * j,
                                                         0.2f);
                    data.slice.speed.push_back(SPEED_MPS);
                }
        }
        data.speedMax = SPEED_MAX_MPS;
    }
};

TEST(Overlay, UniformWindArrowsAndSliceMatchReferenceImage) {
    auto context = createOsMesaContext(160, 120);
    ShellRenderer renderer(*context);
    const TerrainMesh mesh = test::makeFlatMesh(9, 3.0f, 1.5f);
    renderer.setTerrain(mesh);
    GrassParams grass;
    grass.height_m = 0.2f;
    grass.shells = 4;
    grass.tile_m = 1.5f;
    GrassTextureSpec spec;
    spec.size = 64;
    spec.seed = 5;
    renderer.setGrass(grass, generateGrassTexture(spec));
    Lighting lighting;
    lighting.ambient = glm::vec3(0.15f);  // the light the reference image was made with
    renderer.setLighting(lighting);
    FieldOverlay overlay(*context);
    UniformScene scene(/*withSlice=*/true);
    renderer.draw(scene.camera, GrassWind{});
    overlay.draw(scene.camera, scene.data);
    Image actual;
    context->readPixels(actual);

    test::expectMatchesReference(actual, "overlay_uniform");
}

TEST(Overlay, UniformWindArrowsShareOneColourAndPointDownwind) {
    // Arrows alone on a cleared frame, seen from straight above (+x to the right of the image):
    // every pixel that is not background or outline is the colour viridis(3 / 6), and each arrow
    // is wider at its head (east).
    constexpr int OUTLINE_MAX = 30;  // outlines are grey 0.05 (13/255); viridis(0.5) is far above
    auto context = createOsMesaContext(160, 160);
    FieldOverlay overlay(*context);
    UniformScene scene(/*withSlice=*/false);
    scene.data.legend = false;
    scene.camera.wsPosition_m = glm::vec3(0.0f, 0.0f, 8.0f);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    overlay.draw(scene.camera, scene.data);
    Image image;
    context->readPixels(image);
    const glm::vec3 want = viridis(UniformScene::SPEED_MPS / UniformScene::SPEED_MAX_MPS) * 255.0f;
    int arrowPixels = 0, westHalf = 0, eastHalf = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const uint8_t* p = &image.rgba[(size_t(y) * image.width + x) * 4];
            // Black is the cleared frame, near black the arrows' outlines.
            if (p[0] < OUTLINE_MAX && p[1] < OUTLINE_MAX && p[2] < OUTLINE_MAX) continue;
            ++arrowPixels;
            // Flat, unlit colour: only the 8-bit rounding of the colour differs (one level).
            ASSERT_NEAR(p[0], want.r, 1.0) << x << "," << y;
            ASSERT_NEAR(p[1], want.g, 1.0) << x << "," << y;
            ASSERT_NEAR(p[2], want.b, 1.0) << x << "," << y;
        }
    // 25 arrows of about 0.8 x 0.35 m seen from 8 m: dozens of interior pixels each.
    constexpr int MIN_ARROW_PIXELS = 25 * 20;
    EXPECT_GT(arrowPixels, MIN_ARROW_PIXELS);
    // Direction: the head (wide end) is downwind. Count pixels left and right of each arrow's
    // middle column by scanning rows through the centre arrow (world origin = image centre).
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const uint8_t* p = &image.rgba[(size_t(y) * image.width + x) * 4];
            const bool lit = p[0] >= OUTLINE_MAX || p[1] >= OUTLINE_MAX || p[2] >= OUTLINE_MAX;
            if (!lit || std::abs(y - image.height / 2) > 10 || std::abs(x - image.width / 2) > 14)
                continue;
            (x < image.width / 2 ? westHalf : eastHalf) += 1;
        }
    EXPECT_GT(eastHalf, westHalf) << "the wide head of the centre arrow should point east (+x)";
}

TEST(Overlay, RejectsBadInputNamingTheField) {
    auto context = createOsMesaContext(32, 32);
    FieldOverlay overlay(*context);
    UniformScene scene(/*withSlice=*/true);
    FieldOverlayData bad = scene.data;
    bad.speedMax = 0.0f;
    EXPECT_THROW(overlay.draw(scene.camera, bad), std::invalid_argument);
    bad = scene.data;
    bad.slice.speed.pop_back();
    try {
        overlay.draw(scene.camera, bad);
        FAIL() << "accepted a slice with a missing speed";
    } catch (const std::logic_error& e) {
        EXPECT_NE(std::string(e.what()).find("OverlaySlice"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace gale::render
