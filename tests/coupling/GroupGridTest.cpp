// Blending neighbouring groups (coupling/GroupGrid.h): bin coordinates, empty groups, and the
// stripes of grouped wind gone where the renderer blends, for each grouped source.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "coupling/FieldWind.h"
#include "coupling/GroupGrid.h"
#include "coupling/PointSourceWind.h"
#include "coupling/SteadyGustWind.h"
#include "coupling/TerrainMeshBuilder.h"
#include "sim/Heightfield.h"

using namespace gale;

namespace {

// 60 m x 10 m of flat ground, one vertex a metre.
render::TerrainMesh strip() {
    sim::TerrainSpec spec;
    spec.kind = sim::TerrainKind::Flat;
    spec.sizeX_m = 60.0;
    spec.sizeY_m = 10.0;
    spec.spacing_m = 1.0;
    return coupling::buildTerrainMesh(sim::makeTerrain(spec), 2.0f);
}

// Largest |difference| of `values` between vertices one metre apart along x (the strip's rows).
double maxNeighbourJump(const render::TerrainMesh& mesh, const std::vector<float>& values) {
    double jump = 0.0;
    for (int j = 0; j < mesh.ny; ++j)
        for (int i = 0; i + 1 < mesh.nx; ++i) {
            const size_t v = size_t(j) * mesh.nx + i;
            jump = std::max(jump, std::abs(double(values[v + 1]) - values[v]));
        }
    return jump;
}

TEST(GroupGrid, BinCentresSitAtIntegersAndTheEndsClamp) {
    // Four bins over [10, 18): centres at 11, 13, 15, 17 map to 0, 1, 2, 3.
    for (int b = 0; b < 4; ++b)
        EXPECT_FLOAT_EQ(coupling::binCoord(11.0 + 2.0 * b, 10.0, 8.0, 4), float(b));
    EXPECT_FLOAT_EQ(coupling::binCoord(12.0, 10.0, 8.0, 4), 0.5f);  // a bin edge: half way
    EXPECT_FLOAT_EQ(coupling::binCoord(10.0, 10.0, 8.0, 4), 0.0f);
    EXPECT_FLOAT_EQ(coupling::binCoord(18.0, 10.0, 8.0, 4), 3.0f);
    EXPECT_FLOAT_EQ(coupling::binCoord(-1e30, 10.0, 8.0, 4), 0.0f);
}

TEST(GroupGrid, EmptyGroupsContinueTheirPopulatedNeighbours) {
    std::vector<double> values{0.0, 1.0, 0.0, 0.0, 4.0, 0.0};
    const std::vector<uint32_t> members{0, 3, 0, 0, 1, 0};
    coupling::fillEmptyGroups(values, members);
    const std::vector<double> expected{1.0, 1.0, 2.0, 3.0, 4.0, 4.0};
    EXPECT_EQ(values, expected);
    std::vector<double> none{5.0, 6.0};
    coupling::fillEmptyGroups(none, {0, 0});
    EXPECT_EQ(none, (std::vector<double>{5.0, 6.0}));
}

// Grouped static intensity of a wind ramp: I = 0.1 + 0.006 x (x in metres), 8 levels.
struct Ramp {
    render::TerrainMesh mesh = strip();
    render::GrassWind out;
    std::vector<float> exact;
    explicit Ramp(bool blend) {
        coupling::FieldWindSpec spec;
        spec.groups = 8;
        spec.bendSpeed_mps = 10.0;
        spec.blendGroups = blend;
        coupling::FieldWind wind(mesh, spec);
        std::vector<glm::vec3> velocity;
        for (const glm::vec3& p : mesh.wsPosition_m)
            velocity.emplace_back(1.0f + 0.06f * p.x, 0.0f, 0.0f);
        wind.addFieldStep(0.0, velocity);
        wind.update(0.0, out);
        exact = wind.exactStaticIntensity(0.0);
    }
};

// The ramp rises 0.006 a metre; its 8 levels are 0.045 (7.5 m) apart.
constexpr double RAMP_STEP = 0.006;
// A level's mean is over whole vertices, up to half a metre off its bin centre: between two
// centres the blend may be steeper than the ramp by up to 1 m / 7.5 m, and off it by half a step.
constexpr double BLEND_SLOPE_FACTOR = 1.0 + 1.0 / 7.5;
constexpr double INSIDE_ERROR_TOL = 0.5 * RAMP_STEP;

TEST(GroupGrid, BlendedLevelsFollowARampWithoutSteps) {
    const Ramp nearest(false), blended(true);
    const double stepNearest =
        maxNeighbourJump(nearest.mesh, coupling::blendedIntensity(nearest.out));
    const double stepBlended =
        maxNeighbourJump(blended.mesh, coupling::blendedIntensity(blended.out));
    EXPECT_GT(stepNearest, 5.0 * RAMP_STEP);  // the stripes: a level's width at once
    EXPECT_LE(stepBlended, RAMP_STEP * BLEND_SLOPE_FACTOR);
    // And the blend is closer to the exact per-vertex intensity everywhere inside the end bins'
    // centres (beyond them the end groups hold: clamped like any texture edge).
    const std::vector<float> shown = coupling::blendedIntensity(blended.out);
    const double halfLevel = 0.5 * (0.36 / 8.0);
    for (size_t v = 0; v < shown.size(); ++v) {
        if (blended.exact[v] < 0.1 + halfLevel || blended.exact[v] > 0.46 - halfLevel) continue;
        EXPECT_NEAR(shown[v], blended.exact[v], INSIDE_ERROR_TOL) << "vertex " << v;
    }
}

TEST(GroupGrid, PointSourceRingsBlendAcrossTheirEdges) {
    const render::TerrainMesh mesh = strip();
    coupling::PointSourceSpec spec;
    spec.wsSource_m = {0.0f, 5.0f, 0.0f};
    spec.steps = 6;
    spec.stepDelay_s = 0.5;
    const auto curve = coupling::GustCurve::attackDecay(10.0, 0.0, 1.0, 0.3, 4.0);
    render::GrassWind nearest, blended;
    spec.blendGroups = false;
    coupling::PointSourceWind(mesh, spec, curve).update(1.4, nearest);
    spec.blendGroups = true;
    coupling::PointSourceWind(mesh, spec, curve).update(1.4, blended);
    // Six rings over 60 m: a ring is 10 m wide, so blended neighbours one metre apart differ by at
    // most a tenth of the largest jump between neighbouring rings (plus the ring of the source's
    // own row, whose distances are not uniform in x).
    double ringJump = 0.0;
    for (int g = 1; g < spec.steps; ++g)
        ringJump = std::max(
            ringJump, double(std::abs(nearest.groupIntensity[g] - nearest.groupIntensity[g - 1])));
    ASSERT_GT(ringJump, 0.1);
    EXPECT_NEAR(maxNeighbourJump(mesh, coupling::blendedIntensity(nearest)), ringJump, 1e-6);
    constexpr double BLEND_FRACTION = 0.15;  // 1 m of a 10 m ring, with slack for the y offset
    EXPECT_LT(maxNeighbourJump(mesh, coupling::blendedIntensity(blended)),
              BLEND_FRACTION * ringJump);
}

TEST(GroupGrid, SteadyGustBandsAndLevelsBlendBilinearly) {
    const render::TerrainMesh mesh = strip();
    std::vector<glm::vec3> steady;
    for (const glm::vec3& p : mesh.wsPosition_m)
        steady.emplace_back(4.0f + 0.05f * p.y, 0.0f, 0.0f);
    coupling::SteadyGustSpec spec;
    spec.arrivalBands = 6;
    spec.levels = 3;
    spec.convection_mps = 5.0;
    spec.response.bendSpeed_mps = 10.0;
    const auto curve = coupling::GustCurve::attackDecay(30.0, 0.0, 1.0, 1.0, 10.0);
    render::GrassWind nearest, blended;
    spec.response.blendGroups = false;
    coupling::SteadyGustWind(mesh, steady, spec, curve).update(6.0, nearest);
    spec.response.blendGroups = true;
    coupling::SteadyGustWind(mesh, steady, spec, curve).update(6.0, blended);
    ASSERT_EQ(blended.vertex->groupColumns, 3);
    const double before = maxNeighbourJump(mesh, coupling::blendedIntensity(nearest));
    const double after = maxNeighbourJump(mesh, coupling::blendedIntensity(blended));
    ASSERT_GT(before, 0.02);
    constexpr double BLEND_GAIN = 4.0;  // 10 m bands seen 1 m apart: about ten times smaller steps
    EXPECT_LT(after * BLEND_GAIN, before);
}

}  // namespace
