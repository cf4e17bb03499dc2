/// \file GridLayout.cpp
/// Stretched vertical levels: world <-> index conversion and the cell-centre lattice.
#include "sim/GridLayout.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/ParameterError.h"
#include "sim/Format.h"

namespace gale::sim {

GridLayout::GridLayout(int nxCells, int nyCells, int nzCells, double voxelSize, const Vec3d& wsMin)
    : GridIndex{nxCells, nyCells, nzCells}, voxelSize_m(voxelSize), wsMin_m(wsMin) {}

GridLayout::GridLayout(int nxCells, int nyCells, double voxelSize, const Vec3d& wsMin,
                       std::vector<double> zLevels)
    : GridIndex{nxCells, nyCells, int(zLevels.size()) - 1},
      voxelSize_m(voxelSize),
      wsMin_m(wsMin),
      mZLevels_m(std::move(zLevels)) {
    if (mZLevels_m.size() < 2)
        throw ParameterError("solver.first_cell_m", std::to_string(mZLevels_m.size()) + " levels",
                             "a stretched layout needs at least 2 levels");
    for (size_t k = 1; k < mZLevels_m.size(); ++k)
        if (!(mZLevels_m[k] > mZLevels_m[k - 1]) || !std::isfinite(mZLevels_m[k]))
            throw ParameterError("solver.first_cell_m", detail::num(mZLevels_m[k]),
                                 "levels must increase (level " + std::to_string(k) + ")");
    wsMin_m[2] = mZLevels_m[0];
}

std::vector<double> GridLayout::zLevels_m() const {
    std::vector<double> z(size_t(nz) + 1);
    for (int k = 0; k <= nz; ++k) z[size_t(k)] = zFace_m(k);
    return z;
}

double GridLayout::stretchedIsZ(double z) const {
    const std::vector<double>& L = mZLevels_m;
    if (!(z >= L.front())) return (z - L.front()) / (L[1] - L[0]);  // below (and NaN)
    if (z >= L.back()) return nz + (z - L.back()) / (L[size_t(nz)] - L[size_t(nz) - 1]);
    const size_t k = size_t(std::upper_bound(L.begin(), L.end(), z) - L.begin()) - 1;
    return double(k) + (z - L[k]) / (L[k + 1] - L[k]);
}

double GridLayout::stretchedWsZ(double Z) const {
    const std::vector<double>& L = mZLevels_m;
    if (!(Z >= 0.0)) return L.front() + Z * (L[1] - L[0]);
    if (Z >= nz) return L.back() + (Z - nz) * (L[size_t(nz)] - L[size_t(nz) - 1]);
    const size_t k = size_t(Z);
    return L[k] + (Z - double(k)) * (L[k + 1] - L[k]);
}

double GridLayout::centreLatticeZ(double Z) const {
    if (!(Z > 0.0)) return Z - 0.5;  // below the box bottom: clamped by the caller
    if (Z >= nz) return Z - 0.5;     // above the last centre: clamped likewise
    const int k = std::min(int(Z), nz - 1);
    const double t = Z - k;  // fraction of layer k
    const double dk = dz_m(k);
    if (t >= 0.5) {
        if (k + 1 >= nz) return k + (t - 0.5);  // above the last centre
        // Between the centres of layers k and k + 1, linear in world z.
        return k + (t - 0.5) * dk / (0.5 * (dk + dz_m(k + 1)));
    }
    if (k == 0) return t - 0.5;  // below the first centre
    const double dm = dz_m(k - 1);
    return (k - 1) + (0.5 * dm + t * dk) / (0.5 * (dm + dk));
}

}  // namespace gale::sim
