#pragma once
/// \file BenchView.h
/// `gale bench view [SCENE|FOLDER]...`: the frame rate of each scene through the window's own
/// per-frame loop (coupling/ViewPipeline.h: wind worker, shell renderer, overlays, present),
/// headless through OSMesa or in a GLFW window, with each frame split into wind, upload, draw and
/// present, against the target of 30 fps at 640 x 480 with 17 shells.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "coupling/FieldOverlayBuilder.h"
#include "coupling/ViewPipeline.h"
#include "render/GrassInput.h"

namespace gale::app {

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
    ViewSceneLoader loader;  ///< required
    /// Called with the scene files before the renderer starts (optional): where the CPU
    /// policy of live wind beside the renderer is applied (shareCoresWithLiveWind).
    std::function<void(const std::vector<std::string>& files)> beforeRenderer;
};

/// Loads every scene through options.loader, runs its frames through the view's pipeline, prints
/// the table to stdout (progress to stderr) and writes the JSON. Returns EXIT_OK, or EXIT_UNMET
/// when a full run leaves a scene under 30 fps (a quick run is never judged). Throws
/// std::invalid_argument on bad options or when a path holds no scene, and what the loader and the
/// renderer throw.
int runBenchView(const BenchViewOptions& options);

}  // namespace gale::app
