/// \file GridLayoutTest.cpp
/// The one grid layout (sim/GridLayout.h): world <-> index round trips, the face indices are a
/// bijection onto each array, and the staggered sampler reproduces linear fields exactly, with
/// cubic cells and with stretched layers.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "base/ParameterError.h"
#include "sim/GridLayout.h"

namespace {

using gale::sim::GridLayout;
using gale::sim::Placement;
using gale::sim::Vec3d;

/// Round trips and linear reproduction are exact up to a few roundings of O(1) coordinates.
constexpr double ROUND_OFF = 1e-11;

GridLayout cubicLayout() { return GridLayout(7, 5, 6, 2.5, {-10.0, 4.0, 100.0}); }

/// Layers from 0.5 m growing by 1.2, as a stretched scene makes them.
GridLayout stretchedLayout() {
    std::vector<double> z{100.0};
    double dz = 0.5;
    for (int k = 0; k < 9; ++k, dz *= 1.2) z.push_back(z.back() + dz);
    return GridLayout(7, 5, 2.0, {-10.0, 4.0, 100.0}, z);
}

std::vector<GridLayout> layouts() { return {cubicLayout(), stretchedLayout()}; }

/// A linear field in world coordinates, the sampler's exact case.
double linearField(const Vec3d& ws) { return 1.5 + 0.3 * ws[0] - 0.7 * ws[1] + 2.1 * ws[2]; }

TEST(GridLayout, IndexToWorldRoundTripIsExact) {
    std::mt19937 rng(7);
    for (const GridLayout& g : layouts()) {
        std::uniform_real_distribution<double> X(-1.0, g.nx + 1.0), Y(-1.0, g.ny + 1.0),
            Z(-1.0, g.nz + 1.0);
        for (int n = 0; n < 1000; ++n) {
            const Vec3d is{X(rng), Y(rng), Z(rng)};
            const Vec3d back = g.isFromWs(g.wsFromIs(is));
            for (int a = 0; a < 3; ++a) EXPECT_NEAR(back[a], is[a], ROUND_OFF);
        }
        // Level k is index k, the box top index nz.
        for (int k = 0; k <= g.nz; ++k) EXPECT_NEAR(g.isZFromWs(g.zFace_m(k)), k, ROUND_OFF);
        EXPECT_NEAR(g.isZFromWs(g.wsTop_m()), g.nz, ROUND_OFF);
    }
}

TEST(GridLayout, CellCentresAndFacesSitWhereTheFileCommentSays) {
    for (const GridLayout& g : layouts()) {
        for (int k = 0; k < g.nz; ++k) {
            const Vec3d c = g.wsPosition(Placement::Cell, 2, 3, k);
            EXPECT_NEAR(c[0], g.wsMin_m[0] + 2.5 * g.voxelSize_m, ROUND_OFF);
            EXPECT_NEAR(c[1], g.wsMin_m[1] + 3.5 * g.voxelSize_m, ROUND_OFF);
            EXPECT_NEAR(c[2], 0.5 * (g.zFace_m(k) + g.zFace_m(k + 1)), ROUND_OFF);
            EXPECT_NEAR(g.dz_m(k), g.zFace_m(k + 1) - g.zFace_m(k), ROUND_OFF);
            // The centre of layer k is index k + 1/2 in both kinds of layout.
            EXPECT_NEAR(g.isFromWs(c)[2], k + 0.5, ROUND_OFF);
        }
        EXPECT_NEAR(g.wsPosition(Placement::FaceX, 0, 0, 0)[0], g.wsMin_m[0], ROUND_OFF);
        EXPECT_NEAR(g.wsPosition(Placement::FaceZ, 0, 0, 0)[2], g.wsMin_m[2], ROUND_OFF);
    }
}

TEST(GridLayout, FaceIndicesAreABijectionOntoEachArray) {
    const GridLayout g = stretchedLayout();
    for (Placement p : {Placement::FaceX, Placement::FaceY, Placement::FaceZ, Placement::Cell}) {
        const auto d = g.dims(p);
        std::vector<int> hits(g.count(p), 0);
        for (int k = 0; k < d[2]; ++k)
            for (int j = 0; j < d[1]; ++j)
                for (int i = 0; i < d[0]; ++i) {
                    const size_t n = g.index(p, i, j, k);
                    ASSERT_LT(n, hits.size());
                    ++hits[n];
                }
        for (int h : hits) EXPECT_EQ(h, 1);
    }
    // The named accessors are the same formula, and neighbours along x are adjacent.
    EXPECT_EQ(g.faceXIndex(3, 2, 1), g.index(Placement::FaceX, 3, 2, 1));
    EXPECT_EQ(g.faceZIndex(3, 2, 1) + size_t(g.nx) * g.ny, g.faceZIndex(3, 2, 2));
    EXPECT_EQ(g.faceYIndex(3, 2, 1) + size_t(g.nx), g.faceYIndex(3, 3, 1));
    EXPECT_EQ(g.cellIndex(3, 2, 1) + 1, g.cellIndex(4, 2, 1));
}

TEST(GridLayout, SamplerReproducesALinearFieldOnSamplesAndBetweenThem) {
    std::mt19937 rng(11);
    for (const GridLayout& g : layouts()) {
        for (Placement p :
             {Placement::FaceX, Placement::FaceY, Placement::FaceZ, Placement::Cell}) {
            const auto d = g.dims(p);
            std::vector<double> q(g.count(p));
            for (int k = 0; k < d[2]; ++k)
                for (int j = 0; j < d[1]; ++j)
                    for (int i = 0; i < d[0]; ++i)
                        q[g.index(p, i, j, k)] = linearField(g.wsPosition(p, i, j, k));
            // On every sample.
            for (int k = 0; k < d[2]; ++k)
                for (int j = 0; j < d[1]; ++j)
                    for (int i = 0; i < d[0]; ++i) {
                        const Vec3d ws = g.wsPosition(p, i, j, k);
                        EXPECT_NEAR(g.sample(p, q.data(), g.isFromWs(ws)), linearField(ws),
                                    ROUND_OFF * 100);
                    }
            // Between samples: anywhere inside the hull of this placement's samples (outside
            // it the sampler holds the end layer, by design).
            const Vec3d lo = g.wsPosition(p, 0, 0, 0);
            const Vec3d hi = g.wsPosition(p, d[0] - 1, d[1] - 1, d[2] - 1);
            std::uniform_real_distribution<double> t(0.0, 1.0);
            for (int n = 0; n < 500; ++n) {
                const Vec3d ws{lo[0] + t(rng) * (hi[0] - lo[0]), lo[1] + t(rng) * (hi[1] - lo[1]),
                               lo[2] + t(rng) * (hi[2] - lo[2])};
                EXPECT_NEAR(g.sample(p, q.data(), g.isFromWs(ws)), linearField(ws),
                            ROUND_OFF * 100);
            }
        }
    }
}

TEST(GridLayout, SampleFacesEqualsTheThreeSingleSamples) {
    const GridLayout g = stretchedLayout();
    std::vector<double> u(g.count(Placement::FaceX)), v(g.count(Placement::FaceY)),
        w(g.count(Placement::FaceZ));
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> r(-5.0, 5.0);
    for (auto* a : {&u, &v, &w})
        for (double& x : *a) x = r(rng);
    const Vec3d is{2.3, 1.7, 3.4};
    const Vec3d all = g.sampleFaces(u.data(), v.data(), w.data(), is);
    EXPECT_EQ(all[0], g.sample(Placement::FaceX, u.data(), is));
    EXPECT_EQ(all[1], g.sample(Placement::FaceY, v.data(), is));
    EXPECT_EQ(all[2], g.sample(Placement::FaceZ, w.data(), is));
}

TEST(GridLayout, LevelsThatDoNotIncreaseAreRefused) {
    EXPECT_THROW(GridLayout(4, 4, 1.0, {0, 0, 0}, {0.0, 1.0, 1.0}), gale::ParameterError);
    EXPECT_THROW(GridLayout(4, 4, 1.0, {0, 0, 0}, {0.0}), gale::ParameterError);
    EXPECT_THROW(GridLayout(4, 4, 1.0, {0, 0, 0}, {0.0, NAN}), gale::ParameterError);
}

}  // namespace
