// The intensity function of time: periodic, continuous, strong attack and gradual decay, no
// overshoot of the keys.
#include <gtest/gtest.h>

#include <cmath>

#include "coupling/GustCurve.h"

using gale::coupling::GustCurve;

namespace {

// Evaluations agree to rounding across one period shift.
constexpr double PERIODIC_TOL = 1e-9;
// Step used to probe continuity; a C1 curve changes by ~slope * step there.
constexpr double PROBE_STEP_S = 1e-6;

TEST(GustCurve, PassesThroughItsKeys) {
    const GustCurve c(4.0, {{0.0, 0.1}, {0.5, 0.9}, {2.0, 0.1}, {3.0, -0.2}});
    EXPECT_NEAR(c(0.0), 0.1, 1e-12);
    EXPECT_NEAR(c(0.5), 0.9, 1e-12);
    EXPECT_NEAR(c(2.0), 0.1, 1e-12);
    EXPECT_NEAR(c(3.0), -0.2, 1e-12);
}

TEST(GustCurve, IsPeriodic) {
    const GustCurve c = GustCurve::attackDecay(5.0, 0.05, 1.0, 0.4, 2.5);
    for (double t = -7.3; t < 12.0; t += 0.37) {
        EXPECT_NEAR(c(t), c(t + 5.0), PERIODIC_TOL) << t;
        EXPECT_NEAR(c(t), c(t - 10.0), PERIODIC_TOL) << t;
    }
}

TEST(GustCurve, IsContinuousEverywhereIncludingTheWrap) {
    const GustCurve c(3.0, {{0.2, 0.0}, {0.6, 1.0}, {2.0, 0.3}});
    double maxJump = 0.0;
    for (double t = 0.0; t < 6.0; t += 0.001)
        maxJump = std::max(maxJump, std::abs(c(t + PROBE_STEP_S) - c(t)));
    // Largest slope is about (1.0 / 0.4 s) * 1.5; times the probe step, with margin.
    EXPECT_LT(maxJump, 10.0 * PROBE_STEP_S);
}

TEST(GustCurve, AttackIsSteeperThanDecayAndNeverOvershoots) {
    const double base = 0.1, peak = 0.9, attack = 0.3, decay = 2.0;
    const GustCurve c = GustCurve::attackDecay(4.0, base, peak, attack, decay);
    double maxRise = 0.0, maxFall = 0.0;
    for (double t = 0.0; t < 4.0; t += 0.001) {
        const double v = c(t);
        EXPECT_GE(v, base - 1e-12) << t;
        EXPECT_LE(v, peak + 1e-12) << t;
        const double slope = (c(t + 1e-4) - v) / 1e-4;
        maxRise = std::max(maxRise, slope);
        maxFall = std::max(maxFall, -slope);
    }
    EXPECT_GT(maxRise, 3.0 * maxFall);
    // Calm after the gust: back at the base intensity.
    EXPECT_NEAR(c(3.0), base, 1e-12);
}

TEST(GustCurve, RejectsBadKeys) {
    EXPECT_THROW(GustCurve(0.0, {{0.0, 1.0}}), std::invalid_argument);
    EXPECT_THROW(GustCurve(2.0, {}), std::invalid_argument);
    EXPECT_THROW(GustCurve(2.0, {{0.0, 1.0}, {0.0, 0.5}}), std::invalid_argument);
    EXPECT_THROW(GustCurve(2.0, {{0.0, 1.0}, {2.5, 0.5}}), std::invalid_argument);
    EXPECT_THROW(GustCurve(2.0, {{0.0, NAN}}), std::invalid_argument);
    EXPECT_THROW(GustCurve::attackDecay(2.0, 0.0, 1.0, 1.5, 1.0), std::invalid_argument);
    EXPECT_THROW(GustCurve::attackDecay(2.0, 0.0, 1.0, 0.0, 1.0), std::invalid_argument);
}

TEST(GustCurve, SingleKeyIsConstant) {
    const GustCurve c(1.0, {{0.3, 0.42}});
    EXPECT_EQ(c(-3.1), 0.42);
    EXPECT_EQ(c(17.0), 0.42);
}

}  // namespace
