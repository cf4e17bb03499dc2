#pragma once
// Helpers shared by the app tests: fresh temporary folders, running the gale binary, and the
// message of a scene that fails to parse.

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "TestFiles.h"
#include "app/Errors.h"
#include "app/SceneParser.h"

namespace gale::app::test {

namespace fs = std::filesystem;

using gale::test::TempDir;
using gale::test::readFile;
using gale::test::writeFile;

inline std::string quote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

struct RunResult {
    int exitCode = -1;
    std::string out;
    std::string err;
};

/// Runs GALE_EXE with `args` (each quoted for the shell) in folder `cwd`, capturing both streams.
inline RunResult runGale(const std::vector<std::string>& args, const std::string& cwd = "") {
    TempDir capture;
    std::string cmd;
    if (!cwd.empty()) cmd += "cd " + quote(cwd) + " && ";
    cmd += quote(GALE_EXE);
    for (const std::string& a : args) cmd += " " + quote(a);
    cmd += " >" + quote(capture / "out") + " 2>" + quote(capture / "err") + " </dev/null";
    const int status = std::system(cmd.c_str());
    RunResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readFile(capture / "out");
    r.err = readFile(capture / "err");
    return r;
}

using gale::test::sourcePath;

inline int countLines(const std::string& text) {
    int n = 0;
    for (char c : text) n += (c == '\n');
    return n;
}

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
