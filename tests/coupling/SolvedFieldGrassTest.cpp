// The solved steady field drives the grass: uniform flat wind, speed-up over a hill's crest.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "coupling/FieldSampling.h"
#include "coupling/FieldWind.h"
#include "coupling/TerrainMeshBuilder.h"
#include "sim/AirDomain.h"
#include "sim/SteadyWind.h"

using namespace gale;

namespace {

// The steady solve's tolerance: intensities agree to well under this.
constexpr float UNIFORM_INTENSITY_TOL = 1e-4f;

sim::Heightfield terrain(sim::TerrainKind kind) {
    sim::TerrainSpec spec;
    spec.kind = kind;
    spec.sizeX_m = spec.sizeY_m = 64.0;
    spec.spacing_m = 1.0;
    spec.height_m = 8.0;
    spec.radius_m = 8.0;
    spec.centerX_m = spec.centerY_m = 32.0;
    return sim::makeTerrain(spec);
}

struct Solved {
    render::TerrainMesh mesh;
    render::GrassWind wind;
};

Solved solveAndCouple(const sim::Heightfield& field, double voxel_m) {
    sim::AirDomain domain(field, {voxel_m, {}, 2e9});
    sim::AmbientWind ambient;
    ambient.speed_mps = 6.0;
    ambient.profile = sim::WindProfile::Uniform;
    const sim::SteadyWindResult res =
        sim::solveSteadyWind(domain, ambient, {}, sim::SolverSettings{});
    EXPECT_TRUE(res.report.converged) << res.report.message;
    Solved s;
    s.mesh = coupling::buildTerrainMesh(field, 2.0f, 2);
    coupling::FieldWindSpec spec;
    spec.grouping = coupling::Grouping::PerVertex;
    spec.bendSpeed_mps = 10.0;
    spec.maxIntensity = 5.0;
    coupling::FieldWind wind(s.mesh, spec);
    wind.addFieldStep(0.0, coupling::sampleAtGrass(res.field, s.mesh, 0.5));
    wind.update(0.0, s.wind);
    return s;
}

TEST(SolvedFieldGrass, UniformWindOverFlatGroundBendsEveryVertexAlike) {
    const Solved s = solveAndCouple(terrain(sim::TerrainKind::Flat), 2.0);
    const auto shown = coupling::FieldWind::shownIntensity(s.wind);
    for (size_t v = 0; v < shown.size(); ++v) {
        const glm::vec3& p = s.mesh.wsPosition_m[v];
        // Interior vertices: the sampler's clamping at the box sides is not what we test here.
        if (p.x < 2 || p.x > 62 || p.y < 2 || p.y > 62) continue;
        EXPECT_NEAR(shown[v], 0.6f, UNIFORM_INTENSITY_TOL);
        EXPECT_NEAR(s.wind.wsDirection()[v].x, 1.0f, 1e-5f);
    }
}

TEST(SolvedFieldGrass, HillCrestBendsMoreThanTheUpstreamFoot) {
    const Solved s = solveAndCouple(terrain(sim::TerrainKind::GaussianHill), 1.0);
    const auto shown = coupling::FieldWind::shownIntensity(s.wind);
    auto intensityNear = [&](float x, float y) {
        size_t best = 0;
        float bestD = 1e30f;
        for (size_t v = 0; v < shown.size(); ++v) {
            const float d = glm::length(glm::vec2(s.mesh.wsPosition_m[v]) - glm::vec2(x, y));
            if (d < bestD) bestD = d, best = v;
        }
        return shown[best];
    };
    const float crest = intensityNear(32.0f, 32.0f), foot = intensityNear(12.0f, 32.0f);
    EXPECT_GT(crest, 1.2f * foot) << "crest " << crest << ", upstream foot " << foot;
    for (float i : shown) ASSERT_TRUE(std::isfinite(i));
}

}  // namespace
