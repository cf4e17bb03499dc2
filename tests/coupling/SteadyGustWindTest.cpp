// Kinematic gusts over a steady field: fronts travel downwind at the convection speed, the bend
// scales with the steady speed-up, and the oscillator stays bounded.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "coupling/SteadyGustWind.h"
#include "coupling/TerrainMeshBuilder.h"
#include "sim/Heightfield.h"

using namespace gale;

namespace {

render::TerrainMesh flat() {
    sim::TerrainSpec spec;
    spec.kind = sim::TerrainKind::Flat;
    spec.sizeX_m = 50.0;
    spec.sizeY_m = 10.0;
    spec.spacing_m = 1.0;
    return coupling::buildTerrainMesh(sim::makeTerrain(spec), 2.0f);
}

TEST(SteadyGustWind, FrontArrivesDownstreamAtDistanceOverConvectionSpeed) {
    const render::TerrainMesh mesh = flat();
    std::vector<glm::vec3> steady(mesh.wsPosition_m.size(), glm::vec3(5.0f, 0.0f, 0.0f));
    coupling::SteadyGustSpec spec;
    spec.arrivalBands = 50;
    spec.levels = 1;
    spec.convection_mps = 5.0;
    spec.response.bendSpeed_mps = 10.0;
    const auto curve = coupling::GustCurve::attackDecay(20.0, 0.2, 1.0, 0.3, 3.0);
    coupling::SteadyGustWind wind(mesh, steady, spec, curve);
    for (size_t v = 0; v < mesh.wsPosition_m.size(); ++v)
        EXPECT_NEAR(wind.arrival_s(v), mesh.wsPosition_m[v].x / 5.0, 1e-5);
    // Peak time of the shown intensity at x = 0, 25, 50 m: 0.3 s plus x / c.
    render::GrassWind out;
    const size_t row = 5 * static_cast<size_t>(mesh.nx);
    for (int i : {0, 25, 50}) {
        double best = -1.0, bestT = 0.0;
        for (double t = 0.0; t < 15.0; t += 0.01) {
            wind.update(t, out);
            const float shown = out.groupIntensity[out.group()[row + i]];
            if (shown > best) best = shown, bestT = t;
        }
        // Band width 1 m = 0.2 s of arrival; the group's mean arrival is within half of that.
        EXPECT_NEAR(bestT, 0.3 + i / 5.0, 0.11) << "x = " << i;
        EXPECT_NEAR(best, 0.5 * 1.0, 1e-3);  // steady 5 m/s over 10 m/s, times the peak 1.0
    }
}

TEST(SteadyGustWind, OscillatorStaysFiniteAndBoundedUnderAStepGust) {
    const render::TerrainMesh mesh = flat();
    std::vector<glm::vec3> steady(mesh.wsPosition_m.size(), glm::vec3(100.0f, 0.0f, 0.0f));
    steady[3] = glm::vec3(NAN, 0.0f, 0.0f);
    coupling::SteadyGustSpec spec;
    spec.response.response = coupling::BladeResponse::Oscillator;
    spec.response.frequency_hz = 3.0;
    spec.response.dampingRatio = 0.05;
    // A near-step attack: 1 ms.
    coupling::SteadyGustWind wind(mesh, steady, spec,
                                  coupling::GustCurve::attackDecay(5.0, 0.0, 1.0, 0.001, 2.0));
    render::GrassWind out;
    for (double t = 0.0; t < 30.0; t += 1.0 / 30.0) {
        wind.update(t, out);
        for (float i : out.groupIntensity) {
            ASSERT_TRUE(std::isfinite(i));
            // Clamped drive 1.3; an oscillator at most doubles a step.
            ASSERT_LE(std::abs(i), 2.0f * 1.3f + 1e-3f);
        }
    }
    EXPECT_EQ(out.wsDirection()[3], glm::vec3(0.0f));
}

// Views of the field show the gust the grass feels: the kept steady field, each face scaled by
// the curve at its own arrival delay, rebuilt when the time moves.
TEST(SteadyGustWind, FieldViewCarriesTheSameTravellingFront) {
    const render::TerrainMesh mesh = flat();  // x in [0, 50] m
    std::vector<glm::vec3> steady(mesh.wsPosition_m.size(), glm::vec3(5.0f, 0.0f, 0.0f));
    coupling::SteadyGustSpec spec;
    spec.convection_mps = 5.0;
    const auto curve = coupling::GustCurve::attackDecay(20.0, 0.2, 1.0, 0.3, 3.0);
    coupling::SteadyGustWind wind(mesh, steady, spec, curve);
    render::GrassWind out;
    wind.update(0.0, out);
    EXPECT_EQ(wind.currentField(), nullptr);  // no field kept: nothing to show

    // A uniform 5 m/s field over the mesh's plan, 2 m cells.
    constexpr int NX = 25, NY = 5, NZ = 4;
    auto field =
        std::make_shared<sim::WindField>(NX, NY, NZ, 2.0, std::array<double, 3>{0.0, 0.0, 0.0},
                                         nullptr, std::vector<uint8_t>(size_t(NX) * NY * NZ, 1));
    std::fill(field->u_mps().begin(), field->u_mps().end(), 5.0);
    wind.keepField(field);
    for (double t : {1.0, 4.0, 4.0, 7.5}) {
        wind.update(t, out);
        const sim::WindField* gust = wind.currentField();
        ASSERT_NE(gust, nullptr);
        for (double x : {4.0, 22.0, 40.0}) {  // on x-faces (every 2 m), at a cell centre in y and z
            const double expected = 5.0 * curve(t - x / 5.0);
            EXPECT_NEAR(gust->velocityAt_mps(x, 5.0, 3.0)[0], expected, 1e-9)
                << "t = " << t << ", x = " << x;
        }
        EXPECT_EQ(gust->v_mps(), field->v_mps());  // zero stays zero
    }
    // The kept field itself is untouched.
    EXPECT_EQ(field->u_mps().front(), 5.0);
    EXPECT_EQ(field->u_mps().back(), 5.0);
}

}  // namespace
