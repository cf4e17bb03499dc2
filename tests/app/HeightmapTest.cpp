// Heightmaps: 8- and 16-bit images become the heights they encode, in the documented orientation;
// bad images are refused with the file named.

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "AppTestSupport.h"
#include "app/io/Errors.h"
#include "app/scene/Heightmap.h"
#include "sim/Heightfield.h"

namespace gale::app {
namespace {

using test::TempDir;

/// float32 heights of a few metres: rounding in the float store.
constexpr double FLOAT_STORE_TOLERANCE_M = 1e-5;

template <typename T>
void writeGrey(const std::string& path, int w, int h, const std::vector<T>& pixels,
               OIIO::TypeDesc type, int channels = 1) {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out) << OIIO::geterror();
    OIIO::ImageSpec spec(w, h, channels, type);
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(type, pixels.data())) << out->geterror();
    ASSERT_TRUE(out->close());
}

std::string errorOf(const HeightmapSpec& spec) {
    try {
        loadHeightmap(spec);
    } catch (const ImageError& e) {
        return e.what();
    }
    return "";
}

TEST(Heightmap, EightBitPngGivesOffsetPlusScaleTimesValue) {
    TempDir dir;
    // 3 x 2 image, rows top-down: top row 0, 51, 255; bottom row 102, 153, 204.
    const std::vector<uint8_t> px = {0, 51, 255, 102, 153, 204};
    writeGrey(dir / "h8.png", 3, 2, px, OIIO::TypeDesc::UINT8);
    const sim::Heightfield f = loadHeightmap({dir / "h8.png", /*metresPerPixel=*/0.5,
                                              /*heightScale_m=*/10.0, /*heightOffset_m=*/-2.0});
    ASSERT_EQ(f.nx, 3);
    ASSERT_EQ(f.ny, 2);
    EXPECT_DOUBLE_EQ(f.spacing_m, 0.5);
    // The top row is the far edge: row 0 -> j = 1.
    EXPECT_NEAR(f.at(0, 1), -2.0, FLOAT_STORE_TOLERANCE_M);
    EXPECT_NEAR(f.at(1, 1), -2.0 + 10.0 * 51 / 255.0, FLOAT_STORE_TOLERANCE_M);
    EXPECT_NEAR(f.at(2, 1), 8.0, FLOAT_STORE_TOLERANCE_M);
    EXPECT_NEAR(f.at(0, 0), -2.0 + 10.0 * 102 / 255.0, FLOAT_STORE_TOLERANCE_M);
    EXPECT_NEAR(f.at(2, 0), -2.0 + 10.0 * 204 / 255.0, FLOAT_STORE_TOLERANCE_M);
}

TEST(Heightmap, SixteenBitPngKeepsSixteenBitsOfHeight) {
    TempDir dir;
    const std::vector<uint16_t> px = {0, 1, 65535, 32768};
    writeGrey(dir / "h16.png", 2, 2, px, OIIO::TypeDesc::UINT16);
    const sim::Heightfield f = loadHeightmap({dir / "h16.png", 1.0, 65.535, 0.0});
    EXPECT_NEAR(f.at(0, 1), 0.0, FLOAT_STORE_TOLERANCE_M);
    EXPECT_NEAR(f.at(1, 1), 0.001, FLOAT_STORE_TOLERANCE_M);  // one 16-bit step is 1 mm here
    EXPECT_NEAR(f.at(0, 0), 65.535, 1e-4);
    EXPECT_NEAR(f.at(1, 0), 32.768, 1e-4);
}

TEST(Heightmap, RgbImageUsesItsFirstChannel) {
    TempDir dir;
    const std::vector<uint8_t> px = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    writeGrey(dir / "rgb.png", 2, 2, px, OIIO::TypeDesc::UINT8, /*channels=*/3);
    const sim::Heightfield f = loadHeightmap({dir / "rgb.png", 1.0, 1.0, 0.0});
    EXPECT_NEAR(f.at(0, 1), 1.0, FLOAT_STORE_TOLERANCE_M);
    EXPECT_NEAR(f.at(1, 1), 0.0, FLOAT_STORE_TOLERANCE_M);
}

TEST(Heightmap, FloatImageValuesAreRaw) {
    TempDir dir;
    const std::vector<float> px = {-3.5f, 0.0f, 2.25f, 1000.0f};
    writeGrey(dir / "f.exr", 2, 2, px, OIIO::TypeDesc::FLOAT);
    const sim::Heightfield f = loadHeightmap({dir / "f.exr", 1.0, 1.0, 0.0});
    EXPECT_NEAR(f.at(0, 1), -3.5, FLOAT_STORE_TOLERANCE_M);
    EXPECT_NEAR(f.at(1, 0), 1000.0, FLOAT_STORE_TOLERANCE_M);
}

TEST(Heightmap, WrittenPngReadsBackWithinHalfASixteenBitStep) {
    TempDir dir;
    sim::TerrainSpec spec;
    spec.kind = sim::TerrainKind::GaussianHill;
    spec.sizeX_m = 20, spec.sizeY_m = 12, spec.spacing_m = 0.5;
    spec.height_m = 5, spec.radius_m = 4, spec.centerX_m = 8, spec.centerY_m = 5;
    const sim::Heightfield field = sim::makeTerrain(spec);
    const HeightmapRange range = writeHeightmapPng16(field, dir / "t.png");
    const double span_m = range.maxHeight_m - range.minHeight_m;
    const sim::Heightfield back =
        loadHeightmap({dir / "t.png", field.spacing_m, span_m, range.minHeight_m});
    ASSERT_EQ(back.nx, field.nx);
    ASSERT_EQ(back.ny, field.ny);
    const double tolerance_m = span_m / 131070.0 + FLOAT_STORE_TOLERANCE_M;  // half a 16-bit step
    for (int j = 0; j < field.ny; ++j)
        for (int i = 0; i < field.nx; ++i)
            ASSERT_NEAR(back.at(i, j), field.at(i, j), tolerance_m) << i << ", " << j;
    // No temporary file is left next to it.
    EXPECT_EQ(test::countFiles(dir.path().string()), 1);
}

TEST(Heightmap, MissingFileIsNamed) {
    const std::string message = errorOf({"/nonexistent/gale/h.png"});
    EXPECT_NE(message.find("/nonexistent/gale/h.png: no such file"), std::string::npos) << message;
}

TEST(Heightmap, NotAnImageIsRefused) {
    TempDir dir;
    test::writeFile(dir / "text.png", "hello, not a png\n");
    const std::string message = errorOf({dir / "text.png"});
    EXPECT_NE(message.find("text.png: not a readable image"), std::string::npos) << message;
}

TEST(Heightmap, TruncatedPngIsRefused) {
    TempDir dir;
    // Noise does not compress, so the pixel data spans most of the file.
    std::vector<uint16_t> px(64 * 64);
    uint32_t state = 12345;
    for (uint16_t& p : px)
        p = static_cast<uint16_t>((state = state * 1664525u + 1013904223u) >> 16);
    writeGrey(dir / "full.png", 64, 64, px, OIIO::TypeDesc::UINT16);
    const std::string full = test::readFile(dir / "full.png");
    ASSERT_GT(full.size(), 2000u);
    test::writeFile(dir / "cut.png", full.substr(0, full.size() / 2));
    const std::string message = errorOf({dir / "cut.png"});
    EXPECT_NE(message.find("cut.png: truncated or corrupt"), std::string::npos) << message;
}

TEST(Heightmap, OneByOneImageIsTooSmall) {
    TempDir dir;
    writeGrey(dir / "one.png", 1, 1, std::vector<uint8_t>{128}, OIIO::TypeDesc::UINT8);
    const std::string message = errorOf({dir / "one.png"});
    EXPECT_NE(message.find("one.png: too small"), std::string::npos) << message;
    EXPECT_NE(message.find("1 x 1"), std::string::npos) << message;
}

TEST(Heightmap, EnormousImageIsRefusedFromItsHeader) {
    TempDir dir;
    // 20000 x 2 pixels: little data, but more samples per side than a heightfield may have.
    writeGrey(dir / "wide.png", 20000, 2, std::vector<uint8_t>(40000, 7), OIIO::TypeDesc::UINT8);
    const std::string message = errorOf({dir / "wide.png"});
    EXPECT_NE(message.find("wide.png: too large"), std::string::npos) << message;
}

TEST(Heightmap, NanPixelIsRefusedWithItsPosition) {
    TempDir dir;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    writeGrey(dir / "nan.exr", 2, 2, std::vector<float>{0.0f, 1.0f, nan, 2.0f},
              OIIO::TypeDesc::FLOAT);
    const std::string message = errorOf({dir / "nan.exr"});
    EXPECT_NE(message.find("nan.exr: NaN pixel at column 0, row 1"), std::string::npos) << message;
}

}  // namespace
}  // namespace gale::app
