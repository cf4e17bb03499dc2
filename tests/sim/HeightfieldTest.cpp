// Procedural terrains and the heightfield's sampling and normals.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/Heightfield.h"

using namespace gale::sim;

namespace {

// Central differences on a smooth hill sampled at 0.25 m: O(h^2) slope error, well under this.
constexpr double NORMAL_TOL = 2e-3;

TerrainSpec spec(TerrainKind kind) {
    TerrainSpec s;
    s.kind = kind;
    s.sizeX_m = 100.0;
    s.sizeY_m = 60.0;
    s.spacing_m = 0.5;
    s.height_m = 10.0;
    s.radius_m = 15.0;
    s.centerX_m = 50.0;
    s.centerY_m = 30.0;
    return s;
}

TEST(Heightfield, GridCoversTheRequestedExtent) {
    const Heightfield f = makeTerrain(spec(TerrainKind::Flat));
    EXPECT_EQ(f.nx, 201);
    EXPECT_EQ(f.ny, 121);
    EXPECT_DOUBLE_EQ(f.sizeX_m(), 100.0);
    EXPECT_DOUBLE_EQ(f.sizeY_m(), 60.0);
    EXPECT_EQ(f.maxHeight_m(), 0.0);
}

TEST(Heightfield, GaussianHillPeaksAtTheCentreWithTheGivenHeight) {
    const Heightfield f = makeTerrain(spec(TerrainKind::GaussianHill));
    EXPECT_NEAR(f.sample(50.0, 30.0), 10.0, 1e-5);
    // One sigma out: h = H exp(-1/2).
    EXPECT_NEAR(f.sample(65.0, 30.0), 10.0 * std::exp(-0.5), 1e-4);
}

TEST(Heightfield, HemisphereIsExactOnTheSamples) {
    const Heightfield f = makeTerrain(spec(TerrainKind::Hemisphere));
    EXPECT_NEAR(f.sample(50.0, 30.0), 15.0, 1e-5);
    EXPECT_NEAR(f.sample(59.0, 30.0), std::sqrt(15.0 * 15.0 - 9.0 * 9.0), 1e-4);
    EXPECT_EQ(f.sample(70.0, 30.0), 0.0);
}

TEST(Heightfield, RidgeRunsAlongItsAxisAndValleyIsItsComplement) {
    TerrainSpec s = spec(TerrainKind::Ridge);
    s.axis_deg = 90.0;  // along +y: constant along y, falls off in x
    const Heightfield ridge = makeTerrain(s);
    EXPECT_NEAR(ridge.sample(50.0, 5.0), ridge.sample(50.0, 55.0), 1e-4);
    EXPECT_GT(ridge.sample(50.0, 5.0), ridge.sample(70.0, 5.0));
    s.kind = TerrainKind::Valley;
    const Heightfield valley = makeTerrain(s);
    EXPECT_NEAR(valley.sample(50.0, 20.0), 0.0, 1e-5);
    EXPECT_NEAR(valley.sample(70.0, 20.0) + ridge.sample(70.0, 20.0), 10.0, 1e-4);
}

TEST(Heightfield, FractalIsDeterministicPerSeedAndBounded) {
    TerrainSpec s = spec(TerrainKind::Fractal);
    const Heightfield a = makeTerrain(s), b = makeTerrain(s);
    EXPECT_EQ(a.height_m, b.height_m);
    s.seed = 2;
    EXPECT_NE(makeTerrain(s).height_m, a.height_m);
    EXPECT_GE(a.minHeight_m(), 0.0);
    EXPECT_LE(a.maxHeight_m(), 10.0);
    EXPECT_GT(a.maxHeight_m() - a.minHeight_m(), 1.0);
}

TEST(Heightfield, NormalsMatchTheAnalyticSlope) {
    TerrainSpec s = spec(TerrainKind::GaussianHill);
    s.spacing_m = 0.25;
    const Heightfield f = makeTerrain(s);
    for (int i : {100, 200, 240}) {
        const double x = i * s.spacing_m, dx = x - 50.0;
        const double dhdx = -dx / (15.0 * 15.0) * 10.0 * std::exp(-dx * dx / (2 * 225.0));
        const double len = std::sqrt(dhdx * dhdx + 1.0);
        const auto n = f.normalAt(i, 120);
        EXPECT_NEAR(n[0], -dhdx / len, NORMAL_TOL);
        EXPECT_NEAR(n[1], 0.0, NORMAL_TOL);
        EXPECT_NEAR(n[2], 1.0 / len, NORMAL_TOL);
    }
}

TEST(Heightfield, RejectsBadSpecsWithTheFieldName) {
    TerrainSpec s = spec(TerrainKind::GaussianHill);
    s.spacing_m = 0.0;
    try {
        makeTerrain(s);
        FAIL() << "zero spacing accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("terrain.spacing_m"), std::string::npos) << e.what();
    }
    s.spacing_m = 1e-4;  // 1e6 samples per side
    EXPECT_THROW(makeTerrain(s), std::invalid_argument);
    s = spec(TerrainKind::GaussianHill);
    s.height_m = NAN;
    EXPECT_THROW(makeTerrain(s), std::invalid_argument);
    EXPECT_THROW(makeHeightfield(1, 1, 1.0, {0.0f}), std::invalid_argument);
    EXPECT_THROW(makeHeightfield(2, 2, 1.0, {0.0f, NAN, 0.0f, 0.0f}), std::invalid_argument);
    EXPECT_THROW(makeHeightfield(2, 2, -1.0, {0.0f, 0.0f, 0.0f, 0.0f}), std::invalid_argument);
    EXPECT_THROW(terrainKindFromName("mountain"), std::invalid_argument);
}

}  // namespace
