// Ctrl-C during a long render or solve stops cleanly: finished frames stay and are complete, no
// file is half written, no temporary is left, and a message says where the run stopped.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <thread>

#include "ReliabilitySupport.h"
#include "render/ImageIO.h"

namespace gale::reliability {
namespace {

/// How long we wait for a long run to reach the point we interrupt it at, and for it to stop
/// after SIGINT (a frame of the tiny scene takes milliseconds; sanitizers slow it 10-20 times).
constexpr double REACH_TIMEOUT_S = 120.0;
constexpr double STOP_TIMEOUT_S = 60.0;
/// The exit code of a run stopped by Ctrl-C (128 + SIGINT, docs/cli.md).
constexpr int EXIT_INTERRUPTED = 130;
/// Frames finished before we interrupt: more than one, to see several complete frames kept.
constexpr int FRAMES_BEFORE_INTERRUPT = 3;

std::string frameName(int k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", k);
    return name;
}

/// The frames in `folder` are exactly frame_0000 .. frame_<n-1>, each a complete w x h PNG.
void expectCompleteFrames(const std::string& folder, int n, int width, int height) {
    int pngs = 0;
    const std::regex frame(R"(frame_[0-9]{4,}\.png)");  // not frame_sheet.png
    for (const auto& [rel, size] : listTree(folder)) pngs += std::regex_match(rel, frame);
    EXPECT_EQ(pngs, n) << describeTree(listTree(folder));
    for (int k = 0; k < n; ++k) {
        render::Image image;
        ASSERT_NO_THROW(image = render::readImageRgba8(folder + "/" + frameName(k))) << k;
        EXPECT_EQ(image.width, width);
        EXPECT_EQ(image.height, height);
    }
}

/// Waits until `ready` (asserting it comes within REACH_TIMEOUT_S), sends SIGINT and asserts
/// that the child then exits by itself with code 130; `r` receives how it ended. Call under
/// ASSERT_NO_FATAL_FAILURE so a failed assertion ends the test.
void interruptWhenReady(Child& child, const std::function<bool()>& ready, RunResult& r) {
    ASSERT_TRUE(waitFor(ready, REACH_TIMEOUT_S)) << child.errSoFar();
    child.signal(SIGINT);
    r = child.wait(STOP_TIMEOUT_S);
    ASSERT_FALSE(r.timedOut) << r.describe();
    ASSERT_EQ(r.signal, 0) << r.describe();
    EXPECT_EQ(r.exitCode, EXIT_INTERRUPTED) << r.describe();
}

/// The tiny scene; the tests ask it for 100000 frames, far more than they let it finish.
std::string longTinyScene() { return readFile(sourcePath("tests/data/scenes/tiny.toml")); }

TEST(Interrupt, CtrlCDuringRenderKeepsCompleteFramesNamesTheLastAndExits130) {
    TempDir cwd;
    writeFile(cwd / "scene.toml", longTinyScene());
    RunOptions options;
    options.cwd = cwd.str();
    Child child({"render", "scene.toml", "-o", "frames", "--frames", "100000"}, options);
    const std::string folder = cwd / "frames";
    RunResult r;
    ASSERT_NO_FATAL_FAILURE(interruptWhenReady(
        child,
        [&] {
            // Frames move into place when the run ends; its progress lines say how far it is.
            return child.errSoFar().find(" " + std::to_string(FRAMES_BEFORE_INTERRUPT + 1) +
                                         "/100000") != std::string::npos;
        },
        r));

    const nlohmann::json report = nlohmann::json::parse(readFile(folder + "/frame_report.json"));
    const int done = report["frames"];
    EXPECT_TRUE(report["interrupted"].get<bool>());
    EXPECT_GT(done, FRAMES_BEFORE_INTERRUPT);
    EXPECT_LT(done, 100000);
    EXPECT_EQ(report["files"].size(), static_cast<size_t>(done));
    expectCompleteFrames(folder, done, 64, 48);
    EXPECT_TRUE(hiddenOrTemporary(cwd.str()).empty()) << describeTree(listTree(cwd.str()));
    // Where it stopped: the message names the last finished frame and the count.
    EXPECT_NE(r.out.find("interrupted"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(frameName(done - 1)), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(std::to_string(done) + " of 100000"), std::string::npos) << r.out;
}

TEST(Interrupt, CtrlCAtAnyMomentOfARenderLeavesNoPartialOrTemporaryFile) {
    // From before the scene is read to mid-frame: whatever the moment, the run ends (by exit 130,
    // or by the signal itself before anything is on disk) and leaves only complete files.
    for (const int delay_ms : {0, 20, 80, 200, 400, 700}) {
        SCOPED_TRACE("SIGINT after " + std::to_string(delay_ms) + " ms");
        TempDir cwd;
        writeFile(cwd / "scene.toml", longTinyScene());
        RunOptions options;
        options.cwd = cwd.str();
        Child child({"render", "scene.toml", "-o", "frames", "--frames", "100000"}, options);
        std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
        child.signal(SIGINT);
        const RunResult r = child.wait(STOP_TIMEOUT_S);
        ASSERT_FALSE(r.timedOut) << r.describe();
        EXPECT_TRUE(r.exitCode == EXIT_INTERRUPTED || r.signal == SIGINT) << r.describe();
        EXPECT_TRUE(hiddenOrTemporary(cwd.str()).empty()) << describeTree(listTree(cwd.str()));
        const std::string folder = cwd / "frames";
        if (fs::exists(folder + "/frame_report.json")) {
            const nlohmann::json report =
                nlohmann::json::parse(readFile(folder + "/frame_report.json"));
            expectCompleteFrames(folder, report["frames"], 64, 48);
        } else {
            // Stopped by the signal before the frame loop: no frame was written.
            expectCompleteFrames(folder, 0, 64, 48);
        }
    }
}

TEST(Interrupt, CtrlCDuringSolveWritesNoFieldSaysWhereAndExits130) {
    TempDir cwd;
    // Fine enough to take seconds: 161 x 161 x ~50 cells, a few hundred thousand air cells.
    writeFile(cwd / "scene.toml",
              "[terrain]\nkind = \"hemisphere\"\nsize_m = [40.0, 40.0]\nradius_m = 6.0\n"
              "[wind]\nkind = \"solved\"\n[solver]\nvoxel_size_m = 0.2\ntolerance = 1e-12\n"
              "max_iterations = 100000\n");
    RunOptions options;
    options.cwd = cwd.str();
    Child child({"solve", "scene.toml", "-o", "field/wind.vdb"}, options);
    RunResult r;
    ASSERT_NO_FATAL_FAILURE(interruptWhenReady(
        child, [&] { return child.errSoFar().find("solving") != std::string::npos; }, r));
    EXPECT_NE(r.err.find("interrupted"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("nothing written"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(cwd / "field/wind.vdb"));
    EXPECT_FALSE(fs::exists(cwd / "field/wind.json"));
    EXPECT_TRUE(hiddenOrTemporary(cwd.str()).empty()) << describeTree(listTree(cwd.str()));
}

}  // namespace
}  // namespace gale::reliability
