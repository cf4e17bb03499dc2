/// \file ExampleSeamsTest.cpp
/// No seams in any example (issue 26): every scene in examples/ drawn from its own camera, at its
/// own output size capped to 640 x 480, with the level of detail it asks for against the same
/// frame with every shell everywhere, held to tests/render/SeamMeasure.h's tile and strip bounds.
/// The grass stands still (no wind): seams are a matter of distance and view, and the scenes'
/// solves would cost minutes.
///
/// Disabled: it is the measurement of what is left of issue 26's seams, not yet a bound the
/// examples meet. Session 13 measured (worst tile |mean|, levels; bound 6): fractal_meadow 8.0,
/// gust_ridge_valley 4.7, knoll 10.0 (its far shadow, sharp with every shell, spread over coarse
/// cells; 6.7 without shadows), landscape 1.3, landscape_source 100 (seen from over a kilometre
/// away, where the full stack itself aliases), lee_ridge 8.2, meadow_path 3.5, ridge_solved 8.2,
/// valley 6.8, whirlwind_meadow 4.9; docs/render.md. GALE_SEAMS_NO_SHADOWS=1 draws without the
/// key light's shadow. Run it with --gtest_also_run_disabled_tests.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "../render/SeamMeasure.h"
#include "AppTestSupport.h"
#include "app/scene/SceneBuilder.h"
#include "app/scene/SceneParser.h"
#include "render/GlContext.h"
#include "render/ImageIO.h"
#include "render/ShellRenderer.h"

namespace gale::app {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> exampleScenes() {
    std::vector<fs::path> scenes;
    for (const auto& entry : fs::directory_iterator(fs::path(GALE_SOURCE_DIR) / "examples"))
        if (entry.path().extension() == ".toml") scenes.push_back(entry.path());
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}

TEST(ExampleSeams, DISABLED_EveryExampleLooksTheSameWithItsLevelOfDetailAsWithEveryShell) {
    const std::vector<fs::path> scenes = exampleScenes();
    ASSERT_GE(scenes.size(), 10u);
    for (const fs::path& path : scenes) {
        const Scene scene = parseSceneFile(path.string());
        if (!(scene.grass.params.lodPixels > 0.0f)) continue;  // no level of detail to check
        BuildOptions options;
        options.solveWind = false;
        const BuiltScene built = buildScene(scene, options);
        const int width = std::min(scene.output.width, 640);
        const int height = std::min(scene.output.height, 480);
        auto context = render::createOsMesaContext(width, height);
        render::ShellRenderer renderer(*context);
        renderer.setTerrain(built.mesh);
        renderer.setDensityMap(built.densityMap);
        render::Lighting lighting = scene.lighting;
        lighting.shadows = std::getenv("GALE_SEAMS_NO_SHADOWS") == nullptr;
        renderer.setLighting(lighting);
        const auto frame = [&](float lodPixels) {
            render::GrassParams grass = scene.grass.params;
            grass.lodPixels = lodPixels;
            renderer.setGrass(grass, built.texture);
            renderer.setDensityMap(built.densityMap);
            (void)renderer.draw(built.camera, render::GrassWind{});
            render::Image image;
            context->readPixels(image);
            return image;
        };
        const render::Image lod = frame(scene.grass.params.lodPixels);
        const render::Image full = frame(0.0f);
        const render::test::SeamReport r = render::test::measureSeams(lod, full);
        const std::string name = path.stem().string();
        std::printf("seam %-28s worst tile |mean| %5.2f at (%d, %d), worst step %5.2f\n",
                    name.c_str(), r.worstTileMean, r.worstTileX, r.worstTileY, r.worstStep);
        EXPECT_LE(r.worstTileMean, render::test::TILE_MEAN_TOLERANCE)
            << name << ": tile (" << r.worstTileX << ", " << r.worstTileY << ")";
        EXPECT_LE(r.worstStep, render::test::STEP_TOLERANCE) << name;
        if (r.worstTileMean > render::test::TILE_MEAN_TOLERANCE ||
            r.worstStep > render::test::STEP_TOLERANCE || std::getenv("GALE_KEEP_SEAM_FRAMES")) {
            const fs::path dir = fs::path(GALE_BINARY_DIR) / "app_test_tmp" / "example_seams";
            fs::create_directories(dir);
            render::writeImageAtomic(lod, (dir / (name + "_lod.png")).string());
            render::writeImageAtomic(full, (dir / (name + "_full.png")).string());
        }
    }
}

}  // namespace
}  // namespace gale::app
