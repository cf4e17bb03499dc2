#pragma once
/// \file Bend.h
/// The length-preserving blade bend (Bakay, Lalonde, Heidrich 2002, section 3; Bakay 2003, 3.2),
/// in the corrected form of DESIGN 5.1: segment j of a blade of N segments, each of length S, tilts
/// by theta_j = (pi/2) I (j/N)^gamma from the normal, so shell i sits at
///   n_i = sum_{j=1..i} S cos(theta_j)  along the normal,
///   w_i = sum_{j=1..i} S sin(theta_j)  along the wind direction.
/// Every segment keeps length S whatever I, N and gamma; the tip tilts by (pi/2) I.

#include <vector>

namespace gale::render {

/// Double precision so that segment lengths hold to 1e-7 relative even at 256 shells; the renderer
/// narrows to float when it uploads the table.
struct ShellOffset {
    double n_m;  ///< offset along the vertex normal, metres
    double w_m;  ///< offset along the tangent-plane wind direction, metres
};

/// Offsets of shells 0..N (shell 0 = ground, offset 0) for one intensity.
/// height_m = N * S. Requires shells >= 1; intensity and stiffness finite, stiffness > 0.
std::vector<ShellOffset> bendBlade(int shells, float height_m, float intensity, float stiffness);

/// The same, written into out[0..shells] (out must hold shells + 1 entries); no allocation, for
/// the per-frame per-group tables.
void bendBladeInto(int shells, float height_m, float intensity, float stiffness, ShellOffset* out);

}  // namespace gale::render
