// Contact sheets and animated GIFs: sizes, frame selection, frame count, nothing left on failure.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "render/Animation.h"
#include "render/ImageIO.h"

namespace {

namespace fs = std::filesystem;
using namespace gale::render;

Image solid(int w, int h, uint8_t r, uint8_t g, uint8_t b) {
    Image im;
    im.width = w;
    im.height = h;
    im.rgba.resize(size_t(w) * h * 4);
    for (size_t p = 0; p < im.rgba.size(); p += 4) {
        im.rgba[p] = r, im.rgba[p + 1] = g, im.rgba[p + 2] = b, im.rgba[p + 3] = 255;
    }
    return im;
}

fs::path freshFolder(const std::string& name) {
    const fs::path dir = fs::path(GALE_BINARY_DIR) / "test-output" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

TEST(Animation, SheetIndicesAreEvenlySpacedWithFirstAndLast) {
    EXPECT_EQ(AnimationWriter::sheetIndices(48, 4), (std::vector<int>{0, 16, 31, 47}));
    EXPECT_EQ(AnimationWriter::sheetIndices(3, 24), (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(AnimationWriter::sheetIndices(1, 24), (std::vector<int>{0}));
}

TEST(Animation, DownscaleAveragesAreas) {
    Image im = solid(4, 2, 0, 0, 0);
    // Left half white, right half black: a 2x1 result is one white and one black pixel.
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x)
            for (int c = 0; c < 3; ++c) im.rgba[(y * 4 + x) * 4 + c] = 255;
    const Image small = downscale(im, 2, 1);
    EXPECT_EQ(small.rgba[0], 255);
    EXPECT_EQ(small.rgba[4], 0);
    const Image one = downscale(im, 1, 1);
    EXPECT_NEAR(one.rgba[0], 128, 1);
}

TEST(Animation, WritesAGridSheetAndAGifWithEveryFrame) {
    const fs::path dir = freshFolder("animation");
    AnimationOptions options;
    options.sheetPath = (dir / "sheet.png").string();
    options.gifPath = (dir / "anim.gif").string();
    options.sheetColumns = 3;
    options.sheetFrames = 5;
    options.sheetThumbWidth = 40;
    options.fps = 12.0;
    {
        AnimationWriter writer(options, 7);
        for (int k = 0; k < 7; ++k) writer.addFrame(solid(80, 60, uint8_t(k * 30), 100, 50), k);
        writer.finish();
    }
    const Image sheet = readImageRgba8(options.sheetPath);
    // 3 columns x 2 rows of 40x30 thumbnails with 4-pixel gaps.
    EXPECT_EQ(sheet.width, 3 * 40 + 4 * 4);
    EXPECT_EQ(sheet.height, 2 * 30 + 3 * 4);
    auto in = OIIO::ImageInput::open(options.gifPath);
    ASSERT_TRUE(in) << OIIO::geterror();
    int frames = 0;
    while (in->seek_subimage(frames, 0)) ++frames;
    EXPECT_EQ(frames, 7);
    // Nothing else in the folder: no temporary files left.
    int files = 0;
    for (const auto& e : fs::directory_iterator(dir)) (void)e, ++files;
    EXPECT_EQ(files, 2);
}

TEST(Animation, AnUnfinishedWriterLeavesNoGif) {
    const fs::path dir = freshFolder("animation-abandoned");
    AnimationOptions options;
    options.gifPath = (dir / "anim.gif").string();
    {
        AnimationWriter writer(options, 10);
        writer.addFrame(solid(32, 32, 10, 20, 30), 0);
        // Interrupted before finish().
    }
    EXPECT_TRUE(fs::is_empty(dir));
}

}  // namespace
