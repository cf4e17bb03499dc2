// Gust envelopes and whirlwind profiles: the shapes the scene names, peaks where they are
// documented, zero outside their support, and bad values refused.
#include <gtest/gtest.h>

#include <cmath>

#include "base/Numbers.h"
#include "sim/Gusts.h"
#include "sim/Vortices.h"

namespace gale::sim {
namespace {

using gale::PI;
/// Envelope values are closed-form: round-off only.
constexpr double SHAPE_TOLERANCE = 1e-12;
/// Peaks located by sampling at 1e-4 of the duration / core radius.
constexpr double PEAK_TOLERANCE = 1e-6;

GustEvent gust(GustEnvelope e) {
    GustEvent g;
    g.start_s = 2.0, g.duration_s = 10.0, g.peak_mps = 4.0, g.envelope = e;
    return g;
}

double maxOver(const GustEvent& g, double* at = nullptr) {
    double m = -1e9;
    for (int i = 0; i <= 10000; ++i) {
        const double t = g.start_s + g.duration_s * i / 10000.0, v = g.envelopeAt(t);
        if (v > m) m = v, at ? * at = t : 0.0;
    }
    return m;
}

TEST(GustEnvelope, EveryShapePeaksAtOneAndVanishesOutsideItsDuration) {
    for (GustEnvelope e : {GustEnvelope::Spline, GustEnvelope::IecEog, GustEnvelope::OneMinusCosine,
                           GustEnvelope::Step}) {
        const GustEvent g = gust(e);
        EXPECT_NEAR(maxOver(g), 1.0, PEAK_TOLERANCE) << gustEnvelopeName(e);
        EXPECT_EQ(g.envelopeAt(1.9), 0.0);
        EXPECT_EQ(g.envelopeAt(12.1), 0.0);
        EXPECT_EQ(gustEnvelopeFromName(gustEnvelopeName(e)), e);
    }
}

TEST(GustEnvelope, SplineHasASharpAttackAndAGradualDecay) {
    GustEvent g = gust(GustEnvelope::Spline);
    double at = 0;
    maxOver(g, &at);
    EXPECT_NEAR(at - g.start_s, 0.15 * g.duration_s, 1e-3 * g.duration_s);  // default attack: 15 %
    g.attack_s = 1.0;
    maxOver(g, &at);
    EXPECT_NEAR(at - g.start_s, 1.0, 1e-3 * g.duration_s);
    EXPECT_GT(g.envelopeAt(g.start_s + 5.0), 0.4);  // still blowing half way down the decay
}

TEST(GustEnvelope, IecEogHasItsDipsAndPeaksAtHalfTime) {
    const GustEvent g = gust(GustEnvelope::IecEog);
    // IEC 61400-1: V = V_hub - 0.37 V_gust sin(3 pi t/T)(1 - cos(2 pi t/T)), peak 0.74 V_gust at
    // T/2.
    EXPECT_NEAR(g.envelopeAt(g.start_s + 5.0), 1.0, SHAPE_TOLERANCE);
    const double s = 0.1,
                 expected = -0.37 * std::sin(3 * PI * s) * (1 - std::cos(2 * PI * s)) / 0.74;
    EXPECT_NEAR(g.envelopeAt(g.start_s + s * 10.0), expected, SHAPE_TOLERANCE);
    EXPECT_LT(expected, 0.0);  // the dip before the rise
}

TEST(GustEnvelope, StepIsOnForItsWholeDuration) {
    const GustEvent g = gust(GustEnvelope::Step);
    EXPECT_EQ(g.envelopeAt(2.0), 1.0);
    EXPECT_EQ(g.envelopeAt(11.99), 1.0);
    const auto v = g.velocityAt_mps(5.0);
    EXPECT_NEAR(v[0], 4.0, SHAPE_TOLERANCE);
}

TEST(GustEnvelope, BadValuesAreRefused) {
    GustEvent g = gust(GustEnvelope::Spline);
    g.duration_s = -1;
    EXPECT_THROW(g.validate(), std::invalid_argument);
    g = gust(GustEnvelope::Spline);
    g.attack_s = 20.0;
    EXPECT_THROW(g.validate(), std::invalid_argument);
    EXPECT_THROW(gustEnvelopeFromName("square"), std::invalid_argument);
}

TEST(WhirlwindProfile, PeakSpeedIsTheRequestedOneForEveryProfile) {
    for (VortexProfile p :
         {VortexProfile::Rankine, VortexProfile::LambOseen, VortexProfile::Burgers}) {
        Whirlwind w;
        w.coreRadius_m = 3.0, w.peakSpeed_mps = -5.0, w.profile = p;
        double m = 0.0;
        for (int i = 1; i <= 30000; ++i)
            m = std::min(m, w.tangentialSpeed_mps(i * 1e-4 * w.coreRadius_m));
        EXPECT_NEAR(m, -5.0, 1e-4) << vortexProfileName(p);
        EXPECT_LT(w.circulation(), 0.0);  // clockwise seen from above
        // Far outside the core every profile is the potential vortex Gamma / (2 pi r).
        EXPECT_NEAR(w.tangentialSpeed_mps(30.0), w.circulation() / (2 * PI * 30.0), 1e-9);
        EXPECT_EQ(vortexProfileFromName(vortexProfileName(p)), p);
    }
}

TEST(WhirlwindProfile, BadValuesAreRefused) {
    Whirlwind w;
    w.coreRadius_m = 0.0;
    EXPECT_THROW(w.validate(), std::invalid_argument);
    w = {};
    w.updraft_mps = -1.0;
    EXPECT_THROW(w.validate(), std::invalid_argument);
    EXPECT_THROW(vortexProfileFromName("tornado"), std::invalid_argument);
}

}  // namespace
}  // namespace gale::sim
