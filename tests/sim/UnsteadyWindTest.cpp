// The unsteady wind: the steady field is a fixed point, projection keeps every step
// divergence-free, gust fronts arrive at distance / mean speed, whirlwinds are carried with the
// right sense of rotation, and a viscous Lamb-Oseen vortex decays as the exact solution.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <vector>

#include "SimTestUtil.h"
#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/AirDomain.h"
#include "sim/SteadyWind.h"
#include "sim/UnsteadyWind.h"
#include "validation/ExactSolutions.h"

namespace gale::sim {
namespace {

namespace exact = gale::validation::exact;

using test::tight;
using test::uniformWind;

using gale::PI;

Heightfield terrain(TerrainKind kind, double sx, double sy, double height_m = 0.0,
                    double radius_m = 10.0) {
    TerrainSpec s;
    s.kind = kind;
    s.sizeX_m = sx, s.sizeY_m = sy;
    s.spacing_m = 1.0;
    s.height_m = height_m, s.radius_m = radius_m;
    s.centerX_m = sx / 2, s.centerY_m = sy / 2;
    return makeTerrain(s);
}

/// Flat ground of sx x sy metres under a uniform wind of speed_mps, its domain (2 m cells, the
/// automatic top) and the steady field an unsteady run starts from.
struct FlatGroundWind {
    FlatGroundWind(double sx, double sy, double speed_mps)
        : domain(terrain(TerrainKind::Flat, sx, sy), {2.0, {}, 1e9}),
          steady(solveSteadyWind(domain, uniformWind(speed_mps), {}, tight())) {}
    AirDomain domain;
    SteadyWindResult steady;
};

/// Divergence after a projection, |div u| h / U: the solve stops at 1e-7 relative residual here,
/// so the flux imbalance is far below this.
constexpr double DIVERGENCE_TOLERANCE = 1e-4;

TEST(UnsteadyWind, UniformFlowOverFlatGroundStaysUniform) {
    // The steady field is the mean flow and the far field: with nothing else the state is fixed.
    const FlatGroundWind flow(40, 20, 5.0);
    UnsteadySettings s;
    s.dt_s = 0.7;  // CFL 1.75
    UnsteadyWindSolver solver(flow.domain, flow.steady.field, s, 5.0);
    for (int n = 0; n < 5; ++n) {
        const StepReport r = solver.step(solver.nextDt_s());
        EXPECT_TRUE(r.finite);
        EXPECT_LT(r.maxDivergenceScaled, DIVERGENCE_TOLERANCE);
    }
    // Uniform flow is reproduced to the steady solve's tolerance (round-off of 1e-9 solves).
    constexpr double UNIFORM_TOLERANCE_MPS = 1e-6;
    for (double u : solver.field().u_mps()) EXPECT_NEAR(u, 5.0, UNIFORM_TOLERANCE_MPS);
    for (double w : solver.field().w_mps()) EXPECT_NEAR(w, 0.0, UNIFORM_TOLERANCE_MPS);
}

TEST(UnsteadyWind, ProjectionKeepsEveryStepDivergenceFreeOverAHillAtLargeCfl) {
    const Heightfield hf = terrain(TerrainKind::GaussianHill, 48, 32, 8.0, 6.0);
    AirDomain d(hf, {2.0, {}, 1e9});
    const auto steady = solveSteadyWind(d, uniformWind(6.0), {}, tight());
    UnsteadySettings s;
    s.cfl = 10.0;
    s.maxDt_s = 100.0;
    s.projection.relativeTolerance = 1e-7;
    GustEvent g;
    g.peak_mps = 4.0, g.duration_s = 6.0, g.envelope = GustEnvelope::Spline;
    s.gusts.push_back(g);
    UnsteadyWindSolver solver(d, steady.field, s, 6.0);
    const auto reps = solver.advanceTo(8.0);
    ASSERT_FALSE(reps.empty());
    for (const StepReport& r : reps) {
        EXPECT_TRUE(r.finite);
        EXPECT_LT(r.maxDivergenceScaled, DIVERGENCE_TOLERANCE) << "t = " << r.t_s;
        EXPECT_GT(r.cfl, 9.0);  // the adaptive step used the CFL the settings asked for
    }
}

TEST(UnsteadyWind, GustFrontArrivesAtDistanceOverMeanSpeed) {
    // Flat ground, uniform 5 m/s: a weak 1-cosine gust (0.5 m/s, so it travels with the mean
    // speed rather than its own) enters at x = 0 at t = 0. Its peak passes two probes 100 m apart
    // at grass height 20 s apart.
    const double U = 5.0;
    const FlatGroundWind flow(200, 24, U);
    UnsteadySettings s;
    s.dt_s = 0.4;
    GustEvent g;
    g.peak_mps = 0.5, g.duration_s = 6.0, g.envelope = GustEnvelope::OneMinusCosine;
    s.gusts.push_back(g);
    UnsteadyWindSolver solver(flow.domain, flow.steady.field, s, U);
    const double x1 = 50.0, x2 = 150.0, y = 12.0, z = 1.0;
    double peak1 = -1, peak2 = -1, t1 = 0, t2 = 0;
    while (solver.time_s() < 45.0) {
        const StepReport r = solver.step(s.dt_s);
        ASSERT_TRUE(r.finite);
        const double a = solver.field().velocityAt_mps(x1, y, z)[0],
                     b = solver.field().velocityAt_mps(x2, y, z)[0];
        if (a > peak1) peak1 = a, t1 = r.t_s;
        if (b > peak2) peak2 = b, t2 = r.t_s;
    }
    std::printf(
        "gust peak at x = %.0f m: t = %.1f s (%.2f m/s); at x = %.0f m: t = %.1f s (%.2f m/s)\n",
        x1, t1, peak1, x2, t2, peak2);
    // Arrival from the inflow: the peak enters at duration / 2 and travels x / U.
    const double expected1 = g.duration_s / 2 + x1 / U, expected2 = g.duration_s / 2 + x2 / U;
    // Between the probes 5 % of the travel time (measured 2 %: interpolation smears the front);
    // from the inflow 10 % (measured 8 % early: the projection's instantaneous pressure response
    // lets the front reach the first probe a step or two ahead of the air that carries it).
    constexpr double TRAVEL_TOLERANCE_FRACTION = 0.05;
    constexpr double ARRIVAL_TOLERANCE_FRACTION = 0.10;
    EXPECT_NEAR(t2 - t1, (x2 - x1) / U, TRAVEL_TOLERANCE_FRACTION * (x2 - x1) / U);
    EXPECT_NEAR(t1, expected1, ARRIVAL_TOLERANCE_FRACTION * expected1);
    EXPECT_NEAR(t2, expected2, ARRIVAL_TOLERANCE_FRACTION * expected2);
    EXPECT_GT(peak2, U + 0.25 * g.peak_mps);  // the gust is still there downstream
}

TEST(UnsteadyWind, RegionGustMovesAtItsSpeedAndArrivesLaterDownstream) {
    // A gust that enters as a moving forcing disc (radius 12 m) rather than through the inflow:
    // its disc travels at 5 m/s, so the peak passes probes 60 m apart about 12 s apart.
    const double U = 5.0;
    const FlatGroundWind flow(160, 40, U);
    UnsteadySettings s;
    s.dt_s = 0.5;
    GustEvent g;
    g.entry = GustEntry::Region, g.regionRadius_m = 12.0, g.peak_mps = 3.0, g.duration_s = 30.0;
    g.envelope = GustEnvelope::Step;
    s.gusts.push_back(g);
    UnsteadyWindSolver solver(flow.domain, flow.steady.field, s, U);
    const auto c0 = solver.regionCentre_m(g, 0.0);
    EXPECT_NEAR(c0[0], 0.0, 1e-9);  // the upwind edge, through the centre
    EXPECT_NEAR(c0[1], 20.0, 1e-9);
    const double x1 = 40.0, x2 = 100.0, y = 20.0, z = 1.0;
    double p1 = -1, p2 = -1, t1 = 0, t2 = 0, keMax = 0;
    double injected = 0;
    const double ke0 = solver.kineticEnergy_m5ps2();
    while (solver.time_s() < 26.0) {
        const StepReport r = solver.step(s.dt_s);
        ASSERT_TRUE(r.finite);
        injected += std::max(0.0, r.forcingEnergy_m5ps2);
        keMax = std::max(keMax, r.kineticEnergy_m5ps2);
        const double a = solver.field().velocityAt_mps(x1, y, z)[0],
                     b = solver.field().velocityAt_mps(x2, y, z)[0];
        if (a > p1) p1 = a, t1 = r.t_s;
        if (b > p2) p2 = b, t2 = r.t_s;
    }
    std::printf(
        "region gust: peak %.2f m/s at x = %.0f m, t = %.1f s; %.2f m/s at x = %.0f m, t = %.1f "
        "s\n",
        p1, x1, t1, p2, x2, t2);
    // The disc's centre passes the probes at x / 5 m/s (8 s, 20 s). Measured 8 s and 18 s: its
    // full-strength half reaches a probe 6 m (1.2 s) before the centre, the relaxation lags by
    // about 0.5 s, and the pushed air runs ahead; 3 s allows for all three.
    constexpr double REGION_ARRIVAL_TOLERANCE_S = 3.0;
    EXPECT_NEAR(t2 - t1, (x2 - x1) / U, REGION_ARRIVAL_TOLERANCE_S);
    EXPECT_GT(p1, U + 0.5 * g.peak_mps);
    EXPECT_LE(keMax, ke0 + injected);  // bounded by what the forcing put in
}

struct Found {
    double x, y, omega;
};

Found strongestVortex(const UnsteadyWindSolver& s, int k, bool positive) {
    Found best{0, 0, 0};
    const MacGrid& g = s.grid();
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const double om = verticalVorticity(g, s.velocity(), i, j, k);
            if ((positive ? om : -om) > (positive ? best.omega : -best.omega)) {
                const auto p = g.wsPosition(Placement::Cell, i, j, k);
                best = {p[0], p[1], om};
            }
        }
    return best;
}

TEST(UnsteadyWind, WhirlwindIsCarriedByTheWindWithItsSenseOfRotation) {
    const Heightfield hf = terrain(TerrainKind::Flat, 120, 60);
    AirDomain d(hf, {2.0, std::optional<double>(16.0), 1e9});
    const double U = 3.0, T = 10.0;
    const auto steady = solveSteadyWind(d, uniformWind(U), {}, tight());
    for (double sense : {+1.0, -1.0}) {
        UnsteadySettings s;
        s.advection = AdvectionScheme::MacCormack;
        s.dt_s = 0.5;
        Whirlwind w;
        w.wsPosition_m = {30.0, 30.0};
        w.coreRadius_m = 4.0;
        w.peakSpeed_mps = sense * 4.0;
        w.profile = VortexProfile::LambOseen;
        s.whirlwinds.push_back(w);
        UnsteadyWindSolver solver(d, steady.field, s, U);
        const auto reps = solver.advanceTo(T);
        for (const StepReport& r : reps) ASSERT_TRUE(r.finite);
        const Found f = strongestVortex(solver, 2, sense > 0);
        const double xExpected = 30.0 + U * T;
        std::printf(
            "sense %+g: vortex at (%.1f, %.1f), omega_z %.3f 1/s; marker at (%.1f, %.1f); expected "
            "x %.1f\n",
            sense, f.x, f.y, f.omega, solver.whirlwindAxes_m()[0][0],
            solver.whirlwindAxes_m()[0][1], xExpected);
        // Core position within two cells (the vorticity maximum is found on cell centres).
        constexpr double POSITION_TOLERANCE_M = 4.0;
        EXPECT_NEAR(f.x, xExpected, POSITION_TOLERANCE_M);
        EXPECT_NEAR(f.y, 30.0, POSITION_TOLERANCE_M);
        EXPECT_NEAR(solver.whirlwindAxes_m()[0][0], xExpected, POSITION_TOLERANCE_M);
        EXPECT_GT(sense * f.omega, 0.0);
        const double gamma =
            circulationAround(solver.grid(), solver.velocity(), {f.x, f.y}, 8.0, 5.0);
        EXPECT_GT(sense * gamma, 0.0) << "circulation " << gamma;
    }
}

/// A forced Lamb-Oseen whirlwind at `at` (world metres) of core radius, peak speed and updraft.
Whirlwind forcedWhirlwind(std::array<double, 2> at, double core_m, double peak_mps,
                          double updraft_mps) {
    Whirlwind w;
    w.wsPosition_m = at;
    w.coreRadius_m = core_m;
    w.peakSpeed_mps = peak_mps;
    w.updraft_mps = updraft_mps;
    w.forced = true;
    return w;
}

/// What a step reports of its field (one pass in UnsteadyDiagnostics.cpp) against the definitions
/// written out here over the solver's field: the largest cell-centred speed over air cells, the
/// kinetic energy 1/2 sum theta u^2 V, the largest |open outflux| / U, and the cell rate behind
/// the next step's length (the field's or the far field's, whichever is faster).
TEST(UnsteadyWind, TheStepReportsItsFieldByTheDefinitions) {
    const Heightfield hf = terrain(TerrainKind::GaussianHill, 48, 32, 6.0, 6.0);
    AirDomain d(hf, {2.0, std::optional<double>(20.0), 1e9});
    const double U = 4.0;
    const auto steady = solveSteadyWind(d, uniformWind(U), {}, tight());
    UnsteadySettings s;
    s.cfl = 2.0;
    s.whirlwinds.push_back(forcedWhirlwind({14.0, 16.0}, 3.0, 6.0, 1.0));
    UnsteadyWindSolver solver(d, steady.field, s, U);
    const GridLayout& g = solver.grid();
    auto rateOf = [&](const std::vector<double>& u, const std::vector<double>& v,
                      const std::vector<double>& wz) {
        double r = 0.0;
        for (double x : u) r = std::max(r, std::abs(x) / g.voxelSize_m);
        for (double x : v) r = std::max(r, std::abs(x) / g.voxelSize_m);
        for (int k = 0; k <= g.nz; ++k) {
            const double dz = std::min(g.dz_m(std::max(k - 1, 0)), g.dz_m(std::min(k, g.nz - 1)));
            for (int j = 0; j < g.ny; ++j)
                for (int i = 0; i < g.nx; ++i)
                    r = std::max(r, std::abs(wz[g.faceZIndex(i, j, k)]) / dz);
        }
        return r;
    };
    const double farRate = rateOf(steady.field.u_mps(), steady.field.v_mps(), steady.field.w_mps());
    for (int n = 0; n < 4; ++n) {
        const StepReport r = solver.step(solver.nextDt_s());
        const WindField& f = solver.field();
        const auto &u = f.u_mps(), &v = f.v_mps(), &wz = f.w_mps();
        double speed = 0.0, outflux = 0.0, energy = 0.0;
        for (int k = 0; k < g.nz; ++k)
            for (int j = 0; j < g.ny; ++j)
                for (int i = 0; i < g.nx; ++i) {
                    if (!d.isAir(i, j, k)) continue;
                    const auto c = f.cellVelocity_mps(i, j, k);
                    speed = std::max(speed, std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]));
                    outflux = std::max(outflux, std::abs(d.openOutflux(u, v, wz, i, j, k)));
                }
        const double h = g.voxelSize_m;
        for (size_t a = 0; a < u.size(); ++a)
            energy += d.openFractionsX()[a] * u[a] * u[a] * h * h * h;
        for (size_t a = 0; a < v.size(); ++a)
            energy += d.openFractionsY()[a] * v[a] * v[a] * h * h * h;
        for (size_t a = 0; a < wz.size(); ++a)
            energy += d.openFractionsZ()[a] * wz[a] * wz[a] * h * h * h;
        energy *= 0.5;
        EXPECT_EQ(r.maxSpeed_mps, speed);
        EXPECT_EQ(r.maxDivergenceScaled, outflux / U);
        EXPECT_NEAR(r.kineticEnergy_m5ps2, energy, 1e-12 * energy);
        EXPECT_TRUE(r.finite);
        // The rate the step left for the next one is the field's as it is now.
        EXPECT_EQ(solver.cellRate_ps(), std::max(rateOf(u, v, wz), farRate));
        EXPECT_NEAR(solver.nextDt_s(), std::min(s.maxDt_s, s.cfl / solver.cellRate_ps()), 1e-15);
    }
    // An edit from outside is measured again: a face twice as fast as any other sets the rate.
    WindField& edit = solver.editField();
    const double fast = 3.0 * solver.maxSpeed_mps() + 10.0;
    edit.u_mps()[g.faceXIndex(5, 5, g.nz - 1)] = fast;
    EXPECT_EQ(solver.cellRate_ps(), fast / g.voxelSize_m);
}

/// gale view's coarser live grid: a solver on cells twice as large takes up a running one's time,
/// whirlwind markers and flow. The flow stays divergence-free, the whirlwind keeps its sense and
/// most of its circulation, and the run steps on.
TEST(UnsteadyWind, ASolverOnCoarserCellsTakesUpTheRunWithItsWhirlwind) {
    const Heightfield hf = terrain(TerrainKind::Flat, 64, 48);
    AirDomain fine(hf, {1.0, std::optional<double>(16.0), 1e9});
    AirDomain coarse(hf, {2.0, std::optional<double>(16.0), 1e9});
    const double U = 2.0;
    UnsteadySettings s;
    s.dt_s = 0.25;
    s.whirlwinds.push_back(forcedWhirlwind({24.0, 24.0}, 4.0, 5.0, 0.0));
    UnsteadyWindSolver a(fine, solveSteadyWind(fine, uniformWind(U), {}, tight()).field, s, U);
    for (int n = 0; n < 6; ++n) ASSERT_TRUE(a.step(a.nextDt_s()).finite);
    const std::array<double, 2> axis = a.whirlwindAxes_m()[0];
    const double before = circulationAround(a.grid(), a.velocity(), axis, 8.0, 6.0);
    UnsteadyWindSolver b(coarse, solveSteadyWind(coarse, uniformWind(U), {}, tight()).field, s, U);
    const SolveReport rep = b.continueFrom(a);
    EXPECT_TRUE(rep.converged) << rep.message;
    EXPECT_EQ(b.time_s(), a.time_s());
    EXPECT_EQ(b.whirlwindAxes_m()[0], axis);
    EXPECT_LT(b.maxDivergenceScaled(), DIVERGENCE_TOLERANCE);
    const double after = circulationAround(b.grid(), b.velocity(), axis, 8.0, 6.0);
    std::printf("circulation at 8 m around the axis: %.2f m^2/s on 1 m cells, %.2f on 2 m\n",
                before, after);
    EXPECT_GT(before, 0.0);
    EXPECT_GT(after, 0.7 * before);  // a 2 m grid resolves a 4 m core with some loss
    EXPECT_LT(after, 1.1 * before);
    for (int n = 0; n < 4; ++n) {
        const StepReport r = b.step(b.nextDt_s());
        ASSERT_TRUE(r.finite);
        EXPECT_LT(r.maxDivergenceScaled, DIVERGENCE_TOLERANCE);
    }
    EXPECT_DOUBLE_EQ(b.time_s(), a.time_s() + 4 * 0.25);
    // A solver of other whirlwinds cannot take the run up.
    UnsteadySettings none = s;
    none.whirlwinds.clear();
    UnsteadyWindSolver c(coarse, solveSteadyWind(coarse, uniformWind(U), {}, tight()).field, none,
                         U);
    EXPECT_THROW((void)c.continueFrom(a), std::logic_error);
}

/// Mean tangential speed on a ring of radius r around (x, y) at height z, m/s.
double ringSpeed(const UnsteadyWindSolver& s, double x, double y, double r, double z) {
    return circulationAround(s.grid(), s.velocity(), {x, y}, r, z) / (2 * PI * r);
}

TEST(UnsteadyWind, LambOseenVortexDecaysAsTheExactViscousSolution) {
    // Lamb-Oseen under viscosity nu: v(r, t) = Gamma / (2 pi r) (1 - exp(-r^2 / (r0^2 + 4 nu t))).
    // Calm air, a lid 4 m up, the vortex resolved by 6 cells per core radius.
    const Heightfield hf = terrain(TerrainKind::Flat, 72, 72);
    AirDomain d(hf, {1.0, std::optional<double>(4.0), 1e9});
    const auto steady = solveSteadyWind(d, uniformWind(0.0), {}, tight());
    const double r0 = 6.0, nu = 1.0, T = 4.0;
    UnsteadySettings s;
    s.advection = AdvectionScheme::MacCormack;
    s.dt_s = 0.25;
    s.viscosity_m2ps = nu;
    Whirlwind w;
    w.wsPosition_m = {36.0, 36.0};
    w.coreRadius_m = r0;
    w.peakSpeed_mps = 2.0;
    w.outerRadiusFactor = 3.0;  // seeded to 18 m, tapered to 27 m: far from the rings we measure
    s.whirlwinds.push_back(w);
    UnsteadyWindSolver solver(d, steady.field, s, 1.0);
    const auto reps = solver.advanceTo(T);
    for (const StepReport& r : reps) ASSERT_TRUE(r.finite);
    const double G = w.circulation(), rc2 = r0 * r0 + 4 * nu * T;
    double maxErr = 0.0;
    for (double r = 2.0; r <= 12.0; r += 2.0) {
        const double exact = gale::validation::exact::lambOseenSpeed_mps(G, rc2, r);
        const double got = ringSpeed(solver, 36.0, 36.0, r, 2.0);
        maxErr = std::max(maxErr, std::abs(got - exact));
        std::printf("r = %4.1f m: v = %.4f m/s, exact %.4f m/s\n", r, got, exact);
    }
    // 5 % of the initial peak speed: the scheme's own numerical diffusion (MacCormack at 6
    // cells per core) adds to nu; the inviscid run of the same vortex loses less than this.
    constexpr double LAMB_OSEEN_TOLERANCE_OF_PEAK = 0.05;
    EXPECT_LT(maxErr, LAMB_OSEEN_TOLERANCE_OF_PEAK * w.peakSpeed_mps);
}

TEST(UnsteadyWind, VorticityConfinementKeepsAVortexCoreStronger) {
    // Semi-Lagrangian advection smears a 2-cell core; confinement (Fedkiw et al. 2001) puts the
    // lost vorticity back near the core, so the peak stays higher than without it.
    const Heightfield hf = terrain(TerrainKind::Flat, 48, 48);
    AirDomain d(hf, {2.0, std::optional<double>(8.0), 1e9});
    const auto steady = solveSteadyWind(d, uniformWind(0.0), {}, tight());
    double peak[2] = {0, 0};
    for (int run = 0; run < 2; ++run) {
        UnsteadySettings s;
        s.dt_s = 0.5;
        s.vorticityConfinement = run == 0 ? 0.0 : 0.5;
        s.whirlwinds.push_back([] {
            Whirlwind w;
            w.wsPosition_m = {24.0, 24.0};
            w.coreRadius_m = 4.0;
            w.peakSpeed_mps = 4.0;
            return w;
        }());
        UnsteadyWindSolver solver(d, steady.field, s, 1.0);
        for (const StepReport& r : solver.advanceTo(10.0)) ASSERT_TRUE(r.finite);
        peak[run] = strongestVortex(solver, 1, true).omega;
    }
    std::printf("peak vorticity after 10 s: %.3f 1/s without confinement, %.3f 1/s with\n", peak[0],
                peak[1]);
    // At least 10 % stronger (measured 3.5 times: 2.30 against 0.66 1/s; the seeded peak is 3.1),
    // and confinement must not overshoot the seeded vortex.
    constexpr double CONFINEMENT_GAIN = 1.1;
    EXPECT_GT(peak[1], peak[0] * CONFINEMENT_GAIN);
    EXPECT_LT(peak[1], 3.2);
}

/// Largest change of any face velocity after the steps, m/s: a log profile over flat ground is a
/// fixed point of advection and projection, so only round-off of the 1e-9 steady solve remains...
constexpr double SHEAR_FIXED_POINT_TOLERANCE_MPS = 1e-6;
/// ...while the vortex code's confinement force on the same shear (eps h |omega| with |omega| about
/// 0.9 1/s in the lowest cells) moves the lowest faces by tenths of a m/s in the same time.
constexpr double CONFINEMENT_VISIBLE_MPS = 1e-2;

TEST(UnsteadyWind, SceneWithoutWhirlwindsAddsNoVortexForcingToAShearedFlow) {
    // The log profile's shear carries vorticity: any vortex code that ran (a whirlwind seeded,
    // confinement) would push on it. Without whirlwinds the field must stay the steady one.
    const AirDomain domain(terrain(TerrainKind::Flat, 20, 20), {2.0, {}, 1e9});
    AmbientWind logProfile;  // 5 m/s at 10 m over z0 = 0.03 m
    const SteadyWindResult steady = solveSteadyWind(domain, logProfile, {}, tight());
    auto largestChange_mps = [&](const UnsteadySettings& s) {
        UnsteadyWindSolver solver(domain, steady.field, s, logProfile.speed_mps);
        for (int n = 0; n < 4; ++n) (void)solver.step(0.5);
        // A NaN or Inf anywhere makes the change NaN, which no comparison below passes.
        double change = 0.0;
        auto compare = [&](const std::vector<double>& now, const std::vector<double>& before) {
            for (size_t f = 0; f < now.size(); ++f) {
                const double d = std::abs(now[f] - before[f]);
                if (!(d <= change)) change = d;
            }
        };
        compare(solver.field().u_mps(), steady.field.u_mps());
        compare(solver.field().v_mps(), steady.field.v_mps());
        compare(solver.field().w_mps(), steady.field.w_mps());
        return change;
    };
    EXPECT_LT(largestChange_mps(UnsteadySettings{}), SHEAR_FIXED_POINT_TOLERANCE_MPS);
    // The same check sees the vortex code when it runs.
    UnsteadySettings confined;
    confined.vorticityConfinement = 0.1;
    EXPECT_GT(largestChange_mps(confined), CONFINEMENT_VISIBLE_MPS);
}

TEST(UnsteadyWind, BadSettingsThrowNamingTheKey) {
    UnsteadySettings s;
    s.cfl = -1;
    EXPECT_THROW(s.validate(), std::invalid_argument);
    s = {};
    GustEvent g;
    g.duration_s = 0;
    s.gusts.push_back(g);
    try {
        s.validate();
        ADD_FAILURE();
    } catch (const ParameterError& e) {
        EXPECT_EQ(e.key(), "wind.gusts[0].duration_s");
    }
}

}  // namespace
}  // namespace gale::sim
