#pragma once
/// \file PoissonDetail.h
/// \internal Included only by sim/, tests/sim and dist/ (gale_dist runs these kernels on each
/// rank's subdomain; docs/architecture.md lists sim's public headers).
/// Internal to PoissonSolver (namespace gale::sim::multigrid, so its plain names such as Level
/// cannot collide with other sim internals), not part of gale_sim's interface: the multigrid level
/// (padded arrays, uniform runs, transfers to the next level), the row loops every kernel runs on,
/// and the kernels the solver's files share. MGPCG after McAdams, Sifakis, Teran 2010 ("A parallel
/// multigrid Poisson solver for fluids simulation on large grids"); the parts live in
///   PoissonLevels.cpp     the hierarchy: level 0 from the PoissonSystem, coarsening, uniform runs,
///                         the dense Cholesky of the coarsest level;
///   PoissonOperator.cpp   the 7-point operator: A x with x . A x, the residual, and the
///                         constant-coefficient row kernels;
///   PoissonSmoothing.cpp  the pipelined red-black Gauss-Seidel sweep (fusedSweep);
///   PoissonLineSmoothing.cpp  the z-line sweep of stretched layers (lineSweep), pipelined plane
///                         by plane;
///   PoissonTransfer.cpp   trilinear prolongation, restriction (its transpose), and the redirects;
///   PoissonSolver.cpp     the public class, the V-cycle and the CG driver.
///
/// Layout: every level stores its arrays padded by one ghost cell per side, so the stencil needs no
/// bounds tests. Ghost entries of solution-like arrays stay 0 (homogeneous Dirichlet data), and the
/// weight of a face is stored in the padded cell on its high side: weight of the face between
/// cells (i-1, j, k) and (i, j, k) is wx[at(i, j, k)], i in [0, nx].

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "sim/GridLayout.h"
#include "sim/PoissonSolver.h"

namespace gale::sim::multigrid {

/// Row kernels written for the compiler to vectorise are compiled twice, for x86-64-v3 (AVX2, FMA)
/// and the baseline, and picked at run time.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define GALE_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define GALE_VECTOR_CLONES
#endif

/// Below this many cells a level runs serially: TBB's scheduling costs more than it saves.
inline constexpr size_t PARALLEL_MIN_CELLS = 16 * 1024;
/// Levels of at most this many cells smooth phase by phase (each colour over the whole level in
/// one parallel loop) instead of slab by slab: they fit in a core's cache, so the pipeline saves
/// no memory traffic and its fork and join per slab costs more than the slab's work. Both orders
/// give the same x to the bit (PoissonSmoothing.cpp).
inline constexpr size_t PHASED_MAX_CELLS = 256 * 1024;
/// The threshold in force: PHASED_MAX_CELLS, unless a test compares the two orders on one system
/// (setPhasedMaxCells; 0 pipelines every level, SIZE_MAX none).
size_t phasedMaxCells();
void setPhasedMaxCells(size_t cells);

/// Cell-centred linear transfer along one axis between a level and the next coarser one.
struct Transfer1D {
    // Prolongation: fine index i takes w0 * coarse[c0] + w1 * coarse[c1] (indices in [-1, N]).
    std::vector<int> c0, c1;
    std::vector<double> w0, w1;
    // Restriction (transpose): coarse index I gathers sum over n < count of w[n] * fine[f[n]].
    std::vector<std::array<int, 4>> f;
    std::vector<std::array<double, 4>> w;
    std::vector<int> count;
};

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
    std::vector<uint32_t> rowRuns;  // runs of row (j, k) are runs[rowRuns[r] .. rowRuns[r+1])
    std::vector<std::array<int, 2>> runs;  // [i0, i1)
    size_t uniformCells = 0;
    bool zLines = false;         // smooth with lineSweep instead of fusedSweep
    int cx = 1, cy = 1, cz = 1;  // coarsening factors to the next level
    Transfer1D tx, ty, tz;       // transfers to the next level
    /// Fine cells next to an inactive coarse cell or a Neumann side: the trilinear weight those
    /// coarse values would carry goes to the cell's own coarse parent instead (constant
    /// extrapolation, the discrete analogue of the no-flux condition). Restriction applies the
    /// transpose, so the V-cycle stays symmetric.
    struct Redirect {
        size_t fine, home;
        double weight;
    };
    std::vector<Redirect> redirects;
    std::vector<size_t>
        redirectSlab;  // redirects of fine slab k: [redirectSlab[k], redirectSlab[k+1])
    /// z-line levels, which sweep plane by plane (fixed j): the redirects of fine plane j are
    /// redirects[planeRedirects[n]] for n in [planeRedirectStart[j], planeRedirectStart[j+1]).
    std::vector<uint32_t> planeRedirects;
    std::vector<size_t> planeRedirectStart;

    void resize(int nx_, int ny_, int nz_) {
        nx = nx_, ny = ny_, nz = nz_;
        sx = nx + 2, sy = ny + 2, sz = nz + 2;
        sxy = size_t(sx) * sy;
        total = sxy * sz;
        wx.assign(total, 0.f);
        wy.assign(total, 0.f);
        wz.assign(total, 0.f);
    }
    size_t cells() const { return GridIndex{nx, ny, nz}.cellCount(); }
    /// Unpadded index of cell (i, j, k) (the solver's input and output arrays).
    size_t cellIndex(int i, int j, int k) const { return GridIndex{nx, ny, nz}.cellIndex(i, j, k); }
    size_t at(int i, int j, int k) const {
        return size_t(i + 1) + sx * (size_t(j + 1) + sy * size_t(k + 1));
    }
    size_t rowIndex(int j, int k) const { return size_t(j) + size_t(ny) * k; }
    /// Calls general(i0, i1) and uniform(i0, i1) over the segments of row (j, k), in order.
    template <class G, class U>
    void segments(int j, int k, const G& general, const U& uniform) const {
        int i = 0;
        const size_t row = rowIndex(j, k);
        for (uint32_t n = rowRuns[row]; n < rowRuns[row + 1]; ++n) {
            if (runs[n][0] > i) general(i, runs[n][0]);
            uniform(runs[n][0], runs[n][1]);
            i = runs[n][1];
        }
        if (i < nx) general(i, nx);
    }
    /// Sets the full-open weights (bx_, by_, bz_) and finds the runs of cells that have them on
    /// all six faces (PoissonLevels.cpp).
    void findUniformRuns(float bx_, float by_, float bz_);
    /// z-line levels (stretched layers, whose full-open weights differ from layer to layer): the
    /// full-open weights of each layer (x- and y-faces of layer k; z-face k, below layer k, for
    /// k in [0, nz]) and the runs of active cells that have their layer's weights on all six
    /// faces (PoissonLevels.cpp). Kernels treat those with the layer's constants.
    /// Also fills lowestActive: per column (i + nx j), the lowest active layer (nz if none),
    /// below which the z-line smoother has nothing to solve.
    void findLayerRuns();
    std::vector<float> layerBx, layerBy, layerBz;
    std::vector<int> lowestActive;
    /// active = diag > 0 on every cell (PoissonLevels.cpp).
    void markActive();
    double diag(size_t p) const {
        return double(wx[p]) + wx[p + 1] + wy[p] + wy[p + sx] + wz[p] + wz[p + sxy];
    }
};

/// Runs body(j, k) over every row of a level, in parallel when the work is big enough: `cells`,
/// the cells the rows' work touches (a restriction's rows on the coarse level read the finer
/// level's cells), by default the level's own.
template <class Body>
void forRows(const Level& L, const Body& body, size_t cells) {
    if (cells < PARALLEL_MIN_CELLS) {
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

template <class Body>
void forRows(const Level& L, const Body& body) {
    forRows(L, body, L.cells());
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

inline constexpr auto SUM = [](double a, double b) { return a + b; };
inline constexpr auto MAX = [](double a, double b) { return std::max(a, b); };

// --- the hierarchy (PoissonLevels.cpp) ---------------------------------------------------------

/// The coarsening factors (cx, cy, cz) buildHierarchy uses on an nx * ny * nz box, one entry per
/// coarser level, finest first: 2 along every axis longer than one cell, until a level has at
/// most COARSEST_MAX_CELLS cells (then solved by dense Cholesky).
std::vector<std::array<int, 3>> coarseningPlan(int nx, int ny, int nz);

/// One rank's subdomain of a box split across ranks (gale_dist): a side marked as an interface
/// touches a neighbouring rank, so its face weights are the box's own interior weights, kept
/// unscaled (the ghost cell holds the neighbour's current value, exchanged by the caller), and
/// the transfers treat it as a Neumann side (weight towards the ghost goes to the fine cell's own
/// parent), so each rank's prolongation and restriction are local and still each other's
/// transpose. The plan is the whole box's coarseningPlan, so every rank builds the same levels;
/// the caller places the subdomain so that its cells start at a multiple of the product of the
/// plan's factors along each split axis (no coarse cell straddles two ranks).
struct SubdomainShape {
    std::array<bool, 6> interfaceSides{};
    std::vector<std::array<int, 3>> plan;
};

/// Builds level 0 from a validated system (boundary-face weights scaled: Dirichlet x 2, Neumann
/// 0, interfaces of a subdomain 1) and coarsens it by coarseningPlan (or the subdomain's plan);
/// levels on output holds them finest first, with the transfers between them. Returns the number
/// of active cells of level 0.
size_t buildHierarchy(const PoissonSystem& sys, std::vector<Level>& levels,
                      const SubdomainShape* subdomain = nullptr);

/// The coarsest level solved exactly: dense Cholesky factor over its active cells.
struct CoarseSolver {
    std::vector<size_t> cells;  // padded index of each active cell
    std::vector<double> chol;   // m x m lower triangle, row-major
    std::vector<double> tmp;
    /// Factors the operator of L (singular pure-Neumann components pinned, see the definition).
    void factor(const Level& L);
    /// x = A^-1 b on L's active cells, 0 elsewhere (all of x is written).
    void solve(const Level& L, const double* b, double* x);
};

// --- the operator (PoissonOperator.cpp) --------------------------------------------------------

/// out = A in on level L; returns in . out (row partial sums in row order: deterministic).
double applyDot(const Level& L, const double* in, double* out);

/// r = b - A x on level L, 0 in inactive cells; returns max |r| over the level's cells (exact, so
/// the same bits for any thread count).
double residualMaxAbs(const Level& L, const double* x, const double* b, double* r);

/// r = b - A x through each cell's own weights on padded cells [pBegin, pEnd) of one row, 0 in
/// inactive cells. Inline: fusedSweep calls it on every segment between uniform runs.
inline void residualSpan(const Level& L, const double* x, const double* b, double* r, size_t pBegin,
                         size_t pEnd) {
    const size_t sx = L.sx, sxy = L.sxy;
    const float *wx = L.wx.data(), *wy = L.wy.data(), *wz = L.wz.data();
    for (size_t p = pBegin; p < pEnd; ++p) {
        const double d = double(wx[p]) + wx[p + 1] + wy[p] + wy[p + sx] + wz[p] + wz[p + sxy];
        const double v = b[p] - (d * x[p] - (wx[p] * x[p - 1] + wx[p + 1] * x[p + 1] +
                                             wy[p] * x[p - sx] + wy[p + sx] * x[p + sx] +
                                             wz[p] * x[p - sxy] + wz[p + sxy] * x[p + sxy]));
        r[p] = d > 0.0 ? v : 0.0;
    }
}

/// tmp[i - i0] = (b + sum of weighted neighbours) / D for i in [i0, i1) of the uniform run that
/// starts the row at padded index p0: the Gauss-Seidel value of every cell of the run, from the
/// current x (the caller keeps one colour).
void uniformCandidates(const double* __restrict x, const double* __restrict b,
                       double* __restrict tmp, size_t p0, int i0, int i1, std::ptrdiff_t sx,
                       std::ptrdiff_t sxy, double bx, double by, double bz, double invD);

/// The same on a run of a z-line level's row in layer k (findLayerRuns): horizontal weights bx,
/// by, z-weights bzLo below and bzUp above.
double layerApply(const double* __restrict x, const double* __restrict b, double* __restrict out,
                  size_t p0, int i0, int i1, std::ptrdiff_t sx, std::ptrdiff_t sxy, double bx,
                  double by, double bzLo, double bzUp);

/// out = b - A x on a uniform run (residual), or out = A x with b == nullptr; returns sum out * x
/// (0 for the residual).
double uniformApply(const double* __restrict x, const double* __restrict b, double* __restrict out,
                    size_t p0, int i0, int i1, std::ptrdiff_t sx, std::ptrdiff_t sxy, double bx,
                    double by, double bz, double D);

// --- smoothing (PoissonSmoothing.cpp) ----------------------------------------------------------

/// One red-black Gauss-Seidel sweep on level L, pipelined slab by slab; optionally starting from
/// x = 0, adding the coarse correction P xc first, forming the residual, and summing b . x. The
/// result equals the unpipelined sweep exactly, serial or threaded (details at the definition).
void fusedSweep(const Level& L, double* x, const double* b, int first, bool fromZero,
                double* residualOut, const Level* C = nullptr, const double* xc = nullptr,
                double* dotOut = nullptr);

/// The same contract as fusedSweep with z-line Gauss-Seidel: colour `first` of the columns
/// ((i + j) % 2 == first) first, each column solved exactly for its z-couplings (Thomas
/// algorithm) with the horizontal neighbours' current values, then the other colour. Not
/// pipelined; optional coarse correction P xc added before, residual and b . x formed after
/// (PoissonLineSmoothing.cpp).
void lineSweep(const Level& L, double* x, const double* b, int first, bool fromZero,
               double* residualOut, const Level* C = nullptr, const double* xc = nullptr,
               double* dotOut = nullptr);

// --- transfers (PoissonTransfer.cpp) -----------------------------------------------------------

/// The 1-D transfer between nFine cells and nCoarse = ceil(nFine / factor) cells (factor 1 or 2).
Transfer1D makeTransfer(int nFine, int nCoarse, int factor);

/// F.redirects, F.redirectSlab (and on z-line levels the per-plane index): the fine cells that lose
/// trilinear weight to inactive coarse cells or Neumann ghosts of C, sorted by fine index whatever
/// the thread count.
void buildRedirects(Level& F, const Level& C, const std::array<BoundaryKind, 6>& sides);

/// C.b = P^T rf (the coarse right-hand side from the fine residual), 0 in inactive coarse cells.
void restrictTo(const Level& F, const double* rf, Level& C);

/// xf += P xc on fine cells [i0, i1) of row (j, k), trilinear part only (prolongRedirects adds
/// the rest).
void prolongRow(const Level& C, const double* xc, const Level& F, double* xf, int j, int k, int i0,
                int i1);

/// xf += the redirected part of P xc on fine slab k, in redirect order.
void prolongRedirects(const Level& F, const double* xc, double* xf, int k);

// --- the CG driver (PoissonSolver.cpp) --------------------------------------------------------

/// What the CG driver needs from whoever holds level 0, one process (PoissonSolver) or one rank
/// of many (gale_dist): the ghosts of a level-0 vector made current before the operator reads
/// them, and a partial sum or maximum combined over ranks. On one process: nothing and the
/// identity, which is this base class.
struct PcgCommunication {
    virtual ~PcgCommunication() = default;
    virtual void exchange(double* v) { (void)v; }
    virtual double sum(double v) { return v; }
    virtual double max(double v) { return v; }
};

/// Level 0's padded PCG vectors: solution, residual, preconditioned residual, direction,
/// operator times direction.
struct PcgVectors {
    double *x, *r, *z, *p, *q;
};

/// Preconditioned CG on level 0 (McAdams, Sifakis, Teran 2010 precondition with one V-cycle):
/// on input r holds b and x the warm start (both padded, 0 off the unknowns; warm says whether x
/// is one); on output x is the solution. vcycle(r, z): z = M^-1 r, returning this process's
/// r . z; loadRhs(b): b := the right-hand side again (padded), for the true residual reported at
/// the end. Fills rep's converged, iterations and residuals (the max norm, relative to max |b|);
/// returns why it stopped, in words.
const char* pcg(const Level& L, const PcgVectors& v, bool warm, const SolverSettings& settings,
                const std::function<double(double* r, double* z)>& vcycle,
                const std::function<void(double* b)>& loadRhs, PcgCommunication& comm,
                SolveReport& rep);

}  // namespace gale::sim::multigrid
