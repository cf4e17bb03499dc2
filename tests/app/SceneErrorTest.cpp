// A library's gale::ParameterError reaches the user at FILE:LINE of the key it names: the key's
// own line, its enclosing key's line for an element ("terrain.size_m[0]"), or its section's line
// marked "the default" when the scene left the key out. A plain std::invalid_argument (data no
// key holds) is placed at the caller's fallback key.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "app/io/Errors.h"
#include "app/scene/SceneBuilder.h"
#include "app/scene/SceneParser.h"
#include "base/ParameterError.h"

namespace gale::app {
namespace {

const char* const SCENE =
    "# line 1\n"
    "[terrain]\n"            // 2
    "size_m = [8.0, 6.0]\n"  // 3
    "spacing_m = 0.5\n"      // 4
    "\n"                     // 5
    "[solver]\n"             // 6
    "voxel_size_m = 2.0\n"   // 7
    "\n"                     // 8
    "[wind]\n"               // 9
    "kind = \"solved\"\n"    // 10
    "[[wind.gusts]]\n"       // 11
    "peak_mps = 2.0\n"       // 12
    "[[wind.gusts]]\n"       // 13
    "duration_s = 2.0\n";    // 14

/// The message of the SceneError rethrowAsSceneError makes of `error` in SCENE (only its lines
/// matter: the errors are made up).
std::string placed(const std::string& fallbackKey, const std::invalid_argument& error) {
    const Scene scene = parseSceneString(SCENE, "s.toml");
    try {
        rethrowAsSceneError(scene, fallbackKey, error);
    } catch (const SceneError& e) {
        return e.what();
    }
    ADD_FAILURE() << "rethrowAsSceneError returned";
    return {};
}

TEST(SceneError, ParameterErrorIsPlacedAtTheLineOfItsKey) {
    EXPECT_EQ(placed("solver", ParameterError("solver.voxel_size_m", "2", "must be smaller")),
              "s.toml:7: solver.voxel_size_m: must be smaller (got 2)");
    // An element of an array key sits on the array's line.
    EXPECT_EQ(placed("terrain", ParameterError("terrain.size_m[1]", "-1", "must be > 0")),
              "s.toml:3: terrain.size_m[1]: must be > 0 (got -1)");
    // An element of an array of tables: that table's key.
    EXPECT_EQ(placed("wind", ParameterError("wind.gusts[1].duration_s", "2", "must be longer")),
              "s.toml:14: wind.gusts[1].duration_s: must be longer (got 2)");
}

TEST(SceneError, ADefaultIsPlacedAtItsSectionAndSaysSo) {
    EXPECT_EQ(placed("solver", ParameterError("solver.top_m", "9", "must be above the terrain")),
              "s.toml:6: solver.top_m: must be above the terrain (got 9, the default)");
    EXPECT_EQ(placed("wind", ParameterError("wind.gusts[0].duration_s", "4", "must be longer")),
              "s.toml:11: wind.gusts[0].duration_s: must be longer (got 4, the default)");
}

TEST(SceneError, OtherErrorsArePlacedAtTheFallbackKey) {
    EXPECT_EQ(placed("terrain", std::invalid_argument("height at sample (1, 2) is nan")),
              "s.toml:2: terrain: height at sample (1, 2) is nan");
    // A key of a section the scene does not have: its fallback's line.
    EXPECT_EQ(placed("wind", ParameterError("camera.fov_deg", "0", "must be in (0, 180)")),
              "s.toml:9: camera.fov_deg: must be in (0, 180) (got 0, the default)");
}

TEST(SceneError, ParserPlacesALibraryCheckAtTheKeyOfTheElement) {
    try {
        (void)parseSceneString(std::string(SCENE) + "attack_s = 3.0\n", "s.toml");
        ADD_FAILURE() << "a gust rising for longer than it lasts was accepted";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "s.toml:15: wind.gusts[1].attack_s: must be in (0, duration_s = 2) (got 3)");
    }
    try {
        (void)parseSceneString("[wind]\nkind = \"solved\"\nroughness_m = 5.0\n", "s.toml");
        ADD_FAILURE() << "a reference height under 3 roughness lengths was accepted";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("s.toml:1: wind.reference_height_m: "),
                  std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("(got 10 m, the default)"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace gale::app
