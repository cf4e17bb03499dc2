#pragma once
/// \file LoadScene.h
/// The one entry every scene verb uses: parse a scene file and apply the command line's
/// overrides of its [output] section, checked as the parser checks the scene.

#include <optional>
#include <string>

#include "app/scene/Scene.h"

namespace gale::app {

/// A scene and the command-line overrides of its [output] section.
struct SceneRunOptions {
    std::string scenePath;
    std::string folder;  ///< -o; empty: the scene's output.folder
    std::optional<int> frames;
    std::optional<int> width;
    std::optional<int> height;
};

/// Parses the scene and applies the overrides. Throws SceneError (bad scene) or InputError (an
/// override out of range, named by its option).
Scene loadScene(const SceneRunOptions& options);

/// Where the output folder came from, for messages: "FILE:LINE: output.folder" or "-o".
std::string outputFolderSource(const Scene& scene, const SceneRunOptions& options);

}  // namespace gale::app
