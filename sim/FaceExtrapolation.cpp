/// \file FaceExtrapolation.cpp
/// Layer-by-layer averaging of valid face neighbours into faces the terrain closes.
#include "sim/FaceExtrapolation.h"

#include <tbb/parallel_for.h>

namespace gale::sim::detail {

namespace {
/// Below this many fills a layer is applied serially: TBB's scheduling costs more.
constexpr size_t PARALLEL_MIN_FILLS = 4096;
}  // namespace

FaceExtrapolation::FaceExtrapolation(const std::vector<uint8_t>& valid0, const GridIndex& g,
                                     Placement pl, int layers) {
    const auto n = g.dims(pl);
    const int n0 = n[0], n1 = n[1], n2 = n[2];
    // Only the levels k that hold a closed face change (filling reads its neighbours but writes
    // only closed faces); over terrain they are the lowest few, so the rest are skipped.
    std::vector<uint8_t> holdsClosed(size_t(n2), 0);
    for (int k = 0; k < n2; ++k) {
        const size_t begin = g.index(pl, 0, 0, k), end = begin + size_t(n0) * size_t(n1);
        for (size_t p = begin; p < end && !holdsClosed[size_t(k)]; ++p)
            if (!valid0[p]) holdsClosed[size_t(k)] = 1;
    }
    std::vector<uint8_t> valid = valid0, next;
    for (int layer = 0; layer < layers; ++layer) {
        next = valid;
        std::vector<Fill> fills;
        for (int k = 0; k < n2; ++k) {
            if (!holdsClosed[size_t(k)]) continue;
            for (int j = 0; j < n1; ++j)
                for (int i = 0; i < n0; ++i) {
                    const size_t p = g.index(pl, i, j, k);
                    if (valid[p]) continue;
                    Fill f;
                    f.face = p;
                    auto take = [&](int ii, int jj, int kk) {
                        if (ii < 0 || jj < 0 || kk < 0 || ii >= n0 || jj >= n1 || kk >= n2) return;
                        const size_t q = g.index(pl, ii, jj, kk);
                        if (valid[q]) f.from[f.count++] = q;
                    };
                    take(i - 1, j, k), take(i + 1, j, k), take(i, j - 1, k);
                    take(i, j + 1, k), take(i, j, k - 1), take(i, j, k + 1);
                    if (f.count > 0) fills.push_back(f), next[p] = 1;
                }
        }
        mLayers.push_back(std::move(fills));
        valid.swap(next);
    }
    for (size_t p = 0; p < valid.size(); ++p)
        if (!valid[p]) mZeroed.push_back(p);
}

void FaceExtrapolation::apply(std::vector<double>& a) const {
    for (const std::vector<Fill>& fills : mLayers) {
        // A layer reads only faces valid before it and writes only its own: any order will do.
        auto fill = [&](size_t n) {
            const Fill& f = fills[n];
            double s = 0.0;
            for (int c = 0; c < f.count; ++c) s += a[f.from[c]];
            a[f.face] = s / f.count;
        };
        if (fills.size() < PARALLEL_MIN_FILLS)
            for (size_t n = 0; n < fills.size(); ++n) fill(n);
        else
            tbb::parallel_for(size_t(0), fills.size(), fill);
    }
    for (size_t p : mZeroed) a[p] = 0.0;
}

size_t FaceExtrapolation::filledCount() const {
    size_t n = 0;
    for (const auto& fills : mLayers) n += fills.size();
    return n;
}

void extrapolateFaces(std::vector<double>& a, const std::vector<uint8_t>& valid, const GridIndex& g,
                      Placement p, int layers) {
    FaceExtrapolation(valid, g, p, layers).apply(a);
}

}  // namespace gale::sim::detail
