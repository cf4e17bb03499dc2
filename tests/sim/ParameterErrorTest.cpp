// A bad scene value given to sim/ throws gale::ParameterError carrying the scene's dotted key as
// docs/scene-format.md spells it (so the program can point at that key's line) and the value as
// written; a broken precondition of the calling code throws std::logic_error, never a
// std::invalid_argument (docs/architecture.md, "Errors").
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "ParameterErrorCheck.h"
#include "base/ParameterError.h"
#include "sim/AirDomain.h"
#include "sim/AmbientWind.h"
#include "sim/Gusts.h"
#include "sim/Heightfield.h"
#include "sim/PoissonSolver.h"
#include "sim/SteadyModel.h"
#include "sim/SteadyWind.h"
#include "sim/Vortices.h"

namespace gale::sim {
namespace {

using gale::test::logicErrorOf;
using gale::test::thrownBy;

constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

/// A small procedural terrain of `kind` (the scene's defaults otherwise).
TerrainSpec terrain(TerrainKind kind) {
    TerrainSpec s;
    s.kind = kind;
    s.sizeX_m = s.sizeY_m = 8.0;
    s.spacing_m = 1.0;
    return s;
}

/// The key the terrain builder names for `spec`.
std::string terrainKey(const TerrainSpec& spec) {
    return thrownBy([&] { (void)makeTerrain(spec); }).key();
}

TEST(ParameterError, TerrainNamesTheSceneKeyAndTheValue) {
    TerrainSpec s = terrain(TerrainKind::GaussianHill);
    s.spacing_m = 0.0;
    const ParameterError e = thrownBy([&] { (void)makeTerrain(s); });
    EXPECT_EQ(e.key(), "terrain.spacing_m");
    EXPECT_EQ(e.value(), "0");

    s = terrain(TerrainKind::GaussianHill);
    s.sizeY_m = -3.0;
    EXPECT_EQ(terrainKey(s), "terrain.size_m[1]");
    s = terrain(TerrainKind::GaussianHill);
    s.height_m = NaN;
    EXPECT_EQ(terrainKey(s), "terrain.height_m");
    s = terrain(TerrainKind::Crater);
    s.radius_m = 0.0;
    EXPECT_EQ(terrainKey(s), "terrain.radius_m");
    s = terrain(TerrainKind::Ridge);
    s.axis_deg = std::numeric_limits<double>::infinity();
    EXPECT_EQ(terrainKey(s), "terrain.axis_deg");
    s = terrain(TerrainKind::Fractal);
    s.octaves = 17;
    const ParameterError octaves = thrownBy([&] { (void)makeTerrain(s); });
    EXPECT_EQ(octaves.key(), "terrain.octaves");
    EXPECT_EQ(octaves.value(), "17");
    s = terrain(TerrainKind::Fractal);
    s.roughness = 1.5;
    EXPECT_EQ(terrainKey(s), "terrain.roughness");
    // A million samples per side: the spacing is what to change.
    s = terrain(TerrainKind::Flat);
    s.sizeX_m = 1e6;
    EXPECT_EQ(terrainKey(s), "terrain.spacing_m");

    const ParameterError kind = thrownBy([] { (void)terrainKindFromName("mountain"); });
    EXPECT_EQ(kind.key(), "terrain.kind");
    EXPECT_EQ(kind.value(), "\"mountain\"");
    EXPECT_EQ(
        thrownBy([] { (void)makeHeightfield(2, 2, -1.0, std::vector<float>(4, 0.0f)); }).key(),
        "terrain.metres_per_pixel");
}

TEST(ParameterError, GustsAndWhirlwindsNameTheirKeyWithoutTheIndex) {
    GustEvent g;
    g.duration_s = -1.0;
    EXPECT_EQ(thrownBy([&] { g.validate(); }).key(), "wind.gusts.duration_s");
    g = {};
    g.attack_s = 20.0;  // longer than the 4 s gust
    const ParameterError attack = thrownBy([&] { g.validate(); });
    EXPECT_EQ(attack.key(), "wind.gusts.attack_s");
    EXPECT_EQ(attack.value(), "20");
    g = {};
    g.peak_mps = 2000.0;
    EXPECT_EQ(thrownBy([&] { g.validate(); }).key(), "wind.gusts.peak_mps");
    g = {};
    g.entry = GustEntry::Region;
    g.regionRadius_m = 0.0;
    EXPECT_EQ(thrownBy([&] { g.validate(); }).key(), "wind.gusts.region_radius_m");
    EXPECT_EQ(thrownBy([] { (void)gustEnvelopeFromName("square"); }).key(), "wind.gusts.envelope");
    EXPECT_EQ(thrownBy([] { (void)gustEntryFromName("roof"); }).key(), "wind.gusts.entry");

    Whirlwind w;
    w.coreRadius_m = 0.0;
    EXPECT_EQ(thrownBy([&] { w.validate(); }).key(), "wind.whirlwinds.core_radius_m");
    w = {};
    w.updraft_mps = -1.0;
    EXPECT_EQ(thrownBy([&] { w.validate(); }).key(), "wind.whirlwinds.updraft_mps");
    w = {};
    w.lifetime_s = 0.0;
    EXPECT_EQ(thrownBy([&] { w.validate(); }).key(), "wind.whirlwinds.lifetime_s");
    w = {};
    w.peakSpeed_mps = NaN;
    EXPECT_EQ(thrownBy([&] { w.validate(); }).key(), "wind.whirlwinds.peak_speed_mps");
    EXPECT_EQ(thrownBy([] { (void)vortexProfileFromName("tornado"); }).key(),
              "wind.whirlwinds.profile");
    // No scene key sets the outer radius: a bad one is the caller's bug.
    w = {};
    w.outerRadiusFactor = 0.5;
    EXPECT_NE(logicErrorOf([&] { w.validate(); }).find("outerRadiusFactor"), std::string::npos);
}

TEST(ParameterError, InElementPutsTheIndexIntoTheKey) {
    const ParameterError e("wind.gusts.peak_mps", "2000", "must be in [-1000, 1000]");
    const ParameterError third = e.inElement("wind.gusts", 2);
    EXPECT_EQ(third.key(), "wind.gusts[2].peak_mps");
    EXPECT_EQ(third.value(), "2000");
    EXPECT_EQ(third.expected(), "must be in [-1000, 1000]");
    EXPECT_EQ(e.inElement("wind.whirlwinds", 0).key(), "wind.gusts.peak_mps");
    EXPECT_EQ(e.inElement("wind.gust", 0).key(), "wind.gusts.peak_mps");  // not a prefix
}

TEST(ParameterError, AmbientWindNamesTheSceneKey) {
    AmbientWind a;
    a.speed_mps = -1.0;
    EXPECT_EQ(thrownBy([&] { a.validate(); }).key(), "wind.speed_mps");
    a = {};
    a.direction_deg = NaN;
    EXPECT_EQ(thrownBy([&] { a.validate(); }).key(), "wind.direction_deg");
    a = {};
    a.roughness_m = 0.0;
    EXPECT_EQ(thrownBy([&] { a.validate(); }).key(), "wind.roughness_m");
    // The log law needs z_ref >= 3 z0: 10 m over 5 m roughness is refused at the reference height.
    a = {};
    a.roughness_m = 5.0;
    const ParameterError e = thrownBy([&] { a.validate(); });
    EXPECT_EQ(e.key(), "wind.reference_height_m");
    EXPECT_NE(e.expected().find(">= 15 m"), std::string::npos) << e.what();
    EXPECT_EQ(thrownBy([] { (void)windProfileFromName("power"); }).key(), "wind.profile");
}

TEST(ParameterError, SolverNamesTheSceneKey) {
    const Heightfield flat = makeHeightfield(9, 9, 1.0, std::vector<float>(81, 0.0f));
    DomainSpec spec;
    spec.voxelSize_m = 0.0;
    EXPECT_EQ(thrownBy([&] { AirDomain d(flat, spec); }).key(), "solver.voxel_size_m");
    spec = {};
    spec.top_m = -1.0;
    EXPECT_EQ(thrownBy([&] { AirDomain d(flat, spec); }).key(), "solver.top_m");
    spec = {};
    spec.firstCell_m = 0.5;
    spec.stretchRatio = 1.5;
    EXPECT_EQ(thrownBy([&] { AirDomain d(flat, spec); }).key(), "solver.stretch_ratio");
    spec = {};
    spec.memoryLimit_bytes = 1024.0;
    EXPECT_EQ(thrownBy([&] { AirDomain d(flat, spec); }).key(), "solver.memory_limit_mb");

    const AirDomain domain(flat, DomainSpec{});
    EXPECT_EQ(thrownBy([&] { SteadyWindSolver s(domain, {0.0, 1.0}); }).key(), "solver.alpha_h");
    EXPECT_EQ(thrownBy([&] { SteadyWindSolver s(domain, {1.0, -1.0}); }).key(), "solver.alpha_v");
    // Each weight valid, their ratio (1/10)^2 outside [0.1, 10]: named at alpha_v.
    EXPECT_EQ(thrownBy([&] { SteadyWindSolver s(domain, {1.0, 10.0}); }).key(), "solver.alpha_v");
    EXPECT_EQ(thrownBy([] { (void)steadyModelFromName("rans"); }).key(), "solver.model");

    PoissonSolver poisson(PoissonSystem::uniformBox(4, 4, 4));
    std::vector<double> x;
    const std::vector<double> rhs(64, 1.0);
    SolverSettings bad;
    bad.relativeTolerance = 1.0;
    EXPECT_EQ(thrownBy([&] { (void)poisson.solve(rhs, x, bad); }).key(), "solver.tolerance");
    bad = {};
    bad.maxIterations = 0;
    EXPECT_EQ(thrownBy([&] { (void)poisson.solve(rhs, x, bad); }).key(), "solver.max_iterations");
}

TEST(ParameterError, CallersBugsAreLogicErrorsNotBadInput) {
    EXPECT_NE(logicErrorOf([] {
                  (void)makeHeightfield(2, 2, 1.0, std::vector<float>(3));
              }).find("3 heights"),
              std::string::npos);
    EXPECT_NE(
        logicErrorOf([] { (void)makeTerrain(terrain(TerrainKind::Heightmap)); }).find("heightmap"),
        std::string::npos);
    PoissonSolver poisson(PoissonSystem::uniformBox(4, 4, 4));
    std::vector<double> x, out;
    EXPECT_NE(logicErrorOf([&] { (void)poisson.solve(std::vector<double>(3), x, {}); }).find("rhs"),
              std::string::npos);
    EXPECT_FALSE(logicErrorOf([&] { poisson.applyOperator(std::vector<double>(3), out); }).empty());
    SolverSettings sweeps;
    sweeps.smoothingSweeps = 0;
    EXPECT_NE(logicErrorOf([&] {
                  (void)poisson.solve(std::vector<double>(64), x, sweeps);
              }).find("smoothingSweeps"),
              std::string::npos);
    PoissonSystem sys = PoissonSystem::uniformBox(4, 4, 4);
    sys.weightZ.pop_back();
    EXPECT_NE(logicErrorOf([&] { PoissonSolver p(sys); }).find("weightZ"), std::string::npos);
}

}  // namespace
}  // namespace gale::sim
