/// \file KEpsilon.cpp
/// k and epsilon on the cells: upwind advection and diffusion implicit along columns, point-
/// implicit across them, sinks implicit (sim/KEpsilon.h).
#include "sim/KEpsilon.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/Tridiagonal.h"

namespace gale::sim {
namespace {

/// C_mu^(1/4), the ratio u*_k / sqrt(k).
const double CMU_QUARTER = std::sqrt(keps::ROOT_CMU);

/// Per-thread coefficients of one row of columns (level-major, as detail::solveTridiagonalRows
/// wants them).
struct Rows {
    std::vector<double> sub, diag, sup, rhs;
    Rows(int n0, int n2)
        : sub(size_t(n0) * n2), diag(size_t(n0) * n2), sup(size_t(n0) * n2), rhs(size_t(n0) * n2) {}
};

}  // namespace

KEpsilonTransport::KEpsilonTransport(const AirDomain& D, const std::vector<double>& groundCell,
                                     const std::vector<double>& wallHeight,
                                     const std::vector<double>& wallDistance, double z0, double d,
                                     double uStar, double nuMol, const std::vector<uint8_t>& okX,
                                     const std::vector<uint8_t>& okY,
                                     const std::vector<uint8_t>& okZ)
    : mDomain(D),
      mGround(groundCell),
      mWallHeight(wallHeight),
      mWallDistance(wallDistance),
      mZ0(z0),
      mD(d),
      mUStar(uStar),
      mNuMol(nuMol),
      mOkX(okX),
      mOkY(okY),
      mOkZ(okZ) {
    const GridLayout& L = D.layout();
    const GridIndex G = L;
    if (groundCell.size() != G.columnCount(Placement::Cell) ||
        wallHeight.size() != G.columnCount(Placement::Cell) ||
        wallDistance.size() != G.columnCount(Placement::Cell))
        throw std::logic_error("KEpsilonTransport: column arrays do not match the domain");
    if (!(uStar > 0.0) || !std::isfinite(uStar))
        throw std::logic_error("KEpsilonTransport: the friction velocity must be > 0");
    const int nx = D.nx(), ny = D.ny(), nz = D.nz();
    mWallK.assign(G.columnCount(Placement::Cell), -1);
    mK.assign(G.cellCount(), 0.0);
    mEps.assign(G.cellCount(), 0.0);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const size_t col = G.column(Placement::Cell, i, j);
            for (int k = 0; k < nz; ++k) {
                if (!D.isAir(i, j, k)) continue;
                if (mWallK[col] < 0) mWallK[col] = k;
                const size_t c = G.cellIndex(i, j, k);
                const double z =
                    k == mWallK[col] ? wallSampleHeight_m(col) : L.zCentre_m(k) - mGround[col];
                mK[c] = keps::inflowTke_m2ps2(uStar);
                mEps[c] = keps::inflowDissipation_m2ps3(uStar, z, z0, d);
            }
        }
}

double KEpsilonTransport::wallFrictionVelocity_mps(size_t column) const {
    const int k = mWallK[column];
    if (k < 0) return 0.0;
    const GridIndex G = mDomain.layout();
    const size_t c = size_t(column) + G.columnCount(Placement::Cell) * size_t(k);
    return CMU_QUARTER * std::sqrt(std::max(mK[c], 0.0));
}

void KEpsilonTransport::step(double dt, const std::vector<double>& U, const std::vector<double>& V,
                             const std::vector<double>& W, const std::vector<double>& P) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw std::logic_error("KEpsilonTransport::step: dt_s must be > 0");
    const AirDomain& D = mDomain;
    const GridLayout& L = D.layout();
    const GridIndex G = L;
    const int nx = D.nx(), ny = D.ny(), nz = D.nz();
    const double h = D.voxelSize_m(), kappa = surface::KAPPA;
    if (P.size() != G.cellCount() || U.size() != mOkX.size() || V.size() != mOkY.size() ||
        W.size() != mOkZ.size())
        throw std::logic_error("KEpsilonTransport::step: arrays do not match the domain");

    mNuT.assign(G.cellCount(), 0.0);
    tbb::parallel_for(0, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const size_t c = G.cellIndex(i, j, k);
                if (D.isAir(i, j, k)) mNuT[c] = eddyViscosity_m2ps(c);
            }
    });

    // Height above the ground of a cell's sample, and the Richards-Hoxey value of quantity q (0:
    // k, 1: epsilon) at a height.
    auto sampleHeight = [&](size_t col, int k) {
        return k == mWallK[col] ? wallSampleHeight_m(col) : L.zCentre_m(k) - mGround[col];
    };
    auto inflow = [&](int q, double height_m) {
        return q == 0 ? keps::inflowTke_m2ps2(mUStar)
                      : keps::inflowDissipation_m2ps3(mUStar, height_m, mZ0, mD);
    };

    for (int q = 0; q < 2; ++q) {
        std::vector<double>& phi = q == 0 ? mK : mEps;
        mOld = phi;
        const double sigma = q == 0 ? keps::SIGMA_K : keps::SIGMA_E;
        tbb::parallel_for(tbb::blocked_range<int>(0, ny), [&](const tbb::blocked_range<int>& rs) {
            Rows s(nx, nz);
            for (int j = rs.begin(); j != rs.end(); ++j) {
                for (int k = 0; k < nz; ++k)
                    for (int i = 0; i < nx; ++i) {
                        const size_t e = size_t(k) * nx + size_t(i), c = G.cellIndex(i, j, k);
                        const size_t col = G.column(Placement::Cell, i, j);
                        const int kb = mWallK[col];
                        s.sub[e] = s.sup[e] = 0.0;
                        if (kb < 0 || k < kb) {
                            s.diag[e] = 1.0, s.rhs[e] = mOld[c];
                            continue;
                        }
                        const double z = sampleHeight(col, k);
                        // Wall cell, epsilon: the wall function's value (u*_k from the new k).
                        if (q == 1 && k == kb) {
                            const double uk = CMU_QUARTER * std::sqrt(mK[c]);
                            s.diag[e] = 1.0, s.rhs[e] = uk * uk * uk / (kappa * z);
                            continue;
                        }
                        const double dzc = k == kb ? mWallHeight[col] : L.dz_m(k);
                        const double vol = h * h * dzc;
                        double diag = vol / dt, rhs = vol / dt * mOld[c];
                        const double nuC = mNuT[c];
                        // A face of area A (m^2) with velocity un (m/s) out of the cell: upwind
                        // inflow and diffusion coefficients, m^3/s.
                        auto coefficient = [&](double A, double un, double nuNb, double dist) {
                            const double inflowRate = std::max(-un * A, 0.0);
                            const double diff = (mNuMol + 0.5 * (nuC + nuNb) / sigma) * A / dist;
                            return inflowRate + diff;
                        };
                        // Horizontal faces, point-implicit.
                        auto horizontal = [&](int axis, int side) {
                            const int fi = axis == 0 ? i + (side > 0) : i;
                            const int fj = axis == 1 ? j + (side > 0) : j;
                            const float theta =
                                axis == 0 ? D.openFractionX(fi, fj, k) : D.openFractionY(fi, fj, k);
                            if (!(theta > 0.f)) return;
                            const double A = double(theta) * h * L.dz_m(k);
                            const double un = side * (axis == 0 ? U[G.faceXIndex(fi, fj, k)]
                                                                : V[G.faceYIndex(fi, fj, k)]);
                            const int ni = axis == 0 ? i + side : i, nj = axis == 1 ? j + side : j;
                            if (ni < 0 || nj < 0 || ni >= nx || nj >= ny) {
                                // Box side: the inflow profile where air enters, nothing else.
                                if (un >= 0.0) return;
                                const double a = coefficient(A, un, nuC, h);
                                diag += a, rhs += a * inflow(q, z);
                                return;
                            }
                            const size_t nb = G.cellIndex(ni, nj, k);
                            const double a = coefficient(A, un, mNuT[nb], h);
                            diag += a, rhs += a * mOld[nb];
                        };
                        horizontal(0, -1), horizontal(0, +1), horizontal(1, -1), horizontal(1, +1);
                        // Below: the cell underneath (the wall cell's bottom is the ground).
                        if (k > kb) {
                            const double A = double(D.openFractionZ(i, j, k)) * h * h;
                            const double a =
                                coefficient(A, -W[G.faceZIndex(i, j, k)],
                                            mNuT[c - G.cellIndex(0, 0, 1)], L.centreGap_m(k));
                            diag += a, s.sub[e] = -a;
                        }
                        // Above: the cell overhead, or the top's Richards-Hoxey value.
                        {
                            const double A = double(D.openFractionZ(i, j, k + 1)) * h * h;
                            const double wn = W[G.faceZIndex(i, j, k + 1)];
                            if (k + 1 < nz) {
                                const double a = coefficient(A, wn, mNuT[c + G.cellIndex(0, 0, 1)],
                                                             L.centreGap_m(k + 1));
                                diag += a, s.sup[e] = -a;
                            } else {
                                const double a = coefficient(A, wn, nuC, L.dz_m(k));
                                diag += a, rhs += a * inflow(q, z + L.dz_m(k));
                            }
                        }
                        // Sources and sinks, per unit volume.
                        if (q == 0) {
                            double production = P[c],
                                   sinkRate = mEps[c] / std::max(mOld[c], keps::MIN_TKE);
                            if (k == kb) {
                                // Wall function: P_p = u*_k^2 |U_p| / (z_p ln((z_p - d) / z0)),
                                // epsilon_p / k_p = C_mu^(3/4) sqrt(k_p) / (kappa z_p).
                                const double uk = CMU_QUARTER * std::sqrt(mOld[c]);
                                double su = 0.0, wu = 0.0, sv = 0.0, wv = 0.0;
                                for (int f = 0; f < 2; ++f) {
                                    const double tx = D.openFractionX(i + f, j, k);
                                    const double ty = D.openFractionY(i, j + f, k);
                                    su += tx * U[G.faceXIndex(i + f, j, k)], wu += tx;
                                    sv += ty * V[G.faceYIndex(i, j + f, k)], wv += ty;
                                }
                                // The speed along the wall: the normal component is the
                                // projection's (near zero), so |U| at the cell, w from its top.
                                const double wTop = W[G.faceZIndex(i, j, k + 1)];
                                const double uc = wu > 0.0 ? su / wu : 0.0,
                                             vc = wv > 0.0 ? sv / wv : 0.0;
                                const double speed = std::sqrt(uc * uc + vc * vc + wTop * wTop);
                                production = uk * uk * speed / (z * surface::logFactor(z, mZ0, mD));
                                sinkRate = CMU_QUARTER * CMU_QUARTER * CMU_QUARTER *
                                           std::sqrt(mOld[c]) / (kappa * z);
                            }
                            rhs += vol * production;
                            diag += vol * sinkRate;
                        } else {
                            const double kNew = std::max(mK[c], keps::MIN_TKE);
                            rhs += vol * keps::C1 * P[c] / kNew * mOld[c];
                            diag += vol * keps::C2 * mOld[c] / kNew;
                        }
                        s.diag[e] = diag, s.rhs[e] = rhs;
                    }
                detail::solveTridiagonalRows(nx, nz, s.sub.data(), s.diag.data(), s.sup.data(),
                                             s.rhs.data());
                const double floor = q == 0 ? keps::MIN_TKE : keps::MIN_DISSIPATION;
                for (int k = 0; k < nz; ++k)
                    for (int i = 0; i < nx; ++i) {
                        const size_t c = G.cellIndex(i, j, k);
                        phi[c] =
                            D.isAir(i, j, k) ? std::max(s.rhs[size_t(k) * nx + i], floor) : 0.0;
                    }
            }
        });
    }
}

}  // namespace gale::sim
