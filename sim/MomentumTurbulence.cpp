/// \file MomentumTurbulence.cpp
/// Mixing-length eddy viscosity (Prandtl; Blackadar 1962) and log-law wall stress, one implicit
/// step per column (Thomas algorithm).
#include "sim/MomentumTurbulence.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/Format.h"

namespace gale::sim {
namespace {

using detail::num;

/// The control-volume height (m) of the wall face of a column whose lowest unknown face sits in
/// layer kl over ground at ground_m (world z): surface::wallControlHeight_m of the layer's open
/// height (the one definition the grass sampler shares; on stretched layers the first layer's
/// own thickness, not h). The wall sample sits at half of it (surface::wallSampleHeight_m).
double wallHeight_m(const GridLayout& L, int kl, double ground_m) {
    return surface::wallControlHeight_m(L.zFace_m(kl + 1) - ground_m, L.dz_m(kl));
}

/// Solves `count` tridiagonal systems at once, sub[e] x[e - count] + diag[e] x[e] + sup[e]
/// x[e + count] = rhs[e] with e = k count + i for system i in [0, count) and row k in [0, n), by
/// the Thomas algorithm (stable without pivoting for the diagonally dominant systems of the
/// stress step), level by level so that the inner loop runs along contiguous memory. Overwrites
/// sup and rhs; the solutions land in rhs.
void solveTridiagonalRows(int count, int n, const double* sub, const double* diag, double* sup,
                          double* rhs) {
    const size_t m = size_t(count);
    for (size_t i = 0; i < m; ++i) {
        rhs[i] /= diag[i];
        sup[i] /= diag[i];
    }
    for (size_t k = 1; k < size_t(n); ++k)
        for (size_t i = 0; i < m; ++i) {
            const size_t e = k * m + i;
            const double beta = diag[e] - sub[e] * sup[e - m];
            sup[e] /= beta;
            rhs[e] = (rhs[e] - sub[e] * rhs[e - m]) / beta;
        }
    for (size_t k = size_t(n) - 1; k-- > 0;)
        for (size_t i = 0; i < m; ++i) rhs[k * m + i] -= sup[k * m + i] * rhs[(k + 1) * m + i];
}

/// Per-thread scratch of one row of columns: the systems' coefficients (level-major) and each
/// column's unknown range and wall coefficients.
struct RowScratch {
    std::vector<double> sub, diag, sup, rhs, wallH, wallC;
    std::vector<int> kl, kt;
    RowScratch(int n0, int n2)
        : sub(size_t(n0) * n2),
          diag(size_t(n0) * n2),
          sup(size_t(n0) * n2),
          rhs(size_t(n0) * n2),
          wallH(size_t(n0)),
          wallC(size_t(n0)),
          kl(size_t(n0)),
          kt(size_t(n0)) {}
};

}  // namespace

const char* turbulenceClosureName(TurbulenceClosure c) {
    return c == TurbulenceClosure::KEpsilon ? "k_epsilon" : "mixing_length";
}

TurbulenceClosure turbulenceClosureFromName(const std::string& name) {
    for (TurbulenceClosure c : {TurbulenceClosure::MixingLength, TurbulenceClosure::KEpsilon})
        if (name == turbulenceClosureName(c)) return c;
    throw ParameterError("solver.turbulence", "\"" + name + "\"",
                         "one of \"mixing_length\", \"k_epsilon\"");
}

void validateWallAndMixing(double displacementHeight_m, double mixingLengthMax_m) {
    if (!(displacementHeight_m >= 0.0) || !std::isfinite(displacementHeight_m))
        throw ParameterError("solver.displacement_height_m", num(displacementHeight_m),
                             "must be >= 0 and finite");
    if (!(mixingLengthMax_m > 0.0) || !std::isfinite(mixingLengthMax_m))
        throw ParameterError("solver.mixing_length_max_m", num(mixingLengthMax_m),
                             "must be > 0 and finite");
}

void SurfaceLayerSettings::validate() const {
    if (!(roughness_m > 0.0) || !std::isfinite(roughness_m))
        throw ParameterError("wind.roughness_m", num(roughness_m), "must be > 0 m and finite");
    validateWallAndMixing(displacementHeight_m, mixingLengthMax_m);
    if (closure == TurbulenceClosure::KEpsilon)
        throw std::logic_error("SurfaceLayerSettings: the k-epsilon closure is not built yet");
    if (wallStress && !eddyViscosity)
        throw std::logic_error("SurfaceLayerSettings: the wall stress needs the eddy viscosity");
    if (balanced && !(eddyViscosity && wallStress))
        throw std::logic_error(
            "SurfaceLayerSettings: a balanced profile needs the eddy viscosity and the wall "
            "stress");
    if (balanced) {
        balanced->validate();
        if (!(balanced->referenceHeight_m > displacementHeight_m + roughness_m))
            throw ParameterError("wind.reference_height_m", num(balanced->referenceHeight_m),
                                 "must be above solver.displacement_height_m + wind.roughness_m (" +
                                     num(displacementHeight_m + roughness_m) + " m)");
    }
}

TurbulentStress::TurbulentStress(const AirDomain& D, const SurfaceLayerSettings& s, double nuMol,
                                 const std::vector<uint8_t>& okX, const std::vector<uint8_t>& okY,
                                 const std::vector<uint8_t>& okZ)
    : mDomain(D), mSettings(s), mNuMol(nuMol), mOkX(okX), mOkY(okY), mOkZ(okZ) {
    mSettings.validate();
    if (!(nuMol >= 0.0) || !std::isfinite(nuMol))
        throw ParameterError("unsteady.viscosity_m2ps", num(nuMol),
                             "must be >= 0 m^2/s and finite");
    const int nx = D.nx(), ny = D.ny(), nz = D.nz();
    const GridLayout& L = D.layout();
    const GridIndex G = L;
    if (okX.size() != G.count(Placement::FaceX) || okY.size() != G.count(Placement::FaceY) ||
        okZ.size() != G.count(Placement::FaceZ))
        throw std::logic_error("TurbulentStress: face masks do not match the domain");
    const double h = D.voxelSize_m(), z0 = s.roughness_m, d = s.displacementHeight_m;
    const auto o = D.wsMin_m();
    const Heightfield& T = D.terrain();

    mGroundCell.resize(G.columnCount(Placement::Cell));
    mGroundX.resize(G.columnCount(Placement::FaceX));
    mGroundY.resize(G.columnCount(Placement::FaceY));
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
            const double x = o[0] + i * h, y = o[1] + j * h;
            if (i < nx && j < ny)
                mGroundCell[G.column(Placement::Cell, i, j)] = T.sample(x + 0.5 * h, y + 0.5 * h);
            if (j < ny) mGroundX[G.column(Placement::FaceX, i, j)] = T.sample(x, y + 0.5 * h);
            if (i < nx) mGroundY[G.column(Placement::FaceY, i, j)] = T.sample(x + 0.5 * h, y);
        }

    // Lowest unknown face of each column (the masks are monotone in k over a heightfield).
    auto lowest = [&G](const std::vector<uint8_t>& ok, Placement p, std::vector<int>& low) {
        const auto n = G.dims(p);
        low.assign(G.columnCount(p), -1);
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i)
                for (int k = 0; k < n[2]; ++k)
                    if (ok[G.index(p, i, j, k)]) {
                        low[G.column(p, i, j)] = k;
                        break;
                    }
    };
    lowest(okX, Placement::FaceX, mLowX);
    lowest(okY, Placement::FaceY, mLowY);
    lowest(okZ, Placement::FaceZ, mLowZ);

    // l^2 on every z-face with air below (the top face included), from the cell column's ground,
    // between the centres of the layers below and above (half a layer each way; at the top face
    // the top layer's half mirrored).
    mL2Z.assign(G.count(Placement::FaceZ), 0.f);
    tbb::parallel_for(1, nz + 1, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (!D.isAir(i, j, k - 1) || !s.eddyViscosity) continue;
                const double zE = L.zFace_m(k) - mGroundCell[G.column(Placement::Cell, i, j)];
                const double below = 0.5 * L.dz_m(k - 1), above = 0.5 * L.dz_m(std::min(k, nz - 1));
                const double l = surface::discreteMixingLengthBetween_m(zE, below, above,
                                                                        s.mixingLengthMax_m, z0, d);
                mL2Z[G.faceZIndex(i, j, k)] = float(l * l);
            }
    });

    // Balance force and top stress of the ambient profile, per face of the x and y columns.
    mForceX.assign(okX.size(), 0.0), mForceY.assign(okY.size(), 0.0);
    mTopX.assign(G.columnCount(Placement::FaceX), 0.0);
    mTopY.assign(G.columnCount(Placement::FaceY), 0.0);
    if (!s.balanced) return;
    const AmbientWind& A = *s.balanced;
    const double uStar = surface::frictionVelocity_mps(A.speed_mps, A.referenceHeight_m, z0, d);
    const double dir = gale::radiansFromDegrees(A.direction_deg),
                 e[2] = {std::cos(dir), std::sin(dir)};
    for (int c = 0; c < 2; ++c) {
        const Placement p = Placement(c);
        const int n0 = G.dims(p)[0], n1 = G.dims(p)[1];
        const std::vector<int>& low = c == 0 ? mLowX : mLowY;
        const std::vector<double>& ground = c == 0 ? mGroundX : mGroundY;
        std::vector<double>& force = c == 0 ? mForceX : mForceY;
        std::vector<double>& top = c == 0 ? mTopX : mTopY;
        tbb::parallel_for(0, n1, [&](int j) {
            std::vector<double> tau(size_t(nz) + 1);
            for (int i = 0; i < n0; ++i) {
                const size_t col = G.column(p, i, j);
                const int kl = low[col];
                if (kl < 0) continue;
                // The two cell columns beside the face column (clamped at the box sides).
                const int ia = c == 0 ? std::max(i - 1, 0) : i,
                          ib = c == 0 ? std::min(i, nx - 1) : i;
                const int ja = c == 1 ? std::max(j - 1, 0) : j,
                          jb = c == 1 ? std::min(j, ny - 1) : j;
                auto l2Edge = [&](int k) {
                    return 0.5 * (double(mL2Z[G.faceZIndex(ia, ja, k)]) +
                                  double(mL2Z[G.faceZIndex(ib, jb, k)]));
                };
                const double g = ground[col];
                const double wallH = wallHeight_m(L, kl, g);
                auto profileHeight = [&](int k) {
                    return k == kl ? 0.5 * wallH : L.zCentre_m(k) - g;
                };
                auto U0 = [&](double z) { return surface::logLawSpeed_mps(uStar, z, z0, d); };
                // tau[k - kl]: stress through the bottom of face k; tau[nz - kl]: the top's.
                const double zp = profileHeight(kl), u0p = U0(zp);
                const double cw = surface::KAPPA / surface::logFactor(zp, z0, d);
                tau[0] = cw * cw * u0p * u0p;
                for (int k = kl + 1; k <= nz; ++k) {
                    const double zLo = profileHeight(k - 1),
                                 zHi = k < nz ? profileHeight(k) : zLo + L.centreGap_m(k);
                    const double grad = (U0(zHi) - U0(zLo)) / L.centreGap_m(k);
                    tau[size_t(k - kl)] = l2Edge(k) * grad * grad;
                }
                for (int k = kl; k < nz; ++k) {
                    const double delta = k == kl ? wallH : L.dz_m(k);
                    const double F = -(tau[size_t(k + 1 - kl)] - tau[size_t(k - kl)]) / delta;
                    force[G.index(p, i, j, k)] = F * e[c];
                }
                top[col] = tau[size_t(nz - kl)] * e[c];
            }
        });
    }
}

void TurbulentStress::computeEddyViscosity(const std::vector<double>& U,
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
    mNuZ.assign(G.count(Placement::FaceZ), 0.0);
    mShearZ.assign(G.count(Placement::FaceZ), 0.0);
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
                mNuZ[zi(i, j, k)] = mNuMol + double(mL2Z[zi(i, j, k)]) * mShearZ[zi(i, j, k)];
            }
    });
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
    computeEddyViscosity(U, V, W);
    for (double nu : mNuZ) rep.maxEddyViscosity_m2ps = std::max(rep.maxEddyViscosity_m2ps, nu);

    const GridLayout& L = D.layout();
    const GridIndex G = L;
    auto nuZ = [&](int i, int j, int k) { return mNuZ[G.faceZIndex(i, j, k)]; };
    auto nuCell = [&](int i, int j, int k) { return 0.5 * (nuZ(i, j, k) + nuZ(i, j, k + 1)); };

    // Horizontal speed of each wall face at the start of the step: its own component and the
    // mean of the four faces of the other component around it.
    std::vector<double> speedX(mLowX.size(), 0.0), speedY(mLowY.size(), 0.0);
    tbb::parallel_for(0, ny + 1, [&](int j) {
        for (int i = 0; i <= nx; ++i) {
            const size_t colX = G.column(Placement::FaceX, i, j);
            if (j < ny && mLowX[colX] >= 0) {
                const int k = mLowX[colX], ia = std::max(i - 1, 0), ib = std::min(i, nx - 1);
                auto vAt = [&](int ii, int jj) { return V[G.faceYIndex(ii, jj, k)]; };
                const double other =
                    0.25 * (vAt(ia, j) + vAt(ia, j + 1) + vAt(ib, j) + vAt(ib, j + 1));
                speedX[colX] = std::hypot(U[G.faceXIndex(i, j, k)], other);
            }
            const size_t colY = G.column(Placement::FaceY, i, j);
            if (i < nx && mLowY[colY] >= 0) {
                const int k = mLowY[colY], ja = std::max(j - 1, 0), jb = std::min(j, ny - 1);
                auto uAt = [&](int ii, int jj) { return U[G.faceXIndex(ii, jj, k)]; };
                const double other =
                    0.25 * (uAt(i, ja) + uAt(i + 1, ja) + uAt(i, jb) + uAt(i + 1, jb));
                speedY[colY] = std::hypot(V[G.faceYIndex(i, j, k)], other);
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
                    if (c < 2 && kl >= 0) {
                        const double g = (c == 0 ? mGroundX : mGroundY)[col];
                        wallH = wallHeight_m(L, kl, g);
                        const double speed = (c == 0 ? speedX : speedY)[col];
                        const double cw = surface::KAPPA / surface::logFactor(0.5 * wallH, z0, d);
                        // tau_w = wallC * u, m/s (0: the free-slip diagnostic)
                        wallC = mSettings.wallStress ? cw * cw * speed : 0.0;
                        // The reported u* skips slivers (a wall face under half its layer high
                        // sits below the log law's range and reports the clamp, not the flow).
                        if (wallH >= 0.5 * L.dz_m(kl) && mSettings.wallStress)
                            (c == 0 ? frictionX : frictionY)[col] = cw * speed;
                    }
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
                            diag += a * s.wallC[size_t(i)];
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
                solveTridiagonalRows(n0, n2, s.sub.data(), s.diag.data(), s.sup.data(),
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
