/// \file PoissonSmoothing.cpp
/// The smoother of PoissonSolver's V-cycle (MGPCG after McAdams, Sifakis, Teran 2010): red-black
/// Gauss-Seidel, pre-sweeps red then black and post-sweeps black then red, the adjoint, so the
/// V-cycle stays a symmetric preconditioner as CG requires. Each sweep is pipelined slab by slab
/// with the residual, the prolongation of the coarse correction and PCG's r . z fused in, so it
/// streams each array from memory once (docs/solver.md, "The linear solver"). Runs of full-open
/// cells take the constant-coefficient kernels of PoissonOperator.cpp.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cstddef>
#include <vector>

#include "sim/PoissonDetail.h"

namespace gale::sim::multigrid {

namespace {
std::atomic<size_t> gPhasedMaxCells{PHASED_MAX_CELLS};
}  // namespace

size_t phasedMaxCells() { return gPhasedMaxCells.load(std::memory_order_relaxed); }
void setPhasedMaxCells(size_t cells) { gPhasedMaxCells.store(cells, std::memory_order_relaxed); }

// One Gauss-Seidel sweep in red-black order (colour `first`, then the other), pipelined slab
// by slab so each slab's data is streamed from memory once: step s updates colour `first` on
// slab s and the other colour on slab s-1 (whose first-colour neighbours are then final).
// fromZero: start from x = 0 (first colour = b/d, other colour 0) without reading x.
// residualOut: also r = b - A x, three slabs behind, where every neighbour is final.
// The result equals the unpipelined red-black sweep exactly, serial or threaded.
// C, xc: first add the coarse correction P xc (prolongation fused into the sweep, one slab
// ahead of the colour-A update that first reads it). dotOut: also sum b . x over the final x
// (row partial sums added in row order: deterministic).
void fusedSweep(const Level& L, double* x, const double* b, int first, bool fromZero,
                double* residualOut, const Level* C, const double* xc, double* dotOut) {
    const size_t sx = L.sx, sxy = L.sxy;
    const float *wx = L.wx.data(), *wy = L.wy.data(), *wz = L.wz.data();
    const double bx = L.bx, by = L.by, bz = L.bz, D = L.uniformDiag, invD = L.uniformInvDiag;
    auto update = [&](int j, int k, int colour) {
        const size_t p0 = L.at(0, j, k);
        const int par = (j + k + colour) & 1;
        L.segments(
            j, k,
            [&](int i0, int i1) {
                for (size_t p = p0 + i0 + ((i0 + par) & 1); p < p0 + size_t(i1); p += 2) {
                    const double d =
                        double(wx[p]) + wx[p + 1] + wy[p] + wy[p + sx] + wz[p] + wz[p + sxy];
                    if (d > 0.0)
                        x[p] = (b[p] + wx[p] * x[p - 1] + wx[p + 1] * x[p + 1] + wy[p] * x[p - sx] +
                                wy[p + sx] * x[p + sx] + wz[p] * x[p - sxy] +
                                wz[p + sxy] * x[p + sxy]) /
                               d;
                }
            },
            [&](int i0, int i1) {
                thread_local std::vector<double> tmp;
                if (tmp.size() < size_t(i1 - i0)) tmp.resize(size_t(L.nx));
                uniformCandidates(x, b, tmp.data(), p0, i0, i1, sx, sxy, bx, by, bz, invD);
                for (int i = i0 + ((i0 + par) & 1); i < i1; i += 2) x[p0 + i] = tmp[i - i0];
            });
    };
    auto startRow = [&](int j, int k) {
        const size_t p0 = L.at(0, j, k);
        const int par = (j + k + first) & 1;
        L.segments(
            j, k,
            [&](int i0, int i1) {
                for (int i = i0; i < i1; ++i) {
                    const size_t p = p0 + i;
                    if ((i & 1) != par) {
                        x[p] = 0.0;
                        continue;
                    }
                    const double d =
                        double(wx[p]) + wx[p + 1] + wy[p] + wy[p + sx] + wz[p] + wz[p + sxy];
                    x[p] = d > 0.0 ? b[p] / d : 0.0;
                }
            },
            [&](int i0, int i1) {
                for (int i = i0; i < i1; ++i) x[p0 + i] = (i & 1) == par ? b[p0 + i] * invD : 0.0;
            });
    };
    auto residualRow = [&](int j, int k) {
        const size_t p0 = L.at(0, j, k);
        L.segments(
            j, k,
            [&](int i0, int i1) { residualSpan(L, x, b, residualOut, p0 + i0, p0 + size_t(i1)); },
            [&](int i0, int i1) {
                uniformApply(x, b, residualOut, p0, i0, i1, sx, sxy, bx, by, bz, D);
            });
    };
    std::vector<double> rowDots;  // shared by the row tasks, one slot per row
    if (dotOut) rowDots.assign(size_t(L.ny) * L.nz, 0.0);
    auto dotRow = [&](int j, int k) {
        const size_t p0 = L.at(0, j, k);
        double acc = 0.0;
        for (size_t p = p0; p < p0 + size_t(L.nx); ++p) acc += b[p] * x[p];
        rowDots[L.rowIndex(j, k)] = acc;
    };
    auto prolongSlab = [&](int k, bool serialRows) {
        prolongRedirects(L, xc, x, k);
        if (serialRows) {
            for (int j = 0; j < L.ny; ++j) prolongRow(*C, xc, L, x, j, k, 0, L.nx);
        } else {
            tbb::parallel_for(tbb::blocked_range<int>(0, L.ny, 16),
                              [&](const tbb::blocked_range<int>& r) {
                                  for (int j = r.begin(); j < r.end(); ++j)
                                      prolongRow(*C, xc, L, x, j, k, 0, L.nx);
                              });
        }
    };
    const bool serial = L.cells() < PARALLEL_MIN_CELLS;
    if (!serial && L.cells() <= phasedMaxCells()) {
        // The unpipelined sweep the pipeline reproduces, phase by phase: a level this small sits
        // in cache, and a pipeline would pay a fork and join per slab where each slab is only a
        // few microseconds of work (docs/unsteady.md, "Forks, joins and passes").
        if (C) {
            for (int k = 0; k < L.nz; ++k) prolongRedirects(L, xc, x, k);
            forRows(L, [&](int j, int k) { prolongRow(*C, xc, L, x, j, k, 0, L.nx); });
        }
        forRows(L, [&](int j, int k) {
            if (fromZero)
                startRow(j, k);
            else
                update(j, k, first);
        });
        forRows(L, [&](int j, int k) {
            update(j, k, 1 - first);
            if (dotOut) dotRow(j, k);
        });
        if (residualOut) forRows(L, residualRow);
        if (dotOut) {
            double acc = 0.0;
            for (double v : rowDots) acc += v;
            *dotOut = acc;
        }
        return;
    }
    const int steps = L.nz + (residualOut ? 3 : 1);
    if (C) prolongSlab(0, serial);
    for (int s = 0; s < steps; ++s) {
        const bool prolongNext = C && s + 1 < L.nz;
        if (prolongNext)  // redirects touch scattered rows: serially, before the row tasks
            prolongRedirects(L, xc, x, s + 1);
        auto rows = [&](int j0, int j1) {
            for (int j = j0; j < j1; ++j) {
                if (prolongNext) prolongRow(*C, xc, L, x, j, s + 1, 0, L.nx);
                if (s < L.nz) {
                    if (fromZero)
                        startRow(j, s);
                    else
                        update(j, s, first);
                }
                if (s >= 1 && s - 1 < L.nz) {
                    update(j, s - 1, 1 - first);
                    if (dotOut) dotRow(j, s - 1);
                }
                if (residualOut && s >= 3 && s - 3 < L.nz) residualRow(j, s - 3);
            }
        };
        if (serial) {
            rows(0, L.ny);
        } else {
            tbb::parallel_for(tbb::blocked_range<int>(0, L.ny, 16),
                              [&](const tbb::blocked_range<int>& r) { rows(r.begin(), r.end()); });
        }
    }
    if (dotOut) {
        double acc = 0.0;
        for (double v : rowDots) acc += v;
        *dotOut = acc;
    }
}

}  // namespace gale::sim::multigrid
