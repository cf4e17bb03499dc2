/// \file CommandsSolve.cpp
/// `gale solve SCENE [-o FILE.vdb]`: the scene's steady wind as a .vdb field and a JSON report
/// (docs/solver.md); for wind.kind = "unsteady" a .vdb sequence <stem>_0000.vdb ... with per-step
/// reports (docs/unsteady.md, run by app/CommandsSolveUnsteady.cpp). runSolveVerb builds a
/// SolveRequest from the scene; runSolve does the work.

#include <unistd.h>

#include <algorithm>
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
#include "app/MomentumJson.h"
#include "app/SolveRun.h"
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

std::string houdiniPath(const std::string& vdbPath, double fps, double t_s) {
    char num[32];
    std::snprintf(num, sizeof num, ".%04ld.vdb", std::lround(t_s * fps) + 1);
    return std::filesystem::path(vdbPath).replace_extension("").string() + "_houdini" + num;
}

std::string rasterStem(const std::string& vdbPath, double height_m) {
    char suffix[64];
    std::snprintf(suffix, sizeof suffix, "_%gm", height_m);
    return std::filesystem::path(vdbPath).replace_extension("").string() + suffix;
}

std::string folderOf(const std::string& path) {
    const auto parent = std::filesystem::path(path).parent_path();
    return parent.empty() ? std::string(".") : parent.string();
}

std::unique_ptr<OutputLock> prepareSolveOutputs(const SolveRequest& req) {
    for (const std::string& path : {req.vdbPath, req.reportPath})
        if (!path.empty()) std::filesystem::create_directories(folderOf(path));
    if (req.vdbPath.empty()) return nullptr;
    auto lock = std::make_unique<OutputLock>(folderOf(req.vdbPath), req.outputWhere);
    removeStaleTemporaries(folderOf(req.vdbPath));
    return lock;
}

double writeStagedVdb(StagedFiles& staged, const sim::WindField& field, const std::string& path,
                      const sim::VdbMetadata& meta, std::vector<std::string>* gridNames,
                      const std::vector<double>& tke_m2ps2) {
    const std::string tmp = staged.add(path);
    try {
        field.writeVdb(tmp, meta, tke_m2ps2);
    } catch (const std::runtime_error& e) {
        // WindField::writeVdb says "cannot write VDB file 'TMP': REASON": keep the reason.
        std::string reason = e.what();
        const size_t at = reason.find("': ");
        if (at != std::string::npos) reason = reason.substr(at + 3);
        throw std::runtime_error(path + ": cannot write: " + reason);
    }
    const double bytes = staged.seal(path);
    if (gridNames) *gridNames = sim::vdbGridNames(tmp);
    return bytes;
}

nlohmann::json vdbGridDescriptions(const std::vector<std::string>& names) {
    nlohmann::json out = nlohmann::json::array();
    for (const std::string& name : names) {
        const char* what =
            name == "velocity"         ? " (vec3s, m/s, world axes, cell centres)"
            : name == "speed"          ? " (float, m/s, cell centres)"
            : name == "velocity_faces" ? " (vec3s, m/s, staggered: the MAC face velocities)"
            : name == "velocity_layers"
                ? " (vec3s, m/s, the MAC faces of the stretched layers; metadata "
                  "z_levels_m)"
            : name == sim::TKE_GRID ? " (float, m^2/s^2, turbulent kinetic energy k, cell centres)"
            : name == sim::TKE_LAYERS_GRID
                ? " (float, m^2/s^2, turbulent kinetic energy k on the stretched "
                  "layers' cells; metadata z_levels_m)"
                : "";
        out.push_back(name + what);
    }
    return out;
}

nlohmann::json domainJson(const sim::AirDomain& domain, const Scene& scene) {
    const auto o = domain.wsMin_m();
    nlohmann::json j = {{"cells", {domain.nx(), domain.ny(), domain.nz()}},
                        {"voxel_size_m", domain.voxelSize_m()},
                        {"ws_min_m", {o[0], o[1], o[2]}},
                        {"ws_top_m", domain.wsTop_m()},
                        {"box_cells", domain.boxCellCount()},
                        {"air_cells", domain.activeCellCount()},
                        {"memory_estimate_bytes", domain.memoryEstimate_bytes()},
                        {"memory_limit_bytes", scene.solver.domain.memoryLimit_bytes},
                        {"domain_bytes", domain.memory_bytes()},
                        {"vdb_mask_bytes", domain.vdbMemory_bytes()}};
    const sim::GridLayout& g = domain.layout();
    if (g.uniformZ()) {
        j["layers"] = {{"kind", "cubic"}, {"count", domain.nz()}};
    } else {
        const sim::DomainSpec& spec = scene.solver.domain;
        j["layers"] = {{"kind", "stretched"},
                       {"count", domain.nz()},
                       {"first_cell_m", g.dz_m(0)},
                       {"stretch_ratio", spec.stretchRatio},
                       {"max_cell_m", g.dz_m(domain.nz() - 1)},
                       {"z_levels_m", g.zLevels_m()}};
    }
    // The standard grids' voxels: the cells for cubic cells, the cubic resample for layers.
    j["vdb_voxels"] = {domain.nx(), domain.ny(), sim::vdbCubicLayers(domain.layout())};
    return j;
}

nlohmann::json provenanceJson(const FieldProvenance& p) {
    nlohmann::json j;
    for (const auto& [key, value] : p.metadata()) j[key.substr(5)] = value;  // without "gale_"
    return j;
}

int reportStoppedSolve(const SolveRequest& req, const SceneField& sf, nlohmann::json j) {
    j["interrupted"] = true;
    j["stopped_by"] = interruptSignalName();
    j["outputs"] = nlohmann::json::object();  // no field: a stopped solve is no answer
    if (!req.reportPath.empty()) {
        const std::unique_ptr<OutputLock> lock = prepareSolveOutputs(req);
        StagedFiles staged;
        writeStagedText(staged, req.reportPath, j.dump(2) + "\n");
        staged.commit();
    }
    std::printf("solve: interrupted (%s): %s; no field written%s%s\n", interruptSignalName(),
                sf.summary().c_str(), req.reportPath.empty() ? "" : ", the report says how far: ",
                req.reportPath.c_str());
    return interruptExitCode();
}

int runSolve(const SolveRequest& req) {
    if (req.unsteady) return runUnsteadySolve(req);
    const Scene& scene = *req.scene;
    const auto t0 = Clock::now();
    checkSceneFieldInputs(scene);
    InterruptScope interrupt("while building the air domain: nothing written");
    // No progress line before the domain has validated its inputs: bad input gets one line only.
    std::unique_ptr<sim::AirDomain> domainPtr = buildSceneDomain(scene, req.terrain);
    const sim::AirDomain& domain = *domainPtr;
    const double domainSeconds = secondsSince(t0);
    std::fprintf(stderr, "solve: %d x %d x %d cells, %zu air, estimate %.0f MiB; solving...\n",
                 domain.nx(), domain.ny(), domain.nz(), domain.activeCellCount(),
                 domain.memoryEstimate_bytes() / MIB);
    for (const std::string& line : describeSceneField(scene, domain))
        std::fprintf(stderr, "solve: %s\n", line.c_str());
    // The momentum model's pseudo-time steps poll for a signal and stop with a report of how far
    // they got; the mass-consistent solve (seconds) stops at once with nothing written.
    const bool momentum = scene.solver.model == sim::SteadyModel::Momentum;
    if (momentum)
        interrupt.defer();
    else
        interrupt.exitAtOnce("while solving: nothing written");
    SceneField sf = solveSceneField(scene, std::move(domainPtr), verbFieldOptions("solve"));
    interrupt.defer();  // from here both files are completed, then the run stops
    const sim::SolveReport& rep = sf.report;
    const FieldProvenance provenance = fieldProvenance(scene, req.terrain);

    nlohmann::json j;
    j["scene"] = req.sceneName;
    j["model"] = sf.modelText;
    j["what_ran"] = describeSceneField(scene, domain);
    j["provenance"] = provenanceJson(provenance);
    if (sf.momentum) j["momentum"] = momentumJson(*sf.momentum, scene.solver.momentum);
    j["domain"] = domainJson(domain, scene);
    j["domain"]["solver_bytes"] = sf.solverMemory_bytes;
    const sim::AmbientWind& ambient = scene.wind.ambient;
    j["ambient"] = {{"speed_mps", ambient.speed_mps},
                    {"reference_height_m", ambient.referenceHeight_m},
                    {"direction_deg", ambient.direction_deg},
                    {"direction_convention", "towards, counter-clockwise from +x"},
                    {"profile", sim::windProfileName(ambient.profile)},
                    {"roughness_m", ambient.roughness_m}};
    j["weights"] = {{"alpha_h", scene.solver.weights.alphaH},
                    {"alpha_v", scene.solver.weights.alphaV}};
    const sim::SolverSettings& settings = scene.solver.settings;
    j["solver"] = {{"model", sim::steadyModelName(scene.solver.model)},
                   {"relative_tolerance", settings.relativeTolerance},
                   {"max_iterations", settings.maxIterations},
                   {"smoothing_sweeps", settings.smoothingSweeps},
                   {"multigrid", settings.useMultigrid},
                   {"residual_norm", "max-norm of b - A x over max-norm of b"}};
    j["report"] = {{"converged", rep.converged},
                   {"iterations", rep.iterations},
                   {"relative_residual", rep.relativeResidual},
                   {"initial_relative_residual", rep.initialRelativeResidual},
                   {"max_div_u_h_over_U", rep.maxDivergenceScaled},
                   {"levels", rep.levels},
                   {"message", rep.message},
                   {"summary", sf.summary()},
                   {"domain_s", domainSeconds},
                   {"setup_s", rep.setupSeconds},
                   {"solve_s", rep.solveSeconds}};
    if (sf.stopped()) return reportStoppedSolve(req, sf, j);
    const std::unique_ptr<OutputLock> lock = prepareSolveOutputs(req);
    StagedFiles staged;  // both files move into place together, or neither
    if (!req.vdbPath.empty()) {
        sim::VdbMetadata meta;
        meta.strings = {{"scene", req.sceneName}, {"converged", rep.converged ? "yes" : "no"}};
        for (const auto& kv : provenance.metadata()) meta.strings.push_back(kv);
        meta.numbers = {{"iterations", double(rep.iterations)},
                        {"relative_residual", rep.relativeResidual},
                        {"max_div_u_h_over_U", rep.maxDivergenceScaled}};
        std::vector<std::string> grids;
        writeStagedVdb(staged, sf.field, req.vdbPath, meta, &grids, sf.tke_m2ps2);
        if (req.houdiniFps > 0.0) {
            const std::string path = houdiniPath(req.vdbPath, req.houdiniFps, 0.0);
            sim::writeHoudiniVdb(path, sf.field, req.terrain);
            j["outputs"]["houdini"] = {
                {"paths", nlohmann::json::array({path})},
                {"grids", {"vel (vec3s, m/s, y-up)", "surface (level set of the terrain, y-up)"}},
                {"axes", "houdini (x, y, z) = gale (x, z, -y)"}};
        }
        j["outputs"]["vdb"] = {
            {"path", req.vdbPath},
            {"grids", vdbGridDescriptions(grids)},
            {"placement",
             domain.layout().uniformZ()
                 ? "cell-centred averages of the MAC face velocities; voxel (i,j,k) centre at "
                   "ws_min_m + (i+0.5, j+0.5, k+0.5) * voxel_size_m"
                 : "velocity and speed: a cubic resample (domain.vdb_voxels) sampled at voxel "
                   "centres ws_min_m + (i+0.5, j+0.5, k+0.5) * voxel_size_m; velocity_layers: "
                   "the MAC faces of the stretched layers, voxel k = layer k (domain.layers)"},
            {"grid_class", "GRID_UNKNOWN"},
            {"vector_type", "VEC_CONTRAVARIANT_RELATIVE"}};
    }
    for (const double height_m : req.gridHeights_m) {
        const std::string stem = rasterStem(req.vdbPath, height_m);
        const std::vector<std::string> paths =
            writeWindRasters(sf.field, req.terrain, req.georef, height_m, stem, sf.tke_m2ps2);
        nlohmann::json bands = {"speed_mps (float32)",
                                "from_deg (float32, meteorological, .tif only)"};
        if (!sf.tke_m2ps2.empty())
            for (const char* b : {"tke_m2ps2 (float32, turbulent kinetic energy k, .tif only)",
                                  "turbulence_intensity (float32, sqrt(2k/3) / speed, .tif only)",
                                  "gust_mps (float32, speed + 3.5 sqrt(2k/3), .tif only)"})
                bands.push_back(b);
        j["outputs"]["rasters"].push_back(
            {{"height_agl_m", height_m},
             {"paths", paths},
             {"bands", bands},
             {"turbulence", sf.tke_m2ps2.empty()
                                ? "none: the mass-consistent model has no turbulence"
                                : "bands 3-5 of the .tif: k, intensity and gust at the height"},
             {"crs", req.georef.georeferenced() ? req.georef.crsName : "none (not a DEM scene)"},
             {"nodata", WIND_RASTER_NODATA}});
        for (const std::string& p : paths) std::printf("solve: wrote %s\n", p.c_str());
    }
    j["total_s"] = secondsSince(t0);
    j["domain"]["peak_resident_bytes"] = peakResidentBytes();  // beside the estimate
    if (!req.reportPath.empty()) writeStagedText(staged, req.reportPath, j.dump(2) + "\n");
    staged.commit();
    std::printf("solve: %s (%d x %d x %d cells, %zu air, %.2f s in all)\n", sf.summary().c_str(),
                domain.nx(), domain.ny(), domain.nz(), domain.activeCellCount(),
                j["total_s"].get<double>());
    if (!rep.converged) std::printf("solve: %s\n", rep.message.c_str());
    if (interruptSignal()) return reportInterruptedWhileWriting(req.vdbPath, req.reportPath);
    return rep.converged ? EXIT_OK : EXIT_UNMET;
}

std::string sequencePath(const std::string& vdbPath, int frame) {
    std::filesystem::path p(vdbPath);
    char num[32];
    std::snprintf(num, sizeof num, "_%04d", frame);
    const std::string name = p.stem().string() + num + ".vdb";
    return p.has_parent_path() ? (p.parent_path() / name).string() : name;
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
    request.scene = &scene;
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
        // The report is text: a device or FIFO (/dev/null) is written as a stream.
        std::vector<RunPath> outputs{
            {request.reportPath, reportWhere + " (the report)", /*streamable=*/true}};
        if (request.unsteady) {
            const int files =
                int(std::ceil(request.unsteady->duration_s / request.unsteady->outputEvery_s -
                              1e-9)) +
                1;
            for (int n = 0; n < files && n < MAX_ALIAS_CHECKED_FILES; ++n) {
                outputs.push_back(
                    {sequencePath(request.vdbPath, n), vdbWhere + " (a .vdb of the sequence)"});
                if (request.houdiniFps > 0.0)
                    outputs.push_back({houdiniPath(request.vdbPath, request.houdiniFps,
                                                   std::min(request.unsteady->duration_s,
                                                            n * request.unsteady->outputEvery_s)),
                                       "--houdini (a Houdini .vdb of the sequence)"});
            }
        } else {
            outputs.push_back({request.vdbPath, vdbWhere + " (the .vdb field)"});
            if (request.houdiniFps > 0.0)
                outputs.push_back({houdiniPath(request.vdbPath, request.houdiniFps, 0.0),
                                   "--houdini (the Houdini .vdb)"});
        }
        std::vector<std::string> stems;
        for (const double height_m : request.gridHeights_m) {
            if (!std::isfinite(height_m))
                throw InputError("--grid-height-m: must be a finite height in metres (got " +
                                 std::to_string(height_m) + ")");
            const std::string stem = rasterStem(request.vdbPath, height_m);
            // Heights that print alike (10 and 10.0, or 10.0000001 and 10.0000002) would write
            // one set of files twice, the second over the first.
            if (std::find(stems.begin(), stems.end(), stem) != stems.end())
                throw InputError("--grid-height-m: two heights write the same files '" + stem +
                                 ".tif' (heights are named to 6 significant digits); give "
                                 "each height once, differing in its first 6 digits");
            stems.push_back(stem);
            const std::string role = "--grid-height-m " + fs::path(stem).filename().string();
            std::vector<std::string> files;  // the rasters and every file GDAL may put beside
            for (const char* ext : {".tif", ".asc"}) {
                const std::string raster = stem + ext;
                outputs.push_back({raster, role + " (the " + ext + " raster)"});
                for (const std::string& side : rasterSidecars(raster))
                    if (std::find(files.begin(), files.end(), side) == files.end())
                        files.push_back(side);
            }
            for (const std::string& side : files)
                outputs.push_back({side, role + " (beside the rasters)"});
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
