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
/// This file holds the public class: validation, the V-cycle that ties the levels together, the
/// CG driver and its report, and the memory and traffic estimates. The parts it calls live in
/// PoissonLevels.cpp (hierarchy, coarsest solve), PoissonOperator.cpp (A x, residual),
/// PoissonSmoothing.cpp (the sweep) and PoissonTransfer.cpp (restriction, prolongation), declared
/// in the internal header PoissonDetail.h, which also describes the padded layout.

#include "sim/PoissonSolver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/PoissonDetail.h"

namespace gale::sim {

using multigrid::Level;

namespace multigrid {

const char* pcg(const Level& L, const PcgVectors& v, bool warm, const SolverSettings& settings,
                const std::function<double(double* r, double* z)>& vcycle,
                const std::function<void(double* b)>& loadRhs, PcgCommunication& comm,
                SolveReport& rep) {
    double *x = v.x, *r = v.r, *z = v.z, *p = v.p, *q = v.q;
    // max |v| over the cells of level 0 (max is exact: the same bits for any thread count).
    auto maxAbs = [&](const double* a) {
        return comm.max(reduceRows(
            L,
            [&](int j, int k) {
                double mx = 0.0;
                const size_t p0 = L.at(0, j, k);
                for (int i = 0; i < L.nx; ++i) mx = std::max(mx, std::abs(a[p0 + i]));
                return mx;
            },
            MAX));
    };
    const double normB = maxAbs(r);
    if (!std::isfinite(normB)) {
        rep.converged = false;
        rep.initialRelativeResidual = rep.relativeResidual =
            std::numeric_limits<double>::infinity();
        std::fill(x, x + L.total, 0.0);
        return "right-hand side is not finite";
    }
    if (normB == 0.0) {
        std::fill(x, x + L.total, 0.0);
        rep.converged = true;
        return "right-hand side is zero: solution is zero";
    }
    // Keep b in p temporarily to form r = b - A x0; from zero r = b, whose max is normB.
    double res = 1.0;
    if (warm) {
        std::copy(r, r + L.total, p);  // p = b
        comm.exchange(x);
        res = comm.max(residualMaxAbs(L, x, p, r)) / normB;
    }
    rep.initialRelativeResidual = res;
    rep.relativeResidual = res;
    const double tol = settings.relativeTolerance;
    if (res <= tol) {
        rep.converged = true;
        return "warm start already meets the tolerance";
    }
    auto precondition = [&]() {
        if (settings.useMultigrid) return comm.sum(vcycle(r, z));
        forRows(L, [&](int j, int k) {
            const size_t p0 = L.at(0, j, k);
            for (size_t pp = p0; pp < p0 + size_t(L.nx); ++pp) {
                const double d = L.diag(pp);
                z[pp] = d > 0.0 ? r[pp] / d : 0.0;
            }
        });
        return comm.sum(reduceRows(
            L,
            [&](int j, int k) {
                double s = 0.0;
                const size_t p0 = L.at(0, j, k);
                for (size_t pp = p0; pp < p0 + size_t(L.nx); ++pp) s += r[pp] * z[pp];
                return s;
            },
            SUM));
    };
    double rz = precondition();
    std::copy(z, z + L.total, p);
    const char* why = "reached maxIterations";
    bool ok = false;
    for (int it = 1; it <= settings.maxIterations; ++it) {
        comm.exchange(p);
        const double pq = comm.sum(applyDot(L, p, q));
        if (!(pq > 0.0) || !std::isfinite(pq) || !std::isfinite(rz)) {
            why = "breakdown: p.Ap is not positive (operator not SPD or values not finite)";
            break;
        }
        const double alpha = rz / pq;
        const double rmax = comm.max(reduceRows(
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
            MAX));
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
        forRows(L, [&](int j, int k) {
            const size_t p0 = L.at(0, j, k);
            for (size_t pp = p0; pp < p0 + size_t(L.nx); ++pp) p[pp] = z[pp] + beta * p[pp];
        });
    }
    // Report the true residual, not the recurrence's: b - A x, recomputed once.
    loadRhs(z);
    comm.exchange(x);
    const double trueRes = comm.max(residualMaxAbs(L, x, z, r)) / normB;
    rep.relativeResidual = trueRes;
    // Rounding can leave the true residual a little above the recurrence's.
    constexpr double RECURRENCE_DRIFT = 10.0;
    rep.converged = ok && trueRes <= RECURRENCE_DRIFT * tol;
    if (ok && !rep.converged) why = "recurrence converged but the true residual did not";
    return why;
}

}  // namespace multigrid

struct PoissonSolver::Impl {
    std::vector<Level> levels;
    // PCG vectors on level 0 (padded): solution, residual, preconditioned residual, direction,
    // operator times direction (doubles as the V-cycle's scratch residual on level 0).
    std::vector<double> xs, rs, zs, ps, qs;
    multigrid::CoarseSolver coarse;  // the coarsest level, solved exactly
    size_t activeCells = 0;
    double setupSeconds = 0;
    int sweeps = 2;

    // One symmetric V(n, n) cycle: x = M^{-1} b on level l (x is overwritten). dotOut: b . x.
    void vcycle(size_t l, const double* b, double* x, double* scratch, double* dotOut = nullptr) {
        Level& L = levels[l];
        if (l + 1 == levels.size()) {
            coarse.solve(L, b, x);
            if (dotOut) {
                double acc = 0.0;
                for (size_t p = 0; p < L.total; ++p) acc += b[p] * x[p];
                *dotOut = acc;
            }
            return;
        }
        // Pre-smoothing V(n, .) in red-black order; the last sweep also forms the residual.
        const auto sweep = L.zLines ? multigrid::lineSweep : multigrid::fusedSweep;
        for (int s = 0; s < sweeps; ++s)
            sweep(L, x, b, /*first=*/0, /*fromZero=*/s == 0,
                  /*residualOut=*/s + 1 == sweeps ? scratch : nullptr, nullptr, nullptr, nullptr);
        Level& C = levels[l + 1];
        multigrid::restrictTo(L, scratch, C);
        vcycle(l + 1, C.b.data(), C.x.data(), C.r.data());
        // Post-smoothing in black-red order: the adjoint of the pre-smoother, so the V-cycle is a
        // symmetric preconditioner as CG requires. The first post-sweep adds the coarse
        // correction as it goes; the last one sums b . x.
        for (int s = 0; s < sweeps; ++s)
            sweep(L, x, b, /*first=*/1, /*fromZero=*/false, nullptr, s == 0 ? &C : nullptr,
                  s == 0 ? C.x.data() : nullptr, s + 1 == sweeps ? dotOut : nullptr);
    }
};

void checkSettings(const SolverSettings& settings) {
    if (!(settings.relativeTolerance > 0.0 && settings.relativeTolerance < 1.0))
        throw ParameterError("solver.tolerance", formatG(settings.relativeTolerance),
                             "must be in (0, 1)");
    if (settings.maxIterations < 1)
        throw ParameterError("solver.max_iterations", std::to_string(settings.maxIterations),
                             "must be >= 1");
    // No scene key sets the sweeps: `gale solve` and the benchmarks keep the default.
    if (settings.smoothingSweeps < 1 || settings.smoothingSweeps > 8)
        throw std::logic_error("SolverSettings.smoothingSweeps must be in 1..8, got " +
                               std::to_string(settings.smoothingSweeps));
}

PoissonSystem PoissonSystem::uniformBox(int nx, int ny, int nz) {
    PoissonSystem s;
    s.nx = nx, s.ny = ny, s.nz = nz;
    s.weightX.assign(s.count(Placement::FaceX), 1.f);
    s.weightY.assign(s.count(Placement::FaceY), 1.f);
    s.weightZ.assign(s.count(Placement::FaceZ), 1.f);
    return s;
}

void checkSystem(const PoissonSystem& sys) {
    if (sys.nx < 1 || sys.ny < 1 || sys.nz < 1)
        throw std::logic_error("PoissonSystem: nx, ny, nz must be >= 1, got " +
                               std::to_string(sys.nx) + ", " + std::to_string(sys.ny) + ", " +
                               std::to_string(sys.nz));
    const size_t nxF = sys.count(Placement::FaceX), nyF = sys.count(Placement::FaceY),
                 nzF = sys.count(Placement::FaceZ);
    auto checkWeights = [](const std::vector<float>& w, size_t n, const char* name) {
        if (w.size() != n)
            throw std::logic_error(std::string("PoissonSystem.") + name + " must have " +
                                   std::to_string(n) + " entries, got " + std::to_string(w.size()));
        for (float v : w)
            if (!(v >= 0.f) || !std::isfinite(v))
                throw std::logic_error(std::string("PoissonSystem.") + name +
                                       " must be finite and >= 0, got " + std::to_string(v));
    };
    checkWeights(sys.weightX, nxF, "weightX");
    checkWeights(sys.weightY, nyF, "weightY");
    checkWeights(sys.weightZ, nzF, "weightZ");
}

PoissonSolver::PoissonSolver(const PoissonSystem& sys) : mImpl(std::make_unique<Impl>()) {
    const auto t0 = std::chrono::steady_clock::now();
    checkSystem(sys);

    Impl& m = *mImpl;
    m.activeCells = multigrid::buildHierarchy(sys, m.levels);
    m.coarse.factor(m.levels.back());
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
    bytes += mImpl->coarse.chol.size() * sizeof(double);
    return bytes;
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
        throw std::logic_error("applyOperator: x must have " + std::to_string(L.cells()) +
                               " entries");
    std::vector<double> in(L.total, 0.0), res(L.total, 0.0);
    for (int k = 0; k < L.nz; ++k)
        for (int j = 0; j < L.ny; ++j)
            for (int i = 0; i < L.nx; ++i) in[L.at(i, j, k)] = x[L.cellIndex(i, j, k)];
    (void)multigrid::applyDot(L, in.data(), res.data());
    out.assign(L.cells(), 0.0);
    for (int k = 0; k < L.nz; ++k)
        for (int j = 0; j < L.ny; ++j)
            for (int i = 0; i < L.nx; ++i) out[L.cellIndex(i, j, k)] = res[L.at(i, j, k)];
}

void PoissonSolver::applyPreconditioner(const std::vector<double>& r, std::vector<double>& z,
                                        int smoothingSweeps) {
    Impl& m = *mImpl;
    const Level& L = m.levels[0];
    if (r.size() != L.cells())
        throw std::logic_error("applyPreconditioner: r must have " + std::to_string(L.cells()) +
                               " entries");
    if (smoothingSweeps < 1 || smoothingSweeps > 8)
        throw std::logic_error("applyPreconditioner: smoothingSweeps must be in 1..8, got " +
                               std::to_string(smoothingSweeps));
    m.sweeps = smoothingSweeps;
    double *rs = m.rs.data(), *zs = m.zs.data();
    std::fill(m.rs.begin(), m.rs.end(), 0.0);
    for (int k = 0; k < L.nz; ++k)
        for (int j = 0; j < L.ny; ++j)
            for (int i = 0; i < L.nx; ++i) {
                const size_t p = L.at(i, j, k);
                rs[p] = L.active[p] ? r[L.cellIndex(i, j, k)] : 0.0;
            }
    m.vcycle(0, rs, zs, m.qs.data());
    z.assign(L.cells(), 0.0);
    for (int k = 0; k < L.nz; ++k)
        for (int j = 0; j < L.ny; ++j)
            for (int i = 0; i < L.nx; ++i) {
                const size_t p = L.at(i, j, k);
                z[L.cellIndex(i, j, k)] = L.active[p] ? zs[p] : 0.0;
            }
}

SolveReport PoissonSolver::solve(const std::vector<double>& rhs, std::vector<double>& solution,
                                 const SolverSettings& settings) {
    const auto t0 = std::chrono::steady_clock::now();
    Impl& m = *mImpl;
    Level& L = m.levels[0];
    const size_t n = L.cells();
    if (rhs.size() != n)
        throw std::logic_error("PoissonSolver::solve: rhs must have " + std::to_string(n) +
                               " entries, got " + std::to_string(rhs.size()));
    if (!solution.empty() && solution.size() != n)
        throw std::logic_error(
            "PoissonSolver::solve: solution (warm start) must be empty or have " +
            std::to_string(n) + " entries, got " + std::to_string(solution.size()));
    checkSettings(settings);
    m.sweeps = settings.smoothingSweeps;

    SolveReport rep;
    rep.levels = settings.useMultigrid ? int(m.levels.size()) : 1;
    rep.setupSeconds = m.setupSeconds;
    double *x = m.xs.data(), *r = m.rs.data(), *z = m.zs.data(), *p = m.ps.data(), *q = m.qs.data();
    const bool warm = !solution.empty();
    // Load b (into r) and the warm start (into x), padded; inactive cells stay 0.
    multigrid::forRows(L, [&](int j, int k) {
        const size_t p0 = L.at(0, j, k), c0 = L.cellIndex(0, j, k);
        for (int i = 0; i < L.nx; ++i) {
            const bool active = L.diag(p0 + i) > 0.0;
            r[p0 + i] = active ? rhs[c0 + i] : 0.0;
            x[p0 + i] = (active && warm) ? solution[c0 + i] : 0.0;
        }
    });
    auto finish = [&](const char* why) {
        solution.assign(n, 0.0);
        multigrid::forRows(L, [&](int j, int k) {
            const size_t p0 = L.at(0, j, k), c0 = L.cellIndex(0, j, k);
            for (int i = 0; i < L.nx; ++i) solution[c0 + i] = L.active[p0 + i] ? x[p0 + i] : 0.0;
        });
        rep.message = why;
        rep.solveSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    multigrid::PcgCommunication one;  // one process: nothing to exchange or combine
    const char* why = multigrid::pcg(
        L, {x, r, z, p, q}, warm, settings,
        [&](double* rr, double* zz) {
            double rz = 0.0;
            m.vcycle(0, rr, zz, q, &rz);  // r . z summed inside the last sweep
            return rz;
        },
        [&](double* b) {
            multigrid::forRows(L, [&](int j, int k) {
                const size_t p0 = L.at(0, j, k), c0 = L.cellIndex(0, j, k);
                for (int i = 0; i < L.nx; ++i) b[p0 + i] = L.diag(p0 + i) > 0.0 ? rhs[c0 + i] : 0.0;
            });
        },
        one, rep);
    finish(why);
    return rep;
}

}  // namespace gale::sim
