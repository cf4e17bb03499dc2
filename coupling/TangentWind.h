#pragma once
/// \file TangentWind.h
/// The paper's projection of a wind onto a vertex's tangent plane (Bakay et al. 2002, section 3;
/// docs/design.md 5, step 2). Inline: it runs for every grass vertex at every field step.

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace gale::coupling {

/// Below this fraction of |W| the tangential part is rounding noise: the wind is along the normal
/// and has no direction in the tangent plane.
constexpr double DEGENERATE_TANGENT_FRACTION = 1e-6;

/// V = W - (W.N)N with N = n / |n|, normalised; zero when |V| is below 1e-6 |W| (wind along the
/// normal) or W is zero. Never NaN for finite input; a zero or non-finite n gives zero.
///
/// In double, so the result is perpendicular to N to ~1e-15 even for winds nearly along the
/// normal, and squares cannot overflow or underflow to zero for any finite float input. Scaled by
/// |n|^2 to need neither |n| nor a division by it: V |n|^2 = W (n.n) - (W.n) n; one square root.
inline glm::vec3 tangentWindDirection(const glm::vec3& wsWind, const glm::vec3& wsNormal) {
    const glm::dvec3 w(wsWind), n(wsNormal);
    const double ww = glm::dot(w, w), nn = glm::dot(n, n);
    // Non-finite input makes ww or nn NaN or Inf, which fails these tests too.
    if (!(ww > 0.0 && ww <= 1e300 && nn >= 1e-24 && nn <= 1e300)) return glm::vec3(0.0f);
    const glm::dvec3 v = w * nn - glm::dot(w, n) * n;
    const double vv = glm::dot(v, v);
    constexpr double f2 = DEGENERATE_TANGENT_FRACTION * DEGENERATE_TANGENT_FRACTION;
    if (!(vv > f2 * ww * nn * nn)) return glm::vec3(0.0f);
    return glm::vec3(v * (1.0 / std::sqrt(vv)));
}

}  // namespace gale::coupling
