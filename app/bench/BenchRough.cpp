/// \file BenchRough.cpp
/// `gale bench rough` (BenchRough.h).
#include "app/bench/BenchRough.h"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <vector>

#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/io/Timing.h"
#include "base/Numbers.h"
#include "sim/AirDomain.h"
#include "sim/SteadyWind.h"
#include "validation/PoissonTerrains.h"

namespace gale::app {
namespace {

/// The target: iterations to a 1e-6 max-norm relative residual at every resolution.
constexpr int MAX_ITERATIONS_TARGET = 20;
constexpr double TOLERANCE = 1e-6;
/// A resampled 30 m DEM: 10 m pixels; the spike and the features are one or two pixels wide.
constexpr double PIXEL_M = 10.0, RELIEF_M = 100.0;

/// CPU seconds of this process, all threads (user + system): under a shared machine's load the
/// solve's wall time mostly measures waiting, its CPU time the work.
double processCpuSeconds() {
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return double(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
           1e-6 * double(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

}  // namespace

int runBenchRough(const BenchRoughOptions& opt) {
    const double size_m = opt.quick ? 320.0 : 1280.0;
    const std::vector<double> voxels_m = {20.0, 10.0, 5.0};
    sim::AmbientWind wind;
    wind.profile = sim::WindProfile::Uniform;
    wind.speed_mps = 10.0;
    wind.direction_deg = 30.0;
    sim::SolverSettings settings;
    settings.relativeTolerance = TOLERANCE;
    settings.maxIterations = 200;
    std::printf(
        "steady solve to %.0e max-norm relative residual, uniform 10 m/s towards 30 deg, automatic "
        "top, "
        "%.0f m square, %.0f m pixels\n",
        TOLERANCE, size_m, PIXEL_M);
    std::printf("%-15s %7s %8s %14s %10s %9s %9s %7s %10s %11s %9s %9s %9s %12s\n", "terrain",
                "cell m", "first m", "cells", "air", "est. MiB", "MiB/Mcell", "levels",
                "iterations", "residual", "setup s", "solve s", "cpu s", "cpu ns/c/it");
    nlohmann::json rows = nlohmann::json::array();
    bool ok = true;
    for (validation::RoughTerrainKind kind :
         {validation::RoughTerrainKind::Fractal, validation::RoughTerrainKind::SharpFeatures}) {
        const sim::Heightfield terrain =
            validation::makeRoughTerrain(kind, size_m, PIXEL_M, RELIEF_M);
        // Each resolution with cubic cells, then with stretched layers from h / 4 (growing by 1.2
        // to 2 h; docs/solver.md, "Stretched layers").
        for (double h : voxels_m)
            for (bool stretched : {false, true}) {
                std::fprintf(stderr, "bench rough: %s at %.0f m%s...\n",
                             validation::roughTerrainName(kind), h, stretched ? ", stretched" : "");
                sim::DomainSpec spec;
                spec.voxelSize_m = h;
                spec.memoryLimit_bytes = 8e9;
                if (stretched) spec.firstCell_m = h / 4;
                const double first_m = stretched ? h / 4 : h;
                const auto t0 = Clock::now();
                const sim::AirDomain domain(terrain, spec);
                sim::SteadyWindSolver solver(domain);
                const double setup_s = secondsSince(t0);
                const double cpu0_s = processCpuSeconds();
                const sim::SteadyWindResult res = solver.solve(wind, settings);
                const double cpu_s = processCpuSeconds() - cpu0_s;
                const sim::SolveReport& rep = res.report;
                // Per cell of the box (air and rock: the solver's arrays span the box) and per
                // iteration; the estimate per million cells of the box.
                const double boxCells = double(domain.boxCellCount());
                const double cpuPerCellIteration_ns =
                    1e9 * cpu_s / (boxCells * std::max(1, rep.iterations));
                const double estimate_MiB = double(domain.memoryEstimate_bytes()) / MIB;
                const bool met = rep.converged && rep.iterations <= MAX_ITERATIONS_TARGET;
                ok = ok && met;
                char cells[48];
                std::snprintf(cells, sizeof cells, "%dx%dx%d", domain.nx(), domain.ny(),
                              domain.nz());
                std::printf(
                    "%-15s %7.1f %8.2f %14s %10zu %9.0f %9.1f %7d %10d %11.2e %9.2f %9.2f %9.2f "
                    "%12.1f%s\n",
                    validation::roughTerrainName(kind), h, first_m, cells, domain.activeCellCount(),
                    estimate_MiB, estimate_MiB / (boxCells / 1e6), rep.levels, rep.iterations,
                    rep.relativeResidual, setup_s, rep.solveSeconds, cpu_s, cpuPerCellIteration_ns,
                    met ? "" : "  MISSED");
                rows.push_back(
                    {{"terrain", validation::roughTerrainName(kind)},
                     {"voxel_size_m", h},
                     {"first_cell_m", first_m},
                     {"memory_estimate_bytes", domain.memoryEstimate_bytes()},
                     {"cells", {domain.nx(), domain.ny(), domain.nz()}},
                     {"air_cells", domain.activeCellCount()},
                     {"levels", rep.levels},
                     {"iterations", rep.iterations},
                     {"relative_residual", rep.relativeResidual},
                     {"converged", rep.converged},
                     {"setup_s", setup_s},
                     {"solve_s", rep.solveSeconds},
                     {"solve_cpu_s", cpu_s},
                     {"cpu_ns_per_cell_iteration", cpuPerCellIteration_ns},
                     {"estimate_mib_per_million_cells", estimate_MiB / (boxCells / 1e6)}});
            }
    }
    std::printf("target: <= %d iterations at every resolution: %s\n", MAX_ITERATIONS_TARGET,
                ok ? "met" : "MISSED");
    if (!opt.jsonPath.empty())
        writeTextAtomic(opt.jsonPath,
                        nlohmann::json{{"rows", rows}, {"target_met", ok}}.dump(2) + "\n");
    return ok ? EXIT_OK : EXIT_UNMET;
}

}  // namespace gale::app
