// The fill-rate measurement behind `gale bench render` (paper Table 2 layout).
#include <gtest/gtest.h>

#include "render/RenderBench.h"

namespace gale::render {
namespace {

TEST(RenderBench, SmallCaseFillsTheScreenAndCountsPaperPolygons) {
    ShellFillCase c;
    c.width = 64;
    c.height = 48;
    c.layers = 9;
    c.frames = 1;
    c.warmupFrames = 0;
    const ShellFillResult r = measureShellFill(c);
    EXPECT_EQ(r.triangles, 4608);  // the paper's 9-shell row: 512 base triangles x 9 layers
    EXPECT_DOUBLE_EQ(r.coverage, 1.0);
    EXPECT_GT(r.fps, 0.0);
    EXPECT_GT(r.baselineFps, 0.0);
    EXPECT_NE(r.renderer.find("4.5"), std::string::npos);
}

TEST(RenderBench, GroundOnlyRowDrawsOneLayer) {
    ShellFillCase c;
    c.width = 32;
    c.height = 24;
    c.layers = 1;
    c.frames = 1;
    c.warmupFrames = 0;
    EXPECT_EQ(measureShellFill(c).triangles, 512);
}

TEST(RenderBench, RejectsBadCase) {
    ShellFillCase c;
    c.layers = 0;
    EXPECT_THROW(measureShellFill(c), std::invalid_argument);
    c.layers = 9;
    c.lights = 17;
    EXPECT_THROW(measureShellFill(c), std::invalid_argument);
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
