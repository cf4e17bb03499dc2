/// \file PoissonSolver.cpp
/// MGPCG after McAdams, Sifakis, Teran 2010 ("A parallel multigrid Poisson solver for fluids
/// simulation on large grids"): conjugate gradients preconditioned by one symmetric V-cycle,
/// red-black Gauss-Seidel smoothing, trilinear prolongation with its transpose as restriction.
/// Differences from the paper: the coarsest level is solved exactly (dense Cholesky); the coarse
/// weights are the averaged fine open fractions (weights), slivers counted as at least
/// COARSE_MIN_OPEN_FRACTION open, so cut-cell boundaries (Batty, Bertails, Bridson 2007) coarsen
/// without cell-type rules; interpolation weight from rock or Neumann ghosts goes to the fine
/// cell's own parent (and restriction is its transpose). Sweeps are pipelined slab by slab with
/// the residual, the prolongation and PCG's r.z fused in (docs/solver.md, "The linear solver").
///
/// Layout: every level stores its arrays padded by one ghost cell per side, so the stencil needs no
/// bounds tests. Ghost entries of solution-like arrays stay 0 (homogeneous Dirichlet data), and the
/// weight of a face is stored in the padded cell on its high side: weight of the face between
/// cells (i-1, j, k) and (i, j, k) is wx[at(i, j, k)], i in [0, nx].

#include "sim/PoissonSolver.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>

namespace gale::sim {
namespace detail {
namespace {

/// Below this many cells a level runs serially: TBB's scheduling costs more than it saves.
constexpr size_t PARALLEL_MIN_CELLS = 16 * 1024;
/// The hierarchy stops coarsening once a level has at most this many cells; that level is solved
/// exactly by dense Cholesky (about COARSEST_MAX_CELLS^3 / 3 flops once, ^2 per application).
constexpr size_t COARSEST_MAX_CELLS = 600;
/// Open faces thinner than this fraction of a full-open face count as this thick when the coarse
/// levels are built (the finest level keeps the exact cut-cell weights, so the discretisation and
/// the solution are unchanged: only the preconditioner differs). Slivers of cut cells otherwise
/// make the averaged coarse operator a poor model of the fine one: on a 30 m Gaussian hill at
/// 200 x 200 x 120 cells, 22 -> 11 iterations to 1e-6 (docs/solver.md).
constexpr double COARSE_MIN_OPEN_FRACTION = 0.1;

struct Transfer1D {
    // Prolongation: fine index i takes w0 * coarse[c0] + w1 * coarse[c1] (indices in [-1, N]).
    std::vector<int> c0, c1;
    std::vector<double> w0, w1;
    // Restriction (transpose): coarse index I gathers sum over n < count of w[n] * fine[f[n]].
    std::vector<std::array<int, 4>> f;
    std::vector<std::array<double, 4>> w;
    std::vector<int> count;
};

Transfer1D makeTransfer(int nFine, int nCoarse, int factor) {
    Transfer1D t;
    t.c0.resize(nFine);
    t.c1.resize(nFine);
    t.w0.resize(nFine);
    t.w1.resize(nFine);
    for (int i = 0; i < nFine; ++i) {
        if (factor == 1) {
            t.c0[i] = t.c1[i] = i;
            t.w0[i] = 1.0;
            t.w1[i] = 0.0;
        } else {
            // Cell-centred linear interpolation: fine centres sit at 1/4 and 3/4 of a coarse cell.
            const int I = i / 2;
            t.c0[i] = I;
            t.w0[i] = 0.75;
            t.c1[i] = (i % 2 == 0) ? I - 1 : I + 1;
            t.w1[i] = 0.25;
        }
    }
    t.f.assign(nCoarse, {0, 0, 0, 0});
    t.w.assign(nCoarse, {0, 0, 0, 0});
    t.count.assign(nCoarse, 0);
    for (int i = 0; i < nFine; ++i) {
        auto add = [&](int I, double w) {
            if (I < 0 || I >= nCoarse || w == 0.0) return;
            t.f[I][t.count[I]] = i;
            t.w[I][t.count[I]] = w;
            ++t.count[I];
        };
        add(t.c0[i], t.w0[i]);
        add(t.c1[i], t.w1[i]);
    }
    return t;
}

// Constant-coefficient row kernels for runs of full-open cells, written so the compiler can
// vectorise them (no stores into arrays they read); compiled twice, for x86-64-v3 (AVX2, FMA)
// and the baseline, and picked at run time.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define GALE_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define GALE_VECTOR_CLONES
#endif

/// tmp[i - i0] = (b + sum of weighted neighbours) / D for i in [i0, i1): the Gauss-Seidel value of
/// every cell of the run, from the current x (the caller keeps one colour).
/// The strides are signed so that xr[i - sx] steps back (an unsigned i - sx wraps: UB, UBSan).
GALE_VECTOR_CLONES
void uniformCandidates(const double* __restrict x, const double* __restrict b, double* __restrict tmp, size_t p0,
                       int i0, int i1, std::ptrdiff_t sx, std::ptrdiff_t sxy, double bx, double by, double bz, double invD) {
    const double* xr = x + p0;
    const double* br = b + p0;
    for (int i = i0; i < i1; ++i)
        tmp[i - i0] = (br[i] + bx * (xr[i - 1] + xr[i + 1]) + by * (xr[i - sx] + xr[i + sx]) +
                       bz * (xr[i - sxy] + xr[i + sxy])) *
                      invD;
}

/// out = b - A x on a run (residual), or out = A x with b == nullptr; returns sum out * x.
GALE_VECTOR_CLONES
double uniformApply(const double* __restrict x, const double* __restrict b, double* __restrict out, size_t p0, int i0,
                    int i1, std::ptrdiff_t sx, std::ptrdiff_t sxy, double bx, double by, double bz, double D) {
    const double* xr = x + p0;
    double* o = out + p0;
    double acc = 0.0;
    if (b) {
        const double* br = b + p0;
        for (int i = i0; i < i1; ++i)
            o[i] = br[i] - (D * xr[i] - (bx * (xr[i - 1] + xr[i + 1]) + by * (xr[i - sx] + xr[i + sx]) +
                                         bz * (xr[i - sxy] + xr[i + sxy])));
        return 0.0;
    }
    for (int i = i0; i < i1; ++i) {
        const double v = D * xr[i] - (bx * (xr[i - 1] + xr[i + 1]) + by * (xr[i - sx] + xr[i + sx]) +
                                      bz * (xr[i - sxy] + xr[i + sxy]));
        o[i] = v;
        acc += v * xr[i];
    }
    return acc;
}

struct Level {
    int nx = 0, ny = 0, nz = 0;
    int sx = 0, sy = 0, sz = 0;  // padded sizes
    size_t sxy = 0, total = 0;
    std::vector<float> wx, wy, wz;  // padded, face on the low side of the cell
    std::vector<double> x, b, r;    // levels >= 1 only (level 0 uses the PCG vectors)
    std::vector<uint8_t> active;    // padded: 1 where the cell is an unknown (diag > 0)
    /// Fast path: cells whose six weights equal the level's full-open values (bx, by, bz) form
    /// runs along x; kernels treat them with constant coefficients and never read their weights.
    float bx = 0, by = 0, bz = 0;
    double uniformDiag = 0, uniformInvDiag = 0;
    std::vector<uint32_t> rowRuns;           // runs of row (j, k) are runs[rowRuns[r] .. rowRuns[r+1])
    std::vector<std::array<int, 2>> runs;    // [i0, i1)
    size_t uniformCells = 0;
    int cx = 1, cy = 1, cz = 1;     // coarsening factors to the next level
    Transfer1D tx, ty, tz;          // transfers to the next level
    /// Fine cells next to an inactive coarse cell or a Neumann side: the trilinear weight those
    /// coarse values would carry goes to the cell's own coarse parent instead (constant
    /// extrapolation, the discrete analogue of the no-flux condition). Restriction applies the
    /// transpose, so the V-cycle stays symmetric.
    struct Redirect {
        size_t fine, home;
        double weight;
    };
    std::vector<Redirect> redirects;
    std::vector<size_t> redirectSlab;  // redirects of fine slab k: [redirectSlab[k], redirectSlab[k+1])

    void resize(int nx_, int ny_, int nz_) {
        nx = nx_, ny = ny_, nz = nz_;
        sx = nx + 2, sy = ny + 2, sz = nz + 2;
        sxy = size_t(sx) * sy;
        total = sxy * sz;
        wx.assign(total, 0.f);
        wy.assign(total, 0.f);
        wz.assign(total, 0.f);
    }
    size_t cells() const { return size_t(nx) * ny * nz; }
    size_t at(int i, int j, int k) const { return size_t(i + 1) + sx * (size_t(j + 1) + sy * size_t(k + 1)); }
    size_t rowIndex(int j, int k) const { return size_t(j) + size_t(ny) * k; }
    /// Calls general(i0, i1) and uniform(i0, i1) over the segments of row (j, k), in order.
    template <class G, class U>
    void segments(int j, int k, const G& general, const U& uniform) const {
        int i = 0;
        const size_t r = rowIndex(j, k);
        for (uint32_t n = rowRuns[r]; n < rowRuns[r + 1]; ++n) {
            if (runs[n][0] > i) general(i, runs[n][0]);
            uniform(runs[n][0], runs[n][1]);
            i = runs[n][1];
        }
        if (i < nx) general(i, nx);
    }
    void findUniformRuns(float bx_, float by_, float bz_) {
        constexpr int MIN_RUN = 4;  // shorter runs are not worth a branch
        bx = bx_, by = by_, bz = bz_;
        uniformDiag = 2.0 * (double(bx) + by + bz);
        uniformInvDiag = uniformDiag > 0 ? 1.0 / uniformDiag : 0.0;
        // Rows in parallel (slab by slab into separate lists), concatenated in row order.
        std::vector<std::vector<std::array<int, 2>>> perSlab(static_cast<size_t>(nz));
        std::vector<uint32_t> count(size_t(ny) * nz, 0);
        tbb::parallel_for(0, nz, [&](int k) {
            for (int j = 0; j < ny; ++j) {
                int start = -1;
                for (int i = 0; i <= nx; ++i) {
                    bool u = false;
                    if (i < nx && uniformDiag > 0) {
                        const size_t p = at(i, j, k);
                        u = wx[p] == bx && wx[p + 1] == bx && wy[p] == by && wy[p + sx] == by && wz[p] == bz &&
                            wz[p + sxy] == bz;
                    }
                    if (u && start < 0) start = i;
                    if (!u && start >= 0) {
                        if (i - start >= MIN_RUN) perSlab[size_t(k)].push_back({start, i}), ++count[rowIndex(j, k)];
                        start = -1;
                    }
                }
            }
        });
        rowRuns.assign(size_t(ny) * nz + 1, 0);
        runs.clear();
        uint32_t acc = 0;
        for (size_t r = 0; r < count.size(); ++r) rowRuns[r] = acc, acc += count[r];
        rowRuns[count.size()] = acc;
        uniformCells = 0;
        for (const auto& v : perSlab) {
            runs.insert(runs.end(), v.begin(), v.end());
            for (const auto& run : v) uniformCells += size_t(run[1] - run[0]);
        }
    }
    void markActive() {
        active.assign(total, 0);
        tbb::parallel_for(0, nz, [&](int k) {
            for (int j = 0; j < ny; ++j)
                for (int i = 0; i < nx; ++i) active[at(i, j, k)] = diag(at(i, j, k)) > 0.0;
        });
    }
    double diag(size_t p) const {
        return double(wx[p]) + wx[p + 1] + wy[p] + wy[p + sx] + wz[p] + wz[p + sxy];
    }
};

/// Runs body(j, k) over every row of a level, in parallel when the level is big enough.
template <class Body>
void forRows(const Level& L, const Body& body) {
    if (L.cells() < PARALLEL_MIN_CELLS) {
        for (int k = 0; k < L.nz; ++k)
            for (int j = 0; j < L.ny; ++j) body(j, k);
        return;
    }
    tbb::parallel_for(tbb::blocked_range2d<int>(0, L.nz, 1, 0, L.ny, 8),
                      [&](const tbb::blocked_range2d<int>& r) {
                          for (int k = r.rows().begin(); k < r.rows().end(); ++k)
                              for (int j = r.cols().begin(); j < r.cols().end(); ++j) body(j, k);
                      });
}

/// Deterministic reduction of body(j, k) -> double over rows (sum or max), so solves repeat
/// bit for bit whatever the thread count does.
template <class Body, class Join>
double reduceRows(const Level& L, const Body& body, const Join& join) {
    if (L.cells() < PARALLEL_MIN_CELLS) {
        double acc = 0.0;
        for (int k = 0; k < L.nz; ++k)
            for (int j = 0; j < L.ny; ++j) acc = join(acc, body(j, k));
        return acc;
    }
    return tbb::parallel_deterministic_reduce(
        tbb::blocked_range2d<int>(0, L.nz, 1, 0, L.ny, 16), 0.0,
        [&](const tbb::blocked_range2d<int>& r, double acc) {
            for (int k = r.rows().begin(); k < r.rows().end(); ++k)
                for (int j = r.cols().begin(); j < r.cols().end(); ++j) acc = join(acc, body(j, k));
            return acc;
        },
        join);
}

const auto SUM = [](double a, double b) { return a + b; };
const auto MAX = [](double a, double b) { return std::max(a, b); };

}  // namespace
}  // namespace detail

using detail::Level;

struct PoissonSolver::Impl {
    std::vector<Level> levels;
    // PCG vectors on level 0 (padded): solution, residual, preconditioned residual, direction,
    // operator times direction (doubles as the V-cycle's scratch residual on level 0).
    std::vector<double> xs, rs, zs, ps, qs;
    // Coarsest level: dense Cholesky factor over its active cells.
    std::vector<size_t> coarseCells;  // padded index of each active cell
    std::vector<double> chol;         // m x m lower triangle, row-major
    std::vector<double> coarseTmp;
    size_t activeCells = 0;
    double setupSeconds = 0;
    int sweeps = 2;

    // --- kernels -------------------------------------------------------------------------

    // x = A in (on level L), returns in . out.
    static double applyDot(const Level& L, const double* in, double* out) {
        const size_t sx = L.sx, sxy = L.sxy;
        const float *wx = L.wx.data(), *wy = L.wy.data(), *wz = L.wz.data();
        const double bx = L.bx, by = L.by, bz = L.bz, D = L.uniformDiag;
        return detail::reduceRows(
            L,
            [&](int j, int k) {
                double acc = 0.0;
                const size_t p0 = L.at(0, j, k);
                L.segments(
                    j, k,
                    [&](int i0, int i1) {
                        for (size_t p = p0 + i0; p < p0 + size_t(i1); ++p) {
                            const double d = double(wx[p]) + wx[p + 1] + wy[p] + wy[p + sx] + wz[p] + wz[p + sxy];
                            const double v = d * in[p] - (wx[p] * in[p - 1] + wx[p + 1] * in[p + 1] +
                                                          wy[p] * in[p - sx] + wy[p + sx] * in[p + sx] +
                                                          wz[p] * in[p - sxy] + wz[p + sxy] * in[p + sxy]);
                            out[p] = v;
                            acc += v * in[p];
                        }
                    },
                    [&](int i0, int i1) {
                        acc += detail::uniformApply(in, nullptr, out, p0, i0, i1, sx, sxy, bx, by, bz, D);
                    });
                return acc;
            },
            detail::SUM);
    }

    // r = b - A x on level L.
    static void residual(const Level& L, const double* x, const double* b, double* r) {
        const size_t sx = L.sx, sxy = L.sxy;
        const float *wx = L.wx.data(), *wy = L.wy.data(), *wz = L.wz.data();
        detail::forRows(L, [&](int j, int k) {
            const size_t p0 = L.at(0, j, k);
            for (size_t p = p0; p < p0 + size_t(L.nx); ++p) {
                const double d = double(wx[p]) + wx[p + 1] + wy[p] + wy[p + sx] + wz[p] + wz[p + sxy];
                const double v = b[p] - (d * x[p] - (wx[p] * x[p - 1] + wx[p + 1] * x[p + 1] +
                                                     wy[p] * x[p - sx] + wy[p + sx] * x[p + sx] +
                                                     wz[p] * x[p - sxy] + wz[p + sxy] * x[p + sxy]));
                r[p] = d > 0.0 ? v : 0.0;
            }
        });
    }

    // One Gauss-Seidel sweep in red-black order (colour `first`, then the other), pipelined slab
    // by slab so each slab's data is streamed from memory once: step s updates colour `first` on
    // slab s and the other colour on slab s-1 (whose first-colour neighbours are then final).
    // fromZero: start from x = 0 (first colour = b/d, other colour 0) without reading x.
    // residualOut: also r = b - A x, three slabs behind, where every neighbour is final.
    // The result equals the unpipelined red-black sweep exactly, serial or threaded.
    // C, xc: first add the coarse correction P xc (prolongation fused into the sweep, one slab
    // ahead of the colour-A update that first reads it). dotOut: also sum b . x over the final x
    // (row partial sums added in row order: deterministic).
    static void fusedSweep(const Level& L, double* x, const double* b, int first, bool fromZero,
                           double* residualOut, const Level* C = nullptr, const double* xc = nullptr,
                           double* dotOut = nullptr) {
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
                        const double d = double(wx[p]) + wx[p + 1] + wy[p] + wy[p + sx] + wz[p] + wz[p + sxy];
                        if (d > 0.0)
                            x[p] = (b[p] + wx[p] * x[p - 1] + wx[p + 1] * x[p + 1] + wy[p] * x[p - sx] +
                                    wy[p + sx] * x[p + sx] + wz[p] * x[p - sxy] + wz[p + sxy] * x[p + sxy]) /
                                   d;
                    }
                },
                [&](int i0, int i1) {
                    thread_local std::vector<double> tmp;
                    if (tmp.size() < size_t(i1 - i0)) tmp.resize(size_t(L.nx));
                    detail::uniformCandidates(x, b, tmp.data(), p0, i0, i1, sx, sxy, bx, by, bz, invD);
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
                        const double d = double(wx[p]) + wx[p + 1] + wy[p] + wy[p + sx] + wz[p] + wz[p + sxy];
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
                [&](int i0, int i1) {
                    for (size_t p = p0 + i0; p < p0 + size_t(i1); ++p) {
                        const double d = double(wx[p]) + wx[p + 1] + wy[p] + wy[p + sx] + wz[p] + wz[p + sxy];
                        const double v = b[p] - (d * x[p] - (wx[p] * x[p - 1] + wx[p + 1] * x[p + 1] +
                                                             wy[p] * x[p - sx] + wy[p + sx] * x[p + sx] +
                                                             wz[p] * x[p - sxy] + wz[p + sxy] * x[p + sxy]));
                        residualOut[p] = d > 0.0 ? v : 0.0;
                    }
                },
                [&](int i0, int i1) { detail::uniformApply(x, b, residualOut, p0, i0, i1, sx, sxy, bx, by, bz, D); });
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
            for (size_t n = L.redirectSlab[k]; n < L.redirectSlab[k + 1]; ++n) {
                const Level::Redirect& r = L.redirects[n];
                x[r.fine] += r.weight * xc[r.home];
            }
            if (serialRows) {
                for (int j = 0; j < L.ny; ++j) prolongRow(*C, xc, L, x, j, k);
            } else {
                tbb::parallel_for(tbb::blocked_range<int>(0, L.ny, 16), [&](const tbb::blocked_range<int>& r) {
                    for (int j = r.begin(); j < r.end(); ++j) prolongRow(*C, xc, L, x, j, k);
                });
            }
        };
        const int steps = L.nz + (residualOut ? 3 : 1);
        const bool serial = L.cells() < detail::PARALLEL_MIN_CELLS;
        if (C) prolongSlab(0, serial);
        for (int s = 0; s < steps; ++s) {
            const bool prolongNext = C && s + 1 < L.nz;
            if (prolongNext)  // redirects touch scattered rows: serially, before the row tasks
                for (size_t n = L.redirectSlab[s + 1]; n < L.redirectSlab[s + 2]; ++n) {
                    const Level::Redirect& r = L.redirects[n];
                    x[r.fine] += r.weight * xc[r.home];
                }
            auto rows = [&](int j0, int j1) {
                for (int j = j0; j < j1; ++j) {
                    if (prolongNext) prolongRow(*C, xc, L, x, j, s + 1);
                    if (s < L.nz) {
                        if (fromZero) startRow(j, s);
                        else update(j, s, first);
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

    // Coarse right-hand side = P^T (fine residual); zero in inactive coarse cells. Rows are
    // combined first (y and z weights), then the x weights applied: ~5 loads per fine cell.
    static void restrictTo(const Level& F, const double* rf, Level& C) {
        double* bc = C.b.data();
        detail::forRows(C, [&](int J, int K) {
            thread_local std::vector<double> t;
            t.assign(size_t(F.sx), 0.0);
            for (int a = 0; a < F.tz.count[K]; ++a)
                for (int bb = 0; bb < F.ty.count[J]; ++bb) {
                    const double w = F.tz.w[K][a] * F.ty.w[J][bb];
                    const double* row = rf + F.at(-1, F.ty.f[J][bb], F.tz.f[K][a]);
                    for (int i = 0; i < F.sx; ++i) t[i] += w * row[i];
                }
            const size_t pc0 = C.at(0, J, K);
            for (int I = 0; I < C.nx; ++I) {
                double s = 0.0;
                for (int c = 0; c < F.tx.count[I]; ++c) s += F.tx.w[I][c] * t[F.tx.f[I][c] + 1];
                bc[pc0 + I] = C.active[pc0 + I] ? s : 0.0;
            }
        });
        for (const Level::Redirect& r : F.redirects) bc[r.home] += r.weight * rf[r.fine];
    }

    // x_fine += P x_coarse on fine row (j, k), trilinear part only (the redirects are added by
    // the caller). Inactive fine cells may receive values; they are decoupled (all their weights
    // are 0) and the solver masks them on output.
    static void prolongRow(const Level& C, const double* xc, const Level& F, double* xf, int j, int k) {
        thread_local std::vector<double> t;
        t.assign(size_t(C.sx), 0.0);
        const int kc[2] = {F.tz.c0[k], F.tz.c1[k]};
        const double kw[2] = {F.tz.w0[k], F.tz.w1[k]};
        const int jc[2] = {F.ty.c0[j], F.ty.c1[j]};
        const double jw[2] = {F.ty.w0[j], F.ty.w1[j]};
        for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b) {
                const double w = kw[a] * jw[b];
                if (w == 0.0) continue;
                const double* row = xc + C.at(-1, jc[b], kc[a]);
                for (int I = 0; I < C.sx; ++I) t[I] += w * row[I];
            }
        const size_t p0 = F.at(0, j, k);
        for (int i = 0; i < F.nx; ++i) xf[p0 + i] += F.tx.w0[i] * t[F.tx.c0[i] + 1] + F.tx.w1[i] * t[F.tx.c1[i] + 1];
    }

    // Which fine cells lose trilinear weight to inactive coarse cells or Neumann ghosts.
    static void buildRedirects(Level& F, const Level& C, const std::array<BoundaryKind, 6>& sides) {
        F.redirects.clear();
        auto ghostKind = [&](int I, int J, int K) {
            // -1: interior; 0: Dirichlet ghost (value 0 is right); 1: Neumann ghost.
            bool out = false, dir = false;
            const int idx[3] = {I, J, K}, n[3] = {C.nx, C.ny, C.nz};
            for (int d = 0; d < 3; ++d) {
                if (idx[d] < 0 || idx[d] >= n[d]) {
                    out = true;
                    dir |= sides[2 * d + (idx[d] < 0 ? 0 : 1)] == BoundaryKind::Dirichlet;
                }
            }
            return out ? (dir ? 0 : 1) : -1;
        };
        // Slabs in parallel, each into its own list; concatenated in slab order so the list is
        // sorted by fine index whatever the thread count.
        // Coarse cells whose 3x3x3 neighbourhood is active and inside the box: their fine
        // children lose nothing (all trilinear contributors lie in that neighbourhood).
        // Separable 3-point minimum of the activity flags along x, then y, then z.
        std::vector<uint8_t> m1(C.total, 0), m2(C.total, 0);
        auto minFilter = [&](const std::vector<uint8_t>& in, std::vector<uint8_t>& out, size_t stride) {
            tbb::parallel_for(0, C.nz, [&](int K) {
                for (int J = 0; J < C.ny; ++J)
                    for (int I = 0; I < C.nx; ++I) {
                        const size_t q = C.at(I, J, K);
                        out[q] = in[q] & in[q - stride] & in[q + stride];
                    }
            });
        };
        minFilter(C.active, m1, 1);
        minFilter(m1, m2, size_t(C.sx));
        minFilter(m2, m1, C.sxy);
        const std::vector<uint8_t>& surrounded = m1;
        std::vector<std::vector<Level::Redirect>> perSlab(size_t(F.nz));
        tbb::parallel_for(0, F.nz, [&](int k) {
            std::vector<Level::Redirect>& out = perSlab[size_t(k)];
            for (int j = 0; j < F.ny; ++j)
                for (int i = 0; i < F.nx; ++i) {
                    const size_t p = F.at(i, j, k);
                    if (!F.active[p] || surrounded[C.at(F.tx.c0[i], F.ty.c0[j], F.tz.c0[k])]) continue;
                    const int ci[2] = {F.tx.c0[i], F.tx.c1[i]}, cj[2] = {F.ty.c0[j], F.ty.c1[j]},
                              ck[2] = {F.tz.c0[k], F.tz.c1[k]};
                    const double wi[2] = {F.tx.w0[i], F.tx.w1[i]}, wj[2] = {F.ty.w0[j], F.ty.w1[j]},
                                 wk[2] = {F.tz.w0[k], F.tz.w1[k]};
                    double lost = 0.0;
                    for (int a = 0; a < 2; ++a)
                        for (int b = 0; b < 2; ++b)
                            for (int c = 0; c < 2; ++c) {
                                const double w = wk[a] * wj[b] * wi[c];
                                if (w == 0.0) continue;
                                const int I = ci[c], J = cj[b], K = ck[a];
                                const bool inside = I >= 0 && J >= 0 && K >= 0 && I < C.nx && J < C.ny && K < C.nz;
                                if (inside ? !C.active[C.at(I, J, K)] : ghostKind(I, J, K) == 1) lost += w;
                            }
                    if (lost > 0.0) out.push_back({p, C.at(ci[0], cj[0], ck[0]), lost});
                }
        });
        F.redirectSlab.assign(size_t(F.nz) + 1, 0);
        for (int k = 0; k < F.nz; ++k) {
            F.redirectSlab[k] = F.redirects.size();
            F.redirects.insert(F.redirects.end(), perSlab[k].begin(), perSlab[k].end());
        }
        F.redirectSlab[F.nz] = F.redirects.size();
    }

    void coarseSolve(const Level& L, const double* b, double* x) {
        std::fill(x, x + L.total, 0.0);
        const size_t m = coarseCells.size();
        if (m == 0) return;
        double* y = coarseTmp.data();
        for (size_t a = 0; a < m; ++a) y[a] = b[coarseCells[a]];
        for (size_t a = 0; a < m; ++a) {  // L y' = y
            double s = y[a];
            for (size_t c = 0; c < a; ++c) s -= chol[a * m + c] * y[c];
            y[a] = s / chol[a * m + a];
        }
        for (size_t a = m; a-- > 0;) {  // L^T x = y'
            double s = y[a];
            for (size_t c = a + 1; c < m; ++c) s -= chol[c * m + a] * y[c];
            y[a] = s / chol[a * m + a];
        }
        for (size_t a = 0; a < m; ++a) x[coarseCells[a]] = y[a];
    }

    // One symmetric V(n, n) cycle: x = M^{-1} b on level l (x is overwritten).
    // One symmetric V(n, n) cycle: x = M^{-1} b on level l (x is overwritten). dotOut: b . x.
    void vcycle(size_t l, const double* b, double* x, double* scratch, double* dotOut = nullptr) {
        Level& L = levels[l];
        if (l + 1 == levels.size()) {
            coarseSolve(L, b, x);
            if (dotOut) {
                double acc = 0.0;
                for (size_t p = 0; p < L.total; ++p) acc += b[p] * x[p];
                *dotOut = acc;
            }
            return;
        }
        // Pre-smoothing V(n, .) in red-black order; the last sweep also forms the residual.
        for (int s = 0; s < sweeps; ++s)
            fusedSweep(L, x, b, /*first=*/0, /*fromZero=*/s == 0, s + 1 == sweeps ? scratch : nullptr);
        Level& C = levels[l + 1];
        restrictTo(L, scratch, C);
        vcycle(l + 1, C.b.data(), C.x.data(), C.r.data());
        // Post-smoothing in black-red order: the adjoint of the pre-smoother, so the V-cycle is a
        // symmetric preconditioner as CG requires. The first post-sweep adds the coarse
        // correction as it goes; the last one sums b . x.
        for (int s = 0; s < sweeps; ++s)
            fusedSweep(L, x, b, /*first=*/1, /*fromZero=*/false, nullptr, s == 0 ? &C : nullptr,
                       s == 0 ? C.x.data() : nullptr, s + 1 == sweeps ? dotOut : nullptr);
    }

    void buildCoarse(const Level& F, Level& C) {
        C.resize((F.nx + F.cx - 1) / F.cx, (F.ny + F.cy - 1) / F.cy, (F.nz + F.cz - 1) / F.cz);
        // Coarse face weight = sum of the fine face weights covering it / coarsening factor along
        // the face normal: the conductance of the averaged open fraction at the coarse spacing.
        auto sumFaces = [&](int axis, int I, int J, int K) {
            const int c[3] = {F.cx, F.cy, F.cz};
            const int n[3] = {F.nx, F.ny, F.nz};
            int lo[3] = {I * c[0], J * c[1], K * c[2]};
            int hi[3] = {lo[0] + c[0], lo[1] + c[1], lo[2] + c[2]};
            lo[axis] = std::min(lo[axis], n[axis]);  // face index, boundary face at n
            hi[axis] = lo[axis] + 1;
            for (int d = 0; d < 3; ++d)
                if (d != axis) hi[d] = std::min(hi[d], n[d]);
            const std::vector<float>& w = axis == 0 ? F.wx : axis == 1 ? F.wy : F.wz;
            const double small = detail::COARSE_MIN_OPEN_FRACTION * (axis == 0 ? F.bx : axis == 1 ? F.by : F.bz);
            double s = 0.0;
            for (int k = lo[2]; k < hi[2]; ++k)
                for (int j = lo[1]; j < hi[1]; ++j)
                    for (int i = lo[0]; i < hi[0]; ++i) {
                        const double v = w[F.at(i, j, k)];
                        s += (v > 0.0 && v < small) ? small : v;
                    }
            return float(s / c[axis]);
        };
        tbb::parallel_for(0, C.nz + 1, [&](int K) {
            for (int J = 0; J <= C.ny; ++J)
                for (int I = 0; I <= C.nx; ++I) {
                    const size_t p = C.at(I, J, K);
                    if (J < C.ny && K < C.nz) C.wx[p] = sumFaces(0, I, J, K);
                    if (I < C.nx && K < C.nz) C.wy[p] = sumFaces(1, I, J, K);
                    if (I < C.nx && J < C.ny) C.wz[p] = sumFaces(2, I, J, K);
                }
        });
        C.x.assign(C.total, 0.0);
        C.b.assign(C.total, 0.0);
        C.r.assign(C.total, 0.0);
    }

    void factorCoarsest() {
        const Level& L = levels.back();
        coarseCells.clear();
        for (int k = 0; k < L.nz; ++k)
            for (int j = 0; j < L.ny; ++j)
                for (int i = 0; i < L.nx; ++i)
                    if (L.diag(L.at(i, j, k)) > 0.0) coarseCells.push_back(L.at(i, j, k));
        const size_t m = coarseCells.size();
        chol.assign(m * m, 0.0);
        coarseTmp.assign(m, 0.0);
        std::vector<long> slot(L.total, -1);
        for (size_t a = 0; a < m; ++a) slot[coarseCells[a]] = long(a);
        double maxDiag = 0.0;
        for (size_t a = 0; a < m; ++a) {
            const size_t p = coarseCells[a];
            const double d = L.diag(p);
            maxDiag = std::max(maxDiag, d);
            chol[a * m + a] = d;
            const std::pair<size_t, float> nb[6] = {{p - 1, L.wx[p]},        {p + 1, L.wx[p + 1]},
                                                    {p - L.sx, L.wy[p]},     {p + L.sx, L.wy[p + L.sx]},
                                                    {p - L.sxy, L.wz[p]},    {p + L.sxy, L.wz[p + L.sxy]}};
            for (const auto& [q, w] : nb)
                if (slot[q] >= 0) chol[a * m + size_t(slot[q])] -= w;
        }
        // In-place Cholesky (lower). A pure-Neumann component makes the matrix singular; a pivot
        // that collapses is then replaced by the largest diagonal, which pins that component and
        // keeps the preconditioner symmetric positive definite.
        for (size_t a = 0; a < m; ++a) {
            for (size_t c = 0; c <= a; ++c) {
                double s = chol[a * m + c];
                for (size_t e = 0; e < c; ++e) s -= chol[a * m + e] * chol[c * m + e];
                if (a == c) {
                    chol[a * m + a] = std::sqrt(s > 1e-12 * maxDiag ? s : maxDiag);
                } else {
                    chol[a * m + c] = s / chol[c * m + c];
                }
            }
            for (size_t c = a + 1; c < m; ++c) chol[a * m + c] = 0.0;
        }
    }
};

PoissonSystem PoissonSystem::uniformBox(int nx, int ny, int nz) {
    PoissonSystem s;
    s.nx = nx, s.ny = ny, s.nz = nz;
    s.weightX.assign(size_t(nx + 1) * ny * nz, 1.f);
    s.weightY.assign(size_t(nx) * (ny + 1) * nz, 1.f);
    s.weightZ.assign(size_t(nx) * ny * (nz + 1), 1.f);
    return s;
}

PoissonSolver::PoissonSolver(const PoissonSystem& sys) : mImpl(std::make_unique<Impl>()) {
    const auto t0 = std::chrono::steady_clock::now();
    if (sys.nx < 1 || sys.ny < 1 || sys.nz < 1)
        throw std::invalid_argument("PoissonSystem: nx, ny, nz must be >= 1, got " + std::to_string(sys.nx) +
                                    ", " + std::to_string(sys.ny) + ", " + std::to_string(sys.nz));
    const size_t nxF = size_t(sys.nx + 1) * sys.ny * sys.nz, nyF = size_t(sys.nx) * (sys.ny + 1) * sys.nz,
                 nzF = size_t(sys.nx) * sys.ny * (sys.nz + 1);
    auto checkWeights = [](const std::vector<float>& w, size_t n, const char* name) {
        if (w.size() != n)
            throw std::invalid_argument(std::string("PoissonSystem.") + name + " must have " + std::to_string(n) +
                                        " entries, got " + std::to_string(w.size()));
        for (float v : w)
            if (!(v >= 0.f) || !std::isfinite(v))
                throw std::invalid_argument(std::string("PoissonSystem.") + name +
                                            " must be finite and >= 0, got " + std::to_string(v));
    };
    checkWeights(sys.weightX, nxF, "weightX");
    checkWeights(sys.weightY, nyF, "weightY");
    checkWeights(sys.weightZ, nzF, "weightZ");

    Impl& m = *mImpl;
    m.levels.emplace_back();
    Level& L = m.levels[0];
    L.resize(sys.nx, sys.ny, sys.nz);
    // Boundary faces: Dirichlet data sits on the face, half a cell from the centre (weight x 2);
    // Neumann faces carry no flux (weight 0).
    auto boundaryScale = [&](int side) { return sys.sides[side] == BoundaryKind::Dirichlet ? 2.f : 0.f; };
    tbb::parallel_for(0, sys.nz, [&](int k) {
        for (int j = 0; j < sys.ny; ++j)
            for (int i = 0; i <= sys.nx; ++i) {
                const float s = i == 0 ? boundaryScale(SIDE_XMIN) : i == sys.nx ? boundaryScale(SIDE_XMAX) : 1.f;
                L.wx[L.at(i, j, k)] = s * sys.weightX[sys.faceXIndex(i, j, k)];
            }
        for (int j = 0; j <= sys.ny; ++j)
            for (int i = 0; i < sys.nx; ++i) {
                const float s = j == 0 ? boundaryScale(SIDE_YMIN) : j == sys.ny ? boundaryScale(SIDE_YMAX) : 1.f;
                L.wy[L.at(i, j, k)] = s * sys.weightY[sys.faceYIndex(i, j, k)];
            }
    });
    tbb::parallel_for(0, sys.nz + 1, [&](int k) {
        for (int j = 0; j < sys.ny; ++j)
            for (int i = 0; i < sys.nx; ++i) {
                const float s = k == 0 ? boundaryScale(SIDE_ZMIN) : k == sys.nz ? boundaryScale(SIDE_ZMAX) : 1.f;
                L.wz[L.at(i, j, k)] = s * sys.weightZ[sys.faceZIndex(i, j, k)];
            }
    });
    L.markActive();
    {
        // Full-open weights: the largest interior face weight per direction (per-slab maxima,
        // then the maximum of those: exact, so deterministic).
        std::vector<std::array<float, 3>> slabMax(size_t(sys.nz), {0.f, 0.f, 0.f});
        std::vector<size_t> slabActive(size_t(sys.nz), 0);
        tbb::parallel_for(0, sys.nz, [&](int k) {
            std::array<float, 3>& mx = slabMax[size_t(k)];
            for (int j = 0; j < sys.ny; ++j)
                for (int i = 0; i < sys.nx; ++i) {
                    const size_t p = L.at(i, j, k);
                    if (i > 0) mx[0] = std::max(mx[0], L.wx[p]);
                    if (j > 0) mx[1] = std::max(mx[1], L.wy[p]);
                    if (k > 0) mx[2] = std::max(mx[2], L.wz[p]);
                    slabActive[size_t(k)] += L.active[p];
                }
        });
        float bx = 0, by = 0, bz = 0;
        for (int k = 0; k < sys.nz; ++k) {
            bx = std::max(bx, slabMax[size_t(k)][0]), by = std::max(by, slabMax[size_t(k)][1]);
            bz = std::max(bz, slabMax[size_t(k)][2]);
            m.activeCells += slabActive[size_t(k)];
        }
        L.findUniformRuns(bx, by, bz);
    }

    while (m.levels.back().cells() > detail::COARSEST_MAX_CELLS) {
        Level& F = m.levels.back();
        F.cx = F.nx > 1 ? 2 : 1;
        F.cy = F.ny > 1 ? 2 : 1;
        F.cz = F.nz > 1 ? 2 : 1;
        if (F.cx == 1 && F.cy == 1 && F.cz == 1) break;
        Level C;
        m.buildCoarse(F, C);
        C.markActive();
        // A coarse face over full-open fine faces: (number of fine faces) * base / factor, exact
        // in floating point for the power-of-two factors used here.
        C.findUniformRuns(float(double(F.bx) * F.cy * F.cz / F.cx), float(double(F.by) * F.cx * F.cz / F.cy),
                          float(double(F.bz) * F.cx * F.cy / F.cz));
        F.tx = detail::makeTransfer(F.nx, C.nx, F.cx);
        F.ty = detail::makeTransfer(F.ny, C.ny, F.cy);
        F.tz = detail::makeTransfer(F.nz, C.nz, F.cz);
        Impl::buildRedirects(F, C, sys.sides);
        m.levels.push_back(std::move(C));
    }
    m.factorCoarsest();
    const size_t total = m.levels[0].total;
    for (auto* v : {&m.xs, &m.rs, &m.zs, &m.ps, &m.qs}) v->assign(total, 0.0);
    m.setupSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

PoissonSolver::~PoissonSolver() = default;
PoissonSolver::PoissonSolver(PoissonSolver&&) noexcept = default;
PoissonSolver& PoissonSolver::operator=(PoissonSolver&&) noexcept = default;

int PoissonSolver::levelCount() const { return int(mImpl->levels.size()); }
size_t PoissonSolver::activeCellCount() const { return mImpl->activeCells; }

size_t PoissonSolver::memory_bytes() const {
    size_t bytes = 0;
    for (const Level& L : mImpl->levels)
        bytes += (L.wx.size() + L.wy.size() + L.wz.size()) * sizeof(float) +
                 (L.x.size() + L.b.size() + L.r.size()) * sizeof(double);
    bytes += 5 * mImpl->xs.size() * sizeof(double);
    bytes += mImpl->chol.size() * sizeof(double);
    return bytes;
}

double PoissonSolver::estimatedBytesPerCell() {
    // Level 0: five PCG vectors (double) + three weight arrays (float); coarser levels x, b, r and
    // weights at 1/8 + 1/64 + ... = 1/7 of the cells; plus ~5% padding.
    return 1.05 * (5 * 8 + 3 * 4 + (3 * 8 + 3 * 4) / 7.0);
}

double PoissonSolver::bytesPerCellPerIteration(int n, double uniformFraction) {
    // Streams per kernel on one level (doubles 8 B, the three weight arrays 12 B per cell), with
    // the slab pipelining of fusedSweep (neighbour slabs come from cache):
    //   first sweep from zero (both colours): read b, w, write x                   8 + 12 + 8 = 28
    //   each later sweep (both colours): read x, b, w, write x                     36
    //   the residual fused into the last pre-sweep: write r                        8
    //   restriction: read the fine residual                                        8
    //   prolongation: fused into the first post-sweep, no extra stream             0
    // Uniform (full-open) cells never read their weights: 12 B less per sweep for them.
    const double u = std::clamp(uniformFraction, 0.0, 1.0);
    const double vcycleLevel = 28 + 36.0 * (2 * n - 1) + 8 + 8 - 12.0 * (2 * n) * u;
    //   PCG on level 0: q = A p (+dot): read p, w, write q 28; x += a p, r -= a q (+max): 48;
    //   r.z fused into the last post-sweep: 0; p = z + b p: 24.
    const double pcg = 28 + 48 + 24 - 12.0 * u;
    // Coarser levels hold 1/8 + 1/64 + ... = 1/7 of the cells.
    return pcg + vcycleLevel * (1.0 + 1.0 / 7.0);
}

double PoissonSolver::uniformCellFraction() const {
    const Level& L = mImpl->levels[0];
    return L.cells() ? double(L.uniformCells) / double(L.cells()) : 0.0;
}

void PoissonSolver::applyOperator(const std::vector<double>& x, std::vector<double>& out) const {
    const Level& L = mImpl->levels[0];
    if (x.size() != L.cells())
        throw std::invalid_argument("applyOperator: x must have " + std::to_string(L.cells()) + " entries");
    std::vector<double> in(L.total, 0.0), res(L.total, 0.0);
    for (int k = 0; k < L.nz; ++k)
        for (int j = 0; j < L.ny; ++j)
            for (int i = 0; i < L.nx; ++i) in[L.at(i, j, k)] = x[size_t(i) + size_t(L.nx) * (j + size_t(L.ny) * k)];
    (void)Impl::applyDot(L, in.data(), res.data());
    out.assign(L.cells(), 0.0);
    for (int k = 0; k < L.nz; ++k)
        for (int j = 0; j < L.ny; ++j)
            for (int i = 0; i < L.nx; ++i) out[size_t(i) + size_t(L.nx) * (j + size_t(L.ny) * k)] = res[L.at(i, j, k)];
}

SolveReport PoissonSolver::solve(const std::vector<double>& rhs, std::vector<double>& solution,
                                 const SolverSettings& settings) {
    const auto t0 = std::chrono::steady_clock::now();
    Impl& m = *mImpl;
    Level& L = m.levels[0];
    const size_t n = L.cells();
    if (rhs.size() != n)
        throw std::invalid_argument("PoissonSolver::solve: rhs must have " + std::to_string(n) + " entries, got " +
                                    std::to_string(rhs.size()));
    if (!solution.empty() && solution.size() != n)
        throw std::invalid_argument("PoissonSolver::solve: solution (warm start) must be empty or have " +
                                    std::to_string(n) + " entries, got " + std::to_string(solution.size()));
    if (!(settings.relativeTolerance > 0.0 && settings.relativeTolerance < 1.0))
        throw std::invalid_argument("SolverSettings.relativeTolerance must be in (0, 1), got " +
                                    std::to_string(settings.relativeTolerance));
    if (settings.maxIterations < 1)
        throw std::invalid_argument("SolverSettings.maxIterations must be >= 1, got " +
                                    std::to_string(settings.maxIterations));
    if (settings.smoothingSweeps < 1 || settings.smoothingSweeps > 8)
        throw std::invalid_argument("SolverSettings.smoothingSweeps must be in 1..8, got " +
                                    std::to_string(settings.smoothingSweeps));
    m.sweeps = settings.smoothingSweeps;

    SolveReport rep;
    rep.levels = settings.useMultigrid ? int(m.levels.size()) : 1;
    rep.setupSeconds = m.setupSeconds;
    double *x = m.xs.data(), *r = m.rs.data(), *z = m.zs.data(), *p = m.ps.data(), *q = m.qs.data();
    const bool warm = !solution.empty();
    // Load b (into r) and the warm start (into x), padded; inactive cells stay 0.
    detail::forRows(L, [&](int j, int k) {
        const size_t p0 = L.at(0, j, k), c0 = size_t(L.nx) * (j + size_t(L.ny) * k);
        for (int i = 0; i < L.nx; ++i) {
            const bool active = L.diag(p0 + i) > 0.0;
            r[p0 + i] = active ? rhs[c0 + i] : 0.0;
            x[p0 + i] = (active && warm) ? solution[c0 + i] : 0.0;
        }
    });
    const double normB = detail::reduceRows(
        L,
        [&](int j, int k) {
            double mx = 0.0;
            const size_t p0 = L.at(0, j, k);
            for (int i = 0; i < L.nx; ++i) mx = std::max(mx, std::abs(r[p0 + i]));
            return mx;
        },
        detail::MAX);
    auto finish = [&](const char* why) {
        solution.assign(n, 0.0);
        detail::forRows(L, [&](int j, int k) {
            const size_t p0 = L.at(0, j, k), c0 = size_t(L.nx) * (j + size_t(L.ny) * k);
            for (int i = 0; i < L.nx; ++i) solution[c0 + i] = L.active[p0 + i] ? x[p0 + i] : 0.0;
        });
        rep.message = why;
        rep.solveSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    if (!std::isfinite(normB)) {
        rep.converged = false;
        rep.initialRelativeResidual = rep.relativeResidual = std::numeric_limits<double>::infinity();
        std::fill(x, x + L.total, 0.0);
        finish("right-hand side is not finite");
        return rep;
    }
    if (normB == 0.0) {
        std::fill(x, x + L.total, 0.0);
        rep.converged = true;
        finish("right-hand side is zero: solution is zero");
        return rep;
    }
    // Keep b in z temporarily to form r = b - A x0.
    if (warm) {
        std::copy(r, r + L.total, p);  // p = b
        Impl::residual(L, x, p, r);
    }
    auto maxAbs = [&](const double* v) {
        return detail::reduceRows(
            L,
            [&](int j, int k) {
                double mx = 0.0;
                const size_t p0 = L.at(0, j, k);
                for (int i = 0; i < L.nx; ++i) mx = std::max(mx, std::abs(v[p0 + i]));
                return mx;
            },
            detail::MAX);
    };
    double res = maxAbs(r) / normB;
    rep.initialRelativeResidual = res;
    rep.relativeResidual = res;
    const double tol = settings.relativeTolerance;
    if (res <= tol) {
        rep.converged = true;
        finish("warm start already meets the tolerance");
        return rep;
    }
    auto precondition = [&]() {
        if (settings.useMultigrid) {
            double rz = 0.0;
            m.vcycle(0, r, z, q, &rz);  // r . z summed inside the last sweep
            return rz;
        } else {
            detail::forRows(L, [&](int j, int k) {
                const size_t p0 = L.at(0, j, k);
                for (size_t pp = p0; pp < p0 + size_t(L.nx); ++pp) {
                    const double d = L.diag(pp);
                    z[pp] = d > 0.0 ? r[pp] / d : 0.0;
                }
            });
        }
        return detail::reduceRows(
            L,
            [&](int j, int k) {
                double s = 0.0;
                const size_t p0 = L.at(0, j, k);
                for (size_t pp = p0; pp < p0 + size_t(L.nx); ++pp) s += r[pp] * z[pp];
                return s;
            },
            detail::SUM);
    };
    double rz = precondition();
    std::copy(z, z + L.total, p);
    const char* why = "reached maxIterations";
    bool ok = false;
    for (int it = 1; it <= settings.maxIterations; ++it) {
        const double pq = Impl::applyDot(L, p, q);
        if (!(pq > 0.0) || !std::isfinite(pq) || !std::isfinite(rz)) {
            why = "breakdown: p.Ap is not positive (operator not SPD or values not finite)";
            break;
        }
        const double alpha = rz / pq;
        const double rmax = detail::reduceRows(
            L,
            [&](int j, int k) {
                double mx = 0.0;
                const size_t p0 = L.at(0, j, k);
                for (size_t pp = p0; pp < p0 + size_t(L.nx); ++pp) {
                    x[pp] += alpha * p[pp];
                    r[pp] -= alpha * q[pp];
                    mx = std::max(mx, std::abs(r[pp]));
                }
                return mx;
            },
            detail::MAX);
        rep.iterations = it;
        res = rmax / normB;
        if (!std::isfinite(res)) {
            why = "residual is not finite";
            break;
        }
        if (res <= tol) {
            ok = true;
            why = "converged";
            break;
        }
        const double rzNew = precondition();
        const double beta = rzNew / rz;
        rz = rzNew;
        detail::forRows(L, [&](int j, int k) {
            const size_t p0 = L.at(0, j, k);
            for (size_t pp = p0; pp < p0 + size_t(L.nx); ++pp) p[pp] = z[pp] + beta * p[pp];
        });
    }
    // Report the true residual, not the recurrence's: b - A x, recomputed once.
    {
        detail::forRows(L, [&](int j, int k) {
            const size_t p0 = L.at(0, j, k), c0 = size_t(L.nx) * (j + size_t(L.ny) * k);
            for (int i = 0; i < L.nx; ++i) z[p0 + i] = L.diag(p0 + i) > 0.0 ? rhs[c0 + i] : 0.0;
        });
        Impl::residual(L, x, z, r);
        const double trueRes = maxAbs(r) / normB;
        rep.relativeResidual = trueRes;
        // Rounding can leave the true residual a little above the recurrence's.
        constexpr double RECURRENCE_DRIFT = 10.0;
        rep.converged = ok && trueRes <= RECURRENCE_DRIFT * tol;
        if (ok && !rep.converged) why = "recurrence converged but the true residual did not";
    }
    finish(why);
    return rep;
}

}  // namespace gale::sim
