/// \file Flutter.cpp
#include "coupling/Flutter.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>
#include <string>

#include "base/Numbers.h"

namespace gale::coupling {

float flutterFromTke(double tke_m2ps2, double speed_mps, double bendSpeed_mps) {
    if (!(bendSpeed_mps > 0.0) || !std::isfinite(bendSpeed_mps))
        throw std::invalid_argument("flutterFromTke: bend speed must be > 0, got " +
                                    std::to_string(bendSpeed_mps));
    if (!(tke_m2ps2 > 0.0) || !std::isfinite(tke_m2ps2)) return 0.0f;
    const double u = std::isfinite(speed_mps) ? std::abs(speed_mps) : 0.0;
    const double s2 = 2.0 * tke_m2ps2 / 3.0;  // sigma_u^2
    const double dragRms = std::sqrt(4.0 * u * u * s2 + 2.0 * s2 * s2);
    return static_cast<float>(
        std::min(0.5 * PI * dragRms / (bendSpeed_mps * bendSpeed_mps), MAX_FLUTTER_RAD));
}

std::vector<float> flutterFromTke(const std::vector<double>& tke_m2ps2,
                                  const std::vector<glm::vec3>& wsVelocity_mps,
                                  double bendSpeed_mps) {
    if (tke_m2ps2.size() != wsVelocity_mps.size())
        throw std::logic_error("flutterFromTke: " + std::to_string(tke_m2ps2.size()) +
                               " k values but " + std::to_string(wsVelocity_mps.size()) +
                               " velocities");
    std::vector<float> out(tke_m2ps2.size());
    for (size_t v = 0; v < out.size(); ++v)
        out[v] =
            flutterFromTke(tke_m2ps2[v], double(glm::length(wsVelocity_mps[v])), bendSpeed_mps);
    return out;
}

double shearTke_m2ps2(double speedLow_mps, double speedHigh_mps, double zLow_m, double zHigh_m) {
    if (!(zLow_m > 0.0) || !(zHigh_m > zLow_m))
        throw std::invalid_argument("shearTke_m2ps2: needs 0 < zLow < zHigh, got " +
                                    std::to_string(zLow_m) + " and " + std::to_string(zHigh_m));
    if (!std::isfinite(speedLow_mps) || !std::isfinite(speedHigh_mps)) return 0.0;
    const double dudz_per_s = (speedHigh_mps - speedLow_mps) / (zHigh_m - zLow_m);
    // The finite difference is the log law's dU/dz = u* / (kappa z) at the logarithmic mean of
    // the two heights, (zHigh - zLow) / ln(zHigh / zLow); the mixing length is taken there, so a
    // log-law profile gives k = u*^2 / sqrt(C_mu) exactly, the surface layer's equilibrium k.
    const double zMean_m = (zHigh_m - zLow_m) / std::log(zHigh_m / zLow_m);
    const double l_m = KARMAN * zMean_m;
    return (l_m * dudz_per_s) * (l_m * dudz_per_s) / std::sqrt(C_MU);
}

std::vector<double> resolvedTke_m2ps2(const std::vector<glm::vec3>& wsVelocity_mps,
                                      const std::vector<glm::vec3>& wsMean_mps) {
    if (wsVelocity_mps.size() != wsMean_mps.size())
        throw std::logic_error("resolvedTke_m2ps2: " + std::to_string(wsVelocity_mps.size()) +
                               " velocities but " + std::to_string(wsMean_mps.size()) + " means");
    std::vector<double> k(wsVelocity_mps.size(), 0.0);
    for (size_t v = 0; v < k.size(); ++v) {
        const glm::vec3 d = wsVelocity_mps[v] - wsMean_mps[v];
        const double k_v = 0.5 * double(glm::dot(d, d));
        k[v] = std::isfinite(k_v) ? k_v : 0.0;
    }
    return k;
}

}  // namespace gale::coupling
