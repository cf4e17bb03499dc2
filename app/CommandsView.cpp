/// \file CommandsView.cpp
/// `gale view SCENE`: the scene in a GLFW window (context through OSMesa, docs/design.md 7), with a
/// mouse camera, play / pause / step / speed, toggles for grass, terrain and field overlays, and a
/// heads-up line. The wind runs on a worker thread and hands the renderer snapshots, so the window
/// stays responsive while a step computes; when the wind falls behind, the heads-up line says so.

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>  // key codes only: the window itself is render::GlfwWindow

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "app/Cli.h"
#include "app/Commands.h"
#include "app/io/Errors.h"
#include "app/io/Timing.h"
#include "app/scene/SceneBuilder.h"
#include "app/scene/SceneParser.h"
#include "coupling/FieldOverlayBuilder.h"
#include "render/FieldOverlay.h"
#include "render/GlfwWindow.h"
#include "render/ImageIO.h"
#include "render/OrbitCamera.h"
#include "render/RenderLimits.h"
#include "render/ShellRenderer.h"

namespace gale::app {
namespace {

/// Interactive frames are paced to at most this rate, so drawing leaves CPU to the wind worker
/// (llvmpipe and the solver share the same cores).
constexpr double MAX_INTERACTIVE_FPS = 60.0;
/// The heads-up line reports the wind as behind when the step drawn is older than the previous
/// frame's request and lags the clock by more than this many output frame intervals.
constexpr double BEHIND_FRAMES = 1.5;
constexpr double MIN_SPEED = 1.0 / 16.0, MAX_SPEED = 16.0;

/// Overlay modes the O key cycles through.
enum class OverlayMode { Scene, None, Arrows, Slice, Streamlines, All, Count };
const char* overlayModeName(OverlayMode m) {
    switch (m) {
        case OverlayMode::Scene:
            return "scene overlays";
        case OverlayMode::None:
            return "no overlays";
        case OverlayMode::Arrows:
            return "arrows";
        case OverlayMode::Slice:
            return "slice";
        case OverlayMode::Streamlines:
            return "streamlines";
        case OverlayMode::All:
            return "all overlays";
        default:
            return "?";
    }
}
coupling::OverlaySpec overlayFor(OverlayMode m, const coupling::OverlaySpec& scene) {
    coupling::OverlaySpec s = scene;
    s.arrows = s.slice = s.streamlines = s.vortexCores = false;
    switch (m) {
        case OverlayMode::Scene:
            return scene;
        case OverlayMode::None:
            break;
        case OverlayMode::Arrows:
            s.arrows = true;
            break;
        case OverlayMode::Slice:
            s.slice = true;
            break;
        case OverlayMode::Streamlines:
            s.streamlines = true;
            break;
        case OverlayMode::All:
            s.arrows = s.slice = s.streamlines = s.vortexCores = true;
            break;
        default:
            break;
    }
    return s;
}

/// What the wind worker hands the renderer: the grass wind at sim time t_s and its overlays.
struct Snapshot {
    double t_s = -1.0;
    render::GrassWind wind;
    render::FieldOverlayData overlay;
    double step_ms = 0.0;  ///< wall time of the wind update (and overlay build) for t_s
    std::string report;    ///< the source's stepReport() after that update
    uint64_t serial = 0;   ///< increments with every snapshot
};

/// The wind on its own thread. The main thread asks for a time (request), the worker brings the
/// source there and publishes a snapshot; the main thread copies the latest one (take) without
/// ever waiting for a step, unless it asks to (waitFor, used by --frames for exact frames).
class WindWorker {
  public:
    WindWorker(coupling::WindSource& source, const render::TerrainMesh& mesh, double grassHeight_m)
        : mSource(source), mMesh(mesh), mGrassHeight_m(grassHeight_m), mThread([this] { run(); }) {}
    ~WindWorker() {
        {
            std::lock_guard<std::mutex> lock(mMutex);
            mStop = true;
        }
        mWake.notify_all();
        mThread.join();
    }

    void request(double t_s, const coupling::OverlaySpec& overlay) {
        {
            std::lock_guard<std::mutex> lock(mMutex);
            mRequested_s = t_s;
            mOverlay = overlay;
        }
        mWake.notify_all();
    }
    /// Copies the latest snapshot into `out` if it is newer than out.serial (the per-vertex wind
    /// is shared, not copied: GrassWind::vertex). Returns true if it copied.
    bool take(Snapshot& out) {
        std::lock_guard<std::mutex> lock(mMutex);
        return copyLocked(out);
    }
    /// Waits until the snapshot for exactly t_s is there, then takes it.
    void waitFor(double t_s, Snapshot& out) {
        std::unique_lock<std::mutex> lock(mMutex);
        mDone.wait(lock, [&] { return mError || (mLatest.t_s == t_s && mLatest.serial > 0); });
        rethrowLocked();
        copyLocked(out);
    }
    /// Rethrows a failure of the worker on the calling (main) thread.
    void rethrowIfFailed() {
        std::lock_guard<std::mutex> lock(mMutex);
        rethrowLocked();
    }

  private:
    bool copyLocked(Snapshot& out) {
        if (mLatest.serial == out.serial) return false;
        out.wind = mLatest.wind;
        out.overlay = mLatest.overlay;
        out.t_s = mLatest.t_s;
        out.step_ms = mLatest.step_ms;
        out.report = mLatest.report;
        out.serial = mLatest.serial;
        return true;
    }
    void rethrowLocked() {
        if (mError) std::rethrow_exception(mError);
    }

    void run() {
        render::GrassWind wind;  // the worker's own, brought forward step by step
        coupling::OverlayScaleKeeper overlayScale;  // the automatic colour scale only grows
        double done_s = std::nan("");
        coupling::OverlaySpec doneOverlay;
        bool doneOverlaySet = false;
        for (;;) {
            double t_s;
            coupling::OverlaySpec overlay;
            {
                std::unique_lock<std::mutex> lock(mMutex);
                mWake.wait(lock, [&] {
                    return mStop ||
                           (mRequested_s && (!(*mRequested_s == done_s) || !doneOverlaySet ||
                                             !sameOverlay(mOverlay, doneOverlay)));
                });
                if (mStop) return;
                t_s = *mRequested_s;
                overlay = mOverlay;
            }
            try {
                const auto start = Clock::now();
                mSource.update(t_s, wind);
                render::FieldOverlayData data = coupling::buildOverlay(
                    mSource, wind, mMesh, overlayScale.frame(overlay), mGrassHeight_m);
                overlayScale.seen(data);
                const double step_ms = msSince(start);
                std::lock_guard<std::mutex> lock(mMutex);
                mLatest.wind = wind;
                mLatest.overlay = std::move(data);
                mLatest.t_s = t_s;
                mLatest.step_ms = step_ms;
                mLatest.report = mSource.stepReport();
                ++mLatest.serial;
            } catch (...) {
                std::lock_guard<std::mutex> lock(mMutex);
                mError = std::current_exception();
                mDone.notify_all();
                return;
            }
            done_s = t_s;
            doneOverlay = overlay;
            doneOverlaySet = true;
            mDone.notify_all();
        }
    }
    static bool sameOverlay(const coupling::OverlaySpec& a, const coupling::OverlaySpec& b) {
        return a.arrows == b.arrows && a.slice == b.slice && a.streamlines == b.streamlines &&
               a.vortexCores == b.vortexCores;
    }

    coupling::WindSource& mSource;
    const render::TerrainMesh& mMesh;
    double mGrassHeight_m;
    std::mutex mMutex;
    std::condition_variable mWake, mDone;
    std::optional<double> mRequested_s;
    coupling::OverlaySpec mOverlay;
    Snapshot mLatest;
    std::exception_ptr mError;
    bool mStop = false;
    std::thread mThread;  // last: starts after everything above is constructed
};

/// --keys: one character per frame stands for a key press ('>' the right arrow, ' ' space).
render::InputEvent scriptedKey(char c) {
    render::InputEvent e;
    e.kind = render::InputEvent::Kind::Key;
    switch (c) {
        case '>':
            e.key = GLFW_KEY_RIGHT;
            break;
        case ' ':
            e.key = GLFW_KEY_SPACE;
            break;
        case '+':
            e.key = GLFW_KEY_EQUAL;
            break;
        case '-':
            e.key = GLFW_KEY_MINUS;
            break;
        case '[':
            e.key = GLFW_KEY_LEFT_BRACKET;
            break;
        case ']':
            e.key = GLFW_KEY_RIGHT_BRACKET;
            break;
        case '.':
            e.key = GLFW_KEY_UNKNOWN;
            break;  // no key this frame
        default:
            e.key = std::toupper(static_cast<unsigned char>(c));
            break;  // GLFW_KEY_A.. = 'A'..
    }
    return e;
}

std::string fmt(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

}  // namespace

int runView(const ViewOptions& options) {
    SceneRunOptions sceneOptions;
    sceneOptions.scenePath = options.scenePath;
    sceneOptions.width = options.width;
    sceneOptions.height = options.height;
    Scene scene = loadScene(sceneOptions);
    const OutputSection& out = scene.output;

    // The window first: without a display there is no point in building (or solving) anything.
    std::unique_ptr<render::GlfwWindow> window;
    try {
        window = render::GlfwWindow::open(out.width, out.height, "gale view " + scene.name);
    } catch (const render::NoDisplayError& e) {
        const std::string what = e.what();
        throw std::runtime_error(what.rfind("no display", 0) == 0 ? what : "no display: " + what);
    }

    BuildOptions buildOptions;
    buildOptions.progress = [](const std::string& text) {
        std::fprintf(stderr, "gale: %s\n", text.c_str());
    };
    BuiltScene built = buildScene(scene, buildOptions);
    std::string solveLine;
    if (built.solve) {
        const sim::SolveReport& r = *built.solve;
        char buf[160];
        std::snprintf(buf, sizeof buf, "solve %s %d it res %.1e",
                      r.converged ? "ok" : "NOT CONVERGED", r.iterations, r.relativeResidual);
        solveLine = buf;
        std::fprintf(stderr, "gale: steady wind %s\n", buf);
    }

    window->makeCurrent();
    render::ShellRenderer renderer(*window);
    renderer.setTerrain(built.mesh);
    renderer.setGrass(scene.grass.params, built.texture);
    renderer.setDensityMap(built.densityMap);
    renderer.setLighting(scene.lighting);
    render::FieldOverlay overlay(*window);
    render::OrbitCamera orbit(built.camera);

    const bool scripted = options.frames.has_value();  // --frames: exact frames, then exit
    const int frameLimit = options.frames.value_or(0);
    OverlayMode overlayMode = scene.overlay.any() ? OverlayMode::Scene : OverlayMode::None;
    render::DrawOptions drawOptions;
    bool playing = true, showHud = true;
    double speed = 1.0;
    double simClock_s = out.startTime_s;  // the time the viewer wants to show
    int screenshotCount = 0;

    WindWorker worker(*built.wind, built.mesh, scene.grass.params.height_m);
    worker.request(simClock_s, overlayFor(overlayMode, scene.overlay));
    Snapshot shown;
    render::Image image;
    double frame_ms = 0.0, fpsSmoothed = 0.0;
    auto last = Clock::now();
    const auto start = Clock::now();
    int frames = 0;
    int behindFrames = 0;  // frames drawn while the wind lagged the clock
    double maxLag_s = 0.0;
    double previousRequest_s = out.startTime_s;
    std::string hudMessage;  // a transient note (screenshot saved, overlay mode)
    auto messageUntil = Clock::now();
    auto note = [&](const std::string& text) {
        hudMessage = text;
        messageUntil = Clock::now() + std::chrono::seconds(2);
        std::fprintf(stderr, "gale: %s\n", text.c_str());
    };

    std::fprintf(stderr,
                 "gale: viewing %s (%s); space play/pause, right arrow step, +/- speed, R reset "
                 "camera, G grass, T terrain, O overlays, [ ] shells, S screenshot, H heads-up, "
                 "Esc/Q quit; mouse: left drag orbit, right drag pan, scroll zoom\n",
                 scene.path.c_str(), window->description().c_str());

    while (!window->closeRequested()) {
        const auto frameStart = Clock::now();
        bool quit = false;
        std::vector<render::InputEvent> events = window->pollEvents();
        if (size_t(frames) < options.keys.size())
            events.push_back(scriptedKey(options.keys[frames]));
        for (const render::InputEvent& e : events) {
            using K = render::InputEvent::Kind;
            if (e.kind == K::Close) quit = true;
            if (e.kind == K::MouseDrag) {
                if (e.button == 0) orbit.orbit(e.dx, e.dy);
                if (e.button == 1 || e.button == 2) orbit.pan(e.dx, e.dy, out.height);
            }
            if (e.kind == K::Scroll) orbit.zoom(e.dy);
            if (e.kind != K::Key) continue;
            switch (e.key) {
                case GLFW_KEY_ESCAPE:
                case GLFW_KEY_Q:
                    quit = true;
                    break;
                case GLFW_KEY_SPACE:
                    playing = !playing;
                    break;
                case GLFW_KEY_RIGHT:
                    playing = false;
                    simClock_s += 1.0 / out.fps;
                    break;
                case GLFW_KEY_EQUAL:
                case GLFW_KEY_KP_ADD:
                    speed = std::min(MAX_SPEED, speed * 2.0);
                    break;
                case GLFW_KEY_MINUS:
                case GLFW_KEY_KP_SUBTRACT:
                    speed = std::max(MIN_SPEED, speed / 2.0);
                    break;
                case GLFW_KEY_R:
                    orbit.reset();
                    break;
                case GLFW_KEY_G:
                    drawOptions.grass = !drawOptions.grass;
                    break;
                case GLFW_KEY_T:
                    drawOptions.terrain = !drawOptions.terrain;
                    break;
                case GLFW_KEY_H:
                    showHud = !showHud;
                    break;
                case GLFW_KEY_O:
                    overlayMode = OverlayMode((int(overlayMode) + 1) % int(OverlayMode::Count));
                    if (overlayMode == OverlayMode::Scene && !scene.overlay.any())
                        overlayMode = OverlayMode::None;
                    note(overlayModeName(overlayMode));
                    break;
                case GLFW_KEY_LEFT_BRACKET:
                    renderer.setShellCount(std::max(0, renderer.shellCount() - 1));
                    break;
                case GLFW_KEY_RIGHT_BRACKET:
                    renderer.setShellCount(std::min(render::kMaxShells, renderer.shellCount() + 1));
                    break;
                case GLFW_KEY_S: {
                    const std::string path =
                        "gale_view_" + std::to_string(screenshotCount++) + ".png";
                    window->readPixels(image);  // the last frame, with its heads-up line
                    render::writeImageAtomic(image, path);
                    note("saved " + path);
                    break;
                }
                default:
                    break;
            }
        }
        if (quit) break;

        // The clock: exact frame times under --frames (like `gale render`), else wall time.
        if (scripted) {
            simClock_s = out.startTime_s + frames / out.fps;
        } else if (playing) {
            simClock_s += speed * std::chrono::duration<double>(frameStart - last).count();
        }
        last = frameStart;
        const coupling::OverlaySpec overlaySpec = overlayFor(overlayMode, scene.overlay);
        worker.request(simClock_s, overlaySpec);
        if (scripted)
            worker.waitFor(simClock_s, shown);
        else
            worker.take(shown);
        worker.rethrowIfFailed();

        const render::Camera camera = orbit.camera();
        if (shown.serial > 0) {
            renderer.draw(camera, shown.wind, drawOptions);
            if (overlaySpec.any()) overlay.draw(camera, shown.overlay);
        } else {
            renderer.draw(camera, render::GrassWind{}, drawOptions);  // the wind's first step
        }
        const bool lastFrame = scripted && frames + 1 >= frameLimit;
        if (lastFrame && !options.screenshotPath.empty()) {
            // Before the heads-up line, so it matches `gale render` of the same frame.
            window->readPixels(image);
            render::writeImageAtomic(image, options.screenshotPath);
        }

        // The heads-up line: frame rate, sim time, the wind step's cost, and lag.
        const double lag_s =
            (shown.serial > 0 ? simClock_s - shown.t_s : simClock_s - out.startTime_s);
        // The snapshot drawn answers at best the previous frame's request (one frame of pipeline
        // latency); older than that, the wind cannot keep up with the clock.
        const bool behind =
            !scripted && shown.t_s < previousRequest_s - 1e-9 && lag_s > BEHIND_FRAMES / out.fps;
        previousRequest_s = simClock_s;
        if (behind) ++behindFrames, maxLag_s = std::max(maxLag_s, lag_s);
        // Two lines, the state that changes first, so a narrow window still shows the lag.
        std::string hud = fmt("%.1f fps", fpsSmoothed) + "  " + fmt("%.0f ms", frame_ms) + "  t " +
                          fmt("%.2f s", shown.serial > 0 ? shown.t_s : 0.0) + "  step " +
                          fmt("%.1f ms", shown.step_ms);
        if (behind) hud += "  simulation behind by " + fmt("%.2f s", lag_s);
        std::string hud2 = "x" + fmt("%g", speed) + (playing ? "" : "  paused") + "  shells " +
                           std::to_string(renderer.shellCount());
        if (!shown.report.empty())
            hud2 += "  " + shown.report;
        else if (!solveLine.empty())
            hud2 += "  " + solveLine;
        if (Clock::now() < messageUntil) hud2 += "  " + hudMessage;
        if (showHud) {
            const int scale = out.height >= 600 ? 2 : 1;
            overlay.drawText(hud, 6 * scale, out.height - 26 * scale, scale, glm::vec3(1.0f));
            overlay.drawText(hud2, 6 * scale, out.height - 13 * scale, scale, glm::vec3(1.0f));
        }
        window->present();
        window->setTitle("gale view " + scene.name + "  " + hud + "  " + hud2);

        ++frames;
        frame_ms = msSince(frameStart);
        fpsSmoothed = fpsSmoothed > 0.0
                          ? 0.9 * fpsSmoothed + 0.1 * 1000.0 / std::max(frame_ms, 1e-3)
                          : 1000.0 / std::max(frame_ms, 1e-3);
        if (lastFrame) break;
        if (!scripted) {
            const double budget_ms = 1000.0 / MAX_INTERACTIVE_FPS;
            if (frame_ms < budget_ms)
                std::this_thread::sleep_for(
                    std::chrono::duration<double, std::milli>(budget_ms - frame_ms));
        }
    }
    const double total_s = msSince(start) / 1000.0;
    std::string behindNote;
    if (behindFrames > 0)
        behindNote = "; the wind lagged the clock in " + std::to_string(behindFrames) +
                     " frames (at most " + fmt("%.2f s", maxLag_s) + ")";
    std::printf("viewed %d frames in %.2f s (%.1f fps at %d x %d)%s%s%s\n", frames, total_s,
                frames / std::max(total_s, 1e-9), out.width, out.height,
                options.screenshotPath.empty() ? "" : "; screenshot ",
                options.screenshotPath.c_str(), behindNote.c_str());
    return EXIT_OK;
}

void addViewVerb(CLI::App& app, VerbTable& verbs) {
    auto options = std::make_shared<ViewOptions>();
    CLI::App* verb = app.add_subcommand(
        "view", "Show a scene in a window: mouse camera, play/pause, overlays (needs a display)");
    verb->add_option("scene", options->scenePath, "Scene file")->required();
    verb->add_option("--frames", options->frames,
                     "Draw this many frames at the scene's frame times, then exit")
        ->check(CLI::Range(1, MAX_FRAMES));
    verb->add_option("--screenshot", options->screenshotPath,
                     "Save the last frame (without the heads-up line) to this PNG");
    verb->add_option("--keys", options->keys,
                     "Replay key presses, one character per frame ('>' right arrow, ' ' space, "
                     "'.' none): for tests and demos");
    verb->add_option("--width", options->width, "Window width in pixels (default output.width)")
        ->check(CLI::Range(1, MAX_IMAGE_SIDE_PX));
    verb->add_option("--height", options->height, "Window height in pixels (default output.height)")
        ->check(CLI::Range(1, MAX_IMAGE_SIDE_PX));
    verb->footer(std::string("\nKeys: space play/pause, right arrow step, +/- speed, R reset "
                             "camera, G grass, T terrain, O overlays, [ ] shells, S screenshot, "
                             "H heads-up, Esc/Q quit. Mouse: left drag orbit, right drag pan, "
                             "scroll zoom. Without a display: exit 1, use 'gale render'.") +
                 EXIT_CODES_FOOTER);
    verbs.add(verb, [options] { return runView(*options); });
}

}  // namespace gale::app
