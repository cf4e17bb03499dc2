/// \file BenchView.cpp
/// The view benchmark: each scene's frames through coupling::ViewPipeline, the loop `gale view`
/// runs, with the frame split into its parts (see BenchView.h).

#include "app/bench/BenchView.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/io/Progress.h"
#include "app/io/Timing.h"
#include "render/GlContext.h"
#include "render/GlInfo.h"
#include "render/GlfwWindow.h"
#include "render/RenderBench.h"
#include "render/RenderLimits.h"

namespace gale::app {
namespace {

namespace fs = std::filesystem;

/// The frame-rate target of issue 13: every example at 640 x 480 with 17 shells; reported, not
/// judged (absolute rates on a shared machine move 2-3x from day to day).
constexpr double TARGET_FPS = 30.0;
/// The judged target of issue 26: every scene's frame time at most this many times the fill
/// floor's, measured in the same run (the floor: shells + 1 full-screen, nearest-sampled,
/// alpha-tested layers of the same size, render::measureShellFill's nearest fill).
constexpr double TARGET_FLOOR_RATIO = 2.0;

/// The fill floor's frame time, ms: the nearest-sampled trivial fill of render::measureShellFill
/// at the bench's size and layer count, in its own headless context.
double fillFloor_ms(int width, int height, int shells, bool quick) {
    render::ShellFillCase c;
    c.width = width;
    c.height = height;
    c.layers = shells + 1;
    c.frames = quick ? 2 : 20;
    c.warmupFrames = quick ? 1 : 2;
    const render::ShellFillResult r = render::measureShellFill(c);
    return 1000.0 / std::max(r.nearestFps, 1e-9);
}

struct ViewRow {
    std::string name;
    size_t vertices = 0;
    double build_ms = 0.0;
    double fps = 0.0;
    coupling::FrameTimes mean;  ///< per timed frame
    double windStep_ms = 0.0;   ///< the worker's mean step (wind update and overlays), its thread
    double windUpdates_per_s = 0.0;  ///< new snapshots the frames received, per second
    int frames = 0;
    int blades = 0;  ///< near blades per frame, mean
};

/// Scene files: each path as given, or every *.toml in a folder, sorted by name.
std::vector<std::string> sceneFiles(const std::vector<std::string>& paths) {
    std::vector<std::string> files;
    for (const std::string& path : paths) {
        std::error_code error;
        if (fs::is_directory(path, error)) {
            std::vector<std::string> found;
            for (const fs::directory_entry& e : fs::directory_iterator(path, error))
                if (e.is_regular_file() && e.path().extension() == ".toml")
                    found.push_back(e.path().string());
            if (found.empty())
                throw std::invalid_argument("bench view: no *.toml scene in the folder '" + path +
                                            "'");
            std::sort(found.begin(), found.end());
            files.insert(files.end(), found.begin(), found.end());
        } else {
            files.push_back(path);
        }
    }
    return files;
}

ViewRow measure(render::GlContext& context, ViewBenchScene& scene, int warmup, int frames) {
    ViewRow row;
    row.name = scene.name;
    row.vertices = scene.inputs.mesh->wsPosition_m.size();
    row.build_ms = scene.build_ms;
    row.frames = frames;
    context.makeCurrent();
    coupling::ViewPipeline view(context, scene.inputs);
    const render::DrawOptions drawOptions;
    auto frameTime = [&](int i) { return scene.startTime_s + i / scene.fps; };
    // Warm-up: the first frame waits for the wind's first step (the view shows still grass until
    // then), the rest run as the view runs.
    for (int i = 0; i < warmup; ++i) {
        view.draw(scene.camera, frameTime(i), scene.overlay, drawOptions, /*exact=*/i == 0);
        view.present();
    }
    std::set<uint64_t> serials;
    double stepSum_ms = 0.0;
    const auto start = Clock::now();
    for (int i = 0; i < frames; ++i) {
        coupling::FrameTimes t = view.draw(scene.camera, frameTime(warmup + i), scene.overlay,
                                           drawOptions, /*exact=*/false);
        t.present_ms = view.present();
        row.mean.wind_ms += t.wind_ms;
        row.mean.upload_ms += t.upload_ms;
        row.mean.draw_ms += t.draw_ms;
        row.mean.present_ms += t.present_ms;
        row.blades += t.blades;
        if (serials.insert(view.shown().serial).second) stepSum_ms += view.shown().step_ms;
    }
    const double elapsed_s = secondsSince(start);
    row.fps = frames / std::max(elapsed_s, 1e-9);
    row.mean.wind_ms /= frames;
    row.mean.upload_ms /= frames;
    row.mean.draw_ms /= frames;
    row.mean.present_ms /= frames;
    row.blades /= frames;
    row.windStep_ms = stepSum_ms / double(serials.size());
    row.windUpdates_per_s = double(serials.size()) / std::max(elapsed_s, 1e-9);
    return row;
}

nlohmann::json rowJson(const ViewRow& r) {
    return {{"scene", r.name},
            {"vertices", r.vertices},
            {"build_ms", r.build_ms},
            {"frames", r.frames},
            {"fps", r.fps},
            {"frame_ms", r.mean.total_ms()},
            {"wind_ms", r.mean.wind_ms},
            {"upload_ms", r.mean.upload_ms},
            {"draw_ms", r.mean.draw_ms},
            {"present_ms", r.mean.present_ms},
            {"near_blades", r.blades},
            {"wind_step_ms", r.windStep_ms},
            {"wind_updates_per_s", r.windUpdates_per_s},
            {"meets_target", r.fps >= TARGET_FPS}};
}

}  // namespace

std::vector<std::string> benchViewSceneFiles(const std::vector<std::string>& paths) {
    return sceneFiles(paths);
}

int runBenchView(const BenchViewOptions& options) {
    if (options.motion) return runBenchViewMotion(options);
    if (!options.loader) throw std::invalid_argument("bench view: no scene loader");
    if (options.frames < 1)
        throw std::invalid_argument("bench view: --frames must be >= 1, got " +
                                    std::to_string(options.frames));
    if (options.shells < 0 || options.shells > render::MAX_SHELLS)
        throw std::invalid_argument("bench view: --shells must be 0.." +
                                    std::to_string(render::MAX_SHELLS) + ", got " +
                                    std::to_string(options.shells));
    const std::vector<std::string> files = sceneFiles(options.scenes);
    const int frames = options.quick ? 3 : options.frames;
    const int warmup = options.quick ? 1 : 5;

    if (options.beforeRenderer) options.beforeRenderer(files);
    std::unique_ptr<render::GlContext> context;
    if (options.window)
        context = render::GlfwWindow::open(options.width, options.height, "gale bench view");
    else
        context = render::createOsMesaContext(options.width, options.height);
    context->makeCurrent();
    const render::GlInfo info = render::queryGlInfo();

    // The floor before and after the scenes, so load that changes during the run hits both.
    const double floorBefore_ms =
        fillFloor_ms(options.width, options.height, options.shells, options.quick);
    std::vector<ViewRow> rows;
    Progress progress("scene", int(files.size()));
    for (size_t k = 0; k < files.size(); ++k) {
        const auto sceneStart = Clock::now();
        ViewBenchScene scene =
            options.loader(files[k], options.width, options.height, options.shells, options.quick);
        rows.push_back(measure(*context, scene, warmup, frames));
        progress.step(int(k) + 1, msSince(sceneStart));
    }
    progress.finish();
    const double floorAfter_ms =
        fillFloor_ms(options.width, options.height, options.shells, options.quick);
    const double floor_ms = 0.5 * (floorBefore_ms + floorAfter_ms);

    std::printf("gale view's frame loop (coupling/ViewPipeline), %d x %d, %d shells, %s\n",
                options.width, options.height, options.shells,
                options.window ? "in a GLFW window" : "headless (OSMesa)");
    std::printf("renderer: %s, %s; %d timed frames per scene after %d warm-up\n",
                info.renderer.c_str(), info.version.c_str(), frames, warmup);
    std::printf(
        "per frame on the render thread (ms): wind = ask the worker and take its snapshot, "
        "upload = group tables and uploads, draw = draw calls to glFinish (overlays included), "
        "present = the context's present; the wind step runs on its own thread\n\n");
    std::printf("%-28s  %8s  %7s  %7s  %8s  %7s  %7s  %7s  %8s  %9s  %8s  %7s  %s\n", "scene",
                "vertices", "blades", "fps", "frame ms", "wind", "upload", "draw", "present",
                "step ms", "wind Hz", "x floor", "<= 2x");
    char floorName[64];
    std::snprintf(floorName, sizeof floorName, "fill floor (%d layers)", options.shells + 1);
    std::printf("%-28s  %8s  %7s  %7.1f  %8.1f  %7s  %7s  %7.1f  %8s  %9s  %8s  %7.2f  %s\n",
                floorName, "", "", 1000.0 / floor_ms, floor_ms, "", "", floor_ms, "", "", "", 1.0,
                "");
    bool allMet = true, all30 = true;
    nlohmann::json jsonRows = nlohmann::json::array();
    for (const ViewRow& r : rows) {
        const double ratio = r.mean.total_ms() / floor_ms;
        const bool met = ratio <= TARGET_FLOOR_RATIO;
        allMet = allMet && met;
        all30 = all30 && r.fps >= TARGET_FPS;
        std::printf(
            "%-28s  %8zu  %7d  %7.1f  %8.1f  %7.2f  %7.2f  %7.1f  %8.2f  %9.1f  %8.1f  %7.2f  %s\n",
            r.name.c_str(), r.vertices, r.blades, r.fps, r.mean.total_ms(), r.mean.wind_ms,
            r.mean.upload_ms, r.mean.draw_ms, r.mean.present_ms, r.windStep_ms, r.windUpdates_per_s,
            ratio, met ? "met" : "MISSED");
        nlohmann::json j = rowJson(r);
        j["floor_ratio"] = ratio;
        j["meets_floor_target"] = met;
        jsonRows.push_back(j);
    }
    std::printf("\nfill floor: %.1f ms before the scenes, %.1f ms after\n", floorBefore_ms,
                floorAfter_ms);
    std::printf("target: every scene's frame time <= %.0fx the fill floor's: %s\n",
                TARGET_FLOOR_RATIO, allMet ? "met" : "MISSED");
    std::printf("every scene >= %.0f fps (not judged; rates move with the machine's load): %s\n",
                TARGET_FPS, all30 ? "yes" : "no");
    if (options.quick) std::printf("(quick run: %d frames per scene, not a measurement)\n", frames);

    // The JSON (written only with --json: finishViewBench).
    nlohmann::json doc;
    doc["benchmark"] = "view";
    doc["renderer"] = info.renderer;
    doc["width"] = options.width;
    doc["height"] = options.height;
    doc["shells"] = options.shells;
    doc["window"] = options.window;
    doc["frames_per_scene"] = frames;
    doc["warmup_frames"] = warmup;
    doc["quick"] = options.quick;
    doc["target_fps"] = TARGET_FPS;
    doc["fill_floor_ms"] = floor_ms;
    doc["fill_floor_before_ms"] = floorBefore_ms;
    doc["fill_floor_after_ms"] = floorAfter_ms;
    doc["target_floor_ratio"] = TARGET_FLOOR_RATIO;
    return finishViewBench(options, doc, jsonRows, allMet);
}

int finishViewBench(const BenchViewOptions& options, nlohmann::json& doc, nlohmann::json& rows,
                    bool allMet) {
    if (!options.jsonPath.empty()) {
        doc["target_met"] = allMet;
        doc["rows"] = std::move(rows);
        writeTextAtomic(options.jsonPath, doc.dump(2) + "\n");
        std::fprintf(stderr, "bench view: wrote %s\n", options.jsonPath.c_str());
    }
    if (options.quick) return EXIT_OK;
    return allMet ? EXIT_OK : EXIT_UNMET;
}

}  // namespace gale::app
