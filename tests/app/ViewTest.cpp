// `gale view`: under a virtual display (ctest runs View.* under xvfb-run) it opens a window,
// draws N frames, saves a screenshot and exits; the screenshot is the headless render of the same
// frame. Without a display it fails with a message pointing to `gale render`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "../render/RenderTestUtil.h"
#include "AppTestSupport.h"
#include "render/ImageIO.h"

namespace gale::app::test {
namespace {

// The window's context is OSMesa too (docs/design.md 7), so the pixels should be those of `gale
// render`; the same slack as the reference-image tests covers any difference in the copy to the
// window.
constexpr int CHANNEL_TOLERANCE = 8;
constexpr double MAX_DIFFERING_FRACTION = 0.005;
// A blank (one-colour) frame has variance 0; sky over grass has thousands (8-bit levels squared).
constexpr double MIN_PIXEL_VARIANCE = 100.0;

double lumaVariance(const render::Image& image) {
    double sum = 0.0, sum2 = 0.0;
    const size_t n = size_t(image.width) * image.height;
    for (size_t p = 0; p < n; ++p) {
        const double y = 0.2126 * image.rgba[p * 4] + 0.7152 * image.rgba[p * 4 + 1] +
                         0.0722 * image.rgba[p * 4 + 2];
        sum += y;
        sum2 += y * y;
    }
    const double mean = sum / double(n);
    return sum2 / double(n) - mean * mean;
}

/// Fraction of pixels of two same-size image files differing by more than CHANNEL_TOLERANCE.
double differingFraction(const std::string& pathA, const std::string& pathB) {
    const render::Image a = render::readImageRgba8(pathA);
    const render::Image b = render::readImageRgba8(pathB);
    return render::test::compareImages(a, b, CHANNEL_TOLERANCE).differingFraction;
}

TEST(View, UnderXvfbScreenshotMatchesHeadlessRenderOfTheSameFrame) {
    if (std::getenv("DISPLAY") == nullptr)
        GTEST_SKIP() << "no display; ctest runs this under xvfb-run";
    TempDir dir;
    const std::string scene = sourcePath("tests/data/scenes/tiny.toml");
    const std::string shot = dir / "view.png";
    const RunResult view = runGale({"view", scene, "--frames", "3", "--screenshot", shot, "--width",
                                    "160", "--height", "120"});
    ASSERT_EQ(view.exitCode, 0) << view.err;
    EXPECT_NE(view.out.find("viewed 3 frames"), std::string::npos) << view.out;
    const RunResult render = runGale({"render", scene, "-o", dir / "frames", "--frames", "3",
                                      "--width", "160", "--height", "120"});
    ASSERT_EQ(render.exitCode, 0) << render.err;

    const render::Image actual = render::readImageRgba8(shot);
    const render::Image expected = render::readImageRgba8(dir / "frames/frame_0002.png");
    EXPECT_GT(lumaVariance(actual), MIN_PIXEL_VARIANCE) << "the screenshot is blank";
    ASSERT_EQ(actual.width, expected.width);
    ASSERT_EQ(actual.height, expected.height);
    const render::test::ImageDiff diff =
        render::test::compareImages(actual, expected, CHANNEL_TOLERANCE);
    if (diff.differingFraction > MAX_DIFFERING_FRACTION) {
        const fs::path out = fs::path(GALE_BINARY_DIR) / "app_test_output";
        fs::create_directories(out);
        render::writeImageAtomic(actual, (out / "view.actual.png").string());
        render::writeImageAtomic(expected, (out / "view.expected.png").string());
        render::writeImageAtomic(diff.diff, (out / "view.diff.png").string());
        ADD_FAILURE() << diff.differingFraction * 100.0 << "% of pixels differ by more than "
                      << CHANNEL_TOLERANCE << "/255 (max " << diff.maxChannelDiff << "); images in "
                      << out;
    }
}

TEST(View, UnderXvfbKeysToggleGrassAndSaveAScreenshotWithTheHeadsUpLine) {
    if (std::getenv("DISPLAY") == nullptr)
        GTEST_SKIP() << "no display; ctest runs this under xvfb-run";
    TempDir dir;
    const std::string scene = sourcePath("tests/data/scenes/tiny.toml");
    const std::vector<std::string> size = {"--width", "160", "--height", "120"};
    auto view = [&](const std::string& keys, const std::string& shot) {
        std::vector<std::string> args = {"view",         scene, "--frames", "3",
                                         "--screenshot", shot,  "--keys",   keys};
        args.insert(args.end(), size.begin(), size.end());
        return runGale(args, dir.path().string());
    };
    // Frame 0 presses S (saved into the current folder, heads-up line included), frame 1 G.
    const RunResult withGrass = view("...", dir / "grass.png");
    const RunResult noGrass = view("sg.", dir / "nograss.png");
    ASSERT_EQ(withGrass.exitCode, 0) << withGrass.err;
    ASSERT_EQ(noGrass.exitCode, 0) << noGrass.err;
    EXPECT_TRUE(fs::exists(dir / "gale_view_0.png")) << noGrass.err;
    // S again in a new run: gale_view_0.png is taken, so it saves gale_view_1.png and leaves the
    // earlier screenshot as it was.
    const std::string first = readFile(dir / "gale_view_0.png");
    const RunResult again = view("s..", dir / "again.png");
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_EQ(readFile(dir / "gale_view_0.png"), first);
    EXPECT_TRUE(fs::exists(dir / "gale_view_1.png")) << again.err;
    // Hiding the shells leaves the bare ground: a large part of the frame changes.
    constexpr double MIN_CHANGED_FRACTION = 0.05;
    EXPECT_GT(differingFraction(dir / "grass.png", dir / "nograss.png"), MIN_CHANGED_FRACTION);
}

TEST(OverlayRender, HeadlessRenderDrawsTheSceneOverlaysAndCheckListsThem) {
    TempDir dir;
    const std::string base = readFile(sourcePath("tests/data/scenes/tiny.toml"));
    writeFile(dir / "plain.toml", base);
    writeFile(dir / "views.toml", base + "\n[overlay]\narrows = true\narrow_spacing_m = 2.0\n");
    const RunResult check = runGale({"check", dir / "views.toml"});
    ASSERT_EQ(check.exitCode, 0) << check.err;
    EXPECT_NE(check.out.find("overlay   arrows every 2 m"), std::string::npos) << check.out;
    for (const char* name : {"plain", "views"}) {
        const RunResult r =
            runGale({"render", dir / (std::string(name) + ".toml"), "-o", dir / name, "--frames",
                     "1", "--width", "160", "--height", "120"});
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    // Arrows and the legend cover a visible part of the frame.
    constexpr double MIN_OVERLAY_FRACTION = 0.01;
    EXPECT_GT(differingFraction(dir / "plain/frame_0000.png", dir / "views/frame_0000.png"),
              MIN_OVERLAY_FRACTION);
}

TEST(OverlayRender, ExrFormatWritesExrFrames) {
    TempDir dir;
    std::string text = readFile(sourcePath("tests/data/scenes/tiny.toml"));
    text.replace(text.find("[output]"), 8, "[output]\nformat = \"exr\"");
    writeFile(dir / "exr.toml", text);
    const RunResult r = runGale({"render", dir / "exr.toml", "-o", dir / "out", "--frames", "2"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "out/frame_0001.exr"));
    EXPECT_FALSE(fs::exists(dir / "out/frame_0001.png"));
}

TEST(View, WithoutADisplaySaysUseGaleRenderAndFails) {
    const char* saved = std::getenv("DISPLAY");
    const std::string display = saved ? saved : "";
    ::unsetenv("DISPLAY");
    const RunResult r =
        runGale({"view", sourcePath("tests/data/scenes/tiny.toml"), "--frames", "1"});
    if (saved) ::setenv("DISPLAY", display.c_str(), 1);
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("gale: error: no display"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("gale render"), std::string::npos) << r.err;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
}

TEST(View, BadSceneIsBadInputEvenWithoutADisplay) {
    const RunResult r = runGale({"view", sourcePath("tests/data/scenes/unknown_key.toml")});
    EXPECT_EQ(r.exitCode, 2) << r.err;
}

}  // namespace
}  // namespace gale::app::test
