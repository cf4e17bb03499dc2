/// \file SceneField.cpp
/// The one composition of a scene's wind (SceneField.h).

#include "app/scene/SceneField.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "app/io/Errors.h"
#include "app/io/Interrupt.h"
#include "app/io/Progress.h"
#include "app/scene/SceneBuilder.h"
#include "app/scene/SceneParser.h"
#include "base/Numbers.h"
#include "coupling/UnsteadyFieldWind.h"
#include "sim/MemoryEstimate.h"
#ifdef GALE_HAVE_DIST
#include "dist/ProcessGroup.h"
#endif

namespace gale::app {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Progress lines at most this often on a terminal, seconds (the line is rewritten in place)...
constexpr double PROGRESS_INTERACTIVE_S = 0.25;
/// ...and in logs (every line is kept).
constexpr double PROGRESS_LOG_S = 5.0;

/// FNV-1a, 64 bits (Fowler, Noll, Vo): a digest to tell two inputs apart, not a cryptographic hash.
class Digest {
  public:
    void bytes(const void* data, size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i) mHash = (mHash ^ p[i]) * 0x100000001b3ull;
    }
    void text(const std::string& s) { bytes(s.data(), s.size() + 1); }  // with its terminator
    void number(double v) { text(formatG(v, 17)); }
    std::string hex() const {
        char buf[20];
        std::snprintf(buf, sizeof buf, "%016" PRIx64, mHash);
        return buf;
    }

  private:
    uint64_t mHash = 0xcbf29ce484222325ull;
};

std::string cropText(const Scene& scene) {
    if (!scene.terrain.crop) return "none";
    const CropWindow& c = *scene.terrain.crop;
    return formatG(c.minX_m, 17) + " " + formatG(c.minY_m, 17) + " " + formatG(c.maxX_m, 17) + " " +
           formatG(c.maxY_m, 17);
}

void addSolverSettings(Digest& d, const sim::SolverSettings& s) {
    d.number(s.relativeTolerance), d.number(s.maxIterations), d.number(s.smoothingSweeps);
    d.number(s.useMultigrid);
}

void addSurfaceLayer(Digest& d, const sim::SurfaceLayerSettings& s) {
    d.number(s.enabled), d.number(s.roughness_m), d.number(s.displacementHeight_m);
    d.number(s.mixingLengthMax_m), d.number(s.eddyViscosity), d.number(s.wallStress);
    d.number(s.balanced.has_value());
    // Added only for a closure other than the first, so that fields solved before the closure
    // was a choice keep their digest.
    if (s.closure != sim::TurbulenceClosure::MixingLength)
        d.text(sim::turbulenceClosureName(s.closure));
}

void addAmbient(Digest& d, const sim::AmbientWind& a) {
    d.number(a.speed_mps), d.number(a.referenceHeight_m), d.number(a.direction_deg);
    d.text(sim::windProfileName(a.profile)), d.number(a.roughness_m);
}

/// "8.1 s", "3 min 05 s".
std::string duration(double s) { return Progress::formatDuration(s); }

/// The momentum model's progress line and stop poll (SceneFieldOptions), throttled.
class MomentumProgress {
  public:
    MomentumProgress(const SceneFieldOptions& options, double residualTolerance)
        : mOptions(options), mTolerance(residualTolerance), mStart(Clock::now()), mLast(mStart) {}

    bool operator()(const sim::MomentumIteration& m, int levelMaxIterations, int levelCount) {
        if (m.level != mLevel || m.iteration == 1) mLevel = m.level, mLevelStart = Clock::now();
        const auto now = Clock::now();
        // The first step at once (the user sees the solve has started), then throttled.
        if (mOptions.progress &&
            (!mPrinted || std::chrono::duration<double>(now - mLast).count() >=
                              (mInteractive ? PROGRESS_INTERACTIVE_S : PROGRESS_LOG_S))) {
            mLast = now, mPrinted = true;
            const double levelS = std::chrono::duration<double>(now - mLevelStart).count();
            const double perStep = levelS / std::max(1, m.iteration);
            const int pass = levelCount - m.level;  // coarsest first: 1 .. levelCount
            mOptions.progress(
                "momentum: level " + std::to_string(pass) + " of " + std::to_string(levelCount) +
                (m.level == 0 ? " (the scene's cells)"
                              : " (cells " + std::to_string(1 << m.level) + "x)") +
                ", pseudo-time step " + std::to_string(m.iteration) +
                (m.iteration <= levelMaxIterations
                     ? " of at most " + std::to_string(levelMaxIterations)
                     : std::string(" (averaging the residual's cycles)")) +
                ", residual " + formatG(m.momentumResidual, 3) + " (converged at " +
                formatG(mTolerance, 3) + "), " + duration(secondsSince(mStart)) + " so far" +
                (m.iteration <= levelMaxIterations
                     ? ", at most " + duration(perStep * (levelMaxIterations - m.iteration)) +
                           " more on this level"
                     : std::string()));
        }
        return !(mOptions.stopRequested && mOptions.stopRequested());
    }

  private:
    const SceneFieldOptions& mOptions;
    double mTolerance;
    Clock::time_point mStart, mLast, mLevelStart;
    int mLevel = -1;
    bool mPrinted = false;
    bool mInteractive = isatty(2) != 0;
};

std::string layersText(const sim::AirDomain& d) {
    const sim::GridLayout& g = d.layout();
    if (g.uniformZ())
        return "cubic cells of " + formatG(d.voxelSize_m(), 3) + " m, " + std::to_string(d.nz()) +
               " up to the top at " + formatFixed(d.wsTop_m(), 1) + " m";
    double ratio = 1.0;
    for (int k = 1; k < d.nz(); ++k) ratio = std::max(ratio, g.dz_m(k) / g.dz_m(k - 1));
    return "stretched layers: first " + formatG(g.dz_m(0), 3) + " m thick, growing by " +
           formatG(ratio, 3) + " to " + formatG(g.dz_m(d.nz() - 1), 3) + " m, " +
           std::to_string(d.nz()) + " layers up to the top at " + formatFixed(d.wsTop_m(), 1) +
           " m; " + formatG(d.voxelSize_m(), 3) + " m horizontally";
}

std::string massConsistentText(const Scene& scene) {
    const sim::MassConsistentWeights& w = scene.solver.weights;
    return "mass-consistent (Sherman 1978; alpha_h " + formatG(w.alphaH, 3) + ", alpha_v " +
           formatG(w.alphaV, 3) + "), cut cells, MGPCG";
}

std::string momentumText(const Scene& scene) {
    const sim::MomentumSettings& m = scene.solver.momentum;
    const bool eulerian = m.advection == sim::PseudoTimeAdvection::Eulerian;
    const std::string closure =
        m.turbulence == sim::TurbulenceClosure::KEpsilon
            ? "k-epsilon closure (Launder and Spalding 1974, Kato-Launder production, Richards "
              "and Hoxey 1993 inflow and top), wall functions from k (z0 "
        : m.turbulence == sim::TurbulenceClosure::KOmegaSst
            ? "k-omega SST closure (Menter 1994, Kato-Launder production, Richards and Hoxey "
              "1993 inflow and top), wall functions from k (z0 "
            : "mixing-length closure (Blackadar 1962, l_max " + formatG(m.mixingLengthMax_m, 3) +
                  " m), log-law wall stress (z0 ";
    return "momentum model (RANS): " + closure + formatG(scene.wind.ambient.roughness_m, 3) +
           " m, d " + formatG(m.displacementHeight_m, 3) + " m), " +
           (eulerian ? "Eulerian pseudo-time step (van Leer slopes, cfl " +
                           formatG(m.eulerianCfl, 3) + ")"
                     : "semi-Lagrangian pseudo-time step (cfl " + formatG(m.cfl, 3) + ")") +
           ", started from the mass-consistent field";
}

std::string steadyModelText(const Scene& scene) {
    return scene.solver.model == sim::SteadyModel::Momentum ? momentumText(scene)
                                                            : massConsistentText(scene);
}

}  // namespace

std::unique_ptr<sim::AirDomain> buildSceneDomain(const Scene& scene,
                                                 const sim::Heightfield& terrain) {
    std::unique_ptr<sim::AirDomain> domain;
    try {
        domain = std::make_unique<sim::AirDomain>(terrain, scene.solver.domain);
    } catch (const std::invalid_argument& e) {
        rethrowAsSceneError(scene, "solver", e);  // at the key's line when it names one
    }
    // The log law is zero at and below z0 + d above the ground: when that reaches above the
    // domain's highest air over the lowest ground, the whole field would be calm and "converge"
    // at once (docs/reliability.md).
    const sim::AmbientWind& a = scene.wind.ambient;
    const double calm_m = a.roughness_m + (scene.solver.model == sim::SteadyModel::Momentum
                                               ? scene.solver.momentum.displacementHeight_m
                                               : 0.0);
    const double reach_m = domain->wsTop_m() - terrain.minHeight_m();
    if (scene.wind.kind != WindKind::PointSource && a.profile == sim::WindProfile::LogLaw &&
        calm_m >= reach_m)
        throw SceneError(scene.where("wind.roughness_m") + ": roughness_m = " +
                         formatG(a.roughness_m, 4) + " m makes the log profile zero up to " +
                         formatG(calm_m, 4) + " m above the ground (z0 + d), and the air domain " +
                         "reaches only " + formatG(reach_m, 4) +
                         " m above the lowest ground: the whole field would be calm (lower " +
                         "wind.roughness_m or raise solver.top_m)");
    return domain;
}

coupling::NearGround nearGroundOf(const Scene& scene) {
    // An unsteady field is read as coupling::UnsteadyFieldWind reads it for the grass: the log law
    // of its surface layer when [unsteady] surface_layer is on, the tangential law otherwise.
    if (scene.wind.kind == WindKind::Unsteady)
        return coupling::nearGroundOf(scene.unsteady.settings);
    coupling::NearGround n;
    if (scene.solver.model == sim::SteadyModel::Momentum) {
        n.model = coupling::NearGroundModel::LogLaw;
        n.roughness_m = scene.wind.ambient.roughness_m;
        n.displacement_m = scene.solver.momentum.displacementHeight_m;
    }
    return n;
}

UnsteadyStepping unsteadySteppingOf(const Scene& scene) {
    return {scene.unsteady.settings, scene.wind.ambient.speed_mps};
}

std::vector<std::string> describeSceneField(const Scene& scene, const sim::AirDomain& d) {
    std::vector<std::string> lines;
    if (scene.wind.kind == WindKind::PointSource) return lines;
    const bool unsteady = scene.wind.kind == WindKind::Unsteady;
    const bool momentum = scene.solver.model == sim::SteadyModel::Momentum;
    lines.push_back(std::string(unsteady ? "steady start and mean flow: " : "steady field: ") +
                    steadyModelText(scene));
    const sim::SolverSettings& s = scene.solver.settings;
    std::string budget = "mass-consistent solve to a relative residual of " +
                         formatG(s.relativeTolerance, 3) + " in at most " +
                         std::to_string(s.maxIterations) + " iterations";
    if (momentum) {
        const sim::MomentumSettings& m = scene.solver.momentum;
        budget += "; at most " + std::to_string(m.maxIterations) +
                  " pseudo-time steps on each level, " +
                  (m.coarseLevels > 0 ? "up to " + std::to_string(m.coarseLevels) +
                                            " coarser levels first (solver.momentum_coarse_levels)"
                                      : std::string("no coarser levels")) +
                  ", converged at a momentum residual of " + formatG(m.residualTolerance, 3) +
                  " within each level's step limit";
    }
    lines.push_back("budgets: " + budget);
    if (unsteady) {
        const sim::UnsteadySettings& us = scene.unsteady.settings;
        lines.push_back(std::string("then unsteady stepping: ") +
                        sim::advectionSchemeName(us.advection) + " advection, " +
                        (us.dt_s > 0 ? "fixed dt " + formatG(us.dt_s, 3) + " s"
                                     : "adaptive CFL " + formatG(us.cfl, 3) +
                                           " (dt <= " + formatG(us.maxDt_s, 3) + " s)") +
                        ", projection to " + formatG(us.projection.relativeTolerance, 3) +
                        " in at most " + std::to_string(us.projection.maxIterations) +
                        " iterations (warm MGPCG), " +
                        (!us.surfaceLayer.enabled ? "no surface layer, "
                         : us.surfaceLayer.closure == sim::TurbulenceClosure::KEpsilon
                             ? "surface layer (k-epsilon, wall functions from k), "
                         : us.surfaceLayer.closure == sim::TurbulenceClosure::KOmegaSst
                             ? "surface layer (k-omega SST, wall functions from k), "
                             : "surface layer (mixing length, log-law wall stress), ") +
                        (us.openTop ? "open top" : "free-slip lid on top"));
    }
    lines.push_back("cells: " + std::to_string(d.nx()) + " x " + std::to_string(d.ny()) + " x " +
                    std::to_string(d.nz()) + ", " + std::to_string(d.activeCellCount()) + " air; " +
                    layersText(d));
    lines.push_back("memory: about " + formatBytes(double(d.memoryEstimate_bytes())) +
                    " estimated (limit " + formatBytes(scene.solver.domain.memoryLimit_bytes) +
                    ", solver.max_memory_gib)");
    return lines;
}

void checkSceneFieldInputs(const Scene& scene) {
    try {
        scene.wind.ambient.validate();
        if (scene.solver.model == sim::SteadyModel::Momentum)
            sim::validateMomentumWind(scene.wind.ambient, scene.solver.momentum);
        if (scene.wind.kind == WindKind::Unsteady) scene.unsteady.settings.validate();
        coupling::validate(nearGroundOf(scene));
    } catch (const std::invalid_argument& e) {
        rethrowAsSceneError(scene, "solver", e);
    }
}

std::vector<std::pair<std::string, std::string>> FieldProvenance::metadata() const {
    return {{"gale_terrain_digest", terrainDigest},
            {"gale_crop", crop},
            {"gale_model", model},
            {"gale_solver_digest", solverDigest},
            {"gale_wind_digest", windDigest}};
}

FieldProvenance fieldProvenance(const Scene& scene, const sim::Heightfield& t) {
    FieldProvenance p;
    Digest terrain;
    terrain.number(t.nx), terrain.number(t.ny), terrain.number(t.spacing_m);
    terrain.number(t.originX_m), terrain.number(t.originY_m);
    terrain.bytes(t.height_m.data(), t.height_m.size() * sizeof(float));
    p.terrainDigest = terrain.hex();
    p.crop = cropText(scene);
    p.model = sim::steadyModelName(scene.solver.model);

    Digest solver;
    const sim::DomainSpec& dom = scene.solver.domain;
    solver.number(dom.voxelSize_m), solver.number(dom.top_m.value_or(-1.0));
    solver.number(dom.cutCells), solver.number(dom.firstCell_m.value_or(-1.0));
    solver.number(dom.stretchRatio), solver.number(dom.maxCell_m.value_or(-1.0));
    solver.number(dom.closedSidesY);
    solver.number(scene.solver.weights.alphaH), solver.number(scene.solver.weights.alphaV);
    addSolverSettings(solver, scene.solver.settings);
    solver.text(p.model);
    if (scene.solver.model == sim::SteadyModel::Momentum) {
        const sim::MomentumSettings& m = scene.solver.momentum;
        solver.text(sim::pseudoTimeAdvectionName(m.advection));
        solver.number(m.cfl), solver.number(m.eulerianCfl), solver.number(m.maxIterations);
        solver.number(m.residualTolerance), solver.number(m.displacementHeight_m);
        solver.number(m.mixingLengthMax_m), solver.number(m.coarseLevels);
        solver.number(m.minIterationsAfterProlongation), solver.number(m.averageCycles);
        solver.number(m.averageMinSteps);
        if (m.turbulence != sim::TurbulenceClosure::MixingLength)  // as in addSurfaceLayer
            solver.text(sim::turbulenceClosureName(m.turbulence));
        addSolverSettings(solver, m.projection), addSolverSettings(solver, m.finalProjection);
    }
    solver.text(windKindName(scene.wind.kind));
    Digest wind;
    addAmbient(wind, scene.wind.ambient);
    if (scene.wind.kind == WindKind::Unsteady) {
        const sim::UnsteadySettings& u = scene.unsteady.settings;
        solver.text(sim::advectionSchemeName(u.advection));
        solver.number(u.dt_s), solver.number(u.cfl), solver.number(u.maxDt_s);
        solver.number(u.viscosity_m2ps), solver.number(u.vorticityConfinement);
        solver.number(u.openTop);
        addSolverSettings(solver, u.projection);
        addSurfaceLayer(solver, u.surfaceLayer);
        for (const sim::GustEvent& g : u.gusts) {
            wind.text(sim::gustEnvelopeName(g.envelope));
            wind.number(g.start_s), wind.number(g.direction_deg), wind.number(g.peak_mps);
            wind.number(g.duration_s), wind.number(g.attack_s.value_or(-1.0));
            wind.number(g.entry == sim::GustEntry::Inflow), wind.number(g.regionRadius_m);
            wind.number(g.regionStart_m[0]), wind.number(g.regionStart_m[1]);
        }
        for (const sim::Whirlwind& v : u.whirlwinds) {
            wind.text(sim::vortexProfileName(v.profile));
            wind.number(v.wsPosition_m[0]), wind.number(v.wsPosition_m[1]);
            wind.number(v.coreRadius_m), wind.number(v.circulation()), wind.number(v.updraft_mps);
            wind.number(v.start_s), wind.number(v.lifetime_s.value_or(-1.0)), wind.number(v.forced);
            wind.number(v.height_m);
        }
    }
    p.solverDigest = solver.hex();
    p.windDigest = wind.hex();
    return p;
}

ProvenanceDiff compareProvenance(const std::map<std::string, std::string>& file,
                                 const FieldProvenance& scene) {
    ProvenanceDiff d;
    auto value = [&](const char* key) -> const std::string* {
        const auto it = file.find(key);
        return it == file.end() ? nullptr : &it->second;
    };
    if (!value("gale_terrain_digest")) {
        d.warnings.push_back(
            "written without gale's provenance (an older gale or another tool): nothing shows "
            "that it is this scene's field");
        return d;
    }
    if (*value("gale_terrain_digest") != scene.terrainDigest)
        d.refusals.push_back("solved over another terrain (terrain digest " +
                             *value("gale_terrain_digest") + ", this scene's " +
                             scene.terrainDigest + ")");
    const std::string* crop = value("gale_crop");
    if (!crop || *crop != scene.crop)
        d.refusals.push_back("solved on another crop of the DEM (terrain.crop_m " +
                             (crop ? *crop : std::string("not recorded")) + ", this scene's " +
                             scene.crop + ")");
    const std::string* model = value("gale_model");
    if (!model || *model != scene.model)
        d.warnings.push_back("solved with solver.model = \"" + (model ? *model : std::string("?")) +
                             "\", this scene has \"" + scene.model + "\"");
    const std::string* solver = value("gale_solver_digest");
    if (!solver || *solver != scene.solverDigest)
        d.warnings.push_back("solved with other [solver] or [unsteady] settings than this scene's");
    const std::string* wind = value("gale_wind_digest");
    if (!wind || *wind != scene.windDigest)
        d.warnings.push_back(
            "solved for another wind (speed, direction, profile, gusts or "
            "whirlwinds) than this scene's");
    return d;
}

namespace {

/// "; level 2 (4 m cells) stopped at its step limit (300 steps in all)" for every level that did
/// not converge, coarse ones included (MomentumLevel::converged), or "".
std::string unconvergedLevels(const sim::MomentumReport& m) {
    std::string out;
    for (const sim::MomentumLevel& lv : m.levels) {
        if (lv.converged) continue;
        out += "; level " + std::to_string(lv.level) + " (" + formatG(lv.voxelSize_m, 3) +
               " m cells) " +
               (lv.atStepLimit ? "stopped at its step limit (" + std::to_string(lv.iterations) +
                                     " steps in all)"
                               : std::string("did not converge"));
    }
    return out;
}

}  // namespace

std::string SceneField::summary() const {
    const sim::SolveReport& r = report;
    std::string head = modelText + ": ";
    if (stopped())
        return head + "STOPPED: " + momentum->message + " (" + std::to_string(r.iterations) +
               " pseudo-time steps)";
    if (momentum) {
        const sim::MomentumReport& m = *momentum;
        return head + (r.converged ? "converged in " : "DID NOT CONVERGE in ") +
               std::to_string(m.iterations) + " pseudo-time steps (" +
               std::to_string(m.fineIterations) + " on the scene's cells, " +
               std::to_string(m.levels.size()) + " level" + (m.levels.size() == 1 ? "" : "s") +
               "), momentum residual " + formatG(m.momentumResidual, 3) + ", max|div u| h/U " +
               formatG(m.maxDivergenceScaled, 3) + ", " + formatFixed(solve_s, 2) + " s, field " +
               fieldDigest + unconvergedLevels(m);
    }
    return head + (r.converged ? "converged in " : "DID NOT CONVERGE in ") +
           std::to_string(r.iterations) + " iterations, relative residual " +
           formatG(r.relativeResidual, 3) + ", max|div u| h/U " +
           formatG(r.maxDivergenceScaled, 3) + ", " + formatFixed(solve_s, 2) + " s, field " +
           fieldDigest;
}

std::string fieldDigestOf(const sim::WindField& field) {
    Digest d;
    for (const std::vector<double>* a : {&field.u_mps(), &field.v_mps(), &field.w_mps()})
        d.bytes(a->data(), a->size() * sizeof(double));
    return d.hex();
}

SceneField solveSceneField(const Scene& scene, std::unique_ptr<sim::AirDomain> domain,
                           const SceneFieldOptions& options) {
    checkSceneFieldInputs(scene);
    SceneField out;
    out.modelText = steadyModelText(scene);
    const auto t0 = Clock::now();
    try {
        if (scene.solver.model == sim::SteadyModel::Momentum) {
            sim::MomentumSettings settings = scene.solver.momentum;
            MomentumProgress progress(options, settings.residualTolerance);
            if (options.progress || options.stopRequested)
                settings.onStep = [&progress](const sim::MomentumIteration& m, int maxIt,
                                              int levels) { return progress(m, maxIt, levels); };
            sim::SteadyModelResult r =
                sim::solveSteadyModel(*domain, scene.wind.ambient, scene.solver.model,
                                      scene.solver.weights, scene.solver.settings, settings);
            out.field = std::move(r.field);
            out.report = r.report;
            out.momentum = std::move(r.momentum);
            out.tke_m2ps2 = std::move(r.tke_m2ps2);
        } else {
            // The mass-consistent branch of sim::solveSteadyModel, with the solver kept for the
            // report's memory figure.
            sim::SteadyWindSolver solver(*domain, scene.solver.weights);
#ifdef GALE_HAVE_DIST
            // Under mpirun every rank takes part in the solve (dist/ProcessGroup.h).
            if (auto solve = dist::groupPoissonSolve(solver.system()))
                solver.setPoissonSolve(std::move(solve));
#endif
            sim::SteadyWindResult r = solver.solve(scene.wind.ambient, scene.solver.settings);
            out.field = std::move(r.field);
            out.report = r.report;
            out.solverMemory_bytes = double(solver.poisson().memory_bytes());
        }
    } catch (const std::invalid_argument& e) {
        rethrowAsSceneError(scene, "wind", e);
    }
    if (options.progressDone) options.progressDone();
    out.solve_s = secondsSince(t0);
    out.fieldDigest = fieldDigestOf(out.field);
    out.domain = std::move(domain);
    return out;
}

SceneFieldOptions verbFieldOptions(const std::string& verb) {
    SceneFieldOptions o;
    const bool terminal = isatty(2) != 0;
    auto printed = std::make_shared<bool>(false);
    o.progress = [verb, terminal, printed](const std::string& line) {
        if (terminal)
            std::fprintf(stderr, "\r%s: %s\033[K", verb.c_str(), line.c_str());
        else
            std::fprintf(stderr, "%s: %s\n", verb.c_str(), line.c_str());
        *printed = true;
    };
    o.progressDone = [terminal, printed] {
        if (terminal && *printed) std::fputc('\n', stderr);
        *printed = false;
    };
    o.stopRequested = [] { return interruptSignal() != 0; };
    return o;
}

SceneField buildSceneField(const Scene& scene, const sim::Heightfield& terrain,
                           const SceneFieldOptions& options) {
    const auto t0 = Clock::now();
    std::unique_ptr<sim::AirDomain> domain = buildSceneDomain(scene, terrain);
    const double domainSeconds = secondsSince(t0);
    SceneField out = solveSceneField(scene, std::move(domain), options);
    out.domain_s = domainSeconds;
    return out;
}

}  // namespace gale::app
