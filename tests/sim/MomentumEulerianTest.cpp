/// \file MomentumEulerianTest.cpp
/// The momentum model's Eulerian pseudo-time step (sim/MomentumAdvection.h,
/// MomentumSettings::advection): the operator against exact derivatives and its stated order, its
/// boundedness at the stability limit, uniform flow as an exact fixed point, a steady state that
/// does not depend on the pseudo-time step (the cliff at 100 m/s: MomentumWindTest). Every verdict
/// is computed here from the fields.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "MomentumTestCases.h"
#include "base/ParameterError.h"
#include "sim/AirDomain.h"
#include "sim/Heightfield.h"
#include "sim/MomentumAdvection.h"
#include "sim/MomentumWind.h"

namespace gale::sim {
namespace {

using testcases::expectLogLawColumn, testcases::flatGround, testcases::logWind;

/// A monotone smooth profile along one axis (no extremum, so the limiter stays smooth):
/// tanh((s - 0.5 L) / (0.1 L)) and its derivative, s in metres along a box of length L.
double profile(double s, double L) { return std::tanh((s - 0.5 * L) / (0.1 * L)); }
double profileDerivative(double s, double L) {
    const double t = std::tanh((s - 0.5 * L) / (0.1 * L));
    return (1.0 - t * t) / (0.1 * L);
}

/// RMS error of the convective term (q - out) / dt of the FaceX samples of an n-cell line along
/// `axis` (0: x, 2: z) advected by a constant velocity a_mps along that axis, against a dq/ds of
/// the profile. The value outside the box is the exact profile.
double convectiveError(int n, int axis, double a_mps) {
    constexpr double L = 100.0;
    const double h = L / n;
    const int nx = axis == 0 ? n : 1, nz = axis == 2 ? n : 1;
    const MacGrid g(nx, 1, nz, h, {0.0, 0.0, 0.0});
    std::vector<double> u(g.count(Placement::FaceX), 0.0), v(g.count(Placement::FaceY), 0.0),
        w(g.count(Placement::FaceZ), 0.0);
    (axis == 0 ? u : w).assign((axis == 0 ? u : w).size(), a_mps);
    std::vector<double> q(u.size());
    for (int k = 0; k < nz; ++k)
        for (int i = 0; i <= nx; ++i)
            q[g.faceXIndex(i, 0, k)] =
                profile(g.wsPosition(Placement::FaceX, i, 0, k)[size_t(axis)], L);
    const OutsideValue exact = [&](const Vec3d& p) { return profile(p[size_t(axis)], L); };
    const double dt = 0.1 * h / std::abs(a_mps);
    std::vector<double> out;
    (void)advectEulerian(g, Placement::FaceX, q, {&u, &v, &w}, exact, dt, out);
    double sumSq = 0.0;
    int count = 0;
    for (int k = 0; k < nz; ++k)
        for (int i = 0; i <= nx; ++i) {
            const size_t f = g.faceXIndex(i, 0, k);
            const double s = g.wsPosition(Placement::FaceX, i, 0, k)[size_t(axis)];
            const double e = (q[f] - out[f]) / dt - a_mps * profileDerivative(s, L);
            sumSq += e * e, ++count;
        }
    return std::sqrt(sumSq / count);
}

TEST(MomentumEulerian, ConvectiveTermIsSecondOrderInSmoothFlowAlongXAndZ) {
    // Oracle: the exact derivative of the profile; halving the cells must cut the RMS error by
    // 2^p with p near 2 (the scheme's stated order; the limiter clips a little at the profile's
    // ends, where its curvature changes sign).
    constexpr double MIN_ORDER = 1.7;  // second order less the limiter's local clipping
    for (int axis : {0, 2})
        for (double a : {3.0, -3.0}) {
            const double coarse = convectiveError(32, axis, a), fine = convectiveError(64, axis, a);
            const double order = std::log2(coarse / fine);
            EXPECT_GE(order, MIN_ORDER)
                << "axis " << axis << ", a " << a << ": errors " << coarse << " -> " << fine;
        }
}

TEST(MomentumEulerian, StepAtTheStabilityLimitCreatesNoNewExtrema) {
    // A square wave advected by a diagonal velocity with dt (|u| + |v|) / h + |w| dt / h = the
    // limit: each step is a convex combination (Harten 1983), so every value stays within the
    // initial [min, max] for any number of steps. Oracle: the initial bounds.
    constexpr int N = 24;
    constexpr double H = 1.0;
    const MacGrid g(N, N, 4, H, {0.0, 0.0, 0.0});
    std::vector<double> u(g.count(Placement::FaceX), 2.0), v(g.count(Placement::FaceY), 1.0),
        w(g.count(Placement::FaceZ), 1.0);
    std::vector<double> q(u.size());
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < N; ++j)
            for (int i = 0; i <= N; ++i)
                q[g.faceXIndex(i, j, k)] = (i > 6 && i < 12 && j > 8 && j < 14) ? 1.0 : 0.0;
    const OutsideValue zero = [](const Vec3d&) { return 0.0; };
    const double dt = EULERIAN_MAX_CFL * H / (2.0 + 1.0 + 1.0);
    constexpr double ROUND_OFF = 1e-12;  // sums of a few terms of order 1
    std::vector<double> out;
    for (int n = 0; n < 40; ++n) {
        const double reached = advectEulerian(g, Placement::FaceX, q, {&u, &v, &w}, zero, dt, out);
        EXPECT_NEAR(reached, EULERIAN_MAX_CFL, ROUND_OFF);
        for (double x : out) {
            ASSERT_GE(x, -ROUND_OFF);
            ASSERT_LE(x, 1.0 + ROUND_OFF);
        }
        q.swap(out);
    }
}

TEST(MomentumEulerian, UniformFlowIsAnExactFixedPointOfTheOperator) {
    // Every component constant: every slope is zero, so the step returns the same bits.
    const MacGrid g(10, 6, 5, 2.0, {0.0, 0.0, 0.0});
    std::vector<double> u(g.count(Placement::FaceX), 7.5), v(g.count(Placement::FaceY), -2.25),
        w(g.count(Placement::FaceZ), 0.5);
    const double value[3] = {7.5, -2.25, 0.5};
    const std::vector<double>* src[3] = {&u, &v, &w};
    for (int c = 0; c < 3; ++c) {
        const OutsideValue far = [&](const Vec3d&) { return value[c]; };
        std::vector<double> out;
        (void)advectEulerian(g, Placement(c), *src[c], {&u, &v, &w}, far, 0.05, out);
        EXPECT_EQ(out, *src[c]) << "component " << c;
    }
}

/// The momentum model with the Eulerian step on flat ground: the log law's fixed point.
MomentumSettings eulerian(double step = 0.4) {
    MomentumSettings ms;
    ms.advection = PseudoTimeAdvection::Eulerian;
    ms.eulerianCfl = step;
    return ms;
}

TEST(MomentumEulerian, FlatGroundKeepsTheLogProfileOnCubesAndLayers) {
    // Oracle: the neutral log law, 1 m to 50 m above the ground (expectLogLawColumn).
    for (bool stretched : {false, true}) {
        DomainSpec spec;
        spec.voxelSize_m = 2.0;
        spec.top_m = 62.0;
        spec.momentumModel = true;
        if (stretched) spec.firstCell_m = 0.5, spec.stretchRatio = 1.2;
        const AirDomain domain(flatGround(0.0), spec);
        const MomentumWindResult res = solveMomentumWind(domain, logWind(5.0), eulerian());
        EXPECT_TRUE(res.report.converged) << res.report.message;
        expectLogLawColumn(domain, res.field, 5.0, 0.0, stretched ? "layers" : "cubes");
    }
}

/// A small Gaussian ridge across the wind (H 6 m, sigma 30 m, slope 0.12) in a 2-D box of 8 m
/// cells, 3 across between free-slip side walls; u 10 m above the ground 64 m behind the crest.
double leeSpeed(const MomentumSettings& ms, MomentumReport* report = nullptr) {
    constexpr double H = 6.0, SIGMA = 30.0, CREST = 100.0, CELL = 8.0;
    const int nx = 161, ny = 7;  // 320 m at 2 m spacing
    std::vector<float> z(size_t(nx) * ny);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const double x = 2.0 * i - CREST;
            z[size_t(j) * nx + i] = float(H * std::exp(-x * x / (2 * SIGMA * SIGMA)));
        }
    const Heightfield hf = makeHeightfield(nx, ny, 2.0, std::move(z));
    DomainSpec spec;
    spec.voxelSize_m = CELL;
    spec.top_m = 96.0;
    spec.momentumModel = true;
    spec.closedSidesY = true;
    const AirDomain domain(hf, spec);
    const MomentumWindResult res = solveMomentumWind(domain, logWind(10.0), ms);
    if (report) *report = res.report;
    const double x = CREST + 64.0, y = hf.sizeY_m() / 2;
    return res.field.velocityAt_mps(x, y, hf.sample(x, y) + 10.0)[0];
}

TEST(MomentumEulerian, SteadyStateDoesNotDependOnThePseudoTimeStep) {
    // Oracle: the same ridge solved at two pseudo-time steps a factor 2.5 apart. Each stops at a
    // residual of RESIDUAL, which leaves it within about RESIDUAL U of its fixed point times the
    // steps its slowest mode needs; the two fixed points must agree to that.
    constexpr double RESIDUAL = 1e-5;
    // 1e-3 of U: about four times the gap measured here (0.0026 m/s between 0.2 and 0.5), ten
    // times below the semi-Lagrangian step's spread on a gentle ridge (1.2 % of U, validation.md).
    constexpr double STEP_INDEPENDENCE_TOLERANCE_MPS = 0.01;
    MomentumSettings a = eulerian(0.2), b = eulerian(0.5);
    a.residualTolerance = b.residualTolerance = RESIDUAL;
    a.maxIterations = b.maxIterations = 3000;
    MomentumReport ra, rb;
    const double ua = leeSpeed(a, &ra), ub = leeSpeed(b, &rb);
    // The pseudo-time iterations must have converged (the final tight projection's own verdict,
    // the report's `converged`, is about the divergence it leaves, not the fixed point).
    ASSERT_TRUE(ra.levels.back().converged) << ra.message;
    ASSERT_TRUE(rb.levels.back().converged) << rb.message;
    EXPECT_NEAR(ua, ub, STEP_INDEPENDENCE_TOLERANCE_MPS) << "dt " << ra.dt_s << " and " << rb.dt_s;
}

// The cliff at 100 m/s in 0.5 m cells with the Eulerian step at its limit: tests/sim/
// MomentumWindTest.cpp, MomentumWind.StaysFiniteForHugeWindTinyCellsAndACliff (both steps).

TEST(MomentumEulerian, RefusesAStepAboveItsStabilityLimit) {
    MomentumSettings ms = eulerian(EULERIAN_MAX_CFL * 1.01);
    EXPECT_THROW(ms.validate(), std::logic_error);
    ms.eulerianCfl = 0.0;
    EXPECT_THROW(ms.validate(), std::logic_error);
    EXPECT_EQ(pseudoTimeAdvectionFromName("eulerian"), PseudoTimeAdvection::Eulerian);
    EXPECT_THROW((void)pseudoTimeAdvectionFromName("upwind"), ParameterError);
}

}  // namespace
}  // namespace gale::sim
