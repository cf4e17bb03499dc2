#pragma once
/// \file SceneField.h
/// The one composition of a scene's wind (docs/architecture.md, "One scene, one field"). Every
/// verb that builds a scene's field -- check (the plan only), render, view, solve, probe, and the
/// benches that run a scene -- builds it here, so they run the same model with the same keys and
/// say the same things about what ran.
///
/// What it composes, from the scene alone:
/// - the air domain over the terrain ([solver] voxel_size_m, top_m, first_cell_m, stretch_ratio,
///   max_cell_m, max_memory_gib; the momentum model's arrays counted when solver.model =
///   "momentum");
/// - the steady field of solver.model: the mass-consistent field (alpha_h, alpha_v, tolerance,
///   max_iterations), or the momentum model (every momentum_* key, displacement_height_m, the
///   pseudo-time advection) started from the mass-consistent field solved with the same
///   tolerance;
/// - for wind.kind = "unsteady", that same steady field as the unsteady solver's initial state and
///   mean flow, stepped with [unsteady] and its gusts and whirlwinds (unsteadySteppingOf);
/// - the near-ground read which the grass and the probes share (nearGroundOf,
///   coupling/NearGround.h);
/// - the provenance a written field carries (fieldProvenance), so that a reader can refuse a
///   field of another terrain.
///
/// @code
///   const Scene scene = loadScene({"examples/lee_ridge_momentum.toml"});
///   const SceneTerrain terrain = buildTerrain(scene);
///   SceneField f = buildSceneField(scene, terrain.field, {});
///   std::puts(f.summary().c_str());  // "momentum model ...: converged in 412 pseudo-time steps"
///   if (!f.converged()) return EXIT_UNMET;
/// @endcode

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/scene/Scene.h"
#include "coupling/NearGround.h"
#include "sim/AirDomain.h"
#include "sim/Heightfield.h"
#include "sim/MomentumWind.h"
#include "sim/PoissonSolver.h"
#include "sim/SteadyWind.h"
#include "sim/UnsteadyWind.h"
#include "sim/WindField.h"

namespace gale::app {

/// The scene's air domain over `terrain` (the scene's heightfield, local frame). Throws SceneError
/// at the [solver] key a bad value came from (voxel size, top, layers, memory limit).
std::unique_ptr<sim::AirDomain> buildSceneDomain(const Scene& scene,
                                                 const sim::Heightfield& terrain);

/// What the grass and the probes read below the first solved faces (coupling/NearGround.h): the
/// log law of the momentum model's wall stress (z0 = wind.roughness_m, d =
/// solver.displacement_height_m), the free-slip tangential law of the mass-consistent field; for
/// an unsteady scene what its grass reads (coupling::nearGroundOf of its [unsteady] settings).
coupling::NearGround nearGroundOf(const Scene& scene);

/// The unsteady solver's settings and reference speed of a wind.kind = "unsteady" scene.
struct UnsteadyStepping {
    sim::UnsteadySettings settings;
    double referenceSpeed_mps = 1.0;  ///< U of the solver's scaled divergence: the ambient speed
};
UnsteadyStepping unsteadySteppingOf(const Scene& scene);

/// One line each of what buildSceneField runs for this scene on `domain`, for `gale check` and
/// the reports: the model with its closure and pseudo-time step (or the unsteady stepping), the
/// cells (cubes or stretched layers: first cell, ratio, count, top), the memory estimate and
/// limit, and the iteration budgets. Empty for a point-source scene.
std::vector<std::string> describeSceneField(const Scene& scene, const sim::AirDomain& domain);

/// The refusals the run would make before solving, checked without solving (gale check): each a
/// SceneError at its key. Today: a displacement height at or above the first solved level or the
/// reference height (the log law has no wind there), and a momentum model with a profile other
/// than the log law. buildSceneField runs the same checks.
void checkSceneFieldInputs(const Scene& scene);

/// Where a field came from, written into its .vdb and JSON (gale solve) and compared by readers
/// (gale probe --vdb). Digests are FNV-1a 64-bit of a canonical text of the values, in hex.
struct FieldProvenance {
    std::string terrainDigest;  ///< the heightfield's sizes, spacing, origin and samples
    std::string crop;           ///< terrain.crop_m as "minX minY maxX maxY" (DEM metres), or "none"
    std::string model;          ///< solver.model ("mass_consistent", "momentum")
    std::string solverDigest;   ///< every [solver] value the field depends on, and [unsteady]'s
    std::string windDigest;     ///< the ambient wind, gusts and whirlwinds
    /// As metadata strings: gale_terrain_digest, gale_crop, gale_model, gale_solver_digest,
    /// gale_wind_digest.
    std::vector<std::pair<std::string, std::string>> metadata() const;
};
FieldProvenance fieldProvenance(const Scene& scene, const sim::Heightfield& terrain);

/// FNV-1a 64 of a field's face velocities (u, v, w arrays, their bits), hex.
std::string fieldDigestOf(const sim::WindField& field);

/// How a file's provenance (its metadata strings) differs from the scene's: `refusals` for
/// another terrain or crop (the field does not belong to this scene), `warnings` for another
/// model, solver keys or wind, or a file written without provenance. Each a sentence naming what
/// differs.
struct ProvenanceDiff {
    std::vector<std::string> refusals;
    std::vector<std::string> warnings;
};
ProvenanceDiff compareProvenance(const std::map<std::string, std::string>& fileMetadata,
                                 const FieldProvenance& scene);

struct SceneFieldOptions {
    /// Progress lines for long work (the momentum model's pseudo-time steps: level, step, residual,
    /// time left on the level), a few a second at most; empty: quiet.
    std::function<void(const std::string& line)> progress;
    /// Called once when the solve ends, if progress lines were given (ends a line a terminal
    /// rewrote in place). Empty: nothing.
    std::function<void()> progressDone;
    /// Polled after every momentum pseudo-time step: true stops the solve there (the result is
    /// then stopped(), not converged, and its report says how far it got). Empty: never stops.
    std::function<bool()> stopRequested;
};

/// The options every verb that solves uses (solve, probe): progress on stderr as "VERB: LINE",
/// rewritten in place on a terminal and one line each otherwise; a SIGINT, SIGTERM or SIGHUP
/// caught by the verb's deferred InterruptScope (app/io/Interrupt.h) stops the momentum model
/// between pseudo-time steps.
SceneFieldOptions verbFieldOptions(const std::string& verb);

/// The scene's steady field, with what ran.
struct SceneField {
    std::unique_ptr<sim::AirDomain> domain;  ///< the field's geometry (kept alive for the field)
    sim::WindField field;  ///< the steady field; for unsteady scenes the initial state
    /// The mass-consistent solve, or the momentum model's summary (iterations = pseudo-time
    /// steps over all levels; converged only when every level converged within its step limit
    /// and the field stayed finite).
    sim::SolveReport report;
    std::optional<sim::MomentumReport> momentum;  ///< solver.model = "momentum"
    /// Turbulent kinetic energy k (m^2/s^2) on the domain's cells (GridIndex cell layout; sample it
    /// with coupling::sampleTke_m2ps2, coupling/Turbulence.h), from the momentum model's closure
    /// (sim/MomentumTurbulence.h); empty for the mass-consistent model, which has no turbulence.
    std::vector<double> tke_m2ps2;
    double domain_s = 0.0;            ///< building the domain, seconds
    double solve_s = 0.0;             ///< the steady solve, seconds
    double solverMemory_bytes = 0.0;  ///< the mass-consistent solver's levels (0: momentum)
    std::string modelText;            ///< one line: the model that ran, with its closure and step
    /// FNV-1a 64 of the face velocities' bits (hex): equal digests, the same field to the last
    /// bit (every verb prints it in its summary, gale solve's report records it).
    std::string fieldDigest;

    bool converged() const { return report.converged; }
    /// SceneFieldOptions::stopRequested stopped the momentum solve.
    bool stopped() const { return momentum && momentum->stopped; }
    /// "mass-consistent (Sherman 1978): converged in 7 iterations, relative residual 3.1e-07,
    /// max|div u| h/U 1.2e-07, 0.41 s, field 9f3c..." or the momentum model's pseudo-time steps,
    /// levels and residual.
    std::string summary() const;
};

/// Builds the scene's domain over `terrain` and solves its steady field. Throws SceneError at the
/// key for bad input (the domain's, the wind's, the model's). Non-convergence is in the result,
/// never thrown.
SceneField buildSceneField(const Scene& scene, const sim::Heightfield& terrain,
                           const SceneFieldOptions& options = {});

/// As buildSceneField, on a domain already built by buildSceneDomain for this scene.
SceneField solveSceneField(const Scene& scene, std::unique_ptr<sim::AirDomain> domain,
                           const SceneFieldOptions& options = {});

}  // namespace gale::app
