/// \file WindField.cpp
#include "sim/WindField.h"

#include <algorithm>
#include <cmath>

namespace gale::sim {

WindField::WindField(const GridLayout& layout, std::shared_ptr<const Heightfield> terrain,
                     std::vector<uint8_t> air)
    : mLayout(layout), mTerrain(std::move(terrain)), mAir(std::move(air)) {
    mU.assign(mLayout.count(Placement::FaceX), 0.0);
    mV.assign(mLayout.count(Placement::FaceY), 0.0);
    mW.assign(mLayout.count(Placement::FaceZ), 0.0);
}

WindField::WindField(int nx, int ny, int nz, double voxelSize_m, std::array<double, 3> wsMin_m,
                     std::shared_ptr<const Heightfield> terrain, std::vector<uint8_t> air)
    : WindField(GridLayout(nx, ny, nz, voxelSize_m, wsMin_m), std::move(terrain), std::move(air)) {}

bool WindField::belowTerrain(double x, double y, double z) const {
    return mTerrain && z < mTerrain->sample(x, y);
}

std::array<double, 3> WindField::velocityAt_mps(double x, double y, double z) const {
    if (belowTerrain(x, y, z)) return {0, 0, 0};
    return velocityAboveTerrainAt_mps(x, y, z);
}

std::array<double, 3> WindField::velocityAboveTerrainAt_mps(double x, double y, double z) const {
    const GridLayout& g = mLayout;
    if (g.nx == 0) return {0, 0, 0};
    const Vec3d is = g.isFromWs({x, y, z});
    if (!g.containsIs(is)) return {0, 0, 0};
    return g.sampleFaces(mU.data(), mV.data(), mW.data(), is);
}

std::array<double, 3> WindField::velocityComponentsAt_mps(
    const std::array<double, 3>& wsUV_m, const std::array<double, 3>& wsW_m) const {
    std::array<double, 3> out{0, 0, 0};
    const GridLayout& g = mLayout;
    if (g.nx == 0) return out;
    const Vec3d is = g.isFromWs(wsUV_m);
    if (g.containsIs(is)) {
        out[0] = g.sample(Placement::FaceX, mU.data(), is);
        out[1] = g.sample(Placement::FaceY, mV.data(), is);
    }
    // w's point usually lies straight above (the log law; the normal over level ground).
    const Vec3d isW = g.isFromWs(wsW_m);
    if (g.containsIs(isW)) out[2] = g.sample(Placement::FaceZ, mW.data(), isW);
    return out;
}

bool WindField::isFlowFace(int axis, int i, int j, int k) const {
    // The face between cells c - 1 and c along `axis` (face index c on that axis, in [0, n]) is a
    // flow face when the cells on both sides that exist are air; the box bottom never is (it lies
    // under the terrain), the other box sides are when their one cell is.
    int c[3] = {i, j, k};
    const int n = axis == 0 ? mLayout.nx : axis == 1 ? mLayout.ny : mLayout.nz;
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
    const Vec3d c = mLayout.wsPosition(Placement(axis), i, j, k);
    return c[2] > mTerrain->sample(c[0], c[1]);
}

bool WindField::readsOnlySolvedFaces(double x, double y, double z, unsigned components) const {
    const GridLayout& g = mLayout;
    if (g.nx == 0) return false;
    const Vec3d is = g.isFromWs({x, y, z});
    if (!g.containsIs(is)) return false;
    // u and v sit on the cell-centre lattice vertically: below the lowest centre (above the
    // highest) their interpolation holds that layer's value instead of interpolating.
    if ((components & (COMPONENT_U | COMPONENT_V)) && !(is[2] >= 0.5 && is[2] <= g.nz - 0.5))
        return false;
    for (int axis = 0; axis < 3; ++axis) {
        if (!(components & (1u << axis))) continue;
        const AxisStencil a = g.stencil(0, axis == 0, is[0]);
        const AxisStencil b = g.stencil(1, axis == 1, is[1]);
        const AxisStencil c = g.stencil(2, axis == 2, is[2]);
        for (int k : {c.i0, c.i1})
            for (int j : {b.i0, b.i1})
                for (int i : {a.i0, a.i1})
                    if (!isSolvedFace(axis, i, j, k)) return false;
    }
    return true;
}

}  // namespace gale::sim
