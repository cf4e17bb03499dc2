#pragma once
/// \internal
/// \file TwoEquation.h
/// The transported two-equation closures of the surface-layer stresses (TurbulenceClosure::
/// KEpsilon and KOmegaSst, sim/MomentumTurbulence.h): turbulent kinetic energy k and a second
/// variable, epsilon or omega, on the AirDomain's cells, advanced by one implicit step per call.
/// docs/solver.md, "The two-equation closures", has the method and its tests.
///
/// k-epsilon (Launder and Spalding 1974), kinematic, m^2/s^2 and m^2/s^3:
///   Dk/Dt   = div((nu + nu_t / sigma_k) grad k)   + P - epsilon
///   Deps/Dt = div((nu + nu_t / sigma_e) grad eps) + (C1 P - C2 epsilon) epsilon / k
///   nu_t    = C_mu k^2 / epsilon
/// Constants: C_mu = 0.09, C1 = 1.44, C2 = 1.92, sigma_k = 1 (Launder and Spalding 1974);
/// sigma_e = kappa^2 / ((C2 - C1) sqrt(C_mu)) = 1.167, the value for which Richards and Hoxey's
/// (1993) neutral profiles solve the epsilon equation exactly.
///
/// k-omega SST (Menter 1994; Menter, Kuntz and Langtry 2003), omega in 1/s:
///   Dk/Dt = div((nu + sigma_k nu_t) grad k) + min(P, 10 beta* k omega) - beta* k omega
///   Dw/Dt = div((nu + sigma_w nu_t) grad w) + gamma P / nu_t - beta omega^2
///           + 2 (1 - F1) sigma_w2 grad k . grad omega / omega
///   nu_t  = a1 k / max(a1 omega, S F2)
/// each of sigma_k, sigma_w, beta, gamma the blend F1 phi_1 + (1 - F1) phi_2 of the inner (k-omega)
/// and outer (k-epsilon) sets: sigma_k 0.85 / 1, sigma_w 0.5 / 0.856, beta 0.075 / 0.0828,
/// beta* = 0.09, a1 = 0.31, and gamma_i = beta_i / beta* - sigma_wi kappa^2 / sqrt(beta*) (Menter
/// 1994's definition, 0.553 / 0.440 with kappa = 0.41: both sets then keep the log law exact).
/// F1 = tanh(arg1^4), arg1 = min(max(sqrt(k) / (beta* omega y), 500 nu / (y^2 omega)),
/// 4 sigma_w2 k / (CD y^2)), CD = max(2 sigma_w2 grad k . grad omega / omega, 1e-20);
/// F2 = tanh(arg2^2), arg2 = max(2 sqrt(k) / (beta* omega y), 500 nu / (y^2 omega)); y the wall
/// distance, here the sample's height above its column's ground (the terrain below is the
/// nearest wall except beside a riser; the decision is in docs/solver.md). The limiter of nu_t
/// (Bradshaw's assumption: the shear stress a1 k in a boundary layer) is what lets SST separate
/// in an adverse pressure gradient where k-epsilon stays attached; the caller evaluates it on
/// the z-faces, where its strain is a sampled log profile's exact one, and passes each cell's
/// factor (TwoEquationTransport::step).
///
/// In both the production P = nu_t S Omega is Kato and Launder's (1993) form (S = sqrt(2 S_ij
/// S_ij), Omega = sqrt(2 W_ij W_ij)): in simple shear S = Omega and the log layer keeps its
/// production; at a windward stagnation point, where the strain is irrotational, no k is made
/// where the standard form nu_t S^2 makes far too much. The caller computes P (TurbulentStress,
/// from the strain it already takes on the z-faces).
///
/// Inflow and start: Richards and Hoxey (1993),
///   U = (u* / kappa) ln((z - d) / z0),  k = u*^2 / sqrt(C_mu),  epsilon = u*^3 / (kappa (z - d)),
///   omega = epsilon / (C_mu k) = u* / (sqrt(C_mu) kappa (z - d)),
/// z - d the height above the displacement plane of the local ground, u* the ambient wind's. With
/// the top's shear stress u*^2 (TurbulentStress) the profile is a solution of either model
/// without any body force.
///
/// Wall (the lowest air cell of each column): rough-wall functions with the velocity scale from k,
/// u*_k = C_mu^(1/4) k_p^(1/2), at the wall sample's distance z_p to the terrain along its normal
/// (the sample at the centroid of the cell's open part, half its open height above the ground, as
/// TurbulentStress places the wall faces' samples):
///   epsilon_p = u*_k^3 / (kappa z_p)  (omega_p = u*_k / (sqrt(C_mu) kappa z_p)),
///   P_p = tau_w u*_k / (kappa z_p),  tau_w = kappa u*_k |U_p| / ln((z_p - d) / z0),
/// so that in the log layer P_p = epsilon_p and tau_w = u*^2.
///
/// Discretisation: finite volumes on the cells, a cell's volume h^2 times its open height (the
/// wall cell) or its layer thickness, its faces' areas times their open fractions. Advection is
/// first-order upwind in advective form (the projected field's fluxes sum to zero), diffusion
/// central; both implicit along each column (one tridiagonal solve per column, Thomas) and
/// point-implicit across the horizontal neighbours (their old values); the sinks implicit,
/// linearised with the old values, SST's cross-diffusion a source where it is positive and an
/// implicit sink where it is negative. Every new value is then a positive weighted mean of old
/// ones plus a positive source, so k and epsilon (omega) stay positive at any step (an M-matrix),
/// and a fixed point solves the steady discrete equations whatever the pseudo-time step was. The
/// box's sides read the Richards and Hoxey profile where air enters and nothing where it leaves;
/// the top holds that profile (Dirichlet).

#include <cstdint>
#include <vector>

#include "sim/AirDomain.h"
#include "sim/SurfaceLayer.h"

namespace gale::sim {

namespace keps {
inline constexpr double CMU = 0.09;      ///< C_mu (beta* of the SST model)
inline constexpr double ROOT_CMU = 0.3;  ///< sqrt(C_mu)
inline constexpr double C1 = 1.44;
inline constexpr double C2 = 1.92;
inline constexpr double SIGMA_K = 1.0;
/// Richards and Hoxey's (1993) sigma_epsilon for the constants above: 1.167.
inline constexpr double SIGMA_E = surface::KAPPA * surface::KAPPA / ((C2 - C1) * ROOT_CMU);
/// Floors that keep k / epsilon (omega) defined in still air, m^2/s^2, m^2/s^3 and 1/s.
inline constexpr double MIN_TKE = 1e-10, MIN_DISSIPATION = 1e-14, MIN_OMEGA = 1e-8;

/// Richards and Hoxey's inflow k, m^2/s^2, for friction velocity u* (m/s).
inline double inflowTke_m2ps2(double uStar_mps) { return uStar_mps * uStar_mps / ROOT_CMU; }
/// Richards and Hoxey's inflow epsilon, m^2/s^3, at height_m above the ground (clamped as
/// surface::logFactor clamps: at least 2 z0 above the displacement plane).
inline double inflowDissipation_m2ps3(double uStar_mps, double height_m, double z0_m, double d_m) {
    const double z = std::max(height_m - d_m, 2.0 * z0_m);
    return uStar_mps * uStar_mps * uStar_mps / (surface::KAPPA * z);
}
}  // namespace keps

/// Menter's (1994) SST constants (the file comment).
namespace sst {
inline constexpr double BETA_STAR = keps::CMU;
inline constexpr double A1 = 0.31;
inline constexpr double SIGMA_K1 = 0.85, SIGMA_K2 = 1.0;
inline constexpr double SIGMA_W1 = 0.5, SIGMA_W2 = 0.856;
inline constexpr double BETA1 = 0.075, BETA2 = 0.0828;
/// gamma_i = beta_i / beta* - sigma_wi kappa^2 / sqrt(beta*): 0.553 and 0.440.
inline constexpr double GAMMA1 =
    BETA1 / BETA_STAR - SIGMA_W1 * surface::KAPPA * surface::KAPPA / keps::ROOT_CMU;
inline constexpr double GAMMA2 =
    BETA2 / BETA_STAR - SIGMA_W2 * surface::KAPPA * surface::KAPPA / keps::ROOT_CMU;
}  // namespace sst

/// Which two-equation model a TwoEquationTransport advances.
enum class TwoEquationModel { KEpsilon, KOmegaSst };

/// k and epsilon (or omega) of one domain. Keeps a reference to the domain, which must outlive it.
class TwoEquationTransport {
  public:
    /// groundCell_m: the terrain height (world z, m) under each cell column's centre (GridIndex's
    /// cell columns); wallHeight_m: per cell column, the open height (m) of its lowest air cell,
    /// as TurbulentStress clamps it; wallDistance_m: per cell column, the wall sample's distance
    /// to the terrain along its normal (half the open height over sqrt(1 + |grad h|^2)), where
    /// the wall functions are evaluated; okX/okY/okZ: the faces that are unknowns (between air
    /// cells or on the box). Starts from the Richards and Hoxey profile of uStar_mps (> 0).
    TwoEquationTransport(TwoEquationModel model, const AirDomain& domain,
                         const std::vector<double>& groundCell_m,
                         const std::vector<double>& wallHeight_m,
                         const std::vector<double>& wallDistance_m, double z0_m, double d_m,
                         double uStar_mps, double molecularViscosity_m2ps,
                         const std::vector<uint8_t>& okX, const std::vector<uint8_t>& okY,
                         const std::vector<uint8_t>& okZ);

    /// One step of dt_s (> 0) seconds through the frozen face velocities (m/s): production_m2ps3
    /// is P on every cell (m^2/s^3; ignored in wall cells, which take the wall function's).
    /// limiter: SST only, per cell the factor in (0, 1] by which the stress limiter scales
    /// k / omega (the caller's, from the z-faces; empty: 1 everywhere); ignored by k-epsilon.
    void step(double dt_s, const std::vector<double>& u, const std::vector<double>& v,
              const std::vector<double>& w, const std::vector<double>& production_m2ps3,
              const std::vector<double>& limiter = {});

    TwoEquationModel model() const { return mModel; }
    /// The eddy viscosity before SST's limiter (m^2/s) of a cell, 0 in solid cells:
    /// C_mu k^2 / epsilon or k / omega.
    double eddyViscosity_m2ps(size_t cell) const {
        if (!(mSecond[cell] > 0.0)) return 0.0;
        return mModel == TwoEquationModel::KEpsilon
                   ? keps::CMU * mK[cell] * mK[cell] / mSecond[cell]
                   : mK[cell] / mSecond[cell];
    }
    /// omega (1/s) of a cell: SST's own, epsilon / (C_mu k) for k-epsilon; 0 in solid cells.
    double specificDissipation_1ps(size_t cell) const {
        if (mModel == TwoEquationModel::KOmegaSst) return mSecond[cell];
        return mK[cell] > 0.0 ? mSecond[cell] / (keps::CMU * mK[cell]) : 0.0;
    }
    /// SST's F2 blend of a cell (1 in the log layer, 0 far from walls) as the last step left
    /// it; 1 for k-epsilon.
    double blendF2(size_t cell) const { return mF2.empty() ? 1.0 : mF2[cell]; }
    const std::vector<double>& tke_m2ps2() const { return mK; }  ///< k on cells
    /// The lowest air cell's k index of a cell column, -1 when the column has no air.
    int wallCell(size_t column) const { return mWallK[column]; }
    /// u*_k = C_mu^(1/4) sqrt(k) (m/s) of a column's wall cell, 0 without air.
    double wallFrictionVelocity_mps(size_t column) const;
    /// The wall sample's distance to the terrain along the normal z_p (m).
    double wallSampleHeight_m(size_t column) const { return mWallDistance[column]; }

  private:
    /// Height (m) above its column's ground of a cell's sample: the wall sample's distance in
    /// the wall cell, the centre's height above.
    double sampleHeight_m(size_t column, int k) const;
    /// Richards and Hoxey's value of k (q = 0) or of the second variable (q = 1) at a height.
    double inflow(int q, double height_m) const;
    /// grad k . grad omega (1/s^3) on the cells, SST's cross-diffusion.
    std::vector<double> crossGradient() const;
    /// SST: F2 of the current state, and F1 too when the cross gradient is given.
    void updateBlends(const std::vector<double>* crossGradient);

    TwoEquationModel mModel;
    const AirDomain& mDomain;
    std::vector<double> mGround, mWallHeight, mWallDistance;
    double mZ0 = 0.03, mD = 0.0, mUStar = 0.0, mNuMol = 0.0;
    std::vector<uint8_t> mOkX, mOkY, mOkZ;
    std::vector<int> mWallK;
    // k; epsilon or omega; nu_t of this step; SST's blends F1 and F2 on cells (empty otherwise)
    std::vector<double> mK, mSecond, mNuT, mOld, mF1, mF2;
};

}  // namespace gale::sim
