// The turbulent flutter (render::VertexWind::flutter_rad, shaders/shell.vert): grass moves over
// time where the flutter amplitude is positive and stands exactly still where it is zero, so
// shelter reads as stillness and turbulence as agitation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "RenderTestUtil.h"
#include "render/GlContext.h"
#include "render/GrassTexture.h"
#include "render/ShellRenderer.h"

namespace gale::render {
namespace {

constexpr int WIDTH_PX = 160, HEIGHT_PX = 120;
constexpr int FRAMES = 12;
// 0.3 rad (17 degrees), below coupling/Flutter.h's cap of 0.35: strongly turbulent air.
constexpr float FLUTTER_RAD = 0.3f;
// The agitated half must move clearly: a mean temporal standard deviation of at least this many
// 8-bit levels (a blade tip sweeping across a pixel changes it by tens of levels).
constexpr double MIN_AGITATED_STD = 2.0;
// Still grass: the very same pixels every frame; the one-pass variance of identical values
// leaves round-off of about 1e-6 levels.
constexpr double STILL_STD = 1e-3;

struct FlutterField {
    std::unique_ptr<GlContext> context = createOsMesaContext(WIDTH_PX, HEIGHT_PX);
    ShellRenderer renderer{*context};
    TerrainMesh mesh = test::makeFlatMesh(33, 4.0f, 2.0f);
    FlutterField() {
        renderer.setTerrain(mesh);
        GrassParams grass;
        grass.height_m = 0.5f;
        grass.shells = 16;
        grass.lodPixels = 0.0f;
        GrassTextureSpec spec;
        spec.size = 128;
        renderer.setGrass(grass, generateGrassTexture(spec));
        Lighting lighting;
        lighting.lights.push_back({glm::vec3(20, -30, 40), glm::vec3(1.0f), glm::vec3(1, 0, 0)});
        renderer.setLighting(lighting);
    }
    // Per-pixel temporal standard deviation of luminance over FRAMES frames, 1/12 s apart, of a
    // steady wind (intensity 0.3 everywhere) with the given flutter west (x < 0) and east.
    std::vector<double> motion(float west_rad, float east_rad) {
        GrassWind wind = test::makeUniformWind(mesh, glm::vec3(1, 0, 0), 0.3f, 0.3f);
        auto vertex = std::make_shared<VertexWind>(*wind.vertex);
        for (const glm::vec3& p : mesh.wsPosition_m)
            vertex->flutter_rad.push_back(p.x < 0.0f ? west_rad : east_rad);
        wind.vertex = vertex;
        Camera camera;
        camera.wsPosition_m = glm::vec3(0.0f, -0.5f, 6.0f);  // from above: the halves side by side
        camera.wsTarget_m = glm::vec3(0.0f);
        const size_t n = size_t(WIDTH_PX) * HEIGHT_PX;
        std::vector<double> sum(n, 0.0), sum2(n, 0.0);
        Image image;
        for (int k = 0; k < FRAMES; ++k) {
            wind.time_s = k / 12.0;
            (void)renderer.draw(camera, wind);
            context->readPixels(image);
            for (size_t p = 0; p < n; ++p) {
                const double l = 0.2126 * image.rgba[p * 4] + 0.7152 * image.rgba[p * 4 + 1] +
                                 0.0722 * image.rgba[p * 4 + 2];
                sum[p] += l;
                sum2[p] += l * l;
            }
        }
        std::vector<double> sd(n);
        for (size_t p = 0; p < n; ++p) {
            const double mean = sum[p] / FRAMES;
            sd[p] = std::sqrt(std::max(0.0, sum2[p] / FRAMES - mean * mean));
        }
        return sd;
    }
};

// Mean over the columns [x0, x1) of the frame (the west half is on the left seen from the south).
double meanOver(const std::vector<double>& v, int x0, int x1) {
    double s = 0.0;
    for (int y = 0; y < HEIGHT_PX; ++y)
        for (int x = x0; x < x1; ++x) s += v[size_t(y) * WIDTH_PX + x];
    return s / double((x1 - x0) * HEIGHT_PX);
}

TEST(Flutter, TurbulentGrassMovesAndShelteredGrassStandsStill) {
    FlutterField field;
    const std::vector<double> sd = field.motion(FLUTTER_RAD, 0.0f);
    // A margin of 16 columns each side of the frame's middle, where the halves meet.
    const double west = meanOver(sd, 0, WIDTH_PX / 2 - 16);
    const double east = meanOver(sd, WIDTH_PX / 2 + 16, WIDTH_PX);
    std::printf("flutter: mean temporal std west (agitated) %.2f, east (calm) %.4f levels\n", west,
                east);
    EXPECT_GT(west, MIN_AGITATED_STD);
    EXPECT_LT(east, STILL_STD);  // no flutter: the very same pixels every frame
}

TEST(Flutter, WithoutFlutterEveryFrameOfASteadyWindIsTheSame) {
    FlutterField field;
    const std::vector<double> sd = field.motion(0.0f, 0.0f);
    EXPECT_LT(meanOver(sd, 0, WIDTH_PX), STILL_STD);
}

}  // namespace
}  // namespace gale::render
