#pragma once
/// \file SurfaceLayer.h
/// The neutral atmospheric surface layer, in one place for every model that needs it: the log
/// law, the wall function that turns a velocity near the ground into a surface stress, and the
/// mixing length of the eddy viscosity.
///
///   u(z) = (u* / kappa) ln((z - d) / z0)          (neutral log law; Stull 1988, section 9.7)
///   u*   = kappa U_p / ln((z_p - d) / z0)         (the same law solved for u* at a point p)
///   tau  = rho u*^2, along the tangential velocity (kinematic: tau / rho = u*^2, m^2/s^2)
///   l(z) = kappa (z - d) / (1 + kappa (z - d) / l_max)   (Blackadar 1962)
///
/// Heights are metres above the local ground (not world z); z0 is the aerodynamic roughness
/// length and d the displacement height (about 2/3 of a dense canopy's height; 0 for bare
/// ground). kappa = 0.41 (von Karman's constant, the value most surface-layer work uses).
///
/// Every function is finite for every finite input: at or below z0 + d the log law is clamped to
/// zero speed and the friction velocity to that of the lowest valid height, so a cell centre that
/// sits inside the roughness layer never produces Inf or NaN.

#include <algorithm>
#include <cmath>

namespace gale::sim::surface {

inline constexpr double KAPPA = 0.41;  ///< von Karman's constant

/// The lowest height above the displacement plane at which the log law is evaluated: one z0
/// above z0 + d (so ln(...) >= ln 2). Below it the functions clamp.
inline double lowestLogHeight_m(double z0_m, double d_m) { return d_m + 2.0 * z0_m; }

/// ln((z - d) / z0) for z above the clamp height, else ln 2. Requires z0 > 0.
inline double logFactor(double height_m, double z0_m, double d_m = 0.0) {
    const double zEff = std::max(height_m - d_m, 2.0 * z0_m);
    return std::log(zEff / z0_m);
}

/// Mean speed (m/s) at height_m above ground for friction velocity uStar_mps; 0 at or below
/// z0 + d.
inline double logLawSpeed_mps(double uStar_mps, double height_m, double z0_m, double d_m = 0.0) {
    if (height_m - d_m <= z0_m) return 0.0;
    return uStar_mps / KAPPA * std::log((height_m - d_m) / z0_m);
}

/// Friction velocity u* (m/s) from a speed U_p (m/s, >= 0) known at height z_p above ground:
/// the wall function of the first air cell.
inline double frictionVelocity_mps(double speed_mps, double height_m, double z0_m,
                                   double d_m = 0.0) {
    return KAPPA * speed_mps / logFactor(height_m, z0_m, d_m);
}

/// Speed at height z_a given the speed at z_b, both on one log profile (the ratio of two log
/// factors): how a value at a cell centre is carried down to grass height.
inline double logLawRescale_mps(double speedAtB_mps, double heightA_m, double heightB_m,
                                double z0_m, double d_m = 0.0) {
    if (heightA_m - d_m <= z0_m) return 0.0;
    return speedAtB_mps * logFactor(heightA_m, z0_m, d_m) / logFactor(heightB_m, z0_m, d_m);
}

/// Blackadar's mixing length (m) at height_m above ground, growing as kappa z near the ground and
/// levelling off at lMax_m aloft.
inline double mixingLength_m(double height_m, double lMax_m, double d_m = 0.0) {
    const double z = std::max(height_m - d_m, 0.0);
    return KAPPA * z / (1.0 + KAPPA * z / lMax_m);
}

/// Blackadar's (1962) asymptotic mixing length l_max = 0.00027 G / f for a geostrophic wind
/// G = 15 m/s at mid latitudes (Coriolis parameter f = 1e-4 1/s): 40.5 m. One constant for every
/// scene (no per-case tuning); the momentum model's default.
inline constexpr double BLACKADAR_MAX_MIXING_LENGTH_M = 0.00027 * 15.0 / 1.0e-4;

/// Blackadar's mixing length (m) on a face at edgeHeight_m above ground between two samples
/// below_m under it and above_m over it (at edgeHeight_m - below_m and edgeHeight_m + above_m;
/// unequal on stretched layers, where the centres of a thin and a thicker layer sit at different
/// distances from the face between them), with kappa z replaced by the length that makes a
/// sampled log profile carry exactly u*^2 through that face:
///   l_d = kappa (a + b) / [ln((z_e + b - d) / z0) - ln((z_e - a - d) / z0)]
///   (-> kappa (z_e - d) as a, b -> 0),
/// since the log law's difference quotient over the two samples is (u* / kappa) times that
/// bracket over a + b. Without it the first face above a wall cell carries (ln 3)^2 = 1.21 u*^2
/// and the profile drifts. Lengths clamp as logFactor does; 0 at or below the displacement plane.
inline double discreteMixingLengthBetween_m(double edgeHeight_m, double below_m, double above_m,
                                            double lMax_m, double z0_m, double d_m) {
    if (edgeHeight_m - d_m <= 0.0) return 0.0;
    const double dLog =
        logFactor(edgeHeight_m + above_m, z0_m, d_m) - logFactor(edgeHeight_m - below_m, z0_m, d_m);
    const double l =
        dLog > 1e-12 ? KAPPA * (below_m + above_m) / dLog : KAPPA * (edgeHeight_m - d_m);
    return l / (1.0 + l / lMax_m);
}

/// Where the wall function samples the first open layer of a column, one definition for the
/// solver's wall stress, its start field and balance profile (sim/MomentumTurbulence.cpp) and the
/// grass sampler (coupling/NearGround.cpp). openHeight_m is the open part of the layer above the
/// ground (the layer's top minus the ground height, m), layerThickness_m the layer's thickness
/// (h on cubic cells, dz_k on stretched layers). The control-volume height of the wall face is
/// the open height clamped to [MIN, MAX]_WALL_HEIGHT_CELLS layers: below the range a sliver of a
/// cut face would turn the wall drag into a division by almost nothing; above it a face far above
/// the ground (beside a cliff) would be treated as touching it.
inline constexpr double MIN_WALL_HEIGHT_CELLS = 0.05;
inline constexpr double MAX_WALL_HEIGHT_CELLS = 1.5;

/// The wall face's control-volume height (m): openHeight_m clamped as above.
inline double wallControlHeight_m(double openHeight_m, double layerThickness_m) {
    return std::clamp(openHeight_m, MIN_WALL_HEIGHT_CELLS * layerThickness_m,
                      MAX_WALL_HEIGHT_CELLS * layerThickness_m);
}

/// The height (m above the ground) of the wall sample: the centroid of the open part of the
/// first layer, half the control-volume height. A first layer cut at a fraction f of its
/// thickness dz (open height f dz) holds its velocity at f dz / 2, not at its centre
/// (f - 1/2) dz above the ground.
inline double wallSampleHeight_m(double openHeight_m, double layerThickness_m) {
    return 0.5 * wallControlHeight_m(openHeight_m, layerThickness_m);
}

/// The same with the two samples spacing_m apart, centred on the face (cubic cells).
inline double discreteMixingLength_m(double edgeHeight_m, double spacing_m, double lMax_m,
                                     double z0_m, double d_m = 0.0) {
    return discreteMixingLengthBetween_m(edgeHeight_m, 0.5 * spacing_m, 0.5 * spacing_m, lMax_m,
                                         z0_m, d_m);
}

}  // namespace gale::sim::surface
