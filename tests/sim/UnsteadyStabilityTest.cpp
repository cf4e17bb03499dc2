// The fast subset of the unsteady wind's stability suite (`gale bench stability` runs them all),
// judged here by the tests' own oracles: every velocity finite (scanned here), every air cell's
// net outflow (computed here from the open fractions) below the projection's tolerance, kinetic
// energy (computed here) that does not grow without forcing, and for the cases that start from a
// steady potential flow (an exact steady Euler solution) a field that stays near where it started.
// The vortex studies compare with exact solutions written out here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "sim/UnsteadyStability.h"

namespace gale::sim {
namespace {

constexpr double PI = 3.14159265358979323846;
/// The projection solves to 1e-7 relative; its worst cell's net outflow stays far below this
/// (measured <= 2e-7 U).
constexpr double DIVERGENCE_TOLERANCE = 1e-4;
/// Without forcing the energy may not grow; the projection's tolerance leaves round-off.
constexpr double ENERGY_GROWTH_TOLERANCE = 1e-3;

/// Kinetic energy per unit density, 1/2 sum_f theta_f u_f^2 h^3, of a field on the run's domain.
double kineticEnergy(const StabilityRun& run, const WindField& f) {
    const AirDomain& d = *run.domain;
    const double h = d.voxelSize_m();
    const std::vector<double>* a[3] = {&f.u_mps(), &f.v_mps(), &f.w_mps()};
    const std::vector<float>* th[3] = {&d.openFractionsX(), &d.openFractionsY(),
                                       &d.openFractionsZ()};
    double e = 0.0;
    for (int c = 0; c < 3; ++c)
        for (size_t i = 0; i < a[c]->size(); ++i)
            e += double((*th[c])[i]) * (*a[c])[i] * (*a[c])[i];
    return 0.5 * e * h * h * h;
}

/// sqrt(sum theta (u - u_start)^2 / sum theta u_start^2): how far the field moved from its start.
double relativeDeviation(const StabilityRun& run) {
    const AirDomain& d = *run.domain;
    const WindField& f = run.solver->field();
    const std::vector<double>* a[3] = {&f.u_mps(), &f.v_mps(), &f.w_mps()};
    const std::vector<double>* s[3] = {&run.start.u_mps(), &run.start.v_mps(), &run.start.w_mps()};
    const std::vector<float>* th[3] = {&d.openFractionsX(), &d.openFractionsY(),
                                       &d.openFractionsZ()};
    double num = 0.0, den = 0.0;
    for (int c = 0; c < 3; ++c)
        for (size_t i = 0; i < a[c]->size(); ++i) {
            const double diff = (*a[c])[i] - (*s[c])[i];
            num += (*th[c])[i] * diff * diff, den += (*th[c])[i] * (*s[c])[i] * (*s[c])[i];
        }
    return den > 0 ? std::sqrt(num / den) : std::sqrt(num);
}

bool allFinite(const WindField& f) {
    for (const auto* a : {&f.u_mps(), &f.v_mps(), &f.w_mps()})
        for (double x : *a)
            if (!std::isfinite(x)) return false;
    return true;
}

double maxOutflowScaled(const StabilityRun& run) {
    const AirDomain& d = *run.domain;
    const WindField& f = run.solver->field();
    double m = 0.0;
    for (int k = 0; k < d.nz(); ++k)
        for (int j = 0; j < d.ny(); ++j)
            for (int i = 0; i < d.nx(); ++i)
                if (d.isAir(i, j, k))
                    m = std::max(m,
                                 std::abs(d.openOutflux(f.u_mps(), f.v_mps(), f.w_mps(), i, j, k)));
    return m / run.referenceSpeed_mps;
}

/// Per case: the deviation from the starting field allowed (0: not checked) and whether energy
/// may grow (forcing).
struct Oracle {
    double maxDeviation;
    bool forced;
};

/// The CFL cases start from the potential flow over a smooth ridge, an exact steady solution:
/// after 12 steps the field is within 5.5% of it (measured; the error sits in the four cell layers
/// of cut cells next to the ridge, < 0.2% above eight cells), so 10% catches a real regression.
/// The cliff and the spike have corners where the potential flow is singular: their discrete
/// start is no smooth solution, and only finiteness, divergence and energy are judged there.
constexpr double STEADY_DEVIATION_TOLERANCE = 0.1;

Oracle oracleFor(const std::string& name) {
    if (name == "step_gust") return {0.0, true};
    if (name.rfind("cfl", 0) == 0) return {STEADY_DEVIATION_TOLERANCE, false};
    return {0.0, false};
}

class Stability : public ::testing::TestWithParam<std::string> {};

TEST_P(Stability, StaysFiniteDivergenceFreeAndWithinItsEnergyBudget) {
    const StabilityRun r = runStabilityCase(GetParam());
    const Oracle o = oracleFor(r.name);
    const double ke0 = kineticEnergy(r, r.start), ke1 = kineticEnergy(r, r.solver->field());
    const double dev = relativeDeviation(r), div = maxOutflowScaled(r);
    std::printf("%-24s steps %3d  CFL %6.2f  KE %.4g -> %.4g (%+.2f%%)  deviation %.2e  div %.2e\n",
                r.name.c_str(), r.steps, r.maxCfl, ke0, ke1,
                ke0 > 0 ? 100.0 * (ke1 - ke0) / ke0 : 0.0, dev, div);
    EXPECT_TRUE(allFinite(r.solver->field()));
    EXPECT_LE(div, DIVERGENCE_TOLERANCE);
    if (!o.forced) {
        EXPECT_LE(ke1, ke0 * (1.0 + ENERGY_GROWTH_TOLERANCE));
    }
    if (o.maxDeviation > 0) {
        EXPECT_LE(dev, o.maxDeviation);
    }
    if (r.name.rfind("cfl", 0) == 0) {
        // The named CFL is U dt / h of the 10 m/s wind (the speed-up over the ridge only raises
        // the reached one), and the box holds at least 10 U dt, so traces cross the terrain
        // inside the box instead of all reading the far field.
        const double named = std::stod(r.name.substr(3)), h = r.domain->voxelSize_m();
        EXPECT_NEAR(10.0 * r.dt_s / h, named, 1e-9);
        EXPECT_GE(r.maxCfl, named);
        EXPECT_GE(r.domain->nx() * h, 10.0 * 10.0 * r.dt_s);
    }
}

INSTANTIATE_TEST_SUITE_P(FastSubset, Stability,
                         ::testing::ValuesIn(stabilityCaseNames(/*fastOnly=*/true)),
                         [](const ::testing::TestParamInfo<std::string>& caseName) {
                             return caseName.param;
                         });

TEST(Stability, StepGustEnergyStaysBelowTheMeanFlowsAtTheGustPeak) {
    // 5 m/s with a +10 m/s gust: the inflow carries at most (15/5)^2 = 9 times the mean energy.
    const StabilityRun r = runStabilityCase("step_gust");
    constexpr double GUST_FACTOR = 9.0;
    EXPECT_LE(r.keMax_m5ps2, GUST_FACTOR * kineticEnergy(r, r.start));
}

TEST(Stability, UnknownCaseNameThrows) {
    EXPECT_THROW(runStabilityCase("cfl_9000"), std::invalid_argument);
}

// ---- exact solutions -----------------------------------------------------------------------

/// RMS of |u - u_exact| / v_peak over horizontal faces within 2 cores of the exact axis, where
/// u_exact = U e_x + Lamb-Oseen swirl about the axis carried at U (Galilean invariance).
double translatingError(const StabilityRun& r) {
    using S = TranslatingVortexSpec;
    const double t = r.solver->time_s(), cx = S::START_X_M + S::WIND_MPS * t, cy = S::START_Y_M;
    // Lamb-Oseen's peak: v_peak = max_x (1 - e^{-x^2}) / x * Gamma / (2 pi r_c), the maximum found
    // here on a fine grid (0.6382 at x = 1.1209).
    double peakFactor = 0.0;
    for (double x = 0.5; x < 2.0; x += 1e-5)
        peakFactor = std::max(peakFactor, (1 - std::exp(-x * x)) / x);
    const double gamma = S::PEAK_MPS * 2 * PI * S::CORE_M / peakFactor;
    const MacGrid& g = r.solver->grid();
    const WindField& f = r.solver->field();
    double sum = 0.0;
    int count = 0;
    for (int c = 0; c < 2; ++c) {
        const auto n = g.dims(Placement(c));
        const std::vector<double>& a = c == 0 ? f.u_mps() : f.v_mps();
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    const Vec3d p = g.wsPosition(Placement(c), i, j, k);
                    const double dx = p[0] - cx, dy = p[1] - cy, r2 = dx * dx + dy * dy;
                    if (r2 > 4 * S::CORE_M * S::CORE_M) continue;
                    const double vr = r2 > 0 ? gamma / (2 * PI * r2) *
                                                   (1 - std::exp(-r2 / (S::CORE_M * S::CORE_M)))
                                             : 0;
                    const double exact = c == 0 ? S::WIND_MPS - vr * dy : vr * dx;
                    const double d = a[size_t(i) + size_t(n[0]) * (j + size_t(n[1]) * k)] - exact;
                    sum += d * d, ++count;
                }
    }
    return std::sqrt(sum / count) / S::PEAK_MPS;
}

TEST(TranslatingVortex, ConvergesToTheExactGalileanSolutionAsTheCellsHalveAtFixedCfl) {
    const double e4 = translatingError(runTranslatingVortex(4, 1.0));
    const double e8 = translatingError(runTranslatingVortex(8, 1.0));
    std::printf("translating Lamb-Oseen, CFL 1: error %.4f (4 cells/core), %.4f (8), order %.2f\n",
                e4, e8, std::log2(e4 / e8));
    /// Semi-Lagrangian with trilinear interpolation at fixed CFL is first order (h^2 / dt ~ h).
    constexpr double MIN_ORDER = 0.7;
    EXPECT_GE(std::log2(e4 / e8), MIN_ORDER);
}

TEST(BurgersVortex, CoreHoldsItsRadiusOnlyWhenStrainAndViscosityBalance) {
    // Burgers 1948: r_c^2 = 4 nu / a is steady. Without viscosity the strain contracts the core
    // (r_c e^{-a t / 2}); without strain viscosity spreads it (sqrt(r_c^2 + 4 nu t)).
    using S = BurgersSpec;
    const double balanced =
        burgersCoreRadius_m(runBurgersVortex(BurgersVariant::Balanced, 4)) / S::CORE_M;
    const double inviscid =
        burgersCoreRadius_m(runBurgersVortex(BurgersVariant::NoViscosity, 4)) / S::CORE_M;
    const double unstrained =
        burgersCoreRadius_m(runBurgersVortex(BurgersVariant::NoStrain, 4)) / S::CORE_M;
    std::printf(
        "Burgers core / r_c after a t = %.1f: balanced %.3f, no viscosity %.3f (exact %.3f), no "
        "strain %.3f "
        "(exact %.3f)\n",
        S::STRAIN_PER_S * S::TIME_S, balanced, inviscid,
        std::exp(-0.5 * S::STRAIN_PER_S * S::TIME_S), unstrained,
        std::sqrt(1 + 4 * S::viscosity_m2ps() * S::TIME_S / (S::CORE_M * S::CORE_M)));
    // At 4 cells per core the interpolation adds a numerical viscosity of about nu / 4 (measured:
    // the unstrained core spreads to 1.50 r_c against the exact 1.41), and the p = 0 open top and
    // sides cannot carry the strain's pressure, so the strain inside the box weakens (to 0.73 a
    // on the balanced axis, docs/unsteady.md): the inviscid core contracts far less than the exact
    // e^{-a t / 2}. The claim tested is that the balance holds the core where either force alone
    // moves it.
    constexpr double CORE_TOLERANCE = 0.1;  // the balanced core within 10% of r_c after a t = 1
    constexpr double MIN_CONTRAST = 0.1;    // each unbalanced variant at least 10% r_c away from it
    EXPECT_NEAR(balanced, 1.0, CORE_TOLERANCE);
    EXPECT_LT(inviscid, balanced - MIN_CONTRAST);
    EXPECT_GT(unstrained, balanced + MIN_CONTRAST);
}

}  // namespace
}  // namespace gale::sim
