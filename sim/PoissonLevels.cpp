/// \file PoissonLevels.cpp
/// The multigrid hierarchy of PoissonSolver (MGPCG after McAdams, Sifakis, Teran 2010): level 0
/// from the PoissonSystem (boundary faces scaled for Dirichlet data half a cell away, Neumann
/// faces closed), the runs of full-open cells for the constant-coefficient fast path, coarsening
/// by 2 per axis with coarse face weights = averaged fine open fractions at twice the spacing
/// (slivers counted as at least COARSE_MIN_OPEN_FRACTION open, so cut-cell boundaries, Batty,
/// Bertails, Bridson 2007, coarsen without cell-type rules; a difference from the paper), and the
/// exact solve of the coarsest level by dense Cholesky (another difference from the paper)
/// (docs/solver.md, "The linear solver").

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "sim/PoissonDetail.h"

namespace gale::sim::multigrid {

/// The hierarchy stops coarsening once a level has at most this many cells; that level is solved
/// exactly by dense Cholesky (about COARSEST_MAX_CELLS^3 / 3 flops once, ^2 per application).
constexpr size_t COARSEST_MAX_CELLS = 600;

namespace {
/// Open faces thinner than this fraction of a full-open face count as this thick when the coarse
/// levels are built (the finest level keeps the exact cut-cell weights, so the discretisation and
/// the solution are unchanged: only the preconditioner differs). Slivers of cut cells otherwise
/// make the averaged coarse operator a poor model of the fine one: on a 30 m Gaussian hill at
/// 200 x 200 x 120 cells, 22 -> 11 iterations to 1e-6 (docs/solver.md).
constexpr double COARSE_MIN_OPEN_FRACTION = 0.1;

/// C = the coarsening of F by its factors (F.cx, F.cy, F.cz): sizes, face weights, zeroed x, b, r.
void buildCoarse(const Level& F, Level& C) {
    C.resize((F.nx + F.cx - 1) / F.cx, (F.ny + F.cy - 1) / F.cy, (F.nz + F.cz - 1) / F.cz);
    // Coarse face weight = sum of the fine face weights covering it / coarsening factor along
    // the face normal: the conductance of the averaged open fraction at the coarse spacing.
    std::array<std::vector<float>, 3> layerFull;  // per fine layer (z-faces: per face k)
    if (F.zLines) {
        // Interior faces only, as the level's bx, by, bz (boundary faces carry the factor 2).
        for (auto& v : layerFull) v.assign(size_t(F.nz) + 1, 0.f);
        for (int k = 0; k < F.nz; ++k)
            for (int j = 0; j < F.ny; ++j)
                for (int i = 0; i < F.nx; ++i) {
                    const size_t p = F.at(i, j, k);
                    const size_t kk = size_t(k);
                    if (i > 0) layerFull[0][kk] = std::max(layerFull[0][kk], F.wx[p]);
                    if (j > 0) layerFull[1][kk] = std::max(layerFull[1][kk], F.wy[p]);
                    if (k > 0) layerFull[2][kk] = std::max(layerFull[2][kk], F.wz[p]);
                }
        layerFull[2][0] = layerFull[2][1 % F.nz];
        layerFull[2][size_t(F.nz)] = layerFull[2][size_t(F.nz) - 1];
    }
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
        const double full = axis == 0 ? F.bx : axis == 1 ? F.by : F.bz;
        double s = 0.0;
        for (int k = lo[2]; k < hi[2]; ++k) {
            // Stretched layers: a full-open face's weight depends on its layer, so the sliver
            // floor is a fraction of the layer's own largest weight.
            const double small =
                COARSE_MIN_OPEN_FRACTION * (F.zLines ? layerFull[size_t(axis)][size_t(k)] : full);
            for (int j = lo[1]; j < hi[1]; ++j)
                for (int i = lo[0]; i < hi[0]; ++i) {
                    const double v = w[F.at(i, j, k)];
                    s += (v > 0.0 && v < small) ? small : v;
                }
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

}  // namespace

namespace {

/// L's runs (at least MIN_RUN long) of cells for which uniform(p, k) holds, rows in parallel
/// (slab by slab into separate lists), concatenated in row order.
template <class Uniform>
void findRuns(Level& L, const Uniform& uniform) {
    constexpr int MIN_RUN = 4;  // shorter runs are not worth a branch
    std::vector<std::vector<std::array<int, 2>>> perSlab(static_cast<size_t>(L.nz));
    std::vector<uint32_t> count(size_t(L.ny) * L.nz, 0);
    tbb::parallel_for(0, L.nz, [&](int k) {
        for (int j = 0; j < L.ny; ++j) {
            int start = -1;
            for (int i = 0; i <= L.nx; ++i) {
                const bool u = i < L.nx && uniform(L.at(i, j, k), k);
                if (u && start < 0) start = i;
                if (!u && start >= 0) {
                    if (i - start >= MIN_RUN)
                        perSlab[size_t(k)].push_back({start, i}), ++count[L.rowIndex(j, k)];
                    start = -1;
                }
            }
        }
    });
    L.rowRuns.assign(size_t(L.ny) * L.nz + 1, 0);
    L.runs.clear();
    uint32_t acc = 0;
    for (size_t row = 0; row < count.size(); ++row) L.rowRuns[row] = acc, acc += count[row];
    L.rowRuns[count.size()] = acc;
    L.uniformCells = 0;
    for (const auto& v : perSlab) {
        L.runs.insert(L.runs.end(), v.begin(), v.end());
        for (const auto& run : v) L.uniformCells += size_t(run[1] - run[0]);
    }
}

}  // namespace

void Level::findUniformRuns(float bx_, float by_, float bz_) {
    bx = bx_, by = by_, bz = bz_;
    uniformDiag = 2.0 * (double(bx) + by + bz);
    uniformInvDiag = uniformDiag > 0 ? 1.0 / uniformDiag : 0.0;
    findRuns(*this, [&](size_t p, int) {
        return uniformDiag > 0 && wx[p] == bx && wx[p + 1] == bx && wy[p] == by &&
               wy[p + sx] == by && wz[p] == bz && wz[p + sxy] == bz;
    });
}

void Level::findLayerRuns() {
    // Per layer the largest weights of its interior x- and y-faces and of the z-faces below it
    // (boundary z-faces at k = 0 and nz: their own, scaled, values), exact maxima, so
    // deterministic; a cell whose six faces carry them is on the fast path with its layer's
    // constants (cells on the box's sides carry the side's scaled weight and are not).
    layerBx.assign(size_t(nz), 0.f);
    layerBy.assign(size_t(nz), 0.f);
    layerBz.assign(size_t(nz) + 1, 0.f);
    tbb::parallel_for(0, nz + 1, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const size_t p = at(i, j, k);
                if (k < nz && i > 0) layerBx[size_t(k)] = std::max(layerBx[size_t(k)], wx[p]);
                if (k < nz && j > 0) layerBy[size_t(k)] = std::max(layerBy[size_t(k)], wy[p]);
                layerBz[size_t(k)] = std::max(layerBz[size_t(k)], wz[p]);
            }
    });
    lowestActive.assign(size_t(nx) * size_t(ny), nz);
    tbb::parallel_for(0, ny, [&](int j) {
        for (int i = 0; i < nx; ++i) {
            int k = 0;
            while (k < nz && !active[at(i, j, k)]) ++k;
            lowestActive[size_t(i) + size_t(nx) * size_t(j)] = k;
        }
    });
    findRuns(*this, [&](size_t p, int k) {
        const float fx = layerBx[size_t(k)], fy = layerBy[size_t(k)];
        return active[p] && wx[p] == fx && wx[p + 1] == fx && wy[p] == fy && wy[p + sx] == fy &&
               wz[p] == layerBz[size_t(k)] && wz[p + sxy] == layerBz[size_t(k) + 1];
    });
}

void Level::markActive() {
    active.assign(total, 0);
    tbb::parallel_for(0, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) active[at(i, j, k)] = diag(at(i, j, k)) > 0.0;
    });
}

std::vector<std::array<int, 3>> coarseningPlan(int nx, int ny, int nz) {
    std::vector<std::array<int, 3>> plan;
    while (GridIndex{nx, ny, nz}.cellCount() > COARSEST_MAX_CELLS) {
        const std::array<int, 3> f = {nx > 1 ? 2 : 1, ny > 1 ? 2 : 1, nz > 1 ? 2 : 1};
        if (f[0] == 1 && f[1] == 1 && f[2] == 1) break;
        plan.push_back(f);
        nx = (nx + f[0] - 1) / f[0], ny = (ny + f[1] - 1) / f[1], nz = (nz + f[2] - 1) / f[2];
    }
    return plan;
}

size_t buildHierarchy(const PoissonSystem& sys, std::vector<Level>& levels,
                      const SubdomainShape* subdomain) {
    levels.clear();
    levels.emplace_back();
    Level& L = levels[0];
    size_t activeCells = 0;
    L.resize(sys.nx, sys.ny, sys.nz);
    L.zLines = sys.zLineSmoothing;
    // Boundary faces: Dirichlet data sits on the face, half a cell from the centre (weight x 2);
    // Neumann faces carry no flux (weight 0).
    auto boundaryScale = [&](int side) {
        if (subdomain && subdomain->interfaceSides[size_t(side)]) return 1.f;
        return sys.sides[side] == BoundaryKind::Dirichlet ? 2.f : 0.f;
    };
    tbb::parallel_for(0, sys.nz, [&](int k) {
        for (int j = 0; j < sys.ny; ++j)
            for (int i = 0; i <= sys.nx; ++i) {
                const float s = i == 0        ? boundaryScale(SIDE_XMIN)
                                : i == sys.nx ? boundaryScale(SIDE_XMAX)
                                              : 1.f;
                L.wx[L.at(i, j, k)] = s * sys.weightX[sys.faceXIndex(i, j, k)];
            }
        for (int j = 0; j <= sys.ny; ++j)
            for (int i = 0; i < sys.nx; ++i) {
                const float s = j == 0        ? boundaryScale(SIDE_YMIN)
                                : j == sys.ny ? boundaryScale(SIDE_YMAX)
                                              : 1.f;
                L.wy[L.at(i, j, k)] = s * sys.weightY[sys.faceYIndex(i, j, k)];
            }
    });
    tbb::parallel_for(0, sys.nz + 1, [&](int k) {
        for (int j = 0; j < sys.ny; ++j)
            for (int i = 0; i < sys.nx; ++i) {
                const float s = k == 0        ? boundaryScale(SIDE_ZMIN)
                                : k == sys.nz ? boundaryScale(SIDE_ZMAX)
                                              : 1.f;
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
            activeCells += slabActive[size_t(k)];
        }
        if (L.zLines)
            L.findLayerRuns();
        else
            L.findUniformRuns(bx, by, bz);
    }

    // The transfers see an interface as a Neumann side (SubdomainShape).
    std::array<BoundaryKind, 6> transferSides = sys.sides;
    if (subdomain)
        for (size_t s = 0; s < 6; ++s)
            if (subdomain->interfaceSides[s]) transferSides[s] = BoundaryKind::Neumann;
    const std::vector<std::array<int, 3>> plan =
        subdomain ? subdomain->plan : coarseningPlan(sys.nx, sys.ny, sys.nz);
    for (const std::array<int, 3>& factors : plan) {
        Level& F = levels.back();
        F.cx = factors[0], F.cy = factors[1], F.cz = factors[2];
        Level C;
        C.zLines = F.zLines;
        buildCoarse(F, C);
        C.markActive();
        // A coarse face over full-open fine faces: (number of fine faces) * base / factor, exact
        // in floating point for the power-of-two factors used here.
        if (C.zLines)
            C.findLayerRuns();
        else
            C.findUniformRuns(float(double(F.bx) * F.cy * F.cz / F.cx),
                              float(double(F.by) * F.cx * F.cz / F.cy),
                              float(double(F.bz) * F.cx * F.cy / F.cz));
        F.tx = makeTransfer(F.nx, C.nx, F.cx);
        F.ty = makeTransfer(F.ny, C.ny, F.cy);
        F.tz = makeTransfer(F.nz, C.nz, F.cz);
        buildRedirects(F, C, transferSides);
        levels.push_back(std::move(C));
    }
    return activeCells;
}

void CoarseSolver::factor(const Level& L) {
    cells.clear();
    for (int k = 0; k < L.nz; ++k)
        for (int j = 0; j < L.ny; ++j)
            for (int i = 0; i < L.nx; ++i)
                if (L.diag(L.at(i, j, k)) > 0.0) cells.push_back(L.at(i, j, k));
    const size_t m = cells.size();
    chol.assign(m * m, 0.0);
    tmp.assign(m, 0.0);
    std::vector<long> slot(L.total, -1);
    for (size_t a = 0; a < m; ++a) slot[cells[a]] = long(a);
    double maxDiag = 0.0;
    for (size_t a = 0; a < m; ++a) {
        const size_t p = cells[a];
        const double d = L.diag(p);
        maxDiag = std::max(maxDiag, d);
        chol[a * m + a] = d;
        const std::pair<size_t, float> nb[6] = {{p - 1, L.wx[p]},     {p + 1, L.wx[p + 1]},
                                                {p - L.sx, L.wy[p]},  {p + L.sx, L.wy[p + L.sx]},
                                                {p - L.sxy, L.wz[p]}, {p + L.sxy, L.wz[p + L.sxy]}};
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

void CoarseSolver::solve(const Level& L, const double* b, double* x) {
    std::fill(x, x + L.total, 0.0);
    const size_t m = cells.size();
    if (m == 0) return;
    double* y = tmp.data();
    for (size_t a = 0; a < m; ++a) y[a] = b[cells[a]];
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
    for (size_t a = 0; a < m; ++a) x[cells[a]] = y[a];
}

}  // namespace gale::sim::multigrid

namespace gale::sim {

double PoissonSolver::estimatedBytes(double nx, double ny, double nz) {
    // Mirrors buildHierarchy's coarsening and memory_bytes()'s arrays (Level::resize pads each
    // level by one ghost cell per side, which is most of a thin level).
    auto padded = [](double a, double b, double c) { return (a + 2) * (b + 2) * (c + 2); };
    // Level 0: weights (3 floats) and activity flags over the padded box, the five PCG vectors;
    // the solve's solution and the preconditioner's scratch over the cells.
    double bytes = padded(nx, ny, nz) * (3 * 4.0 + 1.0 + 5 * 8.0) + nx * ny * nz * 2 * 8.0;
    bytes += ny * nz * 12.0;  // row runs: an offset per row and one run per row, at least
    while (nx * ny * nz > double(multigrid::COARSEST_MAX_CELLS)) {
        if (nx <= 1 && ny <= 1 && nz <= 1) break;
        nx = std::ceil(nx / (nx > 1 ? 2 : 1)), ny = std::ceil(ny / (ny > 1 ? 2 : 1)),
        nz = std::ceil(nz / (nz > 1 ? 2 : 1));
        // A coarse level: weights, flags and x, b, r over its padded box, its row runs.
        bytes += padded(nx, ny, nz) * (3 * 4.0 + 1.0 + 3 * 8.0) + ny * nz * 12.0;
    }
    const double m = nx * ny * nz;  // the coarsest level's unknowns, at most
    return bytes + m * m * 8.0;
}

}  // namespace gale::sim
