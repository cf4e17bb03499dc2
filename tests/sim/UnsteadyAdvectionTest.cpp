// Advection on the MAC grid: uniform flow moves a smooth profile by exactly u dt metres
// (= u dt / h cells) for every scheme and every placement; the limiters keep values in range.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <vector>

#include "sim/Advection.h"

namespace gale::sim {
namespace {

/// A cell edge far from 1 m, so a trace that forgets to divide by h moves the profile by the
/// wrong number of cells (the incompressible-fluids slip STYLE.md warns about).
constexpr double H_M = 2.5;
constexpr double U_MPS = 3.0;
/// Centroid shift: linear interpolation keeps the first moment of a profile far from the sides
/// exactly, so only round-off remains for the semi-Lagrangian scheme...
constexpr double CENTROID_TOLERANCE_CELLS = 1e-6;
/// ...while the min/max limiter of MacCormack and BFECC clips the peak slightly asymmetrically
/// (measured: 3e-4 cells after 3 cells of travel). A forgotten division by h is 1.5 cells off.
constexpr double CENTROID_TOLERANCE_LIMITED_CELLS = 2e-3;
/// Pointwise error of the translated unit Gaussian (sigma = 3 cells) after ~3 cells of travel:
/// the interpolation's smoothing (measured 0.09 for semi-Lagrangian at 0.37 cells per step, 0.025
/// for the limited schemes); a 1.5-cell slip would leave 0.3.
constexpr double POINTWISE_TOLERANCE_SL = 0.12;
constexpr double POINTWISE_TOLERANCE_HIGH_ORDER = 0.035;

struct Case {
    AdvectionScheme scheme;
    Placement placement;
    double cellsPerStep;
};

class Translation : public ::testing::TestWithParam<Case> {};

TEST_P(Translation, UniformFlowMovesProfileByUDt) {
    const Case c = GetParam();
    MacGrid g{64, 3, 3, H_M, {-10.0, 5.0, 1.0}};
    std::vector<double> u(g.count(Placement::FaceX), U_MPS), v(g.count(Placement::FaceY), 0.0),
        w(g.count(Placement::FaceZ), 0.0);
    const MacVelocity vel{&u, &v, &w};
    const auto n = g.dims(c.placement);
    const double sigma_m = 3.0 * H_M, x0_m = g.wsMin_m[0] + 30.0 * H_M;
    auto profile = [&](double x) {
        return std::exp(-0.5 * (x - x0_m) * (x - x0_m) / (sigma_m * sigma_m));
    };
    std::vector<double> q(g.count(c.placement));
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i)
                q[size_t(i) + size_t(n[0]) * (j + size_t(n[1]) * k)] =
                    profile(g.wsPosition(c.placement, i, j, k)[0]);
    const double dt_s = c.cellsPerStep * H_M / U_MPS;
    const int steps = std::max(1, int(std::lround(3.0 / c.cellsPerStep)));
    auto centroid = [&](const std::vector<double>& a) {
        double s = 0, sx = 0;
        for (int i = 0; i < n[0]; ++i) {
            const double val = a[size_t(i) + size_t(n[0]) * (1 + size_t(n[1]) * 1)];
            s += val, sx += val * g.wsPosition(c.placement, i, 1, 1)[0];
        }
        return sx / s;
    };
    const double before_m = centroid(q);
    std::vector<double> out;
    for (int s = 0; s < steps; ++s) {
        advect(g, c.placement, q, vel, {}, {}, dt_s, c.scheme, out);
        q.swap(out);
    }
    const double shift_m = U_MPS * dt_s * steps;
    EXPECT_NEAR((centroid(q) - before_m) / H_M, shift_m / H_M,
                c.scheme == AdvectionScheme::SemiLagrangian ? CENTROID_TOLERANCE_CELLS
                                                            : CENTROID_TOLERANCE_LIMITED_CELLS)
        << advectionSchemeName(c.scheme) << " moved the profile by the wrong distance";
    double err = 0;
    for (int i = 0; i < n[0]; ++i) {
        const size_t idx = size_t(i) + size_t(n[0]) * (1 + size_t(n[1]) * 1);
        err = std::max(err,
                       std::abs(q[idx] - profile(g.wsPosition(c.placement, i, 1, 1)[0] - shift_m)));
    }
    std::printf("%s placement %d, %.2f cells/step: max error %.4f\n", advectionSchemeName(c.scheme),
                int(c.placement), c.cellsPerStep, err);
    EXPECT_LT(err, c.scheme == AdvectionScheme::SemiLagrangian ? POINTWISE_TOLERANCE_SL
                                                               : POINTWISE_TOLERANCE_HIGH_ORDER);
}

INSTANTIATE_TEST_SUITE_P(
    EveryScheme, Translation,
    ::testing::Values(Case{AdvectionScheme::SemiLagrangian, Placement::Cell, 0.37},
                      Case{AdvectionScheme::SemiLagrangian, Placement::FaceX, 0.37},
                      Case{AdvectionScheme::SemiLagrangian, Placement::FaceZ, 2.6},
                      Case{AdvectionScheme::MacCormack, Placement::Cell, 0.37},
                      Case{AdvectionScheme::MacCormack, Placement::FaceX, 1.3},
                      Case{AdvectionScheme::Bfecc, Placement::Cell, 0.37},
                      Case{AdvectionScheme::Bfecc, Placement::FaceY, 1.3}));

TEST(Advection, LimitedSchemesStayWithinTheInitialRange) {
    // A step profile is the hard case for MacCormack and BFECC: without the min/max clamp they
    // over- and undershoot.
    MacGrid g{48, 2, 2, 1.0, {0, 0, 0}};
    std::vector<double> u(g.count(Placement::FaceX), 1.0), v(g.count(Placement::FaceY), 0.0),
        w(g.count(Placement::FaceZ), 0.0);
    for (AdvectionScheme s : {AdvectionScheme::MacCormack, AdvectionScheme::Bfecc}) {
        std::vector<double> q(g.count(Placement::Cell)), out;
        for (size_t c = 0; c < q.size(); ++c) q[c] = (c % 48) >= 10 && (c % 48) < 20 ? 1.0 : 0.0;
        for (int n = 0; n < 10; ++n) {
            advect(g, Placement::Cell, q, {&u, &v, &w}, {}, {}, 0.43, s, out);
            q.swap(out);
        }
        for (double x : q) {
            EXPECT_GE(x, 0.0) << advectionSchemeName(s);
            EXPECT_LE(x, 1.0) << advectionSchemeName(s);
        }
    }
}

TEST(Advection, TraceThatLeavesTheBoxReadsTheFarField) {
    MacGrid g{8, 2, 2, 1.0, {0, 0, 0}};
    std::vector<double> u(g.count(Placement::FaceX), 2.0), v(g.count(Placement::FaceY), 0.0),
        w(g.count(Placement::FaceZ), 0.0), q(g.count(Placement::Cell), 0.0), out;
    const FarField far = [](const Vec3d&) { return Vec3d{2.0, 0.0, 0.0}; };
    advect(
        g, Placement::Cell, q, {&u, &v, &w}, far, [](const Vec3d&) { return 7.0; }, 1.0,
        AdvectionScheme::SemiLagrangian, out);
    EXPECT_DOUBLE_EQ(out[0], 7.0);  // cell 0 centre - 2 m lies outside the box: inflow value
    EXPECT_DOUBLE_EQ(out[1], 7.0);
    EXPECT_DOUBLE_EQ(out[2], 0.0);
}

/// A solid-body rotation by 1 radian at 10 cells from the axis: one midpoint step would land 1.6
/// cells off the circle (rotation error ~ r theta^3 / 6); substeps of <= 2 cells bring it under
/// 0.1 cells. Trilinear interpolation is exact for the linear field, so only the trace errs.
constexpr double ROTATION_TRACE_TOLERANCE_CELLS = 0.1;
/// Bisection puts the stop within 2^-12 of a substep above the surface.
constexpr double TERRAIN_STOP_TOLERANCE_CELLS = 1e-3;

TEST(Advection, SubstepsKeepALongTraceOnItsCurvedStreamline) {
    const double h = 2.0, omega = 0.5, dt = 1.0 / omega;  // omega dt = 1 rad
    MacGrid g{48, 48, 2, h, {-48.0, -48.0, 0.0}};
    std::vector<double> u(g.count(Placement::FaceX)), v(g.count(Placement::FaceY)),
        w(g.count(Placement::FaceZ), 0.0);
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 48; ++j)
            for (int i = 0; i <= 48; ++i)
                u[size_t(i) + 49 * (j + size_t(48) * k)] =
                    -omega * g.wsPosition(Placement::FaceX, i, j, k)[1];
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j <= 48; ++j)
            for (int i = 0; i < 48; ++i)
                v[size_t(i) + 48 * (j + size_t(49) * k)] =
                    omega * g.wsPosition(Placement::FaceY, i, j, k)[0];
    const double r = 10.0 * h;
    const Vec3d dep = traceBack(g, {&u, &v, &w}, {}, {r, 0.0, 1.0}, dt);
    // Exact: the particle was at angle -omega dt on the same circle.
    EXPECT_NEAR(dep[0] / h, r * std::cos(-1.0) / h, ROTATION_TRACE_TOLERANCE_CELLS);
    EXPECT_NEAR(dep[1] / h, r * std::sin(-1.0) / h, ROTATION_TRACE_TOLERANCE_CELLS);
}

TEST(Advection, TraceStopsOnTheTerrainSurface) {
    // Updraft of 1 m/s over ground at z = 2 m: tracing back 10 s from z = 5 m would end at -5 m,
    // inside the rock; the trace must stop on the surface.
    TerrainSpec flat;
    flat.kind = TerrainKind::Flat;
    flat.sizeX_m = flat.sizeY_m = 16.0;
    Heightfield ground = makeTerrain(flat);
    for (float& z : ground.height_m) z = 2.0f;
    MacGrid g{8, 8, 8, 2.0, {0.0, 0.0, 0.0}, &ground};
    std::vector<double> u(g.count(Placement::FaceX), 0.0), v(g.count(Placement::FaceY), 0.0),
        w(g.count(Placement::FaceZ), 1.0);
    const Vec3d dep = traceBack(g, {&u, &v, &w}, {}, {7.0, 7.0, 5.0}, 10.0);
    EXPECT_NEAR(dep[2], 2.0, TERRAIN_STOP_TOLERANCE_CELLS * g.voxelSize_m);
    EXPECT_GE(dep[2], 2.0);
    // Without the terrain the same trace runs its full time (through the clamped field).
    g.terrain = nullptr;
    EXPECT_NEAR(traceBack(g, {&u, &v, &w}, {}, {7.0, 7.0, 5.0}, 10.0)[2], -5.0, 1e-9);
}

TEST(Advection, SchemeNamesRoundTripAndUnknownNamesThrow) {
    for (AdvectionScheme s :
         {AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack, AdvectionScheme::Bfecc})
        EXPECT_EQ(advectionSchemeFromName(advectionSchemeName(s)), s);
    EXPECT_THROW(advectionSchemeFromName("rk4"), std::invalid_argument);
}

TEST(Advection, MacCormackIsItsTwoSemiLagrangianPassesCombinedAndLimited) {
    // The scheme shares each trace's start (velocity, layer, above the ground) between its
    // forward and backward passes; assembled here from two independent semi-Lagrangian passes
    // and traceBack's departure points (Selle et al. 2008), it must come out the same, bit for
    // bit: over a hill the traces stop on, in a swirling field, with inflow through the sides.
    TerrainSpec hill;
    hill.kind = TerrainKind::GaussianHill;
    hill.sizeX_m = 12.0, hill.sizeY_m = 10.0, hill.spacing_m = 0.5;
    hill.height_m = 3.0, hill.radius_m = 2.0, hill.centerX_m = 6.0, hill.centerY_m = 5.0;
    const Heightfield ground = makeTerrain(hill);
    const MacGrid g{12, 10, 8, 1.0, {0.0, 0.0, 0.0}, &ground};
    auto field = [&](Placement p, auto f) {
        const auto n = g.dims(p);
        std::vector<double> a(g.count(p));
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) a[g.index(p, i, j, k)] = f(g.wsPosition(p, i, j, k));
        return a;
    };
    const std::vector<double> u = field(Placement::FaceX,
                                        [](const Vec3d&x) { return 1.0 + 0.6 * std::sin(x[1]); }),
                              v = field(Placement::FaceY,
                                        [](const Vec3d&x) { return 0.8 * std::cos(x[0]); }),
                              w = field(Placement::FaceZ,
                                        [](const Vec3d&x) { return -0.4 * std::sin(x[0] + x[1]); });
    const std::vector<double> q = field(Placement::FaceX, [](const Vec3d& x) {
        return std::sin(0.7 * x[0]) * std::cos(0.5 * x[2]) + (x[1] > 5.0 ? 1.0 : 0.0);
    });
    const MacVelocity vel{&u, &v, &w};
    const FarField far = [](const Vec3d&) { return Vec3d{1.0, 0.3, 0.0}; };
    const OutsideValue inflow = [](const Vec3d& x) { return 0.5 + 0.01 * x[2]; };
    constexpr double dt = 1.7;  // up to 2.4 cells: two substeps for the fastest traces
    std::vector<double> mc, fwd, back;
    advect(g, Placement::FaceX, q, vel, far, inflow, dt, AdvectionScheme::MacCormack, mc);
    advect(g, Placement::FaceX, q, vel, far, inflow, dt, AdvectionScheme::SemiLagrangian, fwd);
    advect(g, Placement::FaceX, fwd, vel, far, inflow, -dt, AdvectionScheme::SemiLagrangian, back);
    const auto n = g.dims(Placement::FaceX);
    int limited = 0;
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i) {
                const size_t c = g.index(Placement::FaceX, i, j, k);
                const Vec3d dep =
                    traceBack(g, vel, far, g.wsPosition(Placement::FaceX, i, j, k), dt);
                double lo = -HUGE_VAL, hi = HUGE_VAL;
                const bool inside = dep[0] >= 0.0 && dep[0] <= 12.0 && dep[1] >= 0.0 &&
                                    dep[1] <= 10.0 && dep[2] <= 8.0;
                if (inside) (void)sampleAt(g, Placement::FaceX, q, dep, &lo, &hi);
                const double raw = fwd[c] + 0.5 * (q[c] - back[c]);
                limited += raw < lo || raw > hi;
                EXPECT_EQ(mc[c], std::clamp(raw, lo, hi)) << i << " " << j << " " << k;
            }
    EXPECT_GT(limited, 0) << "the case should exercise the limiter";
}

}  // namespace
}  // namespace gale::sim
