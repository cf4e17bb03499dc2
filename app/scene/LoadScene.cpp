/// \file LoadScene.cpp
/// Scene loading shared by the scene verbs.

#include "app/scene/LoadScene.h"

#include <algorithm>

#include "app/io/Errors.h"
#include "app/io/ProcessMemory.h"
#include "app/scene/SceneParser.h"

namespace gale::app {

Scene loadScene(const SceneRunOptions& options) {
    Scene scene = parseSceneFile(options.scenePath);
    OutputSection& o = scene.output;
    if (!options.folder.empty()) o.folder = options.folder;
    o.duration_s = static_cast<double>(o.frames) / o.fps;  // before --frames (Scene.h)
    if (options.frames) o.frames = *options.frames;
    if (options.width) o.width = *options.width;
    if (options.height) o.height = *options.height;
    if (options.frames || options.width || options.height) {
        if (auto problem = outputBudgetProblem(o))
            throw InputError(
                std::string(problem->key == "frames" ? "--frames" : "--width/--height") + ": " +
                problem->reason);
    }
    // The solve's memory estimate and limit count the whole run: the program as it stands now
    // (libraries, scene) and, for unsteady scenes, the time stepper's arrays.
    sim::DomainSpec& domain = scene.solver.domain;
    if (scene.wind.kind == WindKind::Unsteady)
        domain.run = sim::unsteadyRunMemory(scene.unsteady.settings);
    if (scene.solver.model == sim::SteadyModel::Momentum)
        domain.run.closureCellBytes =
            std::max(domain.run.closureCellBytes,
                     sim::TurbulentStress::closureBytesPerCell(scene.solver.momentum.turbulence));
    domain.run.processBaseline_bytes = residentBytes();
    return scene;
}

std::string outputFolderSource(const Scene& scene, const SceneRunOptions& options) {
    return options.folder.empty() ? scene.where("output.folder") : std::string("-o");
}

}  // namespace gale::app
