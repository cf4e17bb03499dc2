#pragma once
/// \file Commands.h
/// The verbs of the gale program. Each returns the process exit code (0 ok) and throws
/// InputError for bad input (exit 2) and other exceptions for internal failures (exit 1); only
/// main catches.

#include <optional>
#include <string>
#include <vector>

#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/scene/LoadScene.h"
#include "app/scene/Scene.h"

namespace gale::app {

/// `gale solve`: the scene's steady wind (docs/design.md 4.1) to a .vdb file and a JSON report.
struct SolveVerbOptions {
    std::string scenePath;
    std::string vdbPath;     ///< -o; empty: <output.folder>/<prefix>_wind.vdb
    std::string reportPath;  ///< --report; empty: the .vdb path with .json
    /// --grid-height-m: also write the wind this high above the ground (metres) as
    /// <stem>_<H>m.tif (speed and from-direction bands) and <stem>_<H>m.asc (speed), steady only.
    std::vector<double> gridHeights_m;
    /// --houdini: also write <stem>_houdini.NNNN.vdb (grids vel and surface, y-up), NNNN the
    /// scene's frame number at each output time (1-based, output.fps).
    bool houdini = false;
};
/// Returns EXIT_OK when the solve converged, EXIT_UNMET when it did not (files still written, the
/// report says so).
int runSolveVerb(const SolveVerbOptions& options);

/// `gale check SCENE`: validates, builds the CPU side, prints what the run would build and what it
/// leaves out, to stdout.
int runCheck(const SceneRunOptions& options);

/// `gale render SCENE`: renders the frames headless into the output folder, with a run report.
int runRender(const SceneRunOptions& options);

/// The files a scene reads (the scene, its heightmap or DEM and the world, .prj and .aux.xml files
/// GDAL reads beside it, its grass texture and density map; empty paths for those it does not
/// have), with their roles (the key each came from) for refuseAliases messages.
std::vector<RunPath> sceneInputs(const Scene& scene);

/// `gale view SCENE`: the scene in a window (docs/cli.md).
struct ViewOptions {
    std::string scenePath;
    std::optional<int> frames;  ///< render this many frames at exact times, then exit (tests)
    std::optional<int> width;   ///< window size; default output.width / output.height
    std::optional<int> height;
    std::string screenshotPath;  ///< save the last frame here (without the heads-up line)
    /// Key presses to replay, one per frame from the first ('>' right arrow, ' ' space, '.' none,
    /// letters and + - [ ] as on the keyboard): for tests and demos without a person at the keys.
    std::string keys;
    /// Mouse actions and live-wind keys to replay: "FRAME:ACTION:X,Y[,X2,Y2];..."
    /// (app/ViewInput.h).
    std::string input;
};
/// The view's (and `gale bench view`'s) change to an unsteady scene: an adaptive time step of
/// at most one output frame (1 / output.fps), so that wind dropped into the flow shows in the
/// grass at the next frame instead of after a long step (calm air steps up to max_dt_s). A fixed
/// unsteady.dt_s is kept. The projection stops at unsteady.live_tolerance instead of
/// unsteady.tolerance, or after unsteady.live_iterations. Other scenes are left as they are.
void limitUnsteadyStepToAFrame(Scene& scene);
/// The CPU policy when the wind is stepped live beside the renderer (docs/unsteady.md, "Two
/// jobs on two cores"): llvmpipe's rasteriser threads take half the cores (LP_NUM_THREADS, at
/// least 1), the wind's worker thread and its TBB threads keep theirs. With every core given to
/// llvmpipe as well, the two jobs thrash: measured on 2 cores, the whirlwind meadow's wind ran
/// at 9.5 Hz beside 27 fps, and with the rasteriser on one core at 21 Hz beside 22.5 fps. A
/// user's own LP_NUM_THREADS wins. Must run before the first GL context is made; says what it
/// did on stderr.
void shareCoresWithLiveWind();

/// Opens the window, runs until closed (or --frames), returns 0. Throws std::runtime_error
/// "no display: ..." when there is no display (exit 1).
int runView(const ViewOptions& options);

struct BladeOptions {
    int shells = 16;
    double intensity = 0.5;
    double stiffness = 1.0;
    double height_m = 0.5;
    std::string svgPath;  ///< empty: no SVG
};

/// `gale blade`: the bend's offsets of shells 0..N as CSV (i,n_m,w_m) on stdout, and optionally an
/// SVG drawing of the blade.
int runBlade(const BladeOptions& options);

/// The SVG drawing of one bent blade (written by `gale blade --svg`).
std::string bladeSvg(const BladeOptions& options);

struct TerrainExportOptions {
    std::string scenePath;
    std::string imagePath;  ///< a .png file
};

/// `gale terrain SCENE -o FILE.png`: the scene's heightfield as a 16-bit grey PNG.
int runTerrainExport(const TerrainExportOptions& options);

}  // namespace gale::app
