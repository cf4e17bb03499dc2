// The GLFW window context: same GL implementation as headless, or a clear no-display error.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <gtest/gtest.h>

#include <cstdlib>

#include "render/GlInfo.h"
#include "render/GlfwWindow.h"

namespace {

using gale::render::GlfwWindow;

TEST(GlfwWindow, WithoutADisplayFailsWithAMessageNamingGaleRender) {
    if (std::getenv("DISPLAY") != nullptr) GTEST_SKIP() << "a display is set; see the Xvfb test";
    try {
        GlfwWindow::open(64, 48, "gale test");
        FAIL() << "opened a window without a display";
    } catch (const gale::render::NoDisplayError& e) {
        EXPECT_NE(std::string(e.what()).find("gale render"), std::string::npos) << e.what();
    }
}

TEST(GlfwWindow, UnderXvfbOpensACoreContextThroughOsMesa) {
    if (std::getenv("DISPLAY") == nullptr) GTEST_SKIP() << "no display; run under xvfb-run";
    auto window = GlfwWindow::open(64, 48, "gale test");
    const gale::render::GlInfo info = gale::render::queryGlInfo();
    EXPECT_GE(info.majorVersion * 10 + info.minorVersion, 45);
    EXPECT_TRUE(info.coreProfile);
    EXPECT_NE(info.renderer.find("llvmpipe"), std::string::npos) << info.renderer;
    glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    gale::render::Image image;
    window->readPixels(image);
    ASSERT_EQ(image.rgba.size(), 64u * 48u * 4u);
    EXPECT_EQ(image.rgba[0], 255);
    EXPECT_EQ(image.rgba[1], 0);
    window->present();
    window->pollEvents();
}

}  // namespace
