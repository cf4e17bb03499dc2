/// \file FaceExtrapolationTest.cpp
/// The closed faces' refill worked out once from a mask (sim/FaceExtrapolation.h) against its
/// definition, layer by layer, written out here: each layer's closed faces with a valid
/// neighbour get the mean of those neighbours (-x, +x, -y, +y, -z, +z), faces still closed get 0.

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "sim/FaceExtrapolation.h"

namespace {

using namespace gale::sim;

/// The definition, face by face and layer by layer.
std::vector<double> byDefinition(std::vector<double> a, std::vector<uint8_t> valid,
                                 const GridIndex& g, Placement p, int layers) {
    const auto n = g.dims(p);
    for (int layer = 0; layer < layers; ++layer) {
        std::vector<uint8_t> next = valid;
        std::vector<double> filled = a;
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    const size_t f = g.index(p, i, j, k);
                    if (valid[f]) continue;
                    double sum = 0.0;
                    int count = 0;
                    const int d[6][3] = {{-1, 0, 0}, {1, 0, 0},  {0, -1, 0},
                                         {0, 1, 0},  {0, 0, -1}, {0, 0, 1}};
                    for (const auto& o : d) {
                        const int ii = i + o[0], jj = j + o[1], kk = k + o[2];
                        if (ii < 0 || jj < 0 || kk < 0 || ii >= n[0] || jj >= n[1] || kk >= n[2])
                            continue;
                        const size_t q = g.index(p, ii, jj, kk);
                        if (valid[q]) sum += a[q], ++count;
                    }
                    if (count > 0) filled[f] = sum / count, next[f] = 1;
                }
        a = filled, valid = next;
    }
    for (size_t f = 0; f < a.size(); ++f)
        if (!valid[f]) a[f] = 0.0;
    return a;
}

TEST(FaceExtrapolation, TheListAppliedIsTheLayerByLayerDefinitionOnEveryPlacement) {
    GridLayout g(64, 48, 12, 1.0, {0.0, 0.0, 0.0});  // layers of more than 4096 fills: threaded
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> value(-5.0, 5.0);
    for (int pl = 0; pl < 3; ++pl) {
        const Placement p = Placement(pl);
        const size_t n = g.count(p);
        // Closed below a bumpy ground, plus scattered closed faces above it.
        std::vector<uint8_t> valid(n, 1);
        const auto d = g.dims(p);
        for (int k = 0; k < d[2]; ++k)
            for (int j = 0; j < d[1]; ++j)
                for (int i = 0; i < d[0]; ++i)
                    if (k < 1 + (i * 7 + j * 3) % 5 || rng() % 13 == 0)
                        valid[g.index(p, i, j, k)] = 0;
        std::vector<double> a(n);
        for (double& v : a) v = value(rng);
        for (int layers : {1, 2, 4}) {
            const std::vector<double> want = byDefinition(a, valid, g, p, layers);
            std::vector<double> got = a;
            const detail::FaceExtrapolation plan(valid, g, p, layers);
            plan.apply(got);
            ASSERT_EQ(got.size(), want.size());
            for (size_t f = 0; f < n; ++f)
                ASSERT_EQ(got[f], want[f])
                    << "placement " << pl << ", layers " << layers << ", face " << f;
            EXPECT_GT(plan.filledCount(), 0u);
            // Applied again to other values, the same list fills them by the same rule.
            std::vector<double> b(n);
            for (double& v : b) v = value(rng);
            const std::vector<double> wantB = byDefinition(b, valid, g, p, layers);
            plan.apply(b);
            for (size_t f = 0; f < n; ++f) ASSERT_EQ(b[f], wantB[f]);
        }
    }
}

}  // namespace
