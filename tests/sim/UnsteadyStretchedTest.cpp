/// \file UnsteadyStretchedTest.cpp
/// The unsteady solver on vertically stretched layers (docs/unsteady.md, "Stretched layers"):
/// a uniform wind stays uniform, a blob carried by w across growing layers lands where the exact
/// translation puts it, the projection leaves the divergence at its tolerance, a translating
/// vortex whose core crosses the thin layers matches the cubic run, and extreme winds on the
/// thinnest first layer stay finite. Every verdict is computed here from the fields.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "SimTestUtil.h"
#include "sim/Advection.h"
#include "sim/AirDomain.h"
#include "sim/SteadyWind.h"
#include "sim/UnsteadyWind.h"
#include "validation/ExactSolutions.h"

namespace gale::sim {
namespace {

namespace exact = gale::validation::exact;

using test::uniformWind;

constexpr AdvectionScheme SCHEMES[] = {AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack,
                                       AdvectionScheme::Bfecc};

Heightfield flatGround(double sizeX_m, double sizeY_m, double spacing_m) {
    TerrainSpec s;
    s.kind = TerrainKind::Flat;
    s.sizeX_m = sizeX_m, s.sizeY_m = sizeY_m;
    s.spacing_m = spacing_m;
    return makeTerrain(s);
}

DomainSpec layers(double voxel_m, double first_m, double top_m, double maxCell_m) {
    DomainSpec s;
    s.voxelSize_m = voxel_m;
    s.top_m = top_m;
    s.firstCell_m = first_m;
    s.maxCell_m = maxCell_m;
    return s;
}

/// Largest |x - value| over an array.
double maxDeviation(const std::vector<double>& a, double value) {
    double m = 0.0;
    for (double x : a) m = std::max(m, std::abs(x - value));
    return m;
}

TEST(UnsteadyStretched, UniformWindStaysUniformToRoundOff) {
    // Sums of a few hundred terms of 5 m/s each: round-off, far below any discretisation error.
    constexpr double ROUND_OFF_MPS = 1e-9;
    const Heightfield flat = flatGround(24.0, 16.0, 1.0);
    const AirDomain domain(flat, layers(2.0, 0.4, 12.0, 2.0));
    ASSERT_FALSE(domain.layout().uniformZ());
    const SteadyWindResult mean = solveSteadyWind(domain, uniformWind(5.0), {}, test::tight());
    for (AdvectionScheme scheme : SCHEMES) {
        UnsteadySettings s;
        s.advection = scheme;
        s.cfl = 3.0;
        UnsteadyWindSolver solver(domain, mean.field, s, 5.0);
        for (const StepReport& r : solver.advanceTo(6.0)) ASSERT_TRUE(r.finite);
        EXPECT_LT(maxDeviation(solver.field().u_mps(), 5.0), ROUND_OFF_MPS)
            << advectionSchemeName(scheme);
        EXPECT_LT(maxDeviation(solver.field().v_mps(), 0.0), ROUND_OFF_MPS);
        EXPECT_LT(maxDeviation(solver.field().w_mps(), 0.0), ROUND_OFF_MPS);
    }
}

TEST(UnsteadyStretched, AdaptiveStepHoldsTheCflOfWInTheThinnestLayer) {
    // A vertical wind of 1 m/s through layers from 0.4 m: cfl 2 allows 0.8 s, where the
    // horizontal spacing alone (2 m) would allow 4 s.
    constexpr double RATIO_TOLERANCE = 1e-12;  // one division
    const Heightfield flat = flatGround(16.0, 16.0, 1.0);
    const AirDomain domain(flat, layers(2.0, 0.4, 12.0, 2.0));
    const SteadyWindResult mean = solveSteadyWind(domain, uniformWind(0.5), {}, test::tight());
    UnsteadySettings s;
    s.cfl = 2.0;
    s.maxDt_s = 100.0;
    UnsteadyWindSolver solver(domain, mean.field, s, 0.5);
    for (double& w : solver.editField().w_mps()) w = 1.0;
    const double thinnest_m = domain.layout().dz_m(0);
    EXPECT_NEAR(solver.nextDt_s(), 2.0 * thinnest_m / 1.0, RATIO_TOLERANCE);
}

/// The blob's pointwise error after 9 m of travel through 1.8-3.6 m layers: the linear
/// interpolation's smoothing of a peak one or two layers wide (measured at most 0.23, for
/// semi-Lagrangian on the z-faces); the index-space slip the test guards against leaves about 0.9.
constexpr double BLOB_POINTWISE_TOLERANCE = 0.3;
/// The blob's centroid: interpolation on layers that grow upwards smooths the upper flank over
/// thicker layers and lifts the centroid a little (measured: +0.64 m semi-Lagrangian, -0.17 m
/// MacCormack, +0.37 m BFECC; a fifth of the 3.6 m layer it lands in); the slip moves it by 6 m.
constexpr double BLOB_CENTROID_TOLERANCE_M = 0.8;

/// A Gaussian in world z of amplitude 1 and width sigma_m centred at zc_m.
double gaussian(double z_m, double zc_m, double sigma_m) {
    const double d = (z_m - zc_m) / sigma_m;
    return std::exp(-0.5 * d * d);
}

/// Layers from 0.4 m growing by 1.2 to 4 m under 2 m cells, 3 x 3 columns, no terrain.
MacGrid growingLayers() {
    return MacGrid(GridLayout(3, 3, 2.0, {0.0, 0.0, 0.0},
                              AirDomain::stretchedLevels_m(0.0, 40.0, 0.4, 1.2, 4.0)),
                   nullptr);
}

TEST(UnsteadyStretched, ProfileLinearInHeightIsCarriedByWExactlyAcrossTheLayers) {
    // The sampler reproduces a field linear in world z exactly, and a constant w makes every
    // trace exact, so semi-Lagrangian steps turn q = z into q = z - W t to round-off on every
    // placement (above the bottom, where the clamped inflow is not the profile). A trace that
    // moved W dt / h cells of index space would be off by metres. (The limited schemes' backward
    // passes carry the box ends' clamping inwards; the blob test below covers them.)
    constexpr double ROUND_OFF_M = 1e-9;  // sums of O(10) lengths of O(10) m
    const double W = 1.5, dt = 1.5;
    const int steps = 4;
    const MacGrid g = growingLayers();
    std::vector<double> u(g.count(Placement::FaceX), 0.0), v(g.count(Placement::FaceY), 0.0),
        w(g.count(Placement::FaceZ), W);
    const MacVelocity vel{&u, &v, &w};
    for (Placement p : {Placement::FaceX, Placement::Cell, Placement::FaceZ}) {
        const AdvectionScheme scheme = AdvectionScheme::SemiLagrangian;
        {
            std::vector<double> q(g.count(p)), out;
            const auto n = g.dims(p);
            for (int k = 0; k < n[2]; ++k)
                for (int j = 0; j < n[1]; ++j)
                    for (int i = 0; i < n[0]; ++i)
                        q[g.index(p, i, j, k)] = g.wsPosition(p, i, j, k)[2];
            for (int s = 0; s < steps; ++s) {
                advect(g, p, q, vel, {}, {}, dt, scheme, out);
                q.swap(out);
            }
            double err = 0.0;
            // Checked over the growing layers (up to 20 m) above the bottom's clamped inflow,
            // which reaches W t = 9 m (plus the layer its value is interpolated across).
            constexpr double GROWING_TOP_M = 20.0;
            for (int k = 0; k < n[2]; ++k) {
                const double z = g.wsPosition(p, 1, 1, k)[2];
                if (z > W * dt * (steps + 1) && z < GROWING_TOP_M)
                    err = std::max(err, std::abs(q[g.index(p, 1, 1, k)] - (z - W * dt * steps)));
            }
            EXPECT_LT(err, ROUND_OFF_M) << "placement " << int(p);
        }
    }
}

TEST(UnsteadyStretched, BlobCarriedByWCrossesTheLayersAndLandsOnTheExactTranslation) {
    // Layers from 0.4 m growing by 1.2 to 4 m (h = 2 m); the blob (sigma 2 m) starts at 7 m,
    // where the layers are 1.8 m thick, and rises 9 m at 1.5 m/s in 4 steps to 16 m, where they
    // are 3.6 m thick: it crosses six layer boundaries. A trace that moved W dt / h cells of
    // index space instead of W dt metres would put it near 22 m instead.
    const double W = 1.5, sigma = 2.0, z0 = 7.0, dt = 1.5;
    const int steps = 4;
    const MacGrid g = growingLayers();
    std::vector<double> u(g.count(Placement::FaceX), 0.0), v(g.count(Placement::FaceY), 0.0),
        w(g.count(Placement::FaceZ), W);
    const MacVelocity vel{&u, &v, &w};
    const double zc = z0 + W * dt * steps;
    for (Placement p : {Placement::Cell, Placement::FaceZ}) {
        for (AdvectionScheme scheme : SCHEMES) {
            const auto n = g.dims(p);
            std::vector<double> q(g.count(p)), out;
            for (int k = 0; k < n[2]; ++k)
                for (int j = 0; j < n[1]; ++j)
                    for (int i = 0; i < n[0]; ++i)
                        q[g.index(p, i, j, k)] = gaussian(g.wsPosition(p, i, j, k)[2], z0, sigma);
            for (int s = 0; s < steps; ++s) {
                advect(g, p, q, vel, {}, {}, dt, scheme, out);
                q.swap(out);
            }
            // Error against the exact translation, and the centroid (trapezoidal rule over the
            // samples' world heights).
            double err = 0.0, m0 = 0.0, m1 = 0.0;
            for (int k = 0; k < n[2]; ++k) {
                const double z = g.wsPosition(p, 1, 1, k)[2], value = q[g.index(p, 1, 1, k)];
                err = std::max(err, std::abs(value - gaussian(z, zc, sigma)));
                if (k + 1 < n[2]) {
                    const double z1 = g.wsPosition(p, 1, 1, k + 1)[2];
                    const double v1 = q[g.index(p, 1, 1, k + 1)];
                    m0 += 0.5 * (z1 - z) * (value + v1);
                    m1 += 0.5 * (z1 - z) * (value * z + v1 * z1);
                }
            }
            EXPECT_LT(err, BLOB_POINTWISE_TOLERANCE) << advectionSchemeName(scheme);
            EXPECT_NEAR(m1 / m0, zc, BLOB_CENTROID_TOLERANCE_M) << advectionSchemeName(scheme);
        }
    }
}

/// The test's own divergence of the open fluxes of cell (i, j, k), m^3/s: the open area of each
/// face (h dz_k on the sides, h^2 on top and bottom) times its velocity, outward positive.
double cellOutflow_m3ps(const AirDomain& d, const WindField& f, int i, int j, int k) {
    const GridLayout& g = d.layout();
    const double h = g.voxelSize_m, side = h * g.dz_m(k), top = h * h;
    const auto &U = f.u_mps(), &V = f.v_mps(), &W = f.w_mps();
    return side * (d.openFractionX(i + 1, j, k) * U[g.faceXIndex(i + 1, j, k)] -
                   d.openFractionX(i, j, k) * U[g.faceXIndex(i, j, k)] +
                   d.openFractionY(i, j + 1, k) * V[g.faceYIndex(i, j + 1, k)] -
                   d.openFractionY(i, j, k) * V[g.faceYIndex(i, j, k)]) +
           top * (d.openFractionZ(i, j, k + 1) * W[g.faceZIndex(i, j, k + 1)] -
                  d.openFractionZ(i, j, k) * W[g.faceZIndex(i, j, k)]);
}

double maxOutflow_m3ps(const AirDomain& d, const WindField& f) {
    double m = 0.0;
    for (int k = 0; k < d.nz(); ++k)
        for (int j = 0; j < d.ny(); ++j)
            for (int i = 0; i < d.nx(); ++i)
                if (d.isAir(i, j, k)) m = std::max(m, std::abs(cellOutflow_m3ps(d, f, i, j, k)));
    return m;
}

TEST(UnsteadyStretched, ProjectionOverAHillLeavesTheDivergenceAtTheSolverTolerance) {
    // The projection's residual is the divergence it leaves (times h), relative to the right-hand
    // side it started from; a factor 10 covers the max-norm against the solver's own norm.
    constexpr double TOLERANCE = 1e-8, NORM_FACTOR = 10.0;
    const Heightfield hill = test::centredGaussianHill(48.0, 1.0, 6.0, 8.0);
    const AirDomain domain(hill, layers(2.0, 0.5, 20.0, 2.0));
    const SteadyWindResult mean = solveSteadyWind(domain, uniformWind(5.0), {}, test::tight());
    UnsteadySettings s;
    s.advection = AdvectionScheme::MacCormack;
    s.viscosity_m2ps = 0.05;
    s.projection.relativeTolerance = TOLERANCE;
    s.projection.maxIterations = 200;
    UnsteadyWindSolver solver(domain, mean.field, s, 5.0);
    for (int n = 0; n < 3; ++n) {
        const StepReport r = solver.step(0.5);
        ASSERT_TRUE(r.finite);
        ASSERT_TRUE(r.projection.converged);
    }
    // Stir the field, then project it once more and compare the divergence before and after.
    const std::vector<double> noise = test::randomVector(solver.field().u_mps().size(), 7u);
    for (size_t f = 0; f < noise.size(); ++f) solver.editField().u_mps()[f] += noise[f];
    const double before = maxOutflow_m3ps(domain, solver.field());
    const SolveReport rep = solver.project();
    ASSERT_TRUE(rep.converged);
    const double after = maxOutflow_m3ps(domain, solver.field());
    EXPECT_GT(before, 1e-2);  // the stirring did make a divergent field
    EXPECT_LT(after, NORM_FACTOR * TOLERANCE * before) << before << " -> " << after;
}

/// A Lamb-Oseen vortex with its axis along y at (xc, zc), added to the field's u and w faces.
void addVortexAlongY(UnsteadyWindSolver& solver, double xc, double zc, double circulation,
                     double rc) {
    const GridLayout& g = solver.grid();
    WindField& f = solver.editField();
    for (Placement p : {Placement::FaceX, Placement::FaceZ}) {
        std::vector<double>& a = p == Placement::FaceX ? f.u_mps() : f.w_mps();
        const auto n = g.dims(p);
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    const Vec3d x = g.wsPosition(p, i, j, k);
                    const double dx = x[0] - xc, dz = x[2] - zc, r = std::hypot(dx, dz);
                    if (r < 1e-12) continue;
                    const double vt = exact::lambOseenSpeed_mps(circulation, rc * rc, r);
                    // Counter-clockwise in (x, z): e_theta = (-dz, dx) / r.
                    a[g.index(p, i, j, k)] += vt * (p == Placement::FaceX ? -dz / r : dx / r);
                }
    }
}

TEST(UnsteadyStretched, TranslatingVortexThroughTheThinLayersMatchesTheCubicRun) {
    // A vortex (core 0.8 m = 4 cells, peak 1 m/s) carried at 1 m/s along x 1.6 m above free-slip
    // ground, under a lid at 4 m, for 2 s; stretched layers from h / 4 (0.05 m) reach h at about
    // 0.45 m, so the strong flow between the core and the ground crosses them. Both runs see the
    // same ground, lid and open sides and differ by the vertical sampling only; the vortex's
    // path differs by a fraction of a cell, which at the core's gradient (about 2 / s) is a few
    // hundredths of a m/s (measured 0.063 m/s); a tenth of the peak speed holds it.
    constexpr double MATCH_TOLERANCE = 0.1;
    const double h = 0.2, U = 1.0, rc = 0.8, zc = 1.6, xc = 3.0, T = 2.0;
    const double circulation = 1.0 / (exact::lambOseenSpeed_mps(1.0, rc * rc, 1.1209 * rc));
    const Heightfield flat = flatGround(10.0, 1.0, 0.25);
    DomainSpec cubic;
    cubic.voxelSize_m = h;
    cubic.top_m = 4.0;
    const AirDomain cubes(flat, cubic), stretched(flat, layers(h, 0.25 * h, 4.0, h));
    ASSERT_GT(stretched.nz(), cubes.nz());
    auto run = [&](const AirDomain& d) {
        const SteadyWindResult mean = solveSteadyWind(d, uniformWind(U), {}, test::tight());
        UnsteadySettings s;
        s.advection = AdvectionScheme::MacCormack;
        s.dt_s = 0.1;
        auto solver = std::make_unique<UnsteadyWindSolver>(d, mean.field, s, U);
        addVortexAlongY(*solver, xc, zc, circulation, rc);
        (void)solver->project();
        for (const StepReport& r : solver->advanceTo(T)) EXPECT_TRUE(r.finite);
        return solver;
    };
    const auto a = run(cubes), b = run(stretched);
    // From 1.5 h up: below the cubic run's second centre it holds its first centre's value, which
    // the thin layers resolve (there the runs differ by 0.2 m/s).
    double worst = 0.0;
    for (double x = xc + U * T - 1.5; x <= xc + U * T + 1.5; x += 0.1)
        for (double z = 1.5 * h; z <= 3.0; z += 0.1) {
            const Vec3d va = a->field().velocityAt_mps(x, 0.5, z);
            const Vec3d vb = b->field().velocityAt_mps(x, 0.5, z);
            worst = std::max({worst, std::abs(va[0] - vb[0]), std::abs(va[2] - vb[2])});
        }
    EXPECT_LT(worst, MATCH_TOLERANCE);
}

TEST(UnsteadyStretched, ExtremeWindOnTheThinnestFirstLayerStaysFinite) {
    // 1e3 m/s over a hill with the first layer at h / 5 (the smallest allowed): every scheme,
    // viscosity and confinement on, adaptive steps. Bounded: within 10 U (a projection can
    // redistribute speed, not multiply it).
    constexpr double SPEED_BOUND_FACTOR = 10.0;
    const double U = 1e3;
    const Heightfield hill = test::centredGaussianHill(32.0, 1.0, 5.0, 6.0);
    const AirDomain domain(hill, layers(2.0, 0.4, 16.0, 4.0));
    const SteadyWindResult mean = solveSteadyWind(domain, uniformWind(U), {}, {});
    for (AdvectionScheme scheme : SCHEMES) {
        UnsteadySettings s;
        s.advection = scheme;
        s.cfl = 20.0;
        s.viscosity_m2ps = 1.0;
        s.vorticityConfinement = 0.5;
        UnsteadyWindSolver solver(domain, mean.field, s, U);
        for (int n = 0; n < 3; ++n) (void)solver.step(solver.nextDt_s());
        double maxAbs = 0.0;
        bool finite = true;
        for (const auto* a :
             {&solver.field().u_mps(), &solver.field().v_mps(), &solver.field().w_mps()})
            for (double x : *a) {
                finite = finite && std::isfinite(x);
                maxAbs = std::max(maxAbs, std::abs(x));
            }
        EXPECT_TRUE(finite) << advectionSchemeName(scheme);
        EXPECT_LT(maxAbs, SPEED_BOUND_FACTOR * U) << advectionSchemeName(scheme);
    }
}

}  // namespace
}  // namespace gale::sim
