#pragma once
// Helpers shared by the app tests: fresh temporary folders, the program (tests/GaleProcess.h),
// and the message of a scene that fails to parse.

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "GaleProcess.h"
#include "TestFiles.h"
#include "app/io/Errors.h"
#include "app/scene/SceneParser.h"

namespace gale::app::test {

namespace fs = std::filesystem;

using gale::test::readFile;
using gale::test::TempDir;
using gale::test::writeFile;

using gale::test::runGale;
using gale::test::RunResult;

using gale::test::sourcePath;

using gale::test::countLines;

/// Files directly in `folder`; 0 if it does not exist.
inline int countFiles(const std::string& folder) {
    std::error_code ec;
    if (!fs::exists(folder, ec)) return 0;
    int n = 0;
    for (const auto& e : fs::directory_iterator(folder, ec)) {
        (void)e;
        ++n;
    }
    return n;
}

/// Parses `text` as "scene.toml" and returns the SceneError message ("" if it parsed).
inline std::string errorOf(const std::string& text) {
    try {
        parseSceneString(text, "scene.toml");
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

}  // namespace gale::app::test
