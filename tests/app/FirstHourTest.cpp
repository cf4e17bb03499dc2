// What a newcomer writes first: short gust periods, keys without their unit suffix, ambient wind
// keys without a wind kind, and the DEM keys, each parsed or refused with a message that helps.

#include <gtest/gtest.h>

#include <string>

#include "AppTestSupport.h"

namespace gale::app {
namespace {

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

TEST(FirstHour, AShortGustPeriodAloneParsesWithDefaultsThatScale) {
    const Scene s = parseSceneString("[wind.gust]\nperiod_s = 2.0\n", "scene.toml");
    ASSERT_TRUE(s.wind.curve);
    EXPECT_DOUBLE_EQ(s.wind.curve->period_s(), 2.0);
    EXPECT_NE(s.wind.curveDescription.find("attack 0.2 s"), std::string::npos)
        << s.wind.curveDescription;
    EXPECT_NE(s.wind.curveDescription.find("decay 0.8 s"), std::string::npos)
        << s.wind.curveDescription;
}

TEST(FirstHour, AKeyWithoutItsUnitSuffixGetsDidYouMean) {
    const std::string e = test::errorOf("[wind]\nspeed = 5.0\n");
    EXPECT_TRUE(contains(e, "scene.toml:2: wind.speed: unknown key (did you mean 'speed_mps'?)"))
        << e;
}

TEST(FirstHour, AmbientWindWithoutKindGetsANoteSayingHowToSeeIt) {
    const Scene s = parseSceneString("[wind]\nspeed_mps = 7.0\n", "scene.toml");
    ASSERT_EQ(s.notes.size(), 1u);
    EXPECT_TRUE(contains(s.notes[0], "scene.toml:2: wind.speed_mps:")) << s.notes[0];
    EXPECT_TRUE(contains(s.notes[0], "wind.kind = \"solved\"")) << s.notes[0];
    EXPECT_TRUE(parseSceneString("[wind]\nkind = \"solved\"\nspeed_mps = 7.0\n", "scene.toml")
                    .notes.empty());
}

TEST(FirstHour, DemKeysAreCheckedAndNotedWhenUnused) {
    EXPECT_TRUE(
        contains(test::errorOf("[terrain]\nkind = \"dem\"\n"), "kind \"dem\" needs a raster file"));
    EXPECT_TRUE(contains(
        test::errorOf("[terrain]\nkind = \"dem\"\ndem = \"x.tif\"\ncrop_m = [10, 0, 5, 1]\n"),
        "terrain.crop_m: expected [min x, min y, max x, max y] with max > min"));
    EXPECT_TRUE(contains(test::errorOf("[terrain]\nkind = \"dem\"\ndem = \"missing.tif\"\n"),
                         "terrain.dem: no such file"));
    const Scene s = parseSceneString("[terrain]\nkind = \"flat\"\ndem = \"x.tif\"\n", "scene.toml");
    ASSERT_EQ(s.notes.size(), 1u);
    EXPECT_TRUE(contains(s.notes[0], "terrain.dem: not used by kind \"flat\"")) << s.notes[0];
}

}  // namespace
}  // namespace gale::app
