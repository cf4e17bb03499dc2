/// \file WindWorker.cpp
/// The wind on its own thread (see WindWorker.h).

#include "coupling/WindWorker.h"

#include <chrono>
#include <cmath>
#include <utility>

namespace gale::coupling {
namespace {

bool sameOverlay(const OverlaySpec& a, const OverlaySpec& b) {
    return a.arrows == b.arrows && a.slice == b.slice && a.streamlines == b.streamlines &&
           a.vortexCores == b.vortexCores;
}

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

}  // namespace

WindWorker::WindWorker(WindSource& source, const render::TerrainMesh& mesh, double grassHeight_m)
    : mSource(source), mMesh(mesh), mGrassHeight_m(grassHeight_m), mThread([this] { run(); }) {}

WindWorker::~WindWorker() {
    {
        std::lock_guard<std::mutex> lock(mMutex);
        mStop = true;
    }
    mWake.notify_all();
    mThread.join();
}

void WindWorker::request(double t_s, const OverlaySpec& overlay) {
    {
        std::lock_guard<std::mutex> lock(mMutex);
        mRequested_s = t_s;
        mOverlay = overlay;
    }
    mWake.notify_all();
}

uint64_t WindWorker::post(std::function<void(WindSource&)> work) {
    uint64_t number = 0;
    {
        std::lock_guard<std::mutex> lock(mMutex);
        mPosted.push_back(std::move(work));
        number = ++mPostedCount;
        mPostedAtomic.store(number);
    }
    mWake.notify_all();
    return number;
}

bool WindWorker::take(WindSnapshot& out) {
    std::lock_guard<std::mutex> lock(mMutex);
    return copyLocked(out);
}

void WindWorker::waitFor(double t_s, WindSnapshot& out) {
    std::unique_lock<std::mutex> lock(mMutex);
    mDone.wait(lock, [&] { return mError || (mLatest.t_s == t_s && mLatest.serial > 0); });
    if (mError) std::rethrow_exception(mError);
    copyLocked(out);
}

void WindWorker::rethrowIfFailed() {
    std::lock_guard<std::mutex> lock(mMutex);
    if (mError) std::rethrow_exception(mError);
}

bool WindWorker::copyLocked(WindSnapshot& out) const {
    if (mLatest.serial == out.serial) return false;
    out = mLatest;
    return true;
}

void WindWorker::run() {
    render::GrassWind wind;           // the worker's own, brought forward step by step
    OverlayScaleKeeper overlayScale;  // the automatic colour scale only grows
    double done_s = std::nan("");     // NaN: nothing done yet (NaN equals nothing)
    uint64_t donePosted = 0;
    OverlaySpec doneOverlay;
    bool doneOverlaySet = false;
    for (;;) {
        double t_s = 0.0;
        OverlaySpec overlay;
        std::vector<std::function<void(WindSource&)>> work;
        uint64_t posted = 0;
        {
            std::unique_lock<std::mutex> lock(mMutex);
            mWake.wait(lock, [&] {
                return mStop || (mRequested_s && (!(*mRequested_s == done_s) || !doneOverlaySet ||
                                                  !sameOverlay(mOverlay, doneOverlay) ||
                                                  mPostedCount != donePosted));
            });
            if (mStop) return;
            t_s = *mRequested_s;
            overlay = mOverlay;
            work.swap(mPosted);
            posted = mPostedCount;
        }
        double reached_s = t_s;
        try {
            // Brings the source to `at_s`, builds the overlays and publishes the snapshot; returns
            // at_s. Stopped short because work was posted, it publishes nothing (the work's own
            // snapshot follows at once) and returns the time the source reached.
            const auto stop = [this, posted] { return mPostedAtomic.load() != posted; };
            auto workStarted = std::chrono::steady_clock::time_point{};
            double work_ms = 0.0;
            const auto publish = [&](double at_s, std::chrono::steady_clock::time_point start) {
                const double shown_s = mSource.updateUntil(at_s, wind, stop);
                if (shown_s < at_s) return shown_s;
                render::FieldOverlayData data =
                    buildOverlay(mSource, wind, mMesh, overlayScale.frame(overlay), mGrassHeight_m);
                overlayScale.seen(data);
                const double step_ms = msSince(start);
                std::string report = mSource.stepReport();
                std::lock_guard<std::mutex> lock(mMutex);
                mLatest.wind = wind;
                mLatest.overlay = std::move(data);
                mLatest.t_s = shown_s;
                mLatest.step_ms = step_ms;
                mLatest.report = std::move(report);
                mLatest.workDone = posted;
                if (!work.empty()) mLatest.workStarted = workStarted, mLatest.work_ms = work_ms;
                mLatest.published = std::chrono::steady_clock::now();
                ++mLatest.serial;
                return shown_s;
            };
            const auto start = std::chrono::steady_clock::now();
            if (!work.empty()) {
                workStarted = start;
                for (auto& w : work) w(mSource);
                work_ms = msSince(start);
            }
            // Work changed the source (a whirlwind dropped with the mouse): show it at the time
            // already shown first, which takes no solver step, so the reader's next frame has it
            // instead of waiting for the step to the newer request as well.
            if (!work.empty() && done_s < t_s) {
                (void)publish(done_s, start);
                mDone.notify_all();
                reached_s = publish(t_s, std::chrono::steady_clock::now());
            } else {
                reached_s = publish(t_s, start);
            }
        } catch (...) {
            std::lock_guard<std::mutex> lock(mMutex);
            mError = std::current_exception();
            mDone.notify_all();
            return;
        }
        done_s = reached_s;  // short of t_s when work was posted meanwhile: the loop goes on
        donePosted = posted;
        doneOverlay = overlay;
        doneOverlaySet = true;
        mDone.notify_all();
    }
}

}  // namespace gale::coupling
