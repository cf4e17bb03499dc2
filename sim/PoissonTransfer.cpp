/// \file PoissonTransfer.cpp
/// The grid transfers of PoissonSolver's V-cycle (MGPCG after McAdams, Sifakis, Teran 2010):
/// cell-centred trilinear prolongation (fine centres at 1/4 and 3/4 of a coarse cell, weights
/// 3/4 and 1/4 per axis) and restriction as its transpose, so the V-cycle is symmetric. Weight
/// that would come from an inactive (rock) coarse cell or a Neumann ghost goes to the fine cell's
/// own parent instead (constant extrapolation, the discrete no-flux condition; the "redirects"),
/// with the transpose in restriction (docs/solver.md, "The linear solver").

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sim/PoissonDetail.h"

namespace gale::sim::multigrid {

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

// Which fine cells lose trilinear weight to inactive coarse cells or Neumann ghosts.
void buildRedirects(Level& F, const Level& C, const std::array<BoundaryKind, 6>& sides) {
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
                            const bool inside =
                                I >= 0 && J >= 0 && K >= 0 && I < C.nx && J < C.ny && K < C.nz;
                            if (inside ? !C.active[C.at(I, J, K)] : ghostKind(I, J, K) == 1)
                                lost += w;
                        }
                // A home that is itself inactive holds 0 and never receives a residual: the
                // weight is dropped in both directions (symmetric), rather than written into a
                // cell no level reads.
                const size_t home = C.at(ci[0], cj[0], ck[0]);
                if (lost > 0.0 && C.active[home]) out.push_back({p, home, lost});
            }
    });
    F.redirectSlab.assign(size_t(F.nz) + 1, 0);
    for (int k = 0; k < F.nz; ++k) {
        F.redirectSlab[k] = F.redirects.size();
        F.redirects.insert(F.redirects.end(), perSlab[k].begin(), perSlab[k].end());
    }
    F.redirectSlab[F.nz] = F.redirects.size();
    if (!F.zLines) return;
    // Plane index for the z-line sweep: a counting sort by j, stable, so each plane keeps the
    // list's (fine index) order.
    F.planeRedirectStart.assign(size_t(F.ny) + 1, 0);
    auto planeOf = [&](size_t fine) { return int((fine / size_t(F.sx)) % size_t(F.sy)) - 1; };
    for (const Level::Redirect& r : F.redirects)
        ++F.planeRedirectStart[size_t(planeOf(r.fine)) + 1];
    for (int j = 0; j < F.ny; ++j)
        F.planeRedirectStart[size_t(j) + 1] += F.planeRedirectStart[size_t(j)];
    F.planeRedirects.assign(F.redirects.size(), 0);
    std::vector<size_t> next(F.planeRedirectStart.begin(), F.planeRedirectStart.end() - 1);
    for (size_t n = 0; n < F.redirects.size(); ++n)
        F.planeRedirects[next[size_t(planeOf(F.redirects[n].fine))]++] = uint32_t(n);
}

// Coarse right-hand side = P^T (fine residual); zero in inactive coarse cells. Rows are
// combined first (y and z weights), then the x weights applied: ~5 loads per fine cell.
void restrictTo(const Level& F, const double* rf, Level& C) {
    double* bc = C.b.data();
    forRows(
        C,
        [&](int J, int K) {
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
        },
        F.cells());  // the coarse rows read every fine cell: parallel by the fine level's size
    for (const Level::Redirect& r : F.redirects) bc[r.home] += r.weight * rf[r.fine];
}

// x_fine += P x_coarse on fine row (j, k), trilinear part only (prolongRedirects adds the
// redirects). Inactive fine cells receive nothing: restriction never reads them (their residual
// is 0) and never writes inactive coarse cells, so a value left there would make P differ from
// the transpose of restriction on the next finer level and the V-cycle unsymmetric. With every
// inactive cell 0 on every level, the trilinear weight of an inactive coarse neighbour meets a 0
// and only its redirect to the home cell carries the correction, in both directions.
void prolongRow(const Level& C, const double* xc, const Level& F, double* xf, int j, int k, int i0,
                int i1) {
    if (i0 >= i1) return;
    // The coarse cells fine cells [i0, i1) read: the transfer is monotone in i.
    const int lo = std::min(F.tx.c0[i0], F.tx.c1[i0]),
              hi = std::max(F.tx.c0[i1 - 1], F.tx.c1[i1 - 1]);
    thread_local std::vector<double> t;
    if (t.size() < size_t(C.sx)) t.resize(size_t(C.sx));
    std::fill(t.begin() + (lo + 1), t.begin() + (hi + 2), 0.0);
    const int kc[2] = {F.tz.c0[k], F.tz.c1[k]};
    const double kw[2] = {F.tz.w0[k], F.tz.w1[k]};
    const int jc[2] = {F.ty.c0[j], F.ty.c1[j]};
    const double jw[2] = {F.ty.w0[j], F.ty.w1[j]};
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
            const double w = kw[a] * jw[b];
            if (w == 0.0) continue;
            const double* row = xc + C.at(0, jc[b], kc[a]);
            for (int I = lo; I <= hi; ++I) t[size_t(I + 1)] += w * row[I];
        }
    const size_t p0 = F.at(0, j, k);
    const uint8_t* active = F.active.data() + p0;
    for (int i = i0; i < i1; ++i)
        if (active[i])
            xf[p0 + i] += F.tx.w0[i] * t[F.tx.c0[i] + 1] + F.tx.w1[i] * t[F.tx.c1[i] + 1];
}

void prolongRedirects(const Level& F, const double* xc, double* xf, int k) {
    for (size_t n = F.redirectSlab[k]; n < F.redirectSlab[k + 1]; ++n) {
        const Level::Redirect& r = F.redirects[n];
        xf[r.fine] += r.weight * xc[r.home];
    }
}

}  // namespace gale::sim::multigrid
