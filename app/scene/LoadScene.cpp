/// \file LoadScene.cpp
/// Scene loading shared by the scene verbs.

#include "app/scene/LoadScene.h"

#include "app/io/Errors.h"
#include "app/scene/SceneParser.h"

namespace gale::app {

Scene loadScene(const SceneRunOptions& options) {
    Scene scene = parseSceneFile(options.scenePath);
    OutputSection& o = scene.output;
    if (!options.folder.empty()) o.folder = options.folder;
    if (options.frames) o.frames = *options.frames;
    if (options.width) o.width = *options.width;
    if (options.height) o.height = *options.height;
    if (options.frames || options.width || options.height) {
        if (auto problem = outputBudgetProblem(o))
            throw InputError(
                std::string(problem->key == "frames" ? "--frames" : "--width/--height") + ": " +
                problem->reason);
    }
    return scene;
}

std::string outputFolderSource(const Scene& scene, const SceneRunOptions& options) {
    return options.folder.empty() ? scene.where("output.folder") : std::string("-o");
}

}  // namespace gale::app
