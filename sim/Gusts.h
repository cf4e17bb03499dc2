#pragma once
/// \file Gusts.h
/// Gust events of the unsteady wind (docs/design.md 4.2): a gust adds a horizontal velocity
///   G(t) = peak_mps * e((t - start_s) / duration_s) * (cos d, sin d, 0)
/// to the air that enters the domain (UnsteadyWindSolver's far field), scaled with height like the
/// mean flow (|u_mean(z)| / U_ref, capped at 1, so a log-law inflow gusts less near the ground).
/// The flow then carries the front over the terrain: it arrives later downstream.
///
/// Envelopes e(s), s = (t - start) / duration, all 0 for s < 0 and s > 1:
///  - Spline: the thesis' gust shape, a sharp attack and a gradual decay: a cubic Hermite
///    smoothstep from 0 to 1 over the attack fraction a = attack_s / duration_s, then a smoothstep
///    from 1 back to 0 over the rest (C1, never outside [0, 1]).
///  - IecEog: the extreme operating gust of IEC 61400-1 (ed. 3, section 6.3.2.2):
///    V(t) = V_hub - 0.37 V_gust sin(3 pi t / T) (1 - cos(2 pi t / T)), 0 <= t <= T. We use its
///    shape normalised so that the peak (at t = T/2, where it is 0.74 V_gust) equals peak_mps:
///    e(s) = -0.37 sin(3 pi s) (1 - cos(2 pi s)) / 0.74, with the standard's dips before and
///    after the peak (e reaches about -0.27 there).
///  - OneMinusCosine: e(s) = (1 - cos(2 pi s)) / 2.
///  - Step: e(s) = 1 for 0 <= s < 1: an infinitely sharp attack (and release), for the stability
///    suite.

#include <array>
#include <optional>
#include <string>

namespace gale::sim {

enum class GustEnvelope { Spline, IecEog, OneMinusCosine, Step };

/// How a gust enters the domain: through the inflow boundary (the far field, default), or as a
/// moving forcing region: a disc of radius regionRadius_m whose centre starts at regionStart_m
/// when the gust starts and moves along the gust's direction at regionSpeed_mps; inside it the
/// horizontal velocity relaxes towards the mean flow plus G(t) with time scale
/// REGION_RELAXATION_S (full strength out to half the radius, a smoothstep to zero at the radius).
/// Only while the envelope runs; the energy it adds is reported as forcing.
enum class GustEntry { Inflow, Region };

/// "inflow", "region" and back; fromName throws gale::ParameterError (wind.gusts.entry).
const char* gustEntryName(GustEntry e);
GustEntry gustEntryFromName(const std::string& name);

/// "spline", "iec_eog", "one_minus_cosine", "step" and back; fromName throws
/// gale::ParameterError (wind.gusts.envelope) listing the valid names.
const char* gustEnvelopeName(GustEnvelope e);
GustEnvelope gustEnvelopeFromName(const std::string& name);

struct GustEvent {
    double start_s = 0.0;        ///< time the gust starts entering the domain, seconds
    double direction_deg = 0.0;  ///< direction it blows towards, degrees counter-clockwise from +x
    double peak_mps = 3.0;       ///< peak added speed, m/s (may be negative: a lull)
    double duration_s = 4.0;     ///< length of the envelope, seconds, > 0
    GustEnvelope envelope = GustEnvelope::Spline;
    /// Spline only: rise time, seconds, in (0, duration_s); unset: 0.15 duration_s.
    std::optional<double> attack_s;
    GustEntry entry = GustEntry::Inflow;
    std::array<double, 2> regionStart_m{0.0, 0.0};  ///< Region: centre at start_s, world metres
    bool regionStartGiven = false;  ///< false: the solver puts it on the upwind side of the domain
    double regionRadius_m = 10.0;   ///< Region: radius of the disc, metres, > 0
    double regionSpeed_mps =
        0.0;  ///< Region: speed of the disc, m/s; 0: the mean wind's reference speed

    /// Relaxation time of the region forcing, seconds.
    static constexpr double REGION_RELAXATION_S = 0.5;

    /// Throws gale::ParameterError naming the scene key without the gust's index
    /// ("wind.gusts.peak_mps"; ParameterError::inElement adds it) when a value is out of range or
    /// not finite.
    void validate() const;
    /// Envelope value e at time t_s (dimensionless; 0 outside [start_s, start_s + duration_s]).
    double envelopeAt(double t_s) const;
    /// Added velocity at time t_s at full height (the profile factor is the caller's), m/s.
    std::array<double, 3> velocityAt_mps(double t_s) const;
};

}  // namespace gale::sim
