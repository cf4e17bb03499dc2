/// \file AmbientWind.cpp
#include "sim/AmbientWind.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/Format.h"

namespace gale::sim {
namespace {
using detail::num;

/// An angle in degrees brought into [0, 360).
double wrap360(double deg) {
    const double w = std::fmod(deg, 360.0);
    const double r = w < 0.0 ? w + 360.0 : w;
    return r >= 360.0 ? 0.0 : r;
}
}  // namespace

double AmbientWind::towardsFromMeteorological_deg(double from_deg) {
    return wrap360(270.0 - from_deg);
}

double AmbientWind::from_deg() const { return wrap360(270.0 - direction_deg); }

double AmbientWind::towardsBearing_deg() const { return wrap360(90.0 - direction_deg); }

const char* windProfileName(WindProfile profile) {
    return profile == WindProfile::Uniform ? "uniform" : "log";
}

WindProfile windProfileFromName(const std::string& name) {
    if (name == "uniform") return WindProfile::Uniform;
    if (name == "log") return WindProfile::LogLaw;
    throw ParameterError("wind.profile", "\"" + name + "\"", "expected one of: uniform, log");
}

void AmbientWind::validate() const {
    if (!(speed_mps >= 0.0) || !std::isfinite(speed_mps))
        throw ParameterError("wind.speed_mps", num(speed_mps), "must be >= 0 and finite");
    if (!std::isfinite(direction_deg))
        throw ParameterError("wind.direction_deg", num(direction_deg), "must be finite");
    if (!(referenceHeight_m > 0.0) || !std::isfinite(referenceHeight_m))
        throw ParameterError("wind.reference_height_m", num(referenceHeight_m),
                             "must be > 0 and finite");
    if (profile == WindProfile::LogLaw) {
        // z_ref / z0 at least this: ln(3) = 1.1 keeps u(z) within a factor ln(z / z0) / 1.1.
        constexpr double MIN_REFERENCE_OVER_ROUGHNESS = 3.0;
        if (!(roughness_m > 0.0) || !std::isfinite(roughness_m))
            throw ParameterError("wind.roughness_m", num(roughness_m), "must be > 0 and finite");
        // u(z) = U ln(z / z0) / ln(z_ref / z0): as z_ref nears z0 the denominator goes to 0 and
        // the field to infinity (z_ref = 1.0000001 z0 gave 9e9 m/s) or, rounded, to nothing. The
        // neutral log law describes the surface layer well above the roughness elements, so the
        // reference height must be at least a few z0.
        if (!(referenceHeight_m >= MIN_REFERENCE_OVER_ROUGHNESS * roughness_m))
            throw ParameterError("wind.reference_height_m", num(referenceHeight_m) + " m",
                                 "must be at least " + num(MIN_REFERENCE_OVER_ROUGHNESS) +
                                     " x roughness_m (" + num(roughness_m) + " m), i.e. >= " +
                                     num(MIN_REFERENCE_OVER_ROUGHNESS * roughness_m) +
                                     " m, for the log law to hold");
    }
}

double AmbientWind::speedAt_mps(double z) const {
    if (profile == WindProfile::Uniform) return z >= 0.0 ? speed_mps : 0.0;
    if (!(z > roughness_m)) return 0.0;
    // Neutral surface layer: u(z) = (u* / kappa) ln(z / z0), scaled so u(z_ref) = speed_mps.
    return speed_mps * std::log(z / roughness_m) / std::log(referenceHeight_m / roughness_m);
}

std::array<double, 3> AmbientWind::velocityAt_mps(double z) const {
    const double s = speedAt_mps(z), a = radiansFromDegrees(direction_deg);
    return {s * std::cos(a), s * std::sin(a), 0.0};
}

}  // namespace gale::sim
