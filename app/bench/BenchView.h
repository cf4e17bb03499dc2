#pragma once
/// \file BenchView.h
/// `gale bench view [SCENE|FOLDER]...`: the frame rate of each scene through the window's own
/// per-frame loop (coupling/ViewPipeline.h: wind worker, shell renderer, overlays, present),
/// headless through OSMesa or in a GLFW window, with each frame split into wind, upload, draw and
/// present, against the fill floor measured in the same run (shells + 1 full-screen,
/// nearest-sampled, alpha-tested layers: render::measureShellFill): every scene's frame time at
/// most 2x the floor's. 30 fps at 640 x 480 is reported beside it.

#include <functional>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "coupling/FieldOverlayBuilder.h"
#include "coupling/ViewPipeline.h"
#include "render/GrassInput.h"

namespace gale::app {

/// Ground regions whose grass motion `gale bench view --motion` compares (issue 26): over the
/// frames, the mean per-pixel temporal standard deviation of luminance where the wind is agitated
/// (a ridge's crest, a whirlwind's core) against where it is calm (the lee, the meadow around).
/// Both come from the scene's own geometry.
struct MotionRegions {
    std::string agitated;  ///< names for the table, e.g. "crest"
    std::string calm;      ///< e.g. "lee"
    /// Called once per frame after the wind source's update to t_s (seconds), before it is
    /// drawn: the source's current field may be read (e.g. to track a moving core).
    std::function<void(double t_s)> onFrame;
    /// After all frames: a ground point (plan, world metres) is +1 agitated, -1 calm, 0 neither.
    std::function<int(double wsX_m, double wsY_m)> classify;
};

/// One scene, built on the CPU and ready for the view's pipeline (what `gale view` draws).
struct ViewBenchScene {
    std::string name;  ///< the scene file's stem
    /// Points into `owner`, which keeps the built scene (mesh, texture, wind source) alive and in
    /// place: wind sources keep references to the mesh they were built over.
    coupling::ViewInputs inputs;
    std::shared_ptr<void> owner;
    render::Camera camera;          ///< the view's starting camera
    coupling::OverlaySpec overlay;  ///< the scene's own overlays, drawn as `gale view` does
    double startTime_s = 0.0;       ///< output.start_time_s
    double fps = 30.0;              ///< output.fps: frame i shows sim time start + i / fps
    double build_ms = 0.0;          ///< wall time of building it (solves included)
    /// The scene's motion regions, when its geometry has them (a ridge under a solved wind,
    /// whirlwinds); empty function members otherwise.
    MotionRegions motion;
};

/// Builds the scene at `path` for a width x height view with `shells` shells; `quick` (a smoke
/// run) may cut a long solve short (the frames are then not the scene's converged wind). Throws
/// InputError (bad scene) or std::runtime_error as building the scene does.
using ViewSceneLoader = std::function<ViewBenchScene(const std::string& path, int width, int height,
                                                     int shells, bool quick)>;

struct BenchViewOptions {
    /// Scene files, or folders whose *.toml files are all taken (sorted by name).
    std::vector<std::string> scenes = {"examples"};
    int width = 640;       ///< pixels, 1..16384
    int height = 480;      ///< pixels, 1..16384
    int shells = 17;       ///< every scene drawn with this many shells, 0..render::MAX_SHELLS
    int frames = 120;      ///< timed frames per scene, >= 1
    bool quick = false;    ///< 3 timed frames after 1 warm-up: a smoke run, not a measurement
    bool window = false;   ///< draw into a GLFW window (needs a display) instead of headless OSMesa
    std::string jsonPath;  ///< if set, the table is also written there as JSON (atomically)
    /// Measure the wind's readability instead of the frame rate: for every scene with motion
    /// regions, motionFrames frames at its fps from 4 s after its start (runBenchViewMotion).
    bool motion = false;
    int motionFrames = 24;   ///< >= 2
    ViewSceneLoader loader;  ///< required
    /// Called with the scene files before the renderer starts (optional): where the CPU
    /// policy of live wind beside the renderer is applied (shareCoresWithLiveWind).
    std::function<void(const std::vector<std::string>& files)> beforeRenderer;
};

/// The end both view benches share: with options.jsonPath, `doc` gets the verdict and the rows
/// and is written there (atomically); returns EXIT_OK, or EXIT_UNMET when a full run missed its
/// target (a quick run is never judged).
int finishViewBench(const BenchViewOptions& options, nlohmann::json& doc, nlohmann::json& rows,
                    bool allMet);

/// Loads every scene through options.loader, runs its frames through the view's pipeline, prints
/// the table to stdout (progress to stderr) and writes the JSON. Returns EXIT_OK, or EXIT_UNMET
/// when a full run leaves a scene's frame time over 2x the fill floor's (a quick run is never
/// judged). Throws
/// std::invalid_argument on bad options or when a path holds no scene, and what the loader and the
/// renderer throw.
int runBenchView(const BenchViewOptions& options);

/// Scene files: each path as given, or every *.toml in a folder, sorted by name. Throws
/// std::invalid_argument when a path holds no scene.
std::vector<std::string> benchViewSceneFiles(const std::vector<std::string>& paths);

/// `gale bench view --motion` (app/bench/BenchViewMotion.cpp): for each scene with motion regions,
/// draws options.motionFrames frames with the scene's wind (source updated, then drawn, in one
/// thread; the first 4 s after the scene's start only update the wind, so the blades' response
/// has settled), the per-pixel temporal standard deviation of luminance over them, and its mean
/// over the pixels whose ground (mesh vertices projected into the frame) is agitated and calm;
/// prints the table and the ratio. Returns EXIT_OK, or EXIT_UNMET when a full run gives a ratio
/// under 2 (a quick run is never judged). Throws as runBenchView.
int runBenchViewMotion(const BenchViewOptions& options);

}  // namespace gale::app
