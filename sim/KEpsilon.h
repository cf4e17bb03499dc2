#pragma once
/// \internal
/// \file KEpsilon.h
/// The transported two-equation closure of the surface-layer stresses
/// (TurbulenceClosure::KEpsilon, sim/MomentumTurbulence.h): turbulent kinetic energy k and its
/// dissipation rate epsilon on the AirDomain's cells, advanced by one implicit step per call.
/// docs/solver.md, "The k-epsilon closure", has the method and its tests.
///
/// Model (Launder and Spalding 1974), kinematic, m^2/s^2 and m^2/s^3:
///   Dk/Dt   = div((nu + nu_t / sigma_k) grad k)   + P - epsilon
///   Deps/Dt = div((nu + nu_t / sigma_e) grad eps) + (C1 P - C2 epsilon) epsilon / k
///   nu_t    = C_mu k^2 / epsilon
/// with the production in Kato and Launder's (1993) form P = nu_t S Omega (S = sqrt(2 S_ij S_ij),
/// Omega = sqrt(2 W_ij W_ij)): in simple shear S = Omega and the log layer keeps its production;
/// at a windward stagnation point, where the strain is irrotational, no k is made where the
/// standard form nu_t S^2 makes far too much. The caller computes P (TurbulentStress, from the
/// strain it already takes on the z-faces).
/// Constants: C_mu = 0.09, C1 = 1.44, C2 = 1.92, sigma_k = 1 (Launder and Spalding 1974);
/// sigma_e = kappa^2 / ((C2 - C1) sqrt(C_mu)) = 1.167, the value for which Richards and Hoxey's
/// (1993) neutral profiles solve the epsilon equation exactly.
///
/// Inflow and start: Richards and Hoxey (1993),
///   U = (u* / kappa) ln((z - d) / z0),  k = u*^2 / sqrt(C_mu),  epsilon = u*^3 / (kappa (z - d)),
/// z - d the height above the displacement plane of the local ground, u* the ambient wind's. With
/// the top's shear stress u*^2 (TurbulentStress) the profile is a solution of the model without
/// any body force.
///
/// Wall (the lowest air cell of each column): rough-wall functions with the velocity scale from k,
/// u*_k = C_mu^(1/4) k_p^(1/2), at the wall sample's distance z_p to the terrain along its normal
/// (the sample at the centroid of the cell's open part, half its open height above the ground, as
/// TurbulentStress places the wall faces' samples):
///   epsilon_p = u*_k^3 / (kappa z_p),  P_p = tau_w u*_k / (kappa z_p),
///   tau_w = kappa u*_k |U_p| / ln((z_p - d) / z0),
/// so that in the log layer P_p = epsilon_p and tau_w = u*^2.
///
/// Discretisation: finite volumes on the cells, a cell's volume h^2 times its open height (the
/// wall cell) or its layer thickness, its faces' areas times their open fractions. Advection is
/// first-order upwind in advective form (the projected field's fluxes sum to zero), diffusion
/// central; both implicit along each column (one tridiagonal solve per column, Thomas) and
/// point-implicit across the horizontal neighbours (their old values); the sinks implicit,
/// linearised with the old epsilon / k. Every new value is then a positive weighted mean of old
/// ones plus a positive source, so k and epsilon stay positive at any step (an M-matrix), and a
/// fixed point solves the steady discrete equations whatever the pseudo-time step was. The box's
/// sides read the Richards and Hoxey profile where air enters and nothing where it leaves; the
/// top holds that profile (Dirichlet).

#include <cstdint>
#include <vector>

#include "sim/AirDomain.h"
#include "sim/SurfaceLayer.h"

namespace gale::sim {

namespace keps {
inline constexpr double CMU = 0.09;      ///< C_mu
inline constexpr double ROOT_CMU = 0.3;  ///< sqrt(C_mu)
inline constexpr double C1 = 1.44;
inline constexpr double C2 = 1.92;
inline constexpr double SIGMA_K = 1.0;
/// Richards and Hoxey's (1993) sigma_epsilon for the constants above: 1.167.
inline constexpr double SIGMA_E = surface::KAPPA * surface::KAPPA / ((C2 - C1) * ROOT_CMU);
/// Floors that keep k / epsilon defined in still air, m^2/s^2 and m^2/s^3.
inline constexpr double MIN_TKE = 1e-10, MIN_DISSIPATION = 1e-14;

/// Richards and Hoxey's inflow k, m^2/s^2, for friction velocity u* (m/s).
inline double inflowTke_m2ps2(double uStar_mps) { return uStar_mps * uStar_mps / ROOT_CMU; }
/// Richards and Hoxey's inflow epsilon, m^2/s^3, at height_m above the ground (clamped as
/// surface::logFactor clamps: at least 2 z0 above the displacement plane).
inline double inflowDissipation_m2ps3(double uStar_mps, double height_m, double z0_m, double d_m) {
    const double z = std::max(height_m - d_m, 2.0 * z0_m);
    return uStar_mps * uStar_mps * uStar_mps / (surface::KAPPA * z);
}
}  // namespace keps

/// k and epsilon of one domain. Keeps a reference to the domain, which must outlive it.
class KEpsilonTransport {
  public:
    /// groundCell_m: the terrain height (world z, m) under each cell column's centre (GridIndex's
    /// cell columns); wallHeight_m: per cell column, the open height (m) of its lowest air cell,
    /// as TurbulentStress clamps it; wallDistance_m: per cell column, the wall sample's distance
    /// to the terrain along its normal (half the open height over sqrt(1 + |grad h|^2)), where
    /// the wall functions are evaluated; okX/okY/okZ: the faces that are unknowns (between air
    /// cells or on the box). Starts from the Richards and Hoxey profile of uStar_mps (> 0).
    KEpsilonTransport(const AirDomain& domain, const std::vector<double>& groundCell_m,
                      const std::vector<double>& wallHeight_m,
                      const std::vector<double>& wallDistance_m, double z0_m, double d_m,
                      double uStar_mps, double molecularViscosity_m2ps,
                      const std::vector<uint8_t>& okX, const std::vector<uint8_t>& okY,
                      const std::vector<uint8_t>& okZ);

    /// One step of dt_s (> 0) seconds through the frozen face velocities (m/s): production_m2ps3
    /// is P on every cell (m^2/s^3; ignored in wall cells, which take the wall function's).
    void step(double dt_s, const std::vector<double>& u, const std::vector<double>& v,
              const std::vector<double>& w, const std::vector<double>& production_m2ps3);

    /// C_mu k^2 / epsilon (m^2/s) of a cell, 0 in solid cells.
    double eddyViscosity_m2ps(size_t cell) const {
        return mEps[cell] > 0.0 ? keps::CMU * mK[cell] * mK[cell] / mEps[cell] : 0.0;
    }
    const std::vector<double>& tke_m2ps2() const { return mK; }            ///< k on cells
    const std::vector<double>& dissipation_m2ps3() const { return mEps; }  ///< epsilon on cells
    /// The lowest air cell's k index of a cell column, -1 when the column has no air.
    int wallCell(size_t column) const { return mWallK[column]; }
    /// u*_k = C_mu^(1/4) sqrt(k) (m/s) of a column's wall cell, 0 without air.
    double wallFrictionVelocity_mps(size_t column) const;
    /// The wall sample's distance to the terrain along the normal z_p (m).
    double wallSampleHeight_m(size_t column) const { return mWallDistance[column]; }

  private:
    const AirDomain& mDomain;
    std::vector<double> mGround, mWallHeight, mWallDistance;
    double mZ0 = 0.03, mD = 0.0, mUStar = 0.0, mNuMol = 0.0;
    std::vector<uint8_t> mOkX, mOkY, mOkZ;
    std::vector<int> mWallK;
    std::vector<double> mK, mEps, mNuT, mOld;
};

}  // namespace gale::sim
