// A scene written from scratch renders usefully (issue 14, first hour): without lights the frame
// is in daylight, not near black; the default camera frames the whole terrain.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "AppTestSupport.h"
#include "app/scene/SceneBuilder.h"
#include "app/scene/SceneParser.h"
#include "base/Numbers.h"
#include "coupling/LiveWind.h"
#include "render/CameraMath.h"
#include "render/ImageIO.h"

namespace gale::app::test {
namespace {

/// Mean Rec. 709 luma of an 8-bit image, in levels 0..255.
double meanLuma(const render::Image& image) {
    double sum = 0.0;
    const size_t n = size_t(image.width) * image.height;
    for (size_t p = 0; p < n; ++p)
        sum += 0.2126 * image.rgba[p * 4] + 0.7152 * image.rgba[p * 4 + 1] +
               0.0722 * image.rgba[p * 4 + 2];
    return sum / double(n);
}

/// tiny.toml without its light, seen from above so the frame is all ground (the sky's clear
/// colour does not depend on the lights). With `oldDefault`, lit as a scene without lights was
/// before the default sun: a grey ambient of 0.25 alone (one black light stands for "no light").
std::string unlitTiny(bool oldDefault) {
    std::string text = readFile(sourcePath("tests/data/scenes/tiny.toml"));
    const std::string light = "[[lighting.light]]\nposition_m = [20.0, -10.0, 15.0]\n";
    const std::string camera = "position_m = [-2.0, -4.0, 5.0]\ntarget_m = [4.0, 4.0, 0.5]\n";
    const size_t at = text.find(light), cameraAt = text.find(camera);
    EXPECT_NE(at, std::string::npos) << "tiny.toml changed its light";
    EXPECT_NE(cameraAt, std::string::npos) << "tiny.toml changed its camera";
    text.replace(cameraAt, camera.size(),
                 "position_m = [4.0, 2.5, 9.0]\ntarget_m = [4.0, 4.0, 0.5]\n");
    text.erase(text.find(light), light.size());
    if (oldDefault)
        text +=
            "\n[lighting]\nambient = [0.25, 0.25, 0.25]\n\n[[lighting.light]]\nposition_m = [0.0, "
            "0.0, 10.0]\ncolor = [0, 0, 0]\n";
    return text;
}

TEST(FirstHourRender, ASceneWithoutLightsRendersInDaylightNotNearBlack) {
    TempDir dir;
    double luma[2] = {0.0, 0.0};
    for (int oldDefault = 0; oldDefault < 2; ++oldDefault) {
        const std::string name = oldDefault ? "old" : "default";
        writeFile(dir / (name + ".toml"), unlitTiny(oldDefault != 0));
        const RunResult r = runGale({"render", dir / (name + ".toml"), "-o", dir / name, "--frames",
                                     "1", "--width", "160", "--height", "120"});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        luma[oldDefault] = meanLuma(render::readImageRgba8(dir / (name + "/frame_0000.png")));
    }
    // Sunlit grass: the mean is well off black (a third of full scale)...
    constexpr double MIN_MEAN_LUMA = 85.0;
    EXPECT_GT(luma[0], MIN_MEAN_LUMA) << "old default " << luma[1];
    // ...and far brighter than the grey ambient alone that lit such scenes before.
    constexpr double MIN_GAIN_OVER_AMBIENT = 1.5;
    EXPECT_GT(luma[0], MIN_GAIN_OVER_AMBIENT * luma[1])
        << "default " << luma[0] << ", ambient alone " << luma[1];
}

/// A scene with no [camera] over a terrain of the given side, as a newcomer writes it.
BuiltScene fromScratch(double side_m, Scene& scene) {
    const std::string text = "[terrain]\nkind = \"gaussian_hill\"\nsize_m = [" +
                             std::to_string(side_m) + ", " + std::to_string(side_m) +
                             "]\nspacing_m = " + std::to_string(side_m / 100.0) +
                             "\nheight_m = " + std::to_string(side_m / 20.0) +
                             "\nradius_m = " + std::to_string(side_m / 5.0) + "\n";
    scene = parseSceneString(text, "scratch.toml");
    return buildScene(scene);
}

TEST(FirstHourRender, TheDefaultCameraFramesTheWholeTerrain) {
    // Issue 26: a scene without a camera shows its whole terrain, as the default scene shows its
    // knoll (a close-up 9 m from the summit of a 200 m hill never showed the hill).
    for (double side_m : {40.0, 200.0, 1000.0}) {
        Scene scene;
        const BuiltScene built = fromScratch(side_m, scene);
        const render::Camera& camera = built.camera;
        const float aspect = float(scene.output.width) / float(scene.output.height);
        const glm::mat4 clipFromWorld = render::clipFromWorld(camera, aspect);
        // The terrain's corners and its summit, projected by the test: inside the frame, in front
        // of the camera.
        const sim::Heightfield& field = built.heightfield;
        const double x0 = field.originX_m, y0 = field.originY_m;
        const double x1 = x0 + field.sizeX_m(), y1 = y0 + field.sizeY_m();
        const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
        for (const auto& [x, y] : {std::pair{x0, y0}, {x1, y0}, {x0, y1}, {x1, y1}, {cx, cy}}) {
            const glm::vec4 clip =
                clipFromWorld * glm::vec4(float(x), float(y), float(field.sample(x, y)), 1.0f);
            ASSERT_GT(clip.w, 0.0f) << side_m << " m: (" << x << ", " << y << ") behind the camera";
            EXPECT_LE(std::abs(clip.x / clip.w), 1.0f)
                << side_m << " m: (" << x << ", " << y << ")";
            EXPECT_LE(std::abs(clip.y / clip.w), 1.0f)
                << side_m << " m: (" << x << ", " << y << ")";
        }
        // Above the ground, looking at it.
        EXPECT_GT(camera.wsPosition_m.z,
                  built.heightfield.sample(camera.wsPosition_m.x, camera.wsPosition_m.y));
    }
}

}  // namespace
}  // namespace gale::app::test
