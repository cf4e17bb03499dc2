// The fill-rate measurement behind `gale bench render` (paper Table 2 layout).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render/RenderBench.h"

namespace gale::render {
namespace {

/// A width x height pixel case drawing `layers` layers for one timed frame and no warm-up: enough
/// to count triangles and coverage in milliseconds.
ShellFillCase oneFrameCase(int width, int height, int layers) {
    ShellFillCase c;
    c.width = width;
    c.height = height;
    c.layers = layers;
    c.frames = 1;
    c.warmupFrames = 0;
    return c;
}

TEST(RenderBench, SmallCaseFillsTheScreenAndCountsPaperPolygons) {
    const ShellFillResult r =
        measureShellFill(oneFrameCase(/*width=*/64, /*height=*/48, /*layers=*/9));
    EXPECT_EQ(r.triangles, 4608);  // the paper's 9-shell row: 512 base triangles x 9 layers
    EXPECT_DOUBLE_EQ(r.coverage, 1.0);
    EXPECT_GT(r.fps, 0.0);
    EXPECT_GT(r.baselineFps, 0.0);
    EXPECT_GT(r.nearestFps, 0.0);
    EXPECT_NE(r.renderer.find("4.5"), std::string::npos);
}

TEST(RenderBench, GroundOnlyRowDrawsOneLayer) {
    const ShellFillCase groundOnly = oneFrameCase(/*width=*/32, /*height=*/24, /*layers=*/1);
    EXPECT_EQ(measureShellFill(groundOnly).triangles, 512);
}

TEST(RenderBench, RejectsBadCase) {
    ShellFillCase c;
    c.layers = 0;
    EXPECT_THROW(measureShellFill(c), std::invalid_argument);
    c.layers = 9;
    c.lights = 17;
    EXPECT_THROW(measureShellFill(c), std::invalid_argument);
}

TEST(FillProfile, EveryVariantIsTimedAndOneIsTheTrivialFill) {
    FillProfileCase c;
    c.width = 32;
    c.height = 24;
    c.layers = 3;
    c.frames = 1;
    const std::vector<FillProfileRow> rows = profileShellFill(c);
    ASSERT_GE(rows.size(), 10u);
    int baselines = 0;
    for (const FillProfileRow& row : rows) {
        EXPECT_FALSE(row.name.empty());
        EXPECT_TRUE(std::isfinite(row.cpu_ms) && row.cpu_ms >= 0.0) << row.name;
        EXPECT_TRUE(std::isfinite(row.wall_ms) && row.wall_ms > 0.0) << row.name;
        if (row.baseline) {
            ++baselines;
            EXPECT_NE(row.name.find("trilinear"), std::string::npos);
        }
    }
    EXPECT_EQ(baselines, 1);
}

TEST(FillProfile, RejectsBadCase) {
    FillProfileCase c;
    c.layers = 0;
    EXPECT_THROW(profileShellFill(c), std::invalid_argument);
    c.layers = 17;
    c.frames = 0;
    EXPECT_THROW(profileShellFill(c), std::invalid_argument);
}

TEST(RenderBench, FlatGridHasUpNormalsAndTiledUv) {
    const TerrainMesh mesh = makeFlatGridMesh(3, 4.0f, 2.0f);
    ASSERT_EQ(mesh.wsPosition_m.size(), 9u);
    EXPECT_EQ(mesh.wsPosition_m[0], glm::vec3(-2.0f, -2.0f, 0.0f));
    EXPECT_EQ(mesh.wsNormal[4], glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(mesh.uv[8], glm::vec2(1.0f, 1.0f));
    EXPECT_THROW(makeFlatGridMesh(1, 4.0f, 2.0f), std::invalid_argument);
}

}  // namespace
}  // namespace gale::render
