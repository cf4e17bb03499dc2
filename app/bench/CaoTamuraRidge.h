#pragma once
/// \file CaoTamuraRidge.h
/// The steep ridge of Cao and Tamura (2006), scaled to H = 40 m, as `gale bench models` and its
/// crest study set it up (docs/validation.md, section 3): geometry, grid, inflow.

#include <cmath>
#include <vector>

#include "base/Numbers.h"
#include "sim/AirDomain.h"
#include "sim/AmbientWind.h"
#include "sim/Heightfield.h"

namespace gale::app::ridge {

constexpr double H_M = 40.0;
constexpr double B_M = 2.5 * H_M;  ///< half-width at the base
constexpr double UPWIND_M = 10 * H_M, DOWNWIND_M = 20 * H_M;
/// z0 of the least-squares log fit to the measured windward-foot profile (docs/validation.md).
constexpr double Z0_M = 0.65;
/// The slope of the same log fit, u / U_inf = A ln(z / z0) (docs/validation.md): the model's
/// inflow (10 m/s at z = H, z0 above) is that fit, so its U_inf is 10 m/s / (A ln(H / z0)).
constexpr double FIT_SLOPE = 0.137;
constexpr double REFERENCE_SPEED_MPS = 10.0;  ///< the inflow's speed at z = H

/// Ground height (m) of the ridge at xFromCrest_m (m, along the wind), z_s = H cos^2(pi x / 2b).
inline double height_m(double xFromCrest_m) {
    if (std::abs(xFromCrest_m) > B_M) return 0.0;
    const double c = std::cos(gale::PI * xFromCrest_m / (2 * B_M));
    return H_M * c * c;
}

/// The ridge from UPWIND_M before the crest to DOWNWIND_M after it, sampled every h / 2 metres,
/// 3 cells of h across (world x = xFromCrest + UPWIND_M).
inline sim::Heightfield terrain(double h_m) {
    const double spacing = h_m / 2, length = UPWIND_M + DOWNWIND_M;
    const int nx = int(std::lround(length / spacing)) + 1, ny = 7;
    std::vector<float> z(size_t(nx) * ny);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            z[size_t(j) * nx + i] = float(height_m(i * spacing - UPWIND_M));
    return sim::makeHeightfield(nx, ny, spacing, std::move(z));
}

/// The inflow: the log fit (10 m/s at z = H, z0 = Z0_M), or a uniform 10 m/s (the potential-flow
/// and Euler diagnostics).
inline sim::AmbientWind wind(bool uniform) {
    sim::AmbientWind w;
    w.profile = uniform ? sim::WindProfile::Uniform : sim::WindProfile::LogLaw;
    w.speed_mps = REFERENCE_SPEED_MPS;
    w.referenceHeight_m = H_M;
    w.roughness_m = Z0_M;
    return w;
}

/// The free-stream speed U_inf (m/s) of the inflow: the log fit's, or the uniform speed.
inline double freeStream_mps(bool uniform) {
    return uniform ? REFERENCE_SPEED_MPS : REFERENCE_SPEED_MPS / (FIT_SLOPE * std::log(H_M / Z0_M));
}

}  // namespace gale::app::ridge
