/// \file CommandsSolveUnsteady.cpp
/// `gale solve` on an unsteady scene (wind.kind = "unsteady", docs/unsteady.md): the steady
/// solve for the initial state, then time steps to the scene's duration, writing the .vdb
/// sequence <stem>_0000.vdb ... and a JSON report with every step. Interrupts keep the complete
/// frames and a report that says where the run stopped.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <system_error>
#include <vector>

#include "app/SolveRun.h"
#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/io/Interrupt.h"
#include "app/io/OutputLock.h"
#include "app/io/ProcessMemory.h"
#include "app/io/Progress.h"
#include "app/io/Timing.h"
#include "app/scene/SceneField.h"
#include "app/scene/SceneParser.h"
#include "base/Numbers.h"
#include "sim/AirDomain.h"
#include "sim/MemoryEstimate.h"
#include "sim/SteadyWind.h"
#include "sim/UnsteadyWind.h"
#include "sim/VdbIO.h"

namespace gale::app {

namespace {

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

}  // namespace

int runUnsteadySolve(const SolveRequest& req) {
    const auto t0 = Clock::now();
    const UnsteadySolveRequest& u = *req.unsteady;
    const Scene& scene = *req.scene;
    checkSceneFieldInputs(scene);
    InterruptScope interrupt("while building the air domain: nothing written");
    // No progress line before the domain and the sequence's size are checked: bad input gets one
    // line only.
    std::unique_ptr<sim::AirDomain> domainPtr = buildSceneDomain(scene, req.terrain);
    const sim::AirDomain& domain = *domainPtr;
    if (!req.vdbPath.empty())
        if (auto problem = sequenceBytesProblem(
                u.limits, sim::vdbWindFile_bytes(domain.nx(), domain.ny(), domain.nz())))
            throw InputError(u.outputEveryWhere + ": " + *problem);
    std::fprintf(
        stderr,
        "solve: %d x %d x %d cells, %zu air; steady solve (initial state and mean flow)...\n",
        domain.nx(), domain.ny(), domain.nz(), domain.activeCellCount());
    for (const std::string& line : describeSceneField(scene, domain))
        std::fprintf(stderr, "solve: %s\n", line.c_str());
    interrupt.exitAtOnce("during the steady solve: nothing written");
    SceneField steady = solveSceneField(scene, std::move(domainPtr), verbFieldOptions("solve"));
    if (steady.stopped()) {
        std::printf("solve: interrupted during the steady start: %s; nothing written\n",
                    steady.summary().c_str());
        return interruptExitCode();
    }
    const UnsteadyStepping stepping = unsteadySteppingOf(scene);
    sim::UnsteadyWindSolver solver(domain, steady.field, stepping.settings,
                                   stepping.referenceSpeed_mps);
    const FieldProvenance provenance = fieldProvenance(scene, req.terrain);

    nlohmann::json j;
    j["scene"] = req.sceneName;
    j["model"] =
        "unsteady incompressible wind (docs/design.md 4.2): operator splitting on the MAC grid "
        "(Stam 1999), " +
        std::string(sim::advectionSchemeName(u.settings.advection)) +
        " advection, projection on cut cells with warm-started MGPCG (McAdams, Sifakis, Teran "
        "2010); initial state and mean flow: " +
        steady.modelText;
    j["what_ran"] = describeSceneField(scene, domain);
    j["provenance"] = provenanceJson(provenance);
    j["domain"] = domainJson(domain, scene);
    j["steady"] = {{"converged", steady.report.converged},
                   {"iterations", steady.report.iterations},
                   {"max_div_u_h_over_U", steady.report.maxDivergenceScaled},
                   {"summary", steady.summary()}};
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
    std::vector<std::string> gridNames;  // of the first file; every file holds the same
    auto writeFrame = [&](int n) {
        const std::string path = sequencePath(req.vdbPath, n);
        if (!req.vdbPath.empty()) {
            sim::VdbMetadata meta;
            meta.strings = {{"scene", req.sceneName}};
            for (const auto& kv : provenance.metadata()) meta.strings.push_back(kv);
            meta.numbers = {{"time_s", solver.time_s()}};
            const double bytes =
                writeStagedVdb(staged, solver.field(), path, meta, n == 0 ? &gridNames : nullptr);
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
    // Stopped before the last output: the report says where. A signal after it (while the
    // report and files are moved into place) stops nothing: the run is complete.
    const bool stoppedEarly = interruptSignal() != 0 && int(frames.size()) <= outputs;
    if (stoppedEarly) {
        j["interrupted"] = true;
        j["stopped_by"] = interruptSignalName();
        j["stopped_at_t_s"] = solver.time_s();
    }
    j["steps"] = steps;
    j["domain"]["peak_resident_bytes"] = peakResidentBytes();  // beside the estimate
    j["outputs"] = {{"vdb_sequence", frames},
                    {"grids", vdbGridDescriptions(gridNames)},
                    {"placement", domain.layout().uniformZ()
                                      ? "cell-centred averages of the MAC face velocities"
                                      : "velocity and speed: a cubic resample "
                                        "(domain.vdb_voxels); velocity_layers: the MAC faces "
                                        "of the stretched layers"}};
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
    if (stoppedEarly) {
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
    if (interruptSignal())
        return reportInterruptedWhileWriting(
            req.vdbPath.empty()
                ? std::string()
                : sequencePath(req.vdbPath, 0) + " .. " + frames.back()["path"].get<std::string>(),
            req.reportPath);
    return ok ? EXIT_OK : EXIT_UNMET;
}

}  // namespace gale::app
