// The length-preserving bend (docs/design.md 5.1): segment lengths, tip tilt, straight blade at
// rest.
#include <gtest/gtest.h>

#include <cmath>

#include "base/Numbers.h"
#include "render/Bend.h"

using gale::render::bendBlade;
using gale::render::GROUND_MARGIN_RAD;
using gale::render::MAX_TIP_TILT_RAD;
using gale::render::ShellOffset;
using gale::render::TIP_TILT_KNEE_RAD;
using gale::render::tipTilt_rad;

namespace {

using gale::PI;
// The bound on segment length: 1e-5 relative; double sums reach ~1e-13.
constexpr double SEGMENT_LENGTH_REL_TOL = 1e-5;
// Tip tilt from the last segment's direction; atan2 of double offsets is good to ~1e-9 rad.
constexpr double TIP_TILT_TOL_RAD = 1e-6;

struct BendCase {
    int shells;
    float intensity;
    float stiffness;
};

class BendInvariants : public ::testing::TestWithParam<BendCase> {};

TEST_P(BendInvariants, EverySegmentKeepsLengthAndTheTipTiltsAsThePaperUpToHalfFlat) {
    const BendCase c = GetParam();
    const float height_m = 0.6f;
    const std::vector<ShellOffset> s = bendBlade(c.shells, height_m, c.intensity, c.stiffness);
    ASSERT_EQ(s.size(), static_cast<size_t>(c.shells) + 1);
    EXPECT_EQ(s[0].n_m, 0.0);
    EXPECT_EQ(s[0].w_m, 0.0);
    const double segment_m = double(height_m) / c.shells;
    for (int i = 1; i <= c.shells; ++i) {
        const double dn = s[i].n_m - s[i - 1].n_m, dw = s[i].w_m - s[i - 1].w_m;
        EXPECT_NEAR(std::hypot(dn, dw), segment_m, SEGMENT_LENGTH_REL_TOL * segment_m)
            << "segment " << i << " of " << c.shells;
    }
    const double dn = s[c.shells].n_m - s[c.shells - 1].n_m;
    const double dw = s[c.shells].w_m - s[c.shells - 1].w_m;
    const double tilt = std::atan2(dw, dn);  // the last segment's tilt from the normal
    const double paper = 0.5 * PI * c.intensity;
    if (std::abs(c.intensity) <= 0.5f) {
        // Up to half-flat the tip tilts exactly as the paper's (pi/2) I.
        EXPECT_NEAR(tilt, paper, TIP_TILT_TOL_RAD);
    } else {
        // Beyond, the tilt keeps the sign of I, tilts further than the knee and stays short of
        // the ground margin (never past pi/2 - margin; tanh rounds to 1 in double for large I).
        EXPECT_GT(std::abs(tilt), gale::render::TIP_TILT_KNEE_RAD);
        EXPECT_LE(std::abs(tilt), gale::render::MAX_TIP_TILT_RAD + TIP_TILT_TOL_RAD);
        EXPECT_EQ(tilt > 0.0, c.intensity > 0.0f);
    }
}

std::vector<BendCase> allCases() {
    std::vector<BendCase> cases;
    for (int shells : {1, 2, 9, 17, 65, 256})
        for (float intensity : {-5.0f, -1.0f, -0.3f, 0.0f, 0.5f, 1.0f, 2.5f, 5.0f})
            for (float stiffness : {0.5f, 1.0f, 2.0f})
                cases.push_back({shells, intensity, stiffness});
    return cases;
}

INSTANTIATE_TEST_SUITE_P(ShellsIntensitiesStiffness, BendInvariants,
                         ::testing::ValuesIn(allCases()),
                         [](const ::testing::TestParamInfo<BendCase>& paramInfo) {
                             auto name = [](float v) {
                                 std::string s =
                                     std::to_string(static_cast<int>(std::lround(v * 10)));
                                 return (v < 0 ? "m" + s.substr(1) : s);
                             };
                             return "N" + std::to_string(paramInfo.param.shells) + "_I" +
                                    name(paramInfo.param.intensity) + "_G" +
                                    name(paramInfo.param.stiffness);
                         });

TEST(Bend, ZeroIntensityGivesAStraightBladeOfFullHeight) {
    for (int shells : {1, 9, 256}) {
        const auto s = bendBlade(shells, 0.5f, 0.0f, 1.0f);
        for (int i = 0; i <= shells; ++i) {
            EXPECT_EQ(s[i].w_m, 0.0);
            EXPECT_NEAR(s[i].n_m, 0.5 * i / shells, 1e-12);
        }
    }
}

TEST(Bend, StifferGrassBendsLessAtTheSameIntensity) {
    const auto floppy = bendBlade(16, 1.0f, 0.8f, 0.5f);
    const auto paper = bendBlade(16, 1.0f, 0.8f, 1.0f);
    const auto stiff = bendBlade(16, 1.0f, 0.8f, 2.0f);
    EXPECT_GT(floppy[16].w_m, paper[16].w_m);
    EXPECT_GT(paper[16].w_m, stiff[16].w_m);
}

TEST(Bend, NegativeIntensityMirrorsTheBlade) {
    const auto pos = bendBlade(9, 1.0f, 0.7f, 1.0f);
    const auto neg = bendBlade(9, 1.0f, -0.7f, 1.0f);
    for (int i = 0; i <= 9; ++i) {
        EXPECT_NEAR(pos[i].n_m, neg[i].n_m, 1e-12);
        EXPECT_NEAR(pos[i].w_m, -neg[i].w_m, 1e-12);
    }
}

TEST(Bend, TipTiltSaturatesSmoothlyAndMonotonically) {
    // Slope of the tilt against (pi/2) I on both sides of the knee: 1 (C1), by central differences
    // of step h; the curvature there is 0, so one-sided differences agree to O(h^2).
    constexpr double STEP = 1e-5;
    constexpr double SLOPE_TOL = 1e-6;  // O(h^2) with h = 1e-5 rad, plus rounding of 1e-11 / h
    const double kneeI = TIP_TILT_KNEE_RAD / (0.5 * PI);
    auto slope = [&](double i) {
        const double h = STEP / (0.5 * PI);
        return (tipTilt_rad(i + h) - tipTilt_rad(i - h)) / (2.0 * STEP);
    };
    EXPECT_NEAR(slope(kneeI - 2 * STEP), 1.0, SLOPE_TOL);
    EXPECT_NEAR(slope(kneeI + 2 * STEP), 1.0, SLOPE_TOL);
    // Monotone, odd and bounded from rest to far past any drive an oscillator reaches.
    double previous = 0.0;
    for (double i = 0.0; i < 50.0; i += 0.01) {
        const double t = tipTilt_rad(i);
        EXPECT_GE(t, previous) << "I = " << i;
        EXPECT_LE(t, MAX_TIP_TILT_RAD) << "I = " << i;
        EXPECT_EQ(tipTilt_rad(-i), -t);
        previous = t;
    }
    // And it reaches the bound: within 1e-9 rad by I = 50 (tanh saturates exponentially).
    EXPECT_NEAR(tipTilt_rad(50.0), MAX_TIP_TILT_RAD, 1e-9);
}

TEST(Bend, ExtremeIntensitiesGiveFiniteBladesInsideTheGroundMarginCone) {
    // Every shell point keeps n >= tan(margin) |w|: the blade never reaches the tangent plane.
    constexpr double CONE_TOL_M = 1e-12;  // double sums of at most 256 terms of <= 1 m
    for (float intensity : {-3.4e38f, -1e6f, -2.45f, 1.9f, 2.45f, 1e6f, 3.4e38f}) {
        for (float stiffness : {0.3f, 1.0f, 3.0f}) {
            const auto s = bendBlade(64, 1.0f, intensity, stiffness);
            for (int i = 1; i <= 64; ++i) {
                ASSERT_TRUE(std::isfinite(s[i].n_m) && std::isfinite(s[i].w_m));
                EXPECT_GT(s[i].n_m, 0.0);
                EXPECT_GE(s[i].n_m + CONE_TOL_M, std::tan(GROUND_MARGIN_RAD) * std::abs(s[i].w_m))
                    << "I = " << intensity << ", stiffness " << stiffness << ", shell " << i;
            }
        }
    }
}

TEST(Bend, RejectsBadArguments) {
    EXPECT_THROW(bendBlade(0, 1.0f, 0.5f, 1.0f), std::invalid_argument);
    EXPECT_THROW(bendBlade(4, 1.0f, NAN, 1.0f), std::logic_error);
    EXPECT_THROW(bendBlade(4, 1.0f, 0.5f, 0.0f), std::invalid_argument);
    EXPECT_THROW(bendBlade(4, INFINITY, 0.5f, 1.0f), std::invalid_argument);
}

}  // namespace
