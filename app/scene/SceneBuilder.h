#pragma once
/// \file SceneBuilder.h
/// Everything a run builds on the CPU from a validated Scene: the heightfield, the render mesh,
/// the grass texture with its MIP chain, the wind source, and the camera with its defaults
/// resolved. `gale check` builds this to report on it; `gale render` then adds GL.

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "app/scene/Scene.h"
#include "coupling/WindSource.h"
#include "render/DensityMap.h"
#include "render/GrassInput.h"
#include "render/GrassTexture.h"
#include "sim/AirDomain.h"
#include "sim/Heightfield.h"
#include "sim/PoissonSolver.h"
#include "sim/UnsteadyWind.h"
#include "sim/WindField.h"

namespace gale::app {

/// Turns a library's std::invalid_argument into the scene's error (SceneError, exit 2): a
/// gale::ParameterError names its own scene key, and the message points at that key's FILE:LINE,
/// at its enclosing key's ("terrain.size_m[0]" on size_m's line), or, when the scene left the
/// key out, at its section's line with "(got VALUE, the default)"; any other is placed at
/// `fallbackKey` (the section the failing call was built from).
[[noreturn]] void rethrowAsSceneError(const Scene& scene, const std::string& fallbackKey,
                                      const std::invalid_argument& error);

struct BuiltScene {
    sim::Heightfield heightfield;  ///< in the local frame (Dem.h) for a DEM
    Georeference georef;  ///< the DEM's coordinate system and local offset; empty otherwise
    render::TerrainMesh mesh;
    render::GrassTexture texture;
    render::DensityMap densityMap;  ///< grass.density_map over the mesh's plan; width 0: none
    std::unique_ptr<coupling::WindSource> wind;
    render::Camera camera;           ///< the scene's camera with defaults resolved
    glm::vec3 wsWindSource_m{0.0f};  ///< point source actually used
    double build_ms = 0.0;           ///< wall time of buildScene
    /// Settings that would give silently wrong output (an explicit far plane before the whole
    /// terrain), one line each starting FILE:LINE: key; check and render print them.
    std::vector<std::string> warnings;

    // wind.kind = "solved":
    std::string domainSummary;              ///< cells, air cells, memory of the air domain
    double domainEstimate_bytes = 0.0;      ///< the air domain's run estimate (its baseline incl.)
    double domainVdbFile_bytes = 0.0;       ///< one .vdb of its field, at most (MemoryEstimate.h)
    std::optional<sim::SolveReport> solve;  ///< the steady solve (absent when not solved)
    /// What the field's composition runs (describeSceneField, app/scene/SceneField.h) and, when
    /// it ran, what it did (SceneField::summary).
    std::vector<std::string> fieldPlan;
    std::string fieldSummary;
    double solve_ms = 0.0;  ///< domain + solve + sampling wall time
};

struct BuildOptions {
    /// false: `gale check` builds the domain and reports it but does not solve; the wind source is
    /// then left empty for a solved scene.
    bool solveWind = true;
    /// Progress lines for long steps (the solve), to stderr; nullptr: quiet.
    void (*progress)(const std::string& line) = nullptr;
};

/// Builds the scene's CPU side. Throws SceneError naming the scene key (FILE:LINE: key: reason)
/// when an input (heightmap, texture image) turns out bad; std::runtime_error for internal
/// failures.
BuiltScene buildScene(const Scene& scene, const BuildOptions& options = {});

/// An unsteady scene's live wind on cells of another size: what UnsteadyFieldWind::moveToGrid
/// takes (gale view's coarser live grid).
struct LiveWindGrid {
    std::unique_ptr<sim::AirDomain> domain;
    sim::WindField steady;  ///< the steady field on `domain`: the mean flow there
    sim::UnsteadySettings settings;
    double referenceSpeed_mps = 1.0;
    std::string summary;  ///< the steady solve's summary (SceneField::summary)
};

/// The scene's domain and steady field with solver.voxel_size_m = voxelSize_m (cubic cells only),
/// through the composition every verb uses (buildSceneDomain, solveSceneField,
/// unsteadySteppingOf), over `terrain` (the built scene's heightfield). Throws SceneError as
/// buildScene for a grid the scene cannot have (memory, a box too small for the cells), and
/// SceneError at solver.first_cell_m for stretched layers.
LiveWindGrid buildLiveWindGrid(const Scene& scene, const sim::Heightfield& terrain,
                               double voxelSize_m);

/// A scene's terrain: the heightfield (local frame) and, for a DEM, where it sits.
struct SceneTerrain {
    sim::Heightfield field;
    Georeference georef;
};

/// Only the terrain (procedural, from the heightmap image, or from the DEM); throws like
/// buildScene.
SceneTerrain buildTerrain(const Scene& scene);

/// buildTerrain's heightfield alone.
sim::Heightfield buildHeightfield(const Scene& scene);

/// The default camera for `field`: from the south-west (azimuth 235 deg), 20 deg above the
/// horizon, looking at the terrain's centre (half way between the ground there and the lowest
/// point), at 0.8 of the distance at which the terrain's bounding sphere just fits the frame: the
/// whole terrain in view, as the default scene frames its knoll. Never less than 1.7 m above the
/// ground under it. Keeps fov, near and far of `base`, and its position or target where
/// keepPosition / keepTarget say so.
render::Camera defaultCamera(const sim::Heightfield& field, const render::Camera& base,
                             bool keepPosition, bool keepTarget);

}  // namespace gale::app
