/// \file MomentumEddyViscosity.cpp
/// The eddy viscosity of each stress step (sim/MomentumTurbulence.h): the strain and vorticity
/// on the z-faces, then nu_t from Prandtl's mixing length or from the two-equation transport, and
/// the closure's k on the cells.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "sim/MomentumTurbulence.h"
#include "sim/TwoEquation.h"

namespace gale::sim {

void TurbulentStress::computeEddyViscosity(double dt, const std::vector<double>& U,
                                           const std::vector<double>& V,
                                           const std::vector<double>& W) {
    const AirDomain& D = mDomain;
    const int nx = D.nx(), ny = D.ny(), nz = D.nz();
    const double h = D.voxelSize_m();
    const GridLayout& L = D.layout();
    const GridIndex G = L;
    auto xi = [&G](int i, int j, int k) { return G.faceXIndex(i, j, k); };
    auto yi = [&G](int i, int j, int k) { return G.faceYIndex(i, j, k); };
    // Cells and z-faces share the first nx * ny * nz indices (the strain lives on cells).
    auto zi = [&G](int i, int j, int k) { return G.faceZIndex(i, j, k); };
    mStrainH.assign(G.cellCount(), 0.0);
    // The vorticity only feeds the two-equation production (Kato-Launder): the mixing length skips
    // it.
    const bool vorticity = mTwoEquation != nullptr;
    mRotationH.assign(vorticity ? G.cellCount() : 0, 0.0);
    mNuZ.assign(G.count(Placement::FaceZ), 0.0);
    mShearZ.assign(G.count(Placement::FaceZ), 0.0);
    mVorticityZ.assign(vorticity ? G.count(Placement::FaceZ) : 0, 0.0);
    // Cell-centred part of 2 S_ij S_ij without the vertical shears: 2 (du/dx^2 + dv/dy^2 + dw/dz^2)
    // + (du/dy + dv/dx)^2, central differences of cell-centred velocities across the cell.
    tbb::parallel_for(0, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (!D.isAir(i, j, k)) continue;
                const double dudx = (U[xi(i + 1, j, k)] - U[xi(i, j, k)]) / h;
                const double dvdy = (V[yi(i, j + 1, k)] - V[yi(i, j, k)]) / h;
                const double dwdz = (W[zi(i, j, k + 1)] - W[zi(i, j, k)]) / L.dz_m(k);
                const int jm = std::max(j - 1, 0), jp = std::min(j + 1, ny - 1);
                const int im = std::max(i - 1, 0), ip = std::min(i + 1, nx - 1);
                const double dudy = jp > jm ? 0.5 *
                                                  (U[xi(i, jp, k)] + U[xi(i + 1, jp, k)] -
                                                   U[xi(i, jm, k)] - U[xi(i + 1, jm, k)]) /
                                                  ((jp - jm) * h)
                                            : 0.0;
                const double dvdx = ip > im ? 0.5 *
                                                  (V[yi(ip, j, k)] + V[yi(ip, j + 1, k)] -
                                                   V[yi(im, j, k)] - V[yi(im, j + 1, k)]) /
                                                  ((ip - im) * h)
                                            : 0.0;
                mStrainH[zi(i, j, k)] =
                    2.0 * (dudx * dudx + dvdy * dvdy + dwdz * dwdz) + (dudy + dvdx) * (dudy + dvdx);
                if (vorticity) mRotationH[zi(i, j, k)] = (dudy - dvdx) * (dudy - dvdx);
            }
    });
    // nu_t = nu + l^2 |S| on z-faces between two air cells; the vertical shears S_xz, S_yz as
    // face differences there, over the distance between the two layers' centres.
    tbb::parallel_for(1, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (!D.isAir(i, j, k - 1)) continue;
                const double gap = L.centreGap_m(k);
                const double dudz = 0.5 *
                                    (U[xi(i, j, k)] - U[xi(i, j, k - 1)] + U[xi(i + 1, j, k)] -
                                     U[xi(i + 1, j, k - 1)]) /
                                    gap;
                const double dvdz = 0.5 *
                                    (V[yi(i, j, k)] - V[yi(i, j, k - 1)] + V[yi(i, j + 1, k)] -
                                     V[yi(i, j + 1, k - 1)]) /
                                    gap;
                const int im = std::max(i - 1, 0), ip = std::min(i + 1, nx - 1);
                const int jm = std::max(j - 1, 0), jp = std::min(j + 1, ny - 1);
                const double dwdx =
                    ip > im ? (W[zi(ip, j, k)] - W[zi(im, j, k)]) / ((ip - im) * h) : 0.0;
                const double dwdy =
                    jp > jm ? (W[zi(i, jp, k)] - W[zi(i, jm, k)]) / ((jp - jm) * h) : 0.0;
                const double s2 = (dudz + dwdx) * (dudz + dwdx) + (dvdz + dwdy) * (dvdz + dwdy) +
                                  0.5 * (mStrainH[zi(i, j, k - 1)] + mStrainH[zi(i, j, k)]);
                mShearZ[zi(i, j, k)] = std::sqrt(s2);
                if (vorticity) {
                    const double w2 = (dudz - dwdx) * (dudz - dwdx) +
                                      (dvdz - dwdy) * (dvdz - dwdy) +
                                      0.5 * (mRotationH[zi(i, j, k - 1)] + mRotationH[zi(i, j, k)]);
                    mVorticityZ[zi(i, j, k)] = std::sqrt(w2);
                }
                if (!mTwoEquation)
                    mNuZ[zi(i, j, k)] = mNuMol + double(mL2Z[zi(i, j, k)]) * mShearZ[zi(i, j, k)];
            }
    });
    if (mTwoEquation) twoEquationStep(dt, U, V, W);
    // The wall-level and top faces of each column take the value of their air neighbour (the
    // wall's stress is the wall function's; the top's is prescribed): they only enter the
    // cell-centred averages.
    tbb::parallel_for(0, ny, [&](int j) {
        for (int i = 0; i < nx; ++i) {
            int kb = -1;
            for (int k = 0; k < nz; ++k)
                if (D.isAir(i, j, k)) {
                    kb = k;
                    break;
                }
            if (kb < 0) continue;
            mNuZ[zi(i, j, kb)] = kb + 1 < nz ? mNuZ[zi(i, j, kb + 1)] : mNuMol;
            mNuZ[zi(i, j, nz)] = nz - 1 > kb ? mNuZ[zi(i, j, nz - 1)] : mNuZ[zi(i, j, kb)];
            mShearZ[zi(i, j, kb)] = kb + 1 < nz ? mShearZ[zi(i, j, kb + 1)] : 0.0;
            mShearZ[zi(i, j, nz)] = nz - 1 > kb ? mShearZ[zi(i, j, nz - 1)] : mShearZ[zi(i, j, kb)];
        }
    });
    if (mTwoEquation) {
        mTke = mTwoEquation->tke_m2ps2();
        return;
    }
    // Local-equilibrium k on the cells (turbulentKineticEnergy_m2ps2): the two z-faces' mean.
    mTke.assign(G.cellCount(), 0.0);
    const double rootCmu = std::sqrt(TKE_EQUILIBRIUM_CMU);
    tbb::parallel_for(0, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (!D.isAir(i, j, k)) continue;
                auto kz = [&](int kk) {
                    const size_t f = zi(i, j, kk);
                    return std::max(mNuZ[f] - mNuMol, 0.0) * mShearZ[f] / rootCmu;
                };
                mTke[zi(i, j, k)] = 0.5 * (kz(k) + kz(k + 1));
            }
    });
}

void TurbulentStress::faceEddyViscosityFromTransport() {
    const AirDomain& D = mDomain;
    const int nx = D.nx(), ny = D.ny(), nz = D.nz();
    const GridIndex G = D.layout();
    const TwoEquationTransport& T = *mTwoEquation;
    const bool limited = T.model() == TwoEquationModel::KOmegaSst;
    if (limited) mLimiterZ.assign(G.count(Placement::FaceZ), 1.0);
    tbb::parallel_for(1, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (!D.isAir(i, j, k - 1)) continue;
                const size_t f = G.faceZIndex(i, j, k);
                const size_t a = G.cellIndex(i, j, k - 1), b = G.cellIndex(i, j, k);
                const bool upper = D.isAir(i, j, k);
                const double correction = double(mLogCorrectionZ[f]);
                double nuT = 0.5 * (T.eddyViscosity_m2ps(a) + T.eddyViscosity_m2ps(b)) * correction;
                if (limited) {
                    // SST's limiter nu_t = a1 k / max(a1 omega, S F2) as the factor
                    // min(1, a1 omega / (S F2)) on k / omega, with the face's strain times the
                    // log-law correction: a sampled log profile's exact strain u* / (kappa z),
                    // where the limiter is inactive (a1 omega / S = 1.03 there).
                    const double omega =
                        upper ? 0.5 * (T.specificDissipation_1ps(a) + T.specificDissipation_1ps(b))
                              : T.specificDissipation_1ps(a);
                    const double f2 = upper ? 0.5 * (T.blendF2(a) + T.blendF2(b)) : T.blendF2(a);
                    const double strain = mShearZ[f] * correction * f2;
                    const double bound = sst::A1 * omega;
                    if (strain > bound) {
                        mLimiterZ[f] = bound / strain;
                        nuT *= mLimiterZ[f];
                    }
                }
                mNuZ[f] = mNuMol + nuT;
            }
    });
}

void TurbulentStress::twoEquationStep(double dt, const std::vector<double>& U,
                                      const std::vector<double>& V, const std::vector<double>& W) {
    const AirDomain& D = mDomain;
    const int nx = D.nx(), ny = D.ny(), nz = D.nz();
    const GridLayout& L = D.layout();
    const GridIndex G = L;
    // Production on the z-faces from the state before the step, P_f = nu_t S Omega (Kato and
    // Launder 1993), shared between the two cells by the log profile's energy split; the top
    // cell takes its bottom face's rate for its upper half.
    faceEddyViscosityFromTransport();
    mProductionZ.assign(G.count(Placement::FaceZ), 0.0);
    tbb::parallel_for(1, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (!D.isAir(i, j, k - 1)) continue;
                const size_t f = G.faceZIndex(i, j, k);
                mProductionZ[f] = std::max(mNuZ[f] - mNuMol, 0.0) * mShearZ[f] * mVorticityZ[f];
            }
    });
    mProductionCell.assign(G.cellCount(), 0.0);
    tbb::parallel_for(0, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (!D.isAir(i, j, k)) continue;
                const size_t below = G.faceZIndex(i, j, k), above = G.faceZIndex(i, j, k + 1);
                double energy = 0.0;  // m^3/s^3 per unit area
                if (k > 0 && D.isAir(i, j, k - 1))
                    energy += double(mUpperShareZ[below]) * mProductionZ[below] * L.centreGap_m(k);
                if (k + 1 < nz)
                    energy += (1.0 - double(mUpperShareZ[above])) * mProductionZ[above] *
                              L.centreGap_m(k + 1);
                else
                    energy += 0.5 * mProductionZ[below] * L.dz_m(k);
                mProductionCell[G.cellIndex(i, j, k)] = energy / L.dz_m(k);
            }
    });
    // SST: each cell's limiter, the mean of its z-faces' between air cells.
    mLimiterCell.clear();
    if (mTwoEquation->model() == TwoEquationModel::KOmegaSst) {
        mLimiterCell.assign(G.cellCount(), 1.0);
        tbb::parallel_for(0, nz, [&](int k) {
            for (int j = 0; j < ny; ++j)
                for (int i = 0; i < nx; ++i) {
                    if (!D.isAir(i, j, k)) continue;
                    double sum = 0.0;
                    int n = 0;
                    if (k > 0 && D.isAir(i, j, k - 1)) sum += mLimiterZ[G.faceZIndex(i, j, k)], ++n;
                    if (k + 1 < nz && D.isAir(i, j, k + 1))
                        sum += mLimiterZ[G.faceZIndex(i, j, k + 1)], ++n;
                    if (n > 0) mLimiterCell[G.cellIndex(i, j, k)] = sum / n;
                }
        });
    }
    mTwoEquation->step(dt, U, V, W, mProductionCell, mLimiterCell);
    faceEddyViscosityFromTransport();
}

}  // namespace gale::sim
