// Scenes of the unsteady wind: the examples parse with their gusts and whirlwinds, defaults apply,
// and bad [unsteady] / [[wind.gusts]] / [[wind.whirlwinds]] keys are errors naming FILE:LINE and
// key.
#include <gtest/gtest.h>

#include <string>

#include "AppTestSupport.h"
#include "app/Commands.h"
#include "app/io/Errors.h"
#include "app/scene/SceneParser.h"

namespace gale::app {
namespace {

using test::errorOf;

const char* const BASE = "[wind]\nkind = \"unsteady\"\nspeed_mps = 4.0\n";

TEST(UnsteadyScene, ExamplesParseWithTheirEvents) {
    const Scene gust = parseSceneFile(test::sourcePath("examples/gust_ridge_valley.toml"));
    EXPECT_EQ(gust.wind.kind, WindKind::Unsteady);
    ASSERT_EQ(gust.unsteady.settings.gusts.size(), 1u);
    EXPECT_EQ(gust.unsteady.settings.gusts[0].envelope, sim::GustEnvelope::Spline);
    const Scene whirl = parseSceneFile(test::sourcePath("examples/whirlwind_meadow.toml"));
    ASSERT_EQ(whirl.unsteady.settings.whirlwinds.size(), 1u);
    EXPECT_TRUE(whirl.unsteady.settings.whirlwinds[0].forced);
    EXPECT_EQ(whirl.unsteady.settings.advection, sim::AdvectionScheme::MacCormack);
}

TEST(UnsteadyScene, DefaultsApply) {
    const Scene s =
        parseSceneString(std::string(BASE) + "[[wind.gusts]]\npeak_mps = 2.0\n", "scene.toml");
    EXPECT_EQ(s.unsteady.settings.dt_s, 0.0);  // adaptive
    EXPECT_EQ(s.unsteady.settings.cfl, 2.0);
    EXPECT_FALSE(s.unsteady.settings.openTop);
    EXPECT_EQ(s.unsteady.settings.gusts[0].direction_deg, 0.0);
    EXPECT_EQ(s.unsteady.settings.gusts[0].duration_s, 4.0);
    EXPECT_EQ(s.unsteady.settings.precision, sim::AdvectionPrecision::Single);
    EXPECT_EQ(s.unsteady.liveTolerance, 1e-3);
    EXPECT_EQ(s.unsteady.liveIterations, 3);
    EXPECT_EQ(s.unsteady.settings.projection.relativeTolerance, 1e-5);  // gale solve's
}

TEST(UnsteadyScene, TheLiveWindProjectsToTheLiveTolerance) {
    // gale view and the live benches step what limitUnsteadyStepToAFrame leaves: the
    // projection at unsteady.live_tolerance, a step of at most one frame.
    Scene s = parseSceneString(std::string(BASE) + "[unsteady]\ntolerance = 1e-6\n" +
                                   "live_tolerance = 2e-3\nlive_iterations = 2\n" +
                                   "max_iterations = 40\n[output]\nfps = 20\n",
                               "scene.toml");
    EXPECT_EQ(s.unsteady.settings.projection.relativeTolerance, 1e-6);
    EXPECT_EQ(s.unsteady.settings.projection.maxIterations, 40);  // gale solve's budget
    limitUnsteadyStepToAFrame(s);
    EXPECT_EQ(s.unsteady.settings.projection.relativeTolerance, 2e-3);
    EXPECT_EQ(s.unsteady.settings.projection.maxIterations, 2);  // the live budget
    EXPECT_EQ(s.unsteady.settings.maxDt_s, 1.0 / 20);
}

TEST(UnsteadyScene, PrecisionAndLiveToleranceAreRead) {
    const Scene s = parseSceneString(
        std::string(BASE) + "[unsteady]\nprecision = \"double\"\nlive_tolerance = 1e-4\n",
        "scene.toml");
    EXPECT_EQ(s.unsteady.settings.precision, sim::AdvectionPrecision::Double);
    EXPECT_EQ(s.unsteady.liveTolerance, 1e-4);
}

TEST(UnsteadyScene, SurfaceLayerAndMomentumModelAcceptStretchedLayers) {
    const std::string layers = "[solver]\nvoxel_size_m = 1.0\nfirst_cell_m = 0.25\n";
    const Scene s = parseSceneString(
        std::string(BASE) + layers + "[unsteady]\nsurface_layer = true\n", "scene.toml");
    EXPECT_TRUE(s.unsteady.settings.surfaceLayer.enabled);
    EXPECT_EQ(s.solver.domain.firstCell_m, 0.25);
    EXPECT_EQ(errorOf("[wind]\nprofile = \"log\"\n" + layers + "model = \"momentum\"\n"), "");
}

TEST(UnsteadyScene, BadKeysNameFileLineAndKey) {
    std::string m = errorOf(std::string(BASE) + "[unsteady]\ncfl = -2\n");
    EXPECT_NE(m.find("scene.toml:5: unsteady.cfl"), std::string::npos) << m;
    m = errorOf(std::string(BASE) + "[unsteady]\ndt_s = 0.1\ncfl = 2\n");
    EXPECT_NE(m.find("not both"), std::string::npos) << m;
    m = errorOf(std::string(BASE) + "[unsteady]\nadvection = \"rk4\"\n");
    EXPECT_NE(m.find("unsteady.advection"), std::string::npos) << m;
    m = errorOf(std::string(BASE) + "[unsteady]\nprecision = \"half\"\n");
    EXPECT_NE(m.find("scene.toml:5: unsteady.precision"), std::string::npos) << m;
    m = errorOf(std::string(BASE) + "[unsteady]\nlive_tolerance = 0.9\n");
    EXPECT_NE(m.find("scene.toml:5: unsteady.live_tolerance"), std::string::npos) << m;
    m = errorOf(std::string(BASE) + "[unsteady]\nlive_iterations = 0\n");
    EXPECT_NE(m.find("scene.toml:5: unsteady.live_iterations"), std::string::npos) << m;
    m = errorOf(std::string(BASE) + "[[wind.gusts]]\nenvelope = \"square\"\n");
    EXPECT_NE(m.find("wind.gusts[0].envelope"), std::string::npos) << m;
    m = errorOf(std::string(BASE) + "[[wind.gusts]]\npeak = 3\n");
    EXPECT_NE(m.find("unknown key"), std::string::npos) << m;
    m = errorOf(std::string(BASE) + "[[wind.whirlwinds]]\ncore_radius_m = 2\npeak_speed_mps = 3\n");
    EXPECT_NE(m.find("position_m"), std::string::npos) << m;
    m = errorOf(std::string(BASE) + "[[wind.whirlwinds]]\nposition_m = [1, 2]\n");
    EXPECT_NE(m.find("circulation_m2ps or peak_speed_mps"), std::string::npos) << m;
    m = errorOf(
        std::string(BASE) +
        "[[wind.whirlwinds]]\nposition_m = [1, 2]\npeak_speed_mps = 3\ncirculation_m2ps = 4\n");
    EXPECT_NE(m.find("not both"), std::string::npos) << m;
    m = errorOf(
        std::string(BASE) +
        "[[wind.whirlwinds]]\nposition_m = [1, 2]\npeak_speed_mps = 3\nprofile = \"tornado\"\n");
    EXPECT_NE(m.find("wind.whirlwinds[0].profile"), std::string::npos) << m;
}

TEST(UnsteadyScene, EventsOfAnotherKindAreNotedAsIgnored) {
    const Scene s = parseSceneString(
        "[wind]\nkind = \"solved\"\n[[wind.gusts]]\npeak_mps = 1\n[unsteady]\ncfl = 3\n",
        "scene.toml");
    ASSERT_GE(s.notes.size(), 2u);
    bool gustNote = false, unsteadyNote = false;
    for (const std::string& n : s.notes) {
        gustNote = gustNote || n.find("wind.gusts[0]") != std::string::npos;
        unsteadyNote = unsteadyNote || n.find("unsteady") != std::string::npos;
    }
    EXPECT_TRUE(gustNote);
    EXPECT_TRUE(unsteadyNote);
}

}  // namespace
}  // namespace gale::app
