/// \file DistributedPoisson.cpp
/// Distributed MGPCG (DistributedPoisson.h): the decomposition by a PETSc DMDA, the halos by
/// PetscSF on sim's padded level arrays, the V-cycle over sim's kernels and sim's own CG driver
/// (sim/PoissonDetail.h), the coarsest level by PETSc's redundant LU. The single-process driver
/// this mirrors is sim/PoissonSolver.cpp; what differs is only where ranks meet: an exchange
/// before each sweep and each A p, the residual of the cells next to an interface formed again
/// once their ghosts are current, and every reduction summed over ranks.

#include "dist/DistributedPoisson.h"

#include <petscdmda.h>
#include <petscksp.h>
#include <petscsf.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "sim/PoissonDetail.h"

namespace gale::dist {

namespace mg = sim::multigrid;
using mg::Level;
using sim::SIDE_XMAX;
using sim::SIDE_XMIN;
using sim::SIDE_YMAX;
using sim::SIDE_YMIN;

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

void petscCheck(PetscErrorCode code, const char* call) {
    if (code != 0)
        throw std::runtime_error(std::string("PETSc: ") + call + " failed with error " +
                                 std::to_string(int(code)));
}

/// Splits the plane between `ranks` ranks: px * py = ranks (MPI_Dims_create, the larger count
/// along the longer axis), each rank's first cell a multiple of the coarsest level's spacing
/// along each axis. When the box is too small for that, the plan loses its coarsest levels (the
/// redundant coarse solve takes a larger level) until it fits; std::logic_error when even one
/// cell per rank does not.
Decomposition decompose(int nx, int ny, int ranks, std::vector<std::array<int, 3>>& plan) {
    int dims[2] = {0, 0};
    MPI_Dims_create(ranks, 2, dims);
    Decomposition d;
    d.px = dims[0], d.py = dims[1];
    if (ny > nx) std::swap(d.px, d.py);
    for (;;) {
        int bx = 1, by = 1;
        for (const auto& f : plan) bx *= f[0], by *= f[1];
        const int nbx = (nx + bx - 1) / bx, nby = (ny + by - 1) / by;
        if (nbx >= d.px && nby >= d.py) {
            d.xStart.resize(size_t(d.px) + 1);
            d.yStart.resize(size_t(d.py) + 1);
            for (int r = 0; r <= d.px; ++r)
                d.xStart[size_t(r)] = r == d.px ? nx : bx * int(long(r) * nbx / d.px);
            for (int r = 0; r <= d.py; ++r)
                d.yStart[size_t(r)] = r == d.py ? ny : by * int(long(r) * nby / d.py);
            d.levels = int(plan.size()) + 1;
            return d;
        }
        if (plan.empty())
            throw std::logic_error("DistributedPoissonSolver: a " + std::to_string(nx) + " x " +
                                   std::to_string(ny) + " plane cannot be split into " +
                                   std::to_string(d.px) + " x " + std::to_string(d.py) + " ranks");
        plan.pop_back();
    }
}

}  // namespace

struct DistributedPoissonSolver::Impl {
    MPI_Comm comm = MPI_COMM_NULL;
    int rank = 0, size = 1, rx = 0, ry = 0;
    int gnx = 0, gny = 0, gnz = 0;
    Decomposition dec;
    DM da = nullptr;
    mg::SubdomainShape shape;
    std::vector<Level> levels;
    /// Per level: every rank's first cell along x (px + 1 entries) and along y, at that level.
    std::vector<std::vector<int>> levelX, levelY;
    /// Per level: the halo (leaves: this rank's interface ghosts; roots: the owners' cells) and
    /// the ghost cells it writes.
    std::vector<PetscSF> halos;
    std::vector<std::vector<PetscInt>> ghostCells;
    // PCG vectors on level 0 (padded), as sim's solver: x, r, z, p, q (q doubles as scratch).
    std::vector<double> xs, rs, zs, ps, qs;
    size_t activeCells = 0;  // over all ranks
    double setupSeconds = 0;
    int sweeps = 2;
    // The coarsest level as a PETSc system.
    Mat coarseA = nullptr;
    Vec coarseB = nullptr, coarseX = nullptr;
    KSP coarseKsp = nullptr;
    DistributedSolveStats stats;

    ~Impl() {
        for (PetscSF& sf : halos) PetscSFDestroy(&sf);
        if (coarseKsp) KSPDestroy(&coarseKsp);
        if (coarseA) MatDestroy(&coarseA);
        if (coarseB) VecDestroy(&coarseB);
        if (coarseX) VecDestroy(&coarseX);
        if (da) DMDestroy(&da);
    }

    int rankOf(int ix, int iy) const { return ix + dec.px * iy; }
    int levelNx(size_t l, int ix) const {
        return levelX[l][size_t(ix) + 1] - levelX[l][size_t(ix)];
    }
    int levelNy(size_t l, int iy) const {
        return levelY[l][size_t(iy) + 1] - levelY[l][size_t(iy)];
    }

    // --- communication ---------------------------------------------------------------------

    double allreduce(double v, MPI_Op op) {
        const auto t0 = Clock::now();
        double out = 0;
        MPI_Allreduce(&v, &out, 1, MPI_DOUBLE, op, comm);
        stats.reduceSeconds += secondsSince(t0);
        return out;
    }

    /// Ghosts of v on level l := the neighbours' current values.
    void exchange(size_t l, double* v) {
        if (ghostCells[l].empty()) return;
        const auto t0 = Clock::now();
        petscCheck(PetscSFBcastBegin(halos[l], MPI_DOUBLE, v, v, MPI_REPLACE), "PetscSFBcastBegin");
        petscCheck(PetscSFBcastEnd(halos[l], MPI_DOUBLE, v, v, MPI_REPLACE), "PetscSFBcastEnd");
        stats.haloSeconds += secondsSince(t0);
        stats.haloBytes += double(ghostCells[l].size()) * sizeof(double);
        ++stats.exchanges;
    }

    /// Interface ghosts of v on level l := 0, as sim's kernels expect of a value never set: the
    /// block-local transfers read them with weight 0 only through their redirects, and a sweep
    /// from zero reads them as the zero start.
    void zeroGhosts(size_t l, double* v) const {
        for (PetscInt g : ghostCells[l]) v[g] = 0.0;
    }

    void buildHalo(size_t l) {
        const Level& L = levels[l];
        std::vector<PetscInt> leaves;
        std::vector<PetscSFNode> roots;
        auto add = [&](size_t leaf, int ix, int iy, int i, int j, int k) {
            const size_t sx = size_t(levelNx(l, ix)) + 2, sy = size_t(levelNy(l, iy)) + 2;
            leaves.push_back(PetscInt(leaf));
            roots.push_back({rankOf(ix, iy),
                             PetscInt(size_t(i + 1) + sx * (size_t(j + 1) + sy * size_t(k + 1)))});
        };
        for (int k = 0; k < L.nz; ++k) {
            for (int j = 0; j < L.ny; ++j) {
                if (rx > 0) add(L.at(-1, j, k), rx - 1, ry, levelNx(l, rx - 1) - 1, j, k);
                if (rx + 1 < dec.px) add(L.at(L.nx, j, k), rx + 1, ry, 0, j, k);
            }
            for (int i = 0; i < L.nx; ++i) {
                if (ry > 0) add(L.at(i, -1, k), rx, ry - 1, i, levelNy(l, ry - 1) - 1, k);
                if (ry + 1 < dec.py) add(L.at(i, L.ny, k), rx, ry + 1, i, 0, k);
            }
        }
        PetscSF sf = nullptr;
        petscCheck(PetscSFCreate(comm, &sf), "PetscSFCreate");
        petscCheck(PetscSFSetGraph(sf, PetscInt(L.total), PetscInt(leaves.size()), leaves.data(),
                                   PETSC_COPY_VALUES, roots.data(), PETSC_COPY_VALUES),
                   "PetscSFSetGraph");
        petscCheck(PetscSFSetUp(sf), "PetscSFSetUp");
        halos.push_back(sf);
        ghostCells.push_back(std::move(leaves));
    }

    /// r = b - A x again on the cells next to an interface, whose sweep formed it with the
    /// neighbours' values from before the sweep; x's ghosts must be current.
    void interfaceResidual(size_t l, const double* x, const double* b, double* r) const {
        const Level& L = levels[l];
        const auto& s = shape.interfaceSides;
        mg::forRows(L, [&](int j, int k) {
            const size_t p0 = L.at(0, j, k), nx = size_t(L.nx);
            if ((j == 0 && s[SIDE_YMIN]) || (j + 1 == L.ny && s[SIDE_YMAX])) {
                mg::residualSpan(L, x, b, r, p0, p0 + nx);
                return;
            }
            if (s[SIDE_XMIN]) mg::residualSpan(L, x, b, r, p0, p0 + 1);
            if (s[SIDE_XMAX] && nx > 1) mg::residualSpan(L, x, b, r, p0 + nx - 1, p0 + nx);
        });
    }

    // --- the coarsest level --------------------------------------------------------------------

    void buildCoarse() {
        const size_t l = levels.size() - 1;
        const Level& C = levels[l];
        const PetscInt m = PetscInt(C.cells());
        std::vector<PetscInt> counts(size_t(size), 0);
        MPI_Allgather(&m, 1, MPIU_INT, counts.data(), 1, MPIU_INT, comm);
        std::vector<PetscInt> offset(size_t(size) + 1, 0);
        for (int r = 0; r < size; ++r)
            offset[size_t(r) + 1] = offset[size_t(r)] + counts[size_t(r)];
        // The global number of cell (i, j, k) of rank (ix, iy)'s part of the coarsest level.
        auto global = [&](int ix, int iy, int i, int j, int k) {
            const PetscInt onx = levelNx(l, ix), ony = levelNy(l, iy);
            return offset[size_t(rankOf(ix, iy))] + i + onx * (j + ony * PetscInt(k));
        };
        petscCheck(MatCreateAIJ(comm, m, m, PETSC_DETERMINE, PETSC_DETERMINE, 7, nullptr, 4,
                                nullptr, &coarseA),
                   "MatCreateAIJ");
        for (int k = 0; k < C.nz; ++k)
            for (int j = 0; j < C.ny; ++j)
                for (int i = 0; i < C.nx; ++i) {
                    const size_t p = C.at(i, j, k);
                    const PetscInt row = global(rx, ry, i, j, k);
                    const double d = C.diag(p);
                    if (!(d > 0.0)) {  // not an unknown: x = 0 there
                        petscCheck(MatSetValue(coarseA, row, row, 1.0, INSERT_VALUES),
                                   "MatSetValue");
                        continue;
                    }
                    petscCheck(MatSetValue(coarseA, row, row, d, INSERT_VALUES), "MatSetValue");
                    const float w[6] = {C.wx[p],        C.wx[p + 1], C.wy[p],
                                        C.wy[p + C.sx], C.wz[p],     C.wz[p + C.sxy]};
                    const int di[6] = {-1, 1, 0, 0, 0, 0}, dj[6] = {0, 0, -1, 1, 0, 0},
                              dk[6] = {0, 0, 0, 0, -1, 1};
                    for (int f = 0; f < 6; ++f) {
                        if (w[f] == 0.f) continue;
                        int ii = i + di[f], jj = j + dj[f], ix = rx, iy = ry;
                        const int kk = k + dk[f];
                        if (kk < 0 || kk >= C.nz) continue;  // the box's bottom or top
                        if (ii < 0) {
                            if (rx == 0) continue;  // the box's side: in the diagonal only
                            ix = rx - 1, ii = levelNx(l, ix) - 1;
                        } else if (ii >= C.nx) {
                            if (rx + 1 == dec.px) continue;
                            ix = rx + 1, ii = 0;
                        }
                        if (jj < 0) {
                            if (ry == 0) continue;
                            iy = ry - 1, jj = levelNy(l, iy) - 1;
                        } else if (jj >= C.ny) {
                            if (ry + 1 == dec.py) continue;
                            iy = ry + 1, jj = 0;
                        }
                        petscCheck(MatSetValue(coarseA, row, global(ix, iy, ii, jj, kk),
                                               -double(w[f]), INSERT_VALUES),
                                   "MatSetValue");
                    }
                }
        petscCheck(MatAssemblyBegin(coarseA, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
        petscCheck(MatAssemblyEnd(coarseA, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
        petscCheck(MatCreateVecs(coarseA, &coarseX, &coarseB), "MatCreateVecs");
        petscCheck(KSPCreate(comm, &coarseKsp), "KSPCreate");
        petscCheck(KSPSetOperators(coarseKsp, coarseA, coarseA), "KSPSetOperators");
        petscCheck(KSPSetType(coarseKsp, KSPPREONLY), "KSPSetType");
        PC pc = nullptr;
        petscCheck(KSPGetPC(coarseKsp, &pc), "KSPGetPC");
        // Every rank gathers the level and factors it (PCREDUNDANT, LU inside): the level is
        // small (sim's COARSEST_MAX_CELLS per the whole box), so one exact solve per rank costs
        // less than solving it across ranks. A pure-Neumann component makes it singular: a
        // vanishing pivot is shifted, which pins that component as sim's Cholesky does.
        petscCheck(PCSetType(pc, PCREDUNDANT), "PCSetType(PCREDUNDANT)");
        KSP inner = nullptr;
        petscCheck(PCRedundantGetKSP(pc, &inner), "PCRedundantGetKSP");
        PC innerPc = nullptr;
        petscCheck(KSPGetPC(inner, &innerPc), "KSPGetPC");
        petscCheck(PCSetType(innerPc, PCLU), "PCSetType(PCLU)");
        petscCheck(PCFactorSetShiftType(innerPc, MAT_SHIFT_NONZERO), "PCFactorSetShiftType");
        petscCheck(KSPSetUp(coarseKsp), "KSPSetUp");
    }

    /// x = A^-1 b on the coarsest level (padded arrays; all of x is written, 0 off the unknowns).
    void coarseSolve(const double* b, double* x) {
        const auto t0 = Clock::now();
        const Level& C = levels.back();
        PetscScalar* a = nullptr;
        petscCheck(VecGetArray(coarseB, &a), "VecGetArray");
        for (int k = 0; k < C.nz; ++k)
            for (int j = 0; j < C.ny; ++j)
                for (int i = 0; i < C.nx; ++i) {
                    const size_t p = C.at(i, j, k);
                    a[C.cellIndex(i, j, k)] = C.active[p] ? b[p] : 0.0;
                }
        petscCheck(VecRestoreArray(coarseB, &a), "VecRestoreArray");
        petscCheck(KSPSolve(coarseKsp, coarseB, coarseX), "KSPSolve");
        const PetscScalar* s = nullptr;
        petscCheck(VecGetArrayRead(coarseX, &s), "VecGetArrayRead");
        std::fill(x, x + C.total, 0.0);
        for (int k = 0; k < C.nz; ++k)
            for (int j = 0; j < C.ny; ++j)
                for (int i = 0; i < C.nx; ++i) {
                    const size_t p = C.at(i, j, k);
                    if (C.active[p]) x[p] = s[C.cellIndex(i, j, k)];
                }
        petscCheck(VecRestoreArrayRead(coarseX, &s), "VecRestoreArrayRead");
        stats.coarseSeconds += secondsSince(t0);
    }

    // --- the V-cycle ---------------------------------------------------------------------------

    /// xf += P xc (the block-local prolongation: trilinear part, then the redirects).
    void prolong(const Level& C, const double* xc, const Level& F, double* xf) const {
        mg::forRows(F, [&](int j, int k) { mg::prolongRow(C, xc, F, xf, j, k, 0, F.nx); });
        tbb::parallel_for(0, F.nz, [&](int k) { mg::prolongRedirects(F, xc, xf, k); });
    }

    /// One symmetric V(n, n) cycle, x = M^-1 b on level l; dotOut: this rank's b . x.
    void vcycle(size_t l, const double* b, double* x, double* scratch, double* dotOut = nullptr) {
        Level& L = levels[l];
        if (l + 1 == levels.size()) {
            coarseSolve(b, x);
            if (dotOut) {
                *dotOut = mg::reduceRows(
                    L,
                    [&](int j, int k) {
                        double s = 0.0;
                        const size_t p0 = L.at(0, j, k);
                        for (size_t p = p0; p < p0 + size_t(L.nx); ++p) s += b[p] * x[p];
                        return s;
                    },
                    mg::SUM);
            }
            return;
        }
        const auto sweep = L.zLines ? mg::lineSweep : mg::fusedSweep;
        zeroGhosts(l, x);  // the first sweep starts from zero, ghosts included
        for (int s = 0; s < sweeps; ++s) {
            if (s > 0) exchange(l, x);
            sweep(L, x, b, /*first=*/0, /*fromZero=*/s == 0,
                  /*residualOut=*/s + 1 == sweeps ? scratch : nullptr, nullptr, nullptr, nullptr);
        }
        exchange(l, x);
        interfaceResidual(l, x, b, scratch);
        Level& C = levels[l + 1];
        mg::restrictTo(L, scratch, C);
        vcycle(l + 1, C.b.data(), C.x.data(), C.r.data());
        zeroGhosts(l + 1, C.x.data());  // the block-local prolongation reads them as 0
        prolong(C, C.x.data(), L, x);
        // Black-red post-sweeps: the adjoint of the pre-sweeps, rank by rank.
        for (int s = 0; s < sweeps; ++s) {
            exchange(l, x);
            sweep(L, x, b, /*first=*/1, /*fromZero=*/false, nullptr, nullptr, nullptr,
                  s + 1 == sweeps ? dotOut : nullptr);
        }
    }
};

DistributedPoissonSolver::DistributedPoissonSolver(const sim::PoissonSystem& sys, MPI_Comm comm)
    : mImpl(std::make_unique<Impl>()) {
    const auto t0 = Clock::now();
    sim::checkSystem(sys);
    Impl& m = *mImpl;
    m.comm = comm;
    MPI_Comm_rank(comm, &m.rank);
    MPI_Comm_size(comm, &m.size);
    m.gnx = sys.nx, m.gny = sys.ny, m.gnz = sys.nz;
    std::vector<std::array<int, 3>> plan = mg::coarseningPlan(sys.nx, sys.ny, sys.nz);
    m.dec = decompose(sys.nx, sys.ny, m.size, plan);
    const Decomposition& d = m.dec;

    // The DMDA owns the decomposition: our ranges given to it, its corners read back.
    std::vector<PetscInt> lx(size_t(d.px)), ly(size_t(d.py));
    for (int r = 0; r < d.px; ++r) lx[size_t(r)] = d.xStart[size_t(r) + 1] - d.xStart[size_t(r)];
    for (int r = 0; r < d.py; ++r) ly[size_t(r)] = d.yStart[size_t(r) + 1] - d.yStart[size_t(r)];
    petscCheck(DMDACreate2d(comm, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DMDA_STENCIL_STAR, sys.nx,
                            sys.ny, d.px, d.py, /*dof=*/1, /*s=*/1, lx.data(), ly.data(), &m.da),
               "DMDACreate2d");
    petscCheck(DMSetUp(m.da), "DMSetUp");
    PetscInt xs = 0, ys = 0, zs = 0, xm = 0, ym = 0, zm = 0;
    petscCheck(DMDAGetCorners(m.da, &xs, &ys, &zs, &xm, &ym, &zm), "DMDAGetCorners");
    m.rx = int(std::upper_bound(d.xStart.begin(), d.xStart.end(), int(xs)) - d.xStart.begin()) - 1;
    m.ry = int(std::upper_bound(d.yStart.begin(), d.yStart.end(), int(ys)) - d.yStart.begin()) - 1;
    if (m.rankOf(m.rx, m.ry) != m.rank || d.xStart[size_t(m.rx) + 1] != xs + xm ||
        d.yStart[size_t(m.ry) + 1] != ys + ym)
        throw std::logic_error("DistributedPoissonSolver: the DMDA placed rank " +
                               std::to_string(m.rank) + " off the planned decomposition");

    // This rank's part of the system: its columns, the faces around them.
    sim::PoissonSystem local;
    local.nx = int(xm), local.ny = int(ym), local.nz = sys.nz;
    local.sides = sys.sides;
    local.zLineSmoothing = sys.zLineSmoothing;
    local.weightX.resize(local.count(sim::Placement::FaceX));
    local.weightY.resize(local.count(sim::Placement::FaceY));
    local.weightZ.resize(local.count(sim::Placement::FaceZ));
    tbb::parallel_for(0, sys.nz + 1, [&](int k) {
        for (int j = 0; j <= local.ny; ++j)
            for (int i = 0; i <= local.nx; ++i) {
                const int gi = int(xs) + i, gj = int(ys) + j;
                if (k < sys.nz && j < local.ny)
                    local.weightX[local.faceXIndex(i, j, k)] =
                        sys.weightX[sys.faceXIndex(gi, gj, k)];
                if (k < sys.nz && i < local.nx)
                    local.weightY[local.faceYIndex(i, j, k)] =
                        sys.weightY[sys.faceYIndex(gi, gj, k)];
                if (i < local.nx && j < local.ny)
                    local.weightZ[local.faceZIndex(i, j, k)] =
                        sys.weightZ[sys.faceZIndex(gi, gj, k)];
            }
    });
    m.shape.plan = plan;
    m.shape.interfaceSides[SIDE_XMIN] = m.rx > 0;
    m.shape.interfaceSides[SIDE_XMAX] = m.rx + 1 < d.px;
    m.shape.interfaceSides[SIDE_YMIN] = m.ry > 0;
    m.shape.interfaceSides[SIDE_YMAX] = m.ry + 1 < d.py;
    const size_t localActive = mg::buildHierarchy(local, m.levels, &m.shape);
    m.activeCells = size_t(m.allreduce(double(localActive), MPI_SUM));
    m.stats = {};
    if (int(m.levels.size()) != d.levels)
        throw std::logic_error("DistributedPoissonSolver: rank " + std::to_string(m.rank) +
                               " built " + std::to_string(m.levels.size()) + " levels, planned " +
                               std::to_string(d.levels));

    // Every rank's ranges on every level: the starts divide exactly (they are multiples of the
    // coarsest spacing), the box's far end rounds up as the coarsening does.
    m.levelX.assign(m.levels.size(), d.xStart);
    m.levelY.assign(m.levels.size(), d.yStart);
    for (size_t l = 1; l < m.levels.size(); ++l) {
        const auto& f = plan[l - 1];
        for (auto* v : {&m.levelX, &m.levelY}) {
            const int c = v == &m.levelX ? f[0] : f[1];
            std::vector<int>& cur = (*v)[l];
            cur = (*v)[l - 1];
            for (size_t r = 0; r + 1 < cur.size(); ++r) cur[r] /= c;
            cur.back() = (cur.back() + c - 1) / c;
        }
    }
    for (size_t l = 0; l < m.levels.size(); ++l) {
        if (m.levels[l].nx != m.levelNx(l, m.rx) || m.levels[l].ny != m.levelNy(l, m.ry))
            throw std::logic_error("DistributedPoissonSolver: level " + std::to_string(l) +
                                   " of rank " + std::to_string(m.rank) +
                                   " does not match the decomposition");
        m.buildHalo(l);
    }
    m.buildCoarse();
    const size_t total = m.levels[0].total;
    for (auto* v : {&m.xs, &m.rs, &m.zs, &m.ps, &m.qs}) v->assign(total, 0.0);
    m.setupSeconds = secondsSince(t0);
}

DistributedPoissonSolver::~DistributedPoissonSolver() = default;

const Decomposition& DistributedPoissonSolver::decomposition() const { return mImpl->dec; }
const DistributedSolveStats& DistributedPoissonSolver::stats() const { return mImpl->stats; }
int DistributedPoissonSolver::rank() const { return mImpl->rank; }
int DistributedPoissonSolver::size() const { return mImpl->size; }

size_t DistributedPoissonSolver::memoryBytes() const {
    size_t bytes = 0;
    for (const Level& L : mImpl->levels)
        bytes += (L.wx.size() + L.wy.size() + L.wz.size()) * sizeof(float) +
                 (L.x.size() + L.b.size() + L.r.size()) * sizeof(double);
    return bytes + 5 * mImpl->xs.size() * sizeof(double);
}

sim::SolveReport DistributedPoissonSolver::solve(const std::vector<double>& rhs,
                                                 std::vector<double>& solution,
                                                 const sim::SolverSettings& settings) {
    const auto t0 = Clock::now();
    Impl& m = *mImpl;
    m.stats = {};
    Level& L = m.levels[0];
    const size_t n = size_t(m.gnx) * size_t(m.gny) * size_t(m.gnz);
    if (rhs.size() != n)
        throw std::logic_error("DistributedPoissonSolver::solve: rhs must have " +
                               std::to_string(n) + " entries, got " + std::to_string(rhs.size()));
    if (!solution.empty() && solution.size() != n)
        throw std::logic_error(
            "DistributedPoissonSolver::solve: solution (warm start) must be empty or have " +
            std::to_string(n) + " entries, got " + std::to_string(solution.size()));
    sim::checkSettings(settings);
    m.sweeps = settings.smoothingSweeps;
    const sim::GridIndex whole{m.gnx, m.gny, m.gnz};
    const int x0 = m.dec.xStart[size_t(m.rx)], y0 = m.dec.yStart[size_t(m.ry)];

    sim::SolveReport rep;
    rep.levels = settings.useMultigrid ? int(m.levels.size()) : 1;
    rep.setupSeconds = m.setupSeconds;
    double *x = m.xs.data(), *r = m.rs.data(), *z = m.zs.data(), *p = m.ps.data(), *q = m.qs.data();
    for (auto* v : {&m.xs, &m.rs, &m.zs, &m.ps, &m.qs}) std::fill(v->begin(), v->end(), 0.0);
    const bool warm = !solution.empty();
    mg::forRows(L, [&](int j, int k) {
        const size_t p0 = L.at(0, j, k), c0 = whole.cellIndex(x0, y0 + j, k);
        for (int i = 0; i < L.nx; ++i) {
            const bool active = L.active[p0 + i];
            r[p0 + i] = active ? rhs[c0 + i] : 0.0;
            x[p0 + i] = (active && warm) ? solution[c0 + i] : 0.0;
        }
    });
    // The whole solution on every rank: each sends its cells, in its own cell order.
    auto finish = [&](const char* why) {
        std::vector<double> mine(L.cells());
        mg::forRows(L, [&](int j, int k) {
            const size_t p0 = L.at(0, j, k), c0 = L.cellIndex(0, j, k);
            for (int i = 0; i < L.nx; ++i) mine[c0 + i] = L.active[p0 + i] ? x[p0 + i] : 0.0;
        });
        std::vector<int> counts(size_t(m.size)), displs(size_t(m.size) + 1, 0);
        for (int iy = 0; iy < m.dec.py; ++iy)
            for (int ix = 0; ix < m.dec.px; ++ix)
                counts[size_t(m.rankOf(ix, iy))] = m.levelNx(0, ix) * m.levelNy(0, iy) * m.gnz;
        for (int rr = 0; rr < m.size; ++rr)
            displs[size_t(rr) + 1] = displs[size_t(rr)] + counts[size_t(rr)];
        std::vector<double> all(n);
        MPI_Allgatherv(mine.data(), int(mine.size()), MPI_DOUBLE, all.data(), counts.data(),
                       displs.data(), MPI_DOUBLE, m.comm);
        solution.assign(n, 0.0);
        for (int iy = 0; iy < m.dec.py; ++iy)
            for (int ix = 0; ix < m.dec.px; ++ix) {
                const int onx = m.levelNx(0, ix), ony = m.levelNy(0, iy);
                const double* src = all.data() + displs[size_t(m.rankOf(ix, iy))];
                const int ox = m.dec.xStart[size_t(ix)], oy = m.dec.yStart[size_t(iy)];
                for (int k = 0; k < m.gnz; ++k)
                    for (int j = 0; j < ony; ++j)
                        std::copy(
                            src + size_t(onx) * (size_t(j) + size_t(ony) * size_t(k)),
                            src + size_t(onx) * (size_t(j) + 1 + size_t(ony) * size_t(k)),
                            solution.begin() + std::ptrdiff_t(whole.cellIndex(ox, oy + j, k)));
            }
        rep.message = why;
        rep.solveSeconds = secondsSince(t0);
        m.stats.solveSeconds = rep.solveSeconds;
        m.stats.iterations = rep.iterations;
    };
    // sim's CG driver, with this rank's exchanges and the sums and maxima over ranks.
    struct Ranks : mg::PcgCommunication {
        Impl& solver;
        explicit Ranks(Impl& impl) : solver(impl) {}
        void exchange(double* v) override { solver.exchange(0, v); }
        double sum(double v) override { return solver.allreduce(v, MPI_SUM); }
        double max(double v) override { return solver.allreduce(v, MPI_MAX); }
    } ranks(m);
    const char* why = mg::pcg(
        L, {x, r, z, p, q}, warm, settings,
        [&](double* rr, double* zz) {
            double rz = 0.0;
            m.vcycle(0, rr, zz, q, &rz);
            return rz;
        },
        [&](double* b) {
            mg::forRows(L, [&](int j, int k) {
                const size_t p0 = L.at(0, j, k), c0 = whole.cellIndex(x0, y0 + j, k);
                for (int i = 0; i < L.nx; ++i) b[p0 + i] = L.active[p0 + i] ? rhs[c0 + i] : 0.0;
            });
        },
        ranks, rep);
    finish(why);
    return rep;
}

}  // namespace gale::dist
