// Nothing lost (docs/reliability.md): a disk that fills mid-run, outputs that alias inputs, two
// runs into one folder, a killed run's leftovers. Each case checks the exit code, the message
// and the files left behind byte for byte.
//
// The full disk is simulated by FullDiskShim.c (LD_PRELOAD): GALE_FULL_DISK_BYTES bytes may be
// written under GALE_FULL_DISK_FOLDER, then every write there fails with ENOSPC. Mounting a small
// tmpfs would need privileges CI containers do not always have.

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "ReliabilitySupport.h"

namespace gale::reliability {
namespace {

/// The tiny scene renders and solves in well under a second; a generous bound for sanitizers.
constexpr double RUN_TIMEOUT_S = 120.0;

/// Every file under `folder` with its bytes.
std::map<std::string, std::string> snapshot(const std::string& folder) {
    std::map<std::string, std::string> out;
    for (const auto& [rel, size] : listTree(folder))
        if (fs::is_regular_file(fs::path(folder) / rel)) out[rel] = readFile(folder + "/" + rel);
    return out;
}

std::string names(const std::map<std::string, std::string>& files) {
    std::string s;
    for (const auto& [name, bytes] : files)
        s += "  " + name + " (" + std::to_string(bytes.size()) + " B)\n";
    return s;
}

/// Runs gale in `cwd` with the full-disk shim allowing `bytes` under `cwd/folder`.
RunResult runOnFullDisk(const std::vector<std::string>& args, const std::string& cwd,
                        const std::string& folder, long long bytes) {
    RunOptions options;
    options.cwd = cwd;
    options.timeout_s = RUN_TIMEOUT_S;
    const char* asan = std::getenv("ASAN_OPTIONS");
    options.env = {{"LD_PRELOAD", GALE_FULL_DISK_SHIM},
                   {"GALE_FULL_DISK_FOLDER", cwd + "/" + folder},
                   {"GALE_FULL_DISK_BYTES", std::to_string(bytes)},
                   // A preloaded library ahead of the sanitizer runtime is intended here.
                   {"ASAN_OPTIONS", std::string(asan ? asan : "") + ":verify_asan_link_order=0"}};
    return runGale(args, options);
}

/// The one-line error of a failed write: names the file and the reason.
void expectOneWriteError(const RunResult& r, const std::string& folder) {
    EXPECT_EQ(r.exitCode, 1) << r.describe();
    EXPECT_EQ(
        countLines(r.err.substr(
            r.err.find("gale: error:") == std::string::npos ? 0 : r.err.find("gale: error:"))),
        1)
        << r.err;
    EXPECT_NE(r.err.find("gale: error: " + folder), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("cannot write: No space left on device"), std::string::npos) << r.err;
}

const char* const TINY = "tests/data/scenes/tiny.toml";

/// The first run's outputs, before a second run fills the disk at each of these byte counts.
struct FullDiskCase {
    std::vector<std::string> args;
    std::string folder;  ///< relative to the working folder
    /// Bytes the disk takes before it is full; a negative budget counts back from the first
    /// run's total (-1000: all but its last kB), so it stays short of the total whatever the
    /// outputs compress to.
    std::vector<long long> budgets;
};

/// A complete run, then runs of the same command that find the disk full after `budget` bytes:
/// each fails with exit 1 and one message, and leaves the first run's files byte for byte.
void expectFullDiskKeepsEarlierRun(const FullDiskCase& c, const std::string& sceneText) {
    TempDir cwd;
    writeFile(cwd / "scene.toml", sceneText);
    fs::create_directories(cwd / c.folder);
    RunOptions options;
    options.cwd = cwd.str();
    options.timeout_s = RUN_TIMEOUT_S;
    const RunResult first = runGale(c.args, options);
    ASSERT_EQ(first.exitCode, 0) << first.describe();
    const auto before = snapshot(cwd / c.folder);
    ASSERT_FALSE(before.empty());
    long long total = 0;
    for (const auto& [name, bytes] : before) total += static_cast<long long>(bytes.size());
    for (long long budget : c.budgets) {
        if (budget < 0) budget += total;
        // A budget the outputs fit in would test nothing: the run must find the disk full.
        ASSERT_LT(budget, total) << "the first run wrote only " << total << " bytes";
        SCOPED_TRACE("disk full after " + std::to_string(budget) + " bytes");
        const RunResult r = runOnFullDisk(c.args, cwd.str(), c.folder, budget);
        expectOneWriteError(r, c.folder);
        const auto after = snapshot(cwd / c.folder);
        EXPECT_TRUE(after == before) << "before:\n" << names(before) << "after:\n" << names(after);
    }
}

TEST(FullDisk, RenderThatFillsTheDiskFailsWithExit1AndKeepsTheEarlierFramesByteForByte) {
    // 0: the first frame cannot be written; 5000: the second frame is cut (a tiny frame is
    // about 3 kB); 12000: the frames fit, the GIF or contact sheet does not; the first run's
    // total less 1000 bytes: all but the end of the last file written.
    expectFullDiskKeepsEarlierRun(
        {{"render", "scene.toml", "-o", "frames"}, "frames", {0, 5000, 12000, -1000}},
        readFile(sourcePath(TINY)));
}

TEST(FullDisk, TerrainExportThatFillsTheDiskFailsWithExit1AndKeepsTheEarlierPng) {
    expectFullDiskKeepsEarlierRun(
        {{"terrain", "scene.toml", "-o", "out/hill.png"}, "out", {0, 100, 400}},
        readFile(sourcePath(TINY)));
}

/// A solve of a few thousand cells: a .vdb of some tens of kB.
const char* const SMALL_SOLVE =
    "[terrain]\nkind = \"hemisphere\"\nsize_m = [8.0, 8.0]\nradius_m = 2.0\n"
    "[wind]\nkind = \"solved\"\n[solver]\nvoxel_size_m = 0.5\n";

TEST(FullDisk, SolveThatFillsTheDiskFailsWithExit1AndKeepsTheEarlierFieldAndReport) {
    expectFullDiskKeepsEarlierRun(
        {{"solve", "scene.toml", "-o", "field/wind.vdb"}, "field", {0, 1000, 100000}}, SMALL_SOLVE);
}

/// An unsteady run of a few steps writing a short .vdb sequence.
const char* const SMALL_UNSTEADY =
    "[terrain]\nkind = \"hemisphere\"\nsize_m = [8.0, 8.0]\nradius_m = 2.0\n"
    "[wind]\nkind = \"unsteady\"\nspeed_mps = 2.0\n[solver]\nvoxel_size_m = 0.5\n"
    "[unsteady]\nduration_s = 0.6\noutput_every_s = 0.2\n";

TEST(FullDisk, UnsteadySolveThatFillsTheDiskMidSequenceKeepsTheEarlierSequence) {
    expectFullDiskKeepsEarlierRun(
        {{"solve", "scene.toml", "-o", "field/wind.vdb"}, "field", {0, 60000, 300000}},
        SMALL_UNSTEADY);
}

}  // namespace
}  // namespace gale::reliability
