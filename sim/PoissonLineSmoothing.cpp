/// \file PoissonLineSmoothing.cpp
/// z-line Gauss-Seidel, the smoother of PoissonSolver's V-cycle on stretched layers
/// (PoissonSystem::zLineSmoothing). Thin layers make the z-couplings up to (h / dz)^2 = 16 times
/// the horizontal ones; point Gauss-Seidel then hardly smooths along z and the iterations grow
/// with resolution. Solving each column's z-couplings exactly (block Gauss-Seidel with the
/// columns as blocks) restores the smoothing along z with full coarsening (Trottenberg,
/// Oosterlee, Schueller 2001, "Multigrid", section 5.1). Columns are coloured red-black by
/// (i + j) % 2; the post-sweeps run the colours in the reverse order of the pre-sweeps, the
/// adjoint, so the V-cycle stays a symmetric preconditioner as CG requires.
///
/// Layout and order (docs/solver.md, "Stretched layers"): the arrays are x-fastest, so walking one
/// column strides a whole slab per layer. The sweep therefore solves all the columns of one
/// colour in a plane of fixed j together, layer by layer, the inner loop running along x (the
/// Thomas algorithm's forward elimination for every column of the plane at once, then the back
/// substitution). Planes are pipelined like fusedSweep's slabs: step s updates colour `first` in
/// plane s and the other colour in plane s - 1, whose first-colour neighbours are then final, so
/// each plane is streamed from memory about once per sweep; the coarse correction, the residual
/// and b . x ride along. The result equals the unpipelined red-black line sweep exactly.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <cstddef>
#include <vector>

#include "sim/PoissonDetail.h"

namespace gale::sim::multigrid {
namespace {

/// Columns per task of a plane step: an even width (so a chunk boundary never splits the colour
/// pattern) that keeps a chunk's plane (about 64 x nz cells) in the core's L2 cache between the
/// forward and the back substitution. Fixed, not derived from the thread count, so b . x sums
/// per chunk in the same order on any number of threads.
constexpr int CHUNK_COLUMNS = 64;

// One layer of the forward elimination (the Thomas algorithm, Conte and de Boor 1980, section
// 4.2) for every column of padded indices [p0, p0 + n) of one row, both colours. Row k of a
// column reads -lo x_{k-1} + d x_k - up x_{k+1} = rhs (lo the weight of the face below, up of
// the face above, the horizontal neighbours' current values in rhs). With c_k = up_k / pivot_k
// and pivot_k = d_k - lo_k c_{k-1} (lo_k = up_{k-1}: the same face), the eliminated right-hand
// side is tmp = (rhs + lo x'_{k-1}) / pivot_k and back substitution x_k = x'_k + c_k x_{k+1}.
// cBelow holds c_{k-1} per column (zeros under the lowest layer), c receives c_k. Every column is
// computed, so the loop has no stride and vectorises; the caller keeps its colour's columns (the
// other colour's values are the same elimination with another right-hand side: finite, and
// discarded). No branch or select: d >= 0, mask is 1 where d > 0 (a positive float weight times
// 1e300 exceeds 1) and 0 in inactive cells (diag 0), whose c and tmp are then 0; an active cell's
// pivot is positive, far above the floor that keeps inactive ones finite.
GALE_VECTOR_CLONES
void forwardRow(const float* __restrict wx, const float* __restrict wy, const float* __restrict wz,
                const double* __restrict x, const double* __restrict b,
                const double* __restrict cBelow, double* __restrict c, double* __restrict tmp,
                std::ptrdiff_t p0, int n, std::ptrdiff_t sx, std::ptrdiff_t sxy) {
    const float *wxr = wx + p0, *wyr = wy + p0, *wzr = wz + p0;
    const double *xr = x + p0, *br = b + p0;
    for (int i = 0; i < n; ++i) {
        const double lo = wzr[i], up = wzr[i + sxy];
        const double d =
            double(wxr[i]) + double(wxr[i + 1]) + double(wyr[i]) + double(wyr[i + sx]) + lo + up;
        const double iv = std::min(d * 1e300, 1.0) / std::max(d - lo * cBelow[i], 1e-300);
        c[i] = up * iv;
        tmp[i] = (br[i] + wxr[i] * xr[i - 1] + wxr[i + 1] * xr[i + 1] + wyr[i] * xr[i - sx] +
                  wyr[i + sx] * xr[i + sx] + lo * xr[i - sxy]) *
                 iv;
    }
}

// forwardRow on a run of cells with the layer's full-open weights (Level::findLayerRuns): the
// same elimination with constant weights, reading none.
GALE_VECTOR_CLONES
void forwardRowUniform(const double* __restrict x, const double* __restrict b,
                       const double* __restrict cBelow, double* __restrict c,
                       double* __restrict tmp, std::ptrdiff_t p0, int n, std::ptrdiff_t sx,
                       std::ptrdiff_t sxy, double bx, double by, double lo, double up) {
    const double* xr = x + p0;
    const double* br = b + p0;
    const double d = 2.0 * (bx + by) + lo + up;
    for (int i = 0; i < n; ++i) {
        const double iv = 1.0 / (d - lo * cBelow[i]);
        c[i] = up * iv;
        tmp[i] = (br[i] + bx * (xr[i - 1] + xr[i + 1]) + by * (xr[i - sx] + xr[i + sx]) +
                  lo * xr[i - sxy]) *
                 iv;
    }
}

/// Solves the z-couplings of every column of colour `colour` ((i + j) % 2 == colour) in
/// [i0, i1) of plane j exactly, with the horizontal neighbours' current values: forward
/// elimination layer by layer (forwardRow, or forwardRowUniform on the layer's uniform runs),
/// storing each column's eliminated right-hand side in x itself (a column's own old values are
/// never read), then back substitution. `c` and `tmp` are scratch.
void solvePlaneColumns(const Level& L, double* x, const double* b, int j, int colour, int i0,
                       int i1, std::vector<double>& c, std::vector<double>& tmp) {
    const int n = i1 - i0, lane = (i0 + j + colour) & 1;  // first column of the colour
    if (n <= lane) return;
    // Layers below every column's lowest active cell are rock (x stays 0): not visited.
    const int* lowest = L.lowestActive.data() + size_t(L.nx) * size_t(j);
    const int k0 = *std::min_element(lowest + i0, lowest + i1);
    if (k0 >= L.nz) return;
    const size_t row = size_t(n);
    c.resize(row * (size_t(L.nz) + 1));
    tmp.resize(row);
    // c of the layer below the first one visited: rock or the ground, no coupling.
    std::fill(c.begin() + std::ptrdiff_t(row * size_t(k0)),
              c.begin() + std::ptrdiff_t(row * (size_t(k0) + 1)), 0.0);
    const std::ptrdiff_t sx = L.sx, sxy = std::ptrdiff_t(L.sxy);
    for (int k = k0; k < L.nz; ++k) {
        const std::ptrdiff_t p0 = std::ptrdiff_t(L.at(i0, j, k));
        double* cRow = c.data() + row * (size_t(k) + 1);
        const double* cBelow = cRow - row;
        L.segments(
            j, k,
            [&](int a, int e) {
                a = std::max(a, i0), e = std::min(e, i1);
                if (a < e)
                    forwardRow(L.wx.data(), L.wy.data(), L.wz.data(), x, b, cBelow + (a - i0),
                               cRow + (a - i0), tmp.data() + (a - i0), p0 + (a - i0), e - a, sx,
                               sxy);
            },
            [&](int a, int e) {
                a = std::max(a, i0), e = std::min(e, i1);
                if (a < e)
                    forwardRowUniform(x, b, cBelow + (a - i0), cRow + (a - i0),
                                      tmp.data() + (a - i0), p0 + (a - i0), e - a, sx, sxy,
                                      L.layerBx[size_t(k)], L.layerBy[size_t(k)],
                                      L.layerBz[size_t(k)], L.layerBz[size_t(k) + 1]);
            });
        for (int i = lane; i < n; i += 2) x[p0 + i] = tmp[size_t(i)];
    }
    for (int k = L.nz - 2; k >= k0; --k) {
        const std::ptrdiff_t p0 = std::ptrdiff_t(L.at(i0, j, k));
        const double* cRow = c.data() + row * (size_t(k) + 1);
        for (int i = lane; i < n; i += 2) x[p0 + i] += cRow[i] * x[p0 + i + sxy];
    }
}

}  // namespace

void lineSweep(const Level& L, double* x, const double* b, int first, bool fromZero,
               double* residualOut, const Level* C, const double* xc, double* dotOut) {
    const int chunks = (L.nx + CHUNK_COLUMNS - 1) / CHUNK_COLUMNS;
    auto chunkBegin = [&](int c) { return std::min(L.nx, c * CHUNK_COLUMNS); };
    // b . x per (row (j, k), chunk), added in that order at the end: deterministic.
    std::vector<double> partialDots;
    if (dotOut) partialDots.assign(size_t(L.ny) * size_t(L.nz) * size_t(chunks), 0.0);
    auto zeroPlane = [&](int j, int i0, int i1) {
        for (int k = 0; k < L.nz; ++k) std::fill(x + L.at(i0, j, k), x + L.at(i1, j, k), 0.0);
    };
    auto redirectsOfPlane = [&](int j) {
        for (size_t n = L.planeRedirectStart[size_t(j)]; n < L.planeRedirectStart[size_t(j) + 1];
             ++n) {
            const Level::Redirect& r = L.redirects[L.planeRedirects[n]];
            x[r.fine] += r.weight * xc[r.home];
        }
    };
    if (fromZero) zeroPlane(0, 0, L.nx);
    if (C) {
        redirectsOfPlane(0);
        for (int k = 0; k < L.nz; ++k) prolongRow(*C, xc, L, x, 0, k, 0, L.nx);
    }
    // Step s: plane s + 1 made ready (zeroed or corrected), colour `first` on plane s, the other
    // colour on plane s - 1 (final after it), the residual on plane s - 2 (its neighbours in
    // planes s - 3 and s - 1 are final, and it reads plane s - 1 only in its own columns, which
    // this chunk just finished). Chunks of one step touch disjoint columns and read the other
    // chunks' cells only in the same plane's other colour, which the step does not write.
    const int steps = L.ny + (residualOut ? 2 : 1);
    tbb::affinity_partitioner affinity;
    for (int s = 0; s < steps; ++s) {
        const bool next = s + 1 < L.ny;
        if (C && next) redirectsOfPlane(s + 1);  // scattered cells: serially, before the chunks
        auto chunk = [&](int c) {
            thread_local std::vector<double> cScratch, tmp;
            const int i0 = chunkBegin(c), i1 = chunkBegin(c + 1);
            if (next && fromZero) zeroPlane(s + 1, i0, i1);
            if (next && C)
                for (int k = 0; k < L.nz; ++k) prolongRow(*C, xc, L, x, s + 1, k, i0, i1);
            if (s < L.ny) solvePlaneColumns(L, x, b, s, first, i0, i1, cScratch, tmp);
            if (s >= 1 && s - 1 < L.ny) {
                solvePlaneColumns(L, x, b, s - 1, 1 - first, i0, i1, cScratch, tmp);
                if (dotOut)
                    for (int k = 0; k < L.nz; ++k) {
                        double acc = 0.0;
                        const size_t p0 = L.at(0, s - 1, k);
                        for (size_t p = p0 + i0; p < p0 + size_t(i1); ++p) acc += b[p] * x[p];
                        partialDots[L.rowIndex(s - 1, k) * size_t(chunks) + size_t(c)] = acc;
                    }
            }
            if (residualOut && s >= 2 && s - 2 < L.ny)
                for (int k = 0; k < L.nz; ++k) {
                    const size_t p0 = L.at(0, s - 2, k);
                    L.segments(
                        s - 2, k,
                        [&](int a, int e) {
                            a = std::max(a, i0), e = std::min(e, i1);
                            if (a < e) residualSpan(L, x, b, residualOut, p0 + a, p0 + size_t(e));
                        },
                        [&](int a, int e) {
                            a = std::max(a, i0), e = std::min(e, i1);
                            if (a < e)
                                layerApply(x, b, residualOut, p0, a, e, L.sx, std::ptrdiff_t(L.sxy),
                                           L.layerBx[size_t(k)], L.layerBy[size_t(k)],
                                           L.layerBz[size_t(k)], L.layerBz[size_t(k) + 1]);
                        });
                }
        };
        if (L.cells() < PARALLEL_MIN_CELLS || chunks == 1) {
            for (int c = 0; c < chunks; ++c) chunk(c);
        } else {
            auto body = [&](const tbb::blocked_range<int>& r) {
                for (int c = r.begin(); c < r.end(); ++c) chunk(c);
            };
            // Chunks go back to the threads that ran them in the previous step (the planes they
            // share stay in that core's cache), but idle threads may still take them: a static
            // assignment would wait for a thread the OS has descheduled at every step.
            tbb::parallel_for(tbb::blocked_range<int>(0, chunks, 1), body, affinity);
        }
    }
    if (dotOut) {
        double acc = 0.0;
        for (double v : partialDots) acc += v;
        *dotOut = acc;
    }
}

}  // namespace gale::sim::multigrid
