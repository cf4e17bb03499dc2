/// \file CommandsView.cpp
/// `gale view SCENE`: the scene in a GLFW window (context through OSMesa, docs/design.md 7), with a
/// mouse camera, play / pause / step / speed, toggles for grass, terrain and field overlays, and a
/// heads-up line. The wind runs on a worker thread and hands the renderer snapshots, so the window
/// stays responsive while a step computes; when the wind falls behind, the heads-up line says so.

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "app/Cli.h"
#include "app/Commands.h"
#include "app/ViewInput.h"
#include "app/io/Errors.h"
#include "app/io/Timing.h"
#include "app/scene/SceneBuilder.h"
#include "app/scene/SceneParser.h"
#include "coupling/FieldOverlayBuilder.h"
#include "coupling/LiveWind.h"
#include "coupling/UnsteadyFieldWind.h"
#include "coupling/ViewPipeline.h"
#include "render/CameraMath.h"
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
/// The clock runs at most this many output frames ahead of the wind drawn. A wind that cannot keep
/// up (an unsteady solver on a loaded machine) then plays in slow motion instead of taking ever
/// longer updates to catch up, during which wind dropped into the flow would wait its turn.
constexpr double MAX_WIND_AHEAD_FRAMES = 2.0;
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

/// A live source posted to the wind worker whose effect the grass does not show yet.
struct LivePending {
    bool active = false;
    coupling::LiveSourceKind kind = coupling::LiveSourceKind::Whirlwind;
    Clock::time_point posted{};
    uint64_t work = 0;  ///< WindWorker::post's number
};

/// A move of the live wind to other cells (the C key), posted to the wind worker, until done.
struct GridPending {
    bool active = false;
    uint64_t work = 0;                   ///< WindWorker::post's number
    double cell_m = 0.0;                 ///< the cells asked for
    std::shared_ptr<std::string> error;  ///< set by the worker when the move failed
    std::shared_ptr<std::string> grid;   ///< set by the worker: the new grid's size, in words
};

/// Posts the move of the live wind to cells of cell_m to the wind worker: the scene's grid there
/// (buildLiveWindGrid, on the worker) takes up the run (UnsteadyFieldWind::moveToGrid). `scene`
/// and `terrain` must outlive the worker.
GridPending postLiveGridMove(coupling::ViewPipeline& view, const Scene& scene,
                             const sim::Heightfield& terrain, double cell_m) {
    GridPending pending{true, 0, cell_m, std::make_shared<std::string>(),
                        std::make_shared<std::string>()};
    pending.work = view.worker().post([&scene, &terrain, cell_m, error = pending.error,
                                       grid = pending.grid](coupling::WindSource& wind) {
        try {
            LiveWindGrid g = buildLiveWindGrid(scene, terrain, cell_m);
            *grid = std::to_string(g.domain->nx()) + " x " + std::to_string(g.domain->ny()) +
                    " x " + std::to_string(g.domain->nz());
            (void)static_cast<coupling::UnsteadyFieldWind&>(wind).moveToGrid(
                std::move(g.domain), g.steady, g.settings, g.referenceSpeed_mps);
        } catch (const std::exception& failure) {
            *error = failure.what();  // the wind stays on its grid
        }
    });
    return pending;
}

/// The live source a gesture asks for, placed on the terrain under its pixels; nothing when the
/// cursor is off the terrain. Sizes: a 3 m core / half-width / radius and 6 m/s, a little above
/// a breeze, so the grass visibly answers in any of the examples.
std::optional<coupling::LiveSource> placeLiveSource(const LiveRequest& request,
                                                    const render::Camera& camera, int width_px,
                                                    int height_px,
                                                    const render::TerrainMesh& mesh) {
    auto pick = [&](double x_px, double y_px) {
        const render::WorldRay ray = render::pixelRay(camera, width_px, height_px, x_px, y_px);
        return coupling::pickTerrain(mesh, ray.wsOrigin_m, ray.wsDirection);
    };
    const std::optional<glm::vec3> at = pick(request.x_px, request.y_px);
    if (!at) return std::nullopt;
    coupling::LiveSource source;
    source.kind = request.kind;
    source.wsAt_m = {at->x, at->y};
    source.wsTo_m = source.wsAt_m;
    if (request.kind == coupling::LiveSourceKind::GustFront) {
        if (const std::optional<glm::vec3> to = pick(request.x2_px, request.y2_px))
            source.wsTo_m = {to->x, to->y};
    }
    return source;
}

std::string fmt(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

/// --screenshot is checked before the window opens or anything is built: a writable image format,
/// a folder that exists, and not a file the scene reads (refuseAliases). Throws InputError.
void checkScreenshotPath(const Scene& scene, const std::string& path) {
    namespace fs = std::filesystem;
    if (!render::canWriteImageFormat(path))
        throw InputError("--screenshot: '" + path +
                         "': no image format for its extension; name a .png (or .exr, .jpg, .tif)");
    const fs::path folder =
        fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
    std::error_code ec;
    if (!fs::is_directory(folder, ec))
        throw InputError("--screenshot: '" + path + "': the folder '" + folder.string() +
                         (fs::exists(folder, ec) ? "' is a file" : "' does not exist"));
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
        throw InputError("--screenshot: '" + path + "': the folder '" + folder.string() +
                         "' is not writable: " + std::strerror(errno));
    refuseAliases(sceneInputs(scene), {{path, "--screenshot"}});
}

/// The first "gale_view_N.png" (N from `next` up) that does not exist, so that S never replaces
/// a file (an earlier screenshot, or a scene's input named like one); advances `next` past it.
std::string nextScreenshotName(int& next) {
    namespace fs = std::filesystem;
    for (;; ++next) {
        const std::string path = "gale_view_" + std::to_string(next) + ".png";
        std::error_code ec;
        if (!fs::exists(fs::symlink_status(path, ec))) {
            ++next;
            return path;
        }
    }
}

}  // namespace

void limitUnsteadyStepToAFrame(Scene& scene) {
    sim::UnsteadySettings& u = scene.unsteady.settings;
    if (scene.wind.kind == WindKind::Unsteady && !(u.dt_s > 0.0))
        u.maxDt_s = std::min(u.maxDt_s, 1.0 / scene.output.fps);
    u.projection.relativeTolerance = scene.unsteady.liveTolerance;
    u.projection.maxIterations = scene.unsteady.liveIterations;
}

void shareCoresWithLiveWind() {
    if (std::getenv("LP_NUM_THREADS")) return;  // the user's choice
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const std::string n = std::to_string(std::max(1u, cores / 2));
    setenv("LP_NUM_THREADS", n.c_str(), 1);
    std::fprintf(stderr,
                 "gale: live wind beside the renderer: llvmpipe on %s of %u cores "
                 "(LP_NUM_THREADS), the wind solver on the rest\n",
                 n.c_str(), cores);
}

int runView(const ViewOptions& options) {
    SceneRunOptions sceneOptions;
    sceneOptions.scenePath = options.scenePath;
    sceneOptions.width = options.width;
    sceneOptions.height = options.height;
    Scene scene = loadScene(sceneOptions);
    limitUnsteadyStepToAFrame(scene);
    if (scene.wind.kind == WindKind::Unsteady) shareCoresWithLiveWind();
    const OutputSection& out = scene.output;
    // Bad --input is bad input, found before the window opens or anything is solved.
    const std::map<int, std::vector<render::InputEvent>> inputScript =
        parseInputScript(options.input);
    if (!options.screenshotPath.empty()) checkScreenshotPath(scene, options.screenshotPath);

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
        std::fprintf(stderr, "gale: steady wind: %s\n", built.fieldSummary.c_str());
    }

    window->makeCurrent();
    coupling::ViewInputs inputs;
    inputs.mesh = &built.mesh;
    inputs.grass = &scene.grass.params;
    inputs.texture = &built.texture;
    inputs.densityMap = &built.densityMap;
    inputs.lighting = &scene.lighting;
    inputs.wind = built.wind.get();
    coupling::ViewPipeline view(*window, inputs);
    render::ShellRenderer& renderer = view.renderer();
    render::FieldOverlay& overlay = view.overlay();
    render::OrbitCamera orbit(built.camera);
    // Live wind needs a flow to drop it into: the unsteady solver (only its worker touches it).
    const bool liveWind = dynamic_cast<coupling::UnsteadyFieldWind*>(built.wind.get()) != nullptr;
    LiveGestures gestures;
    LivePending livePending;  // the last live source, until the grass has it
    // The C key: the live wind on cells twice the scene's, for a view whose wind cannot keep up,
    // and back. The scene's composition builds the other grid (buildLiveWindGrid) on the wind's
    // worker, which carries the flow over (UnsteadyFieldWind::moveToGrid).
    const double sceneCell_m = scene.solver.domain.voxelSize_m;
    double liveCell_m = sceneCell_m;
    GridPending gridPending;

    const bool scripted = options.frames.has_value();  // --frames: exact frames, then exit
    const int frameLimit = options.frames.value_or(0);
    OverlayMode overlayMode = scene.overlay.any() ? OverlayMode::Scene : OverlayMode::None;
    render::DrawOptions drawOptions;
    bool playing = true, showHud = true;
    double speed = 1.0;
    double simClock_s = out.startTime_s;  // the time the viewer wants to show
    int screenshotCount = 0;

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
                 "Esc/Q quit; mouse: left drag orbit, right drag pan, scroll zoom; live wind: "
                 "click whirlwind, shift-drag gust front, W/B/D whirlwind/blast/downwash, C "
                 "coarser live grid\n",
                 scene.path.c_str(), window->description().c_str());

    while (!window->closeRequested()) {
        const auto frameStart = Clock::now();
        bool quit = false;
        std::vector<render::InputEvent> events = window->pollEvents();
        if (size_t(frames) < options.keys.size())
            events.push_back(scriptedKey(options.keys[frames]));
        if (auto it = inputScript.find(frames); it != inputScript.end())
            events.insert(events.end(), it->second.begin(), it->second.end());
        for (const render::InputEvent& e : events) {
            using K = render::InputEvent::Kind;
            if (e.kind == K::Close) quit = true;
            bool consumed = false;
            if (const std::optional<LiveRequest> request = gestures.handle(e, consumed)) {
                if (!liveWind) {
                    note("live wind needs an unsteady scene (wind.kind = \"unsteady\")");
                } else if (const std::optional<coupling::LiveSource> source = placeLiveSource(
                               *request, orbit.camera(), out.width, out.height, built.mesh)) {
                    const coupling::LiveSource placed = *source;
                    const uint64_t number =
                        view.worker().post([placed](coupling::WindSource& wind) {
                            auto& unsteady = static_cast<coupling::UnsteadyFieldWind&>(wind);
                            (void)coupling::addLiveSource(unsteady.solver(), placed);
                            // The grass reads the field through its sampled steps: the newest
                            // one takes the source now, not at the solver's next step.
                            unsteady.resampleCurrentField();
                        });
                    livePending = LivePending{true, placed.kind, Clock::now(), number};
                    note(std::string(coupling::liveSourceName(placed.kind)) + " at (" +
                         fmt("%.1f", placed.wsAt_m[0]) + ", " + fmt("%.1f", placed.wsAt_m[1]) +
                         ") m");
                } else {
                    note("no terrain under the cursor");
                }
            }
            if (consumed) continue;
            if (e.kind == K::MouseDrag) {
                if (e.button == 0) orbit.orbit(e.dx, e.dy);
                if (e.button == 1 || e.button == 2) orbit.pan(e.dx, e.dy, out.height);
            }
            if (e.kind == K::Scroll) orbit.zoom(e.dy);
            if (e.kind != K::Key) continue;
            switch (e.key) {
                case render::Key::Escape:
                case render::Key::Q:
                    quit = true;
                    break;
                case render::Key::Space:
                    playing = !playing;
                    break;
                case render::Key::Right:
                    playing = false;
                    simClock_s += 1.0 / out.fps;
                    break;
                case render::Key::Equal:
                case render::Key::KeypadAdd:
                    speed = std::min(MAX_SPEED, speed * 2.0);
                    break;
                case render::Key::Minus:
                case render::Key::KeypadSubtract:
                    speed = std::max(MIN_SPEED, speed / 2.0);
                    break;
                case render::Key::R:
                    orbit.reset();
                    break;
                case render::Key::G:
                    drawOptions.grass = !drawOptions.grass;
                    break;
                case render::Key::T:
                    drawOptions.terrain = !drawOptions.terrain;
                    break;
                case render::Key::H:
                    showHud = !showHud;
                    break;
                case render::Key::C: {
                    if (!liveWind) {
                        note("a coarser live grid needs an unsteady scene");
                        break;
                    }
                    if (gridPending.active) {
                        note("the live wind is still moving to " + fmt("%g m", gridPending.cell_m) +
                             " cells");
                        break;
                    }
                    const double target =
                        liveCell_m == sceneCell_m ? 2.0 * sceneCell_m : sceneCell_m;
                    gridPending = postLiveGridMove(view, scene, built.heightfield, target);
                    note("moving the live wind to " + fmt("%g m", target) + " cells");
                    break;
                }
                case render::Key::O:
                    overlayMode = OverlayMode((int(overlayMode) + 1) % int(OverlayMode::Count));
                    if (overlayMode == OverlayMode::Scene && !scene.overlay.any())
                        overlayMode = OverlayMode::None;
                    note(overlayModeName(overlayMode));
                    break;
                case render::Key::LeftBracket:
                    renderer.setShellCount(std::max(0, renderer.shellCount() - 1));
                    break;
                case render::Key::RightBracket:
                    renderer.setShellCount(std::min(render::MAX_SHELLS, renderer.shellCount() + 1));
                    break;
                case render::Key::S: {
                    const std::string path = nextScreenshotName(screenshotCount);
                    window->readPixels(image);  // the last frame, with its heads-up line
                    try {
                        render::writeImageAtomic(image, path);
                        note("saved " + path);
                    } catch (const std::runtime_error& saveError) {
                        // A full disk or a folder made read-only since: say so, keep viewing.
                        std::fprintf(stderr, "gale: warning: %s\n", saveError.what());
                        note("screenshot not saved");
                    }
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
            if (view.shown().serial > 0)
                simClock_s =
                    std::min(simClock_s, view.shown().t_s + MAX_WIND_AHEAD_FRAMES / out.fps);
        }
        last = frameStart;
        const coupling::OverlaySpec overlaySpec = overlayFor(overlayMode, scene.overlay);
        const render::Camera camera = orbit.camera();
        view.draw(camera, simClock_s, overlaySpec, drawOptions, /*exact=*/scripted);
        const coupling::WindSnapshot& shown = view.shown();
        if (livePending.active && shown.workDone >= livePending.work) {
            // The first snapshot updated after the source went in: the grass has it. Where the
            // time went: waiting for the worker (the step under way), adding and projecting the
            // source, and publishing it until this frame took it.
            const double total_ms = msSince(livePending.posted);
            auto msBetween = [](Clock::time_point a, Clock::time_point b) {
                return std::max(0.0, std::chrono::duration<double, std::milli>(b - a).count());
            };
            const double wait_ms = msBetween(livePending.posted, shown.workStarted);
            const double publish_ms =
                std::max(0.0, msBetween(shown.workStarted, shown.published) - shown.work_ms);
            std::fprintf(stderr,
                         "gale: %s answered in %.0f ms (wall): %.0f ms waiting for the worker, "
                         "%.0f ms adding and projecting it, %.0f ms publishing, %.0f ms until "
                         "this frame took and drew it; at sim t %.3f s\n",
                         coupling::liveSourceName(livePending.kind), total_ms, wait_ms,
                         shown.work_ms, publish_ms, msBetween(shown.published, Clock::now()),
                         shown.t_s);
            livePending.active = false;
        }
        if (gridPending.active && shown.workDone >= gridPending.work) {
            gridPending.active = false;
            if (gridPending.error->empty()) {
                liveCell_m = gridPending.cell_m;
                note("live wind on " + fmt("%g m", liveCell_m) + " cells (" + *gridPending.grid +
                     ")");
            } else {
                note("live wind kept on " + fmt("%g m", liveCell_m) +
                     " cells: " + *gridPending.error);
            }
        }
        const bool lastFrame = scripted && frames + 1 >= frameLimit;
        if (lastFrame && !options.screenshotPath.empty()) {
            // Before the heads-up line, so it matches `gale render` of the same frame.
            window->readPixels(image);
            try {
                render::writeImageAtomic(image, options.screenshotPath);
            } catch (const std::runtime_error& e) {
                throw std::runtime_error("--screenshot: " + std::string(e.what()));
            }
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
        if (behind) {
            hud += "  simulation behind by " + fmt("%.2f s", lag_s);
            if (liveWind && liveCell_m == sceneCell_m) hud += " (C: coarser live grid)";
        }
        std::string hud2 = "x" + fmt("%g", speed) + (playing ? "" : "  paused") + "  shells " +
                           std::to_string(renderer.shellCount());
        if (liveCell_m != sceneCell_m) hud2 += "  live grid " + fmt("%g m", liveCell_m);
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
        view.present();
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
    verb->add_option("--input", options->input,
                     "Replay mouse actions, 'FRAME:ACTION:X,Y[,X2,Y2];...' in window pixels, "
                     "ACTION click, gust (a shift-drag to X2,Y2), whirlwind, blast, downwash: for "
                     "tests and demos");
    verb->add_option("--width", options->width, "Window width in pixels (default output.width)")
        ->check(CLI::Range(1, MAX_IMAGE_SIDE_PX));
    verb->add_option("--height", options->height, "Window height in pixels (default output.height)")
        ->check(CLI::Range(1, MAX_IMAGE_SIDE_PX));
    verb->footer(std::string("\nKeys: space play/pause, right arrow step, +/- speed, R reset "
                             "camera, G grass, T terrain, O overlays, [ ] shells, S screenshot, "
                             "H heads-up, Esc/Q quit. Mouse: left drag orbit, right drag pan, "
                             "scroll zoom.\nLive wind (unsteady scenes): left click drops a "
                             "whirlwind, shift + left drag launches a gust front along the drag, "
                             "W / B / D drop a whirlwind / a blast / a downwash at the cursor.\n"
                             "Without a display: exit 1, use 'gale render'.") +
                 EXIT_CODES_FOOTER);
    verbs.add(verb, [options] { return runView(*options); });
}

}  // namespace gale::app
