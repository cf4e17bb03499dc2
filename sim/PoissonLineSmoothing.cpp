/// \file PoissonLineSmoothing.cpp
/// z-line Gauss-Seidel, the smoother of PoissonSolver's V-cycle on stretched layers
/// (PoissonSystem::zLineSmoothing). Thin layers make the z-couplings up to (h / dz)^2 = 16 times
/// the horizontal ones; point Gauss-Seidel then hardly smooths along z and the iterations grow
/// with resolution. Solving each column's z-couplings exactly (block Gauss-Seidel with the
/// columns as blocks) restores the smoothing along z with full coarsening (Trottenberg,
/// Oosterlee, Schueller 2001, "Multigrid", section 5.1). Columns are coloured red-black by
/// (i + j) % 2; the post-sweeps run the colours in the reverse order of the pre-sweeps, the
/// adjoint, so the V-cycle stays a symmetric preconditioner as CG requires.

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <vector>

#include "sim/PoissonDetail.h"

namespace gale::sim::multigrid {
namespace {

/// Solves column (i, j)'s z-couplings exactly with the horizontal neighbours' current values
/// (Thomas algorithm; the matrix is symmetric and weakly diagonally dominant). Inactive cells
/// (diag 0) keep x = 0 and couple to nothing.
void solveColumn(const Level& L, double* x, const double* b, int i, int j, std::vector<double>& cp,
                 std::vector<double>& dp) {
    const size_t sx = L.sx, sxy = L.sxy;
    const float *wx = L.wx.data(), *wy = L.wy.data(), *wz = L.wz.data();
    const int nz = L.nz;
    cp.resize(size_t(nz));
    dp.resize(size_t(nz));
    double cPrev = 0.0, dPrev = 0.0;
    for (int k = 0; k < nz; ++k) {
        const size_t p = L.at(i, j, k);
        const double d = L.diag(p);
        if (!(d > 0.0)) {
            cp[size_t(k)] = 0.0, dp[size_t(k)] = 0.0;
            cPrev = 0.0, dPrev = 0.0;
            continue;
        }
        // Row k: -lo x_{k-1} + d x_k - up x_{k+1} = rhs; the ghosts below and above hold 0.
        const double lo = k > 0 ? double(wz[p]) : 0.0, up = k + 1 < nz ? double(wz[p + sxy]) : 0.0;
        const double rhs = b[p] + wx[p] * x[p - 1] + wx[p + 1] * x[p + 1] + wy[p] * x[p - sx] +
                           wy[p + sx] * x[p + sx];
        const double den = d + lo * cPrev;  // sub-diagonal -lo, super-diagonal -up
        cPrev = -up / den;
        dPrev = (rhs + lo * dPrev) / den;
        cp[size_t(k)] = cPrev, dp[size_t(k)] = dPrev;
    }
    double above = 0.0;
    for (int k = nz - 1; k >= 0; --k) {
        const size_t p = L.at(i, j, k);
        above = dp[size_t(k)] - cp[size_t(k)] * above;
        x[p] = L.active[p] ? above : 0.0;
        if (!L.active[p]) above = 0.0;
    }
}

}  // namespace

void lineSweep(const Level& L, double* x, const double* b, int first, bool fromZero,
               double* residualOut, const Level* C, const double* xc, double* dotOut) {
    if (fromZero) std::fill(x, x + L.total, 0.0);
    if (C) {
        forRows(L, [&](int j, int k) { prolongRow(*C, xc, L, x, j, k); });
        for (int k = 0; k < L.nz; ++k) prolongRedirects(L, xc, x, k);
    }
    for (int colour : {first, 1 - first}) {
        auto rows = [&](int j0, int j1) {
            thread_local std::vector<double> cp, dp;
            for (int j = j0; j < j1; ++j)
                for (int i = (j + colour) & 1; i < L.nx; i += 2) solveColumn(L, x, b, i, j, cp, dp);
        };
        if (L.cells() < PARALLEL_MIN_CELLS) {
            rows(0, L.ny);
        } else {
            tbb::parallel_for(tbb::blocked_range<int>(0, L.ny, 4),
                              [&](const tbb::blocked_range<int>& r) { rows(r.begin(), r.end()); });
        }
    }
    if (residualOut) residual(L, x, b, residualOut);
    if (dotOut) {
        *dotOut = reduceRows(
            L,
            [&](int j, int k) {
                double acc = 0.0;
                const size_t p0 = L.at(0, j, k);
                for (size_t p = p0; p < p0 + size_t(L.nx); ++p) acc += b[p] * x[p];
                return acc;
            },
            SUM);
    }
}

}  // namespace gale::sim::multigrid
