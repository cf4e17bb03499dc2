// The headless OSMesa context (docs/design.md 7).
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <gtest/gtest.h>

#include "render/GlContext.h"
#include "render/GlInfo.h"

namespace gale::render {
namespace {

TEST(OsMesaContext, Reports45CoreProfileWithDepthBuffer) {
    auto context = createOsMesaContext(64, 48);
    const GlInfo info = queryGlInfo();
    EXPECT_EQ(info.majorVersion, 4);
    EXPECT_GE(info.minorVersion, 5);
    EXPECT_TRUE(info.coreProfile);
    EXPECT_GE(info.depthBits, 24);
    EXPECT_EQ(context->width(), 64);
    EXPECT_EQ(context->height(), 48);
    EXPECT_NE(context->description().find("4.5"), std::string::npos) << context->description();
}

TEST(OsMesaContext, ReadPixelsReturnsRowsTopDown) {
    auto context = createOsMesaContext(8, 6);
    glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    // GL's window origin is bottom-left: the scissor box below is the upper half of the image.
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 3, 8, 3);
    glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    Image image;
    context->readPixels(image);
    ASSERT_EQ(image.rgba.size(), 8u * 6u * 4u);
    const uint8_t* top = &image.rgba[0];
    const uint8_t* bottom = &image.rgba[(5 * 8) * 4];
    EXPECT_EQ(top[0], 255);
    EXPECT_EQ(top[2], 0);
    EXPECT_EQ(bottom[0], 0);
    EXPECT_EQ(bottom[2], 255);
}

TEST(OsMesaContext, RejectsEmptySize) {
    EXPECT_THROW(createOsMesaContext(0, 10), std::runtime_error);
}

}  // namespace
}  // namespace gale::render
