// Overlays a newcomer can read (render/FieldOverlay.h): arrows show over a slice of their own
// colour, an arrow too short on screen is drawn at the minimum length, and the legend draws its
// heading (the quantity and where it is measured).
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>

#include "RenderTestUtil.h"
#include "render/BitmapFont.h"
#include "render/FieldOverlay.h"
#include "render/GlContext.h"

namespace gale::render {
namespace {

constexpr int SIZE_PX = 160;

/// A camera 8 m straight above the origin (+x to the right of the image, +y up).
Camera above() {
    Camera c;
    c.wsPosition_m = glm::vec3(0.0f, -0.01f, 8.0f);
    c.wsTarget_m = glm::vec3(0.0f);
    c.near_m = 0.5f;
    c.far_m = 100.0f;
    return c;
}

Image drawOnBlack(GlContext& context, FieldOverlay& overlay, const FieldOverlayData& data) {
    context.makeCurrent();
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    overlay.draw(above(), data);
    Image image;
    context.readPixels(image);
    return image;
}

/// A slice over [-3, 3]^2 at z = 0.2 m, every point at `speed`.
OverlaySlice uniformSlice(float speed) {
    OverlaySlice slice;
    slice.nx = slice.ny = 9;
    for (int j = 0; j < 9; ++j)
        for (int i = 0; i < 9; ++i) {
            slice.wsPosition_m.emplace_back(-3.0f + 0.75f * i, -3.0f + 0.75f * j, 0.2f);
            slice.speed.push_back(speed);
        }
    return slice;
}

// A pixel changes "visibly" by more than this many 8-bit levels in some channel.
constexpr int VISIBLE_LEVELS = 40;

TEST(OverlayVisibility, ArrowsShowOverASliceOfTheirOwnColour) {
    auto context = createOsMesaContext(SIZE_PX, SIZE_PX);
    FieldOverlay overlay(*context);
    FieldOverlayData data;
    data.legend = false;
    data.speedMax = 6.0f;
    data.slice = uniformSlice(3.0f);
    const Image sliceOnly = drawOnBlack(*context, overlay, data);
    // The same speed, so the same viridis colour as the slice under them.
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i)
            data.arrows.push_back(
                {glm::vec3(i * 1.8f - 0.4f, j * 1.8f, 0.6f), glm::vec3(0.8f, 0.0f, 0.0f), 3.0f});
    const Image withArrows = drawOnBlack(*context, overlay, data);
    const double changed =
        test::compareImages(sliceOnly, withArrows, VISIBLE_LEVELS).differingFraction;
    // Nine arrows 0.8 m long seen from 8 m (about 13 px each): their outlines alone are over a
    // hundred pixels, 0.5 % of the frame.
    constexpr double MIN_VISIBLE_FRACTION = 0.005;
    EXPECT_GT(changed, MIN_VISIBLE_FRACTION);
}

TEST(OverlayVisibility, AnArrowTooShortOnScreenIsDrawnAtTheMinimumLength) {
    auto context = createOsMesaContext(SIZE_PX, SIZE_PX);
    FieldOverlay overlay(*context);
    FieldOverlayData data;
    data.legend = false;
    data.speedMax = 6.0f;
    // 1 cm along +x, from 8 m away: a tenth of a pixel as given.
    data.arrows.push_back({glm::vec3(0.0f), glm::vec3(0.01f, 0.0f, 0.0f), 3.0f});
    const Image image = drawOnBlack(*context, overlay, data);
    int minX = SIZE_PX, maxX = -1;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const uint8_t* p = &image.rgba[(size_t(y) * image.width + x) * 4];
            if (std::max({p[0], p[1], p[2]}) > 0)
                minX = std::min(minX, x), maxX = std::max(maxX, x);
        }
    ASSERT_GE(maxX, 0) << "the arrow vanished";
    // Rasterisation may lose a pixel at each end of the outline.
    constexpr int END_PIXELS = 2;
    EXPECT_GE(maxX - minX + 1, int(MIN_ARROW_LENGTH_PX) - END_PIXELS);
}

TEST(OverlayVisibility, TheLegendDrawsItsHeadingLines) {
    auto context = createOsMesaContext(320, 240);
    FieldOverlay overlay(*context);
    FieldOverlayData data;
    data.speedMax = 6.0f;
    data.slice = uniformSlice(3.0f);
    auto litInLegendCorner = [&](const FieldOverlayData& d) {
        context->makeCurrent();
        glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        overlay.draw(above(), d);
        Image image;
        context->readPixels(image);
        // White text pixels in the top-right quarter (the legend's corner; the slice is grey-free).
        int n = 0;
        for (int y = 0; y < image.height / 2; ++y)
            for (int x = image.width / 2; x < image.width; ++x) {
                const uint8_t* p = &image.rgba[(size_t(y) * image.width + x) * 4];
                if (p[0] > 200 && p[1] > 200 && p[2] > 200) ++n;
            }
        return n;
    };
    const int bare = litInLegendCorner(data);
    data.quantity = "wind speed";
    data.where = "2 m above ground";
    const int headed = litInLegendCorner(data);
    // Each lit glyph pixel of the two lines, at text scale 1: at least one per character.
    const int minHeadingPixels = int(data.quantity.size() + data.where.size()) - 5;  // 5 spaces
    EXPECT_GE(headed - bare, minHeadingPixels);
    EXPECT_GT(textWidth_px(data.where, 1), 0);
}

}  // namespace
}  // namespace gale::render
