#pragma once
/// \file Scene.h
/// A validated scene: everything a run needs, in SI units (metres, seconds, m/s). Parsed from TOML
/// by parseSceneFile (SceneParser.h); the schema, with every key and its unit, is
/// docs/scene-format.md.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/scene/Dem.h"
#include "coupling/FieldOverlayBuilder.h"
#include "coupling/FieldWind.h"
#include "coupling/GustCurve.h"
#include "coupling/PointSourceWind.h"
#include "render/GrassInput.h"
#include "render/GrassTexture.h"
#include "sim/AirDomain.h"
#include "sim/AmbientWind.h"
#include "sim/Heightfield.h"
#include "sim/PoissonSolver.h"
#include "sim/SteadyWind.h"
#include "sim/UnsteadyWind.h"

namespace gale::app {

struct TerrainSection {
    sim::TerrainSpec spec;  ///< procedural kinds
    // kind == Heightmap:
    std::string imagePath;        ///< resolved against the scene file's folder
    double metresPerPixel = 1.0;  ///< horizontal spacing of the image's pixels
    double heightScale_m = 10.0;  ///< height of a full-scale pixel (white / 1.0)
    double heightOffset_m = 0.0;  ///< height of a zero pixel
    int meshStride = 1;           ///< render mesh takes every meshStride-th sample
    // kind == "dem" (spec.kind is then Heightmap: loaded, not procedural; Dem.h):
    bool dem = false;                ///< terrain from a georeferenced raster through GDAL
    std::string demPath;             ///< resolved against the scene file's folder
    std::optional<CropWindow> crop;  ///< crop_m, in the DEM's coordinates
};

struct GrassSection {
    render::GrassParams params;
    std::string texturePath;     ///< empty: generate from `generated`
    std::string densityMapPath;  ///< grass.density_map, resolved; empty: density 1 everywhere
    render::GrassTextureSpec generated;
};

/// point_source: the paper's heuristic (Bakay et al. 2002). solved: the steady mass-consistent
/// field over the terrain (sim/SteadyWind), optionally with travelling gusts
/// (coupling/SteadyGustWind). unsteady: the steady field as initial state and mean flow, stepped in
/// time with gusts and whirlwinds ([unsteady], [[wind.gusts]], [[wind.whirlwinds]];
/// sim/UnsteadyWind, docs/unsteady.md).
enum class WindKind { PointSource, Solved, Unsteady };

/// wind.kind as written in a scene: "point_source", "solved", "unsteady".
inline const char* windKindName(WindKind kind) {
    switch (kind) {
        case WindKind::Solved:
            return "solved";
        case WindKind::Unsteady:
            return "unsteady";
        default:
            return "point_source";
    }
}

/// [wind.gust] without keys: the attack-decay intensity curve (coupling::GustCurve::attackDecay).
struct GustShape {
    double period_s = 4.0;        ///< the curve repeats every period, seconds
    double base = 0.1;            ///< calm intensity
    double peak = 0.8;            ///< gust intensity
    double attackFraction = 0.1;  ///< attack_s defaults to this fraction of period_s
    double decayFraction = 0.4;   ///< decay_s defaults to this fraction of period_s
};

struct WindSection {
    WindKind kind = WindKind::PointSource;
    coupling::PointSourceSpec pointSource;
    std::optional<coupling::GustCurve> curve;  ///< set after parsing
    std::string curveDescription;              ///< how the curve was given, for `gale check`
    bool autoSource = true;  ///< source_m not given: placed from the terrain when it is built

    // kind == Solved (the ambient wind is also what `gale solve` solves for, whatever the kind):
    sim::AmbientWind ambient;
    coupling::FieldWindSpec response;  ///< blade response and, without gusts, grouping
    /// The field is sampled this high above the ground, metres; unset: at the grass height.
    std::optional<double> sampleHeight_m;
    bool gusts = false;     ///< [wind.gust] given: travelling gusts over the steady field
    int arrivalBands = 16;  ///< gust groups: arrival-time bands ...
    int levels = 4;         ///< ... times steady-intensity levels
    GustShape gustShape;    ///< [wind.gust]'s curve when it gives no keys
};

/// [solver]: the air domain and the elliptic solve (docs/solver.md).
struct SolverSection {
    sim::DomainSpec domain;
    sim::MassConsistentWeights weights;
    sim::SolverSettings settings;
    sim::SteadyModel model = sim::SteadyModel::MassConsistent;  ///< [solver] model
    sim::MomentumSettings momentum;  ///< model = "momentum" (sim/MomentumWind.h)
};

/// [unsteady] with [[wind.gusts]] and [[wind.whirlwinds]] (docs/unsteady.md). Read for every
/// scene, used by wind.kind = "unsteady" only.
struct UnsteadySection {
    sim::UnsteadySettings settings;  ///< time step, advection, viscosity, gusts, whirlwinds
    double duration_s = 10.0;        ///< `gale solve`: simulated time, seconds
    double outputEvery_s = 1.0;      ///< `gale solve`: a .vdb every this many seconds
    /// The projection's tolerance when the wind runs live (gale view, bench unsteady --live):
    /// unsteady.live_tolerance. The grass reads the velocity near the ground, where a net flux
    /// of 1e-3 U through a cell is a thousandth of the wind (docs/unsteady.md, "The projection's
    /// tolerance"), and each step projects again, so it does not build up; `gale solve` writes
    /// fields for analysis and keeps unsteady.tolerance.
    double liveTolerance = 1e-3;
    /// The projection's budget when the wind runs live: at most this many MGPCG iterations (one
    /// V-cycle each) a step, unsteady.live_iterations; a step that reaches it before the
    /// tolerance keeps its residual, which the view's heads-up line and the bench report, and the
    /// next step starts from it (docs/unsteady.md, "The step's start, the projection's budget").
    int liveIterations = 3;
    int64_t maxFiles = 10000;    ///< refuse runs planning more .vdb files (docs/reliability.md)
    int64_t maxSteps = 1000000;  ///< refuse runs planning more time steps
    /// Refuse runs whose .vdb files would total more (estimated), bytes; unsteady.max_output_gib.
    double maxOutputBytes = 1024.0 * 1024 * 1024 * 1024;
};

struct OutputSection {
    int width = 640;
    int height = 480;
    int frames = 48;
    double fps = 24.0;
    double startTime_s = 0.0;
    /// frames / fps as the scene file gives them, seconds: the scene's duration, which `gale
    /// render --frames N` previews whole (its frames stand duration_s / N apart). Set by loadScene.
    double duration_s = 0.0;
    std::string folder = "out/scene";  ///< resolved against the current directory
    std::string prefix = "frame";      ///< frame files are <prefix>_0000.png ...
    bool contactSheet = true;          ///< <prefix>_sheet.png: a grid of evenly spaced frames
    bool gif = true;                   ///< <prefix>.gif: the frames as an animated GIF
    std::string format = "png";        ///< frame files: "png" (8-bit) or "exr" (half float, linear)
};

struct Scene {
    std::string path;         ///< the file it came from
    std::string name;         ///< the file's stem, for reports
    std::string description;  ///< the optional top-level `description`
    TerrainSection terrain;
    GrassSection grass;
    WindSection wind;
    SolverSection solver;
    UnsteadySection unsteady;
    render::Lighting lighting;
    /// No [[lighting.light]] given: `lighting` holds the default sun (and sky ambient unless
    /// lighting.ambient was given), SceneParser.h.
    bool defaultSun = false;
    render::Camera camera;
    OutputSection output;
    coupling::OverlaySpec overlay;  ///< [overlay]: views of the field drawn over the grass

    bool autoCameraPosition = true;  ///< camera.position_m not given: a 3/4 view of the terrain
    bool autoCameraTarget = true;    ///< camera.target_m not given: the terrain's centre
    bool autoCameraFar = true;       ///< camera.far_m not given: it follows the terrain's extent
    /// Line of each key as written ("terrain.image" -> 7), for messages after parsing.
    std::map<std::string, int> keyLines;
    /// Keys given but not used by this scene (e.g. octaves for a gaussian_hill), one line each.
    std::vector<std::string> notes;

    /// "FILE:LINE: key" for messages about `key` (a dotted scene key); "FILE: key" if the key was
    /// not written in the file (its default is in use).
    std::string where(const std::string& key) const {
        auto it = keyLines.find(key);
        if (it == keyLines.end() || it->second <= 0) return path + ": " + key;
        return path + ":" + std::to_string(it->second) + ": " + key;
    }
};

}  // namespace gale::app
