/// \file CommandsSolve.cpp
/// `gale solve SCENE [-o FILE.vdb]`: the scene's steady wind as a .vdb field and a JSON report; for
/// wind.kind = "unsteady" a .vdb sequence <stem>_0000.vdb ... with per-step reports
/// (the work is in SolveCommand.cpp; this builds the request from the scene).

#include <filesystem>
#include <stdexcept>
#include <string>

#include "app/Commands.h"
#include "app/Errors.h"
#include "app/OutputFolder.h"
#include "app/SceneBuilder.h"
#include "app/SolveCommand.h"

namespace gale::app {

namespace fs = std::filesystem;

int runSolveVerb(const SolveVerbOptions& options) {
    SceneRunOptions sceneOptions;
    sceneOptions.scenePath = options.scenePath;
    const Scene scene = loadScene(sceneOptions);
    SolveRequest request;
    request.terrain = buildHeightfield(scene);
    request.ambient = scene.wind.ambient;
    request.domain = scene.solver.domain;
    request.weights = scene.solver.weights;
    request.solver = scene.solver.settings;
    request.sceneName = scene.name;
    if (scene.wind.kind == WindKind::Unsteady)
        request.unsteady = UnsteadySolveRequest{scene.unsteady.settings, scene.unsteady.duration_s,
                                                scene.unsteady.outputEvery_s};
    request.vdbPath = options.vdbPath.empty()
                          ? (fs::path(scene.output.folder) / (scene.output.prefix + "_wind.vdb")).string()
                          : options.vdbPath;
    if (fs::path(request.vdbPath).extension() != ".vdb")
        throw InputError("-o: the field is written as OpenVDB; the file name must end in .vdb (got '" +
                         request.vdbPath + "')");
    request.reportPath = options.reportPath.empty()
                             ? fs::path(request.vdbPath).replace_extension(".json").string()
                             : options.reportPath;
    // Each folder must be a folder or creatable (checked, not created): nothing is created for a
    // run that fails on input. runSolve creates them just before it writes.
    const std::string vdbWhere = options.vdbPath.empty() ? scene.where("output.folder") : "-o";
    for (const std::string& path : {request.vdbPath, request.reportPath}) {
        const fs::path folder = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
        std::error_code ec;
        if (fs::exists(folder, ec) && !fs::is_directory(folder, ec))
            throw InputError("'" + folder.string() + "' is a file, not a folder (for " + path + ")");
        const bool isReport = path == request.reportPath && !options.reportPath.empty();
        checkOutputFolder(folder.string(), isReport ? "--report" : vdbWhere, scene.output.prefix, 0);
    }
    try {
        // The domain and solve validate their inputs (voxel size, memory limit, wind) before
        // allocating; a bad value is the scene's.
        return runSolve(request);
    } catch (const std::invalid_argument& e) {
        throw InputError(scene.where("solver") + ": " + e.what());
    }
}

}  // namespace gale::app
