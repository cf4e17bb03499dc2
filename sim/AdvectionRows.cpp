/// \file AdvectionRows.cpp
/// The single-precision row pass of the advection (AdvectionRows.h), written once against
/// Google Highway and compiled by it for each x86 instruction set it targets (foreach_target.h);
/// HWY_DYNAMIC_DISPATCH picks the best one the machine runs on, once.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sim/AdvectionRows.cpp"
#include "sim/AdvectionRows.h"

#include <hwy/foreach_target.h>  // before highway.h: re-includes this file per target
#include <hwy/highway.h>

#include <cmath>

HWY_BEFORE_NAMESPACE();
namespace gale::sim::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using MF = hn::Mask<DF>;

/// One axis of a point on a lattice: the lower sample's index and the upper sample's weight.
struct Stencil {
    VI i;
    VF t;
};

/// x clamped to [0, top]; NaN gives 0 (as the double path's c > 0 ? (c < n ? c : n) : 0).
HWY_INLINE VF clampTo(VF x, VF top) {
    const DF df;
    const VF zero = hn::Zero(df);
    return hn::IfThenElse(x > zero, hn::IfThenElse(x < top, x, top), zero);
}

/// The stencil at index coordinate c on a lattice of n + 1 samples at 0 .. n (faces), clamped:
/// UniformLattice::faceStencil in float.
HWY_INLINE Stencil faceStencil(VF c, int n) {
    const DF df;
    const DI di;
    const VF f = clampTo(c, hn::Set(df, float(n)));
    const VI i = hn::Min(hn::ConvertTo(di, f), hn::Set(di, n - 1));
    return {i, f - hn::ConvertTo(df, i)};
}

/// The stencil at index coordinate c on a lattice of n samples at 0.5 .. n - 0.5 (centres):
/// UniformLattice::cellStencil in float.
HWY_INLINE Stencil cellStencil(VF c, int n) {
    const DF df;
    const DI di;
    const VF e = clampTo(c - hn::Set(df, 0.5f), hn::Set(df, float(n - 1)));
    const VI i = hn::Min(hn::ConvertTo(di, e), hn::Set(di, n - 2));
    return {i, e - hn::ConvertTo(df, i)};
}

HWY_INLINE VF lerp(VF a, VF b, VF t) { return a + (b - a) * t; }

/// The 8 values of a cell from base (strides 1, sy, sz), corner (i, j, k) at c[i + 2 j + 4 k].
HWY_INLINE void corners(const float* HWY_RESTRICT a, VI base, int sy, int sz, VF* c) {
    const DF df;
    const DI di;
    const VI one = hn::Set(di, 1), y = hn::Set(di, sy), z = hn::Set(di, sz);
    c[0] = hn::GatherIndex(df, a, base);
    c[1] = hn::GatherIndex(df, a, base + one);
    c[2] = hn::GatherIndex(df, a, base + y);
    c[3] = hn::GatherIndex(df, a, base + y + one);
    c[4] = hn::GatherIndex(df, a, base + z);
    c[5] = hn::GatherIndex(df, a, base + z + one);
    c[6] = hn::GatherIndex(df, a, base + y + z);
    c[7] = hn::GatherIndex(df, a, base + y + z + one);
}

/// Trilinear blend of the 8 corners: along x, then y, then z (trilinearBlend's order).
HWY_INLINE VF blend(const VF* c, VF tx, VF ty, VF tz) {
    return lerp(lerp(lerp(c[0], c[1], tx), lerp(c[2], c[3], tx), ty),
                lerp(lerp(c[4], c[5], tx), lerp(c[6], c[7], tx), ty), tz);
}

/// The three MAC components (m/s) at index points (X, Y, Z), each from its own faces
/// (UniformLattice::sampleFaces): u on (nx + 1) x ny x nz, v on nx x (ny + 1) x nz, w on
/// nx x ny x (nz + 1).
HWY_INLINE void velocity(const RowPassInput& in, VF X, VF Y, VF Z, VF& u, VF& v, VF& w) {
    const DI di;
    const int nx = in.n[0], ny = in.n[1], nz = in.n[2];
    const Stencil xf = faceStencil(X, nx), xc = cellStencil(X, nx);
    const Stencil yf = faceStencil(Y, ny), yc = cellStencil(Y, ny);
    const Stencil zf = faceStencil(Z, nz), zc = cellStencil(Z, nz);
    const int uy = nx + 1, uz = (nx + 1) * ny, vy = nx, vz = nx * (ny + 1), wy = nx, wz = nx * ny;
    VF c[8];
    corners(in.u, xf.i + yc.i * hn::Set(di, uy) + zc.i * hn::Set(di, uz), uy, uz, c);
    u = blend(c, xf.t, yc.t, zc.t);
    corners(in.v, xc.i + yf.i * hn::Set(di, vy) + zc.i * hn::Set(di, vz), vy, vz, c);
    v = blend(c, xc.t, yf.t, zc.t);
    corners(in.w, xc.i + yc.i * hn::Set(di, wy) + zf.i * hn::Set(di, wz), wy, wz, c);
    w = blend(c, xc.t, yc.t, zf.t);
}

/// Lanes outside the box through an x or y side or the top (MacGrid::outside); NaN is outside.
HWY_INLINE MF outside(const RowPassInput& in, VF X, VF Y, VF Z) {
    const DF df;
    const VF zero = hn::Zero(df);
    const MF inside = hn::And(hn::And(X >= zero, X <= hn::Set(df, float(in.n[0]))),
                              hn::And(hn::And(Y >= zero, Y <= hn::Set(df, float(in.n[1]))),
                                      Z <= hn::Set(df, float(in.n[2]))));
    return hn::Not(inside);
}

/// Index-space height of the terrain under (X, Y): Heightfield::sample's weighted bilinear form
/// in float.
HWY_INLINE VF groundZ(const RowPassInput& in, VF X, VF Y) {
    const DF df;
    const DI di;
    const VF scale = hn::Set(df, in.hScale);
    const VF fx = clampTo(X * scale + hn::Set(df, in.hOffsetX), hn::Set(df, float(in.hnx - 1)));
    const VF fy = clampTo(Y * scale + hn::Set(df, in.hOffsetY), hn::Set(df, float(in.hny - 1)));
    const VI i = hn::Min(hn::ConvertTo(di, fx), hn::Set(di, in.hnx - 2));
    const VI j = hn::Min(hn::ConvertTo(di, fy), hn::Set(di, in.hny - 2));
    const VF tx = fx - hn::ConvertTo(df, i), ty = fy - hn::ConvertTo(df, j);
    const VI base = i + j * hn::Set(di, in.hnx);
    const VI one = hn::Set(di, 1), row = hn::Set(di, in.hnx);
    const VF h00 = hn::GatherIndex(df, in.heights, base);
    const VF h10 = hn::GatherIndex(df, in.heights, base + one);
    const VF h01 = hn::GatherIndex(df, in.heights, base + row);
    const VF h11 = hn::GatherIndex(df, in.heights, base + row + one);
    const VF oneF = hn::Set(df, 1.0f);
    const VF z = (h00 * (oneF - tx) + h10 * tx) * (oneF - ty) + (h01 * (oneF - tx) + h11 * tx) * ty;
    return z * hn::Set(df, in.zScale) + hn::Set(df, in.zOffset);
}

/// Indices along one axis whose mean is a velocity component at a sample of the row: the
/// trilinear weights at a lattice point are 0, 1/2 or 1, so the sample's own velocity is a mean of
/// at most 2 x 2 x 2 stored values (lo == hi: one value). A component on this axis's faces, at a
/// sample on a face (integer coordinate m), is face m; at a sample between faces (m + 0.5),
/// faces m and m + 1. A component on the centres, at a sample between centres (on a face, m),
/// is cells m - 1 and m clamped to [0, n - 1] (cellStencil's clamp); at a centre, cell m.
struct AxisPair {
    int lo, hi;
};
HWY_INLINE AxisPair axisPair(int m, bool sampleOnFace, bool componentOnFaces, int n) {
    if (componentOnFaces) return sampleOnFace ? AxisPair{m, m} : AxisPair{m, m + 1};
    if (!sampleOnFace) return {m, m};
    return {m > 0 ? m - 1 : 0, m < n ? m : n - 1};
}

/// The mean of a component over the pairs, for the N lanes of a row from i0: x offsets relative to
/// the lane's own index (contiguous loads), y and z pairs the same for every lane of the row.
HWY_INLINE VF rowMean(const float* HWY_RESTRICT a, int sy, int sz, size_t i0, AxisPair x,
                      AxisPair y, AxisPair z) {
    const DF df;
    const VF half = hn::Set(df, 0.5f);
    auto alongX = [&](int jj, int kk) {
        const float* r = a + size_t(kk) * size_t(sz) + size_t(jj) * size_t(sy) + i0;
        return (hn::LoadU(df, r + x.lo) + hn::LoadU(df, r + x.hi)) * half;
    };
    const VF low = (alongX(y.lo, z.lo) + alongX(y.hi, z.lo)) * half;
    const VF high = (alongX(y.lo, z.hi) + alongX(y.hi, z.hi)) * half;
    return (low + high) * half;
}

/// The velocity at the samples of row (j, k) from lane i0 on, read by loads instead of gathers
/// (the samples sit on the lattice, so the trilinear stencils collapse to means; velocity() gives
/// the same up to rounding). Returns false, writing nothing, where a lane's x pair would need
/// cellStencil's clamp (the row's first and last samples of x faces) or a load would leave the
/// row: the caller then gathers.
HWY_INLINE bool startByLoads(const RowPassInput& in, int p, int j, int k, size_t i0, size_t N,
                             int nxp, VF& u, VF& v, VF& w) {
    const int nx = in.n[0], ny = in.n[1], nz = in.n[2];
    const bool onX = p == 0, onY = p == 1, onZ = p == 2;
    if (i0 + N > size_t(nxp)) return false;  // a partial vector: loads would leave the row
    // Lanes i in [i0, i0 + N): x pairs (offsets from i) of u and of v, w.
    const AxisPair ux = onX ? AxisPair{0, 0} : AxisPair{0, 1};
    const AxisPair cx = onX ? AxisPair{-1, 0} : AxisPair{0, 0};
    if (onX && (i0 < 1 || i0 + N > size_t(nx))) return false;  // the clamped ends of v, w
    u = rowMean(in.u, nx + 1, (nx + 1) * ny, i0, ux, axisPair(j, onY, false, ny),
                axisPair(k, onZ, false, nz));
    v = rowMean(in.v, nx, nx * (ny + 1), i0, cx, axisPair(j, onY, true, ny),
                axisPair(k, onZ, false, nz));
    w = rowMean(in.w, nx, nx * ny, i0, cx, axisPair(j, onY, false, ny), axisPair(k, onZ, true, nz));
    return true;
}

void RowPassImpl(const RowPassInput& in, int j, int k, double* HWY_RESTRICT out,
                 double* HWY_RESTRICT lo, double* HWY_RESTRICT hi, uint8_t* HWY_RESTRICT general) {
    const DF df;
    const int p = in.placement;
    const int nxp = in.n[0] + (p == 0), nyp = in.n[1] + (p == 1);
    const int sy = nxp, sz = nxp * nyp;
    const int row = sy * j + sz * k;
    const bool faceX = p == 0, faceY = p == 1, faceZ = p == 2;
    const VF offX = hn::Set(df, faceX ? 0.0f : 0.5f);
    const VF Y0 = hn::Set(df, float(j) + (faceY ? 0.0f : 0.5f));
    const VF Z0 = hn::Set(df, float(k) + (faceZ ? 0.0f : 0.5f));
    const VF s = hn::Set(df, in.cellsPerMps), half = hn::Set(df, 0.5f);
    const VF maxCells = hn::Set(df, 2.0f);  // MAX_TRACE_CELLS_PER_SUBSTEP (Advection.h)
    const VF groundTop = hn::Set(df, in.groundTop);
    const size_t N = hn::Lanes(df);
    constexpr size_t MAX_LANES = 64;  // more than any x86 vector holds (16 floats)
    HWY_ALIGN float value[MAX_LANES] = {}, low[MAX_LANES] = {}, high[MAX_LANES] = {},
                    redoF[MAX_LANES] = {}, startU[MAX_LANES] = {}, startV[MAX_LANES] = {},
                    startW[MAX_LANES] = {};
    for (int i0 = 0; i0 < nxp; i0 += int(N)) {
        // Lanes past the row's end trace clamped points and are not written.
        const VF X0 = hn::Iota(df, float(i0)) + offX;
        VF u0, v0, w0;
        const size_t at = size_t(row + i0);
        if (in.start) {
            u0 = hn::LoadU(df, in.start + at);
            v0 = hn::LoadU(df, in.start + in.count + at);
            w0 = hn::LoadU(df, in.start + 2 * in.count + at);
        } else {
            if (!startByLoads(in, p, j, k, size_t(i0), N, nxp, u0, v0, w0))
                velocity(in, X0, Y0, Z0, u0, v0, w0);
            if (in.recordStart) {
                hn::Store(u0, df, startU);
                hn::Store(v0, df, startV);
                hn::Store(w0, df, startW);
            }
        }
        const VF dx0 = u0 * s, dy0 = v0 * s, dz0 = w0 * s;
        const VF m = hn::Max(hn::Max(hn::Abs(dx0), hn::Abs(dy0)), hn::Abs(dz0));
        MF redo = hn::Not(m <= maxCells);  // a NaN displacement too
        const VF Xm = X0 - half * dx0, Ym = Y0 - half * dy0, Zm = Z0 - half * dz0;
        redo = hn::Or(redo, outside(in, Xm, Ym, Zm));
        VF um, vm, wm;
        velocity(in, Xm, Ym, Zm, um, vm, wm);
        const VF Xd = X0 - um * s, Yd = Y0 - vm * s, Zd = Z0 - wm * s;
        redo = hn::Or(redo, outside(in, Xd, Yd, Zd));
        if (in.heights) {  // the terrain's gathers only for vectors with a lane low enough
            const MF nearGround = Zd < groundTop;
            if (!hn::AllFalse(df, nearGround))
                redo = hn::Or(redo, hn::And(nearGround, Zd < groundZ(in, Xd, Yd)));
        }
        // q at the departure: the face stencil along the placement's own axis.
        const Stencil sx = faceX ? faceStencil(Xd, in.n[0]) : cellStencil(Xd, in.n[0]);
        const Stencil sY = faceY ? faceStencil(Yd, in.n[1]) : cellStencil(Yd, in.n[1]);
        const Stencil sZ = faceZ ? faceStencil(Zd, in.n[2]) : cellStencil(Zd, in.n[2]);
        const DI di;
        VF c[8];
        corners(in.q, sx.i + sY.i * hn::Set(di, sy) + sZ.i * hn::Set(di, sz), sy, sz, c);
        hn::Store(blend(c, sx.t, sY.t, sZ.t), df, value);
        if (lo) {
            VF l = c[0], h = c[0];
            for (int n = 1; n < 8; ++n) l = hn::Min(l, c[n]), h = hn::Max(h, c[n]);
            hn::Store(l, df, low);
            hn::Store(h, df, high);
        }
        hn::Store(hn::IfThenElseZero(redo, hn::Set(df, 1.0f)), df, redoF);
        const int lanes = nxp - i0 < int(N) ? nxp - i0 : int(N);
        for (int l = 0; l < lanes; ++l) {
            const int idx = row + i0 + l;
            const bool moves = in.mask[idx] != 0;
            out[idx] = moves ? double(value[l]) : in.qExact[idx];
            if (lo) {
                lo[idx] = moves ? double(low[l]) : -HUGE_VAL;
                hi[idx] = moves ? double(high[l]) : HUGE_VAL;
            }
            general[idx] = moves && redoF[l] > 0.0f ? 1 : 0;
        }
        if (in.recordStart && !in.start)  // only this row's lanes: rows run on other threads
            for (int l = 0; l < lanes; ++l) {
                const size_t idx = at + size_t(l);
                in.recordStart[idx] = startU[l];
                in.recordStart[in.count + idx] = startV[l];
                in.recordStart[2 * in.count + idx] = startW[l];
            }
    }
}

// NOLINTNEXTLINE(google-readability-namespace-comments)
}  // namespace HWY_NAMESPACE
}  // namespace gale::sim::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace gale::sim::detail {

HWY_EXPORT(RowPassImpl);

void rowPass(const RowPassInput& in, int j, int k, double* out, double* lo, double* hi,
             uint8_t* general) {
    HWY_DYNAMIC_DISPATCH(RowPassImpl)(in, j, k, out, lo, hi, general);
}

}  // namespace gale::sim::detail
#endif
