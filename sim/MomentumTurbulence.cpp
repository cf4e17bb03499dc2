/// \file MomentumTurbulence.cpp
/// Mixing-length eddy viscosity (Prandtl; Blackadar 1962) and log-law wall stress, one implicit
/// step per column (Thomas algorithm).
#include "sim/MomentumTurbulence.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/Format.h"
#include "sim/KEpsilon.h"
#include "sim/Tridiagonal.h"

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

/// Per-thread scratch of one row of columns: the systems' coefficients (level-major) and each
/// column's unknown range and wall coefficients.
/// A wall face's velocity against the terrain's tangent plane (the wall law on slopes): the
/// tangential speed |U_t| (m/s), the wetted-area factor q = sqrt(1 + |grad h|^2), and its own
/// component c of U_t written as implicitShare * U_c + explicitPart (the other components'
/// contribution, m/s).
struct WallSample {
    double tangentialSpeed = 0.0, q = 1.0, implicitShare = 1.0, explicitPart = 0.0;
};

/// U_t = U - (U.n) n for the unit normal n = (-g_x, -g_y, 1) / q of a surface with gradient g.
WallSample wallSample(const std::array<double, 2>& g, const std::array<double, 3>& U, int c) {
    const double n[3] = {-g[0], -g[1], 1.0};  // the normal times q
    const double q2 = 1.0 + g[0] * g[0] + g[1] * g[1];
    const double un = (U[0] * n[0] + U[1] * n[1] + U[2] * n[2]) / q2;  // (U.n) / q
    const double t[3] = {U[0] - un * n[0], U[1] - un * n[1], U[2] - un * n[2]};
    WallSample s;
    s.tangentialSpeed = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    s.q = std::sqrt(q2);
    s.implicitShare = 1.0 - n[c] * n[c] / q2;
    s.explicitPart = t[c] - U[size_t(c)] * s.implicitShare;
    return s;
}

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
    if (closure == TurbulenceClosure::KEpsilon && !(eddyViscosity && wallStress && balanced))
        throw std::logic_error(
            "SurfaceLayerSettings: the k-epsilon closure needs the eddy viscosity, the wall "
            "stress and the ambient profile (its inflow and top)");
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

    // The terrain's gradient (dh/dx, dh/dy) under each x- and y-face column and cell column, by
    // central differences of the bilinear surface half a cell either way: the wall law's normal.
    auto gradientAt = [&](double x, double y) {
        const double e = 0.5 * h;
        return std::array<double, 2>{(T.sample(x + e, y) - T.sample(x - e, y)) / (2.0 * e),
                                     (T.sample(x, y + e) - T.sample(x, y - e)) / (2.0 * e)};
    };
    mSlopeCell.resize(mGroundCell.size()), mSlopeX.resize(mGroundX.size());
    mSlopeY.resize(mGroundY.size());
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
            const double x = o[0] + i * h, y = o[1] + j * h;
            if (i < nx && j < ny)
                mSlopeCell[G.column(Placement::Cell, i, j)] = gradientAt(x + 0.5 * h, y + 0.5 * h);
            if (j < ny) mSlopeX[G.column(Placement::FaceX, i, j)] = gradientAt(x, y + 0.5 * h);
            if (i < nx) mSlopeY[G.column(Placement::FaceY, i, j)] = gradientAt(x + 0.5 * h, y);
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
                const double g = mGroundCell[G.column(Placement::Cell, i, j)];
                const double zE = L.zFace_m(k) - g;
                // Between the centres of the layers below and above. (The wall cell's sample at
                // its open part's centroid, as the wall function places it, moved the Jackson and
                // Hunt and Cao-Tamura figures of docs/validation.md: not kept until they are
                // measured again; docs/validation.md, "The k-epsilon closure against the mixing
                // length".)
                const double below = 0.5 * L.dz_m(k - 1);
                const double above = 0.5 * L.dz_m(std::min(k, nz - 1));
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
    if (s.closure == TurbulenceClosure::KEpsilon) {
        setUpKEpsilon(uStar, e[0], e[1]);
        return;
    }
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

TurbulentStress::~TurbulentStress() = default;

void TurbulentStress::setUpKEpsilon(double uStar, double ex, double ey) {
    const AirDomain& D = mDomain;
    const int nx = D.nx(), ny = D.ny(), nz = D.nz();
    const GridLayout& L = D.layout();
    const GridIndex G = L;
    const double z0 = mSettings.roughness_m, d = mSettings.displacementHeight_m;
    // The wall cell of each cell column and its open height (the wall faces' clamp).
    std::vector<double> wallH(G.columnCount(Placement::Cell), 0.0);
    std::vector<int> wallK(G.columnCount(Placement::Cell), -1);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const size_t col = G.column(Placement::Cell, i, j);
            for (int k = 0; k < nz; ++k)
                if (D.isAir(i, j, k)) {
                    wallK[col] = k;
                    wallH[col] = wallHeight_m(L, k, mGroundCell[col]);
                    break;
                }
        }
    // Per z-face with air on both sides: the log-law correction of nu_t and the share of the
    // face's production that goes to the cell above (docs/solver.md, "The k-epsilon closure"):
    // with the samples at z- (the cell below: its centre, or the wall sample) and z+ (the centre
    // above), heights above the displacement plane, and the face at z_e,
    //   nu_t factor = (z+ - z-) / (z_e ln(z+ / z-))  (a sampled log profile then carries u*^2),
    //   upper share = ln(z+ / z_e) / ln(z+ / z-)      (the log profile's energy above the face).
    // Both tend to 1 and 1/2 a few cells above the ground.
    mLogCorrectionZ.assign(G.count(Placement::FaceZ), 1.f);
    mUpperShareZ.assign(G.count(Placement::FaceZ), 0.5f);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const size_t col = G.column(Placement::Cell, i, j);
            const int kb = wallK[col];
            if (kb < 0) continue;
            const double g = mGroundCell[col];
            auto above = [&](double height) { return std::max(height - d, 2.0 * z0); };
            for (int k = kb + 1; k < nz; ++k) {
                const double zm = above(k - 1 == kb ? 0.5 * wallH[col] : L.zCentre_m(k - 1) - g);
                const double zp = above(L.zCentre_m(k) - g), ze = above(L.zFace_m(k) - g);
                const double logRatio = std::log(zp / zm);
                if (!(logRatio > 1e-12) || !(ze > zm) || !(zp > ze)) continue;
                const size_t f = G.faceZIndex(i, j, k);
                mLogCorrectionZ[f] = float((zp - zm) / (ze * logRatio));
                mUpperShareZ[f] = float(std::log(zp / ze) / logRatio);
            }
        }
    std::vector<double> wallDistance(wallH.size());
    for (size_t col = 0; col < wallH.size(); ++col) {
        const auto& g = mSlopeCell[col];
        wallDistance[col] = 0.5 * wallH[col] / std::sqrt(1.0 + g[0] * g[0] + g[1] * g[1]);
    }
    mKEpsilon = std::make_unique<KEpsilonTransport>(D, mGroundCell, wallH, wallDistance, z0, d,
                                                    uStar, mNuMol, mOkX, mOkY, mOkZ);
    // Richards and Hoxey's top: the constant shear stress u*^2 along the wind; no body force.
    const double tau = uStar * uStar;
    for (size_t c = 0; c < mTopX.size(); ++c)
        if (mLowX[c] >= 0) mTopX[c] = tau * ex;
    for (size_t c = 0; c < mTopY.size(); ++c)
        if (mLowY[c] >= 0) mTopY[c] = tau * ey;
}

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
    mRotationH.assign(G.cellCount(), 0.0);
    mNuZ.assign(G.count(Placement::FaceZ), 0.0);
    mShearZ.assign(G.count(Placement::FaceZ), 0.0);
    mVorticityZ.assign(G.count(Placement::FaceZ), 0.0);
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
                mRotationH[zi(i, j, k)] = (dudy - dvdx) * (dudy - dvdx);
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
                const double w2 = (dudz - dwdx) * (dudz - dwdx) + (dvdz - dwdy) * (dvdz - dwdy) +
                                  0.5 * (mRotationH[zi(i, j, k - 1)] + mRotationH[zi(i, j, k)]);
                mShearZ[zi(i, j, k)] = std::sqrt(s2);
                mVorticityZ[zi(i, j, k)] = std::sqrt(w2);
                if (!mKEpsilon)
                    mNuZ[zi(i, j, k)] = mNuMol + double(mL2Z[zi(i, j, k)]) * mShearZ[zi(i, j, k)];
            }
    });
    if (mKEpsilon) kEpsilonStep(dt, U, V, W);
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
    if (mKEpsilon) {
        mTke = mKEpsilon->tke_m2ps2();
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

void TurbulentStress::faceEddyViscosityFromKEpsilon() {
    const AirDomain& D = mDomain;
    const int nx = D.nx(), ny = D.ny(), nz = D.nz();
    const GridIndex G = D.layout();
    tbb::parallel_for(1, nz, [&](int k) {
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (!D.isAir(i, j, k - 1)) continue;
                const size_t f = G.faceZIndex(i, j, k);
                const double nuT = 0.5 * (mKEpsilon->eddyViscosity_m2ps(G.cellIndex(i, j, k - 1)) +
                                          mKEpsilon->eddyViscosity_m2ps(G.cellIndex(i, j, k)));
                mNuZ[f] = mNuMol + nuT * double(mLogCorrectionZ[f]);
            }
    });
}

void TurbulentStress::kEpsilonStep(double dt, const std::vector<double>& U,
                                   const std::vector<double>& V, const std::vector<double>& W) {
    const AirDomain& D = mDomain;
    const int nx = D.nx(), ny = D.ny(), nz = D.nz();
    const GridLayout& L = D.layout();
    const GridIndex G = L;
    // Production on the z-faces from the state before the step, P_f = nu_t S Omega (Kato and
    // Launder 1993), shared between the two cells by the log profile's energy split; the top
    // cell takes its bottom face's rate for its upper half.
    faceEddyViscosityFromKEpsilon();
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
    mKEpsilon->step(dt, U, V, W, mProductionCell);
    faceEddyViscosityFromKEpsilon();
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
                        if (mKEpsilon) {
                            int ia = std::min(i, nx - 1), ja = std::min(j, ny - 1), ib = ia,
                                jb = ja;
                            if (c == 0) ia = std::max(i - 1, 0);
                            if (c == 1) ja = std::max(j - 1, 0);
                            uScale = 0.5 * (mKEpsilon->wallFrictionVelocity_mps(
                                                G.column(Placement::Cell, ia, ja)) +
                                            mKEpsilon->wallFrictionVelocity_mps(
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
