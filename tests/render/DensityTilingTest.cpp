// Density maps and the aperiodic layout of the grass texture (render/DensityMap.h,
// shaders/shell.frag): the cut table keeps the wanted share of blade area, a map thins the blades
// where it says, and the aperiodic layout breaks the texture's repeat.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>

#include "RenderTestUtil.h"
#include "base/Numbers.h"
#include "render/DensityMap.h"
#include "render/GlContext.h"
#include "render/GrassTexture.h"
#include "render/ShellRenderer.h"

namespace gale::render {
namespace {

// 16 x 16 texels, every texel a blade, heights in four equal classes 64, 128, 192, 255.
Image fourHeightClasses() {
    Image image = test::makeUniformImage(16, 255, 255, 255, 255);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            image.rgba[(size_t(y) * 16 + x) * 4 + 3] =
                uint8_t(64 * ((x + 2 * y) % 4 + 1) - ((x + 2 * y) % 4 == 3));
    return image;
}

TEST(DensityCuts, KeepTheWantedShareOfBladeAreaTallestFirst) {
    const std::vector<float> cuts = densityCuts(fourHeightClasses());
    ASSERT_EQ(cuts.size(), size_t(DENSITY_CUTS));
    constexpr float HALF = 0.5f / 255.0f;
    EXPECT_GT(cuts[0], 1.0f);                         // density 0: nothing
    EXPECT_FLOAT_EQ(cuts[255], 0.0f);                 // density 1: everything
    EXPECT_FLOAT_EQ(cuts[128], 128.0f / 255 - HALF);  // a half: the two tallest classes (and a bit)
    EXPECT_FLOAT_EQ(cuts[64], 192.0f / 255 - HALF);   // a quarter: the tallest class
    for (int k = 1; k < DENSITY_CUTS; ++k) EXPECT_LE(cuts[k], cuts[k - 1]);
    // A texture without blades: no cut.
    for (float c : densityCuts(test::makeUniformImage(4, 9, 9, 9, 0))) EXPECT_EQ(c, 0.0f);
}

TEST(ShellPassFractions, MultiplyTheSharesEachShellLetsThrough) {
    // Four equal classes, alpha 64, 128, 192, 255. With N = 4, shell k keeps alpha >=
    // 255 k / 4 - 0.5: shell 1 (63.25) keeps all, so no ray passes it; N = 2: shell 1 (127)
    // keeps three classes, shell 2 (254.5) one.
    const std::array<size_t, 256> count = alphaHistogram(fourHeightClasses());
    EXPECT_EQ(count[64] + count[128] + count[192] + count[255], size_t(256));
    const std::vector<float> four = shellPassFractions(count, 4);
    ASSERT_EQ(four.size(), size_t(5));
    EXPECT_FLOAT_EQ(four[0], 1.0f);
    for (int m = 1; m <= 4; ++m) EXPECT_FLOAT_EQ(four[m], 0.0f) << m;
    const std::vector<float> two = shellPassFractions(count, 2);
    ASSERT_EQ(two.size(), size_t(3));
    EXPECT_FLOAT_EQ(two[1], 0.25f);
    EXPECT_FLOAT_EQ(two[2], 0.25f * 0.75f);
    // Bare ground passes every ray; no shells, only entry 0.
    const std::vector<float> bare =
        shellPassFractions(alphaHistogram(test::makeUniformImage(4, 9, 9, 9, 0)), 6);
    for (float p : bare) EXPECT_FLOAT_EQ(p, 1.0f);
    EXPECT_EQ(shellPassFractions(count, 0).size(), size_t(1));
}

// A flat field seen from straight above (CoverageScene's light: brightness is the Banks factor,
// the ground at half, the top shell full); the camera's view is 4.1 m across.
struct TopView {
    std::unique_ptr<GlContext> context;
    ShellRenderer renderer;
    explicit TopView(int size, const Image& texture, float tile_m, int shells, bool aperiodic)
        : context(createOsMesaContext(size, size)), renderer(*context) {
        renderer.setTerrain(test::makeFlatMesh(9, 8.0f, tile_m));
        GrassParams grass;
        grass.height_m = 0.02f;  // short: the shells barely separate in the view
        grass.shells = shells;
        grass.aperiodic = aperiodic;
        grass.lodPixels = 0.0f;  // every shell at every distance: the tests count shells
        grass.nearBlades = 0;    // and no blade geometry in their place
        renderer.setGrass(grass, grassTextureFromImage(texture));
        Lighting lighting;
        lighting.ambient = glm::vec3(0.0f);
        lighting.specularStrength = 0.0f;
        lighting.selfShadowMin = 0.5f;
        lighting.lights.push_back(
            {glm::vec3(1.0e4f, 0.0f, 0.0f), glm::vec3(1.0f), glm::vec3(1.0f, 0.0f, 0.0f)});
        renderer.setLighting(lighting);
    }
    Image draw(float fovY_deg = 45.0f) {
        Camera camera;
        camera.wsPosition_m = glm::vec3(0.0f, 0.0f, 10.0f);
        camera.wsTarget_m = glm::vec3(0.0f);
        camera.fovY_deg = fovY_deg;
        renderer.draw(camera, GrassWind{});
        Image image;
        context->readPixels(image);
        return image;
    }
};

// Fraction of pixels of columns [x0, x1) brighter than the ground's shade (a blade above shell 0).
double bladeFraction(const Image& image, int x0, int x1) {
    constexpr int GROUND_SHADE = 128, SHADE_TOL = 8;  // half brightness, plus rounding
    size_t blades = 0, pixels = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = x0; x < x1; ++x, ++pixels)
            blades += image.rgba[(size_t(y) * image.width + x) * 4] > GROUND_SHADE + SHADE_TOL;
    return double(blades) / pixels;
}

TEST(DensityMap, ThinsTheBladesToTheMapsShare) {
    TopView view(96, fourHeightClasses(), /*tile_m=*/4.0f, /*shells=*/8, /*aperiodic=*/false);
    const Image full = view.draw();
    // West half bare, east half at half density (64 x 1 texels over the 16 m field: the linear
    // blend between the halves spans 0.25 m, 6 pixels, around x = 0).
    DensityMap map;
    map.width = 64;
    map.height = 1;
    for (int t = 0; t < 64; ++t) map.density.push_back(t < 32 ? 0.0f : 0.5f);
    map.wsMin_m = glm::vec2(-8.0f);
    map.wsSize_m = glm::vec2(16.0f);
    view.renderer.setDensityMap(map);
    const Image thinned = view.draw();
    // Away from the blend at x = 0 (the middle column) by 8 pixels each way.
    constexpr double SHARE_TOL = 0.06;  // pixels on class borders; the 1/255 rounding of the cut
    EXPECT_GT(bladeFraction(full, 0, 40), 0.95);
    EXPECT_LT(bladeFraction(thinned, 0, 40), 0.01);
    EXPECT_NEAR(bladeFraction(thinned, 56, 96), 0.5, SHARE_TOL);
    // Removing the map brings every blade back.
    view.renderer.setDensityMap(DensityMap{});
    EXPECT_EQ(view.draw().rgba, full.rgba);
}

TEST(DensityMap, BadMapsAreRefused) {
    TopView view(16, fourHeightClasses(), 4.0f, 2, false);
    DensityMap map;
    map.width = 2;
    map.height = 2;
    map.density = {1.0f, 1.0f, 1.0f};
    EXPECT_THROW(view.renderer.setDensityMap(map), std::logic_error);
    map.density.push_back(NAN);
    EXPECT_THROW(view.renderer.setDensityMap(map), std::logic_error);
    map.density.back() = 1.0f;
    map.wsSize_m = glm::vec2(0.0f, 1.0f);
    EXPECT_THROW(view.renderer.setDensityMap(map), std::logic_error);
}

// Mean absolute difference of the red channel between the image and itself shifted `shift`
// pixels along x.
double shiftDifference(const Image& image, int shift) {
    double sum = 0.0;
    size_t n = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x + shift < image.width; ++x, ++n)
            sum += std::abs(int(image.rgba[(size_t(y) * image.width + x) * 4]) -
                            int(image.rgba[(size_t(y) * image.width + x + shift) * 4]));
    return sum / double(n);
}

TEST(AperiodicTiling, TheTextureNoLongerRepeatsOneTileOver) {
    // The ground alone (no shells: no parallax between layers) seen from 10 m with
    // tan(fov / 2) = 0.2: 128 pixels span 4 m, so one 1 m repeat is exactly 32 pixels.
    GrassTextureSpec spec;
    spec.size = 64;
    spec.seed = 11;
    const Image texture = generateGrassTexture(spec).levels[0];
    const float fov_deg = float(gale::degreesFromRadians(2.0 * std::atan(0.2)));
    TopView plain(128, texture, 1.0f, 0, false), aperiodic(128, texture, 1.0f, 0, true);
    const double repeat = shiftDifference(plain.draw(fov_deg), 32);
    const double broken = shiftDifference(aperiodic.draw(fov_deg), 32);
    // Measured on llvmpipe: the plain repeat matches itself to rounding; two unrelated patches of
    // grass differ by about as much as the texture's own contrast.
    constexpr double REPEAT_TOL = 2.0;  // 8-bit rounding and filtering of a shifted sample grid
    constexpr double UNRELATED = 10.0;
    EXPECT_LT(repeat, REPEAT_TOL);
    EXPECT_GT(broken, UNRELATED);
}

}  // namespace
}  // namespace gale::render
