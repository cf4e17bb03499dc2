#pragma once
/// \file WindWorker.h
/// A wind source on its own thread, handing a reader (the window's frame loop) complete snapshots.
/// The reader asks for a sim time (request); the worker brings the source there, builds the field
/// overlays for it and publishes one snapshot under a lock; the reader copies the newest one (take)
/// without waiting for a step, or waits for an exact time (waitFor, for scripted frames). Work for
/// the source (a whirlwind dropped with the mouse) is posted to the worker and runs on its thread
/// before the next update, so the source is only ever touched by one thread.
///
/// @code
/// WindWorker worker(source, mesh, grassHeight_m);
/// worker.request(t_s, overlaySpec);
/// WindSnapshot shown;
/// worker.take(shown);          // or worker.waitFor(t_s, shown)
/// worker.rethrowIfFailed();    // a failure on the worker thread surfaces here
/// @endcode

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "coupling/FieldOverlayBuilder.h"
#include "coupling/WindSource.h"
#include "render/FieldOverlay.h"
#include "render/GrassInput.h"

namespace gale::coupling {

/// What the worker hands the reader: the grass wind at sim time t_s and its overlays, published
/// together (never one without the other).
struct WindSnapshot {
    double t_s = -1.0;  ///< sim time of the wind, seconds; -1 before the first snapshot
    render::GrassWind wind;
    render::FieldOverlayData overlay;
    double step_ms = 0.0;   ///< wall time of the wind update (and overlay build) for t_s
    std::string report;     ///< the source's stepReport() after that update
    uint64_t serial = 0;    ///< increments with every snapshot; 0: none yet
    uint64_t workDone = 0;  ///< posted work items (post()) that ran before this snapshot's update
    /// When the newest batch of posted work began to run on the worker, and its wall time in
    /// milliseconds (a dropped source's projection): with the time of post(), where a dropped
    /// source's latency goes. Default (epoch, 0) before any work.
    std::chrono::steady_clock::time_point workStarted{};
    double work_ms = 0.0;
    /// When this snapshot was published (after the source's update and the overlays).
    std::chrono::steady_clock::time_point published{};
};

class WindWorker {
  public:
    /// Starts the thread. `source` and `mesh` must outlive the worker and are not touched by the
    /// caller while it runs (post() work to the source instead). grassHeight_m > 0 sets where the
    /// overlays sample (FieldOverlayBuilder.h).
    WindWorker(WindSource& source, const render::TerrainMesh& mesh, double grassHeight_m);
    /// Stops the thread: the step under way finishes, nothing further starts. Never throws; a
    /// failure not yet rethrown is dropped.
    ~WindWorker();
    WindWorker(const WindWorker&) = delete;
    WindWorker& operator=(const WindWorker&) = delete;

    /// Asks for the wind at sim time t_s (seconds) with these overlays. Only the newest request
    /// counts: a request made while a step runs replaces any older one still waiting.
    void request(double t_s, const OverlaySpec& overlay);
    /// Runs `work` on the worker thread before its next update, in the order posted, and makes the
    /// worker update again even at an unchanged request time (the source changed). An update
    /// under way stops after its current solver step (WindSource::updateUntil), publishing nothing,
    /// so the work waits for one step at most, not for the whole update. When the
    /// request is newer than the last snapshot, the worker first publishes a snapshot at the last
    /// snapshot's time (no solver step for a stepped source), then one at the request. An exception
    /// from `work` is a failure of the worker (rethrowIfFailed). Returns the item's number
    /// (1, 2, ...): the first snapshot with workDone >= that number shows its effect.
    uint64_t post(std::function<void(WindSource&)> work);
    /// Copies the newest snapshot into `out` if it is newer than out.serial (the per-vertex wind is
    /// shared, not copied: GrassWind::vertex). Never waits for a step. Returns true if it copied.
    bool take(WindSnapshot& out);
    /// Waits until the snapshot for exactly t_s (requested before) is there, then takes it.
    /// Rethrows the worker's failure instead if it failed.
    void waitFor(double t_s, WindSnapshot& out);
    /// Rethrows a failure of the worker thread (an exception from the source, the overlay builder
    /// or posted work) on the calling thread; does nothing while the worker is well.
    void rethrowIfFailed();

  private:
    void run();
    bool copyLocked(WindSnapshot& out) const;

    WindSource& mSource;
    const render::TerrainMesh& mMesh;
    double mGrassHeight_m;
    std::mutex mMutex;
    std::condition_variable mWake, mDone;
    std::optional<double> mRequested_s;
    OverlaySpec mOverlay;
    std::vector<std::function<void(WindSource&)>> mPosted;
    uint64_t mPostedCount = 0;  ///< work items posted so far (the worker updates after each batch)
    std::atomic<uint64_t> mPostedAtomic{0};  ///< mPostedCount, read by updates without the lock
    WindSnapshot mLatest;
    std::exception_ptr mError;
    bool mStop = false;
    std::thread mThread;  // last: starts after everything above is constructed
};

}  // namespace gale::coupling
