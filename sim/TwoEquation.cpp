/// \file TwoEquation.cpp
/// k and epsilon (or omega) on the cells: upwind advection and diffusion implicit along columns,
/// point-implicit across them, sinks implicit (sim/TwoEquation.h).
#include "sim/TwoEquation.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
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

TwoEquationTransport::TwoEquationTransport(
    TwoEquationModel model, const AirDomain& D, const std::vector<double>& groundCell,
    const std::vector<double>& wallHeight, const std::vector<double>& wallDistance, double z0,
    double d, double uStar, double nuMol, const std::vector<uint8_t>& okX,
    const std::vector<uint8_t>& okY, const std::vector<uint8_t>& okZ)
    : mModel(model),
      mDomain(D),
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
    const GridIndex G = D.layout();
    if (groundCell.size() != G.columnCount(Placement::Cell) ||
        wallHeight.size() != G.columnCount(Placement::Cell) ||
        wallDistance.size() != G.columnCount(Placement::Cell))
        throw std::logic_error("TwoEquationTransport: column arrays do not match the domain");
    if (!(uStar > 0.0) || !std::isfinite(uStar))
        throw std::logic_error("TwoEquationTransport: the friction velocity must be > 0");
    const int nx = D.nx(), ny = D.ny(), nz = D.nz();
    mWallK.assign(G.columnCount(Placement::Cell), -1);
    mK.assign(G.cellCount(), 0.0);
    mSecond.assign(G.cellCount(), 0.0);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const size_t col = G.column(Placement::Cell, i, j);
            for (int k = 0; k < nz; ++k) {
                if (!D.isAir(i, j, k)) continue;
                if (mWallK[col] < 0) mWallK[col] = k;
                const size_t c = G.cellIndex(i, j, k);
                mK[c] = inflow(0, sampleHeight_m(col, k));
                mSecond[c] = inflow(1, sampleHeight_m(col, k));
            }
        }
    if (mModel == TwoEquationModel::KOmegaSst) updateBlends(nullptr);
}

double TwoEquationTransport::sampleHeight_m(size_t column, int k) const {
    return k == mWallK[column] ? wallSampleHeight_m(column)
                               : mDomain.layout().zCentre_m(k) - mGround[column];
}

double TwoEquationTransport::inflow(int q, double height_m) const {
    if (q == 0) return keps::inflowTke_m2ps2(mUStar);
    const double eps = keps::inflowDissipation_m2ps3(mUStar, height_m, mZ0, mD);
    return mModel == TwoEquationModel::KEpsilon ? eps
                                                : eps / (keps::CMU * keps::inflowTke_m2ps2(mUStar));
}

double TwoEquationTransport::wallFrictionVelocity_mps(size_t column) const {
    const int k = mWallK[column];
    if (k < 0) return 0.0;
    const GridIndex G = mDomain.layout();
    const size_t c = size_t(column) + G.columnCount(Placement::Cell) * size_t(k);
    return CMU_QUARTER * std::sqrt(std::max(mK[c], 0.0));
}

std::vector<double> TwoEquationTransport::crossGradient() const {
    const AirDomain& D = mDomain;
    const GridIndex G = D.layout();
    const int nx = D.nx(), ny = D.ny(), nz = D.nz();
    const double h = D.voxelSize_m();
    std::vector<double> dot(G.cellCount(), 0.0);
    tbb::parallel_for(0, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (!D.isAir(i, j, k)) continue;
                const size_t c = G.cellIndex(i, j, k), col = G.column(Placement::Cell, i, j);
                // Central differences between the air neighbours, one-sided beside a wall or the
                // box, 0 with neither (per axis).
                auto along = [&](size_t a, size_t b, bool haveA, bool haveB, double dA,
                                 double dB) -> std::array<double, 2> {
                    if (!haveA && !haveB) return {0.0, 0.0};
                    const size_t lo = haveA ? a : c, hi = haveB ? b : c;
                    const double span = (haveA ? dA : 0.0) + (haveB ? dB : 0.0);
                    return {(mK[hi] - mK[lo]) / span, (mSecond[hi] - mSecond[lo]) / span};
                };
                const bool xm = i > 0 && D.isAir(i - 1, j, k),
                           xp = i + 1 < nx && D.isAir(i + 1, j, k);
                const bool ym = j > 0 && D.isAir(i, j - 1, k),
                           yp = j + 1 < ny && D.isAir(i, j + 1, k);
                const bool zm = k > mWallK[col], zp = k + 1 < nz;
                const auto gx = along(xm ? G.cellIndex(i - 1, j, k) : c,
                                      xp ? G.cellIndex(i + 1, j, k) : c, xm, xp, h, h);
                const auto gy = along(ym ? G.cellIndex(i, j - 1, k) : c,
                                      yp ? G.cellIndex(i, j + 1, k) : c, ym, yp, h, h);
                const double z = sampleHeight_m(col, k);
                const auto gz =
                    along(zm ? G.cellIndex(i, j, k - 1) : c, zp ? G.cellIndex(i, j, k + 1) : c, zm,
                          zp, zm ? z - sampleHeight_m(col, k - 1) : 0.0,
                          zp ? sampleHeight_m(col, k + 1) - z : 0.0);
                dot[c] = gx[0] * gx[1] + gy[0] * gy[1] + gz[0] * gz[1];
            }
    });
    return dot;
}

void TwoEquationTransport::updateBlends(const std::vector<double>* crossGradient) {
    const AirDomain& D = mDomain;
    const GridIndex G = D.layout();
    const int nx = D.nx(), ny = D.ny(), nz = D.nz();
    mF2.assign(G.cellCount(), 0.0);
    if (crossGradient || mF1.empty()) mF1.assign(G.cellCount(), 1.0);
    tbb::parallel_for(0, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (!D.isAir(i, j, k)) continue;
                const size_t c = G.cellIndex(i, j, k), col = G.column(Placement::Cell, i, j);
                const double y = std::max(sampleHeight_m(col, k), 2.0 * mZ0);
                const double kk = std::max(mK[c], keps::MIN_TKE);
                const double w = std::max(mSecond[c], keps::MIN_OMEGA);
                const double turbulent = std::sqrt(kk) / (sst::BETA_STAR * w * y);
                const double viscous = 500.0 * mNuMol / (y * y * w);
                const double arg2 = std::max(2.0 * turbulent, viscous);
                mF2[c] = std::tanh(arg2 * arg2);
                if (!crossGradient) continue;
                const double cd = std::max(2.0 * sst::SIGMA_W2 * (*crossGradient)[c] / w, 1e-20);
                const double arg1 =
                    std::min(std::max(turbulent, viscous), 4.0 * sst::SIGMA_W2 * kk / (cd * y * y));
                mF1[c] = std::tanh(arg1 * arg1 * arg1 * arg1);
            }
    });
}

void TwoEquationTransport::step(double dt, const std::vector<double>& U,
                                const std::vector<double>& V, const std::vector<double>& W,
                                const std::vector<double>& P, const std::vector<double>& limiter) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw std::logic_error("TwoEquationTransport::step: dt_s must be > 0");
    const AirDomain& D = mDomain;
    const GridLayout& L = D.layout();
    const GridIndex G = L;
    const int nx = D.nx(), ny = D.ny(), nz = D.nz();
    const double h = D.voxelSize_m(), kappa = surface::KAPPA;
    const bool sstModel = mModel == TwoEquationModel::KOmegaSst;
    if (P.size() != G.cellCount() || U.size() != mOkX.size() || V.size() != mOkY.size() ||
        W.size() != mOkZ.size() || (!limiter.empty() && limiter.size() != G.cellCount()))
        throw std::logic_error("TwoEquationTransport::step: arrays do not match the domain");

    // SST: the blends and the cross-diffusion from the state before the step.
    std::vector<double> cross;
    if (sstModel) {
        cross = crossGradient();
        updateBlends(&cross);
    }
    mNuT.assign(G.cellCount(), 0.0);
    tbb::parallel_for(0, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const size_t c = G.cellIndex(i, j, k);
                if (!D.isAir(i, j, k)) continue;
                mNuT[c] = eddyViscosity_m2ps(c) * (sstModel && !limiter.empty() ? limiter[c] : 1.0);
            }
    });

    std::vector<double> diffusivity(G.cellCount(), 0.0);  // nu_t / sigma (k-epsilon), sigma nu_t
    for (int q = 0; q < 2; ++q) {
        std::vector<double>& phi = q == 0 ? mK : mSecond;
        mOld = phi;
        for (size_t c = 0; c < diffusivity.size(); ++c) {
            if (!sstModel) {
                diffusivity[c] = mNuT[c] / (q == 0 ? keps::SIGMA_K : keps::SIGMA_E);
                continue;
            }
            const double f1 = mF1[c];
            diffusivity[c] = mNuT[c] * (q == 0 ? f1 * sst::SIGMA_K1 + (1.0 - f1) * sst::SIGMA_K2
                                               : f1 * sst::SIGMA_W1 + (1.0 - f1) * sst::SIGMA_W2);
        }
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
                        const double z = sampleHeight_m(col, k);
                        // Wall cell, epsilon or omega: the wall function's value (u*_k from the
                        // new k).
                        if (q == 1 && k == kb) {
                            const double uk = CMU_QUARTER * std::sqrt(mK[c]);
                            s.diag[e] = 1.0;
                            s.rhs[e] = sstModel ? uk / (keps::ROOT_CMU * kappa * z)
                                                : uk * uk * uk / (kappa * z);
                            continue;
                        }
                        const double dzc = k == kb ? mWallHeight[col] : L.dz_m(k);
                        const double vol = h * h * dzc;
                        double diag = vol / dt, rhs = vol / dt * mOld[c];
                        const double gammaC = diffusivity[c];
                        // A face of area A (m^2) with velocity un (m/s) out of the cell: upwind
                        // inflow and diffusion coefficients, m^3/s.
                        auto coefficient = [&](double A, double un, double gammaNb, double dist) {
                            const double inflowRate = std::max(-un * A, 0.0);
                            const double diff = (mNuMol + 0.5 * (gammaC + gammaNb)) * A / dist;
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
                                const double a = coefficient(A, un, gammaC, h);
                                diag += a, rhs += a * inflow(q, z);
                                return;
                            }
                            const size_t nb = G.cellIndex(ni, nj, k);
                            const double a = coefficient(A, un, diffusivity[nb], h);
                            diag += a, rhs += a * mOld[nb];
                        };
                        horizontal(0, -1), horizontal(0, +1), horizontal(1, -1), horizontal(1, +1);
                        // Below: the cell underneath (the wall cell's bottom is the ground).
                        if (k > kb) {
                            const double A = double(D.openFractionZ(i, j, k)) * h * h;
                            const double a = coefficient(A, -W[G.faceZIndex(i, j, k)],
                                                         diffusivity[c - G.cellIndex(0, 0, 1)],
                                                         L.centreGap_m(k));
                            diag += a, s.sub[e] = -a;
                        }
                        // Above: the cell overhead, or the top's Richards-Hoxey value.
                        {
                            const double A = double(D.openFractionZ(i, j, k + 1)) * h * h;
                            const double wn = W[G.faceZIndex(i, j, k + 1)];
                            if (k + 1 < nz) {
                                const double a =
                                    coefficient(A, wn, diffusivity[c + G.cellIndex(0, 0, 1)],
                                                L.centreGap_m(k + 1));
                                diag += a, s.sup[e] = -a;
                            } else {
                                const double a = coefficient(A, wn, gammaC, L.dz_m(k));
                                diag += a, rhs += a * inflow(q, z + L.dz_m(k));
                            }
                        }
                        // Sources and sinks, per unit volume.
                        if (q == 0) {
                            const double kOld = std::max(mOld[c], keps::MIN_TKE);
                            // k-epsilon: epsilon / k; SST: beta* omega, production limited to
                            // 10 beta* k omega (Menter, Kuntz and Langtry 2003).
                            double sinkRate =
                                sstModel ? sst::BETA_STAR * mSecond[c] : mSecond[c] / kOld;
                            double production =
                                sstModel ? std::min(P[c], 10.0 * sst::BETA_STAR * kOld * mSecond[c])
                                         : P[c];
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
                        } else if (!sstModel) {
                            const double kNew = std::max(mK[c], keps::MIN_TKE);
                            rhs += vol * keps::C1 * P[c] / kNew * mOld[c];
                            diag += vol * keps::C2 * mOld[c] / kNew;
                        } else {
                            const double f1 = mF1[c], wOld = std::max(mOld[c], keps::MIN_OMEGA);
                            const double gamma = f1 * sst::GAMMA1 + (1.0 - f1) * sst::GAMMA2;
                            const double beta = f1 * sst::BETA1 + (1.0 - f1) * sst::BETA2;
                            // gamma P / nu_t, with the production the k equation kept.
                            const double kNew = std::max(mK[c], keps::MIN_TKE);
                            const double produced =
                                std::min(P[c], 10.0 * sst::BETA_STAR * kNew * wOld);
                            rhs += vol * gamma * produced / std::max(mNuT[c], 1e-9);
                            diag += vol * beta * wOld;
                            // Cross-diffusion: a source where positive, an implicit sink else.
                            const double cd = 2.0 * (1.0 - f1) * sst::SIGMA_W2 * cross[c] / wOld;
                            if (cd > 0.0)
                                rhs += vol * cd;
                            else
                                diag += vol * (-cd) / wOld;
                        }
                        s.diag[e] = diag, s.rhs[e] = rhs;
                    }
                detail::solveTridiagonalRows(nx, nz, s.sub.data(), s.diag.data(), s.sup.data(),
                                             s.rhs.data());
                const double floor = q == 0     ? keps::MIN_TKE
                                     : sstModel ? keps::MIN_OMEGA
                                                : keps::MIN_DISSIPATION;
                for (int k = 0; k < nz; ++k)
                    for (int i = 0; i < nx; ++i) {
                        const size_t c = G.cellIndex(i, j, k);
                        phi[c] =
                            D.isAir(i, j, k) ? std::max(s.rhs[size_t(k) * nx + i], floor) : 0.0;
                    }
            }
        });
    }
    // F2 of the new state, for the caller's limiter before the next step.
    if (sstModel) updateBlends(nullptr);
}

}  // namespace gale::sim
