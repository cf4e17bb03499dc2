// Blending neighbouring groups in the shell renderer (render/BendTables.h, shaders/shell.vert):
// a wind whose groups step across the field shows stripes when each vertex takes its group's
// tilt alone and none when the renderer blends the groups at each vertex's place between them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>

#include "RenderTestUtil.h"
#include "render/GlContext.h"
#include "render/GrassTexture.h"
#include "render/ShellRenderer.h"

namespace gale::render {
namespace {

constexpr int GROUPS = 4;
constexpr float HALF_SIZE_M = 6.0f;

// Flat field seen from above, grass of one colour lit by a far light 45 degrees up towards +x, so
// the brightness of a strand follows its tilt towards +x (Kajiya-Kay diffuse sqrt(1 - (T.L)^2),
// thesis 3.3.1); the wind blows +x with a tilt that steps group by group across x.
struct StripeScene {
    std::unique_ptr<GlContext> context = createOsMesaContext(128, 96);
    ShellRenderer renderer{*context};
    TerrainMesh mesh = test::makeFlatMesh(49, HALF_SIZE_M, 1.0f);

    StripeScene() {
        renderer.setTerrain(mesh);
        GrassParams grass;
        grass.height_m = 0.4f;
        grass.shells = 8;
        grass.nearBlades = 0;  // the stripes are the shells' (blades take the nearest group)
        renderer.setGrass(grass,
                          grassTextureFromImage(test::makeUniformImage(16, 200, 200, 200, 255)));
        Lighting lighting;
        lighting.ambient = glm::vec3(0.05f);
        lighting.specularStrength = 0.0f;
        lighting.selfShadowMin = 1.0f;
        lighting.lights.push_back(
            {glm::vec3(1.0e4f, 0.0f, 1.0e4f), glm::vec3(1.0f), glm::vec3(1.0f, 0.0f, 0.0f)});
        renderer.setLighting(lighting);
    }

    // Groups are 3 m bins of x with intensities 0.05, 0.18, 0.31, 0.44 (a ramp seen in steps).
    enum class Coord { None, Continuous, Centres };
    GrassWind wind(Coord mode) const {
        const bool blend = mode != Coord::None;
        auto vertex = std::make_shared<VertexWind>();
        vertex->groupColumns = GROUPS;
        for (const glm::vec3& p : mesh.wsPosition_m) {
            const float bins = (p.x + HALF_SIZE_M) / (2.0f * HALF_SIZE_M) * GROUPS;
            vertex->wsDirection.emplace_back(1.0f, 0.0f, 0.0f);
            vertex->group.push_back(static_cast<uint32_t>(std::clamp(int(bins), 0, GROUPS - 1)));
            const float centre = float(vertex->group.back());
            if (mode == Coord::Continuous)
                vertex->groupCoord.emplace_back(std::clamp(bins - 0.5f, 0.0f, GROUPS - 1.0f), 0.0f);
            if (mode == Coord::Centres) vertex->groupCoord.emplace_back(centre, 0.0f);
        }
        GrassWind w;
        w.vertex = std::move(vertex);
        w.revision = blend ? 2 : 1;  // a new revision: the renderer re-uploads per-vertex data
        for (int g = 0; g < GROUPS; ++g) w.groupIntensity.push_back(0.05f + 0.13f * g);
        return w;
    }

    Image draw(const GrassWind& w) {
        Camera camera;
        camera.wsPosition_m = glm::vec3(0.0f, -0.01f, 9.0f);
        camera.wsTarget_m = glm::vec3(0.0f);
        renderer.draw(camera, w);
        Image image;
        context->readPixels(image);
        return image;
    }
};

using Coord = StripeScene::Coord;

// One 8-bit level: the bilinear weights of llvmpipe's filtering are quantised.
constexpr int ROUNDING_JUMP = 1;
// The blended ramp changes the brightness by about 25 levels over the 96 pixels of the field, so
// under one level a pixel; the grid's per-vertex (Gouraud) lighting adds one or two more.
constexpr int SMOOTH_JUMP = 3;
// A stripe: the 4 groups step the brightness by about 8 levels each (measured 11 at the worst).
constexpr int STRIPE_JUMP = 6;

// Largest difference of any channel between horizontally neighbouring pixels.
int maxNeighbourJump(const Image& image) {
    int jump = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x + 1 < image.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const size_t p = (size_t(y) * image.width + x) * 4 + c;
                jump = std::max(jump, std::abs(int(image.rgba[p]) - int(image.rgba[p + 4])));
            }
    return jump;
}

TEST(GroupBlend, BlendedGroupsShowNoStripes) {
    StripeScene scene;
    const int nearest = maxNeighbourJump(scene.draw(scene.wind(Coord::None)));
    const int blended = maxNeighbourJump(scene.draw(scene.wind(Coord::Continuous)));
    // Measured 11 and 1 on llvmpipe: the stripes are a group's brightness step at once.
    EXPECT_GE(nearest, STRIPE_JUMP);
    EXPECT_LE(blended, SMOOTH_JUMP);
}

TEST(GroupBlend, VerticesAtGroupCentresShowTheirGroupAlone) {
    // Blending at a group's own texel reads that group: the same image as without blending.
    StripeScene scene;
    const Image nearest = scene.draw(scene.wind(Coord::None));
    const Image centres = scene.draw(scene.wind(Coord::Centres));
    EXPECT_LE(test::compareImages(nearest, centres, 0).maxChannelDiff, ROUNDING_JUMP);
}

}  // namespace
}  // namespace gale::render
