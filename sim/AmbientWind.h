#pragma once
/// \file AmbientWind.h
/// The first guess of the steady solve (docs/design.md 4.1): a horizontal ambient wind with a
/// vertical profile, applied relative to the ground below each point.

#include <array>
#include <string>

namespace gale::sim {

enum class WindProfile {
    Uniform,  ///< speed_mps at every height above the ground
    LogLaw,   ///< u(z) = speed_mps * ln(z / z0) / ln(z_ref / z0) for z > z0, 0 below (neutral log
              ///< law)
};

/// Name as written in scene files ("uniform", "log"), and back; fromName throws
/// gale::ParameterError (wind.profile) listing the valid names.
const char* windProfileName(WindProfile profile);
WindProfile windProfileFromName(const std::string& name);

struct AmbientWind {
    double speed_mps = 5.0;           ///< horizontal speed at referenceHeight_m above ground, >= 0
    double referenceHeight_m = 10.0;  ///< height above ground where speed_mps holds, > roughness_m
    /// Direction the wind blows TOWARDS, degrees counter-clockwise from +x (mathematical
    /// convention, as elsewhere in gale): 0 blows along +x, 90 along +y. Not the meteorological
    /// "from" bearing.
    double direction_deg = 0.0;
    WindProfile profile = WindProfile::LogLaw;
    double roughness_m = 0.03;  ///< aerodynamic roughness length z0 (LogLaw), > 0

    /// The meteorological convention: degrees clockwise from north (+y), where the wind comes
    /// FROM (a west wind, from 270, blows along +x). Both helpers return degrees in [0, 360).
    /// direction_deg = 270 - from_deg (mod 360): from 210 = towards bearing 30 = direction 60.
    static double towardsFromMeteorological_deg(double from_deg);
    /// This wind's meteorological "from" direction, degrees clockwise from north, [0, 360).
    double from_deg() const;
    /// The compass bearing it blows towards, degrees clockwise from north, [0, 360).
    double towardsBearing_deg() const;

    /// Throws gale::ParameterError naming the scene key (wind.speed_mps, wind.reference_height_m,
    /// wind.roughness_m, ...) when a value is out of range or not finite, or when the log law's
    /// reference height is below 3 roughness lengths.
    void validate() const;
    /// Horizontal speed at a height above the local ground, m/s (0 at or below z0 for LogLaw;
    /// 0 below the ground for Uniform).
    double speedAt_mps(double heightAboveGround_m) const;
    /// Velocity (u, v, 0) at a height above the local ground, world axes, m/s.
    std::array<double, 3> velocityAt_mps(double heightAboveGround_m) const;
};

}  // namespace gale::sim
