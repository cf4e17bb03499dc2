// The scene format: examples parse, defaults apply, and every kind of bad input is a SceneError
// whose message says FILE:LINE, the key and the reason.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "AppTestSupport.h"
#include "app/io/Errors.h"
#include "app/scene/SceneParser.h"
#include "base/Numbers.h"

namespace gale::app {
namespace {

using test::TempDir;

using test::errorOf;

/// Expects the parse of `text` to fail with a message holding every fragment.
void expectError(const std::string& text, std::initializer_list<std::string> fragments) {
    const std::string message = errorOf(text);
    ASSERT_FALSE(message.empty()) << "parsed without error:\n" << text;
    for (const std::string& f : fragments)
        EXPECT_NE(message.find(f), std::string::npos) << "'" << f << "' not in: " << message;
}

TEST(SceneParser, EveryExampleSceneParses) {
    for (const char* name : {"knoll.toml", "valley_heightmap.toml", "valley_source.toml",
                             "fractal_meadow.toml", "landscape.toml", "landscape_source.toml"}) {
        SCOPED_TRACE(name);
        EXPECT_NO_THROW(parseSceneFile(test::sourcePath(std::string("examples/") + name)));
    }
}

TEST(SceneParser, CompleteSceneInTheFormatDocParses) {
    const std::string doc = test::readFile(test::sourcePath("docs/scene-format.md"));
    const std::string fence = "```toml\n";
    const size_t begin = doc.find(fence);
    ASSERT_NE(begin, std::string::npos) << "docs/scene-format.md has no ```toml block";
    const size_t end = doc.find("```", begin + fence.size());
    ASSERT_NE(end, std::string::npos);
    const std::string text = doc.substr(begin + fence.size(), end - begin - fence.size());
    const Scene s = parseSceneString(text, "docs/scene-format.md");
    EXPECT_EQ(s.grass.params.shells, 20);
    EXPECT_TRUE(s.notes.empty());
}

TEST(SceneParser, KnollIsTheDocumentedDefaultScene) {
    const Scene s = parseSceneFile(test::sourcePath("examples/knoll.toml"));
    EXPECT_EQ(s.name, "knoll");
    EXPECT_EQ(s.terrain.spec.kind, sim::TerrainKind::GaussianHill);
    EXPECT_EQ(s.grass.params.shells, 20);
    EXPECT_EQ(s.output.width, 640);
    EXPECT_EQ(s.output.height, 480);
    EXPECT_EQ(s.output.frames, 48);
    EXPECT_EQ(s.lighting.lights.size(), 2u);
    ASSERT_TRUE(s.wind.curve.has_value());
    EXPECT_DOUBLE_EQ(s.wind.curve->period_s(), 2.0);
}

TEST(SceneParser, EmptySceneTakesTheDocumentedDefaults) {
    const Scene s = parseSceneString("", "dir/empty.toml");
    EXPECT_EQ(s.name, "empty");
    EXPECT_EQ(s.terrain.spec.kind, sim::TerrainKind::GaussianHill);
    EXPECT_DOUBLE_EQ(s.terrain.spec.sizeX_m, 40.0);
    EXPECT_DOUBLE_EQ(s.terrain.spec.sizeY_m, 40.0);
    EXPECT_DOUBLE_EQ(s.terrain.spec.spacing_m, 0.25);
    EXPECT_DOUBLE_EQ(s.terrain.spec.height_m, 6.0);
    EXPECT_DOUBLE_EQ(s.terrain.spec.radius_m, 8.0);
    EXPECT_DOUBLE_EQ(s.terrain.spec.centerX_m, 20.0);  // the middle of the terrain
    EXPECT_DOUBLE_EQ(s.terrain.spec.centerY_m, 20.0);
    EXPECT_EQ(s.terrain.meshStride, 1);
    EXPECT_FLOAT_EQ(s.grass.params.height_m, 0.5f);
    EXPECT_EQ(s.grass.params.shells, 16);
    EXPECT_FLOAT_EQ(s.grass.params.stiffness, 1.0f);
    EXPECT_FLOAT_EQ(s.grass.params.tile_m, 3.0f);
    EXPECT_TRUE(s.grass.texturePath.empty());
    EXPECT_EQ(s.grass.generated.size, 256);
    EXPECT_EQ(s.wind.kind, WindKind::PointSource);
    EXPECT_TRUE(s.wind.autoSource);
    EXPECT_EQ(s.wind.pointSource.steps, 16);
    EXPECT_DOUBLE_EQ(s.wind.pointSource.stepDelay_s, 0.15);
    ASSERT_TRUE(s.wind.curve.has_value());
    EXPECT_DOUBLE_EQ(s.wind.curve->period_s(), 4.0);
    // No lights given: the documented sun, from the south-west and 40 deg up, and a sky.
    ASSERT_EQ(s.lighting.lights.size(), 1u);
    const glm::vec3 sun = s.lighting.lights[0].wsPosition_m;
    const float sunDistance_m = std::sqrt(sun.x * sun.x + sun.y * sun.y + sun.z * sun.z);
    constexpr float DIRECTION_TOLERANCE = 1e-5f;  // float positions 1e6 m away
    EXPECT_NEAR(sun.z / sunDistance_m, std::sin(float(radiansFromDegrees(40.0))),
                DIRECTION_TOLERANCE);
    EXPECT_NEAR(sun.x, sun.y, DIRECTION_TOLERANCE * sunDistance_m);  // azimuth 225 deg
    EXPECT_LT(sun.x, 0.0f);
    EXPECT_FLOAT_EQ(s.lighting.ambient.x, 0.30f);
    EXPECT_FLOAT_EQ(s.lighting.ambient.z, 0.40f);
    EXPECT_TRUE(s.autoCameraPosition);
    EXPECT_TRUE(s.autoCameraTarget);
    EXPECT_FLOAT_EQ(s.camera.fovY_deg, 45.0f);
    EXPECT_EQ(s.output.width, 640);
    EXPECT_EQ(s.output.height, 480);
    EXPECT_EQ(s.output.frames, 48);
    EXPECT_DOUBLE_EQ(s.output.fps, 24.0);
    EXPECT_EQ(s.output.folder, "out/empty");
    EXPECT_EQ(s.output.prefix, "frame");
}

TEST(SceneParser, IntegersAreAcceptedWhereNumbersAreExpected) {
    const Scene s = parseSceneString("[grass]\nheight_m = 1\n", "scene.toml");
    EXPECT_FLOAT_EQ(s.grass.params.height_m, 1.0f);
}

TEST(SceneParser, UnknownKeyNamesFileLineAndKeyWithSuggestion) {
    expectError("[grass]\nheight_m = 0.4\nshell = 4\n",
                {"scene.toml:3:", "grass.shell", "unknown key", "did you mean 'shells'"});
}

TEST(SceneParser, UnknownKeyInNestedTableIsAnError) {
    expectError("[grass.generated]\nsize = 64\nsead = 3\n",
                {"scene.toml:3:", "grass.generated.sead", "unknown key"});
    expectError("[[lighting.light]]\nposition_m = [0, 0, 1]\nbrightness = 2\n",
                {"scene.toml:3:", "lighting.light[0].brightness", "unknown key"});
}

TEST(SceneParser, UnknownSectionIsAnError) {
    expectError("[terrain]\nkind = \"flat\"\n\n[weather]\nrain_mm = 1\n",
                {"scene.toml:4:", "weather", "unknown section"});
}

TEST(SceneParser, WrongTypeNamesExpectedTypeAndValue) {
    expectError("[grass]\nshells = \"twenty\"\n",
                {"scene.toml:2:", "grass.shells", "expected an integer", "\"twenty\""});
    expectError("[grass]\nshells = 16.0\n", {"grass.shells", "expected an integer", "16.0"});
    expectError("[camera]\nposition_m = [1, 2]\n",
                {"camera.position_m", "expected an array of 3 numbers", "[1, 2]"});
    expectError("grass = 3\n", {"scene.toml:1:", "grass", "expected a table"});
    expectError("[terrain]\nkind = 4\n", {"terrain.kind", "expected a string"});
}

TEST(SceneParser, OutOfRangeValuesAreErrors) {
    expectError("[grass]\nshells = 0\n", {"scene.toml:2:", "grass.shells", "1..256", "(got 0)"});
    expectError("[grass]\nshells = 100000\n", {"grass.shells", "(got 100000)"});
    expectError("[grass]\nheight_m = -0.5\n", {"grass.height_m", "(got -0.5)"});
    expectError("[grass]\nstiffness = 0\n", {"grass.stiffness", "must be in (0, 100]"});
    expectError("[terrain]\nspacing_m = 0.0\n", {"terrain.spacing_m", "must be > 0", "(got 0.0)"});
    expectError("[terrain]\nsize_m = [40, -1]\n", {"terrain.size_m[1]", "(got -1)"});
    expectError("[output]\nwidth = 0\n", {"output.width", "(got 0)"});
    expectError("[output]\nwidth = 16385\n", {"output.width", "(got 16385)"});
    expectError("[output]\nframes = 100001\n", {"output.frames", "(got 100001)"});
    expectError("[grass.generated]\nsize = 100\n", {"grass.generated.size", "power of two"});
    expectError("[grass.generated]\ntip_color = [0.5, 1.5, 0.2]\n",
                {"grass.generated.tip_color[1]", "must be in [0, 1]"});
}

TEST(SceneParser, NanAndInfinityAreRejected) {
    expectError("[grass]\nheight_m = nan\n", {"scene.toml:2:", "grass.height_m", "(got nan)"});
    expectError("[camera]\nposition_m = [0, inf, 1]\n", {"camera.position_m[1]", "(got inf)"});
    expectError("[terrain]\naxis_deg = -inf\n", {"terrain.axis_deg", "must be a finite number"});
}

TEST(SceneParser, MalformedTomlGivesFileLineAndColumn) {
    const std::string message = errorOf("[terrain]\nkind = \"flat\n");
    EXPECT_EQ(message.rfind("scene.toml:2:", 0), 0u) << message;
    // FILE:LINE:COL: the line is followed by a column number.
    const size_t afterLine = std::string("scene.toml:2:").size();
    ASSERT_GT(message.size(), afterLine);
    EXPECT_TRUE(std::isdigit(static_cast<unsigned char>(message[afterLine]))) << message;
}

TEST(SceneParser, AbsurdTerrainIsRefusedBeforeAllocating) {
    expectError("[terrain]\nsize_m = [10000, 10000]\nspacing_m = 0.01\n",
                {"terrain.spacing_m", "1000001 x 1000001 samples", "at most 16384"});
    // Within 16384 per side, but heightfield plus mesh would need tens of GB.
    expectError("[terrain]\nsize_m = [40, 40]\nspacing_m = 0.003\n",
                {"terrain.spacing_m", "GiB", "raise spacing_m or mesh_stride"});
}

TEST(SceneParser, AbsurdOutputIsRefused) {
    expectError("[output]\nwidth = 16384\nheight = 16384\n", {"output.width", "of buffers"});
    expectError("[output]\nwidth = 8192\nheight = 8192\nframes = 100000\n",
                {"output.frames", "of PNG"});
}

TEST(SceneParser, GustKeysMustIncreaseAndFitThePeriod) {
    expectError("[wind.gust]\nperiod_s = 2\nkeys = [[0, 0.1], [0.8, 0.9], [0.5, 0.2]]\n",
                {"wind.gust.keys[2][0]", "increase strictly"});
    expectError("[wind.gust]\nperiod_s = 2\nkeys = [[0, 0.1], [2.5, 0.9]]\n",
                {"wind.gust.keys[1][0]", "< period_s"});
    expectError("[wind.gust]\nkeys = [[0, 0.1]]\npeak = 1\n", {"not both"});
    expectError("[wind.gust]\nperiod_s = 1\nattack_s = 0.6\ndecay_s = 0.6\n",
                {"wind.gust.decay_s", "shorter than period_s"});
}

TEST(SceneParser, GustKeysBuildTheCurveThroughTheKeys) {
    const Scene s = parseSceneString(
        "[wind.gust]\nperiod_s = 2\nkeys = [[0, 0.1], [0.5, 0.9], [1.2, 0.2]]\n", "scene.toml");
    ASSERT_TRUE(s.wind.curve.has_value());
    constexpr double KEY_TOLERANCE = 1e-12;  // a Hermite spline passes exactly through its keys
    EXPECT_NEAR((*s.wind.curve)(0.5), 0.9, KEY_TOLERANCE);
    EXPECT_NEAR((*s.wind.curve)(2.5), 0.9, KEY_TOLERANCE);  // periodic
}

TEST(SceneParser, LightsNeedAPositionAndAreLimited) {
    expectError("[[lighting.light]]\ncolor = [1, 1, 1]\n",
                {"scene.toml:1:", "lighting.light[0]", "missing key position_m"});
    std::string many;
    for (int i = 0; i <= maxLights(); ++i) many += "[[lighting.light]]\nposition_m = [0, 0, 10]\n";
    expectError(many, {"lighting.light", "at most " + std::to_string(maxLights()) + " lights"});
    expectError("[[lighting.light]]\nposition_m = [0, 0, 10]\nattenuation = [0, 0, 0]\n",
                {"lighting.light[0].attenuation", "cannot all be 0"});
}

TEST(SceneParser, CameraNeedsADirectionAndFarBeyondNear) {
    expectError("[camera]\nposition_m = [1, 2, 3]\ntarget_m = [1, 2, 3]\n",
                {"camera.target_m", "must differ"});
    expectError("[camera]\nnear_m = 5\nfar_m = 1\n", {"camera.far_m", "greater than near_m"});
}

TEST(SceneParser, HeightmapNeedsAnExistingImage) {
    expectError("[terrain]\nkind = \"heightmap\"\n", {"terrain.image", "needs an image"});
    expectError("[terrain]\nkind = \"heightmap\"\nimage = \"nothere.png\"\n",
                {"scene.toml:3:", "terrain.image", "no such file", "nothere.png"});
}

TEST(SceneParser, UnknownTerrainKindListsTheValidOnes) {
    expectError("[terrain]\nkind = \"mountain\"\n",
                {"terrain.kind", "gaussian_hill", "heightmap", "(got \"mountain\")"});
}

TEST(SceneParser, KeysTheKindDoesNotUseAreNoted) {
    const Scene s =
        parseSceneString("[terrain]\nkind = \"gaussian_hill\"\noctaves = 3\n", "s.toml");
    ASSERT_EQ(s.notes.size(), 1u);
    EXPECT_NE(s.notes[0].find("s.toml:3: terrain.octaves: not used"), std::string::npos)
        << s.notes[0];
}

TEST(SceneParser, PathsResolveAgainstTheSceneFolder) {
    TempDir dir;
    test::fs::create_directories(dir.path() / "scenes" / "maps");
    test::writeFile(dir / "scenes/maps/hill.png", "not read by the parser");
    test::writeFile(dir / "scenes/grass.png", "not read by the parser");
    test::writeFile(dir / "scenes/s.toml",
                    "[terrain]\nkind = \"heightmap\"\nimage = \"maps/hill.png\"\n"
                    "[grass]\ntexture = \"grass.png\"\n[output]\nfolder = \"out/s\"\n");
    const Scene s = parseSceneFile(dir / "scenes/s.toml");
    EXPECT_EQ(test::fs::path(s.terrain.imagePath), dir.path() / "scenes" / "maps" / "hill.png");
    EXPECT_EQ(test::fs::path(s.grass.texturePath), dir.path() / "scenes" / "grass.png");
    // output.folder stays relative: the current directory anchors it (docs/scene-format.md).
    EXPECT_EQ(s.output.folder, "out/s");
}

TEST(SceneParser, MissingSceneFileIsASceneError) {
    EXPECT_THROW(parseSceneFile("/nonexistent/gale/scene.toml"), SceneError);
}

TEST(SceneParser, WhereNamesTheLineOfAKey) {
    const Scene s = parseSceneString("\n[output]\n\nfolder = \"x\"\n", "a.toml");
    EXPECT_EQ(s.where("output.folder"), "a.toml:4: output.folder");
    EXPECT_EQ(s.where("output.prefix"), "a.toml: output.prefix");  // not written: no line
}

}  // namespace
}  // namespace gale::app
