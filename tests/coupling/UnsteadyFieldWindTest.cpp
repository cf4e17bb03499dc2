// The unsteady field drives the grass: the source steps the solver up to each frame, the grass
// answers a gust when its front arrives (later downstream), and memory stays flat.
#include <gtest/gtest.h>

#include <memory>

#include "coupling/TerrainMeshBuilder.h"
#include "coupling/UnsteadyFieldWind.h"
#include "sim/SteadyWind.h"

namespace gale::coupling {
namespace {

TEST(UnsteadyFieldWind, StepsToEachFrameAndTheGustReachesDownstreamGrassLater) {
    sim::TerrainSpec ts;
    ts.kind = sim::TerrainKind::Flat;
    ts.sizeX_m = 80, ts.sizeY_m = 16, ts.spacing_m = 2.0;
    const sim::Heightfield hf = sim::makeTerrain(ts);
    const render::TerrainMesh mesh = buildTerrainMesh(hf, 3.0f);
    auto domain = std::make_unique<sim::AirDomain>(hf, sim::DomainSpec{2.0, {}, 1e9});
    sim::AmbientWind a;
    a.profile = sim::WindProfile::Uniform;
    a.speed_mps = 4.0;
    const auto steady = sim::solveSteadyWind(*domain, a, {}, {});
    sim::UnsteadySettings s;
    s.dt_s = 0.5;
    sim::GustEvent g;
    g.peak_mps = 4.0, g.duration_s = 4.0, g.envelope = sim::GustEnvelope::OneMinusCosine;
    s.gusts.push_back(g);
    FieldWindSpec r;
    r.grouping = Grouping::PerVertex;
    UnsteadyFieldWind wind(mesh, std::move(domain), steady.field, s, a.speed_mps, r, 0.5);
    render::GrassWind gw;
    // Vertices near x = 10 m and x = 60 m on the middle row.
    const size_t row = size_t(mesh.ny / 2) * mesh.nx;
    const size_t near = row + 5, far = row + 30;
    double tNear = -1, tFar = -1, peakNear = 0, peakFar = 0;
    for (double t = 0.0; t <= 24.0; t += 0.5) {
        wind.update(t, gw);
        EXPECT_GE(wind.solver().time_s(), t - 1e-9);
        const auto shown = FieldWind::shownIntensity(gw);
        if (shown[near] > peakNear) peakNear = shown[near], tNear = t;
        if (shown[far] > peakFar) peakFar = shown[far], tFar = t;
    }
    EXPECT_TRUE(wind.stats().allFinite);
    EXPECT_TRUE(wind.stats().allConverged);
    // 50 m apart at about 4-5 m/s: 10-12.5 s later; allow the front's own speed-up.
    EXPECT_GT(tFar - tNear, 7.0) << "near " << tNear << " s, far " << tFar << " s";
    EXPECT_LT(tFar - tNear, 14.0) << "near " << tNear << " s, far " << tFar << " s";
    EXPECT_NE(wind.describe().find("unsteady"), std::string::npos);
}

}  // namespace
}  // namespace gale::coupling
