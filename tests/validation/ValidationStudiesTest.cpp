// Each validation study at a quick size, held to the figures docs/validation.md and
// docs/unsteady.md state (validation/AcceptanceLimits.h holds each figure, its band and why):
// a change that moves a stated figure past its band fails here, and the page must be re-measured.
// Every figure is computed by the study from its own oracle (an exact solution, the measured
// campaign, the model's own upwind column), not read from the solver's report.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "validation/AcceptanceLimits.h"
#include "validation/CaoTamuraStudy.h"
#include "validation/CrestStudy.h"
#include "validation/HemisphereStudy.h"
#include "validation/JacksonHuntStudy.h"
#include "validation/LambOseenStudy.h"
#include "validation/PseudoTimeStudy.h"
#include "validation/ValidationData.h"

namespace gale::validation {
namespace {

namespace L = limits;

/// |actual / stated - 1| <= band, with the numbers in the message.
::testing::AssertionResult withinRelative(double actual, double stated, double band) {
    if (std::abs(actual / stated - 1.0) <= band) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << actual << " is not within " << 100 * band << " % of " << stated;
}

TEST(HemisphereStudy, NearSurfaceErrorsAndOrderAreThePagesAtFourAndEightCellsPerRadius) {
    const HemisphereStudy e4 = runHemisphere({4}), e8 = runHemisphere({8});
    std::printf("hemisphere near L2: %.3e (R/h 4), %.3e (R/h 8), order %.2f\n", e4.nearL2,
                e8.nearL2, observedOrder({4, 8}, {e4.nearL2, e8.nearL2}));
    EXPECT_TRUE(e4.converged && e8.converged);
    EXPECT_TRUE(withinRelative(e4.nearL2, L::FIGURE_HEMISPHERE_ERROR_4, L::HEMISPHERE_ERROR_BAND));
    EXPECT_TRUE(withinRelative(e8.nearL2, L::FIGURE_HEMISPHERE_ERROR_8, L::HEMISPHERE_ERROR_BAND));
    EXPECT_GE(observedOrder({4, 8}, {e4.nearL2, e8.nearL2}), L::MIN_HEMISPHERE_ORDER);
}

TEST(LambOseenStudy, TranslatingVortexErrorsAndOrderAreThePagesAtCfl1) {
    const LambOseenStudy s = runLambOseen({});  // 4 and 8 cells per core, CFL 1
    ASSERT_EQ(s.rows.size(), 2u);
    std::printf("translating Lamb-Oseen: error %.4f (4 cells/core), %.4f (8), order %.2f\n",
                s.rows[0].error, s.rows[1].error, s.lastOrder());
    EXPECT_TRUE(withinRelative(s.rows[0].error, L::FIGURE_VORTEX_ERROR_4, L::VORTEX_ERROR_BAND));
    EXPECT_TRUE(withinRelative(s.rows[1].error, L::FIGURE_VORTEX_ERROR_8, L::VORTEX_ERROR_BAND));
    EXPECT_GE(s.lastOrder(), L::MIN_VORTEX_H_ORDER);
}

TEST(JacksonHuntStudy, CrestCoefficientsAtSixMetresAreThePagesAndNearTheGuideline) {
    for (int i = 0; i < 3; ++i) {
        const double H = jacksonhunt::HEIGHTS_M[i];
        JacksonHuntOptions o;
        o.H_m = H;
        const JacksonHuntStudy s = runJacksonHunt(o);
        const double c = s.coefficient(0, H);
        std::printf("Jackson-Hunt H = %.0f m: Delta S / (H/L) at 6 m %.3f (page %.2f), %d steps\n",
                    H, c, L::FIGURE_JH_COEFFICIENT_6M[i], s.iterations);
        EXPECT_TRUE(s.converged);
        EXPECT_NEAR(c, L::FIGURE_JH_COEFFICIENT_6M[i], L::JH_COEFFICIENT_BAND) << "H = " << H;
        EXPECT_GE(c, L::JH_GUIDELINE_LOW);
        EXPECT_LE(c, L::JH_GUIDELINE_HIGH);
        // The speed-up falls with height above the crest, as the theory's does.
        EXPECT_GT(s.speedup[0], s.speedup[2]) << "H = " << H;
    }
}

TEST(CaoTamuraStudy, EmbeddedCampaignHasThePagesPoints) {
    ASSERT_NE(embeddedData("cao-tamura-2006-ridge.csv"), nullptr);
    EXPECT_EQ(embeddedData("no-such-file.csv"), nullptr);
    const auto data = caoTamuraMeasurements();
    int offFoot = 0, leeDeficits = 0;
    for (const RidgeMeasurement& m : data) {
        if (m.xOverH > -2.5 + 1e-9) ++offFoot;
        if (m.xOverH > 0 && m.speedup < 0) ++leeDeficits;
    }
    EXPECT_EQ(offFoot, L::FIGURE_CT_POINTS);
    EXPECT_EQ(leeDeficits, L::FIGURE_CT_LEE_POINTS);
    EXPECT_THROW(parseRidgeMeasurements("header\n0,1,x,3,4,5\n", "bad.csv"), std::invalid_argument);
}

TEST(CaoTamuraStudy, MomentumModelAtFiveCellsPerHeightGivesThePagesCrestRmsAndLee) {
    const auto data = caoTamuraMeasurements();
    CaoTamuraOptions o;  // momentum, H / h = 5, the published inflow, cfl 2
    const CaoTamuraStudy s = runCaoTamura(o, data);
    std::printf(
        "Cao-Tamura momentum H/h 5: crest %.3f, RMS %.3f over %d, lee same sign %d, within %d "
        "of %d, %d steps, %.1f s\n",
        s.crestSpeedup, s.rmsSpeedupError, s.points, s.leeSameSign, s.leeWithin, s.leePoints,
        s.iterations, s.seconds);
    // The finest level converges; its 16 m coarse start does not (its wake's residual cycles
    // at about 1e-3 until the step limit, docs/validation.md), so the solve as a whole is
    // reported not converged.
    ASSERT_FALSE(s.levels.empty());
    EXPECT_TRUE(s.levels.back().converged);
    EXPECT_EQ(s.converged, std::all_of(s.levels.begin(), s.levels.end(),
                                       [](const StudyLevel& l) { return l.converged; }));
    EXPECT_EQ(s.points, L::FIGURE_CT_POINTS);
    EXPECT_NEAR(s.crestSpeedup, L::FIGURE_CT_CREST_SPEEDUP, L::CT_SPEEDUP_BAND);
    EXPECT_LE(std::abs(s.crestSpeedup / MEASURED_CREST_SPEEDUP - 1.0),
              L::TARGET_CREST_RELATIVE_ERROR);
    EXPECT_NEAR(s.rmsSpeedupError, L::FIGURE_CT_RMS, L::CT_RMS_BAND);
    EXPECT_EQ(s.leePoints, L::FIGURE_CT_LEE_POINTS);
    EXPECT_NEAR(s.leeSameSign, L::FIGURE_CT_LEE_SAME_SIGN, L::CT_LEE_COUNT_BAND);
    EXPECT_NEAR(s.leeWithin, L::FIGURE_CT_LEE_WITHIN, L::CT_LEE_COUNT_BAND);
}

TEST(CaoTamuraStudy, MassConsistentModelGivesThePagesRmsAndNoLeeDeficit) {
    CaoTamuraOptions o;
    o.momentum = false;
    const CaoTamuraStudy s = runCaoTamura(o, caoTamuraMeasurements());
    std::printf("Cao-Tamura mass-consistent H/h 5: RMS %.3f, lee same sign %d\n", s.rmsSpeedupError,
                s.leeSameSign);
    EXPECT_NEAR(s.rmsSpeedupError, L::FIGURE_CT_MC_RMS, L::CT_RMS_BAND);
    EXPECT_EQ(s.leeSameSign, 0);  // free slip: nothing slows the air behind the ridge
}

/// The crest's u / U_inf and speed-up of one experiment against the page's figures.
void expectCrest(const CrestCase& c, const double (&uinf)[3], const double (&speedup)[3]) {
    const CrestStudy r = runCrest({c, /*cellsPerH=*/5, std::nullopt});
    std::printf("crest, %s: u/U_inf %.3f / %.3f / %.3f, speed-up %.3f / %.3f / %.3f, %d steps\n",
                c.name.c_str(), r.crestUinf[0], r.crestUinf[1], r.crestUinf[2], r.crestSpeedup[0],
                r.crestSpeedup[1], r.crestSpeedup[2], r.steps);
    EXPECT_TRUE(r.converged) << c.name;
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(r.crestUinf[i], uinf[i], L::CREST_UINF_BAND) << c.name << ", height " << i;
        EXPECT_NEAR(r.crestSpeedup[i], speedup[i], L::CT_SPEEDUP_BAND) << c.name << ", " << i;
    }
}

TEST(CrestStudy, PotentialFlowMassConsistentAndEulerCrestsAreThePages) {
    using ridge::Inflow;
    expectCrest({"potential flow", false, Inflow::Uniform, false, false},
                L::FIGURE_CREST_POTENTIAL_UINF, L::FIGURE_CREST_POTENTIAL_SPEEDUP);
    expectCrest({"mass-consistent", false, Inflow::Published, false, false},
                L::FIGURE_CREST_MASS_CONSISTENT_UINF, L::FIGURE_CREST_MASS_CONSISTENT_SPEEDUP);
    expectCrest({"Euler", true, Inflow::Published, false, false}, L::FIGURE_CREST_EULER_UINF,
                L::FIGURE_CREST_EULER_SPEEDUP);
}

/// The gentle ridge's lee speed with one pseudo-time step (at most 872 steps at the quick size).
double gentleLee_mps(sim::PseudoTimeAdvection a, double step) {
    PseudoTimeOptions o;
    o.ridge = pseudotime::GENTLE, o.advection = a, o.step = step;
    const PseudoTimeStudy s = runPseudoTime(o);
    std::printf("pseudo-time gentle ridge, %s %.2f: lee %.4f m/s, crest %.4f, %d steps, %.1f s\n",
                sim::pseudoTimeAdvectionName(a), step, s.lee_mps, s.crest_mps, s.iterations,
                s.seconds);
    EXPECT_TRUE(s.converged);
    return s.lee_mps;
}

TEST(PseudoTimeStudy, SemiLagrangianLeeMovesWithItsCflAsThePageStates) {
    using A = sim::PseudoTimeAdvection;
    const double sl1 = gentleLee_mps(A::SemiLagrangian, 1.0);
    const double sl2 = gentleLee_mps(A::SemiLagrangian, 2.0);
    EXPECT_NEAR(sl1, L::FIGURE_PT_SEMI_LAGRANGIAN_LEE_1_MPS, L::PT_LEE_BAND_MPS);
    EXPECT_NEAR(sl2, L::FIGURE_PT_SEMI_LAGRANGIAN_LEE_2_MPS, L::PT_LEE_BAND_MPS);
    // The defect the page states: the fixed point carries the step.
    EXPECT_GE(std::abs(sl2 - sl1), L::MIN_SEMI_LAGRANGIAN_LEE_SPREAD_MPS);
}

TEST(PseudoTimeStudy, EulerianLeeAtItsLargestStepIsThePagesAtAnother) {
    // The page's Eulerian lee at step 0.4 (a run of its own); this run at 0.5: a steady state
    // free of the step agrees with it within the spread the page allows.
    const double eu5 = gentleLee_mps(sim::PseudoTimeAdvection::Eulerian, 0.5);
    EXPECT_NEAR(eu5, L::FIGURE_PT_EULERIAN_LEE_05_MPS, L::PT_LEE_BAND_MPS);
    EXPECT_LE(std::abs(eu5 - L::FIGURE_PT_EULERIAN_LEE_04_MPS), L::MAX_EULERIAN_LEE_SPREAD_MPS);
}

}  // namespace
}  // namespace gale::validation
