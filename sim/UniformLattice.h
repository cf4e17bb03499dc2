#pragma once
/// \file UniformLattice.h
/// \internal Included only by sim/ and tests/sim (docs/architecture.md lists sim's public headers).
/// The staggered sampler of a layout with cubic cells (GridLayout::uniformZ()), specialised for
/// the advection's traces: the same trilinear interpolation as GridLayout::sample and
/// GridLayout::sampleFaces, the same clamping to each placement's lattice, but with 1/h
/// precomputed, no layout branches per sample, each axis's face and cell-centre stencils from one
/// index coordinate, shared by the three components, and the 8 values of a cell addressed from one
/// base index with the placement's strides (every lattice has at least 2 samples per axis, so the
/// upper sample is always the next one). Its answers equal the general sampler's to
/// round-off (a multiplication by 1/h in place of a division by h), which
/// tests/sim/AdvectionUniformLatticeTest.cpp checks. At a sample of a lattice (where every trace
/// starts) facesAtSample reads the velocity from the sample's neighbours without a stencil.

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
/// weights of the upper samples. The same trilinearBlend as blendStencils on the same 8 values
/// in the same order, so equal stencils give bit-equal answers.
inline double blendCorner(const double* p, size_t sy, size_t sz, double tx, double ty, double tz) {
    const double c[8] = {p[0],  p[1],      p[sy],      p[sy + 1],
                         p[sz], p[sz + 1], p[sy + sz], p[sy + sz + 1]};
    return trilinearBlend(c, tx, ty, tz);
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
        const double c = indexCoordinate(axis, ws_m);
        return {faceStencil(axis, c), cellStencil(axis, c)};
    }

    /// Index coordinate (cells) along `axis` of world coordinate ws_m (metres).
    double indexCoordinate(int axis, double ws_m) const { return (ws_m - mMin[axis]) * mInvH; }

    /// The stencil at index coordinate c on the face lattice of `axis` (samples at 0 .. n).
    AxisStencil faceStencil(int axis, double c) const {
        const int n = mN[axis];
        const double f = c > 0.0 ? (c < n ? c : double(n)) : 0.0;
        int i = int(f);
        if (i > n - 1) i = n - 1;
        return {i, i + 1, f - i};
    }

    /// The stencil at index coordinate c on the cell-centre lattice of `axis` (samples at
    /// 0.5 .. n - 0.5, lattice coordinate c - 0.5).
    AxisStencil cellStencil(int axis, double c) const {
        const int n = mN[axis];
        const double e = c - 0.5 > 0.0 ? (c - 0.5 < n - 1 ? c - 0.5 : double(n - 1)) : 0.0;
        int j = int(e);
        if (j > n - 2) j = n - 2;
        return {j, j + 1, e - j};
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

    /// The three MAC components (same units as u, v, w) at sample (i, j, k) of placement p (index
    /// space; the sample must lie in p's lattice): what sampleFaces gives at that sample's world
    /// position, from the samples themselves instead of a stencil. A component on p's own
    /// placement is the sample's value; along an axis where the component sits half a cell off,
    /// its two neighbours are averaged (one at a box side, where the lattice clamps), so each
    /// component is 1, 2 or 4 reads. Equal to sampleFaces to round-off (the weights here are
    /// exactly 1/2, there 1/2 up to the rounding of the world coordinate).
    void facesAtSample(Placement p, int i, int j, int k, const double* u, const double* v,
                       const double* w, double* out) const {
        switch (p) {  // the placement as a constant, so the loops below unroll to straight reads
            case Placement::FaceX:
                return facesAt<0>(i, j, k, u, v, w, out);
            case Placement::FaceY:
                return facesAt<1>(i, j, k, u, v, w, out);
            case Placement::FaceZ:
                return facesAt<2>(i, j, k, u, v, w, out);
            case Placement::Cell:
                return facesAt<3>(i, j, k, u, v, w, out);
        }
    }

    /// Trilinear sample of q (placement p) at world point ws_m (metres), as GridLayout::sample at
    /// isFromWs(ws_m); lo/hi (both or neither) receive the min/max of the 8 values used.
    double sample(Placement p, const double* q, const double* ws_m, double* lo = nullptr,
                  double* hi = nullptr) const {
        // One stencil per axis: the placement's own lattice along it.
        const AxisStencil sx = stencilOn(p == Placement::FaceX, 0, ws_m[0]);
        const AxisStencil sy = stencilOn(p == Placement::FaceY, 1, ws_m[1]);
        const AxisStencil sz = stencilOn(p == Placement::FaceZ, 2, ws_m[2]);
        if (!lo) return blendAt(int(p), q, sx, sy, sz);
        const size_t Y = mStrideY[int(p)], Z = mStrideZ[int(p)];
        const double* c = q + size_t(sx.i0) + Y * size_t(sy.i0) + Z * size_t(sz.i0);
        *lo = std::min({c[0], c[1], c[Y], c[Y + 1], c[Z], c[Z + 1], c[Y + Z], c[Y + Z + 1]});
        *hi = std::max({c[0], c[1], c[Y], c[Y + 1], c[Z], c[Z + 1], c[Y + Z], c[Y + Z + 1]});
        return blendCorner(c, Y, Z, sx.t, sy.t, sz.t);
    }

  private:
    /// facesAtSample for placement P (Placement as an integer).
    template <int P>
    void facesAt(int i, int j, int k, const double* u, const double* v, const double* w,
                 double* out) const {
        const int at[3] = {i, j, k};
        const double* q[3] = {u, v, w};
        for (int c = 0; c < 3; ++c) {
            size_t base = 0, step[3] = {0, 0, 0};
            const size_t stride[3] = {1, mStrideY[c], mStrideZ[c]};
            for (int a = 0; a < 3; ++a) {
                const bool compFace = a == c, sampleFace = a == P;
                int low = at[a], high = at[a];
                if (sampleFace && !compFace)  // a face between two cell centres (clamped)
                    low = std::max(at[a] - 1, 0), high = std::min(at[a], mN[a] - 1);
                else if (compFace && !sampleFace)  // a cell centre between two faces
                    high = at[a] + 1;
                base += size_t(low) * stride[a];
                step[a] = size_t(high - low) * stride[a];
            }
            // At most two axes are off: the component's own and the sample's face axis. An axis
            // that is not off has a step of 0, so its "pair" is one value twice (exact).
            const size_t offA = step[c], offB = P < 3 ? step[P < 3 ? P : 0] : 0;
            const double* b = q[c] + base;
            const double s0 = 0.5 * (b[0] + b[offA]), s1 = 0.5 * (b[offB] + b[offB + offA]);
            out[c] = 0.5 * (s0 + s1);
        }
    }

    AxisStencil stencilOn(bool faces, int axis, double ws_m) const {
        const double c = indexCoordinate(axis, ws_m);
        return faces ? faceStencil(axis, c) : cellStencil(axis, c);
    }
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
