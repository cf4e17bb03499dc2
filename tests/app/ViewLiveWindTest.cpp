// Live wind in `gale view` (under xvfb-run, as View.*): a scripted click drops a whirlwind where
// the cursor meets the terrain and the grass there answers within a few frames; and `gale bench
// view --quick` gives a row for every example scene; `gale bench unsteady --live --advection`
// steps a scene with the scheme it names.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../render/RenderTestUtil.h"
#include "AppTestSupport.h"
#include "render/ImageIO.h"

namespace gale::app::test {
namespace {

// Still air over flat ground, looked at from above: only a dropped source moves the grass. The
// camera's centre ray meets the ground at its target, (16, 16), where the click goes. Every shell
// is drawn (lod_pixels = 0): in so small a window the level of detail would leave the grass 27 m
// below the camera as flat ground, and this test is about the wind reaching the grass.
const char* const CALM_SCENE = R"([terrain]
kind = "flat"
size_m = [32.0, 32.0]
spacing_m = 0.5

[grass]
height_m = 0.5
shells = 8
tile_m = 2.0
lod_pixels = 0.0

[grass.generated]
size = 64

[wind]
kind = "unsteady"
speed_mps = 0.0

[unsteady]
cfl = 2.0
duration_s = 4.0

[solver]
voxel_size_m = 1.0

[[lighting.light]]
position_m = [16.0, -20.0, 40.0]

[camera]
position_m = [16.0, 4.0, 24.0]
target_m = [16.0, 16.0, 0.0]

[output]
width = 160
height = 120
fps = 30.0
)";

// Pixels that differ by more than this (8-bit levels) count as changed: above the run-to-run noise
// of the same frame (zero here: the solver is deterministic), below a bent blade's change.
constexpr int CHANGED_LEVEL = 24;
// The whirlwind bends the grass in a disc of a few core radii around the click: a visible part
// of the middle of the frame changes. Still air changes none of it.
constexpr double MIN_CHANGED_FRACTION = 0.02;
// Three frames at 30 fps: the grass must answer within 100 ms of sim time.
constexpr int FRAMES_TO_ANSWER = 3;

TEST(View, UnderXvfbAScriptedClickDropsAWhirlwindThatTheGrassShowsWithinThreeFrames) {
    if (std::getenv("DISPLAY") == nullptr)
        GTEST_SKIP() << "no display; ctest runs this under xvfb-run";
    TempDir dir;
    writeFile(dir / "calm.toml", CALM_SCENE);
    const int clickFrame = 1, lastFrame = clickFrame + FRAMES_TO_ANSWER;
    auto view = [&](const std::string& input, const std::string& shot) {
        std::vector<std::string> args = {"view",         dir / "calm.toml",
                                         "--frames",     std::to_string(lastFrame + 1),
                                         "--screenshot", shot};
        if (!input.empty()) args.insert(args.end(), {"--input", input});
        return runGale(args, dir.path().string());
    };
    const RunResult still = view("", dir / "still.png");
    const RunResult clicked =
        view(std::to_string(clickFrame) + ":click:80,60", dir / "clicked.png");
    ASSERT_EQ(still.exitCode, 0) << still.err;
    ASSERT_EQ(clicked.exitCode, 0) << clicked.err;
    EXPECT_NE(clicked.err.find("whirlwind at (16.0, 16.0) m"), std::string::npos) << clicked.err;

    const render::Image a = render::readImageRgba8(dir / "still.png");
    const render::Image b = render::readImageRgba8(dir / "clicked.png");
    const double changed = render::test::compareImages(a, b, CHANGED_LEVEL).differingFraction;
    EXPECT_GT(changed, MIN_CHANGED_FRACTION)
        << "the grass did not answer the click within " << FRAMES_TO_ANSWER << " frames";
}

TEST(View, UnderXvfbTheCKeyMovesTheLiveWindToCellsTwiceTheScenesAndBack) {
    if (std::getenv("DISPLAY") == nullptr)
        GTEST_SKIP() << "no display; ctest runs this under xvfb-run";
    TempDir dir;
    writeFile(dir / "calm.toml", CALM_SCENE);
    const RunResult r =
        runGale({"view", dir / "calm.toml", "--frames", "12", "--keys", ".c....c....."},
                dir.path().string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // 32 x 32 m under a 12 m top (the calm scene's automatic one): 16 x 16 cells of 2 m.
    EXPECT_NE(r.err.find("live wind on 2 m cells (16 x 16 x"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("live wind on 1 m cells (32 x 32 x"), std::string::npos) << r.err;
}

TEST(View, TheCKeyInASteadySceneSaysItNeedsAnUnsteadyOne) {
    if (std::getenv("DISPLAY") == nullptr)
        GTEST_SKIP() << "no display; ctest runs this under xvfb-run";
    const RunResult r = runGale(
        {"view", sourcePath("tests/data/scenes/tiny.toml"), "--frames", "3", "--keys", ".c."});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("a coarser live grid needs an unsteady scene"), std::string::npos)
        << r.err;
}

TEST(View, LiveWindInputThatCannotBeReadIsBadInput) {
    const RunResult r = runGale({"view", sourcePath("tests/data/scenes/tiny.toml"), "--input",
                                 "1:tornado:3,4", "--frames", "1"});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("--input: entry '1:tornado:3,4': unknown action 'tornado'"),
              std::string::npos)
        << r.err;
}

TEST(BenchLiveStep, AdvectionOptionReplacesTheScenesSchemeAndNamesItInTheRow) {
    TempDir dir;
    writeFile(dir / "calm.toml", CALM_SCENE);
    const RunResult r = runGale({"bench", "unsteady", "--live", dir / "calm.toml", "--advection",
                                 "maccormack", "--steps", "2", "--json", dir / "live.json"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json rows = nlohmann::json::parse(readFile(dir / "live.json")).at("live_step");
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_EQ(rows[0].at("scene").get<std::string>(), "calm (maccormack)");
    EXPECT_EQ(rows[0].at("steps").get<int>(), 2);
    EXPECT_GT(rows[0].at("cpu_ms_per_step").get<double>(), 0.0);
    // The projection leaves some divergence, never a negative or non-finite one.
    const double div = rows[0].at("max_divergence_scaled").get<double>();
    EXPECT_TRUE(std::isfinite(div) && div >= 0.0) << div;
}

TEST(BenchLiveStep, UnknownAdvectionSchemeIsBadInput) {
    const RunResult r =
        runGale({"bench", "unsteady", "--live",
                 sourcePath("tests/data/live/live_box_64x64x24.toml"), "--advection", "upwind"});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("--advection"), std::string::npos) << r.err;
}

TEST(BenchView, QuickRunGivesARowForEveryExampleScene) {
    TempDir dir;
    const std::string examples = sourcePath("examples");
    const RunResult r = runGale({"bench", "view", "--quick", "--width", "96", "--height", "72",
                                 "--json", dir / "view.json", examples});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::vector<std::string> expected;
    for (const auto& e : fs::directory_iterator(examples))
        if (e.path().extension() == ".toml") expected.push_back(e.path().stem().string());
    std::sort(expected.begin(), expected.end());
    const nlohmann::json doc = nlohmann::json::parse(readFile(dir / "view.json"));
    std::vector<std::string> rows;
    for (const auto& row : doc.at("rows")) {
        rows.push_back(row.at("scene").get<std::string>());
        EXPECT_GT(row.at("fps").get<double>(), 0.0) << rows.back();
        // The parts are each measured, none negative, and sum to the frame.
        for (const char* part : {"wind_ms", "upload_ms", "draw_ms", "present_ms"})
            EXPECT_GE(row.at(part).get<double>(), 0.0) << rows.back() << " " << part;
    }
    EXPECT_EQ(rows, expected);
    for (const std::string& name : expected)
        EXPECT_NE(r.out.find(name), std::string::npos) << "no table row for " << name;
}

}  // namespace
}  // namespace gale::app::test
