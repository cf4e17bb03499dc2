#pragma once
/// \file Bend.h
/// The length-preserving blade bend (Bakay, Lalonde, Heidrich 2002, section 3; Bakay 2003, 3.2):
/// segment j of a blade of N segments, each of length S, tilts from the normal by
///   theta_j = theta_tip (j/N)^gamma,
/// so shell i sits at
///   n_i = sum_{j=1..i} S cos(theta_j)  along the normal,
///   w_i = sum_{j=1..i} S sin(theta_j)  along the wind direction.
/// Every segment keeps length S whatever the tilt, N and gamma.
///
/// The paper's tip tilt is theta_tip = (pi/2) I, which lays the tip below the ground for |I| > 1
/// (an oscillator overshooting a gust drives I to 2 and beyond). Here the tip tilt is the paper's
/// up to |I| = 1/2 and saturates smoothly above, never past MAX_TIP_TILT_RAD = pi/2 -
/// GROUND_MARGIN_RAD (tipTilt_rad, docs/render.md). Every segment then climbs at least
/// GROUND_MARGIN_RAD above the vertex's tangent plane, so the whole blade stays above the ground
/// wherever the ground rises less than that within a blade's reach.

#include <vector>

#include "base/Numbers.h"

namespace gale::render {

/// Double precision so that segment lengths hold to 1e-7 relative even at 256 shells; the renderer
/// narrows to float when it uploads the table.
struct ShellOffset {
    double n_m;  ///< offset along the vertex normal, metres
    double w_m;  ///< offset along the tangent-plane wind direction, metres
};

/// The least angle, radians, between any blade segment and the vertex's tangent plane. A blade
/// then lies inside the cone n >= tan(margin) |w| over its vertex, so it stays above any ground
/// that rises by less than this angle (seen from the vertex) within one blade length: concave
/// ground of curvature radius R >= height / (2 margin) (3.3 m for 1 m grass), or a crease whose
/// faces turn by less than the margin.
inline constexpr double GROUND_MARGIN_RAD = 0.15;
/// The bound of |tip tilt|, radians: pi/2 - GROUND_MARGIN_RAD (about 81.4 degrees).
inline constexpr double MAX_TIP_TILT_RAD = 0.5 * PI - GROUND_MARGIN_RAD;
/// The tip tilt below which the bend is the paper's exactly: (pi/2) * 1/2, radians.
inline constexpr double TIP_TILT_KNEE_RAD = 0.25 * PI;

/// Tip tilt for intensity I, radians, signed like I: x = (pi/2) I up to |x| = TIP_TILT_KNEE_RAD,
/// then knee + (max - knee) tanh((|x| - knee) / (max - knee)): continuous with its first and
/// second derivatives at the knee, monotone, and at most MAX_TIP_TILT_RAD for every finite I
/// (approached exponentially; equal to it in double from |I| of about 10).
/// Requires a finite intensity (non-finite gives NaN; bendBlade checks).
double tipTilt_rad(double intensity);

/// Offsets of shells 0..N (shell 0 = ground, offset 0) for one intensity.
/// height_m = N * S. Requires shells >= 1, height_m >= 0 and stiffness > 0, finite (else
/// gale::ParameterError naming grass.shells, grass.height_m or grass.stiffness) and a finite
/// intensity (else std::logic_error: intensities come from the wind source).
std::vector<ShellOffset> bendBlade(int shells, float height_m, float intensity, float stiffness);

/// The same, written into out[0..shells] (out must hold shells + 1 entries); no allocation, for
/// the per-frame per-group tables.
void bendBladeInto(int shells, float height_m, float intensity, float stiffness, ShellOffset* out);

/// The bend for a given tip tilt (radians, any value; the saturation is the caller's), written
/// into out[0..shells]: the renderer's table of bends over tilts.
void bendBladeByTiltInto(int shells, float height_m, double tipTilt_rad, float stiffness,
                         ShellOffset* out);

}  // namespace gale::render
