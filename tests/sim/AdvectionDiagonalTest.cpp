// Advection along y and z: a uniform flow with all three components non-zero (and v < 0) moves a
// 3-D Gaussian blob by exactly (u, v, w) dt metres, for every placement and scheme. The x-only
// translation tests (UnsteadyAdvectionTest.cpp) cannot see a trace that mixes up the axes, uses
// the wrong face grid's stride along y or z, or forgets to divide v or w by the cell size.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "sim/Advection.h"

namespace gale::sim {
namespace {

/// A cell edge far from 1 m, so a component that is not divided by h moves the wrong distance.
constexpr double H_M = 2.5;
/// Three different speeds, v negative: a swapped or sign-flipped component shows.
constexpr std::array<double, 3> VELOCITY_MPS = {3.0, -2.0, 1.25};
constexpr int CELLS = 40;
constexpr double SIGMA_CELLS = 2.5;
/// Fastest component's travel per step, cells, and steps: 8 x 0.4 = 3.2 cells along x.
constexpr double CELLS_PER_STEP = 0.4;
constexpr int STEPS = 8;
/// Centroid shift, semi-Lagrangian: a uniform flow's midpoint trace is exact and trilinear
/// interpolation keeps a blob's first moment (the tent weights are symmetric about the departure
/// point), so only round-off and the blob's tails at the box sides (e^-27 at 7.4 sigma) remain.
constexpr double CENTROID_TOLERANCE_CELLS = 1e-6;
/// MacCormack and BFECC: the min/max limiter clips the peak a little asymmetrically
/// (measured: 3.6e-3 cells for MacCormack after 3.2 cells of travel of this 2.5-cell blob; 3e-4 in
/// the 1-D test's wider profile). A component forgotten or not divided by h is >= 1 cell off.
constexpr double CENTROID_TOLERANCE_LIMITED_CELLS = 1e-2;

struct Case {
    AdvectionScheme scheme;
    Placement placement;
};

class DiagonalTranslation : public ::testing::TestWithParam<Case> {};

TEST_P(DiagonalTranslation, UniformFlowMovesABlobByVelocityTimesDtAlongEveryAxis) {
    const Case c = GetParam();
    const MacGrid g{CELLS, CELLS, CELLS, H_M, {-7.0, 11.0, 3.0}};
    std::vector<double> u(g.count(Placement::FaceX), VELOCITY_MPS[0]),
        v(g.count(Placement::FaceY), VELOCITY_MPS[1]),
        w(g.count(Placement::FaceZ), VELOCITY_MPS[2]);
    const MacVelocity vel{&u, &v, &w};
    const double dt_s = CELLS_PER_STEP * H_M / VELOCITY_MPS[0];
    std::array<double, 3> shift_m{}, centre_m{};
    for (int a = 0; a < 3; ++a) {
        shift_m[a] = VELOCITY_MPS[a] * dt_s * STEPS;
        // Start so that the blob ends as far from the sides as it started from the other side.
        centre_m[a] = g.wsMin_m[a] + 0.5 * CELLS * H_M - 0.5 * shift_m[a];
    }
    const double sigma_m = SIGMA_CELLS * H_M;
    auto blob = [&](const Vec3d& p, const std::array<double, 3>& at) {
        double r2 = 0.0;
        for (int a = 0; a < 3; ++a) r2 += (p[a] - at[a]) * (p[a] - at[a]);
        return std::exp(-0.5 * r2 / (sigma_m * sigma_m));
    };
    const auto n = g.dims(c.placement);
    auto index = [&](int i, int j, int k) {
        return size_t(i) + size_t(n[0]) * (size_t(j) + size_t(n[1]) * size_t(k));
    };
    std::vector<double> q(g.count(c.placement)), out;
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i)
                q[index(i, j, k)] = blob(g.wsPosition(c.placement, i, j, k), centre_m);
    auto centroid = [&](const std::vector<double>& a) {
        double mass = 0.0;
        std::array<double, 3> moment{};
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    const double val = a[index(i, j, k)];
                    const Vec3d p = g.wsPosition(c.placement, i, j, k);
                    mass += val;
                    for (int ax = 0; ax < 3; ++ax) moment[ax] += val * p[ax];
                }
        for (double& m : moment) m /= mass;
        return moment;
    };
    const std::array<double, 3> before_m = centroid(q);
    for (int s = 0; s < STEPS; ++s) {
        advect(g, c.placement, q, vel, {}, {}, dt_s, c.scheme, out);
        q.swap(out);
    }
    const std::array<double, 3> after_m = centroid(q);
    const double tolerance = c.scheme == AdvectionScheme::SemiLagrangian
                                 ? CENTROID_TOLERANCE_CELLS
                                 : CENTROID_TOLERANCE_LIMITED_CELLS;
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR((after_m[a] - before_m[a]) / H_M, shift_m[a] / H_M, tolerance)
            << advectionSchemeName(c.scheme) << ", placement " << int(c.placement) << ", axis "
            << "xyz"[a];
    for (double x : q) ASSERT_TRUE(std::isfinite(x));
}

INSTANTIATE_TEST_SUITE_P(EveryPlacement, DiagonalTranslation,
                         ::testing::Values(Case{AdvectionScheme::SemiLagrangian, Placement::Cell},
                                           Case{AdvectionScheme::SemiLagrangian, Placement::FaceX},
                                           Case{AdvectionScheme::SemiLagrangian, Placement::FaceY},
                                           Case{AdvectionScheme::SemiLagrangian, Placement::FaceZ},
                                           Case{AdvectionScheme::MacCormack, Placement::FaceY},
                                           Case{AdvectionScheme::Bfecc, Placement::FaceZ}));

}  // namespace
}  // namespace gale::sim
