/// \file Turbulence.cpp
/// The turbulent kinetic energy at a point (Turbulence.h).
#include "coupling/Turbulence.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace gale::coupling {
namespace {

/// One axis of the bilinear blend across cell columns: the two columns and the far one's weight.
struct ColumnPair {
    int i0, i1;
    double t;
};

ColumnPair columnPair(double wsCoord_m, double wsMin_m, double h_m, int n) {
    const double f = std::clamp((wsCoord_m - wsMin_m) / h_m - 0.5, 0.0, double(n - 1));
    const int i0 = std::min(int(f), std::max(n - 2, 0));
    return {i0, std::min(i0 + 1, n - 1), f - i0};
}

}  // namespace

double sampleTke_m2ps2(const sim::WindField& geometry, const std::vector<double>& tke, double x,
                       double y, double z) {
    const sim::GridLayout& g = geometry.layout();
    if (tke.size() != g.cellCount())
        throw std::invalid_argument("sampleTke_m2ps2: " + std::to_string(tke.size()) +
                                    " values for " + std::to_string(g.cellCount()) + " cells");
    if (g.nx == 0 || g.ny == 0 || g.nz == 0) return std::nan("");
    const double h = g.voxelSize_m;
    const ColumnPair a = columnPair(x, g.wsMin_m[0], h, g.nx);
    const ColumnPair b = columnPair(y, g.wsMin_m[1], h, g.ny);
    // The value of column (i, j) at height z: constant below its lowest air centre and above its
    // top centre, linear between centres.
    auto column = [&](int i, int j, double& out) {
        int kb = 0;
        while (kb < g.nz && !geometry.isAir(i, j, kb)) ++kb;
        if (kb == g.nz) return false;
        if (z <= g.zCentre_m(kb)) {
            out = tke[g.cellIndex(i, j, kb)];
            return true;
        }
        int k = kb;
        while (k + 1 < g.nz && g.zCentre_m(k + 1) < z) ++k;
        if (k + 1 >= g.nz) {
            out = tke[g.cellIndex(i, j, g.nz - 1)];
            return true;
        }
        const double t = (z - g.zCentre_m(k)) / (g.zCentre_m(k + 1) - g.zCentre_m(k));
        out = (1.0 - t) * tke[g.cellIndex(i, j, k)] + t * tke[g.cellIndex(i, j, k + 1)];
        return true;
    };
    double sum = 0.0, weights = 0.0;
    const int is[2] = {a.i0, a.i1}, js[2] = {b.i0, b.i1};
    const double wi[2] = {1.0 - a.t, a.t}, wj[2] = {1.0 - b.t, b.t};
    for (int q = 0; q < 2; ++q)
        for (int p = 0; p < 2; ++p) {
            const double w = wi[p] * wj[q];
            double v;
            if (w <= 0.0 || !column(is[p], js[q], v)) continue;
            sum += w * v, weights += w;
        }
    if (weights <= 0.0) {  // the point sits on a column with no weight: take any column with air
        for (int q = 0; q < 2; ++q)
            for (int p = 0; p < 2; ++p) {
                double v;
                if (column(is[p], js[q], v)) return v;
            }
        return std::nan("");
    }
    return sum / weights;
}

}  // namespace gale::coupling
