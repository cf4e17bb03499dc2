/// \file CommandsSolve.cpp
/// `gale solve SCENE [-o FILE.vdb]`: the scene's steady wind as a .vdb field and a JSON report
/// (docs/solver.md); for wind.kind = "unsteady" a .vdb sequence <stem>_0000.vdb ... with per-step
/// reports (docs/unsteady.md). runSolveVerb builds a SolveRequest from the scene; runSolve does
/// the work.

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "app/Cli.h"
#include "app/Commands.h"
#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/io/Interrupt.h"
#include "app/io/OutputFolder.h"
#include "app/io/OutputLock.h"
#include "app/io/ProcessMemory.h"
#include "app/io/Progress.h"
#include "app/io/Timing.h"
#include "app/scene/SceneBuilder.h"
#include "app/scene/SceneParser.h"
#include "app/scene/WindRaster.h"
#include "base/Numbers.h"
#include "sim/AirDomain.h"
#include "sim/AmbientWind.h"
#include "sim/Heightfield.h"
#include "sim/PoissonSolver.h"
#include "sim/SteadyWind.h"
#include "sim/UnsteadyWind.h"
#include "sim/VdbIO.h"

namespace gale::app {

/// wind.kind = "unsteady": the time stepping after the steady solve (docs/unsteady.md).
struct UnsteadySolveRequest {
    sim::UnsteadySettings settings;
    double duration_s = 10.0;    ///< simulated time, seconds
    double outputEvery_s = 1.0;  ///< a .vdb at t = 0, every this many seconds, and at duration_s
    UnsteadySection limits;      ///< the scene's bounds on work (max_output_gib for the sequence)
    std::string
        outputEveryWhere;  ///< FILE:LINE: unsteady.output_every_s, blamed for too many bytes
};

struct SolveRequest {
    sim::Heightfield terrain;
    sim::AmbientWind ambient;
    sim::DomainSpec domain;
    sim::MassConsistentWeights weights;
    sim::SolverSettings solver;
    sim::SteadyModel model = sim::SteadyModel::MassConsistent;  ///< [solver] model
    sim::MomentumSettings momentum;                             ///< model = momentum
    std::string vdbPath;     ///< the field (grids "velocity" and "speed"); empty: not written
    std::string reportPath;  ///< the JSON report; empty: not written
    std::string sceneName;   ///< recorded in the report and the .vdb metadata
    std::string outputWhere = "-o";  ///< where the output path came from, for messages
    /// Set for unsteady scenes: vdbPath is then the stem of a sequence, <stem>_0000.vdb ..., and
    /// the report lists every step (CFL, iterations, divergence, kinetic energy, timings).
    std::optional<UnsteadySolveRequest> unsteady;
    Georeference georef;                ///< a DEM's coordinate system, for the rasters
    std::vector<double> gridHeights_m;  ///< rasters of the wind this high above ground (steady)
    double houdiniFps = 0.0;            ///< > 0: also the y-up .vdb sequence, frames at this rate
};

/// "<stem>_houdini.0025.vdb": the y-up file of the scene frame at t_s (frame 1 at t = 0).
std::string houdiniPath(const std::string& vdbPath, double fps, double t_s) {
    char num[32];
    std::snprintf(num, sizeof num, ".%04ld.vdb", std::lround(t_s * fps) + 1);
    return std::filesystem::path(vdbPath).replace_extension("").string() + "_houdini" + num;
}

/// Builds the domain, solves, writes the .vdb and the JSON report (each atomically), prints a
/// summary to stdout and progress to stderr. Returns EXIT_OK when the solve converged, EXIT_UNMET
/// when it did not (both files are still written, and the report says so). Throws
/// std::invalid_argument naming the parameter on bad input (voxel size, top, memory limit, NaN
/// heights, wind, weights), and std::runtime_error when a file cannot be written.
int runSolve(const SolveRequest& request);

/// The unsteady run of an unsteady scene (runSolve calls it when request.unsteady is set): the
/// steady solve, then steps to duration_s writing the sequence; returns 0 when every solve
/// converged and the field stayed finite, EXIT_UNMET otherwise (files still written, the report
/// says so).
int runUnsteadySolve(const SolveRequest& request);

/// "<stem>_0003.vdb" for path "<stem>.vdb" and frame 3.
std::string sequencePath(const std::string& vdbPath, int frame);

namespace {

/// The folder of `path` ("." for a bare name).
std::string folderOf(const std::string& path) {
    const auto parent = std::filesystem::path(path).parent_path();
    return parent.empty() ? std::string(".") : parent.string();
}

/// Creates the folders of the .vdb and the report, takes the .vdb folder's lock and removes
/// temporaries a killed run left there. Returns the lock.
std::unique_ptr<OutputLock> prepareSolveOutputs(const SolveRequest& req) {
    for (const std::string& path : {req.vdbPath, req.reportPath})
        if (!path.empty()) std::filesystem::create_directories(folderOf(path));
    if (req.vdbPath.empty()) return nullptr;
    auto lock = std::make_unique<OutputLock>(folderOf(req.vdbPath), req.outputWhere);
    removeStaleTemporaries(folderOf(req.vdbPath));
    return lock;
}

/// Writes `field` to the staged temporary of `path` and seals it; returns its size in bytes.
double writeStagedVdb(StagedFiles& staged, const sim::WindField& field, const std::string& path,
                      const sim::VdbMetadata& meta) {
    const std::string tmp = staged.add(path);
    try {
        field.writeVdb(tmp, meta);
    } catch (const std::runtime_error& e) {
        // WindField::writeVdb says "cannot write VDB file 'TMP': REASON": keep the reason.
        std::string reason = e.what();
        const size_t at = reason.find("': ");
        if (at != std::string::npos) reason = reason.substr(at + 3);
        throw std::runtime_error(path + ": cannot write: " + reason);
    }
    return staged.seal(path);
}

/// Steps `solver` to `tEnd` as UnsteadyWindSolver::advanceTo does, but stops after the step in
/// hand when SIGINT, SIGTERM or SIGHUP arrives (app/io/Interrupt.h).
std::vector<sim::StepReport> advanceUntilInterrupted(sim::UnsteadyWindSolver& solver, double tEnd) {
    std::vector<sim::StepReport> reps;
    // As advanceTo: a last step shorter than this fraction of a regular step is merged.
    constexpr double MERGE_FRACTION = 1e-6;
    while (solver.time_s() < tEnd && !interruptSignal()) {
        double dt = solver.nextDt_s();
        if (solver.time_s() + dt * (1.0 + MERGE_FRACTION) >= tEnd) dt = tEnd - solver.time_s();
        reps.push_back(solver.step(dt));
        if (!reps.back().finite) break;
    }
    return reps;
}

/// After the first .vdb of a sequence: its size times the files still to come must fit in the
/// folder's free space. Throws InputError.
void checkRoomForSequence(const std::string& folder, const std::string& where, double fileBytes,
                          int filesToCome) {
    // Later fields carry more structure than the initial one: the same margin as for frames.
    constexpr double FILE_SIZE_MARGIN = 1.25;
    std::error_code ec;
    const std::filesystem::space_info space = std::filesystem::space(folder, ec);
    const double need = fileBytes * FILE_SIZE_MARGIN * filesToCome;
    if (!ec && need > static_cast<double>(space.available))
        throw InputError(where + ": '" + folder + "' has " + formatBytes(double(space.available)) +
                         " free but the " + std::to_string(filesToCome) +
                         " .vdb files still to write need about " + formatBytes(need) +
                         " (the first took " + formatBytes(fileBytes) + "); nothing was written");
}

/// Writes `text` to the staged temporary of `path` and seals it.
void writeStagedText(StagedFiles& staged, const std::string& path, const std::string& text) {
    writeTextAtomic(staged.add(path), text);
    staged.seal(path);
}

/// The momentum model's settings, result and convergence history (one entry per pseudo-time step).
nlohmann::json momentumJson(const sim::MomentumReport& m, const sim::MomentumSettings& s) {
    nlohmann::json history = nlohmann::json::array();
    for (const sim::MomentumIteration& it : m.history)
        history.push_back({{"iteration", it.iteration},
                           {"momentum_residual", it.momentumResidual},
                           {"max_momentum_residual", it.maxMomentumResidual},
                           {"max_div_u_h_over_U", it.maxDivergenceScaled},
                           {"projection_iterations", it.projectionIterations},
                           {"projection_converged", it.projectionConverged},
                           {"step_s", it.seconds}});
    return {{"converged", m.converged},
            {"finite", m.finite},
            {"iterations", m.iterations},
            {"momentum_residual", m.momentumResidual},
            {"residual_definition",
             "open-fraction weighted RMS over faces of |u(n+1) - u(n)| / dt * h / U^2"},
            {"tolerance", s.residualTolerance},
            {"max_div_u_h_over_U", m.maxDivergenceScaled},
            {"pseudo_dt_s", m.dt_s},
            {"cfl", s.cfl},
            {"mixing_length_max_m", s.mixingLengthMax_m},
            {"displacement_height_m", s.displacementHeight_m},
            {"max_eddy_viscosity_m2ps", m.maxEddyViscosity_m2ps},
            {"max_friction_velocity_mps", m.maxFrictionVelocity_mps},
            {"start_iterations", m.start.iterations},
            {"message", m.message},
            {"seconds", m.seconds},
            {"history", history}};
}

}  // namespace

int runSolve(const SolveRequest& req) {
    if (req.unsteady) return runUnsteadySolve(req);
    const auto t0 = Clock::now();
    req.ambient.validate();
    InterruptScope interrupt("while building the air domain: nothing written");
    // No progress line before the domain has validated its inputs: bad input gets one line only.
    const sim::AirDomain domain(req.terrain, req.domain);
    const double domainSeconds = secondsSince(t0);
    interrupt.exitAtOnce("while solving: nothing written");
    std::fprintf(stderr, "solve: %d x %d x %d cells, %zu air, estimate %.0f MiB; solving...\n",
                 domain.nx(), domain.ny(), domain.nz(), domain.activeCellCount(),
                 domain.memoryEstimate_bytes() / MIB);
    sim::SteadyWindResult res;
    std::optional<sim::MomentumReport> momentum;
    std::optional<sim::SteadyWindSolver>
        solver;  // the mass-consistent model's, kept for its memory figure
    if (req.model == sim::SteadyModel::Momentum) {
        sim::SteadyModelResult m = sim::solveSteadyModel(domain, req.ambient, req.model,
                                                         req.weights, req.solver, req.momentum);
        res.field = std::move(m.field), res.report = m.report, momentum = std::move(m.momentum);
    } else {
        solver.emplace(domain, req.weights);
        res = solver->solve(req.ambient, req.solver);
    }
    interrupt.defer();  // from here both files are completed, then the run stops
    const sim::SolveReport& rep = res.report;

    nlohmann::json j;
    j["scene"] = req.sceneName;
    j["model"] = momentum ? "steady momentum model (sim/MomentumWind.h): RANS, mixing length "
                            "(Blackadar 1962), log-law "
                            "wall stress, pseudo-time stepping from the mass-consistent field"
                          : "steady mass-consistent wind (Sherman 1978), cut cells (Batty, "
                            "Bertails, Bridson 2007), MGPCG "
                            "(McAdams, Sifakis, Teran 2010)";
    if (momentum) j["momentum"] = momentumJson(*momentum, req.momentum);
    const auto o = domain.wsMin_m();
    j["domain"] = {{"cells", {domain.nx(), domain.ny(), domain.nz()}},
                   {"voxel_size_m", domain.voxelSize_m()},
                   {"ws_min_m", {o[0], o[1], o[2]}},
                   {"ws_top_m", domain.wsTop_m()},
                   {"box_cells", domain.boxCellCount()},
                   {"air_cells", domain.activeCellCount()},
                   {"memory_estimate_bytes", domain.memoryEstimate_bytes()},
                   {"memory_limit_bytes", req.domain.memoryLimit_bytes},
                   {"domain_bytes", domain.memory_bytes()},
                   {"vdb_mask_bytes", domain.vdbMemory_bytes()},
                   {"solver_bytes", solver ? solver->poisson().memory_bytes() : size_t(0)}};
    j["ambient"] = {{"speed_mps", req.ambient.speed_mps},
                    {"reference_height_m", req.ambient.referenceHeight_m},
                    {"direction_deg", req.ambient.direction_deg},
                    {"direction_convention", "towards, counter-clockwise from +x"},
                    {"profile", sim::windProfileName(req.ambient.profile)},
                    {"roughness_m", req.ambient.roughness_m}};
    j["weights"] = {{"alpha_h", req.weights.alphaH}, {"alpha_v", req.weights.alphaV}};
    j["solver"] = {{"relative_tolerance", req.solver.relativeTolerance},
                   {"max_iterations", req.solver.maxIterations},
                   {"smoothing_sweeps", req.solver.smoothingSweeps},
                   {"multigrid", req.solver.useMultigrid},
                   {"residual_norm", "max-norm of b - A x over max-norm of b"}};
    j["report"] = {{"converged", rep.converged},
                   {"iterations", rep.iterations},
                   {"relative_residual", rep.relativeResidual},
                   {"initial_relative_residual", rep.initialRelativeResidual},
                   {"max_div_u_h_over_U", rep.maxDivergenceScaled},
                   {"levels", rep.levels},
                   {"message", rep.message},
                   {"domain_s", domainSeconds},
                   {"setup_s", rep.setupSeconds},
                   {"solve_s", rep.solveSeconds},
                   {"assembly_s", res.assemblySeconds}};
    const std::unique_ptr<OutputLock> lock = prepareSolveOutputs(req);
    StagedFiles staged;  // both files move into place together, or neither
    if (!req.vdbPath.empty()) {
        sim::VdbMetadata meta;
        meta.strings = {{"scene", req.sceneName}, {"converged", rep.converged ? "yes" : "no"}};
        meta.numbers = {{"iterations", double(rep.iterations)},
                        {"relative_residual", rep.relativeResidual},
                        {"max_div_u_h_over_U", rep.maxDivergenceScaled}};
        writeStagedVdb(staged, res.field, req.vdbPath, meta);
        if (req.houdiniFps > 0.0) {
            const std::string path = houdiniPath(req.vdbPath, req.houdiniFps, 0.0);
            sim::writeHoudiniVdb(path, res.field, req.terrain);
            j["outputs"]["houdini"] = {
                {"paths", nlohmann::json::array({path})},
                {"grids", {"vel (vec3s, m/s, y-up)", "surface (level set of the terrain, y-up)"}},
                {"axes", "houdini (x, y, z) = gale (x, z, -y)"}};
        }
        j["outputs"]["vdb"] = {
            {"path", req.vdbPath},
            {"grids",
             {"velocity (vec3s, m/s, world axes)", "speed (float, m/s)",
              "velocity_faces (vec3s, m/s, staggered: the MAC face velocities)"}},
            {"placement",
             "cell-centred averages of the MAC face velocities; voxel (i,j,k) "
             "centre at ws_min_m + (i+0.5, j+0.5, k+0.5) * voxel_size_m"},
            {"grid_class", "GRID_UNKNOWN"},
            {"vector_type", "VEC_CONTRAVARIANT_RELATIVE"}};
    }
    for (const double height_m : req.gridHeights_m) {
        char suffix[64];
        std::snprintf(suffix, sizeof suffix, "_%gm", height_m);
        const std::string stem =
            std::filesystem::path(req.vdbPath).replace_extension("").string() + suffix;
        const std::vector<std::string> paths =
            writeWindRasters(res.field, req.terrain, req.georef, height_m, stem);
        j["outputs"]["rasters"].push_back(
            {{"height_agl_m", height_m},
             {"paths", paths},
             {"bands", {"speed_mps (float32)", "from_deg (float32, meteorological, .tif only)"}},
             {"crs", req.georef.georeferenced() ? req.georef.crsName : "none (not a DEM scene)"},
             {"nodata", WIND_RASTER_NODATA}});
        for (const std::string& p : paths) std::printf("solve: wrote %s\n", p.c_str());
    }
    j["total_s"] = secondsSince(t0);
    j["domain"]["peak_resident_bytes"] = peakResidentBytes();  // beside the estimate
    if (!req.reportPath.empty()) writeStagedText(staged, req.reportPath, j.dump(2) + "\n");
    staged.commit();
    std::printf(
        "solve: %s in %d iterations, relative residual %.2e, max|div u| h/U %.2e, %.2f s (%d x %d "
        "x %d cells, "
        "%zu air)\n",
        rep.converged ? "converged" : "DID NOT CONVERGE", rep.iterations, rep.relativeResidual,
        rep.maxDivergenceScaled, j["total_s"].get<double>(), domain.nx(), domain.ny(), domain.nz(),
        domain.activeCellCount());
    if (!rep.converged) std::printf("solve: %s\n", rep.message.c_str());
    if (interruptSignal()) {
        std::fflush(stdout);
        std::fprintf(stderr,
                     "gale: interrupted (%s) while writing; the solve had finished and %s%s%s are "
                     "complete\n",
                     interruptSignalName(), req.vdbPath.c_str(),
                     req.reportPath.empty() ? "" : " and ", req.reportPath.c_str());
        return interruptExitCode();
    }
    return rep.converged ? EXIT_OK : EXIT_UNMET;
}

std::string sequencePath(const std::string& vdbPath, int frame) {
    std::filesystem::path p(vdbPath);
    char num[32];
    std::snprintf(num, sizeof num, "_%04d", frame);
    const std::string name = p.stem().string() + num + ".vdb";
    return p.has_parent_path() ? (p.parent_path() / name).string() : name;
}

int runUnsteadySolve(const SolveRequest& req) {
    const auto t0 = Clock::now();
    const UnsteadySolveRequest& u = *req.unsteady;
    req.ambient.validate();
    u.settings.validate();
    InterruptScope interrupt("while building the air domain: nothing written");
    // No progress line before the domain and the sequence's size are checked: bad input gets one
    // line only.
    const sim::AirDomain domain(req.terrain, req.domain);
    if (!req.vdbPath.empty())
        if (auto problem = sequenceBytesProblem(u.limits, double(domain.boxCellCount())))
            throw InputError(u.outputEveryWhere + ": " + *problem);
    std::fprintf(
        stderr,
        "solve: %d x %d x %d cells, %zu air; steady solve (initial state and mean flow)...\n",
        domain.nx(), domain.ny(), domain.nz(), domain.activeCellCount());
    sim::SteadyWindSolver steadySolver(domain, req.weights);
    interrupt.exitAtOnce("during the steady solve: nothing written");
    const sim::SteadyWindResult steady = steadySolver.solve(req.ambient, req.solver);
    sim::UnsteadyWindSolver solver(domain, steady.field, u.settings, req.ambient.speed_mps);

    nlohmann::json j;
    j["scene"] = req.sceneName;
    j["model"] =
        "unsteady incompressible wind (docs/design.md 4.2): operator splitting on the MAC grid "
        "(Stam 1999), " +
        std::string(sim::advectionSchemeName(u.settings.advection)) +
        " advection, projection on cut cells with warm-started MGPCG (McAdams, Sifakis, Teran "
        "2010); "
        "initial state and mean flow: the steady mass-consistent field (Sherman 1978)";
    j["domain"] = {{"cells", {domain.nx(), domain.ny(), domain.nz()}},
                   {"voxel_size_m", domain.voxelSize_m()},
                   {"air_cells", domain.activeCellCount()},
                   {"memory_estimate_bytes", domain.memoryEstimate_bytes()},
                   {"memory_limit_bytes", req.domain.memoryLimit_bytes}};
    j["steady"] = {{"converged", steady.report.converged},
                   {"iterations", steady.report.iterations},
                   {"max_div_u_h_over_U", steady.report.maxDivergenceScaled}};
    const sim::UnsteadySettings& s = u.settings;
    j["settings"] = {{"advection", sim::advectionSchemeName(s.advection)},
                     {"dt_s", s.dt_s},
                     {"cfl", s.cfl},
                     {"max_dt_s", s.maxDt_s},
                     {"viscosity_m2ps", s.viscosity_m2ps},
                     {"vorticity_confinement", s.vorticityConfinement},
                     {"open_top", s.openTop},
                     {"projection_tolerance", s.projection.relativeTolerance},
                     {"duration_s", u.duration_s},
                     {"output_every_s", u.outputEvery_s},
                     {"gusts", s.gusts.size()},
                     {"whirlwinds", s.whirlwinds.size()},
                     {"vortex_code", solver.usesVortexCode()}};
    nlohmann::json steps = nlohmann::json::array(), frames = nlohmann::json::array();
    std::vector<std::string> houdiniPaths;
    bool ok = steady.report.converged, finite = true;
    // The sequence and report go to temporaries and move into place together at the end (or,
    // interrupted, the complete frames and a report that says where the run stopped).
    interrupt.defer();
    const std::unique_ptr<OutputLock> lock = prepareSolveOutputs(req);
    StagedFiles staged;
    const int outputs = int(std::ceil(u.duration_s / u.outputEvery_s - 1e-9));
    auto writeFrame = [&](int n) {
        const std::string path = sequencePath(req.vdbPath, n);
        if (!req.vdbPath.empty()) {
            sim::VdbMetadata meta;
            meta.strings = {{"scene", req.sceneName}};
            meta.numbers = {{"time_s", solver.time_s()}};
            const double bytes = writeStagedVdb(staged, solver.field(), path, meta);
            if (n == 0)
                checkRoomForSequence(folderOf(req.vdbPath), req.outputWhere, bytes, outputs);
            if (req.houdiniFps > 0.0) {
                const std::string hpath = houdiniPath(req.vdbPath, req.houdiniFps, solver.time_s());
                sim::writeHoudiniVdb(hpath, solver.field(), req.terrain);
                houdiniPaths.push_back(hpath);
            }
        }
        frames.push_back(
            {{"frame", n}, {"t_s", solver.time_s()}, {"path", req.vdbPath.empty() ? "" : path}});
    };
    writeFrame(0);
    double maxCfl = 0, maxDiv = 0, solveSeconds = 0;
    int maxIt = 0, stepCount = 0;
    // One updating line with ETA on a terminal, one line per output in logs (app/io/Progress.h);
    // the run's CFL and divergence are in the summary line and the report.
    Progress progress("output", outputs);
    for (int n = 1; n <= outputs && finite && !interruptSignal(); ++n) {
        const auto outputStart = Clock::now();
        const double target = std::min(u.duration_s, n * u.outputEvery_s);
        for (const sim::StepReport& r : advanceUntilInterrupted(solver, target)) {
            ++stepCount;
            maxCfl = std::max(maxCfl, r.cfl), maxDiv = std::max(maxDiv, r.maxDivergenceScaled);
            maxIt = std::max(maxIt, r.projection.iterations);
            solveSeconds += r.total_s;
            ok = ok && r.projection.converged && r.finite;
            finite = finite && r.finite;
            steps.push_back({{"t_s", r.t_s},
                             {"dt_s", r.dt_s},
                             {"cfl", r.cfl},
                             {"projection_iterations", r.projection.iterations},
                             {"projection_relative_residual", r.projection.relativeResidual},
                             {"projection_converged", r.projection.converged},
                             {"max_div_u_h_over_U", r.maxDivergenceScaled},
                             {"kinetic_energy_m5ps2", r.kineticEnergy_m5ps2},
                             {"max_speed_mps", r.maxSpeed_mps},
                             {"finite", r.finite},
                             {"viscosity_iterations", r.viscosityIterations},
                             {"advection_s", r.advection_s},
                             {"forcing_s", r.forcing_s},
                             {"viscosity_s", r.viscosity_s},
                             {"projection_s", r.projection_s},
                             {"step_s", r.total_s}});
        }
        if (solver.time_s() < target) break;  // interrupted between two outputs
        writeFrame(n);
        progress.step(n, msSince(outputStart));
    }
    progress.finish();
    if (interruptSignal()) {
        j["interrupted"] = true;
        j["stopped_by"] = interruptSignalName();
        j["stopped_at_t_s"] = solver.time_s();
    }
    j["steps"] = steps;
    j["domain"]["peak_resident_bytes"] = peakResidentBytes();  // beside the estimate
    j["outputs"] = {{"vdb_sequence", frames},
                    {"grids", {"velocity (vec3s, m/s, world axes)", "speed (float, m/s)"}},
                    {"placement", "cell-centred averages of the MAC face velocities"}};
    if (!houdiniPaths.empty())
        j["outputs"]["houdini"] = {
            {"paths", houdiniPaths},
            {"grids", {"vel (vec3s, m/s, y-up)", "surface (level set of the terrain, y-up)"}},
            {"axes", "houdini (x, y, z) = gale (x, z, -y)"}};
    j["summary"] = {{"steps", stepCount},
                    {"simulated_s", solver.time_s()},
                    {"max_cfl", maxCfl},
                    {"max_projection_iterations", maxIt},
                    {"max_div_u_h_over_U", maxDiv},
                    {"all_converged", ok},
                    {"finite", finite},
                    {"mean_step_s", stepCount ? solveSeconds / stepCount : 0.0}};
    j["total_s"] = secondsSince(t0);
    if (!req.reportPath.empty()) writeStagedText(staged, req.reportPath, j.dump(2) + "\n");
    staged.commit();
    if (interruptSignal()) {
        std::printf(
            "solve: interrupted (%s) at t = %.3g s after %d steps: wrote %zu complete .vdb files "
            "(the last %s) and the report %s\n",
            interruptSignalName(), solver.time_s(), stepCount, frames.size(),
            frames.back()["path"].get<std::string>().c_str(), req.reportPath.c_str());
        return interruptExitCode();
    }
    std::printf(
        "solve: unsteady, %d steps to t = %.2f s (%zu .vdb files), max CFL %.2f, max projection "
        "iterations %d, "
        "max|div u| h/U %.2e, %s, %.2f s (%.3f s per step)\n",
        stepCount, solver.time_s(), frames.size(), maxCfl, maxIt, maxDiv,
        !finite ? "NON-FINITE FIELD"
        : ok    ? "all solves converged"
                : "SOME SOLVES DID NOT CONVERGE",
        j["total_s"].get<double>(), stepCount ? solveSeconds / stepCount : 0.0);
    return ok ? EXIT_OK : EXIT_UNMET;
}

namespace fs = std::filesystem;

/// Sequence files checked against the inputs by name; beyond this many (a limit far above any
/// sequence gale check lets through) the names are not built.
constexpr int MAX_ALIAS_CHECKED_FILES = 100000;

int runSolveVerb(const SolveVerbOptions& options) {
    SceneRunOptions sceneOptions;
    sceneOptions.scenePath = options.scenePath;
    const Scene scene = loadScene(sceneOptions);
    SolveRequest request;
    SceneTerrain terrain = buildTerrain(scene);
    request.terrain = std::move(terrain.field);
    request.georef = std::move(terrain.georef);
    request.gridHeights_m = options.gridHeights_m;
    if (options.houdini) request.houdiniFps = scene.output.fps;
    if (!options.gridHeights_m.empty() && scene.wind.kind == WindKind::Unsteady)
        throw InputError(
            "--grid-height-m: rasters are written for steady scenes only (this scene is unsteady)");
    request.ambient = scene.wind.ambient;
    request.domain = scene.solver.domain;
    request.weights = scene.solver.weights;
    request.solver = scene.solver.settings;
    request.model = scene.solver.model;
    request.momentum = scene.solver.momentum;
    request.sceneName = scene.name;
    if (scene.wind.kind == WindKind::Unsteady)
        request.unsteady = UnsteadySolveRequest{scene.unsteady.settings, scene.unsteady.duration_s,
                                                scene.unsteady.outputEvery_s, scene.unsteady,
                                                scene.where("unsteady.output_every_s")};
    request.vdbPath =
        options.vdbPath.empty()
            ? (fs::path(scene.output.folder) / (scene.output.prefix + "_wind.vdb")).string()
            : options.vdbPath;
    if (fs::path(request.vdbPath).extension() != ".vdb")
        throw InputError(
            "-o: the field is written as OpenVDB; the file name must end in .vdb (got '" +
            request.vdbPath + "')");
    request.reportPath = options.reportPath.empty()
                             ? fs::path(request.vdbPath).replace_extension(".json").string()
                             : options.reportPath;
    // Each folder must be a folder or creatable (checked, not created): nothing is created for a
    // run that fails on input. runSolve creates them just before it writes.
    const std::string vdbWhere = options.vdbPath.empty() ? scene.where("output.folder") : "-o";
    const std::string reportWhere = options.reportPath.empty() ? vdbWhere : "--report";
    request.outputWhere = vdbWhere;
    for (const auto& [path, where] :
         {std::pair{request.vdbPath, vdbWhere}, std::pair{request.reportPath, reportWhere}}) {
        std::error_code ec;
        if (fs::is_directory(path, ec))
            throw InputError(where + ": '" + path +
                             "' is a folder; give the name of the file to write");
    }
    {
        std::vector<RunPath> outputs{{request.reportPath, reportWhere + " (the report)"}};
        if (request.unsteady) {
            const int files =
                int(std::ceil(request.unsteady->duration_s / request.unsteady->outputEvery_s -
                              1e-9)) +
                1;
            for (int n = 0; n < files && n < MAX_ALIAS_CHECKED_FILES; ++n)
                outputs.push_back(
                    {sequencePath(request.vdbPath, n), vdbWhere + " (a .vdb of the sequence)"});
        } else {
            outputs.push_back({request.vdbPath, vdbWhere + " (the .vdb field)"});
        }
        refuseAliases(sceneInputs(scene), outputs);
    }
    for (const std::string& path : {request.vdbPath, request.reportPath}) {
        const fs::path folder =
            fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
        std::error_code ec;
        if (fs::exists(folder, ec) && !fs::is_directory(folder, ec))
            throw InputError("'" + folder.string() + "' is a file, not a folder (for " + path +
                             ")");
        const bool isReport = path == request.reportPath && !options.reportPath.empty();
        checkOutputFolder(folder.string(), isReport ? "--report" : vdbWhere, scene.output.prefix,
                          0);
    }
    try {
        // The domain and solve validate their inputs (voxel size, memory limit, wind) before
        // allocating; a bad value is the scene's.
        return runSolve(request);
    } catch (const std::invalid_argument& e) {
        rethrowAsSceneError(scene, "solver", e);
    }
}

void addSolveVerb(CLI::App& app, VerbTable& verbs) {
    auto options = std::make_shared<SolveVerbOptions>();
    CLI::App* verb = app.add_subcommand(
        "solve",
        "Solve a scene's wind over its terrain (steady; unsteady scenes as a .vdb "
        "sequence); write the field as .vdb and a JSON report");
    verb->add_option("scene", options->scenePath, "Scene file")->required();
    verb->add_option("-o,--output", options->vdbPath,
                     "The .vdb file (default: <output.folder>/<prefix>_wind.vdb)")
        ->check(NOT_EMPTY);
    verb->add_option("--report", options->reportPath,
                     "The JSON report (default: the .vdb path with .json)")
        ->check(NOT_EMPTY);
    verb->add_option("--grid-height-m", options->gridHeights_m,
                     "Also write the wind this high above the ground (m; repeatable) as "
                     "<stem>_<H>m.tif (speed, from-direction; the DEM's CRS) and <stem>_<H>m.asc")
        ->check(CLI::Range(0.001, 1e5));
    verb->add_flag("--houdini", options->houdini,
                   "Also write <stem>_houdini.NNNN.vdb for Houdini: grid 'vel' and the terrain SDF "
                   "'surface', y-up, NNNN the scene's frame (output.fps) of each output time");
    verb->footer(std::string("\nThe .vdb holds a Vec3s grid 'velocity' (m/s, world axes, cell "
                             "centres), a float grid 'speed' and a staggered Vec3s grid "
                             "'velocity_faces' (the MAC face velocities); docs/solver.md says "
                             "more. A solve that did not converge still writes both files and "
                             "exits 3.") +
                 EXIT_CODES_FOOTER);
    verbs.add(verb, [options] { return runSolveVerb(*options); });
}

}  // namespace gale::app
