// The periodic hill study (validation/PeriodicHillStudy.h): its geometry against the published
// cubics' own properties, its measures (bubble, RMS) against hand-computed cases, its embedded
// reference against the figures validation/data/README.md states, and one coarse solve against
// the physics any closure must reproduce behind this hill.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "sim/MomentumTurbulence.h"
#include "sim/SurfaceLayer.h"
#include "validation/PeriodicHill.h"
#include "validation/PeriodicHillStudy.h"

namespace gale::validation {
namespace {

namespace ph = periodichill;

/// The published cubics are printed to 13 digits and were fitted to join: at their joins they
/// agree to 2e-11 mm (computed); read 1e-9 mm apart, their slopes (< 3) add 3e-9 mm. 1e-6 mm
/// fails a wrong digit among the first seven of any coefficient.
constexpr double JOIN_TOLERANCE_H = 1e-6 / ph::HILL_MM;
/// A crossing interpolated on a piecewise-linear line is exact up to round-off.
constexpr double CROSSING_TOLERANCE_H = 1e-12;

TEST(PeriodicHillGeometry, PublishedCubicsSpanCrestToFootAndJoin) {
    EXPECT_DOUBLE_EQ(ph::lowerHillHeight_h(0.0), 1.0);
    EXPECT_DOUBLE_EQ(ph::lowerHillHeight_h(ph::FOOT_MM / ph::HILL_MM), 0.0);
    for (double join_mm : {9.0, 14.0, 20.0, 30.0, 40.0}) {
        const double below = ph::lowerHillHeight_h((join_mm - 1e-9) / ph::HILL_MM);
        const double above = ph::lowerHillHeight_h(join_mm / ph::HILL_MM);
        EXPECT_NEAR(below, above, JOIN_TOLERANCE_H) << "join at " << join_mm << " mm";
    }
    // The hill falls from crest to foot and never leaves [0, 1].
    double last = 1.0;
    for (int i = 0; i <= 540; ++i) {
        const double hgt = ph::lowerHillHeight_h(i * 0.1 / ph::HILL_MM);
        EXPECT_LE(hgt, last + 1e-12) << "at " << i * 0.1 << " mm";
        EXPECT_GE(hgt, 0.0);
        last = hgt;
    }
}

TEST(PeriodicHillGeometry, FloorIsFlatBetweenTheFeetAndSymmetricAboutThePeriodsMiddle) {
    for (double x : {2.0, 4.5, 7.0}) EXPECT_EQ(ph::floorHeight_h(x), 0.0) << x;
    for (double x : {0.0, 0.3, 1.0, 1.5, 1.9})
        EXPECT_DOUBLE_EQ(ph::floorHeight_h(ph::PERIOD_OVER_H - x), ph::floorHeight_h(x)) << x;
    EXPECT_DOUBLE_EQ(ph::floorHeight_h(18.7), ph::floorHeight_h(0.7));  // the period repeats
}

TEST(PeriodicHillGeometry, SmoothWallRoughnessMakesTheRoughLogLawTheSmoothOne) {
    // u / u_tau = ln(y / z0) / kappa must equal ln(y u_tau / nu) / kappa + B at any y.
    const double kappa = sim::surface::KAPPA, z0 = ph::smoothWallZ0_h(kappa);
    const double uTau = ph::deanFrictionRatio(ph::REYNOLDS_H * ph::CREST_GAP_OVER_H);
    const double nu = 1.0 / ph::REYNOLDS_H;  // Ub = h = 1
    for (double y : {0.05, 0.2, 1.0})
        EXPECT_NEAR(std::log(y / z0) / kappa, std::log(y * uTau / nu) / kappa + ph::SMOOTH_WALL_B,
                    1e-9);
    // By hand: c_f = 0.073 (5600 * 2.036)^(-1/4) = 7.064e-3, u_tau / Ub = 0.05943,
    // z0 / h = exp(-2.05) / (5600 * 0.05943) = 3.868e-4 (four digits carried).
    EXPECT_NEAR(uTau, 0.05943, 5e-5);
    EXPECT_NEAR(z0, 3.868e-4, 1e-6);
}

TEST(PeriodicHillMeasures, BubbleOfAPiecewiseLinearLineIsItsZeroCrossings) {
    // u = 1, 0.5, -0.5, -1, 1 at x = 0..4: down through 0 at 1.5, up at 3.5.
    const std::vector<WallSample> line = {{0, 1}, {1, 0.5}, {2, -0.5}, {3, -1}, {4, 1}, {5, 2}};
    const Bubble b = bubbleOf(line);
    EXPECT_NEAR(b.separation_h, 1.5, CROSSING_TOLERANCE_H);
    EXPECT_NEAR(b.reattachment_h, 3.5, CROSSING_TOLERANCE_H);
    // Searching from past the separation finds none (the line only rises there).
    EXPECT_FALSE(bubbleOf(line, 2.5).exists());
    const Bubble open = bubbleOf({{0, 1}, {1, -1}, {2, -1}});
    EXPECT_NEAR(open.separation_h, 0.5, CROSSING_TOLERANCE_H);
    EXPECT_TRUE(std::isnan(open.reattachment_h));
    EXPECT_FALSE(bubbleOf({{0, 1}, {1, 2}}).exists());
}

TEST(PeriodicHillMeasures, RmsDifferenceIsTheHandComputedOne) {
    EXPECT_DOUBLE_EQ(rmsDifference({1, 2, 3}, {1, 1, 1}), std::sqrt(5.0 / 3.0));
    EXPECT_THROW((void)rmsDifference({1, 2}, {1}), std::invalid_argument);
    EXPECT_THROW((void)rmsDifference({}, {}), std::invalid_argument);
}

TEST(PeriodicHillData, EmbeddedReferenceHasTheStationsAndBubbleTheReadmeStates) {
    const PeriodicHillData ref = periodicHillReference();
    const std::vector<double> xs = ref.stations();
    const std::vector<double> expected = {0.5, 1, 2, 3, 4, 5, 6, 7, 8};
    ASSERT_EQ(xs.size(), expected.size());
    for (size_t i = 0; i < xs.size(); ++i) EXPECT_DOUBLE_EQ(xs[i], expected[i]);
    // validation/data/README.md: separation 0.21 h, reattachment 4.68 h (two digits).
    EXPECT_NEAR(ref.separation_h, 0.21, 0.005);
    EXPECT_NEAR(ref.reattachment_h, 4.68, 0.005);
    EXPECT_THROW(parsePeriodicHillData("h\n1,2,x,4,5\n", "p.csv", "h\n1,2,3\n", "w.csv"),
                 std::invalid_argument);
    EXPECT_THROW(parsePeriodicHillData("h\n1,2,3,4,5\n", "p.csv", "h\n", "w.csv"),
                 std::invalid_argument);
}

TEST(PeriodicHillStudy, CoarseChainSeparatesBehindTheCrestAndReattachesBeforeTheNextHill) {
    const PeriodicHillData ref = periodicHillReference();
    // Every closure: one the solver refuses (std::logic_error, not built yet) is skipped here
    // and runs, held to the same physics, once it lands.
    for (sim::TurbulenceClosure closure :
         {sim::TurbulenceClosure::MixingLength, sim::TurbulenceClosure::KEpsilon,
          sim::TurbulenceClosure::KOmegaSst}) {
        SCOPED_TRACE(sim::turbulenceClosureName(closure));
        // The bench's chain (5 hills, the fourth measured) at h / 5 takes a minute; three hills
        // with the last one measured keep the test near 10 s and still hold the physics below.
        PeriodicHillOptions o;
        o.cellsPerH = 5, o.hills = 3, o.measuredHill = 2, o.maxIterations = 300;
        o.closure = closure;
        PeriodicHillStudy s;
        try {
            s = runPeriodicHill(o, ref);
        } catch (const std::logic_error& e) {
            std::printf("periodic hill, %s: not built (%s)\n", sim::turbulenceClosureName(closure),
                        e.what());
            continue;
        }
        std::printf(
            "periodic hill, %s, h/%d: %dx%dx%d, %d steps, %.1f s, separation %.2f h, "
            "reattachment %.2f h (reference %.2f), profile RMS %.3f, repeat RMS %.3f\n",
            sim::turbulenceClosureName(closure), o.cellsPerH, s.nx, s.ny, s.nz, s.iterations,
            s.seconds, s.bubble.separation_h, s.bubble.reattachment_h, ref.reattachment_h, s.rmsU,
            s.repeatRmsU);
        // Physics any closure must give behind this hill: reversed flow on the lee floor, the
        // bubble starting downstream of the crest and closing before the next hill's crest.
        ASSERT_TRUE(s.bubble.exists());
        EXPECT_LT(s.minFloorU_Ub, 0.0);
        EXPECT_GT(s.bubble.separation_h, 0.0);
        EXPECT_GT(s.bubble.reattachment_h, s.bubble.separation_h);
        EXPECT_LT(s.bubble.reattachment_h, ph::PERIOD_OVER_H);
        EXPECT_EQ(s.stations.size(), ref.stations().size());
        for (const PeriodicHillStudy::Station& st : s.stations)
            EXPECT_EQ(st.modelU.size(), size_t(st.points));
    }
}

}  // namespace
}  // namespace gale::validation
