/// \file WindField.cpp
#include "sim/WindField.h"

#include <algorithm>
#include <cmath>

namespace gale::sim {

WindField::WindField(int nx, int ny, int nz, double voxelSize_m, std::array<double, 3> wsMin_m,
                     std::shared_ptr<const Heightfield> terrain, std::vector<uint8_t> air)
    : mNx(nx),
      mNy(ny),
      mNz(nz),
      mH(voxelSize_m),
      mWsMin(wsMin_m),
      mTerrain(std::move(terrain)),
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
        const double r0 = lerpX(plane, y.i0), r1 = lerpX(plane, y.i1);
        return r0 + (r1 - r0) * y.t;
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

std::array<double, 3> WindField::velocityComponentsAt_mps(
    const std::array<double, 3>& wsUV_m, const std::array<double, 3>& wsW_m) const {
    std::array<double, 3> out{0, 0, 0};
    if (mNx == 0) return out;
    const size_t nx = size_t(mNx), ny = size_t(mNy);
    const double X = (wsUV_m[0] - mWsMin[0]) / mH, Y = (wsUV_m[1] - mWsMin[1]) / mH,
                 Z = (wsUV_m[2] - mWsMin[2]) / mH;
    const bool uvInBox = X >= 0.0 && X <= mNx && Y >= 0.0 && Y <= mNy && Z >= 0.0 && Z <= mNz;
    const AxisWeights centreX = axisWeights(X - 0.5, mNx), centreY = axisWeights(Y - 0.5, mNy);
    if (uvInBox) {
        const AxisWeights centreZ = axisWeights(Z - 0.5, mNz);
        out[0] = trilinear(mU, nx + 1, ny, axisWeights(X, mNx + 1), centreY, centreZ);
        out[1] = trilinear(mV, nx, ny + 1, centreX, axisWeights(Y, mNy + 1), centreZ);
    }
    // w's point usually lies straight above (the log law; the normal over level ground): its
    // horizontal stencils are u's and v's.
    if (wsW_m[0] == wsUV_m[0] && wsW_m[1] == wsUV_m[1]) {
        const double Zw = (wsW_m[2] - mWsMin[2]) / mH;
        if (uvInBox || (X >= 0.0 && X <= mNx && Y >= 0.0 && Y <= mNy))
            if (Zw >= 0.0 && Zw <= mNz)
                out[2] = trilinear(mW, nx, ny, centreX, centreY, axisWeights(Zw, mNz + 1));
        return out;
    }
    const double Xw = (wsW_m[0] - mWsMin[0]) / mH, Yw = (wsW_m[1] - mWsMin[1]) / mH,
                 Zw = (wsW_m[2] - mWsMin[2]) / mH;
    if (Xw >= 0.0 && Xw <= mNx && Yw >= 0.0 && Yw <= mNy && Zw >= 0.0 && Zw <= mNz)
        out[2] = trilinear(mW, nx, ny, axisWeights(Xw - 0.5, mNx), axisWeights(Yw - 0.5, mNy),
                           axisWeights(Zw, mNz + 1));
    return out;
}

bool WindField::isFlowFace(int axis, int i, int j, int k) const {
    // The face between cells c - 1 and c along `axis` (face index c on that axis, in [0, n]) is a
    // flow face when the cells on both sides that exist are air; the box bottom never is (it lies
    // under the terrain), the other box sides are when their one cell is.
    int c[3] = {i, j, k};
    const int n = axis == 0 ? mNx : axis == 1 ? mNy : mNz;
    const int face = c[axis];
    if (axis == 2 && face == 0) return false;
    if (face > 0) {
        c[axis] = face - 1;
        if (!isAir(c[0], c[1], c[2])) return false;
    }
    if (face < n) {
        c[axis] = face;
        if (!isAir(c[0], c[1], c[2])) return false;
    }
    return true;
}

bool WindField::isSolvedFace(int axis, int i, int j, int k) const {
    if (!isFlowFace(axis, i, j, k)) return false;
    if (!mTerrain) return true;
    double c[3] = {mWsMin[0] + (i + 0.5) * mH, mWsMin[1] + (j + 0.5) * mH,
                   mWsMin[2] + (k + 0.5) * mH};
    c[axis] -= 0.5 * mH;
    return c[2] > mTerrain->sample(c[0], c[1]);
}

bool WindField::readsOnlySolvedFaces(double x, double y, double z, unsigned components) const {
    if (mNx == 0) return false;
    const double X = (x - mWsMin[0]) / mH, Y = (y - mWsMin[1]) / mH, Z = (z - mWsMin[2]) / mH;
    if (!(X >= 0.0 && X <= mNx && Y >= 0.0 && Y <= mNy && Z >= 0.0 && Z <= mNz)) return false;
    // u and v sit on the cell-centre lattice vertically: below the lowest centre (above the
    // highest) their interpolation holds that layer's value instead of interpolating.
    if ((components & (COMPONENT_U | COMPONENT_V)) && !(Z >= 0.5 && Z <= mNz - 0.5)) return false;
    const AxisWeights faceX = axisWeights(X, mNx + 1), centreX = axisWeights(X - 0.5, mNx);
    const AxisWeights faceY = axisWeights(Y, mNy + 1), centreY = axisWeights(Y - 0.5, mNy);
    const AxisWeights faceZ = axisWeights(Z, mNz + 1), centreZ = axisWeights(Z - 0.5, mNz);
    const AxisWeights* stencil[3][3] = {
        {&faceX, &centreY, &centreZ}, {&centreX, &faceY, &centreZ}, {&centreX, &centreY, &faceZ}};
    for (int axis = 0; axis < 3; ++axis) {
        if (!(components & (1u << axis))) continue;
        const AxisWeights& a = *stencil[axis][0];
        const AxisWeights& b = *stencil[axis][1];
        const AxisWeights& c = *stencil[axis][2];
        for (size_t k : {c.i0, c.i1})
            for (size_t j : {b.i0, b.i1})
                for (size_t i : {a.i0, a.i1})
                    if (!isSolvedFace(axis, int(i), int(j), int(k))) return false;
    }
    return true;
}

}  // namespace gale::sim
