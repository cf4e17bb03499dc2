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

namespace gale::validation::ridge {

constexpr double H_M = 40.0;
constexpr double B_M = 2.5 * H_M;  ///< half-width at the base
/// The box along the wind: the published simulation set-up of this case (Exawind
/// wall_stress_model, complex_terrain/2d_ridge) runs from -8.1 H to 24.4 H; whole ridge heights
/// keep the crest on a cell face at every H / h the bench uses.
constexpr double UPWIND_M = 8 * H_M, DOWNWIND_M = 24 * H_M;
constexpr double TOP_OVER_H = 6.0;  ///< the box's top above the flat ground, as published (6 H)
/// The published set-up's roughness of the ground and of the inflow's boundary layer: 4e-6 m
/// at the tunnel's H = 0.04 m, z0 / H = 1e-4.
constexpr double PUBLISHED_Z0_M = 1e-4 * H_M;
/// History, not the validation: z0 of the least-squares log fit to the measured windward-foot
/// profile, u / U_inf = FIT_SLOPE ln(z / z0) (docs/validation.md, section 3), with 10 m/s at z = H;
/// its U_inf is 10 m/s / (FIT_SLOPE ln(H / z0)).
constexpr double FOOT_FIT_Z0_M = 0.65;
constexpr double FIT_SLOPE = 0.137;
constexpr double REFERENCE_SPEED_MPS = 10.0;  ///< the inflow's speed at its reference height

/// Heights above the crest where the measured crest profile is reported (dz / H).
constexpr double CREST_DZ_OVER_H[3] = {0.25, 0.48, 0.98};

/// Which inflow a run uses.
enum class Inflow {
    Published,  ///< log law, z0 = PUBLISHED_Z0_M, 10 m/s at the top (6 H): U_inf = 10 m/s
    FootFit,    ///< history: the log fit to the measured foot, 10 m/s at z = H
    Uniform,    ///< 10 m/s at every height (the potential-flow and Euler diagnostics)
};

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

/// The inflow's ambient wind (speed in m/s, heights above the local ground in metres); its
/// roughness_m is also the ground's z0 in the momentum model.
inline sim::AmbientWind wind(Inflow inflow) {
    sim::AmbientWind w;
    w.profile = inflow == Inflow::Uniform ? sim::WindProfile::Uniform : sim::WindProfile::LogLaw;
    w.speed_mps = REFERENCE_SPEED_MPS;
    w.referenceHeight_m = inflow == Inflow::Published ? TOP_OVER_H * H_M : H_M;
    w.roughness_m = inflow == Inflow::FootFit ? FOOT_FIT_Z0_M : PUBLISHED_Z0_M;
    return w;
}

/// The free-stream speed U_inf (m/s) the measured u / U_inf is compared with: the published
/// inflow's speed at the top (its reference), the foot fit's U_inf, or the uniform speed.
inline double freeStream_mps(Inflow inflow) {
    if (inflow == Inflow::FootFit)
        return REFERENCE_SPEED_MPS / (FIT_SLOPE * std::log(H_M / FOOT_FIT_Z0_M));
    return REFERENCE_SPEED_MPS;
}

/// A short label of the inflow for the bench's tables.
inline const char* inflowName(Inflow inflow) {
    switch (inflow) {
        case Inflow::Published:
            return "published";
        case Inflow::FootFit:
            return "foot fit (history)";
        case Inflow::Uniform:
            return "uniform";
    }
    return "";
}

}  // namespace gale::validation::ridge
