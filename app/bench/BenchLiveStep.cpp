/// \file BenchLiveStep.cpp
/// The live-wind step's cost (see BenchLiveStep.h).

#include "app/bench/BenchLiveStep.h"

#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/io/Timing.h"
#include "sim/UnsteadyWind.h"

namespace gale::app {
namespace {

/// The live-wind target of issue 13: 30 steps a second beside the renderer.
constexpr double TARGET_STEP_HZ = 30.0;

/// CPU seconds of the whole process (all threads) so far.
double processCpu_s() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

/// The 1-minute load average, or -1 when the system does not say.
double loadAverage() {
    double load[1] = {-1.0};
    return getloadavg(load, 1) == 1 ? load[0] : -1.0;
}

struct LiveRow {
    std::string name;
    int nx = 0, ny = 0, nz = 0;
    int steps = 0;
    double cpu_ms = 0, wall_ms = 0;                                               ///< per step
    double advection = 0, forcing = 0, viscosity = 0, projection = 0, other = 0;  ///< wall shares
    double projectionIterations = 0, viscosityIterations = 0;                     ///< per step
    double maxDivergence = 0;  ///< largest StepReport::maxDivergenceScaled of the timed steps
    double maxResidual = 0;    ///< largest relative residual a step's projection left
    double simulated_s = 0;    ///< simulated time of the timed steps
    double load = 0;
};

LiveRow measure(const LiveStepScene& scene, int steps) {
    sim::UnsteadyWindSolver& solver = *scene.solver;
    LiveRow row;
    row.name = scene.name;
    row.nx = solver.grid().nx, row.ny = solver.grid().ny, row.nz = solver.grid().nz;
    (void)solver.step(solver.nextDt_s());  // warm-up: the first step starts the warm start
    double advection_s = 0, forcing_s = 0, viscosity_s = 0, projection_s = 0, total_s = 0;
    const double cpu0_s = processCpu_s();
    const auto wall0 = Clock::now();
    for (int k = 0; k < steps; ++k) {
        const sim::StepReport r = solver.step(solver.nextDt_s());
        advection_s += r.advection_s, forcing_s += r.forcing_s, viscosity_s += r.viscosity_s;
        projection_s += r.projection_s, total_s += r.total_s;
        row.projectionIterations += r.projection.iterations;
        row.viscosityIterations += r.viscosityIterations;
        row.maxDivergence = std::max(row.maxDivergence, r.maxDivergenceScaled);
        row.maxResidual = std::max(row.maxResidual, r.projection.relativeResidual);
        row.simulated_s += r.dt_s;
    }
    row.cpu_ms = 1e3 * (processCpu_s() - cpu0_s) / steps;
    row.wall_ms = msSince(wall0) / steps;
    row.steps = steps;
    row.projectionIterations /= steps, row.viscosityIterations /= steps;
    if (total_s > 0) {
        row.advection = advection_s / total_s, row.forcing = forcing_s / total_s;
        row.viscosity = viscosity_s / total_s, row.projection = projection_s / total_s;
        row.other = 1.0 - row.advection - row.forcing - row.viscosity - row.projection;
    }
    row.load = loadAverage();
    return row;
}

}  // namespace

int runBenchLiveStep(const BenchLiveStepOptions& opt) {
    std::printf(
        "live-wind step (scene as gale view builds it; CPU ms: the process's CPU time per step, "
        "all threads; parts: the step's wall time split by phase; target %.0f Hz = %.1f ms a "
        "step)\n",
        TARGET_STEP_HZ, 1e3 / TARGET_STEP_HZ);
    std::printf(
        "(ms: the step's wall time and its parts; steps/s and sim/wall: steps and simulated "
        "seconds per wall second; p its: projection iterations a step, max res: the largest "
        "relative residual a projection left, max div: the largest scaled divergence)\n");
    std::printf("%-22s %-12s %5s %8s %8s %7s %8s %7s %7s %7s %7s %7s %6s %6s %8s %8s %6s\n",
                "scene", "box", "steps", "CPU ms", "wall ms", "steps/s", "sim/wall", "advect",
                "force", "visc", "project", "other", "p its", "v its", "max res", "max div",
                "load");
    nlohmann::json rows = nlohmann::json::array();
    for (const std::string& path : opt.scenes) {
        std::fprintf(stderr, "bench unsteady: live step, %s...\n", path.c_str());
        const LiveStepScene scene = opt.loader(path);
        const LiveRow r = measure(scene, opt.steps);
        const std::string box =
            std::to_string(r.nx) + "x" + std::to_string(r.ny) + "x" + std::to_string(r.nz);
        const double stepsPerSecond = r.wall_ms > 0 ? 1e3 / r.wall_ms : 0.0;
        const double simPerWall =
            r.wall_ms > 0 ? r.simulated_s / (1e-3 * r.wall_ms * r.steps) : 0.0;
        std::printf(
            "%-22s %-12s %5d %8.1f %8.1f %7.1f %8.2f %7.1f %7.1f %7.1f %7.1f %7.1f %6.1f %6.1f "
            "%8.1e %8.1e %6.1f\n",
            r.name.c_str(), box.c_str(), r.steps, r.cpu_ms, r.wall_ms, stepsPerSecond, simPerWall,
            r.advection * r.wall_ms, r.forcing * r.wall_ms, r.viscosity * r.wall_ms,
            r.projection * r.wall_ms, r.other * r.wall_ms, r.projectionIterations,
            r.viscosityIterations, r.maxResidual, r.maxDivergence, r.load);
        rows.push_back({{"scene", r.name},
                        {"box", {r.nx, r.ny, r.nz}},
                        {"steps", r.steps},
                        {"cpu_ms_per_step", r.cpu_ms},
                        {"wall_ms_per_step", r.wall_ms},
                        {"share_advection", r.advection},
                        {"share_forcing", r.forcing},
                        {"share_viscosity", r.viscosity},
                        {"share_projection", r.projection},
                        {"share_other", r.other},
                        {"projection_iterations", r.projectionIterations},
                        {"viscosity_iterations", r.viscosityIterations},
                        {"max_divergence_scaled", r.maxDivergence},
                        {"max_projection_residual", r.maxResidual},
                        {"steps_per_second", stepsPerSecond},
                        {"simulated_per_wall_second", simPerWall},
                        {"load_average", r.load}});
    }
    if (!opt.jsonPath.empty()) {
        const auto parent = std::filesystem::path(opt.jsonPath).parent_path();
        if (!parent.empty()) std::filesystem::create_directories(parent);
        writeTextAtomic(opt.jsonPath, nlohmann::json{{"live_step", rows}}.dump(2) + "\n");
    }
    return EXIT_OK;
}

}  // namespace gale::app
