// The cubic-cell fast path of the advection (sim/UniformLattice.h) against the general one: the
// same staggered sampler and the same traces, so on random fields and points (inside the box,
// outside it, below the terrain, on cut cells, on lattice points and at extreme coordinates) the
// two differ only by round-off. The general path is reached on the very same geometry by
// declaring the cubic cells' levels explicitly (a "stretched" layout whose layers are all h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "sim/Advection.h"
#include "sim/UniformLattice.h"

namespace gale::sim {
namespace {

constexpr int NX = 12, NY = 9, NZ = 7;
/// A cell edge far from 1 m and not a power of two, so 1/h is inexact and the two paths really
/// round differently.
constexpr double H_M = 1.7;
const Vec3d WS_MIN_M = {-3.1, 5.3, 11.0};
/// One sample from the two samplers: they differ by a few ulps of the index coordinate (a product
/// by 1/h against a quotient by h) times a field difference of O(1); a wrong stencil or clamp is
/// off by O(0.1).
constexpr double SAMPLE_TOLERANCE = 1e-12;
/// A whole advection step and a departure point (metres): the round-off of each sample carried
/// through a trace's substeps, the terrain bisection and two or three passes (measured: 6e-15);
/// the headroom is for another compiler's rounding, still far below the O(0.1) of a real slip.
constexpr double ADVECT_TOLERANCE = 1e-11;
constexpr double TRACE_TOLERANCE_M = 1e-11;

std::vector<double> randomField(size_t n, std::mt19937& rng) {
    std::uniform_real_distribution<double> d(-1.0, 1.0);
    std::vector<double> f(n);
    for (double& x : f) x = d(rng);
    return f;
}

/// The same cubic cells as a layout with explicit level heights (GridLayout's general path).
GridLayout explicitLevels(const GridLayout& g) {
    std::vector<double> z(size_t(g.nz) + 1);
    for (int k = 0; k <= g.nz; ++k) z[size_t(k)] = g.wsMin_m[2] + k * g.voxelSize_m;
    return GridLayout(g.nx, g.ny, g.voxelSize_m, g.wsMin_m, z);
}

/// Random world points within 3 cells of the box (so about half lie outside it), plus every
/// lattice point of the box's corners and a few face and centre positions.
std::vector<Vec3d> testPoints(const GridLayout& g, std::mt19937& rng) {
    std::vector<Vec3d> pts;
    const double margin_m = 3.0 * H_M;
    std::uniform_real_distribution<double> dx(g.wsMin_m[0] - margin_m,
                                              g.wsMin_m[0] + g.nx * H_M + margin_m);
    std::uniform_real_distribution<double> dy(g.wsMin_m[1] - margin_m,
                                              g.wsMin_m[1] + g.ny * H_M + margin_m);
    std::uniform_real_distribution<double> dz(g.wsMin_m[2] - margin_m,
                                              g.wsMin_m[2] + g.nz * H_M + margin_m);
    for (int n = 0; n < 2000; ++n) pts.push_back({dx(rng), dy(rng), dz(rng)});
    for (int k = 0; k <= 2 * g.nz; k += 3)
        for (int j = 0; j <= 2 * g.ny; j += 2)
            for (int i = 0; i <= 2 * g.nx; i += 3)  // faces and centres: half-cell steps
                pts.push_back(g.wsFromIs({0.5 * i, 0.5 * j, 0.5 * k}));
    return pts;
}

TEST(UniformLattice, SamplesEveryPlacementAsTheLayoutSamplerToRoundOff) {
    const GridLayout g(NX, NY, NZ, H_M, WS_MIN_M);
    ASSERT_TRUE(UniformLattice::usable(g));
    const UniformLattice lattice(g);
    std::mt19937 rng(7);
    const Placement all[] = {Placement::FaceX, Placement::FaceY, Placement::FaceZ, Placement::Cell};
    std::vector<std::vector<double>> q;
    for (Placement p : all) q.push_back(randomField(g.count(p), rng));
    double worst = 0.0;
    for (const Vec3d& x : testPoints(g, rng)) {
        const Vec3d is = g.isFromWs(x);
        for (int p = 0; p < 4; ++p) {
            double lo = 0, hi = 0, loRef = 0, hiRef = 0;
            const double fast = lattice.sample(all[p], q[size_t(p)].data(), x.data(), &lo, &hi);
            const double ref = g.sample(all[p], q[size_t(p)].data(), is, &loRef, &hiRef);
            worst = std::max(worst, std::abs(fast - ref));
            ASSERT_NEAR(fast, ref, SAMPLE_TOLERANCE)
                << "placement " << p << " at " << x[0] << " " << x[1] << " " << x[2];
            // The limiter's bounds are the same 8 values whenever the stencils agree.
            ASSERT_NEAR(lo, loRef, SAMPLE_TOLERANCE);
            ASSERT_NEAR(hi, hiRef, SAMPLE_TOLERANCE);
        }
        double uvw[3];
        lattice.sampleFaces(q[0].data(), q[1].data(), q[2].data(), x.data(), uvw);
        const Vec3d ref = g.sampleFaces(q[0].data(), q[1].data(), q[2].data(), is);
        for (int a = 0; a < 3; ++a) ASSERT_NEAR(uvw[a], ref[a], SAMPLE_TOLERANCE);
    }
    std::printf("largest difference of a sample: %.3g\n", worst);
}

TEST(UniformLattice, VelocityAtEverySampleFromItsNeighboursEqualsTheStencilSample) {
    // The trace starts read the velocity at the samples themselves (facesAtSample); the oracle is
    // the layout's general sampler at each sample's world position, every sample of every
    // placement, the box's side faces (where the cell-centre lattices clamp) included.
    const GridLayout g(NX, NY, NZ, H_M, WS_MIN_M);
    const UniformLattice lattice(g);
    std::mt19937 rng(13);
    const std::vector<double> u = randomField(g.count(Placement::FaceX), rng),
                              v = randomField(g.count(Placement::FaceY), rng),
                              w = randomField(g.count(Placement::FaceZ), rng);
    double worst = 0.0;
    for (Placement p : {Placement::FaceX, Placement::FaceY, Placement::FaceZ, Placement::Cell}) {
        const auto n = g.dims(p);
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    double fast[3];
                    lattice.facesAtSample(p, i, j, k, u.data(), v.data(), w.data(), fast);
                    const Vec3d ref = g.sampleFaces(u.data(), v.data(), w.data(),
                                                    g.isFromWs(g.wsPosition(p, i, j, k)));
                    for (int a = 0; a < 3; ++a) {
                        worst = std::max(worst, std::abs(fast[a] - ref[size_t(a)]));
                        ASSERT_NEAR(fast[a], ref[size_t(a)], SAMPLE_TOLERANCE)
                            << "placement " << int(p) << " sample " << i << " " << j << " " << k
                            << " component " << a;
                    }
                }
    }
    std::printf("largest difference of a velocity at a sample: %.3g\n", worst);
}

TEST(UniformLattice, ExtremeAndNonFiniteCoordinatesClampToTheBoxSamples) {
    const GridLayout g(NX, NY, NZ, H_M, WS_MIN_M);
    const UniformLattice lattice(g);
    std::mt19937 rng(11);
    const std::vector<double> q = randomField(g.count(Placement::FaceZ), rng);
    const double inf = std::numeric_limits<double>::infinity();
    for (double c : {1e300, -1e300, inf, -inf}) {
        const Vec3d x = {c, -c, c};
        const double fast = lattice.sample(Placement::FaceZ, q.data(), x.data());
        EXPECT_TRUE(std::isfinite(fast));
        EXPECT_EQ(fast, g.sample(Placement::FaceZ, q.data(), g.isFromWs(x)));
    }
    // NaN has no place in the box: it clamps to the first sample instead of indexing anywhere.
    const Vec3d nan = {std::nan(""), std::nan(""), std::nan("")};
    EXPECT_EQ(lattice.sample(Placement::FaceZ, q.data(), nan.data()), q[0]);
}

/// A hill whose flanks cut through the lowest layers of the box (cut cells) and whose foot lies
/// below the box bottom.
Heightfield hill(const GridLayout& g) {
    Heightfield hf;
    hf.nx = 41, hf.ny = 31, hf.spacing_m = 0.6;
    hf.originX_m = g.wsMin_m[0] - 1.0, hf.originY_m = g.wsMin_m[1] - 1.0;
    const double cx = hf.originX_m + 12.0, cy = hf.originY_m + 9.0;
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            const double x = hf.originX_m + i * hf.spacing_m - cx,
                         y = hf.originY_m + j * hf.spacing_m - cy;
            hf.height_m.push_back(
                float(g.wsMin_m[2] - 0.5 + 4.5 * std::exp(-(x * x + y * y) / 20)));
        }
    return hf;
}

/// Random velocity about a mean that blows across the box and down into the hill, so traces
/// leave through the sides and the top, cross the terrain and start below it.
struct Flow {
    std::vector<double> u, v, w;
    Flow(const GridLayout& g, std::mt19937& rng)
        : u(randomField(g.count(Placement::FaceX), rng)),
          v(randomField(g.count(Placement::FaceY), rng)),
          w(randomField(g.count(Placement::FaceZ), rng)) {
        for (double& x : u) x = 3.0 + 1.5 * x;
        for (double& x : v) x = -1.0 + 1.5 * x;
        for (double& x : w) x = -1.5 + 1.5 * x;
    }
    MacVelocity vel() const { return {&u, &v, &w}; }
};

TEST(UniformLattice, AdvectionOnCubicCellsEqualsTheGeneralPathToRoundOff) {
    const GridLayout cubic(NX, NY, NZ, H_M, WS_MIN_M);
    const GridLayout general = explicitLevels(cubic);
    ASSERT_TRUE(UniformLattice::usable(cubic));
    ASSERT_FALSE(UniformLattice::usable(general));
    const Heightfield hf = hill(cubic);
    const MacGrid fast(cubic, &hf), slow(general, &hf);
    std::mt19937 rng(3);
    const Flow flow(cubic, rng);
    const FarField far = [](const Vec3d& x) { return Vec3d{3.0, -1.0, -0.5 + 0.01 * x[2]}; };
    const OutsideValue inflow = [](const Vec3d& x) { return 0.3 + 0.02 * x[2]; };
    const double dt_s = 1.5 * H_M / 4.5;  // about 1.5 cells at the mean speed, 3 at the fastest
    double worst = 0.0;
    for (AdvectionScheme scheme :
         {AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack, AdvectionScheme::Bfecc})
        for (Placement p :
             {Placement::FaceX, Placement::FaceY, Placement::FaceZ, Placement::Cell}) {
            const std::vector<double> q = randomField(cubic.count(p), rng);
            std::vector<double> a, b;
            advect(fast, p, q, flow.vel(), far, inflow, dt_s, scheme, a);
            advect(slow, p, q, flow.vel(), far, inflow, dt_s, scheme, b);
            ASSERT_EQ(a.size(), b.size());
            for (size_t i = 0; i < a.size(); ++i) {
                ASSERT_TRUE(std::isfinite(a[i]));
                worst = std::max(worst, std::abs(a[i] - b[i]));
                ASSERT_NEAR(a[i], b[i], ADVECT_TOLERANCE)
                    << advectionSchemeName(scheme) << " placement " << int(p) << " sample " << i;
            }
        }
    std::printf("largest difference of an advected value: %.3g\n", worst);
}

TEST(UniformLattice, TracesOnCubicCellsEqualTheGeneralPathToRoundOff) {
    const GridLayout cubic(NX, NY, NZ, H_M, WS_MIN_M);
    const Heightfield hf = hill(cubic);
    const MacGrid fast(cubic, &hf), slow(explicitLevels(cubic), &hf);
    std::mt19937 rng(5);
    const Flow flow(cubic, rng);
    const FarField far = [](const Vec3d&) { return Vec3d{2.0, 1.0, -0.7}; };
    int below = 0, outsideBox = 0;
    double worst_m = 0.0;
    for (const Vec3d& x : testPoints(cubic, rng)) {
        below += x[2] < hf.sample(x[0], x[1]);
        outsideBox += fast.outside(x);
        for (double dt_s : {0.9, -0.9}) {
            const Vec3d a = traceBack(fast, flow.vel(), far, x, dt_s);
            const Vec3d b = traceBack(slow, flow.vel(), far, x, dt_s);
            for (int k = 0; k < 3; ++k) {
                ASSERT_TRUE(std::isfinite(a[size_t(k)]));
                worst_m = std::max(worst_m, std::abs(a[size_t(k)] - b[size_t(k)]));
                ASSERT_NEAR(a[size_t(k)], b[size_t(k)], TRACE_TOLERANCE_M);
            }
        }
    }
    // The points cover the cases the fast path must agree on.
    EXPECT_GT(below, 100);
    EXPECT_GT(outsideBox, 100);
    std::printf("largest difference of a departure point: %.3g m (%d below ground, %d outside)\n",
                worst_m, below, outsideBox);
}

}  // namespace
}  // namespace gale::sim
