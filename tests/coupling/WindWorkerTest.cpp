// The wind on its own thread (coupling/WindWorker.h): a reader only ever sees complete snapshots,
// the worker stops cleanly, and failures on the worker thread reach the caller.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "coupling/WindWorker.h"

using namespace gale;

namespace {

constexpr int GROUPS = 64;
constexpr int VERTICES = 256;

/// A source whose every output at time t holds t in every entry, written one entry at a time with
/// yields in between, so a reader that could see a half-written snapshot would see mixed values.
class StampSource : public coupling::WindSource {
  public:
    int groupCount() const override { return GROUPS; }
    void update(double t_s, render::GrassWind& wind) override {
        ++updates;
        times.push_back(t_s);
        if (t_s >= failAt_s)
            throw std::runtime_error("source failed at t = " + std::to_string(t_s));
        if (delay_ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
        wind.groupIntensity.resize(GROUPS);
        for (int g = 0; g < GROUPS; ++g) {
            wind.groupIntensity[g] = float(t_s);
            if (g % 8 == 0) std::this_thread::yield();
        }
        auto vertex = std::make_shared<render::VertexWind>();
        vertex->wsDirection.assign(VERTICES, glm::vec3(float(t_s), 0.0f, 0.0f));
        vertex->group.assign(VERTICES, 0u);
        wind.vertex = vertex;
        ++wind.revision;
    }
    std::string describe() const override { return "stamp"; }

    std::atomic<int> updates{0};
    std::vector<double> times;  ///< every update's time; written by the worker thread only
    double failAt_s = 1e300;
    int delay_ms = 0;
};

/// Stamps as float, compared exactly: every entry is the same float conversion of the same t.
bool complete(const coupling::WindSnapshot& s) {
    const float t = float(s.t_s);
    if (int(s.wind.groupIntensity.size()) != GROUPS) return false;
    for (float v : s.wind.groupIntensity)
        if (v != t) return false;
    if (int(s.wind.wsDirection().size()) != VERTICES) return false;
    for (const glm::vec3& d : s.wind.wsDirection())
        if (d.x != t) return false;
    return true;
}

render::TerrainMesh noMesh() { return {}; }

/// A stepping source: update(t) takes steps of STEP_S up to t and asks updateUntil's `stop`
/// between them. Its second step of an update waits until the test lets it go (release), so a
/// test can post work while an update is known to be under way.
class SteppingSource : public coupling::WindSource {
  public:
    static constexpr double STEP_S = 0.125;  // exact in binary: times compare exactly
    int groupCount() const override { return GROUPS; }
    void update(double t_s, render::GrassWind& wind) override { (void)updateUntil(t_s, wind, {}); }
    double updateUntil(double t_s, render::GrassWind& wind,
                       const std::function<bool()>& stop) override {
        int stepsThisUpdate = 0;
        while (time_s < t_s) {
            if (stop && stop()) break;
            if (++stepsThisUpdate == 2) {
                underWay.store(true);
                while (!released.load()) std::this_thread::yield();
            }
            time_s += STEP_S;
        }
        const double shown_s = std::min(time_s, t_s);
        wind.groupIntensity.assign(GROUPS, float(shown_s));
        ++wind.revision;
        return shown_s;
    }
    std::string describe() const override { return "stepping"; }

    double time_s = 0.0;  ///< the "solver" time; worker thread only
    std::atomic<bool> underWay{false}, released{false};
};

TEST(WindWorker, EverySnapshotAReaderTakesIsComplete) {
    StampSource source;
    const render::TerrainMesh mesh = noMesh();
    coupling::WindWorker worker(source, mesh, /*grassHeight_m=*/0.5);
    coupling::WindSnapshot shown;
    // Requests race the worker's steps; every take must see one time's values throughout.
    for (int i = 1; i <= 4000; ++i) {
        worker.request(i * 1e-3, coupling::OverlaySpec{});
        if (worker.take(shown)) {
            ASSERT_TRUE(complete(shown)) << "torn snapshot at t = " << shown.t_s;
        }
    }
    worker.waitFor(4.0, shown);
    EXPECT_TRUE(complete(shown));
    EXPECT_EQ(shown.t_s, 4.0);
    worker.rethrowIfFailed();
}

TEST(WindWorker, WaitForReturnsTheSnapshotOfExactlyTheRequestedTime) {
    StampSource source;
    const render::TerrainMesh mesh = noMesh();
    coupling::WindWorker worker(source, mesh, 0.5);
    coupling::WindSnapshot shown;
    for (double t : {0.25, 0.5, 0.5, 2.0}) {
        worker.request(t, coupling::OverlaySpec{});
        worker.waitFor(t, shown);
        EXPECT_EQ(shown.t_s, t);
        EXPECT_TRUE(complete(shown));
    }
}

TEST(WindWorker, StopsCleanlyMidStepAndNeverUpdatesAfterDestruction) {
    StampSource source;
    source.delay_ms = 30;  // long steps: the destructor meets one under way
    const render::TerrainMesh mesh = noMesh();
    {
        coupling::WindWorker worker(source, mesh, 0.5);
        for (int i = 0; i < 5; ++i) worker.request(i * 0.1, coupling::OverlaySpec{});
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    const int after = source.updates.load();
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    EXPECT_EQ(source.updates.load(), after) << "the source was updated after the worker stopped";
    // A worker that was never asked for anything stops too, without touching the source.
    StampSource idle;
    { coupling::WindWorker worker(idle, mesh, 0.5); }
    EXPECT_EQ(idle.updates.load(), 0);
}

TEST(WindWorker, AnExceptionInTheSourceReachesTheCaller) {
    StampSource source;
    source.failAt_s = 1.0;
    const render::TerrainMesh mesh = noMesh();
    coupling::WindWorker worker(source, mesh, 0.5);
    coupling::WindSnapshot shown;
    worker.request(0.5, coupling::OverlaySpec{});
    worker.waitFor(0.5, shown);
    worker.rethrowIfFailed();  // well so far
    worker.request(1.5, coupling::OverlaySpec{});
    try {
        worker.waitFor(1.5, shown);
        FAIL() << "waitFor returned after the source threw";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("source failed at t = 1.5"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(worker.rethrowIfFailed(), std::runtime_error);
    EXPECT_EQ(shown.t_s, 0.5) << "the last good snapshot stays the reader's";
}

TEST(WindWorker, PostedWorkRunsOnTheWorkerBeforeTheNextUpdateAndItsFailureReachesTheCaller) {
    StampSource source;
    const render::TerrainMesh mesh = noMesh();
    coupling::WindWorker worker(source, mesh, 0.5);
    coupling::WindSnapshot shown;
    worker.request(0.5, coupling::OverlaySpec{});
    worker.waitFor(0.5, shown);
    const int before = source.updates.load();
    std::thread::id ranOn;
    std::atomic<bool> ran{false};
    worker.post([&](coupling::WindSource&) {
        ranOn = std::this_thread::get_id();
        ran = true;
    });
    // Same request time: the posted work alone makes the worker update again.
    const uint64_t serial = shown.serial;
    while (!worker.take(shown) || shown.serial == serial) std::this_thread::yield();
    EXPECT_TRUE(ran.load());
    EXPECT_NE(ranOn, std::this_thread::get_id());
    EXPECT_EQ(source.updates.load(), before + 1);

    worker.post([](coupling::WindSource&) { throw std::invalid_argument("bad whirlwind"); });
    worker.request(0.75, coupling::OverlaySpec{});
    EXPECT_THROW(worker.waitFor(0.75, shown), std::invalid_argument);
}

TEST(WindWorker, PostedWorkIsShownAtTheLastShownTimeBeforeTheStepToANewerRequest) {
    // A whirlwind dropped while the worker steps: the worker publishes the source as changed at
    // the time it last showed (no solver step for a stepping source) before stepping to the newer
    // request, so the reader's next frame has it.
    StampSource source;
    source.delay_ms = 40;  // long steps: the work and the newer request arrive during one
    const render::TerrainMesh mesh = noMesh();
    coupling::WindWorker worker(source, mesh, 0.5);
    coupling::WindSnapshot shown;
    worker.request(0.5, coupling::OverlaySpec{});
    worker.waitFor(0.5, shown);
    const int before = source.updates.load();
    worker.request(0.75, coupling::OverlaySpec{});
    while (source.updates.load() == before) std::this_thread::yield();  // 0.75 under way
    const uint64_t number = worker.post([](coupling::WindSource&) {});
    worker.request(1.0, coupling::OverlaySpec{});
    worker.waitFor(1.0, shown);
    EXPECT_GE(shown.workDone, number);
    // waitFor synchronises with the worker's writes: the log is complete up to 1.0.
    const std::vector<double> expected = {0.5, 0.75, 0.75, 1.0};
    EXPECT_EQ(source.times, expected);
}

TEST(WindWorker, PostedWorkStopsTheUpdateUnderWayAfterItsCurrentStep) {
    // A whirlwind dropped during a long update (many solver steps) waits for one step, not for
    // the whole update: the work runs with the source at the end of the step under way, and the
    // worker then carries on to the request.
    SteppingSource source;
    const render::TerrainMesh mesh = noMesh();
    coupling::WindWorker worker(source, mesh, 0.5);
    constexpr double FAR_S = 100 * SteppingSource::STEP_S;  // an update of 100 steps
    worker.request(FAR_S, coupling::OverlaySpec{});
    while (!source.underWay.load()) std::this_thread::yield();  // in its second step
    double workRanAt_s = -1.0;  // written on the worker, read after waitFor (synchronised)
    const uint64_t number = worker.post([&workRanAt_s](coupling::WindSource& s) {
        workRanAt_s = static_cast<SteppingSource&>(s).time_s;
    });
    source.released.store(true);
    coupling::WindSnapshot shown;
    worker.waitFor(FAR_S, shown);
    EXPECT_EQ(workRanAt_s, 2 * SteppingSource::STEP_S);
    EXPECT_EQ(shown.t_s, FAR_S);
    EXPECT_GE(shown.workDone, number);
    EXPECT_EQ(shown.wind.groupIntensity.front(), float(FAR_S));
}

}  // namespace
