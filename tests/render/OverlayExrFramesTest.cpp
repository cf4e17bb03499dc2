// EXR frames (output.format = "exr"): half floats of linear light, decoded from the frame's sRGB.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>

#include "RenderTestUtil.h"
#include "render/ImageIO.h"

namespace gale::render {
namespace {

// Half floats carry 11 significant bits: 1e-3 relative covers values in [0, 1].
constexpr float HALF_TOL = 1e-3f;

TEST(ExrFrames, HoldLinearLightDecodedFromSrgbAndKeepAlpha) {
    Image image;
    image.width = 3;
    image.height = 1;
    image.rgba = {0, 0, 0, 255, 128, 128, 128, 255, 255, 255, 255, 64};
    const auto dir = test::freshTestDir("exr_frames");
    const std::string path = (dir / "frame.exr").string();
    writeImageAtomic(image, path);
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in) << OIIO::geterror();
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::HALF);
    ASSERT_EQ(in->spec().nchannels, 4);
    std::vector<float> px(12);
    ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, px.data()));
    EXPECT_NEAR(px[0], 0.0f, HALF_TOL);
    // sRGB 128/255 is 21.6 % linear light (IEC 61966-2-1).
    EXPECT_NEAR(px[4], std::pow((128.0f / 255.0f + 0.055f) / 1.055f, 2.4f), HALF_TOL);
    EXPECT_NEAR(px[4], 0.2158f, HALF_TOL);
    EXPECT_NEAR(px[8], 1.0f, HALF_TOL);
    EXPECT_NEAR(px[11], 64.0f / 255.0f, HALF_TOL);
}

}  // namespace
}  // namespace gale::render
