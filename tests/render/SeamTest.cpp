/// \file SeamTest.cpp
/// No seams from any viewpoint (docs/render.md, "Level of detail"): the same scene drawn with the
/// default levels (the near blades, the level of detail's shells, the ground standing in far
/// away) and with every shell everywhere and no blades (lod_pixels = 0, near_blades = 0) must
/// look the same at the scale of a 32 x 32 pixel tile, from cameras at human height, 2 m,
/// 10 m, 12 m and 40 m up, oblique and top-down, over a 20 m hill on a 200 m meadow and over a
/// flat meadow. The oracle is the all-shells frame, drawn by the same renderer with the level of
/// detail off: what the level of detail saves must not show.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "RenderTestUtil.h"
#include "SeamMeasure.h"
#include "render/GlContext.h"
#include "render/ShellRenderer.h"

namespace gale::render {
namespace {

// The frame size: the level of detail works in pixels, so the drop distances of the
// default lod_pixels are those a user sees at 640 x 480.
constexpr int WIDTH_PX = 640;
constexpr int HEIGHT_PX = 480;
// The scene of the issue: a 200 x 200 m meadow, 1 m between vertices, with a 20 m Gaussian
// hill (sigma 25 m) at the centre, or flat.
TerrainMesh makeMeadow(bool hill) {
    const float tile_m = GrassParams{}.tile_m;
    return test::makeGridMesh(201, 201, 100.0f, tile_m, [hill](float x, float y) {
        return hill ? 20.0f * std::exp(-(x * x + y * y) / (2.0f * 25.0f * 25.0f)) : 0.0f;
    });
}

float groundAt(bool hill, float x, float y) {
    return hill ? 20.0f * std::exp(-(x * x + y * y) / (2.0f * 25.0f * 25.0f)) : 0.0f;
}

struct View {
    const char* name;
    glm::vec3 eye;     // x, y and the height above the ground under the eye, metres
    glm::vec3 target;  // world
};

// Eye heights are above the ground under the eye; targets are world points.
const std::vector<View>& views() {
    static const std::vector<View> v = {
        {"human_1p7m", {0.0f, -90.0f, 1.7f}, {0.0f, 0.0f, 8.0f}},
        {"oblique_2m", {-60.0f, -70.0f, 2.0f}, {0.0f, 0.0f, 6.0f}},
        {"oblique_10m", {0.0f, -85.0f, 10.0f}, {0.0f, 0.0f, 4.0f}},
        {"from_scratch_12m", {-80.0f, -60.0f, 12.0f}, {0.0f, 0.0f, 10.0f}},
        {"issue_30m", {-70.0f, -80.0f, 30.0f}, {0.0f, 0.0f, 10.0f}},
        {"oblique_40m", {0.0f, -100.0f, 40.0f}, {0.0f, 0.0f, 0.0f}},
        {"top_down_40m", {0.0f, -6.0f, 60.0f}, {0.0f, 0.0f, 0.0f}},
    };
    return v;
}

// The default scene's look: default grass, texture and lighting, the default sun (225 degrees
// azimuth, 40 degrees up, far away; app/scene/SceneParser.h).
struct SeamScene {
    std::unique_ptr<GlContext> context = createOsMesaContext(WIDTH_PX, HEIGHT_PX);
    ShellRenderer renderer{*context};
    GrassTexture texture = generateGrassTexture(GrassTextureSpec{});
    bool hill;
    FrameStats last;  ///< of the last frame
    explicit SeamScene(bool withHill) : hill(withHill) {
        renderer.setTerrain(makeMeadow(hill));
        Lighting lighting;
        const float az = 225.0f * 3.14159265f / 180.0f, el = 40.0f * 3.14159265f / 180.0f;
        const float d = 1.0e6f;
        lighting.lights.push_back({glm::vec3(d * std::cos(el) * std::cos(az),
                                             d * std::cos(el) * std::sin(az), d * std::sin(el)),
                                   glm::vec3(1.0f, 0.95f, 0.85f), glm::vec3(1, 0, 0)});
        renderer.setLighting(lighting);
    }
    Image frame(const View& view, float lodPixels, int nearBlades) {
        GrassParams grass;
        grass.lodPixels = lodPixels;
        grass.nearBlades = nearBlades;
        renderer.setGrass(grass, texture);
        Camera camera;
        camera.wsPosition_m =
            glm::vec3(view.eye.x, view.eye.y, groundAt(hill, view.eye.x, view.eye.y) + view.eye.z);
        camera.wsTarget_m = view.target;
        camera.far_m = 1000.0f;
        last = renderer.draw(camera, GrassWind{});
        Image image;
        context->readPixels(image);
        return image;
    }
};

void checkScene(bool hill) {
    SeamScene scene(hill);
    const std::filesystem::path dir = test::freshTestDir(hill ? "seam_hill" : "seam_flat");
    const GrassParams defaults;
    for (const View& view : views()) {
        // The default levels (near blades, shells, ground far away) against the shells alone.
        const Image lod = scene.frame(view, defaults.lodPixels, defaults.nearBlades);
        const FrameStats lodStats = scene.last;
        const Image full = scene.frame(view, 0.0f, 0);
        const test::SeamReport r = test::measureSeams(lod, full);
        std::printf(
            "seam %s %-18s worst tile |mean| %5.2f at (%d, %d), worst step %5.2f "
            "(%d near blades within %.1f m)\n",
            hill ? "hill" : "flat", view.name, r.worstTileMean, r.worstTileX, r.worstTileY,
            r.worstStep, lodStats.blades, lodStats.bladeRadius_m);
        const bool ok =
            r.worstTileMean <= test::TILE_MEAN_TOLERANCE && r.worstStep <= test::STEP_TOLERANCE;
        EXPECT_LE(r.worstTileMean, test::TILE_MEAN_TOLERANCE)
            << view.name << ": tile (" << r.worstTileX << ", " << r.worstTileY << ")";
        EXPECT_LE(r.worstStep, test::STEP_TOLERANCE) << view.name;
        if (!ok || std::getenv("GALE_KEEP_SEAM_FRAMES")) {
            writeImageAtomic(lod, (dir / (std::string(view.name) + "_lod.png")).string());
            writeImageAtomic(full, (dir / (std::string(view.name) + "_full.png")).string());
            writeImageAtomic(test::compareImages(lod, full, 8).diff,
                             (dir / (std::string(view.name) + "_diff.png")).string());
        }
    }
}

TEST(Seams, AHillOnAMeadowShowsNoLevelOfDetailBoundaryFromAnyCamera) { checkScene(true); }

TEST(Seams, AFlatMeadowShowsNoLevelOfDetailBoundaryFromAnyCamera) { checkScene(false); }

}  // namespace
}  // namespace gale::render
