#pragma once
/// \file Flutter.h
/// Turbulent flutter of the grass (docs/render.md, "Flutter from the turbulence"): the amplitude,
/// radians, of the fast fluctuation the renderer adds to each vertex's tip tilt
/// (render::VertexWind::flutter_rad, shaders/shell.vert), from the turbulent kinetic energy k at
/// grass height. Zero in calm air, so shelter reads as stillness and a gust front as agitation.
///
/// The rule: isotropic turbulence has k = (3/2) sigma_u^2 (k = <u_i u_i> / 2, Pope 2000, section
/// 5.1), so the rms fluctuation of one velocity component is sigma_u = sqrt(2 k / 3). A blade is
/// bent by its drag, which goes with the square of the speed: with V = U + u', u' of variance
/// sigma_u^2, the fluctuation of V^2 about its mean has the rms sqrt(4 U^2 sigma_u^2 +
/// 2 sigma_u^4) (u' Gaussian). Measured in the drag at the bend speed (the drag that tilts the tip
/// by (pi/2) I with I = 1, Bakay et al. 2002, section 3; render/Bend.h), the flutter amplitude is
/// (pi/2) sqrt(4 U^2 sigma_u^2 + 2 sigma_u^4) / bend_speed^2, capped at MAX_FLUTTER_RAD. The
/// same turbulence shakes a blade in a strong mean wind more than one in a weak wind: the lee of a
/// ridge, slow, stays nearly still even where its shear layer is turbulent.
///
/// Where k comes from:
/// - the momentum model: its closure's k on the cells (app/scene/SceneField.h, tke_m2ps2);
/// - the mass-consistent model, which has no turbulence: the local-equilibrium k of a mixing
///   length l = kappa z at grass height, k = (l dU/dz)^2 / sqrt(C_mu) (the same form as the
///   momentum closure's k = nu_t |S| / sqrt(C_mu) with nu_t = l^2 |dU/dz|, Prandtl's mixing
///   length), dU/dz from the field's speed at two heights (shearTke_m2ps2);
/// - the unsteady field: that shear k of the mean (initial steady) flow plus the resolved
///   fluctuation about it, k = |u - u_mean|^2 / 2 per vertex at every field step
///   (resolvedTke_m2ps2): a whirlwind or a gust front is turbulence the mean flow lacks.
/// Point-source scenes have no field and no flutter.

#include <glm/vec3.hpp>
#include <vector>

namespace gale::coupling {

/// The largest flutter amplitude, radians (20 degrees): beyond it the fluctuation would dominate
/// the mean bend even where the mean wind is strong.
inline constexpr double MAX_FLUTTER_RAD = 0.35;
/// von Karman's constant and the k-epsilon C_mu (Launder and Spalding 1974) of the shear rule.
inline constexpr double KARMAN = 0.41;
inline constexpr double C_MU = 0.09;

/// Flutter amplitude, radians, for k = tke_m2ps2 (m^2/s^2; negative or non-finite count as 0) in
/// a mean wind of speed_mps (m/s, its magnitude is used; non-finite counts as 0) and the blade's
/// bend speed (m/s, > 0; std::invalid_argument otherwise): min((pi/2) sqrt(4 U^2 s^2 + 2 s^4) /
/// bendSpeed^2, MAX_FLUTTER_RAD), s = sqrt(2k/3).
float flutterFromTke(double tke_m2ps2, double speed_mps, double bendSpeed_mps);

/// flutterFromTke for every vertex: k and the world velocity (m/s) at grass height, one each.
/// std::logic_error on different sizes.
std::vector<float> flutterFromTke(const std::vector<double>& tke_m2ps2,
                                  const std::vector<glm::vec3>& wsVelocity_mps,
                                  double bendSpeed_mps);

/// The mixing-length local-equilibrium k, m^2/s^2, between two heights from the speeds
/// speedLow_mps at zLow_m and speedHigh_mps at zHigh_m (m above the ground, 0 < zLow < zHigh;
/// std::invalid_argument otherwise): (kappa z dU/dz)^2 / sqrt(C_mu), dU/dz the finite difference
/// and z the heights' logarithmic mean (zHigh - zLow) / ln(zHigh / zLow), where a log law's
/// derivative equals the difference: a log-law profile U = (u* / kappa) ln(z / z0) gives
/// k = u*^2 / sqrt(C_mu) at any pair of heights. 0 for calm air.
double shearTke_m2ps2(double speedLow_mps, double speedHigh_mps, double zLow_m, double zHigh_m);

/// The resolved fluctuation's k, m^2/s^2, per vertex: |u - mean|^2 / 2 (world velocities, m/s,
/// one each per vertex; std::logic_error on different sizes). Non-finite entries give 0.
std::vector<double> resolvedTke_m2ps2(const std::vector<glm::vec3>& wsVelocity_mps,
                                      const std::vector<glm::vec3>& wsMean_mps);

}  // namespace gale::coupling
