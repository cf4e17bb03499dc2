/// \file WindField.cpp
#include "sim/WindField.h"

#include <algorithm>
#include <cmath>

namespace gale::sim {

WindField::WindField(int nx, int ny, int nz, double voxelSize_m, std::array<double, 3> wsMin_m,
                     std::shared_ptr<const Heightfield> terrain, std::vector<uint8_t> air)
    : mNx(nx), mNy(ny), mNz(nz), mH(voxelSize_m), mWsMin(wsMin_m), mTerrain(std::move(terrain)),
      mAir(std::move(air)) {
    mU.assign(size_t(nx + 1) * ny * nz, 0.0);
    mV.assign(size_t(nx) * (ny + 1) * nz, 0.0);
    mW.assign(size_t(nx) * ny * (nz + 1), 0.0);
}

namespace {
// Trilinear interpolation on a grid of n0 x n1 x n2 samples (index 0 fastest) at fractional
// index coordinates, clamped to the grid.
double trilinear(const std::vector<double>& a, int n0, int n1, int n2, double f0, double f1, double f2) {
    f0 = std::clamp(f0, 0.0, double(n0 - 1));
    f1 = std::clamp(f1, 0.0, double(n1 - 1));
    f2 = std::clamp(f2, 0.0, double(n2 - 1));
    const int i = std::min(int(f0), std::max(n0 - 2, 0)), j = std::min(int(f1), std::max(n1 - 2, 0)),
              k = std::min(int(f2), std::max(n2 - 2, 0));
    const double t0 = n0 > 1 ? f0 - i : 0.0, t1 = n1 > 1 ? f1 - j : 0.0, t2 = n2 > 1 ? f2 - k : 0.0;
    const int i1 = std::min(i + 1, n0 - 1), j1 = std::min(j + 1, n1 - 1), k1 = std::min(k + 1, n2 - 1);
    auto at = [&](int x, int y, int z) { return a[size_t(x) + size_t(n0) * (y + size_t(n1) * z)]; };
    const double c00 = at(i, j, k) * (1 - t0) + at(i1, j, k) * t0;
    const double c10 = at(i, j1, k) * (1 - t0) + at(i1, j1, k) * t0;
    const double c01 = at(i, j, k1) * (1 - t0) + at(i1, j, k1) * t0;
    const double c11 = at(i, j1, k1) * (1 - t0) + at(i1, j1, k1) * t0;
    return (c00 * (1 - t1) + c10 * t1) * (1 - t2) + (c01 * (1 - t1) + c11 * t1) * t2;
}
}  // namespace

std::array<double, 3> WindField::velocityAt_mps(double x, double y, double z) const {
    if (mNx == 0) return {0, 0, 0};
    const double X = (x - mWsMin[0]) / mH, Y = (y - mWsMin[1]) / mH, Z = (z - mWsMin[2]) / mH;
    if (!(X >= 0.0 && X <= mNx && Y >= 0.0 && Y <= mNy && Z >= 0.0 && Z <= mNz)) return {0, 0, 0};
    if (mTerrain && z < mTerrain->sample(x, y)) return {0, 0, 0};
    return {trilinear(mU, mNx + 1, mNy, mNz, X, Y - 0.5, Z - 0.5),
            trilinear(mV, mNx, mNy + 1, mNz, X - 0.5, Y, Z - 0.5),
            trilinear(mW, mNx, mNy, mNz + 1, X - 0.5, Y - 0.5, Z)};
}

}  // namespace gale::sim
