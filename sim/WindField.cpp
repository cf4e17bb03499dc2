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

// One axis of a trilinear stencil on a lattice of n samples: the lower sample, the upper one and
// the weight of the upper, for a fractional index coordinate f clamped to the lattice.
struct AxisWeights {
    size_t i0, i1;
    double t;
};

AxisWeights axisWeights(double f, int n) {
    f = std::clamp(f, 0.0, double(n - 1));
    const int i = std::min(static_cast<int>(f), std::max(n - 2, 0));
    return {size_t(i), size_t(std::min(i + 1, n - 1)), n > 1 ? f - i : 0.0};
}

// Trilinear interpolation of a grid of n0 x n1 x n2 samples (index 0 fastest).
double trilinear(const std::vector<double>& a, size_t n0, size_t n1, const AxisWeights& x,
                 const AxisWeights& y, const AxisWeights& z) {
    const double* lo = a.data() + n0 * n1 * z.i0;
    const double* hi = a.data() + n0 * n1 * z.i1;
    auto lerpX = [&](const double* plane, size_t j) {
        const double* row = plane + n0 * j;
        return row[x.i0] + (row[x.i1] - row[x.i0]) * x.t;
    };
    auto lerpXY = [&](const double* plane) {
        const double a = lerpX(plane, y.i0), b = lerpX(plane, y.i1);
        return a + (b - a) * y.t;
    };
    const double c0 = lerpXY(lo), c1 = lerpXY(hi);
    return c0 + (c1 - c0) * z.t;
}

}  // namespace

bool WindField::belowTerrain(double x, double y, double z) const {
    return mTerrain && z < mTerrain->sample(x, y);
}

std::array<double, 3> WindField::velocityAt_mps(double x, double y, double z) const {
    if (belowTerrain(x, y, z)) return {0, 0, 0};
    return velocityAboveTerrainAt_mps(x, y, z);
}

std::array<double, 3> WindField::velocityAboveTerrainAt_mps(double x, double y, double z) const {
    if (mNx == 0) return {0, 0, 0};
    const double X = (x - mWsMin[0]) / mH, Y = (y - mWsMin[1]) / mH, Z = (z - mWsMin[2]) / mH;
    if (!(X >= 0.0 && X <= mNx && Y >= 0.0 && Y <= mNy && Z >= 0.0 && Z <= mNz)) return {0, 0, 0};
    // Each component lives on its own faces: along its own axis on the face lattice (index X),
    // along the other two on the cell-centre lattice (index X - 1/2). Six axis stencils serve
    // the three components.
    const AxisWeights faceX = axisWeights(X, mNx + 1), centreX = axisWeights(X - 0.5, mNx);
    const AxisWeights faceY = axisWeights(Y, mNy + 1), centreY = axisWeights(Y - 0.5, mNy);
    const AxisWeights faceZ = axisWeights(Z, mNz + 1), centreZ = axisWeights(Z - 0.5, mNz);
    const size_t nx = size_t(mNx), ny = size_t(mNy);
    return {trilinear(mU, nx + 1, ny, faceX, centreY, centreZ),
            trilinear(mV, nx, ny + 1, centreX, faceY, centreZ),
            trilinear(mW, nx, ny, centreX, centreY, faceZ)};
}

}  // namespace gale::sim
