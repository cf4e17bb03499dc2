/// \file Gusts.cpp
#include "sim/Gusts.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/Format.h"

namespace gale::sim {
namespace {
using gale::PI;
/// Default attack of the spline envelope, as a fraction of the duration: a sharp rise.
constexpr double DEFAULT_ATTACK_FRACTION = 0.15;
/// Peak of the un-normalised IEC EOG shape -0.37 sin(3 pi s)(1 - cos(2 pi s)), at s = 1/2.
constexpr double IEC_EOG_PEAK = 0.74;

using detail::smoothstep;

using detail::num;
}  // namespace

const char* gustEnvelopeName(GustEnvelope e) {
    switch (e) {
        case GustEnvelope::Spline:
            return "spline";
        case GustEnvelope::IecEog:
            return "iec_eog";
        case GustEnvelope::OneMinusCosine:
            return "one_minus_cosine";
        case GustEnvelope::Step:
            return "step";
    }
    return "?";
}

GustEnvelope gustEnvelopeFromName(const std::string& name) {
    if (name == "spline") return GustEnvelope::Spline;
    if (name == "iec_eog") return GustEnvelope::IecEog;
    if (name == "one_minus_cosine") return GustEnvelope::OneMinusCosine;
    if (name == "step") return GustEnvelope::Step;
    throw ParameterError("wind.gusts.envelope", "\"" + name + "\"",
                         "expected one of: spline, iec_eog, one_minus_cosine, step");
}

const char* gustEntryName(GustEntry e) { return e == GustEntry::Region ? "region" : "inflow"; }

GustEntry gustEntryFromName(const std::string& name) {
    if (name == "inflow") return GustEntry::Inflow;
    if (name == "region") return GustEntry::Region;
    throw ParameterError("wind.gusts.entry", "\"" + name + "\"", "expected one of: inflow, region");
}

void GustEvent::validate() const {
    if (!std::isfinite(start_s))
        throw ParameterError("wind.gusts.start_s", num(start_s), "must be finite");
    if (!std::isfinite(direction_deg))
        throw ParameterError("wind.gusts.direction_deg", num(direction_deg), "must be finite");
    if (!std::isfinite(peak_mps) || std::abs(peak_mps) > 1000.0)
        throw ParameterError("wind.gusts.peak_mps", num(peak_mps), "must be in [-1000, 1000]");
    if (!(duration_s > 0.0) || !std::isfinite(duration_s))
        throw ParameterError("wind.gusts.duration_s", num(duration_s), "must be > 0 and finite");
    if (entry == GustEntry::Region && (!(regionRadius_m > 0.0) || !std::isfinite(regionRadius_m)))
        throw ParameterError("wind.gusts.region_radius_m", num(regionRadius_m),
                             "must be > 0 and finite");
    if (entry == GustEntry::Region &&
        (!(regionSpeed_mps >= 0.0) || !std::isfinite(regionSpeed_mps)))
        throw ParameterError("wind.gusts.region_speed_mps", num(regionSpeed_mps),
                             "must be >= 0 and finite");
    if (envelope == GustEnvelope::Spline && attack_s &&
        !(*attack_s > 0.0 && *attack_s < duration_s))
        throw ParameterError("wind.gusts.attack_s", num(*attack_s),
                             "must be in (0, duration_s = " + num(duration_s) + ")");
}

double GustEvent::envelopeAt(double t_s) const {
    const double s = (t_s - start_s) / duration_s;
    if (!(s >= 0.0) || s > 1.0) return 0.0;
    switch (envelope) {
        case GustEnvelope::Spline: {
            const double a = attack_s ? *attack_s / duration_s : DEFAULT_ATTACK_FRACTION;
            return s < a ? smoothstep(s / a) : 1.0 - smoothstep((s - a) / (1.0 - a));
        }
        case GustEnvelope::IecEog:
            return -0.37 * std::sin(3.0 * PI * s) * (1.0 - std::cos(2.0 * PI * s)) / IEC_EOG_PEAK;
        case GustEnvelope::OneMinusCosine:
            return 0.5 * (1.0 - std::cos(2.0 * PI * s));
        case GustEnvelope::Step:
            return s < 1.0 ? 1.0 : 0.0;
    }
    return 0.0;
}

std::array<double, 3> GustEvent::velocityAt_mps(double t_s) const {
    const double g = peak_mps * envelopeAt(t_s), a = radiansFromDegrees(direction_deg);
    return {g * std::cos(a), g * std::sin(a), 0.0};
}

}  // namespace gale::sim
