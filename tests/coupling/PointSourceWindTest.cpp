// The paper's point-source wind: tangent-plane directions, distance rings, waves travelling out.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "coupling/PointSourceWind.h"
#include "coupling/TerrainMeshBuilder.h"
#include "sim/Heightfield.h"

using namespace gale;

namespace {

sim::Heightfield hill() {
    sim::TerrainSpec spec;
    spec.kind = sim::TerrainKind::GaussianHill;
    spec.sizeX_m = spec.sizeY_m = 40.0;
    spec.spacing_m = 1.0;
    spec.height_m = 6.0;
    spec.radius_m = 8.0;
    spec.centerX_m = spec.centerY_m = 20.0;
    return sim::makeTerrain(spec);
}

TEST(PointSourceWind, VerticesFartherFromTheSourceGetTheGustLater) {
    const render::TerrainMesh mesh = coupling::buildTerrainMesh(hill(), 2.0f);
    coupling::PointSourceSpec spec;
    spec.wsSource_m = {0.0f, 0.0f, 3.0f};
    spec.steps = 12;
    spec.stepDelay_s = 0.2;
    const auto curve = coupling::GustCurve::attackDecay(6.0, 0.0, 1.0, 0.3, 2.0);
    coupling::PointSourceWind wind(mesh, spec, curve);

    // Group is monotone in distance from the source.
    std::vector<std::pair<float, uint32_t>> byDistance;
    for (size_t v = 0; v < mesh.wsPosition_m.size(); ++v)
        byDistance.emplace_back(glm::length(mesh.wsPosition_m[v] - spec.wsSource_m),
                                wind.groupOf(v));
    std::sort(byDistance.begin(), byDistance.end());
    for (size_t k = 1; k < byDistance.size(); ++k)
        EXPECT_GE(byDistance[k].second, byDistance[k - 1].second);
    EXPECT_EQ(byDistance.front().second, 0u);
    EXPECT_EQ(byDistance.back().second, 11u);

    // Arrival time of the gust peak per group: monotone and spaced by the step delay.
    render::GrassWind out;
    const double dt = 0.01;
    std::vector<double> peakTime(spec.steps, -1.0), peak(spec.steps, -1.0);
    for (double t = 0.0; t < 5.0; t += dt) {
        wind.update(t, out);
        for (int g = 0; g < spec.steps; ++g)
            if (out.groupIntensity[g] > peak[g]) peak[g] = out.groupIntensity[g], peakTime[g] = t;
    }
    for (int g = 1; g < spec.steps; ++g) {
        EXPECT_GT(peakTime[g], peakTime[g - 1]);
        EXPECT_NEAR(peakTime[g] - peakTime[g - 1], spec.stepDelay_s, 1.5 * dt);
    }
}

TEST(PointSourceWind, DirectionsLieInTheTangentPlaneAndPointAwayFromTheSource) {
    const sim::Heightfield field = hill();
    const render::TerrainMesh mesh = coupling::buildTerrainMesh(field, 2.0f);
    coupling::PointSourceSpec spec;
    spec.wsSource_m = {20.0f, -30.0f, 2.0f};
    coupling::PointSourceWind wind(mesh, spec, coupling::GustCurve(1.0, {{0.0, 0.5}}));
    render::GrassWind out;
    wind.update(0.0, out);
    ASSERT_EQ(out.wsDirection().size(), mesh.wsPosition_m.size());
    for (size_t v = 0; v < mesh.wsPosition_m.size(); ++v) {
        const glm::vec3 d = out.wsDirection()[v];
        EXPECT_LT(std::abs(glm::dot(d, mesh.wsNormal[v])), 1e-5f);
        EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
        // Away from a source south of the terrain: northward component.
        EXPECT_GT(d.y, 0.0f);
    }
}

TEST(PointSourceWind, UploadsPerVertexDataOnceAndIntensitiesEveryFrame) {
    const render::TerrainMesh mesh = coupling::buildTerrainMesh(hill(), 2.0f);
    coupling::PointSourceWind wind(mesh, {}, coupling::GustCurve::attackDecay(2.0, 0, 1, 0.2, 1.0));
    render::GrassWind out;
    wind.update(0.0, out);
    const uint64_t revision = out.revision;
    const std::vector<float> first = out.groupIntensity;
    wind.update(0.1, out);
    EXPECT_EQ(out.revision, revision);
    EXPECT_NE(out.groupIntensity, first);
}

TEST(PointSourceWind, SourceOnAVertexGivesZeroDirectionNotNaN) {
    const render::TerrainMesh mesh = coupling::buildTerrainMesh(hill(), 2.0f);
    coupling::PointSourceSpec spec;
    spec.wsSource_m = mesh.wsPosition_m[5];
    coupling::PointSourceWind wind(mesh, spec, coupling::GustCurve(1.0, {{0.0, 0.5}}));
    render::GrassWind out;
    wind.update(0.0, out);
    EXPECT_EQ(glm::length(out.wsDirection()[5]), 0.0f);
}

TEST(PointSourceWind, RejectsBadSpecs) {
    const render::TerrainMesh mesh = coupling::buildTerrainMesh(hill(), 2.0f);
    const coupling::GustCurve curve(1.0, {{0.0, 0.5}});
    coupling::PointSourceSpec spec;
    spec.steps = 0;
    EXPECT_THROW(coupling::PointSourceWind(mesh, spec, curve), std::invalid_argument);
    spec.steps = 4;
    spec.stepDelay_s = -1.0;
    EXPECT_THROW(coupling::PointSourceWind(mesh, spec, curve), std::invalid_argument);
}

}  // namespace
