/// \file CommandsSolve.cpp
/// `gale solve SCENE [-o FILE.vdb]`: the scene's steady wind as a .vdb field and a JSON report
/// (the work is in SolveCommand.cpp; this builds the request from the scene).

#include <filesystem>
#include <stdexcept>
#include <string>

#include "app/Commands.h"
#include "app/Errors.h"
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
    request.vdbPath = options.vdbPath.empty()
                          ? (fs::path(scene.output.folder) / (scene.output.prefix + "_wind.vdb")).string()
                          : options.vdbPath;
    if (fs::path(request.vdbPath).extension() != ".vdb")
        throw InputError("-o: the field is written as OpenVDB; the file name must end in .vdb (got '" +
                         request.vdbPath + "')");
    request.reportPath = options.reportPath.empty()
                             ? fs::path(request.vdbPath).replace_extension(".json").string()
                             : options.reportPath;
    // The folder must exist and be a folder: nothing is created for a run that fails on input.
    for (const std::string& path : {request.vdbPath, request.reportPath}) {
        const fs::path folder = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
        std::error_code ec;
        if (fs::exists(folder, ec) && !fs::is_directory(folder, ec))
            throw InputError("'" + folder.string() + "' is a file, not a folder (for " + path + ")");
    }
    try {
        // The domain and solve validate their inputs (voxel size, memory limit, wind) before
        // allocating; a bad value is the scene's.
        const fs::path folder = fs::path(request.vdbPath).parent_path();
        if (!folder.empty()) fs::create_directories(folder);
        return runSolve(request);
    } catch (const std::invalid_argument& e) {
        throw InputError(scene.path + ": " + e.what());
    } catch (const fs::filesystem_error& e) {
        throw InputError(std::string("cannot create the output folder: ") + e.what());
    }
}

}  // namespace gale::app
