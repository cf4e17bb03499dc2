/// \file CommandsSolveUnsteady.cpp
/// `gale solve` on an unsteady scene (wind.kind = "unsteady", docs/unsteady.md): the steady
/// solve for the initial state, then time steps to the scene's duration, writing the .vdb
/// sequence <stem>_0000.vdb ... and a JSON report with every step. Interrupts keep the complete
/// frames and a report that says where the run stopped.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
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

/// Growth of the flow's kinetic energy over the run, against its initial state, beyond which
/// vorticity confinement is taken to have run away: chosen, not measured, far above what a
/// scene's gusts and whirlwinds add to a domain's ambient flow, far below the runaway's.
constexpr double MAX_CONFINED_ENERGY_GROWTH = 4.0;

/// "%.3g" of `v`.
std::string formatNumber(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", v);
    return text;
}

/// Whether `name` is a file of the sequence of `stem`: "<stem>_NNNN.vdb" (4 or more digits) or
/// its Houdini twin "<stem>_houdini.NNNN.vdb".
bool isSequenceFileOf(const std::string& name, const std::string& stem) {
    const auto digitsBetween = [&](const std::string& head) {
        const std::string tail = ".vdb";
        if (name.size() < head.size() + 4 + tail.size() ||
            name.compare(0, head.size(), head) != 0 ||
            name.compare(name.size() - tail.size(), tail.size(), tail) != 0)
            return false;
        const std::string digits =
            name.substr(head.size(), name.size() - head.size() - tail.size());
        return digits.find_first_not_of("0123456789") == std::string::npos;
    };
    return digitsBetween(stem + "_") || digitsBetween(stem + "_houdini.");
}

/// The .vdb files (sequence and Houdini) an earlier run's report at `reportPath` lists, read
/// before this run replaces it; empty when there is none or it cannot be read.
std::vector<std::string> sequenceOfEarlierReport(const std::string& reportPath) {
    namespace fs = std::filesystem;
    // A report of 10 000 outputs is a few MiB; anything far larger is not one of ours.
    constexpr std::uintmax_t MAX_REPORT_BYTES = 64u << 20;
    std::error_code ec;
    if (reportPath.empty() || !fs::is_regular_file(reportPath, ec) ||
        fs::file_size(reportPath, ec) > MAX_REPORT_BYTES)
        return {};
    std::vector<std::string> paths;
    try {
        std::ifstream in(reportPath);
        const nlohmann::json j = nlohmann::json::parse(in);
        for (const auto& f : j.at("outputs").value("vdb_sequence", nlohmann::json::array()))
            if (f.contains("path") && f["path"].is_string()) paths.push_back(f["path"]);
        if (j.at("outputs").contains("houdini"))
            for (const auto& p : j["outputs"]["houdini"].value("paths", nlohmann::json::array()))
                if (p.is_string()) paths.push_back(p);
    } catch (const std::exception&) {
        return {};  // not an unsteady report of gale's: nothing is known to be an earlier run's
    }
    return paths;
}

/// After this run's files are in place: removes the files an earlier run of the same .vdb path
/// wrote (as its report listed them) that this run did not write (an earlier, longer run's tail,
/// or what an interrupted run did not reach), so the folder never mixes two runs
/// (docs/reliability.md). Files named like the sequence that no report listed are left, with a
/// note. Says what it did.
void removeEarlierSequence(const std::string& vdbPath, const std::vector<std::string>& written,
                           const std::vector<std::string>& earlier) {
    namespace fs = std::filesystem;
    const std::string folder = folderOf(vdbPath);
    const std::string stem = fs::path(vdbPath).stem().string();
    std::vector<std::string> kept, listed;
    for (const std::string& w : written) kept.push_back(fs::path(w).filename().string());
    for (const std::string& e : earlier)
        if (folderOf(e) == folder) listed.push_back(fs::path(e).filename().string());
    std::vector<std::string> removed, unknown;
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (!isSequenceFileOf(name, stem) || !it->is_regular_file(ec) ||
            std::find(kept.begin(), kept.end(), name) != kept.end())
            continue;
        if (std::find(listed.begin(), listed.end(), name) == listed.end()) {
            unknown.push_back(name);
            continue;
        }
        std::error_code rm;
        if (fs::remove(it->path(), rm)) removed.push_back(name);
    }
    std::sort(removed.begin(), removed.end());
    std::sort(unknown.begin(), unknown.end());
    if (!removed.empty())
        std::fprintf(stderr,
                     "gale: note: removed %zu .vdb file%s of the earlier sequence in %s that this "
                     "run did not write (%s .. %s), so the folder holds this run's sequence only\n",
                     removed.size(), removed.size() == 1 ? "" : "s", folder.c_str(),
                     removed.front().c_str(), removed.back().c_str());
    if (!unknown.empty())
        std::fprintf(stderr,
                     "gale: note: %s holds %zu file%s named like this run's sequence that no "
                     "earlier report lists (e.g. %s); they are left as they are\n",
                     folder.c_str(), unknown.size(), unknown.size() == 1 ? "" : "s",
                     unknown.front().c_str());
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
    const double initialEnergy_m5ps2 = solver.kineticEnergy_m5ps2();

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
    const std::vector<std::string> earlierSequence = sequenceOfEarlierReport(req.reportPath);
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
    // Vorticity confinement (Fedkiw, Stam, Jensen 2001) adds energy at vortex cores; a strength
    // the grid cannot take grows the whole flow's energy (100 drove the peak from 6 to 255 m/s).
    // The run still writes its files but is not a result: exit 3, with the reason.
    double peakEnergy_m5ps2 = initialEnergy_m5ps2;
    for (const auto& step : steps)
        peakEnergy_m5ps2 = std::max(peakEnergy_m5ps2, step["kinetic_energy_m5ps2"].get<double>());
    const bool confinementGrew =
        s.vorticityConfinement > 0.0 && initialEnergy_m5ps2 > 0.0 &&
        peakEnergy_m5ps2 > MAX_CONFINED_ENERGY_GROWTH * initialEnergy_m5ps2;
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
    const std::string energyNote =
        confinementGrew ? "vorticity confinement " + formatNumber(s.vorticityConfinement) +
                              " grew the kinetic energy " +
                              formatNumber(peakEnergy_m5ps2 / initialEnergy_m5ps2) +
                              "-fold (limit " + formatNumber(MAX_CONFINED_ENERGY_GROWTH) +
                              "): the field is not a result; lower unsteady.vorticity_confinement"
                        : std::string();
    if (confinementGrew) j["summary"]["problem"] = energyNote;
    j["total_s"] = secondsSince(t0);
    if (!req.reportPath.empty()) writeStagedText(staged, req.reportPath, j.dump(2) + "\n");
    staged.commit();
    if (!req.vdbPath.empty()) {
        std::vector<std::string> written = houdiniPaths;
        for (const auto& f : frames) written.push_back(f["path"].get<std::string>());
        removeEarlierSequence(req.vdbPath, written, earlierSequence);
    }
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
    if (confinementGrew) std::printf("solve: %s\n", energyNote.c_str());
    if (interruptSignal())
        return reportInterruptedWhileWriting(
            req.vdbPath.empty()
                ? std::string()
                : sequencePath(req.vdbPath, 0) + " .. " + frames.back()["path"].get<std::string>(),
            req.reportPath);
    return ok && !confinementGrew ? EXIT_OK : EXIT_UNMET;
}

}  // namespace gale::app
