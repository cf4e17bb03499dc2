/// \file BenchJacksonHunt.cpp
/// `gale bench models --jackson-hunt`: the crest speed-up of low two-dimensional ridges against
/// the linear theory of Jackson and Hunt (1975) (docs/validation.md, section 2). Each ridge is
/// solved in a box a few cells across with free-slip side walls (DomainSpec::closedSidesY), the
/// two-dimensional flow the theory describes.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "app/bench/BenchModels.h"
#include "app/bench/RidgeBox.h"
#include "app/io/Errors.h"
#include "app/io/Timing.h"
#include "base/Numbers.h"
#include "sim/MomentumWind.h"
#include "sim/SteadyWind.h"

namespace gale::app {
namespace {

constexpr double L_M = 200.0;            ///< horizontal distance from the crest to half height
constexpr double CELL_M = 4.0;           ///< the cell size
constexpr double TOP_M = 300.0;          ///< the box's top
constexpr double LENGTH_M = 1600.0;      ///< the box's length along the wind
constexpr double CREST_X_M = 600.0;      ///< the crest's distance from the inflow face
constexpr double REFERENCE_X_M = 100.0;  ///< the flat upwind column the speed-up is taken against
constexpr double Z0_M = 0.03, SPEED_MPS = 10.0, REFERENCE_HEIGHT_M = 10.0;  ///< the log inflow
/// Heights above the local ground the table reports (6 m: the lowest the 4 m grid resolves).
constexpr double DZ_M[3] = {6.0, 10.0, 20.0};
/// The pseudo-time steps per level at most (a crossing of the box is about 320).
constexpr int MAX_ITERATIONS = 1000;

/// Ground height (m) of the cos^2 ridge of height H_m at xFromCrest_m: H cos^2(pi x / 4 L) for
/// |x| < 2 L (half height at x = L), 0 beyond.
double ridgeHeight_m(double H_m, double xFromCrest_m) {
    if (std::abs(xFromCrest_m) >= 2 * L_M) return 0.0;
    const double c = std::cos(PI * xFromCrest_m / (4 * L_M));
    return H_m * c * c;
}

/// Where the ridge sits against the grid: the whole ground raised by base_m (m, vertical) and the
/// crest moved downwind by shift_m (m); both zero in the main table.
struct GridOffset {
    double base_m = 0, shift_m = 0;
};

/// The ridge of height H_m sampled every CELL_M / 2 m, 3 cells across, placed at offset.
sim::Heightfield terrain(double H_m, GridOffset offset) {
    const double spacing = CELL_M / 2;
    const int nx = int(std::lround(LENGTH_M / spacing)) + 1, ny = 7;
    std::vector<float> z(size_t(nx) * ny);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            z[size_t(j) * nx + i] =
                float(offset.base_m + ridgeHeight_m(H_m, i * spacing - CREST_X_M - offset.shift_m));
    return sim::makeHeightfield(nx, ny, spacing, std::move(z));
}

/// One model on one ridge: Delta S at DZ_M above the crest against the upwind column.
struct JhRun {
    double speedup[3] = {NAN, NAN, NAN};
    int iterations = 0;
    bool converged = false;
    double seconds = 0;
};

JhRun solve(double H_m, bool momentum, GridOffset offset = {}) {
    const sim::Heightfield hf = terrain(H_m, offset);
    // A two-dimensional ridge: free-slip side walls.
    const sim::DomainSpec spec = ridgebox::spec(CELL_M, TOP_M + offset.base_m, momentum);
    const sim::AmbientWind wind = ridgebox::logLaw(SPEED_MPS, REFERENCE_HEIGHT_M, Z0_M);
    const auto t0 = Clock::now();
    const sim::AirDomain domain(hf, spec);
    sim::SolverSettings start;
    start.maxIterations = 200;
    sim::MomentumSettings ms;
    ms.maxIterations = MAX_ITERATIONS;
    const sim::SteadyModelResult res = sim::solveSteadyModel(
        domain, wind, momentum ? sim::SteadyModel::Momentum : sim::SteadyModel::MassConsistent,
        sim::MassConsistentWeights{}, start, ms);
    JhRun r;
    r.seconds = secondsSince(t0);
    r.iterations = res.report.iterations;
    r.converged = res.report.converged;
    const double y = hf.sizeY_m() / 2, zCrest = offset.base_m + ridgeHeight_m(H_m, 0.0);
    const double xCrest = CREST_X_M + offset.shift_m;
    auto speed = [&](double x, double z) {
        const auto u = res.field.velocityAt_mps(x, y, z);
        return std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    };
    for (int k = 0; k < 3; ++k) {
        const double upwind = speed(REFERENCE_X_M, offset.base_m + DZ_M[k]);
        r.speedup[k] = (speed(xCrest, zCrest + DZ_M[k]) - upwind) / upwind;
    }
    return r;
}

}  // namespace

int runJacksonHuntStudy() {
    std::printf(
        "Low ridges against Jackson and Hunt (1975) (docs/validation.md section 2): cos^2 "
        "ridges, L = %.0f m, %.0f m cells, 3 cells across with free-slip side walls, top %.0f m, "
        "%.0f m long (crest at %.0f m), log inflow z0 = %.2f m, %.0f m/s at %.0f m; Delta S at dz "
        "above the crest against the model's own wind at x = %.0f m\n",
        L_M, CELL_M, TOP_M, LENGTH_M, CREST_X_M, Z0_M, SPEED_MPS, REFERENCE_HEIGHT_M,
        REFERENCE_X_M);
    std::printf("%6s %8s %7s %8s %7s %8s %7s %10s %6s %5s %9s\n", "H/L", "dS 6m", "/(H/L)",
                "dS 10m", "/(H/L)", "dS 20m", "/(H/L)", "mc dS 6m", "iters", "conv", "seconds");
    bool ok = true;
    for (double H : {5.0, 10.0, 20.0}) {
        const JhRun m = solve(H, /*momentum=*/true);
        const JhRun mc = solve(H, /*momentum=*/false);
        const double hl = H / L_M;
        ok = ok && m.converged && std::isfinite(m.speedup[0]);
        std::printf("%6.3f %8.3f %7.2f %8.3f %7.2f %8.3f %7.2f %10.3f %6d %5s %9.1f\n", hl,
                    m.speedup[0], m.speedup[0] / hl, m.speedup[1], m.speedup[1] / hl, m.speedup[2],
                    m.speedup[2] / hl, mc.speedup[0], m.iterations, m.converged ? "yes" : "NO",
                    m.seconds);
        std::fflush(stdout);
    }
    // Does the crest's place in its cell set the coefficient at 6 m? The same ridges with the
    // whole ground raised by a quarter, a half and three quarters of a cell (the crest and the
    // sampled heights move against the cell centres; the ridge's shape does not change), and
    // the middle ridge moved downwind by a quarter and a half cell.
    std::printf(
        "\nThe momentum model's Delta S / (H/L) with the ridge moved against the grid (ground "
        "raised by base, crest moved downwind by shift)\n");
    std::printf("%6s %7s %7s %18s %8s %8s %8s %6s %5s\n", "H/L", "base m", "shift m",
                "crest in its cell", "6 m", "10 m", "20 m", "iters", "conv");
    std::vector<std::pair<double, GridOffset>> moved;
    for (double H : {5.0, 10.0, 20.0})
        for (double base : {0.0, 0.25, 0.5, 0.75}) moved.push_back({H, {base * CELL_M, 0.0}});
    for (double shift : {0.25, 0.5}) moved.push_back({10.0, {0.0, shift * CELL_M}});
    for (const auto& [H, offset] : moved) {
        const JhRun m = solve(H, /*momentum=*/true, offset);
        const double hl = H / L_M, crestZ = offset.base_m + H;
        ok = ok && m.converged && std::isfinite(m.speedup[0]);
        std::printf("%6.3f %7.1f %7.1f %18.2f %8.2f %8.2f %8.2f %6d %5s\n", hl, offset.base_m,
                    offset.shift_m, crestZ / CELL_M - std::floor(crestZ / CELL_M),
                    m.speedup[0] / hl, m.speedup[1] / hl, m.speedup[2] / hl, m.iterations,
                    m.converged ? "yes" : "NO");
        std::fflush(stdout);
    }
    return ok ? EXIT_OK : EXIT_UNMET;
}

}  // namespace gale::app
