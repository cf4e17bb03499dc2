/// \file MomentumStressStep.cpp
/// One implicit step of the surface-layer stresses (sim/MomentumTurbulence.h): the wall law on
/// the terrain's tangent plane, and per row of columns the tridiagonal systems of the vertical
/// exchange with the horizontal neighbours point-implicit (Thomas algorithm).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "sim/Format.h"
#include "sim/MomentumTurbulence.h"
#include "sim/Tridiagonal.h"
#include "sim/TwoEquation.h"
#include "sim/WallLaw.h"

namespace gale::sim {
namespace {

using detail::num, detail::wallHeight_m, detail::WallSample, detail::wallSample;

/// Per-thread scratch of one row of columns: the systems' coefficients (level-major) and each
/// column's unknown range and wall coefficients.
struct RowScratch {
    std::vector<double> sub, diag, sup, rhs, wallH, wallC, wallI, wallE;
    std::vector<int> kl, kt;
    RowScratch(int n0, int n2)
        : sub(size_t(n0) * n2),
          diag(size_t(n0) * n2),
          sup(size_t(n0) * n2),
          rhs(size_t(n0) * n2),
          wallH(size_t(n0)),
          wallC(size_t(n0)),
          wallI(size_t(n0)),
          wallE(size_t(n0)),
          kl(size_t(n0)),
          kt(size_t(n0)) {}
};

}  // namespace

TurbulenceReport TurbulentStress::apply(double dt, std::vector<double>& U, std::vector<double>& V,
                                        std::vector<double>& W) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw std::logic_error("TurbulentStress::apply: dt_s must be > 0, got " + num(dt));
    if (U.size() != mOkX.size() || V.size() != mOkY.size() || W.size() != mOkZ.size())
        throw std::logic_error("TurbulentStress::apply: velocity arrays do not match the domain");
    const AirDomain& D = mDomain;
    const int nx = D.nx(), ny = D.ny(), nz = D.nz();
    const double h = D.voxelSize_m(), h2 = h * h;
    const double z0 = mSettings.roughness_m, d = mSettings.displacementHeight_m;
    TurbulenceReport rep;
    computeEddyViscosity(dt, U, V, W);
    for (double nu : mNuZ) rep.maxEddyViscosity_m2ps = std::max(rep.maxEddyViscosity_m2ps, nu);

    const GridLayout& L = D.layout();
    const GridIndex G = L;
    auto nuZ = [&](int i, int j, int k) { return mNuZ[G.faceZIndex(i, j, k)]; };
    auto nuCell = [&](int i, int j, int k) { return 0.5 * (nuZ(i, j, k) + nuZ(i, j, k + 1)); };

    // The wall law on sloping ground at the start of the step: each wall face's velocity split
    // into its part tangential to the terrain, U_t = U - (U.n) n with the unit normal
    // n = (-dh/dx, -dh/dy, 1) / q, q = sqrt(1 + |grad h|^2), from its own component and the
    // means of the four nearest faces of the other two (flat ground: U_t = (u, v, 0)).
    std::vector<WallSample> wallX(mLowX.size()), wallY(mLowY.size()), wallZ(mLowZ.size());
    auto wAt = [&](int i, int j, int k) { return W[G.faceZIndex(i, j, k)]; };
    tbb::parallel_for(0, ny + 1, [&](int j) {
        for (int i = 0; i <= nx; ++i) {
            const size_t colX = G.column(Placement::FaceX, i, j);
            if (j < ny && mLowX[colX] >= 0) {
                const int k = mLowX[colX], ia = std::max(i - 1, 0), ib = std::min(i, nx - 1);
                auto vAt = [&](int ii, int jj) { return V[G.faceYIndex(ii, jj, k)]; };
                const double v = 0.25 * (vAt(ia, j) + vAt(ia, j + 1) + vAt(ib, j) + vAt(ib, j + 1));
                const double w =
                    0.25 * (wAt(ia, j, k) + wAt(ia, j, k + 1) + wAt(ib, j, k) + wAt(ib, j, k + 1));
                wallX[colX] = wallSample(mSlopeX[colX], {U[G.faceXIndex(i, j, k)], v, w}, 0);
            }
            const size_t colY = G.column(Placement::FaceY, i, j);
            if (i < nx && mLowY[colY] >= 0) {
                const int k = mLowY[colY], ja = std::max(j - 1, 0), jb = std::min(j, ny - 1);
                auto uAt = [&](int ii, int jj) { return U[G.faceXIndex(ii, jj, k)]; };
                const double u = 0.25 * (uAt(i, ja) + uAt(i + 1, ja) + uAt(i, jb) + uAt(i + 1, jb));
                const double w =
                    0.25 * (wAt(i, ja, k) + wAt(i, ja, k + 1) + wAt(i, jb, k) + wAt(i, jb, k + 1));
                wallY[colY] = wallSample(mSlopeY[colY], {u, V[G.faceYIndex(i, j, k)], w}, 1);
            }
            // The lowest unknown w face: the top of its column's wall cell (kw - 1).
            const size_t colZ = G.column(Placement::FaceZ, i, j);
            if (i < nx && j < ny && mLowZ[colZ] >= 1) {
                const int kc = mLowZ[colZ] - 1;
                const double u = 0.5 * (U[G.faceXIndex(i, j, kc)] + U[G.faceXIndex(i + 1, j, kc)]);
                const double v = 0.5 * (V[G.faceYIndex(i, j, kc)] + V[G.faceYIndex(i, j + 1, kc)]);
                wallZ[colZ] = wallSample(mSlopeCell[colZ], {u, v, wAt(i, j, kc + 1)}, 2);
            }
        }
    });
    std::vector<double> frictionX(mLowX.size(), 0.0), frictionY(mLowY.size(), 0.0);

    std::vector<double>* comps[3] = {&U, &V, &W};
    const std::vector<uint8_t>* masks[3] = {&mOkX, &mOkY, &mOkZ};
    for (int c = 0; c < 3; ++c) {
        std::vector<double>& q = *comps[c];
        const std::vector<uint8_t>& ok = *masks[c];
        mOld = q;
        const Placement p = Placement(c);
        const auto n = G.dims(p);
        const int n0 = n[0], n1 = n[1], n2 = n[2];
        auto idx = [&G, p](int i, int j, int k) { return G.index(p, i, j, k); };
        const std::vector<int>& low = c == 0 ? mLowX : c == 1 ? mLowY : mLowZ;
        // nu_t at the face itself (horizontal exchanges) and on the edge below face k (vertical).
        auto cellsBeside = [&](int i, int j, int& ia, int& ja, int& ib, int& jb) {
            ia = c == 0 ? std::max(i - 1, 0) : i, ib = c == 0 ? std::min(i, nx - 1) : i;
            ja = c == 1 ? std::max(j - 1, 0) : j, jb = c == 1 ? std::min(j, ny - 1) : j;
        };
        // nu_t at every face of this component, once (each face is the neighbour of four).
        mNuFace.resize(q.size());
        tbb::parallel_for(0, n2, [&](int k) {
            for (int j = 0; j < n1; ++j)
                for (int i = 0; i < n0; ++i) {
                    if (!ok[idx(i, j, k)]) continue;
                    int ia, ja, ib, jb;
                    cellsBeside(i, j, ia, ja, ib, jb);
                    mNuFace[idx(i, j, k)] =
                        c == 2 ? nuZ(i, j, k) : 0.5 * (nuCell(ia, ja, k) + nuCell(ib, jb, k));
                }
        });
        auto nuFace = [&](int i, int j, int k) { return mNuFace[idx(i, j, k)]; };
        auto nuBelow = [&](int i, int j, int k) {
            if (c == 2) return nuCell(i, j, k - 1);
            int ia, ja, ib, jb;
            cellsBeside(i, j, ia, ja, ib, jb);
            return 0.5 * (nuZ(ia, ja, k) + nuZ(ib, jb, k));
        };
        // One row of columns (fixed j) at a time, all its tridiagonal systems eliminated together
        // level by level (k outer, i inner), so every array is read along its contiguous i. Faces
        // outside a column's unknowns are identity rows (they keep their value).
        tbb::parallel_for(tbb::blocked_range<int>(0, n1), [&](const tbb::blocked_range<int>& rows) {
            RowScratch s(n0, n2);
            for (int j = rows.begin(); j != rows.end(); ++j) {
                for (int i = 0; i < n0; ++i) {
                    const size_t col = G.column(p, i, j);
                    const int kl = low[col];
                    int kt = kl - 1;  // last unknown face of the column (none: kl - 1)
                    if (kl >= 0)
                        for (kt = kl; kt + 1 < n2 && ok[idx(i, j, kt + 1)];) ++kt;
                    s.kl[size_t(i)] = kl, s.kt[size_t(i)] = kt;
                    double wallH = h, wallC = 0.0;
                    const WallSample* ws = nullptr;
                    if (kl >= 0 && (c < 2 || kl >= 1)) {
                        // The wall face's sample: x, y faces own the open part of their layer;
                        // the lowest w face sits on its wall cell (kl - 1), whose open part it
                        // takes.
                        const int kw = c < 2 ? kl : kl - 1;
                        const double g = (c == 0 ? mGroundX : c == 1 ? mGroundY : mGroundCell)[col];
                        wallH = wallHeight_m(L, kw, g);
                        ws = &(c == 0 ? wallX : c == 1 ? wallY : wallZ)[col];
                        // The log law at the sample's distance to the surface along the normal.
                        const double zn = 0.5 * wallH / ws->q;
                        const double cw = surface::KAPPA / surface::logFactor(zn, z0, d);
                        // The velocity scale of the log law: from the tangential speed (mixing
                        // length), or from the wall cells' k beside the face (k-epsilon,
                        // u*_k = C_mu^(1/4) sqrt(k); Richards and Hoxey 1993).
                        double uScale = cw * ws->tangentialSpeed;
                        if (mTwoEquation) {
                            int ia = std::min(i, nx - 1), ja = std::min(j, ny - 1), ib = ia,
                                jb = ja;
                            if (c == 0) ia = std::max(i - 1, 0);
                            if (c == 1) ja = std::max(j - 1, 0);
                            uScale = 0.5 * (mTwoEquation->wallFrictionVelocity_mps(
                                                G.column(Placement::Cell, ia, ja)) +
                                            mTwoEquation->wallFrictionVelocity_mps(
                                                G.column(Placement::Cell, ib, jb)));
                        }
                        // tau_w = wallC * (U_t)_c over the wetted area q h^2 of the face's
                        // horizontal h^2, m/s (0: the free-slip diagnostic).
                        wallC = mSettings.wallStress ? cw * uScale * ws->q : 0.0;
                        // The reported u* skips slivers (a wall face under half its layer high
                        // sits below the log law's range and reports the clamp, not the flow).
                        if (c < 2 && wallH >= 0.5 * L.dz_m(kl) && mSettings.wallStress)
                            (c == 0 ? frictionX : frictionY)[col] = uScale;
                    }
                    s.wallI[size_t(i)] = ws ? ws->implicitShare : 1.0;
                    s.wallE[size_t(i)] = ws ? ws->explicitPart : 0.0;
                    s.wallH[size_t(i)] = wallH, s.wallC[size_t(i)] = wallC;
                }
                for (int k = 0; k < n2; ++k)
                    for (int i = 0; i < n0; ++i) {
                        const size_t f = idx(i, j, k), e0 = size_t(k) * n0 + size_t(i);
                        const int kl = s.kl[size_t(i)], kt = s.kt[size_t(i)];
                        s.sub[e0] = s.sup[e0] = 0.0;
                        if (k < kl || k > kt) {
                            s.diag[e0] = 1.0, s.rhs[e0] = mOld[f];
                            continue;
                        }
                        // Control-volume height: a layer for x and y (values at layer
                        // centres), centre to centre for w (values on the levels); the spacing
                        // of the vertical fluxes the other way round (Patankar 1980).
                        const double delta = (c < 2 && k == kl) ? s.wallH[size_t(i)]
                                             : c < 2            ? L.dz_m(k)
                                                                : L.centreGap_m(k);
                        auto spacing = [&](int kUpper) {
                            return c < 2 ? L.centreGap_m(kUpper) : L.dz_m(kUpper - 1);
                        };
                        const double a = dt / delta;
                        double diag = 1.0, rhs = mOld[f];
                        // Below: the wall function (x, y) or the edge to the face below.
                        if (k == kl) {
                            // tau_w = wallC (implicit share u' + explicit part): the component's
                            // share of U_t (docs/solver.md, "The wall law on slopes").
                            diag += a * s.wallC[size_t(i)] * s.wallI[size_t(i)];
                            rhs -= a * s.wallC[size_t(i)] * s.wallE[size_t(i)];
                        } else {
                            const double e = a * nuBelow(i, j, k) / spacing(k);
                            diag += e, s.sub[e0] = -e;
                        }
                        // Above: the edge to the face above, or the top stress.
                        if (k < kt) {
                            const double e = a * nuBelow(i, j, k + 1) / spacing(k + 1);
                            diag += e, s.sup[e0] = -e;
                        } else if (c < 2 && k == nz - 1) {
                            rhs += a * (c == 0 ? mTopX : mTopY)[G.column(p, i, j)];
                        }
                        // Horizontal neighbours, point-implicit.
                        const double nuSelf = nuFace(i, j, k);
                        auto nb = [&](int ii, int jj) {
                            if (ii < 0 || jj < 0 || ii >= n0 || jj >= n1) return;
                            const size_t g = idx(ii, jj, k);
                            if (!ok[g]) return;
                            const double e = dt * 0.5 * (nuSelf + nuFace(ii, jj, k)) / h2;
                            diag += e, rhs += e * mOld[g];
                        };
                        nb(i - 1, j), nb(i + 1, j), nb(i, j - 1), nb(i, j + 1);
                        if (c < 2) rhs += dt * (c == 0 ? mForceX : mForceY)[f];
                        s.diag[e0] = diag, s.rhs[e0] = rhs;
                    }
                detail::solveTridiagonalRows(n0, n2, s.sub.data(), s.diag.data(), s.sup.data(),
                                             s.rhs.data());
                for (int k = 0; k < n2; ++k)
                    for (int i = 0; i < n0; ++i) q[idx(i, j, k)] = s.rhs[size_t(k) * n0 + i];
            }
        });
    }
    for (double f : frictionX)
        rep.maxFrictionVelocity_mps = std::max(rep.maxFrictionVelocity_mps, f);
    for (double f : frictionY)
        rep.maxFrictionVelocity_mps = std::max(rep.maxFrictionVelocity_mps, f);
    return rep;
}

}  // namespace gale::sim
