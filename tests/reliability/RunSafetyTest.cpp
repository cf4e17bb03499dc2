// Runs that cannot hurt each other or their inputs (docs/reliability.md): outputs that alias
// inputs are refused up front; SIGTERM, SIGHUP and SIGINT stop render and solve alike, keeping
// complete files only; a killed run's temporaries and lock are cleaned up by the next run; two
// runs never write one folder at once.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "ReliabilitySupport.h"
#include "render/ImageIO.h"

namespace gale::reliability {
namespace {

/// How long a run may take to reach the moment we act at, and to stop afterwards (a tiny frame
/// takes milliseconds; sanitizers slow everything 10-20 times).
constexpr double REACH_TIMEOUT_S = 120.0;
constexpr double STOP_TIMEOUT_S = 60.0;

const char* const TINY = "tests/data/scenes/tiny.toml";

/// A steady solve of a few thousand cells, and the same wind unsteady for far longer than the
/// tests let it run (one output every 0.2 s of simulated time).
const char* const SMALL_SOLVE =
    "[terrain]\nkind = \"hemisphere\"\nsize_m = [8.0, 8.0]\nradius_m = 2.0\n"
    "[wind]\nkind = \"solved\"\n[solver]\nvoxel_size_m = 0.5\n";
const char* const LONG_UNSTEADY =
    "[terrain]\nkind = \"hemisphere\"\nsize_m = [8.0, 8.0]\nradius_m = 2.0\n"
    "[wind]\nkind = \"unsteady\"\nspeed_mps = 2.0\n[solver]\nvoxel_size_m = 0.5\n"
    "[unsteady]\nduration_s = 200.0\noutput_every_s = 0.2\n";

/// Every file under `folder` with its bytes.
std::map<std::string, std::string> snapshot(const std::string& folder) {
    std::map<std::string, std::string> out;
    for (const auto& [rel, size] : listTree(folder))
        if (fs::is_regular_file(fs::path(folder) / rel)) out[rel] = readFile(folder + "/" + rel);
    return out;
}

/// A PID that no process has: a child that has exited and been reaped.
pid_t deadPid() {
    const pid_t pid = ::fork();
    if (pid == 0) ::_exit(0);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return pid;
}

/// Runs `args` in `cwd` and expects exit 2 with one error line holding `fragment`, and the
/// folder's files unchanged byte for byte.
void expectRefusedUpFront(const std::vector<std::string>& args, const std::string& cwd,
                          const std::string& fragment) {
    const auto before = snapshot(cwd);
    const RunResult r = runGale(args, cwd);
    EXPECT_EQ(r.exitCode, 2) << r.describe();
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("gale: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
    EXPECT_TRUE(snapshot(cwd) == before) << describeTree(listTree(cwd));
}

TEST(OutputAliases, SolveReportOntoItsOwnFieldIsRefusedWithExit2) {
    TempDir cwd;
    writeFile(cwd / "s.toml", SMALL_SOLVE);
    expectRefusedUpFront({"solve", "s.toml", "-o", "same.vdb", "--report", "same.vdb"}, cwd.str(),
                         "'same.vdb' is also");
}

TEST(OutputAliases, SolveReportOntoTheSceneIsRefusedWithExit2) {
    TempDir cwd;
    writeFile(cwd / "s.toml", SMALL_SOLVE);
    expectRefusedUpFront({"solve", "s.toml", "-o", "w.vdb", "--report", "s.toml"}, cwd.str(),
                         "is also the scene");
    // Through a symbolic link and another spelling of the path too.
    fs::create_symlink("s.toml", cwd / "link.json");
    expectRefusedUpFront({"solve", "s.toml", "-o", "w.vdb", "--report", "link.json"}, cwd.str(),
                         "is also the scene");
    fs::create_directories(cwd / "sub");
    expectRefusedUpFront({"solve", "s.toml", "-o", "w.vdb", "--report", "sub/../s.toml"}, cwd.str(),
                         "is also the scene");
}

TEST(OutputAliases, TerrainExportOntoTheScenesOwnHeightmapIsRefusedWithExit2) {
    TempDir cwd;
    writeFile(cwd / "tiny.toml", readFile(sourcePath(TINY)));
    ASSERT_EQ(runGale({"terrain", "tiny.toml", "-o", "hill.png"}, cwd.str()).exitCode, 0);
    writeFile(cwd / "h.toml",
              "[terrain]\nkind = \"heightmap\"\nimage = \"hill.png\"\nmetres_per_pixel = 0.5\n");
    expectRefusedUpFront({"terrain", "h.toml", "-o", "hill.png"}, cwd.str(), "(the heightmap)");
}

TEST(OutputAliases, RenderIntoTheScenesFolderOverAnInputNamedLikeAFrameIsRefusedWithExit2) {
    TempDir cwd;
    writeFile(cwd / "tiny.toml", readFile(sourcePath(TINY)));
    ASSERT_EQ(runGale({"terrain", "tiny.toml", "-o", "frame_0001.png"}, cwd.str()).exitCode, 0);
    writeFile(
        cwd / "h.toml",
        "[terrain]\nkind = \"heightmap\"\nimage = \"frame_0001.png\"\n"
        "metres_per_pixel = 0.5\n[output]\nfolder = \".\"\nframes = 3\nwidth = 64\nheight = 48\n");
    expectRefusedUpFront({"render", "h.toml"}, cwd.str(), "(a frame)");
}

TEST(OutputAliases, SolveOutputNamingAFolderIsRefusedBeforeAnyWork) {
    TempDir cwd;
    writeFile(cwd / "s.toml", SMALL_SOLVE);
    fs::create_directories(cwd / "w.vdb");
    expectRefusedUpFront({"solve", "s.toml", "-o", "w.vdb"}, cwd.str(), "is a folder");
    expectRefusedUpFront({"solve", "s.toml", "-o", "x.vdb", "--report", "w.vdb"}, cwd.str(),
                         "is a folder");
}

/// Sends `sig` to a render of 100000 tiny frames once it has finished a few, and checks what it
/// leaves: exit 128 + sig, a report that says where and why it stopped, every frame it names
/// complete, no temporary and no lock.
void expectRenderStopsCleanlyOn(int sig) {
    TempDir cwd;
    writeFile(cwd / "scene.toml", readFile(sourcePath(TINY)));
    RunOptions options;
    options.cwd = cwd.str();
    Child child({"render", "scene.toml", "-o", "frames", "--frames", "100000"}, options);
    ASSERT_TRUE(waitFor([&] { return child.errSoFar().find(" 4/100000") != std::string::npos; },
                        REACH_TIMEOUT_S))
        << child.errSoFar();
    child.signal(sig);
    const RunResult r = child.wait(STOP_TIMEOUT_S);
    ASSERT_FALSE(r.timedOut) << r.describe();
    EXPECT_EQ(r.exitCode, 128 + sig) << r.describe();
    EXPECT_NE(r.out.find(std::string("interrupted (SIG") + sigabbrev_np(sig)), std::string::npos)
        << r.out;
    const nlohmann::json report = nlohmann::json::parse(readFile(cwd / "frames/frame_report.json"));
    EXPECT_TRUE(report["interrupted"].get<bool>());
    EXPECT_EQ(report["stopped_by"], std::string("SIG") + sigabbrev_np(sig));
    const int done = report["frames"];
    EXPECT_GE(done, 4);
    EXPECT_EQ(report["files"].size(), size_t(done));
    for (const auto& name : report["files"]) {
        const render::Image image =
            render::readImageRgba8(cwd / ("frames/" + name.get<std::string>()));
        EXPECT_EQ(image.width, 64);
    }
    EXPECT_TRUE(hiddenOrTemporary(cwd.str()).empty()) << describeTree(listTree(cwd.str()));
}

TEST(Signals, SigtermDuringRenderKeepsCompleteFramesAndExits143) {
    expectRenderStopsCleanlyOn(SIGTERM);
}
TEST(Signals, SighupDuringRenderKeepsCompleteFramesAndExits129) {
    expectRenderStopsCleanlyOn(SIGHUP);
}

TEST(Signals, SigtermOrSighupDuringASteadySolveWritesNothingAndSaysWhere) {
    for (const int sig : {SIGTERM, SIGHUP}) {
        TempDir cwd;
        // Fine enough to take seconds: a few hundred thousand air cells.
        writeFile(cwd / "scene.toml",
                  "[terrain]\nkind = \"hemisphere\"\nsize_m = [40.0, 40.0]\nradius_m = 6.0\n"
                  "[wind]\nkind = \"solved\"\n[solver]\nvoxel_size_m = 0.2\ntolerance = 1e-12\n"
                  "max_iterations = 100000\n");
        RunOptions options;
        options.cwd = cwd.str();
        Child child({"solve", "scene.toml", "-o", "field/wind.vdb"}, options);
        ASSERT_TRUE(waitFor([&] { return child.errSoFar().find("solving") != std::string::npos; },
                            REACH_TIMEOUT_S));
        child.signal(sig);
        const RunResult r = child.wait(STOP_TIMEOUT_S);
        ASSERT_FALSE(r.timedOut) << r.describe();
        EXPECT_EQ(r.exitCode, 128 + sig) << r.describe();
        // "solving..." is printed before the air domain is built, and on a loaded machine the
        // signal can land in that phase (seen in CI): either place is a steady solve's, and the
        // message must name the one it was.
        const std::string said = std::string("interrupted (SIG") + sigabbrev_np(sig) + ") while ";
        EXPECT_TRUE(r.err.find(said + "solving: nothing written") != std::string::npos ||
                    r.err.find(said + "building the air domain: nothing written") !=
                        std::string::npos)
            << r.err;
        EXPECT_TRUE(listTree(cwd / "field").empty()) << describeTree(listTree(cwd / "field"));
    }
}

TEST(Signals, AnySignalDuringAnUnsteadySolveKeepsTheCompleteSequenceAndAReport) {
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
        SCOPED_TRACE(sigabbrev_np(sig));
        TempDir cwd;
        writeFile(cwd / "scene.toml", LONG_UNSTEADY);
        RunOptions options;
        options.cwd = cwd.str();
        Child child({"solve", "scene.toml", "-o", "field/w.vdb"}, options);
        ASSERT_TRUE(waitFor([&] { return child.errSoFar().find(" 3/1000") != std::string::npos; },
                            REACH_TIMEOUT_S))
            << child.errSoFar();
        child.signal(sig);
        const RunResult r = child.wait(STOP_TIMEOUT_S);
        ASSERT_FALSE(r.timedOut) << r.describe();
        EXPECT_EQ(r.exitCode, 128 + sig) << r.describe();
        EXPECT_NE(r.out.find("interrupted"), std::string::npos) << r.out;
        const nlohmann::json report = nlohmann::json::parse(readFile(cwd / "field/w.json"));
        EXPECT_TRUE(report["interrupted"].get<bool>());
        EXPECT_EQ(report["stopped_by"], std::string("SIG") + sigabbrev_np(sig));
        const auto& frames = report["outputs"]["vdb_sequence"];
        EXPECT_GE(frames.size(), 4u);
        // Exactly the files the report names, and the report: nothing half written.
        std::set<std::string> expected{"w.json"};
        for (const auto& f : frames)
            expected.insert(fs::path(f["path"].get<std::string>()).filename().string());
        std::set<std::string> found;
        for (const auto& [rel, size] : listTree(cwd / "field")) found.insert(rel);
        EXPECT_EQ(found, expected) << describeTree(listTree(cwd / "field"));
    }
}

TEST(Signals, ASignalAfterTheLastOutputKeepsACompleteRunsReportAndSaysSo) {
    // 41 outputs of a small box; the signal comes once the last is written, while the files and
    // report are moved into place (or just after the run ended: then exit 0).
    TempDir cwd;
    writeFile(cwd / "scene.toml",
              "[terrain]\nkind = \"hemisphere\"\nsize_m = [8.0, 8.0]\nradius_m = 2.0\n"
              "[wind]\nkind = \"unsteady\"\nspeed_mps = 2.0\n[solver]\nvoxel_size_m = 0.5\n"
              "[unsteady]\nduration_s = 8.0\noutput_every_s = 0.2\n");
    RunOptions options;
    options.cwd = cwd.str();
    Child child({"solve", "scene.toml", "-o", "field/w.vdb"}, options);
    ASSERT_TRUE(waitFor([&] { return child.errSoFar().find("output 40/40") != std::string::npos; },
                        REACH_TIMEOUT_S))
        << child.errSoFar();
    child.signal(SIGTERM);
    const RunResult r = child.wait(STOP_TIMEOUT_S);
    ASSERT_FALSE(r.timedOut) << r.describe();
    ASSERT_TRUE(r.exitCode == 0 || r.exitCode == 128 + SIGTERM) << r.describe();
    const nlohmann::json report = nlohmann::json::parse(readFile(cwd / "field/w.json"));
    // The report is a complete run's: all 41 files, the whole duration, not "interrupted".
    EXPECT_FALSE(report.contains("interrupted")) << report.dump();
    EXPECT_EQ(report["outputs"]["vdb_sequence"].size(), 41u);
    EXPECT_DOUBLE_EQ(report["summary"]["simulated_s"].get<double>(), 8.0);
    EXPECT_EQ(listTree(cwd / "field").size(), 42u) << describeTree(listTree(cwd / "field"));
    if (r.exitCode != 0) {
        EXPECT_NE(r.err.find("interrupted (SIGTERM) while writing; the run had finished"),
                  std::string::npos)
            << r.err;
    }
    EXPECT_EQ(r.out.find("interrupted"), std::string::npos) << r.out;
    EXPECT_TRUE(hiddenOrTemporary(cwd.str()).empty()) << describeTree(listTree(cwd.str()));
}

TEST(Leftovers, AKilledRunsTemporariesAreNamedByCheckAndRemovedByTheNextRun) {
    TempDir cwd;
    writeFile(cwd / "scene.toml", readFile(sourcePath(TINY)));
    fs::create_directories(cwd / "frames");
    const std::string dead = std::to_string(deadPid());
    const std::string tmpName = ".frame_0000.tmp-" + dead + "-3.png";
    writeFile(cwd / ("frames/" + tmpName), "half a frame");
    writeFile(cwd / ("frames/w.vdb.tmp" + dead), "half a field");
    const RunResult check = runGale({"check", "scene.toml", "-o", "frames"}, cwd.str());
    EXPECT_EQ(check.exitCode, 0) << check.describe();
    EXPECT_NE(check.out.find("2 temporary files left by a gale run that was stopped"),
              std::string::npos)
        << check.out;
    EXPECT_TRUE(fs::exists(cwd / ("frames/" + tmpName)));  // check only names them
    const RunResult render = runGale({"render", "scene.toml", "-o", "frames"}, cwd.str());
    EXPECT_EQ(render.exitCode, 0) << render.describe();
    EXPECT_NE(render.err.find("removed 2 temporary files"), std::string::npos) << render.err;
    EXPECT_TRUE(hiddenOrTemporary(cwd.str()).empty()) << describeTree(listTree(cwd.str()));
}

TEST(OneRunPerFolder, ASecondRenderIntoABusyFolderExits2NamingTheOwner) {
    TempDir cwd;
    writeFile(cwd / "scene.toml", readFile(sourcePath(TINY)));
    RunOptions options;
    options.cwd = cwd.str();
    Child first({"render", "scene.toml", "-o", "frames", "--frames", "100000"}, options);
    ASSERT_TRUE(waitFor([&] { return first.errSoFar().find(" 2/100000") != std::string::npos; },
                        REACH_TIMEOUT_S))
        << first.errSoFar();
    const RunResult second =
        runGale({"render", "scene.toml", "-o", "frames", "--frames", "3"}, cwd.str());
    EXPECT_EQ(second.exitCode, 2) << second.describe();
    EXPECT_EQ(countLines(second.err), 1) << second.err;
    EXPECT_NE(second.err.find("in use by another gale run (PID " + std::to_string(first.pid())),
              std::string::npos)
        << second.err;
    first.signal(SIGINT);
    const RunResult r = first.wait(STOP_TIMEOUT_S);
    EXPECT_EQ(r.exitCode, 130) << r.describe();
    // The first run's report and frames only: its scene, all its frames named.
    const nlohmann::json report = nlohmann::json::parse(readFile(cwd / "frames/frame_report.json"));
    EXPECT_EQ(report["frames_requested"], 100000);
    EXPECT_TRUE(hiddenOrTemporary(cwd.str()).empty()) << describeTree(listTree(cwd.str()));
}

TEST(OneRunPerFolder, ALockLeftByADeadRunIsTakenOverWithANote) {
    TempDir cwd;
    writeFile(cwd / "scene.toml", readFile(sourcePath(TINY)));
    fs::create_directories(cwd / "frames");
    const std::string dead = std::to_string(deadPid());
    writeFile(cwd / "frames/.gale.lock", dead + "\n");
    const RunResult r = runGale({"render", "scene.toml", "-o", "frames"}, cwd.str());
    EXPECT_EQ(r.exitCode, 0) << r.describe();
    EXPECT_NE(r.err.find("taking over frames/.gale.lock from PID " + dead), std::string::npos)
        << r.err;
    EXPECT_TRUE(hiddenOrTemporary(cwd.str()).empty()) << describeTree(listTree(cwd.str()));
}

TEST(BoundedInput, CheckOfAnEndlessDeviceStopsAt16MiBWithExit2) {
    const RunResult r = runGale({"check", "/dev/zero"}, RunOptions{});
    ASSERT_FALSE(r.timedOut);
    EXPECT_EQ(r.exitCode, 2) << r.describe();
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("/dev/zero: more than 16"), std::string::npos) << r.err;
}

TEST(BoundsOnWork, CheckReportsTheFilesAndStepsAnUnsteadyRunPlans) {
    TempDir cwd;
    writeFile(cwd / "scene.toml", LONG_UNSTEADY);
    const RunResult r = runGale({"check", "scene.toml"}, cwd.str());
    EXPECT_EQ(r.exitCode, 0) << r.describe();
    // 200 s every 0.2 s and the file at t = 0; adaptive steps of at most cfl h / U = 2 x 0.5 / 2 s.
    EXPECT_NE(r.out.find("gale solve plans 1001 .vdb files (limit 10000"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("at least 400 time steps"), std::string::npos) << r.out;
    // The scene sets the limit: below the plan, the run is refused naming the line.
    writeFile(cwd / "low.toml", std::string(LONG_UNSTEADY) + "max_files = 1000\n");
    const RunResult low = runGale({"check", "low.toml"}, cwd.str());
    EXPECT_EQ(low.exitCode, 2) << low.describe();
    EXPECT_NE(low.err.find("low.toml:12: unsteady.output_every_s"), std::string::npos) << low.err;
}

}  // namespace
}  // namespace gale::reliability
