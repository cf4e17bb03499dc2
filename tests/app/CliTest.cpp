// The gale program as a user meets it: exit codes, one-line errors naming file, field and reason,
// nothing written on bad input, and a tiny end-to-end render whose frames move. (The bad scenes
// of tests/data run once, through every verb, in tests/reliability/BadInputCorpusTest.cpp.)

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "AppTestSupport.h"
#include "render/Bend.h"
#include "render/ImageIO.h"

namespace gale::app {
namespace {

using test::runGale;
using test::RunResult;
using test::TempDir;

std::string corpus(const std::string& name) {
    return test::sourcePath("tests/data/scenes/" + name);
}

/// Exit code 2, exactly one stderr line "gale: error: ..." holding every fragment.
void expectBadInput(const RunResult& r, const std::vector<std::string>& fragments) {
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(test::countLines(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("gale: error: ", 0), 0u) << r.err;
    for (const std::string& f : fragments)
        EXPECT_NE(r.err.find(f), std::string::npos) << "'" << f << "' not in: " << r.err;
}

TEST(Cli, OutputFolderThatIsAFileIsBadInputForRenderAndCheck) {
    TempDir dir;
    test::writeFile(dir / "occupied", "a file where the frames should go\n");
    for (const char* verb : {"render", "check"}) {
        SCOPED_TRACE(verb);
        expectBadInput(runGale({verb, corpus("tiny.toml"), "-o", dir / "occupied"}),
                       {"-o", "occupied", "is a file"});
    }
    EXPECT_EQ(test::readFile(dir / "occupied"), "a file where the frames should go\n");
    EXPECT_EQ(test::countFiles(dir.path().string()), 1);
}

TEST(Cli, SceneOutputFolderThatIsAFileNamesTheSceneKey) {
    TempDir dir;
    test::writeFile(dir / "occupied", "x");
    test::writeFile(dir / "s.toml", "[output]\nframes = 1\nfolder = \"occupied\"\n");
    // output.folder resolves against the current directory: run from `dir`.
    expectBadInput(runGale({"render", "s.toml"}, dir.path().string()),
                   {"s.toml:3: output.folder", "is a file"});
}

TEST(Cli, MissingSceneIsBadInput) {
    expectBadInput(runGale({"check", "/nonexistent/scene.toml"}),
                   {"/nonexistent/scene.toml", "no such file"});
}

TEST(Cli, BadArgumentsExitTwo) {
    expectBadInput(runGale({"render"}), {"scene"});
    expectBadInput(runGale({"render", corpus("tiny.toml"), "--frames", "0"}), {"--frames"});
    expectBadInput(runGale({"frobnicate"}), {"frobnicate"});
    expectBadInput(runGale({}), {"gale --help"});
    expectBadInput(runGale({"blade", "--shells", "4"}), {"--intensity"});
}

TEST(Cli, HelpAndVersionExitZero) {
    RunResult r = runGale({"--version"});
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_EQ(r.out.rfind("gale ", 0), 0u) << r.out;
    for (std::vector<std::string> args : {std::vector<std::string>{"--help"},
                                          {"check", "--help"},
                                          {"render", "--help"},
                                          {"blade", "--help"},
                                          {"bench", "render", "--help"},
                                          {"terrain", "--help"}}) {
        r = runGale(args);
        EXPECT_EQ(r.exitCode, 0) << args[0];
        EXPECT_NE(r.out.find("Usage"), std::string::npos) << r.out;
    }
}

TEST(Cli, BladePrintsOneCsvLinePerShellAndTheBendsTip) {
    const RunResult r = runGale({"blade", "--shells", "12", "--intensity", "0.7", "--stiffness",
                                 "1.5", "--height-m", "0.6"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::istringstream lines(r.out);
    std::string line;
    std::getline(lines, line);
    EXPECT_EQ(line, "i,n_m,w_m");
    std::vector<std::string> rows;
    while (std::getline(lines, line)) rows.push_back(line);
    ASSERT_EQ(rows.size(), 13u);  // shells 0..N
    EXPECT_EQ(rows.front(), "0,0,0");
    int i = -1;
    double n = 0, w = 0;
    ASSERT_EQ(std::sscanf(rows.back().c_str(), "%d,%lf,%lf", &i, &n, &w), 3) << rows.back();
    EXPECT_EQ(i, 12);
    const auto bend = render::bendBlade(12, 0.6f, 0.7f, 1.5f);
    constexpr double PRINTED_TOLERANCE_M = 1e-7;  // printed with 9 significant digits
    EXPECT_NEAR(n, bend.back().n_m, PRINTED_TOLERANCE_M);
    EXPECT_NEAR(w, bend.back().w_m, PRINTED_TOLERANCE_M);
}

TEST(Cli, BladeSvgDrawsTheBladeAtomically) {
    TempDir dir;
    const RunResult r = runGale({"blade", "--shells", "8", "--intensity", "0.5", "--stiffness", "1",
                                 "--svg", dir / "blade.svg"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string svg = test::readFile(dir / "blade.svg");
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("<polyline"), std::string::npos);
    EXPECT_NE(svg.find("ground"), std::string::npos);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    EXPECT_EQ(test::countFiles(dir.path().string()), 1);  // no temporary left
}

TEST(Cli, CheckOnKnollSucceedsAndSaysWhatItLeavesOut) {
    TempDir dir;
    const RunResult r =
        runGale({"check", test::sourcePath("examples/knoll.toml"), "-o", dir / "o"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* fragment :
         {"gaussian_hill", "161 x 161", "vertices", "20 shells", "MIP levels", "point source",
          "groups", "2 point lights", "48 frames of 640 x 480", "left out", "no wind solver",
          "no window: headless"})
        EXPECT_NE(r.out.find(fragment), std::string::npos) << fragment << " not in:\n" << r.out;
    EXPECT_FALSE(test::fs::exists(dir / "o"));  // check creates nothing
}

TEST(Cli, CheckSaysWhatTheNearBladesDrawAndRefusesAnAbsurdBudget) {
    TempDir dir;
    const RunResult knoll =
        runGale({"check", test::sourcePath("examples/knoll.toml"), "-o", dir / "o"});
    ASSERT_EQ(knoll.exitCode, 0) << knoll.err;
    EXPECT_NE(knoll.out.find("blades    up to 6000 a frame"), std::string::npos) << knoll.out;
    EXPECT_NE(knoll.out.find("2 px wide at 480 px"), std::string::npos) << knoll.out;
    test::writeFile(dir / "shells.toml", "[terrain]\nkind = \"flat\"\n[grass]\nnear_blades = 0\n");
    const RunResult off = runGale({"check", dir / "shells.toml", "-o", dir / "o"});
    ASSERT_EQ(off.exitCode, 0) << off.err;
    EXPECT_NE(off.out.find("blades    off"), std::string::npos) << off.out;
    test::writeFile(dir / "absurd.toml",
                    "[terrain]\nkind = \"flat\"\n[grass]\nnear_blades = 1000001\n");
    const RunResult absurd = runGale({"check", dir / "absurd.toml", "-o", dir / "o"});
    EXPECT_EQ(absurd.exitCode, 2);
    EXPECT_NE(absurd.err.find("grass.near_blades"), std::string::npos) << absurd.err;
    EXPECT_FALSE(test::fs::exists(dir / "o"));
}

TEST(Cli, CheckNamesTheDefaultSunAndSkyWhenTheSceneHasNoLights) {
    TempDir dir;
    test::writeFile(dir / "dark.toml", "[terrain]\nkind = \"flat\"\n");
    const RunResult r = runGale({"check", dir / "dark.toml", "-o", dir / "o"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("1 point light"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("no [[lighting.light]]: a default sun (from the south-west, 40 deg up) "
                         "and a sky ambient"),
              std::string::npos)
        << r.out;
}

TEST(Cli, TinyRenderWritesThreeDistinctFramesAndAReport) {
    TempDir dir;
    const std::string out = dir / "frames";
    const RunResult r = runGale({"render", corpus("tiny.toml"), "-o", out});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("wrote 3 frames to " + out), std::string::npos) << r.out;
    // 3 frames, the contact sheet, the GIF and the report; no temporaries.
    ASSERT_EQ(test::countFiles(out), 6);
    const render::Image sheet = render::readImageRgba8(out + "/frame_sheet.png");
    EXPECT_GT(sheet.width, 64);  // three thumbnails side by side
    std::vector<render::Image> frames;
    for (int k = 0; k < 3; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "/frame_%04d.png", k);
        frames.push_back(render::readImageRgba8(out + name));
        EXPECT_EQ(frames.back().width, 64);
        EXPECT_EQ(frames.back().height, 48);
    }
    // The wind moves the grass: consecutive frames differ somewhere.
    for (int k = 1; k < 3; ++k) EXPECT_NE(frames[k].rgba, frames[k - 1].rgba) << "frame " << k;

    const nlohmann::json report = nlohmann::json::parse(test::readFile(out + "/frame_report.json"));
    EXPECT_EQ(report["frames"], 3);
    EXPECT_EQ(report["frame_ms"].size(), 3u);
    EXPECT_EQ(report["files"].size(), 3u);
    EXPECT_EQ(report["previews"].size(), 2u);
    EXPECT_NE(report["gl"].get<std::string>().find("OpenGL"), std::string::npos) << report["gl"];
    // Not a terminal: one progress line per frame.
    EXPECT_NE(r.err.find("frame 3/3"), std::string::npos) << r.err;
}

TEST(Cli, GrassTextureImageIsLoadedRelativeToTheScene) {
    TempDir dir;
    // A 32 x 32 RGBA texture: green blades (alpha = height) on every other texel.
    render::Image texture;
    texture.width = texture.height = 32;
    texture.rgba.assign(32 * 32 * 4, 0);
    for (int t = 0; t < 32 * 32; ++t) {
        uint8_t* p = &texture.rgba[t * 4];
        p[0] = 60, p[1] = 140, p[2] = 40, p[3] = (t % 2) ? static_cast<uint8_t>(100 + t % 155) : 0;
    }
    render::writeImageAtomic(texture, dir / "blades.png");
    test::writeFile(dir / "textured.toml",
                    "[terrain]\nsize_m = [8, 8]\nspacing_m = 0.5\nheight_m = 1\nradius_m = 2\n"
                    "[grass]\nshells = 4\ntexture = \"blades.png\"\n"
                    "[[lighting.light]]\nposition_m = [20, -10, 15]\n"
                    "[output]\nwidth = 64\nheight = 48\n");
    const RunResult c = runGale({"check", dir / "textured.toml", "-o", dir / "o"});
    ASSERT_EQ(c.exitCode, 0) << c.err;
    EXPECT_NE(c.out.find("blades.png, 32 x 32"), std::string::npos) << c.out;
    const RunResult r =
        runGale({"render", dir / "textured.toml", "-o", dir / "o", "--frames", "1"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(test::fs::exists(dir / "o/frame_0000.png"));

    // A texture that is not square is refused with the key named.
    texture.height = 16;
    texture.rgba.resize(32 * 16 * 4);
    render::writeImageAtomic(texture, dir / "blades.png");
    expectBadInput(runGale({"render", dir / "textured.toml", "-o", dir / "o2"}),
                   {"textured.toml:", "grass.texture", "square"});
    EXPECT_FALSE(test::fs::exists(dir / "o2"));
}

TEST(Cli, TerrainExportWritesAHeightmapThatCheckReadsBack) {
    TempDir dir;
    const RunResult r = runGale({"terrain", corpus("tiny.toml"), "-o", dir / "hill.png"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("17 x 17 pixels"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("height_scale_m"), std::string::npos) << r.out;
    test::writeFile(
        dir / "back.toml",
        "[terrain]\nkind = \"heightmap\"\nimage = \"hill.png\"\nmetres_per_pixel = 0.5\n");
    const RunResult c = runGale({"check", dir / "back.toml", "-o", dir / "o"});
    ASSERT_EQ(c.exitCode, 0) << c.err;
    EXPECT_NE(c.out.find("17 x 17 samples at 0.5 m"), std::string::npos) << c.out;
    expectBadInput(runGale({"terrain", corpus("tiny.toml"), "-o", dir / "hill.jpg"}), {".png"});
}

}  // namespace
}  // namespace gale::app
