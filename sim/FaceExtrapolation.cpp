/// \file FaceExtrapolation.cpp
/// Layer-by-layer averaging of valid face neighbours into faces the terrain closes.
#include "sim/FaceExtrapolation.h"

#include <tbb/parallel_for.h>

namespace gale::sim::detail {

void extrapolateFaces(std::vector<double>& a, const std::vector<uint8_t>& valid0,
                      const GridIndex& g, Placement pl, int layers) {
    const auto n = g.dims(pl);
    const int n0 = n[0], n1 = n[1], n2 = n[2];
    // Only the levels k that hold a closed face change (filling reads its neighbours but writes
    // only closed faces); over terrain they are the lowest few, so the rest are skipped.
    std::vector<uint8_t> holdsClosed(size_t(n2), 0);
    tbb::parallel_for(0, n2, [&](int k) {
        const size_t begin = g.index(pl, 0, 0, k), end = begin + size_t(n0) * size_t(n1);
        for (size_t p = begin; p < end; ++p)
            if (!valid0[p]) {
                holdsClosed[size_t(k)] = 1;
                break;
            }
    });
    std::vector<uint8_t> valid = valid0, next;
    for (int layer = 0; layer < layers; ++layer) {
        next = valid;
        tbb::parallel_for(0, n2, [&](int k) {
            if (!holdsClosed[size_t(k)]) return;
            for (int j = 0; j < n1; ++j)
                for (int i = 0; i < n0; ++i) {
                    const size_t p = g.index(pl, i, j, k);
                    if (valid[p]) continue;
                    double s = 0.0;
                    int c = 0;
                    auto take = [&](int ii, int jj, int kk) {
                        if (ii < 0 || jj < 0 || kk < 0 || ii >= n0 || jj >= n1 || kk >= n2) return;
                        const size_t q = g.index(pl, ii, jj, kk);
                        if (valid[q]) s += a[q], ++c;
                    };
                    take(i - 1, j, k), take(i + 1, j, k), take(i, j - 1, k);
                    take(i, j + 1, k), take(i, j, k - 1), take(i, j, k + 1);
                    if (c > 0) a[p] = s / c, next[p] = 1;
                }
        });
        valid.swap(next);
    }
    for (int k = 0; k < n2; ++k) {
        if (!holdsClosed[size_t(k)]) continue;
        const size_t begin = g.index(pl, 0, 0, k), end = begin + size_t(n0) * size_t(n1);
        for (size_t p = begin; p < end; ++p)
            if (!valid[p]) a[p] = 0.0;
    }
}

}  // namespace gale::sim::detail
