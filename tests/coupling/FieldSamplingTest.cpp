// GrassSampler: the field read at grass height above each vertex, with the read plans (the terrain
// test among them) kept across steps of one geometry and made again for another. The field here
// is a shear flow, not a near-wall solution, so the sampler reads it as it stands (Interpolated);
// tests/coupling/NearGroundSamplingTest.cpp tests the near-ground models.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "coupling/FieldSampling.h"

using namespace gale;

namespace {

constexpr int NX = 8, NY = 8, NZ = 6;
constexpr double H = 1.0;  // cell edge, metres
constexpr double SAMPLE_HEIGHT_M = 0.5;
const coupling::NearGround AS_IT_STANDS{coupling::NearGroundModel::Interpolated};

std::shared_ptr<const sim::Heightfield> flatTerrain(float height_m) {
    auto t = std::make_shared<sim::Heightfield>();
    t->nx = t->ny = 9, t->spacing_m = 1.0;
    t->height_m.assign(81, height_m);
    return t;
}

// A field over the box [0, 8]^2 x [0, 6] whose faces hold u = 1 + z, v = 2 + x, w = 0.1 y, plus
// `offset_mps` on u (a later "step" of the same geometry).
sim::WindField field(std::shared_ptr<const sim::Heightfield> terrain, double offset_mps) {
    sim::WindField f(NX, NY, NZ, H, {0.0, 0.0, 0.0}, std::move(terrain),
                     std::vector<uint8_t>(size_t(NX) * NY * NZ, 1));
    for (size_t n = 0; n < f.u_mps().size(); ++n) {
        const size_t k = n / ((NX + 1) * NY);
        f.u_mps()[n] = 1.0 + (k + 0.5) * H + offset_mps;
    }
    for (size_t n = 0; n < f.v_mps().size(); ++n) f.v_mps()[n] = 2.0 + (n % NX + 0.5) * H;
    for (size_t n = 0; n < f.w_mps().size(); ++n) f.w_mps()[n] = 0.1 * ((n / NX) % NY + 0.5) * H;
    return f;
}

render::TerrainMesh meshAt(float height_m) {
    render::TerrainMesh mesh;
    mesh.nx = mesh.ny = 5;
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) {
            mesh.wsPosition_m.push_back({1.0f + 1.5f * i, 1.0f + 1.5f * j, height_m});
            mesh.wsNormal.push_back({0.0f, 0.0f, 1.0f});
        }
    mesh.wsPosition_m.push_back({-5.0f, 3.0f, height_m});  // outside the box: zero
    mesh.wsNormal.push_back({0.0f, 0.0f, 1.0f});
    return mesh;
}

void expectMatchesField(const std::vector<glm::vec3>& got, const sim::WindField& f,
                        const render::TerrainMesh& mesh) {
    ASSERT_EQ(got.size(), mesh.wsPosition_m.size());
    for (size_t v = 0; v < got.size(); ++v) {
        const glm::vec3& p = mesh.wsPosition_m[v];
        const auto u = f.velocityAt_mps(p.x, p.y, p.z + SAMPLE_HEIGHT_M);
        EXPECT_EQ(got[v], glm::vec3(u[0], u[1], u[2])) << "vertex " << v;
    }
}

}  // namespace

TEST(GrassSampler, ReadsTheFieldAtGrassHeightStepAfterStep) {
    const auto ground = flatTerrain(2.0f);
    const render::TerrainMesh mesh = meshAt(2.0f);
    coupling::GrassSampler sampler(mesh, SAMPLE_HEIGHT_M, AS_IT_STANDS);
    std::vector<glm::vec3> out;
    for (double offset : {0.0, 3.0, -1.5}) {
        const sim::WindField f = field(ground, offset);
        sampler.sample(f, out);
        expectMatchesField(out, f, mesh);
        EXPECT_FLOAT_EQ(out[0].x, float(1.0 + 2.5 + offset));  // u = 1 + z at z = 2.5 m
        EXPECT_EQ(out.back(), glm::vec3(0.0f));                // outside the box
    }
}

// A field over other terrain is another geometry: the terrain test is made again, so grass that
// the new ground buries reads zero, and grass it uncovers reads the field.
TEST(GrassSampler, MakesTheTerrainTestAgainForAnotherGeometry) {
    const render::TerrainMesh mesh = meshAt(2.0f);
    coupling::GrassSampler sampler(mesh, SAMPLE_HEIGHT_M, AS_IT_STANDS);
    std::vector<glm::vec3> out;
    const sim::WindField low = field(flatTerrain(2.0f), 0.0);
    sampler.sample(low, out);
    EXPECT_NE(out[0], glm::vec3(0.0f));
    const sim::WindField high =
        field(flatTerrain(4.0f), 0.0);  // the sample points are now 1.5 m under ground
    sampler.sample(high, out);
    for (const glm::vec3& u : out) EXPECT_EQ(u, glm::vec3(0.0f));
    sampler.sample(low, out);
    expectMatchesField(out, low, mesh);
    EXPECT_NE(out[0], glm::vec3(0.0f));
}

TEST(GrassSampler, RefusesABadSampleHeight) {
    const render::TerrainMesh mesh = meshAt(0.0f);
    for (double h : {-0.1, std::nan(""), std::numeric_limits<double>::infinity()}) {
        try {
            coupling::GrassSampler sampler(mesh, h);
            FAIL() << "accepted sample height " << h;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("wind.sample_height_m"), std::string::npos);
        }
    }
}
