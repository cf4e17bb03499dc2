/// \file CommandsRender.cpp
/// `gale render`: scene -> heightfield -> mesh -> grass texture -> point-source wind -> OSMesa ->
/// shells -> PNG frames, with a run report.

#include <cerrno>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <system_error>
#include <vector>

#include "app/Cli.h"
#include "app/Commands.h"
#include "app/Version.h"
#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/io/ImageCheck.h"
#include "app/io/Interrupt.h"
#include "app/io/OutputFolder.h"
#include "app/io/OutputLock.h"
#include "app/io/ProcessMemory.h"
#include "app/io/Progress.h"
#include "app/io/Timing.h"
#include "app/scene/RenderMemory.h"
#include "app/scene/SceneBuilder.h"
#include "app/scene/SceneParser.h"
#include "coupling/FieldOverlayBuilder.h"
#include "render/Animation.h"
#include "render/FieldOverlay.h"
#include "render/GlContext.h"
#include "render/ImageIO.h"
#include "render/ShellRenderer.h"

namespace gale::app {
namespace {

namespace fs = std::filesystem;

/// Output we estimate at this many bytes per pixel or more; a run that cannot fit even this is
/// refused before it starts (real grass PNGs take more, so this refuses only hopeless runs).
constexpr double MIN_PNG_BYTES_PER_PIXEL = 0.5;

/// Bytes the GIF and contact sheet are allowed beside the frames, as a fraction of the frames'
/// total. Measured on the 64 x 48 test scene: 3 frames of 3.4 kB, a 6.6 kB GIF and a 7.8 kB
/// sheet; larger frames are downscaled for the GIF and the sheet has a fixed size, so one frame's
/// worth per frame is an upper bound.
constexpr double PREVIEW_FRACTION = 1.0;
/// Margin on the measured frame size: later frames of a run compress differently.
constexpr double FRAME_SIZE_MARGIN = 1.25;

/// framePath with the extension of output.format (".png" or ".exr").
std::string framePathAs(const std::string& folder, const std::string& prefix, int k,
                        const std::string& format);

/// After the first frame: its measured size times the frames still to come (with margin, and
/// room for the previews) must fit in the output folder's free space. Throws InputError.
void checkRoomForFrames(const OutputSection& out, const std::string& where, double frameBytes) {
    std::error_code ec;
    const fs::space_info space = fs::space(out.folder, ec);
    if (ec) return;
    const double rest = frameBytes * FRAME_SIZE_MARGIN * (out.frames - 1);
    const double previews =
        (out.gif || out.contactSheet) ? frameBytes * out.frames * PREVIEW_FRACTION : 0.0;
    const double need = rest + previews;
    if (need > static_cast<double>(space.available))
        throw InputError(where + ": '" + out.folder + "' has " +
                         formatBytes(static_cast<double>(space.available)) + " free but the " +
                         std::to_string(out.frames - 1) + " frames still to render need about " +
                         formatBytes(need) + " (the first frame took " + formatBytes(frameBytes) +
                         "); nothing was written");
}

/// framePath with the extension of output.format (".png" or ".exr").
std::string framePathAs(const std::string& folder, const std::string& prefix, int k,
                        const std::string& format) {
    return fs::path(framePath(folder, prefix, k)).replace_extension("." + format).string();
}

std::string utcNow() {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&now, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buf;
}

}  // namespace

std::vector<RunPath> sceneInputs(const Scene& scene) {
    std::vector<RunPath> inputs{
        {scene.path, "the scene"},
        {scene.terrain.imagePath, scene.where("terrain.image") + " (the heightmap)"},
        {scene.terrain.demPath, scene.where("terrain.dem") + " (the DEM)"},
        {scene.grass.texturePath, scene.where("grass.texture") + " (the grass texture)"},
        {scene.grass.densityMapPath, scene.where("grass.density_map") + " (the density map)"}};
    // GDAL reads a raster's world file, .prj and .aux.xml beside it: inputs too.
    for (const auto& [path, key] : {std::pair{scene.terrain.imagePath, "terrain.image"},
                                    std::pair{scene.terrain.demPath, "terrain.dem"}}) {
        if (path.empty()) continue;
        std::error_code ec;
        for (const std::string& side : rasterSidecars(path))
            if (fs::exists(side, ec))
                inputs.push_back({side, scene.where(key) + " (beside it, '" +
                                            fs::path(side).filename().string() + "')"});
    }
    return inputs;
}

namespace {}  // namespace

int runRender(const SceneRunOptions& options) {
    const auto runStart = Clock::now();
    InterruptScope interrupt("while reading and building the scene: nothing written");
    Scene scene = loadScene(options);
    if (options.frames && scene.output.duration_s > 0.0) {
        // A preview of N frames samples the scene's whole duration (docs/scene-format.md), so a
        // contact sheet of `--frames 6` shows the gust the full run shows, not its first quarter
        // second.
        scene.output.fps = double(scene.output.frames) / scene.output.duration_s;
    }
    const OutputSection& out = scene.output;
    const std::string folderWhere = outputFolderSource(scene, options);
    const OutputFolderStatus folder =
        checkOutputFolder(out.folder, folderWhere, out.prefix, out.frames);
    const double minBytes =
        static_cast<double>(out.width) * out.height * out.frames * MIN_PNG_BYTES_PER_PIXEL;
    if (folder.freeBytes >= 0 && minBytes > folder.freeBytes)
        throw InputError(folderWhere + ": '" + out.folder + "' has " +
                         formatBytes(folder.freeBytes) + " free but " + std::to_string(out.frames) +
                         " frames of " + std::to_string(out.width) + " x " +
                         std::to_string(out.height) + " need at least " + formatBytes(minBytes));
    const std::string reportPath = (fs::path(out.folder) / (out.prefix + "_report.json")).string();
    render::AnimationOptions animation;
    if (out.contactSheet) animation.sheetPath = out.folder + "/" + out.prefix + "_sheet.png";
    if (out.gif) animation.gifPath = out.folder + "/" + out.prefix + ".gif";
    animation.fps = out.fps;
    {
        std::vector<RunPath> outputs;
        for (int k = 0; k < out.frames; ++k)
            outputs.push_back(
                {framePathAs(out.folder, out.prefix, k, out.format), folderWhere + " (a frame)"});
        outputs.push_back({reportPath, folderWhere + " (the report)"});
        outputs.push_back({animation.sheetPath, folderWhere + " (the contact sheet)"});
        outputs.push_back({animation.gifPath, folderWhere + " (the GIF)"});
        refuseAliases(sceneInputs(scene), outputs);
    }
    for (const std::string& note : scene.notes)
        std::fprintf(stderr, "gale: note: %s\n", note.c_str());

    BuildOptions buildOptions;
    buildOptions.progress = [](const std::string& text) {
        std::fprintf(stderr, "gale: %s\n", text.c_str());
    };
    BuiltScene built = buildScene(scene, buildOptions);
    for (const std::string& warning : built.warnings)
        std::fprintf(stderr, "gale: warning: %s\n", warning.c_str());
    if (built.solve) {
        // The composition's own summary (app/scene/SceneField.h): what ran and how it ended.
        std::fprintf(stderr, "gale: steady wind: %s\n", built.fieldSummary.c_str());
        if (!built.solve->converged)
            std::fprintf(stderr, "gale: %s\n", built.solve->message.c_str());
    }

    // GL: a failure here is ours (or the machine's), not the user's: exit 1.
    std::unique_ptr<render::GlContext> context = render::createOsMesaContext(out.width, out.height);
    render::ShellRenderer renderer(*context);
    renderer.setTerrain(built.mesh);
    renderer.setGrass(scene.grass.params, built.texture);
    renderer.setDensityMap(built.densityMap);
    renderer.setLighting(scene.lighting);
    const std::string glDescription = context->description();
    std::unique_ptr<render::FieldOverlay> overlay;
    if (scene.overlay.any()) overlay = std::make_unique<render::FieldOverlay>(*context);

    // Everything is validated: only now does anything appear on disk.
    const bool createdFolder = prepareOutputFolder(out.folder, folderWhere);
    std::optional<OutputLock> lock;
    try {
        lock.emplace(out.folder, folderWhere);
    } catch (...) {
        // Another run may have taken the lock and begun writing into the folder this run
        // created: remove it only if it is still empty, and keep the lock's message.
        std::error_code ec;
        if (createdFolder) fs::remove(out.folder, ec);
        throw;
    }
    removeStaleTemporaries(out.folder);
    if (!folder.staleFrames.empty())
        std::fprintf(stderr,
                     "gale: note: %s holds %zu older frames beyond this run's last (e.g. %s); "
                     "they are left as they are\n",
                     out.folder.c_str(), folder.staleFrames.size(),
                     folder.staleFrames.front().c_str());

    // Every output goes to its temporary and is moved into place only when the run is done
    // (or interrupted, for what is complete): a failed run leaves the earlier outputs alone.
    StagedFiles staged;
    // On a failure: the temporaries go, the lock is released, and a folder this run created is
    // removed again if nothing else is in it.
    const auto abandon = [&] {
        staged.discard();
        lock.reset();
        if (createdFolder) {
            std::error_code ec;
            fs::remove(out.folder, ec);  // only removes it if empty
        }
    };
    std::vector<std::string> written;  // frames
    std::vector<std::string> extras;   // contact sheet and GIF
    std::vector<double> frame_ms, drawCpu_ms, drawGpu_ms;
    render::GrassWind wind;
    render::Image image;
    std::fprintf(stderr, "gale: rendering %d frames of %d x %d (%s)\n", out.frames, out.width,
                 out.height, glDescription.c_str());
    const auto loopStart = Clock::now();
    int done = 0;
    render::AnimationOptions stagedAnimation = animation;
    if (!animation.sheetPath.empty()) stagedAnimation.sheetPath = staged.add(animation.sheetPath);
    if (!animation.gifPath.empty()) stagedAnimation.gifPath = staged.add(animation.gifPath);
    try {
        interrupt.defer();
        render::AnimationWriter animationWriter(stagedAnimation, out.frames);
        Progress progress("frame", out.frames);
        coupling::OverlayScaleKeeper overlayScale;  // the automatic colour scale only grows
        for (int k = 0; k < out.frames && !interruptSignal(); ++k) {
            const auto frameStart = Clock::now();
            const double t_s = out.startTime_s + k / out.fps;
            built.wind->update(t_s, wind);
            const render::FrameStats stats = renderer.draw(built.camera, wind);
            if (overlay) {
                const render::FieldOverlayData data = coupling::buildOverlay(
                    *built.wind, wind, built.mesh, overlayScale.frame(scene.overlay),
                    scene.grass.params.height_m);
                overlayScale.seen(data);
                overlay->draw(built.camera, data);
            }
            context->readPixels(image);
            const std::string path = framePathAs(out.folder, out.prefix, k, out.format);
            const std::string tmp = staged.add(path);
            errno = 0;
            try {
                render::writeImageAtomic(image, tmp);
            } catch (const std::runtime_error& e) {
                throw std::runtime_error(path + ": cannot write: " + e.what());
            }
            verifyImageFile(tmp, path, image.width, image.height, errno);
            const double frameBytes = staged.seal(path);
            if (k == 0) checkRoomForFrames(out, folderWhere, frameBytes);
            written.push_back(path);
            animationWriter.addFrame(image, k);
            drawCpu_ms.push_back(stats.cpu_ms);
            drawGpu_ms.push_back(stats.gpu_ms);
            frame_ms.push_back(msSince(frameStart));
            ++done;
            progress.step(done, frame_ms.back());
        }
        // An interrupted run still gets its sheet and GIF, of the frames it finished.
        errno = 0;
        animationWriter.finish();
        const int previewErrno = errno;
        if (done > 0 && !animation.sheetPath.empty()) {
            verifyImageFile(stagedAnimation.sheetPath, animation.sheetPath, -1, -1, previewErrno);
            staged.seal(animation.sheetPath);
            extras.push_back(animation.sheetPath);
        }
        if (done > 0 && !animation.gifPath.empty()) {
            verifyImageFile(stagedAnimation.gifPath, animation.gifPath, -1, -1, previewErrno);
            staged.seal(animation.gifPath);
            extras.push_back(animation.gifPath);
        }
    } catch (...) {
        abandon();
        throw;
    }
    const double loop_s = msSince(loopStart) / 1000.0;

    nlohmann::json report;
    report["gale_version"] = GALE_VERSION;
    report["scene"] = scene.path;
    report["scene_name"] = scene.name;
    report["finished_utc"] = utcNow();
    report["interrupted"] = done < out.frames;
    report["frames"] = done;
    report["frames_requested"] = out.frames;
    if (built.solve) {
        const sim::SolveReport& r = *built.solve;
        report["wind_solve"] = {{"domain", built.domainSummary},
                                {"converged", r.converged},
                                {"iterations", r.iterations},
                                {"relative_residual", r.relativeResidual},
                                {"max_divergence_scaled", r.maxDivergenceScaled},
                                {"wall_ms", built.solve_ms},
                                {"what_ran", built.fieldPlan},
                                {"summary", built.fieldSummary}};
    }
    report["width"] = out.width;
    report["height"] = out.height;
    report["fps"] = out.fps;
    report["start_time_s"] = out.startTime_s;
    report["folder"] = out.folder;
    std::vector<std::string> names;
    for (const std::string& f : written) names.push_back(fs::path(f).filename().string());
    report["files"] = names;
    std::vector<std::string> extraNames;
    for (const std::string& f : extras) extraNames.push_back(fs::path(f).filename().string());
    report["previews"] = extraNames;
    report["gl"] = glDescription;
    report["wind"] = built.wind->describe();
    report["terrain_samples"] = {built.heightfield.nx, built.heightfield.ny};
    report["mesh_vertices"] = built.mesh.wsPosition_m.size();
    report["memory_estimate_bytes"] = estimateRenderMemory_bytes(scene, built);
    report["peak_resident_bytes"] = peakResidentBytes();  // beside the estimate
    report["shells"] = scene.grass.params.shells;
    report["build_ms"] = built.build_ms;
    report["frame_ms"] = frame_ms;
    report["draw_cpu_ms"] = drawCpu_ms;
    report["draw_gpu_ms"] = drawGpu_ms;
    report["render_s"] = loop_s;
    report["total_s"] = msSince(runStart) / 1000.0;
    // A signal after the last frame stops nothing: the report is a complete run's.
    if (interruptSignal() && done < out.frames) report["stopped_by"] = interruptSignalName();
    try {
        // The report last: frames without their report are never moved into place.
        writeStagedText(staged, reportPath, report.dump(2) + "\n");
        staged.commit();
    } catch (...) {
        abandon();
        throw;
    }

    std::string shown = out.folder;
    if (shown.back() != '/') shown += '/';
    const double mean_ms = done > 0 ? loop_s * 1000.0 / done : 0.0;
    if (done < out.frames) {
        // Where it stopped: the last complete frame (frames are written atomically).
        const std::string last = done > 0 ? "after " + fs::path(written.back()).filename().string()
                                          : std::string("before the first frame");
        std::printf("interrupted (%s) %s: wrote %d of %d frames to %s (report %s)\n",
                    interruptSignalName(), last.c_str(), done, out.frames, shown.c_str(),
                    reportPath.c_str());
        return interruptExitCode();
    }
    std::printf("wrote %d frames to %s (%s .. %s) in %s, %.0f ms/frame; report %s\n", done,
                shown.c_str(), fs::path(written.front()).filename().c_str(),
                fs::path(written.back()).filename().c_str(),
                Progress::formatDuration(loop_s).c_str(), mean_ms, reportPath.c_str());
    for (const std::string& f : extras) std::printf("preview %s\n", f.c_str());
    if (interruptSignal()) return reportInterruptedWhileWriting(shown, reportPath);
    return EXIT_OK;
}

void addRenderVerb(CLI::App& app, VerbTable& verbs) {
    auto options = std::make_shared<SceneRunOptions>();
    CLI::App* verb = app.add_subcommand(
        "render", "Render a scene headless to PNG frames, with a JSON run report");
    addSceneOptions(verb, *options);
    verb->footer(std::string("\nFrames go to FOLDER/<prefix>_0000.png ..., the report to "
                             "FOLDER/<prefix>_report.json.") +
                 EXIT_CODES_FOOTER);
    verbs.add(verb, [options] { return runRender(*options); });
}

}  // namespace gale::app
