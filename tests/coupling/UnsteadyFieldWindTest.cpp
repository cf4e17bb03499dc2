// The unsteady field drives the grass: the source steps the solver up to each frame, the grass
// answers a gust when its front arrives (later downstream), and memory stays flat.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "coupling/TerrainMeshBuilder.h"
#include "coupling/UnsteadyFieldWind.h"
#include "sim/SteadyWind.h"
#include "sim/SurfaceLayer.h"

namespace gale::coupling {
namespace {

/// Flat ground of sx x sy metres at 2 m spacing, its render mesh, an air domain of 2 m cells and
/// the steady field of a uniform 4 m/s wind along x: the start of the runs below.
struct FlatRun {
    sim::Heightfield hf;
    render::TerrainMesh mesh;
    std::unique_ptr<sim::AirDomain> domain;
    sim::AmbientWind ambient;
    sim::SteadyWindResult steady;
    FlatRun(double sx, double sy) {
        sim::TerrainSpec ts;
        ts.kind = sim::TerrainKind::Flat;
        ts.sizeX_m = sx, ts.sizeY_m = sy, ts.spacing_m = 2.0;
        hf = sim::makeTerrain(ts);
        mesh = buildTerrainMesh(hf, 3.0f);
        domain = std::make_unique<sim::AirDomain>(hf, sim::DomainSpec{2.0, {}, 1e9});
        ambient.profile = sim::WindProfile::Uniform;
        ambient.speed_mps = 4.0;
        steady = sim::solveSteadyWind(*domain, ambient, {}, {});
    }
};

TEST(UnsteadyFieldWind, StepsToEachFrameAndTheGustReachesDownstreamGrassLater) {
    FlatRun run(80, 16);
    const render::TerrainMesh& mesh = run.mesh;
    sim::UnsteadySettings s;
    s.dt_s = 0.5;
    sim::GustEvent g;
    g.peak_mps = 4.0, g.duration_s = 4.0, g.envelope = sim::GustEnvelope::OneMinusCosine;
    s.gusts.push_back(g);
    FieldWindSpec r;
    r.grouping = Grouping::PerVertex;
    UnsteadyFieldWind wind(mesh, std::move(run.domain), run.steady.field, s, run.ambient.speed_mps,
                           r, 0.5);
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

TEST(UnsteadyFieldWind, AnUpdateStoppedBetweenStepsShowsTheTimeItReachedAndCarriesOn) {
    // The wind worker stops an update when a source is dropped (WindSource::updateUntil): the
    // wind then shows the solver's own time, short of the request, and the next update goes on
    // from there to the request as if it had not stopped.
    FlatRun run(32, 16);
    sim::UnsteadySettings s;
    s.dt_s = 0.25;  // exact in binary: the times below compare exactly
    UnsteadyFieldWind wind(run.mesh, std::move(run.domain), run.steady.field, s,
                           run.ambient.speed_mps, {}, 0.5);
    render::GrassWind gw;
    int asked = 0;
    const auto stopAfterTwoSteps = [&] { return ++asked > 2; };  // asked before every step
    EXPECT_EQ(wind.updateUntil(2.0, gw, stopAfterTwoSteps), 0.5);
    EXPECT_EQ(wind.solver().time_s(), 0.5);
    EXPECT_FALSE(gw.groupIntensity.empty());
    // Not stopped: the request itself, from where the stopped update left off.
    EXPECT_EQ(wind.updateUntil(2.0, gw, [] { return false; }), 2.0);
    EXPECT_EQ(wind.solver().time_s(), 2.0);
    EXPECT_EQ(wind.stats().steps, 8);
    EXPECT_TRUE(wind.stats().allFinite);
}

TEST(UnsteadyFieldWind, SurfaceLayerGrassReadsTheLogLawBelowTheFirstCellCentre) {
    // Flat rough ground, 2 m cells: the first cell centre is 1 m up, the grass reads at 0.25 m.
    sim::TerrainSpec ts;
    ts.kind = sim::TerrainKind::Flat;
    ts.sizeX_m = 40, ts.sizeY_m = 8, ts.spacing_m = 1.0;  // vertices every metre: on cell centres
    const sim::Heightfield hf = sim::makeTerrain(ts);
    const render::TerrainMesh mesh = buildTerrainMesh(hf, 4.0f);
    const double h = 2.0, z0 = 0.03, grass = 0.25;
    auto domain = std::make_unique<sim::AirDomain>(hf, sim::DomainSpec{h, 20.0, 1e9});
    const sim::AirDomain& D = *domain;
    sim::AmbientWind a;
    a.profile = sim::WindProfile::LogLaw;
    a.speed_mps = 5.0, a.roughness_m = z0;
    const auto steady = sim::solveSteadyWind(*domain, a, {}, {});
    sim::UnsteadySettings s;
    s.dt_s = 0.5;
    s.surfaceLayer.enabled = true;
    s.surfaceLayer.roughness_m = z0;
    s.surfaceLayer.balanced = a;
    FieldWindSpec r;
    r.grouping = Grouping::PerVertex;
    UnsteadyFieldWind wind(mesh, std::move(domain), steady.field, s, a.speed_mps, r, grass);
    render::GrassWind gw;
    wind.update(2.0, gw);
    const sim::WindField& f = wind.solver().field();
    const std::vector<glm::vec3> got = wind.sampler().sample(f);
    // Oracle, computed here from the raw faces: the log law through the first cell centre of the
    // vertex's column, u(0.25 m) = u_c ln(0.25 / z0) / ln(1 m / z0), u_c the mean of the cell's
    // two x-faces (over flat ground they lie at the centre's height).
    constexpr double LOG_LAW_TOLERANCE = 0.02;  // v and w are ~0 here; u is read at one point
    int checked = 0;
    for (size_t n = 0; n < mesh.wsPosition_m.size(); ++n) {
        const glm::vec3 p = mesh.wsPosition_m[n];
        const int i = int(std::floor((p.x - D.wsMin_m()[0]) / h)),
                  j = int(std::floor((p.y - D.wsMin_m()[1]) / h));
        // Only vertices at cell centres in plan, where the two x-faces' mean is the centre's value.
        if (std::abs(p.x - (D.wsMin_m()[0] + (i + 0.5) * h)) > 1e-3 ||
            std::abs(p.y - (D.wsMin_m()[1] + (j + 0.5) * h)) > 1e-3 || i < 1 || i >= D.nx() - 1)
            continue;
        const double uc = 0.5 * (f.u(i, j, 0) + f.u(i + 1, j, 0));
        const double expect = uc * std::log(grass / z0) / std::log(0.5 * h / z0);
        EXPECT_NEAR(got[n].x, expect, LOG_LAW_TOLERANCE * std::abs(expect)) << "vertex " << n;
        ++checked;
    }
    EXPECT_GT(checked, 0);
}

}  // namespace
}  // namespace gale::coupling
