#pragma once
/// \file UniformLattice.h
/// The staggered sampler of a layout with cubic cells (GridLayout::uniformZ()), specialised for
/// the advection's traces: the same trilinear interpolation as GridLayout::sample and
/// GridLayout::sampleFaces, the same clamping to each placement's lattice, but with 1/h
/// precomputed, no layout branches per sample, each axis's face and cell-centre stencils from one
/// index coordinate, shared by the three components, and the 8 values of a cell addressed from one
/// base index with the placement's strides (every lattice has at least 2 samples per axis, so the
/// upper sample is always the next one). Its answers equal the general sampler's to
/// round-off (a multiplication by 1/h in place of a division by h), which
/// tests/sim/AdvectionUniformLatticeTest.cpp checks.

#include <algorithm>
#include <cstddef>

#include "sim/GridLayout.h"

namespace gale::sim {

/// One axis of a point on a uniform lattice: the stencil on the face lattice (n + 1 samples) and
/// on the cell-centre lattice (n samples), as GridLayout::stencil gives them.
struct AxisPair {
    AxisStencil face, cell;
};

/// Trilinear blend of the 8 samples of a cell of a lattice with at least 2 samples per axis:
/// p points at the lower corner, sy and sz are the array's strides along y and z, tx, ty, tz the
/// weights of the upper samples. Along x, then y, then z, in blendStencils' order (so equal
/// stencils give bit-equal answers). If lo/hi are given they receive the min/max of the 8.
inline double blendCorner(const double* p, size_t sy, size_t sz, double tx, double ty, double tz) {
    const double c00 = p[0] + (p[1] - p[0]) * tx, c10 = p[sy] + (p[sy + 1] - p[sy]) * tx;
    const double c01 = p[sz] + (p[sz + 1] - p[sz]) * tx;
    const double c11 = p[sy + sz] + (p[sy + sz + 1] - p[sy + sz]) * tx;
    const double c0 = c00 + (c10 - c00) * ty, c1 = c01 + (c11 - c01) * ty;
    return c0 + (c1 - c0) * tz;
}

class UniformLattice {
  public:
    /// The layout must have cubic cells (uniformZ()) and at least 2 cells along every axis;
    /// usable() says whether it does. The lattice copies what it needs of the layout.
    explicit UniformLattice(const GridLayout& g)
        : mInvH(1.0 / g.voxelSize_m),
          mMin{g.wsMin_m[0], g.wsMin_m[1], g.wsMin_m[2]},
          mN{g.nx, g.ny, g.nz} {
        for (int p = 0; p < 4; ++p) {
            const auto d = g.dims(Placement(p));
            mStrideY[p] = size_t(d[0]);
            mStrideZ[p] = size_t(d[0]) * size_t(d[1]);
        }
    }

    /// True when the layout has cubic cells and at least 2 cells along each axis (the fast path's
    /// stencils assume both).
    static bool usable(const GridLayout& g) {
        return g.uniformZ() && g.nx >= 2 && g.ny >= 2 && g.nz >= 2;
    }

    /// The face and cell-centre stencils along `axis` at world coordinate ws_m (metres), clamped
    /// to each lattice like latticeStencil. A NaN coordinate clamps to the first sample.
    AxisPair axis(int axis, double ws_m) const {
        const int n = mN[axis];
        const double c = (ws_m - mMin[axis]) * mInvH;  // index coordinate, cells
        AxisPair s;
        // Face lattice: samples at 0 .. n.
        const double f = c > 0.0 ? (c < n ? c : double(n)) : 0.0;
        int i = int(f);
        if (i > n - 1) i = n - 1;
        s.face = {i, i + 1, f - i};
        // Cell-centre lattice: samples at 0.5 .. n - 0.5 (lattice coordinate c - 0.5).
        const double e = c - 0.5 > 0.0 ? (c - 0.5 < n - 1 ? c - 0.5 : double(n - 1)) : 0.0;
        int j = int(e);
        if (j > n - 2) j = n - 2;
        s.cell = {j, j + 1, e - j};
        return s;
    }

    /// The three MAC components (same units as u, v, w) at world point ws_m (metres): u from its
    /// x-faces, v from its y-faces, w from its z-faces, as GridLayout::sampleFaces at
    /// isFromWs(ws_m).
    void sampleFaces(const double* u, const double* v, const double* w, const double* ws_m,
                     double* out) const {
        const AxisPair x = axis(0, ws_m[0]), y = axis(1, ws_m[1]), z = axis(2, ws_m[2]);
        out[0] = blendAt(0, u, x.face, y.cell, z.cell);
        out[1] = blendAt(1, v, x.cell, y.face, z.cell);
        out[2] = blendAt(2, w, x.cell, y.cell, z.face);
    }

    /// Trilinear sample of q (placement p) at world point ws_m (metres), as GridLayout::sample at
    /// isFromWs(ws_m); lo/hi (both or neither) receive the min/max of the 8 values used.
    double sample(Placement p, const double* q, const double* ws_m, double* lo = nullptr,
                  double* hi = nullptr) const {
        const AxisPair x = axis(0, ws_m[0]), y = axis(1, ws_m[1]), z = axis(2, ws_m[2]);
        const AxisStencil& sx = p == Placement::FaceX ? x.face : x.cell;
        const AxisStencil& sy = p == Placement::FaceY ? y.face : y.cell;
        const AxisStencil& sz = p == Placement::FaceZ ? z.face : z.cell;
        if (!lo) return blendAt(int(p), q, sx, sy, sz);
        const size_t Y = mStrideY[int(p)], Z = mStrideZ[int(p)];
        const double* c = q + size_t(sx.i0) + Y * size_t(sy.i0) + Z * size_t(sz.i0);
        *lo = std::min({c[0], c[1], c[Y], c[Y + 1], c[Z], c[Z + 1], c[Y + Z], c[Y + Z + 1]});
        *hi = std::max({c[0], c[1], c[Y], c[Y + 1], c[Z], c[Z + 1], c[Y + Z], c[Y + Z + 1]});
        return blendCorner(c, Y, Z, sx.t, sy.t, sz.t);
    }

  private:
    double blendAt(int p, const double* q, const AxisStencil& x, const AxisStencil& y,
                   const AxisStencil& z) const {
        const size_t Y = mStrideY[p], Z = mStrideZ[p];
        return blendCorner(q + size_t(x.i0) + Y * size_t(y.i0) + Z * size_t(z.i0), Y, Z, x.t, y.t,
                           z.t);
    }

    double mInvH;        ///< 1 / h, 1/m
    double mMin[3];      ///< world position of the box's minimum corner, m
    int mN[3];           ///< cells along x, y, z
    size_t mStrideY[4];  ///< array stride along y of each placement (Placement as index)
    size_t mStrideZ[4];  ///< array stride along z of each placement
};

}  // namespace gale::sim
