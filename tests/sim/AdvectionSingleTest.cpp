// The single-precision row pass of the advection (AdvectionPrecision::Single, sim/AdvectionRows.h)
// against its oracles: a linear field carried by a uniform wind (exact for the midpoint trace and
// trilinear interpolation, so any slip in a stencil, a stride or a lane shows), the double path on
// random flows over a hill (float round-off apart), the samples it must hand to the general path
// (traces longer than one substep, non-finite wind) and the mask.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "sim/Advection.h"

namespace gale::sim {
namespace {

/// Sizes that are no multiple of any vector width, so every row ends in a partial vector.
constexpr int NX = 21, NY = 11, NZ = 9;
constexpr double H_M = 1.7;
const Vec3d WS_MIN_M = {-3.1, 5.3, 11.0};

const Placement ALL[] = {Placement::FaceX, Placement::FaceY, Placement::FaceZ, Placement::Cell};
const AdvectionScheme SCHEMES[] = {AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack,
                                   AdvectionScheme::Bfecc};

std::vector<double> randomField(size_t n, std::mt19937& rng, double mean, double spread) {
    std::uniform_real_distribution<double> d(-1.0, 1.0);
    std::vector<double> f(n);
    for (double& x : f) x = mean + spread * d(rng);
    return f;
}

/// A random MAC wind: each component uniform in mean +- spread (m/s).
struct Wind {
    std::vector<double> u, v, w;
    Wind(const GridIndex& g, std::mt19937& rng, const Vec3d& mean, double spread)
        : u(randomField(g.count(Placement::FaceX), rng, mean[0], spread)),
          v(randomField(g.count(Placement::FaceY), rng, mean[1], spread)),
          w(randomField(g.count(Placement::FaceZ), rng, mean[2], spread)) {}
    MacVelocity vel() const { return {&u, &v, &w}; }
};

/// A hill whose flanks cut the lowest layers and whose foot lies below the box.
Heightfield hill(const GridLayout& g) {
    Heightfield hf;
    hf.nx = 61, hf.ny = 31, hf.spacing_m = 0.65;
    hf.originX_m = g.wsMin_m[0] - 1.0, hf.originY_m = g.wsMin_m[1] - 1.0;
    const double cx = hf.originX_m + 18.0, cy = hf.originY_m + 9.0;
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            const double x = hf.originX_m + i * hf.spacing_m - cx,
                         y = hf.originY_m + j * hf.spacing_m - cy;
            hf.height_m.push_back(
                float(g.wsMin_m[2] - 0.5 + 5.0 * std::exp(-(x * x + y * y) / 25)));
        }
    return hf;
}

TEST(AdvectionSingle, CarriesALinearFieldByTheUniformDisplacement) {
    // u = const: the midpoint trace is exact, departure = x - u dt, and a trilinear sample of a
    // linear field is exact wherever its stencil is not clamped. So at every sample whose
    // departure lies at least one cell inside the box the answer is q(x - u dt), to round-off
    // of the float positions (|grad q| times a few float ulps of a 21-cell coordinate).
    const MacGrid g(NX, NY, NZ, H_M, WS_MIN_M);
    const Vec3d u_mps = {1.3, -0.7, 0.4};
    const std::vector<double> U(g.count(Placement::FaceX), u_mps[0]),
        V(g.count(Placement::FaceY), u_mps[1]), W(g.count(Placement::FaceZ), u_mps[2]);
    const double dt_s = 1.2 * H_M / 1.3;      // 1.2 cells along x: one substep
    const Vec3d slope = {0.31, -0.17, 0.23};  // per metre
    auto linear = [&](const Vec3d& x) {
        return 2.0 + slope[0] * x[0] + slope[1] * x[1] + slope[2] * x[2];
    };
    for (AdvectionPrecision precision : {AdvectionPrecision::Double, AdvectionPrecision::Single})
        for (Placement p : ALL) {
            const auto d = g.dims(p);
            std::vector<double> q(g.count(p)), out;
            for (int k = 0; k < d[2]; ++k)
                for (int j = 0; j < d[1]; ++j)
                    for (int i = 0; i < d[0]; ++i)
                        q[g.index(p, i, j, k)] = linear(g.wsPosition(p, i, j, k));
            advect(g, p, q, {&U, &V, &W}, {}, {}, dt_s, AdvectionScheme::SemiLagrangian, out,
                   nullptr, precision);
            // Float positions: a few ulps of a 36 m coordinate times |grad q| ~0.4 (measured
            // 6e-7); a wrong stencil or stride is off by O(0.1).
            const double tol = precision == AdvectionPrecision::Single ? 5e-6 : 1e-12;
            int checked = 0;
            double worst = 0.0;
            for (int k = 0; k < d[2]; ++k)
                for (int j = 0; j < d[1]; ++j)
                    for (int i = 0; i < d[0]; ++i) {
                        const Vec3d x = g.wsPosition(p, i, j, k);
                        const Vec3d dep = {x[0] - u_mps[0] * dt_s, x[1] - u_mps[1] * dt_s,
                                           x[2] - u_mps[2] * dt_s};
                        const Vec3d is = g.isFromWs(dep);
                        if (!(is[0] > 1 && is[0] < NX - 1 && is[1] > 1 && is[1] < NY - 1 &&
                              is[2] > 1 && is[2] < NZ - 1))
                            continue;
                        const double got = out[g.index(p, i, j, k)];
                        worst = std::max(worst, std::abs(got - linear(dep)));
                        ASSERT_NEAR(got, linear(dep), tol)
                            << advectionPrecisionName(precision) << " placement " << int(p)
                            << " sample " << i << "," << j << "," << k;
                        ++checked;
                    }
            EXPECT_GT(checked, 400) << "placement " << int(p);
            std::printf("%s, placement %d: %d samples, largest error %.3g\n",
                        advectionPrecisionName(precision), int(p), checked, worst);
        }
}

TEST(AdvectionSingle, EveryInstructionSetTheMachineRunsGivesTheSameRows) {
    // The row kernel is compiled once per instruction set and one is picked at run time; CI's
    // machine runs the widest. Each set this machine supports, forced in turn, must agree with
    // the double path to float round-off over the hill (a lane or tail slip in one of them is
    // off by O(0.1)), so the narrower ones are checked too.
    const GridLayout layout(NX, NY, NZ, H_M, WS_MIN_M);
    const Heightfield hf = hill(layout);
    const MacGrid g(layout, &hf);
    std::mt19937 rng(29);
    const Wind wind(g, rng, {3.0, -1.0, -1.5}, 1.5);
    const double dt_s = 1.2 * H_M / 4.5;
    const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
    ASSERT_FALSE(targets.empty());
    for (int64_t target : targets) {
        hwy::SetSupportedTargetsForTest(target);
        for (Placement p : ALL) {
            const std::vector<double> q = randomField(g.count(p), rng, 0.0, 1.0);
            std::vector<double> a, b;
            advect(g, p, q, wind.vel(), {}, {}, dt_s, AdvectionScheme::MacCormack, a, nullptr,
                   AdvectionPrecision::Single);
            advect(g, p, q, wind.vel(), {}, {}, dt_s, AdvectionScheme::MacCormack, b, nullptr,
                   AdvectionPrecision::Double);
            double worst = 0.0;
            for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
            EXPECT_LT(worst, 5e-5) << hwy::TargetName(target) << " placement " << int(p);
        }
        std::printf("%s: rows agree with the double path\n", hwy::TargetName(target));
    }
    hwy::SetSupportedTargetsForTest(0);  // back to the machine's own choice
}

TEST(AdvectionSingle, EqualsTheDoublePathToFloatRoundOffOverAHill) {
    // Random wind about a mean across the box and down into the hill: traces leave through the
    // sides and the top, cross the terrain, start below it, and some need two substeps. Values
    // of O(1): float keeps about 7 digits, so single and double differ by ~1e-6 per pass.
    const GridLayout layout(NX, NY, NZ, H_M, WS_MIN_M);
    const Heightfield hf = hill(layout);
    const MacGrid g(layout, &hf);
    std::mt19937 rng(11);
    const Wind wind(g, rng, {3.0, -1.0, -1.5}, 1.5);
    const std::vector<double>&U = wind.u, &V = wind.v, &W = wind.w;
    const FarField far = [](const Vec3d& x) { return Vec3d{3.0, -1.0, -0.5 + 0.01 * x[2]}; };
    const OutsideValue inflow = [](const Vec3d& x) { return 0.3 + 0.02 * x[2]; };
    const double dt_s = 1.2 * H_M / 4.5;
    for (AdvectionScheme scheme : SCHEMES)
        for (Placement p : ALL) {
            const std::vector<double> q = randomField(g.count(p), rng, 0.0, 1.0);
            std::vector<double> a, b;
            advect(g, p, q, {&U, &V, &W}, far, inflow, dt_s, scheme, a, nullptr,
                   AdvectionPrecision::Single);
            advect(g, p, q, {&U, &V, &W}, far, inflow, dt_s, scheme, b, nullptr,
                   AdvectionPrecision::Double);
            double worst = 0.0;
            size_t same = 0;
            for (size_t i = 0; i < a.size(); ++i) {
                ASSERT_TRUE(std::isfinite(a[i]));
                worst = std::max(worst, std::abs(a[i] - b[i]));
                same += a[i] == b[i];
                // Measured 2e-6; a wrong stencil, stride or lane is off by O(0.1).
                ASSERT_NEAR(a[i], b[i], 5e-5)
                    << advectionSchemeName(scheme) << " placement " << int(p) << " sample " << i;
            }
            std::printf("%s, placement %d: largest difference %.3g, %zu of %zu bit-equal\n",
                        advectionSchemeName(scheme), int(p), worst, same, a.size());
        }
}

TEST(AdvectionSingle, HandsLongTracesToTheGeneralPathBitForBit) {
    // At 5 cells a step no trace is one substep: every sample goes to the double path, so the
    // semi-Lagrangian answer is the double path's exactly.
    const GridLayout layout(NX, NY, NZ, H_M, WS_MIN_M);
    const Heightfield hf = hill(layout);
    const MacGrid g(layout, &hf);
    std::mt19937 rng(13);
    const Wind wind(g, rng, {6.0, 5.0, -5.0}, 0.5);
    const std::vector<double>&U = wind.u, &V = wind.v, &W = wind.w;
    const double dt_s = 5.0 * H_M / 4.5;
    for (Placement p : ALL) {
        const std::vector<double> q = randomField(g.count(p), rng, 0.0, 1.0);
        std::vector<double> a, b;
        advect(g, p, q, {&U, &V, &W}, {}, {}, dt_s, AdvectionScheme::SemiLagrangian, a, nullptr,
               AdvectionPrecision::Single);
        advect(g, p, q, {&U, &V, &W}, {}, {}, dt_s, AdvectionScheme::SemiLagrangian, b, nullptr,
               AdvectionPrecision::Double);
        for (size_t i = 0; i < a.size(); ++i)
            ASSERT_EQ(a[i], b[i]) << "placement " << int(p) << " sample " << i;
    }
}

TEST(AdvectionSingle, NonFiniteWindStaysWhereTheDoublePathPutsIt) {
    // A NaN and an infinite face: lanes that read them are handed to the double path, so every
    // sample is finite exactly where the double path's is, and close to it there.
    const MacGrid g(NX, NY, NZ, H_M, WS_MIN_M);
    std::mt19937 rng(17);
    Wind wind(g, rng, {2.0, 0.5, 0.0}, 0.5);
    std::vector<double>&U = wind.u, &V = wind.v, &W = wind.w;
    U[g.index(Placement::FaceX, 10, 5, 4)] = std::numeric_limits<double>::quiet_NaN();
    W[g.index(Placement::FaceZ, 3, 7, 2)] = std::numeric_limits<double>::infinity();
    const double dt_s = 1.0 * H_M / 2.5;
    for (AdvectionScheme scheme : SCHEMES)
        for (Placement p : ALL) {
            const std::vector<double> q = randomField(g.count(p), rng, 0.0, 1.0);
            std::vector<double> a, b;
            advect(g, p, q, {&U, &V, &W}, {}, {}, dt_s, scheme, a, nullptr,
                   AdvectionPrecision::Single);
            advect(g, p, q, {&U, &V, &W}, {}, {}, dt_s, scheme, b, nullptr,
                   AdvectionPrecision::Double);
            size_t nonFinite = 0;
            for (size_t i = 0; i < a.size(); ++i) {
                ASSERT_EQ(std::isfinite(a[i]), std::isfinite(b[i]))
                    << advectionSchemeName(scheme) << " placement " << int(p) << " sample " << i;
                if (std::isfinite(a[i])) {
                    ASSERT_NEAR(a[i], b[i], 5e-5);
                } else {
                    ++nonFinite;
                }
            }
            EXPECT_LT(nonFinite, a.size() / 10) << "the bad faces spread over the whole box";
        }
}

TEST(AdvectionSingle, MaskedSamplesKeepTheirValuesExactly) {
    const MacGrid g(NX, NY, NZ, H_M, WS_MIN_M);
    std::mt19937 rng(19);
    const Wind wind(g, rng, {2.0, 0.5, 0.0}, 0.5);
    const std::vector<double>&U = wind.u, &V = wind.v, &W = wind.w;
    for (Placement p : ALL) {
        const std::vector<double> q = randomField(g.count(p), rng, 0.0, 1.0);
        std::vector<uint8_t> mask(q.size());
        for (size_t i = 0; i < mask.size(); ++i) mask[i] = (i * 7919) % 5 != 0;
        std::vector<double> out;
        advect(g, p, q, {&U, &V, &W}, {}, {}, H_M / 2.5, AdvectionScheme::MacCormack, out, &mask,
               AdvectionPrecision::Single);
        size_t moved = 0;
        for (size_t i = 0; i < q.size(); ++i) {
            if (!mask[i]) {
                ASSERT_EQ(out[i], q[i]) << "placement " << int(p) << " sample " << i;
            }
            moved += mask[i] && out[i] != q[i];
        }
        EXPECT_GT(moved, q.size() / 2);
    }
}

TEST(AdvectionSingle, AVelocityRoundedByTheCallerGivesTheSameAnswer) {
    const MacGrid g(NX, NY, NZ, H_M, WS_MIN_M);
    std::mt19937 rng(23);
    const Wind wind(g, rng, {2.0, 0.5, 0.0}, 0.5);
    const std::vector<double>&U = wind.u, &V = wind.v, &W = wind.w;
    const std::vector<float> Uf(U.begin(), U.end()), Vf(V.begin(), V.end()), Wf(W.begin(), W.end());
    const MacVelocity rounded{&U, &V, &W, &Uf, &Vf, &Wf};
    for (Placement p : ALL) {
        const std::vector<double> q = randomField(g.count(p), rng, 0.0, 1.0);
        std::vector<double> a, b;
        advect(g, p, q, {&U, &V, &W}, {}, {}, H_M / 2.5, AdvectionScheme::Bfecc, a, nullptr,
               AdvectionPrecision::Single);
        advect(g, p, q, rounded, {}, {}, H_M / 2.5, AdvectionScheme::Bfecc, b, nullptr,
               AdvectionPrecision::Single);
        ASSERT_EQ(a, b) << "placement " << int(p);
    }
    const std::vector<float> shortU(Uf.begin(), Uf.end() - 1);
    std::vector<double> out;
    EXPECT_THROW(advect(g, Placement::Cell, std::vector<double>(g.count(Placement::Cell)),
                        {&U, &V, &W, &shortU, &Vf, &Wf}, {}, {}, 0.1,
                        AdvectionScheme::SemiLagrangian, out, nullptr, AdvectionPrecision::Single),
                 std::logic_error);
}

TEST(AdvectionSingle, PrecisionNamesRoundTripAndABadOneNamesTheKey) {
    for (AdvectionPrecision p : {AdvectionPrecision::Double, AdvectionPrecision::Single})
        EXPECT_EQ(advectionPrecisionFromName(advectionPrecisionName(p)), p);
    try {
        (void)advectionPrecisionFromName("half");
        FAIL() << "no error";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("unsteady.precision"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace gale::sim
