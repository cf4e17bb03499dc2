// Bad parameters given to the coupling and the renderer throw gale::ParameterError carrying the
// scene's dotted key (so the program can point at that key's line), the value as written and
// what was expected; the key is the scene format's name, never a C++ field.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "ParameterErrorCheck.h"
#include "base/ParameterError.h"
#include "coupling/FieldWind.h"
#include "coupling/GustCurve.h"
#include "coupling/PointSourceWind.h"
#include "coupling/TerrainMeshBuilder.h"
#include "render/CameraMath.h"
#include "render/GrassTexture.h"
#include "sim/Heightfield.h"

namespace gale {
namespace {

using gale::test::logicErrorOf;
using gale::test::thrownBy;

render::TerrainMesh smallMesh() {
    return coupling::buildTerrainMesh(sim::makeHeightfield(3, 3, 1.0, std::vector<float>(9, 0.0f)),
                                      /*tile_m=*/1.0f);
}

TEST(ParameterError, CouplingNamesTheSceneKeyAndTheValue) {
    const sim::Heightfield flat = sim::makeHeightfield(3, 3, 1.0, std::vector<float>(9, 0.0f));
    ParameterError e = thrownBy([&] { (void)coupling::buildTerrainMesh(flat, -2.0f); });
    EXPECT_EQ(e.key(), "grass.tile_m");
    EXPECT_EQ(e.value(), "-2");
    EXPECT_EQ(thrownBy([&] { (void)coupling::buildTerrainMesh(flat, 1.0f, 0); }).key(),
              "terrain.mesh_stride");

    const render::TerrainMesh mesh = smallMesh();
    const coupling::GustCurve curve(2.0, {{0.0, 0.5}});
    coupling::PointSourceSpec source;
    source.steps = 0;
    e = thrownBy([&] { coupling::PointSourceWind(mesh, source, curve); });
    EXPECT_EQ(e.key(), "wind.steps");
    EXPECT_EQ(e.value(), "0");
    source = {};
    source.stepDelay_s = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(thrownBy([&] { coupling::PointSourceWind(mesh, source, curve); }).key(),
              "wind.step_delay_s");

    coupling::FieldWindSpec response;
    response.groups = 0;
    EXPECT_EQ(thrownBy([&] { coupling::validate(response); }).key(), "wind.groups");
    response = {};
    response.bendSpeed_mps = -1.0;
    EXPECT_EQ(thrownBy([&] { coupling::validate(response); }).key(), "wind.bend_speed_mps");
    EXPECT_EQ(thrownBy([] { (void)coupling::groupingFromName("rings"); }).key(), "wind.grouping");

    EXPECT_EQ(thrownBy([] { coupling::GustCurve(0.0, {{0.0, 0.5}}); }).key(), "wind.gust.period_s");
    e = thrownBy([] { coupling::GustCurve(2.0, {{0.5, 0.1}, {0.5, 0.8}}); });
    EXPECT_EQ(e.key(), "wind.gust.keys[1]");
    EXPECT_EQ(e.value(), "[0.5, 0.8]");
    EXPECT_EQ(
        thrownBy([] { (void)coupling::GustCurve::attackDecay(2.0, 0.1, 0.8, 1.5, 1.0); }).key(),
        "wind.gust.decay_s");
}

TEST(ParameterError, RendererNamesTheSceneKey) {
    render::Camera camera;
    camera.wsPosition_m = glm::vec3(0.0f, -5.0f, 2.0f);
    camera.fovY_deg = 0.0f;
    EXPECT_EQ(thrownBy([&] { (void)render::clipFromCamera(camera, 1.5f); }).key(),
              "camera.fov_deg");
    camera = {};
    camera.near_m = 5.0f, camera.far_m = 1.0f;
    EXPECT_EQ(thrownBy([&] { (void)render::clipFromCamera(camera, 1.5f); }).key(), "camera.far_m");
    camera = {};
    camera.wsTarget_m = camera.wsPosition_m;
    EXPECT_EQ(thrownBy([&] { (void)render::cameraFromWorld(camera); }).key(), "camera.target_m");

    render::GrassTextureSpec spec;
    spec.size = 100;
    const ParameterError e = thrownBy([&] { (void)render::generateGrassTexture(spec); });
    EXPECT_EQ(e.key(), "grass.generated.size");
    EXPECT_EQ(e.value(), "100");
}

TEST(ParameterError, CouplingBugsAreLogicErrorsNotBadInput) {
    EXPECT_EQ(thrownBy([] { coupling::GustCurve(2.0, {}); }).key(), "wind.gust.keys");
    render::TerrainMesh mesh = smallMesh();
    mesh.wsNormal.pop_back();
    EXPECT_NE(
        logicErrorOf([&] { coupling::FieldWind(mesh, coupling::FieldWindSpec{}); }).find("normals"),
        std::string::npos);
    coupling::FieldWind wind(smallMesh(), coupling::FieldWindSpec{});
    EXPECT_NE(logicErrorOf([&] { wind.addFieldStep(0.0, {}); }).find("velocities"),
              std::string::npos);
    sim::Heightfield line;
    line.nx = 1, line.ny = 4, line.spacing_m = 1.0;
    line.height_m.assign(4, 0.0f);
    EXPECT_NE(logicErrorOf([&] { (void)coupling::buildTerrainMesh(line, 1.0f); }).find("2x2"),
              std::string::npos);
}

}  // namespace
}  // namespace gale
