/// \file BenchJacksonHunt.cpp
/// `gale bench models --jackson-hunt`: the crest speed-up of low two-dimensional ridges against
/// the linear theory of Jackson and Hunt (1975) (docs/validation.md, section 2); the study itself
/// is validation/JacksonHuntStudy.h, this file prints its tables.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "app/bench/BenchModels.h"
#include "app/io/Errors.h"
#include "validation/JacksonHuntStudy.h"

namespace gale::app {
namespace {

using namespace validation::jacksonhunt;

/// Where the ridge sits against the grid: the whole ground raised by base_m (m, vertical) and the
/// crest moved downwind by shift_m (m); both zero in the main table.
struct GridOffset {
    double base_m = 0, shift_m = 0;
};

validation::JacksonHuntStudy solve(double H_m, bool momentum, GridOffset offset = {}) {
    validation::JacksonHuntOptions o;
    o.H_m = H_m, o.momentum = momentum, o.base_m = offset.base_m, o.shift_m = offset.shift_m;
    return validation::runJacksonHunt(o);
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
    for (double H : HEIGHTS_M) {
        const validation::JacksonHuntStudy m = solve(H, /*momentum=*/true);
        const validation::JacksonHuntStudy mc = solve(H, /*momentum=*/false);
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
        const validation::JacksonHuntStudy m = solve(H, /*momentum=*/true, offset);
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
