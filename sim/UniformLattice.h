#pragma once
/// \file UniformLattice.h
/// The staggered sampler of a layout with cubic cells (GridLayout::uniformZ()), specialised for
/// the advection's traces: the same trilinear interpolation as GridLayout::sample and
/// GridLayout::sampleFaces, the same clamping to each placement's lattice, but with 1/h
/// precomputed, no layout branches per sample, and each axis's face and cell-centre stencils
/// derived from one floor of the index coordinate. Its answers equal the general sampler's to
/// round-off (a multiplication by 1/h in place of a division by h; the cell-centre fraction taken
/// from the face fraction), which tests/sim/AdvectionUniformLatticeTest.cpp checks.

#include <cstddef>

#include "sim/GridLayout.h"

namespace gale::sim {

/// One axis of a point on a uniform lattice: the stencil on the face lattice (n + 1 samples) and
/// on the cell-centre lattice (n samples), as GridLayout::stencil gives them.
struct AxisPair {
    AxisStencil face, cell;
};

class UniformLattice {
  public:
    /// The layout must have cubic cells (uniformZ()) and at least 2 cells along every axis;
    /// usable() says whether it does. The layout must outlive the lattice.
    explicit UniformLattice(const GridLayout& g)
        : mInvH(1.0 / g.voxelSize_m),
          mMin{g.wsMin_m[0], g.wsMin_m[1], g.wsMin_m[2]},
          mN{g.nx, g.ny, g.nz} {}

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
        const int nx = mN[0], ny = mN[1];
        out[0] = blendStencils(u, nx + 1, ny, x.face, y.cell, z.cell);
        out[1] = blendStencils(v, nx, ny + 1, x.cell, y.face, z.cell);
        out[2] = blendStencils(w, nx, ny, x.cell, y.cell, z.face);
    }

    /// Trilinear sample of q (placement p) at world point ws_m (metres), as GridLayout::sample at
    /// isFromWs(ws_m); lo/hi as blendStencils.
    double sample(Placement p, const double* q, const double* ws_m, double* lo = nullptr,
                  double* hi = nullptr) const {
        const AxisPair x = axis(0, ws_m[0]), y = axis(1, ws_m[1]), z = axis(2, ws_m[2]);
        const int nx = mN[0] + (p == Placement::FaceX), ny = mN[1] + (p == Placement::FaceY);
        return blendStencils(q, nx, ny, p == Placement::FaceX ? x.face : x.cell,
                             p == Placement::FaceY ? y.face : y.cell,
                             p == Placement::FaceZ ? z.face : z.cell, lo, hi);
    }

  private:
    double mInvH;    ///< 1 / h, 1/m
    double mMin[3];  ///< world position of the box's minimum corner, m
    int mN[3];       ///< cells along x, y, z
};

}  // namespace gale::sim
