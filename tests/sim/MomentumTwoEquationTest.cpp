/// \file MomentumTwoEquationTest.cpp
/// The two-equation closures, k-epsilon and k-omega SST (sim/TwoEquation.h through
/// sim/MomentumTurbulence.h), against Richards and Hoxey's (1993) neutral surface layer, with no
/// body force: from the mass-consistent start, from a uniform start and from a start 20 % off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "MomentumTestCases.h"
#include "sim/AirDomain.h"
#include "sim/MomentumWind.h"
#include "sim/SteadyWind.h"
#include "sim/SurfaceLayer.h"
#include "sim/UnsteadyWind.h"

namespace gale::sim {
namespace {

using testcases::expectLogLawColumn, testcases::flatGround, testcases::logWind;

/// Richards and Hoxey's k = u*^2 / sqrt(C_mu) for the 5 m/s log wind (u* from its 10 m speed).
double richardsHoxeyTke(double speed_mps) {
    const double uStar = surface::frictionVelocity_mps(speed_mps, 10.0, 0.03);
    return uStar * uStar / 0.3;
}

MomentumSettings withClosure(TurbulenceClosure closure) {
    MomentumSettings m;
    m.turbulence = closure;
    return m;
}

constexpr TurbulenceClosure TWO_EQUATION[] = {TurbulenceClosure::KEpsilon,
                                              TurbulenceClosure::KOmegaSst};

/// The box's middle column: k within TKE_TOLERANCE of Richards and Hoxey's from 1 m to 50 m.
void expectRichardsHoxeyTke(const AirDomain& domain, const std::vector<double>& tke,
                            double speed_mps, double groundZ_m) {
    // The discrete balance near the wall moves k a few per cent off the exact constant.
    constexpr double TKE_TOLERANCE = 0.05;
    ASSERT_EQ(tke.size(), domain.layout().cellCount());
    const double exact = richardsHoxeyTke(speed_mps);
    const int i = domain.nx() / 2, j = domain.ny() / 2;
    int checked = 0;
    for (int k = 0; k < domain.nz(); ++k) {
        const double z = domain.layout().zCentre_m(k) - groundZ_m;
        if (!domain.isAir(i, j, k) || z < 1.0 || z > 50.0) continue;
        EXPECT_NEAR(tke[domain.layout().cellIndex(i, j, k)] / exact, 1.0, TKE_TOLERANCE)
            << "z = " << z << " m";
        ++checked;
    }
    EXPECT_GE(checked, 20);
}

class TwoEquationFlatGround
    : public ::testing::TestWithParam<std::tuple<TurbulenceClosure, double>> {};

TEST_P(TwoEquationFlatGround, KeepsTheLogProfileAndRichardsHoxeyTkeWithoutABodyForce) {
    const auto [closure, ground] = GetParam();
    AirDomain domain(flatGround(ground), {/*voxelSize_m=*/2.0, /*top_m=*/62.0});
    const MomentumWindResult res = solveMomentumWind(domain, logWind(5.0), withClosure(closure));
    EXPECT_TRUE(res.report.converged) << res.report.message;
    // Oracle: the neutral log law, 1 m to 50 m above the ground (expectLogLawColumn), and
    // k = u*^2 / sqrt(C_mu).
    expectLogLawColumn(domain, res.field, 5.0, ground, turbulenceClosureName(closure), 24);
    expectRichardsHoxeyTke(domain, res.tke_m2ps2, 5.0, ground);
}

// Ground on a cell face, and ground cutting the first cell (0.7 m into a 2 m cell).
INSTANTIATE_TEST_SUITE_P(MomentumTwoEquation, TwoEquationFlatGround,
                         ::testing::Combine(::testing::ValuesIn(TWO_EQUATION),
                                            ::testing::Values(0.0, 0.7)));

/// Steps the unsteady solver with a two-equation surface layer from `start` (inflow: the
/// mass-consistent log wind) until its field changes by less than 1e-6 U per step.
WindField settle(const AirDomain& domain, TurbulenceClosure closure, const WindField& start,
                 int maxSteps) {
    const AmbientWind wind = logWind(5.0);
    const SteadyWindResult steady = solveSteadyWind(domain, wind, {}, {});
    UnsteadySettings us;
    us.dt_s = 0.4;
    us.openTop = true;
    us.surfaceLayer.enabled = true;
    us.surfaceLayer.roughness_m = wind.roughness_m;
    us.surfaceLayer.balanced = wind;
    us.surfaceLayer.closure = closure;
    UnsteadyWindSolver solver(domain, steady.field, us, 5.0);
    solver.resetState(start);
    for (int n = 0; n < maxSteps; ++n) {
        const std::vector<double> before = solver.field().u_mps();
        const StepReport r = solver.step(us.dt_s);
        EXPECT_TRUE(r.finite);
        double change = 0.0;
        for (size_t f = 0; f < before.size(); ++f)
            change = std::max(change, std::abs(solver.field().u_mps()[f] - before[f]));
        if (change < 1e-6 * 5.0) break;
    }
    return solver.field();
}

class TwoEquationSettles : public ::testing::TestWithParam<TurbulenceClosure> {};

TEST_P(TwoEquationSettles, ToTheLogLawFromAUniformStartAndFromOneTwentyPercentOff) {
    const TurbulenceClosure closure = GetParam();
    AirDomain domain(flatGround(0.0), {/*voxelSize_m=*/2.0, /*top_m=*/62.0});
    const SteadyWindResult steady = solveSteadyWind(domain, logWind(5.0), {}, {});
    WindField uniform = steady.field, off = steady.field;
    for (double& u : uniform.u_mps()) u = 5.0;
    for (double& u : off.u_mps()) u *= 1.2;
    constexpr int MAX_STEPS = 3000;  // 1200 s: many crossings and diffusion times of the box
    expectLogLawColumn(domain, settle(domain, closure, uniform, MAX_STEPS), 5.0, 0.0,
                       "uniform start", 24);
    expectLogLawColumn(domain, settle(domain, closure, off, MAX_STEPS), 5.0, 0.0, "20 % fast start",
                       24);
}

INSTANTIATE_TEST_SUITE_P(MomentumTwoEquation, TwoEquationSettles,
                         ::testing::ValuesIn(TWO_EQUATION));

}  // namespace
}  // namespace gale::sim
