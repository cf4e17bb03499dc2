/// \file PoissonOperator.cpp
/// The matrix-free 7-point operator of PoissonSolver on one multigrid level,
///
///   (A x)_c = sum over the six faces f of c:  w_f (x_c - x_nb(f)),
///
/// with float face weights and double vectors on the padded layout of PoissonDetail.h (MGPCG
/// after McAdams, Sifakis, Teran 2010; every level, coarse ones too, uses it with its own
/// weights): A x with the dot product x . A x that CG needs, the residual b - A x, and the
/// constant-coefficient row kernels for runs of full-open cells that the smoother shares
/// (docs/solver.md, "The linear solver").

#include <algorithm>
#include <cmath>

#include "sim/PoissonDetail.h"

namespace gale::sim::multigrid {

// Constant-coefficient row kernels for runs of full-open cells, written so the compiler can
// vectorise them (no stores into arrays they read); GALE_VECTOR_CLONES (PoissonDetail.h).

// The strides are signed so that xr[i - sx] steps back (an unsigned i - sx wraps: UB, UBSan).
GALE_VECTOR_CLONES
void uniformCandidates(const double* __restrict x, const double* __restrict b,
                       double* __restrict tmp, size_t p0, int i0, int i1, std::ptrdiff_t sx,
                       std::ptrdiff_t sxy, double bx, double by, double bz, double invD) {
    const double* xr = x + p0;
    const double* br = b + p0;
    for (int i = i0; i < i1; ++i)
        tmp[i - i0] = (br[i] + bx * (xr[i - 1] + xr[i + 1]) + by * (xr[i - sx] + xr[i + sx]) +
                       bz * (xr[i - sxy] + xr[i + sxy])) *
                      invD;
}

/// The 7-point stencil with diagonal D on a run: out = b - A x, or out = A x (returning
/// sum out * x) when b is null. Both kinds of run below are this kernel.
GALE_VECTOR_CLONES
double stencilApply(const double* __restrict x, const double* __restrict b, double* __restrict out,
                    size_t p0, int i0, int i1, std::ptrdiff_t sx, std::ptrdiff_t sxy, double bx,
                    double by, double bzLo, double bzUp, double D) {
    const double* xr = x + p0;
    double* o = out + p0;
    double acc = 0.0;
    if (b) {
        const double* br = b + p0;
        for (int i = i0; i < i1; ++i)
            o[i] = br[i] -
                   (D * xr[i] - (bx * (xr[i - 1] + xr[i + 1]) + by * (xr[i - sx] + xr[i + sx]) +
                                 bzLo * xr[i - sxy] + bzUp * xr[i + sxy]));
        return 0.0;
    }
    for (int i = i0; i < i1; ++i) {
        const double v =
            D * xr[i] - (bx * (xr[i - 1] + xr[i + 1]) + by * (xr[i - sx] + xr[i + sx]) +
                         bzLo * xr[i - sxy] + bzUp * xr[i + sxy]);
        o[i] = v;
        acc += v * xr[i];
    }
    return acc;
}

double layerApply(const double* __restrict x, const double* __restrict b, double* __restrict out,
                  size_t p0, int i0, int i1, std::ptrdiff_t sx, std::ptrdiff_t sxy, double bx,
                  double by, double bzLo, double bzUp) {
    return stencilApply(x, b, out, p0, i0, i1, sx, sxy, bx, by, bzLo, bzUp,
                        2.0 * (bx + by) + bzLo + bzUp);
}

double uniformApply(const double* __restrict x, const double* __restrict b, double* __restrict out,
                    size_t p0, int i0, int i1, std::ptrdiff_t sx, std::ptrdiff_t sxy, double bx,
                    double by, double bz, double D) {
    return stencilApply(x, b, out, p0, i0, i1, sx, sxy, bx, by, bz, bz, D);
}

double applyDot(const Level& L, const double* in, double* out) {
    const size_t sx = L.sx, sxy = L.sxy;
    const float *wx = L.wx.data(), *wy = L.wy.data(), *wz = L.wz.data();
    const double bx = L.bx, by = L.by, bz = L.bz, D = L.uniformDiag;
    return reduceRows(
        L,
        [&](int j, int k) {
            double acc = 0.0;
            const size_t p0 = L.at(0, j, k);
            L.segments(
                j, k,
                [&](int i0, int i1) {
                    for (size_t p = p0 + i0; p < p0 + size_t(i1); ++p) {
                        const double d =
                            double(wx[p]) + wx[p + 1] + wy[p] + wy[p + sx] + wz[p] + wz[p + sxy];
                        const double v =
                            d * in[p] - (wx[p] * in[p - 1] + wx[p + 1] * in[p + 1] +
                                         wy[p] * in[p - sx] + wy[p + sx] * in[p + sx] +
                                         wz[p] * in[p - sxy] + wz[p + sxy] * in[p + sxy]);
                        out[p] = v;
                        acc += v * in[p];
                    }
                },
                [&](int i0, int i1) {
                    if (L.zLines)
                        acc += layerApply(in, nullptr, out, p0, i0, i1, sx, sxy,
                                          L.layerBx[size_t(k)], L.layerBy[size_t(k)],
                                          L.layerBz[size_t(k)], L.layerBz[size_t(k) + 1]);
                    else
                        acc += uniformApply(in, nullptr, out, p0, i0, i1, sx, sxy, bx, by, bz, D);
                });
            return acc;
        },
        SUM);
}

double residualMaxAbs(const Level& L, const double* x, const double* b, double* r) {
    const size_t sx = L.sx, sxy = L.sxy;
    const double bx = L.bx, by = L.by, bz = L.bz, D = L.uniformDiag;
    return reduceRows(
        L,
        [&](int j, int k) {
            const size_t p0 = L.at(0, j, k);
            // Runs of full-open cells take the constant-coefficient kernel, as applyDot does.
            L.segments(
                j, k, [&](int i0, int i1) { residualSpan(L, x, b, r, p0 + i0, p0 + size_t(i1)); },
                [&](int i0, int i1) {
                    if (L.zLines)
                        layerApply(x, b, r, p0, i0, i1, sx, sxy, L.layerBx[size_t(k)],
                                   L.layerBy[size_t(k)], L.layerBz[size_t(k)],
                                   L.layerBz[size_t(k) + 1]);
                    else
                        uniformApply(x, b, r, p0, i0, i1, sx, sxy, bx, by, bz, D);
                });
            double mx = 0.0;
            for (size_t p = p0; p < p0 + size_t(L.nx); ++p) mx = std::max(mx, std::abs(r[p]));
            return mx;
        },
        MAX);
}

}  // namespace gale::sim::multigrid
