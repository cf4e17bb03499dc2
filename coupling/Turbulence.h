#pragma once
/// \file Turbulence.h
/// What a user reads of the momentum model's turbulence (docs/cli.md, "gale probe"; issue 24,
/// item 5): the turbulent kinetic energy k at a point, the turbulence intensity and a gust
/// estimate from it, in one place for the probe table, the rasters and any other reader.
///
/// k (m^2/s^2) comes from the closure (sim::MomentumWindResult::tke_m2ps2) on the cells, in
/// GridIndex's cell layout, 0 in solid cells. From it, with isotropic fluctuations (each velocity
/// component's variance 2k/3):
///
///   sigma = sqrt(2k / 3)                    the r.m.s. fluctuation of one component, m/s
///   I     = sigma / U                       turbulence intensity, U the mean speed at the point
///   U_gust = U + g sigma,  g = GUST_PEAK_FACTOR = 3.5
///
/// The peak factor g = 3.5 is the one behind the peak velocity pressure of EN 1991-1-4 (2005),
/// section 4.5, expression (4.8): q_p = (1 + 7 I_v) q_m, where 7 = 2 g because
/// (1 + g I)^2 ~ 1 + 2 g I; it stands for the expected largest short-gust excursion of a
/// 10-minute record (Davenport 1964 gives the peak factor of a Gaussian process,
/// sqrt(2 ln(nu T)) + 0.577 / sqrt(2 ln(nu T)), about 3-3.5 for such records). Isotropy
/// underestimates the along-wind sigma_u of the surface layer (about 2.4 u* measured, sqrt(2k/3)
/// = 1.49 u* for k = u*^2 / sqrt(C_mu)): the gust is the isotropic estimate, a lower figure than
/// the Eurocode's for the same k (docs/cli.md states both).
///
/// Near the ground: in the neutral log layer k is constant with height (k = u*^2 / sqrt(C_mu);
/// Richards and Hoxey 1993), so below the lowest air cell's centre of a column the sampler holds
/// that cell's value (no extrapolation towards the wall, where the closure has no value of its
/// own).

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/WindField.h"

namespace gale::coupling {

/// The peak factor g of the gust estimate U + g sqrt(2k/3) (EN 1991-1-4, expression 4.8; file
/// comment).
inline constexpr double GUST_PEAK_FACTOR = 3.5;
/// Below this mean speed (m/s) the turbulence intensity is undefined (NaN).
inline constexpr double CALM_SPEED_MPS = 1e-9;

/// sqrt(2k/3) (m/s) for k >= 0 (m^2/s^2); negative k (none from the closures) counts as 0.
inline double turbulentVelocity_mps(double tke_m2ps2) {
    return std::sqrt(2.0 * std::max(tke_m2ps2, 0.0) / 3.0);
}

/// Turbulence intensity sqrt(2k/3) / U (dimensionless) for mean speed speed_mps; NaN in calm air
/// (U <= CALM_SPEED_MPS).
inline double turbulenceIntensity(double tke_m2ps2, double speed_mps) {
    return speed_mps > CALM_SPEED_MPS ? turbulentVelocity_mps(tke_m2ps2) / speed_mps : std::nan("");
}

/// The gust estimate U + GUST_PEAK_FACTOR sqrt(2k/3) (m/s) for mean speed speed_mps.
inline double gustSpeed_mps(double speed_mps, double tke_m2ps2) {
    return speed_mps + GUST_PEAK_FACTOR * turbulentVelocity_mps(tke_m2ps2);
}

/// k (m^2/s^2) at world point (wsX_m, wsY_m, wsZ_m) (metres) from cell values tke_m2ps2 on
/// `geometry`'s cells (GridIndex cell layout; only the geometry's layout and air flags are read,
/// not its velocities): bilinear across the four cell columns around the point (the columns
/// without air left out and the weights of the rest renormalised), linear in z between the cell
/// centres of each column (stretched layers: at their own centres); below a column's lowest air
/// cell centre that cell's value (the log layer's constant k, file comment), above the top centre
/// the top cell's. Points outside the box are clamped to it horizontally. NaN when no column
/// around the point has air. Throws std::invalid_argument when tke_m2ps2 does not have one value
/// per cell.
double sampleTke_m2ps2(const sim::WindField& geometry, const std::vector<double>& tke_m2ps2,
                       double wsX_m, double wsY_m, double wsZ_m);

}  // namespace gale::coupling
