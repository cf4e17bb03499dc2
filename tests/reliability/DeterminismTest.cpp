// The same scene gives bit-identical frames and fields across runs and across thread counts
// (docs/reliability.md). llvmpipe's threads are set with LP_NUM_THREADS, TBB's (solver, field
// sampling) with GALE_THREADS.

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ReliabilitySupport.h"

namespace gale::reliability {
namespace {

/// A small render or solve of these scenes takes a few seconds; the limit allows for sanitizers.
constexpr double RUN_TIMEOUT_S = 300.0;

/// The tiny test scene rendered large enough that llvmpipe splits each frame into many 64 x 64
/// tiles (its unit of threading), and with the solved wind when `solved`.
std::string tinyScene(bool solved) {
    std::string text = readFile(sourcePath("tests/data/scenes/tiny.toml"));
    if (solved) {
        // The point-source keys of tiny.toml are ignored by kind "solved" (and noted).
        const std::string wind = "[wind]\n";
        text.replace(text.find(wind), wind.size(),
                     "[wind]\nkind = \"solved\"\nspeed_mps = 5.0\ngroups = 8\n");
        text += "\n[solver]\nvoxel_size_m = 0.5\n";
    }
    return text;
}

struct Threads {
    const char* llvmpipe;
    const char* tbb;
};

RunOptions withThreads(const std::string& cwd, Threads t) {
    RunOptions o;
    o.cwd = cwd;
    o.timeout_s = RUN_TIMEOUT_S;
    o.env = {{"LP_NUM_THREADS", t.llvmpipe}, {"GALE_THREADS", t.tbb}};
    return o;
}

/// Renders `scene` (3 frames of 320 x 240) into cwd/out-<tag> and returns each frame's bytes.
std::vector<std::string> renderFrames(const TempDir& cwd, const std::string& tag, Threads t) {
    const std::string out = "out-" + tag;
    const RunResult r =
        runGale({"render", "scene.toml", "-o", out, "--width", "320", "--height", "240"},
                withThreads(cwd.str(), t));
    EXPECT_EQ(r.exitCode, 0) << r.describe();
    std::vector<std::string> frames;
    for (int k = 0; k < 3; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "/frame_%04d.png", k);
        frames.push_back(readFile(cwd / (out + name)));
        EXPECT_FALSE(frames.back().empty()) << out << name;
    }
    return frames;
}

void expectSameFrames(const std::vector<std::string>& a, const std::vector<std::string>& b,
                      const std::string& what) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t k = 0; k < a.size(); ++k)
        EXPECT_TRUE(a[k] == b[k]) << what << ": frame " << k << " differs (" << a[k].size()
                                  << " vs " << b[k].size() << " bytes)";
}

TEST(Determinism, PointSourceFramesAreByteIdenticalAcrossRunsAndLlvmpipeThreadCounts) {
    TempDir cwd;
    writeFile(cwd / "scene.toml", tinyScene(/*solved=*/false));
    const auto first = renderFrames(cwd, "a", {"2", "2"});
    const auto again = renderFrames(cwd, "b", {"2", "2"});
    const auto single = renderFrames(cwd, "c", {"1", "1"});
    expectSameFrames(first, again, "a second run");
    expectSameFrames(first, single, "one thread instead of two");
    // Not a test that cannot fail: the frames hold moving grass, so they differ from each other.
    EXPECT_NE(first[0], first[2]);
}

TEST(Determinism, SolvedWindFramesAreByteIdenticalAcrossRunsAndThreadCounts) {
    TempDir cwd;
    writeFile(cwd / "scene.toml", tinyScene(/*solved=*/true));
    const auto first = renderFrames(cwd, "a", {"2", "2"});
    const auto again = renderFrames(cwd, "b", {"2", "2"});
    const auto single = renderFrames(cwd, "c", {"1", "1"});
    expectSameFrames(first, again, "a second run");
    expectSameFrames(first, single, "one thread instead of two");
}

/// Every active voxel of every grid of a .vdb, as raw bytes in a fixed order (the file itself
/// holds a random UUID per write, so its bytes differ between identical fields).
std::string vdbValues(const std::string& path) {
    openvdb::initialize();
    openvdb::io::File file(path);
    file.open();
    std::string bytes;
    std::vector<std::string> names;
    for (auto it = file.beginName(); it != file.endName(); ++it) names.push_back(it.gridName());
    std::sort(names.begin(), names.end());
    for (const std::string& name : names) {
        bytes += name + ":";
        const openvdb::GridBase::Ptr base = file.readGrid(name);
        if (auto v = openvdb::gridPtrCast<openvdb::Vec3SGrid>(base)) {
            for (auto it = v->cbeginValueOn(); it; ++it) {
                const openvdb::Coord c = it.getCoord();
                const openvdb::Vec3s x = *it;
                bytes.append(reinterpret_cast<const char*>(c.data()), 3 * sizeof(int32_t));
                bytes.append(reinterpret_cast<const char*>(x.asPointer()), 3 * sizeof(float));
            }
        } else if (auto f = openvdb::gridPtrCast<openvdb::FloatGrid>(base)) {
            for (auto it = f->cbeginValueOn(); it; ++it) {
                const openvdb::Coord c = it.getCoord();
                const float x = *it;
                bytes.append(reinterpret_cast<const char*>(c.data()), 3 * sizeof(int32_t));
                bytes.append(reinterpret_cast<const char*>(&x), sizeof(float));
            }
        } else {
            ADD_FAILURE() << path << ": grid " << name << " of an unexpected type";
        }
    }
    file.close();
    return bytes;
}

struct Solved {
    std::string values;
    nlohmann::json report;
};

Solved solve(const TempDir& cwd, const std::string& tag, const char* threads) {
    const std::string vdb = cwd / ("wind-" + tag + ".vdb");
    const RunResult r =
        runGale({"solve", "scene.toml", "-o", vdb}, withThreads(cwd.str(), {"1", threads}));
    EXPECT_EQ(r.exitCode, 0) << r.describe();
    Solved s;
    s.values = vdbValues(vdb);
    s.report = nlohmann::json::parse(readFile(cwd / ("wind-" + tag + ".json")));
    return s;
}

TEST(Determinism, SolvedFieldIsBitIdenticalAcrossRunsAndTbbThreadCounts) {
    TempDir cwd;
    writeFile(cwd / "scene.toml", tinyScene(/*solved=*/true));
    const Solved first = solve(cwd, "a", "2");
    const Solved again = solve(cwd, "b", "2");
    const Solved single = solve(cwd, "c", "1");
    const Solved four = solve(cwd, "d", "4");
    ASSERT_FALSE(first.values.empty());
    EXPECT_TRUE(first.values == again.values) << "a second run gives another field";
    EXPECT_TRUE(first.values == single.values) << "one thread gives another field than two";
    EXPECT_TRUE(first.values == four.values) << "four threads give another field than two";
    for (const Solved* other : {&again, &single, &four}) {
        EXPECT_EQ(first.report["report"]["iterations"], other->report["report"]["iterations"]);
        EXPECT_EQ(first.report["report"]["relative_residual"],
                  other->report["report"]["relative_residual"]);
    }
}

TEST(Determinism, BadThreadCountIsBadInput) {
    TempDir cwd;
    RunOptions o;
    o.cwd = cwd.str();
    o.env = {{"GALE_THREADS", "zero"}};
    const RunResult r = runGale({"check", sourcePath("tests/data/scenes/tiny.toml")}, o);
    EXPECT_EQ(r.exitCode, 2) << r.describe();
    EXPECT_NE(r.err.find("GALE_THREADS"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace gale::reliability
