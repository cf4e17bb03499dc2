#pragma once
// The reliability tests' view of the program: tests/GaleProcess.h runs it.

#include <chrono>
#include <functional>
#include <thread>

#include "GaleProcess.h"

namespace gale::reliability {

namespace fs = std::filesystem;

using gale::test::Child;
using gale::test::countLines;
using gale::test::describeTree;
using gale::test::listTree;
using gale::test::readFile;
using gale::test::runGale;
using gale::test::RunOptions;
using gale::test::RunResult;
using gale::test::sourcePath;
using gale::test::TempDir;
using gale::test::writeFile;

/// Files under `folder` that a finished run must not leave: temporaries are hidden
/// (".name.tmp-...") or carry ".tmp" (VDB); the lock is ".gale.lock".
inline std::vector<std::string> hiddenOrTemporary(const std::string& folder) {
    std::vector<std::string> out;
    for (const auto& [rel, size] : listTree(folder)) {
        const std::string name = fs::path(rel).filename().string();
        if (name[0] == '.' || name.find(".tmp") != std::string::npos) out.push_back(rel);
    }
    return out;
}

/// Polls `ready` every 10 ms until it holds (true) or `timeout_s` seconds pass (false).
inline bool waitFor(const std::function<bool()>& ready, double timeout_s) {
    const auto start = std::chrono::steady_clock::now();
    while (!ready()) {
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
            timeout_s)
            return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return true;
}

}  // namespace gale::reliability
