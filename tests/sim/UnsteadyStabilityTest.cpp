// The fast subset of the unsteady wind's stability suite (`gale bench stability` runs them all),
// judged here by the tests' own oracles: every velocity finite (scanned here), every air cell's
// net outflow (computed here from the open fractions) below the projection's tolerance, kinetic
// energy (computed here) that does not grow without forcing, and for the cases that start from a
// steady potential flow (an exact steady Euler solution) a field that stays near where it started.
// The vortex studies compare with exact solutions (validation/ExactSolutions.h and
// TranslatingVortex.h, not the code under test) and contrasts between variants.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "validation/AcceptanceLimits.h"
#include "validation/TranslatingVortex.h"
#include "validation/UnsteadyStability.h"

namespace gale::sim {
namespace {

namespace exact = gale::validation::exact;
using validation::burgersCoreRadius_m;
using validation::BurgersSpec;
using validation::BurgersVariant;
using validation::runBurgersVortex;
using validation::runStabilityCase;
using validation::runTranslatingVortex;
using validation::stabilityCaseNames;
using validation::StabilityRun;

// The suite's limits and their reasons: validation/AcceptanceLimits.h (the bench uses them too).
constexpr double DIVERGENCE_TOLERANCE = validation::limits::DIVERGENCE_LIMIT;
constexpr double ENERGY_GROWTH_TOLERANCE = validation::limits::ENERGY_GROWTH_LIMIT;

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

/// max |u_f| dt / h over every face of a field (one component per face): the CFL of a step of
/// dt on that field, computed here from the field and the run's own step, not the solver's report.
double fieldCfl(const StabilityRun& run, const WindField& f) {
    double m = 0.0;
    for (const auto* a : {&f.u_mps(), &f.v_mps(), &f.w_mps()})
        for (double x : *a) m = std::max(m, std::abs(x));
    return m * run.dt_s / run.domain->voxelSize_m();
}

/// The deviation from the start over the ridge only: every face of the air cells within
/// RIDGE_LAYERS cells above the lowest air cell of each column that the ridge raises (its lowest
/// air cell above the box's bottom row), where a semi-Lagrangian trace at a large step crosses
/// cut cells. sqrt(sum theta (u - u_start)^2 / sum theta u_start^2) over those faces; a
/// box-wide RMS dilutes the same error with the far field's untouched faces.
constexpr int RIDGE_LAYERS = 4;
double ridgeDeviation(const StabilityRun& run) {
    const AirDomain& d = *run.domain;
    const WindField& f = run.solver->field();
    double num = 0.0, den = 0.0;
    auto add = [&](double theta, double u, double u0) {
        num += theta * (u - u0) * (u - u0), den += theta * u0 * u0;
    };
    for (int j = 0; j < d.ny(); ++j)
        for (int i = 0; i < d.nx(); ++i) {
            int k0 = 0;
            while (k0 < d.nz() && !d.isAir(i, j, k0)) ++k0;
            if (k0 == 0 || k0 >= d.nz()) continue;  // flat ground or no air: not the ridge
            for (int k = k0; k < std::min(d.nz(), k0 + RIDGE_LAYERS); ++k) {
                add(d.openFractionX(i, j, k), f.u(i, j, k), run.start.u(i, j, k));
                add(d.openFractionZ(i, j, k), f.w(i, j, k), run.start.w(i, j, k));
            }
        }
    return den > 0 ? std::sqrt(num / den) : std::sqrt(num);
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

/// Per case: whether energy may grow (forcing).
struct Oracle {
    bool forced;
};

/// The CFL cases start from the potential flow over a smooth ridge, an exact steady solution,
/// and are judged where a large step matters, over the ridge (ridgeDeviation): after 12 steps
/// the faces there are within 8.7 % (cfl5) and 4.9 % (cfl20) of the start (measured); 15 %, under
/// twice the larger, fails a trace that loses the terrain's cut cells (tens of per cent there),
/// which a box-wide RMS (4-6 %, most faces far from the ridge) would dilute. The cliff and the
/// spike have corners where the potential flow is singular: their discrete start is no smooth
/// solution, and only finiteness, divergence and energy are judged there.
constexpr double RIDGE_DEVIATION_TOLERANCE = 0.15;
/// The potential flow over the 8 m ridge speeds the wind up by far less than this factor, so the
/// computed CFL stays within it of the named one.
constexpr double MAX_SPEED_UP = 2.0;

Oracle oracleFor(const std::string& name) { return {name == "step_gust"}; }

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
    if (r.name.rfind("cfl", 0) == 0) {
        // The named CFL is U dt / h of the 10 m/s wind, and the CFL the run reached, computed
        // here from its start and final fields and its step (the speed-up over the ridge only
        // raises it), is at least that; the box holds at least 10 U dt, so traces cross the
        // terrain inside the box instead of all reading the far field.
        const double named = std::stod(r.name.substr(3)), h = r.domain->voxelSize_m();
        const double reached = std::max(fieldCfl(r, r.start), fieldCfl(r, r.solver->field()));
        std::printf("%-24s CFL computed here %.2f; deviation over the ridge %.3f\n", r.name.c_str(),
                    reached, ridgeDeviation(r));
        EXPECT_NEAR(10.0 * r.dt_s / h, named, 1e-9);
        EXPECT_GE(reached, named);
        EXPECT_LE(reached, named * MAX_SPEED_UP);
        EXPECT_GE(r.domain->nx() * h, 10.0 * 10.0 * r.dt_s);
        // Judged where the large step matters: the faces over the ridge.
        EXPECT_LE(ridgeDeviation(r), RIDGE_DEVIATION_TOLERANCE);
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

TEST(TranslatingVortex, ConvergesToTheExactGalileanSolutionAsTheCellsHalveAtFixedCfl) {
    const double e4 = exact::translatingVortexError(runTranslatingVortex(4, 1.0));
    const double e8 = exact::translatingVortexError(runTranslatingVortex(8, 1.0));
    std::printf("translating Lamb-Oseen, CFL 1: error %.4f (4 cells/core), %.4f (8), order %.2f\n",
                e4, e8, std::log2(e4 / e8));
    namespace L = validation::limits;  // each limit's reason is there
    EXPECT_GE(std::log2(e4 / e8), L::MIN_VORTEX_H_ORDER);
    // An order alone passes two equally wrong runs: the errors themselves, against the exact
    // Galilean solution, stay below the figures the method reaches (docs/unsteady.md) plus
    // their band.
    EXPECT_LE(e4, L::FIGURE_VORTEX_ERROR_4 * (1 + L::VORTEX_ERROR_BAND));
    EXPECT_LE(e8, L::FIGURE_VORTEX_ERROR_8 * (1 + L::VORTEX_ERROR_BAND));
}

TEST(BurgersVortex, CoreHoldsItsRadiusOnlyWhenStrainAndViscosityBalance) {
    // Burgers 1948: r_c^2 = 4 nu / a is steady. Without viscosity the strain contracts the core
    // (r_c e^{-a t / 2}); without strain viscosity spreads it (sqrt(r_c^2 + 4 nu t)). The
    // boundaries carry the exact solution (the strain's pressure on the sides, its outflow
    // through the top), so the strain holds inside the box.
    using S = BurgersSpec;
    const StabilityRun balancedRun = runBurgersVortex(BurgersVariant::Balanced, 4);
    const double balanced = burgersCoreRadius_m(balancedRun) / S::CORE_M;
    const double inviscid =
        burgersCoreRadius_m(runBurgersVortex(BurgersVariant::NoViscosity, 4)) / S::CORE_M;
    const double unstrained =
        burgersCoreRadius_m(runBurgersVortex(BurgersVariant::NoStrain, 4)) / S::CORE_M;
    // The strain on the axis, from the field's w at two heights (exact: w = a z).
    const double half = S::HALF_WIDTH_CORES * S::CORE_M, z0 = S::CORE_M, z1 = 2 * S::CORE_M;
    auto axialStrain = [&](const StabilityRun& r) {
        const WindField& f = r.solver->field();
        return (f.velocityAt_mps(half, half, z1)[2] - f.velocityAt_mps(half, half, z0)[2]) /
               (z1 - z0);
    };
    const double strainAt1 = axialStrain(balancedRun) / S::STRAIN_PER_S;
    // The balanced vortex is an exact steady solution and the run starts on it: its energy
    // (computed here, unweighted sum of squares over the faces) should stay where it started.
    auto energy = [](const WindField& f) {
        double e = 0.0;
        for (const auto* a : {&f.u_mps(), &f.v_mps(), &f.w_mps()})
            for (double x : *a) e += x * x;
        return e;
    };
    const double energyChange =
        energy(balancedRun.solver->field()) / energy(balancedRun.start) - 1.0;
    std::printf(
        "Burgers core / r_c after a t = 1: balanced %.3f; no viscosity %.3f (exact %.3f), no "
        "strain %.3f (exact %.3f); axial strain %.3f a; energy change %+.4f\n",
        balanced, inviscid, std::exp(-0.5 * S::STRAIN_PER_S * S::TIME_S), unstrained,
        std::sqrt(1 + 4 * S::viscosity_m2ps() * S::TIME_S / (S::CORE_M * S::CORE_M)), strainAt1,
        energyChange);
    // At 4 cells per core MacCormack still adds a numerical viscosity of about a sixth of nu
    // (measured: the unstrained core spreads to 1.448 r_c against the exact 1.414), so the
    // balanced core settles a little wide (measured 1.050 at a t = 1, 1.066 when run on to
    // a t = 2) and the inviscid one contracts to 0.79 r_c, not 0.61. With p = 0 on the sides and
    // an open top the strain on the axis fell to 0.66 a and the energy by 24 % (docs/unsteady.md).
    constexpr double CORE_TOLERANCE = validation::limits::BURGERS_CORE_LIMIT;
    constexpr double STRAIN_TOLERANCE = 0.05;  // the axial strain within 5% of a (measured 1.037)
    constexpr double ENERGY_TOLERANCE = 0.02;  // energy within 2% of the exact start's
    constexpr double MIN_CONTRAST = 0.1;  // each unbalanced variant at least 10% r_c away from it
    EXPECT_NEAR(balanced, 1.0, CORE_TOLERANCE);
    EXPECT_NEAR(strainAt1, 1.0, STRAIN_TOLERANCE);
    EXPECT_NEAR(energyChange, 0.0, ENERGY_TOLERANCE);
    EXPECT_LT(inviscid, balanced - MIN_CONTRAST);
    EXPECT_GT(unstrained, balanced + MIN_CONTRAST);
}

}  // namespace
}  // namespace gale::sim
