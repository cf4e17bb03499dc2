// docs/tutorial.md's commands run as written: every ```sh block, in order, in an empty folder,
// with this build's gale first on PATH. A tutorial whose commands fail is a broken tutorial.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

#include "AppTestSupport.h"

namespace gale::app {
namespace {

using test::TempDir;

/// The ```sh blocks of a Markdown text, joined in order.
std::string shellBlocks(const std::string& markdown) {
    std::istringstream in(markdown);
    std::string line, script;
    bool inside = false;
    int blocks = 0;
    while (std::getline(in, line)) {
        if (!inside && line == "```sh") {
            inside = true;
            ++blocks;
            continue;
        }
        if (inside && line == "```") {
            inside = false;
            continue;
        }
        if (inside) script += line + "\n";
    }
    return blocks > 0 ? script : "";
}

TEST(Tutorial, CommandsRun) {
    TempDir dir;
    const std::string script = shellBlocks(test::readFile(test::sourcePath("docs/tutorial.md")));
    ASSERT_FALSE(script.empty()) << "docs/tutorial.md has no sh blocks";
    test::writeFile(dir / "tutorial.sh", "set -euo pipefail\n" + script);
    const std::string bin = std::filesystem::path(GALE_EXE).parent_path().string();
    const std::string command =
        "cd '" + dir.str() + "' && PATH='" + bin + "':\"$PATH\" bash tutorial.sh > log.txt 2>&1";
    const int status = std::system(command.c_str());
    const std::string log = test::readFile(dir / "log.txt");
    ASSERT_EQ(status, 0) << log;
    // What the tutorial tells the reader they will see.
    EXPECT_NE(log.find("UTM zone 32N"), std::string::npos) << log;
    EXPECT_NE(log.find("from 270 deg = towards 90 deg, counter-clockwise from +x 0 deg"),
              std::string::npos)
        << log;
    EXPECT_TRUE(std::filesystem::exists(dir / "out/wind_10m.tif")) << log;
    EXPECT_TRUE(std::filesystem::exists(dir / "out/frames/frame_0001.png")) << log;
    const std::string masts = test::readFile(dir / "out/masts.csv");
    EXPECT_NE(masts.find("summit"), std::string::npos) << masts;
}

}  // namespace
}  // namespace gale::app
