#pragma once
/// \file BenchLiveStep.h
/// `gale bench unsteady --live SCENE`: the cost of one unsteady solver step on the live-wind path
/// (the scene built as `gale view` builds it, the step limited to an output frame), as CPU time
/// per step and its parts. CPU time is the process's (every thread, TBB's workers included), so
/// the figure holds on a loaded machine where wall times stretch; the parts are the solver's own
/// wall-time split (advection, forcing, viscosity, projection), scaled to the step's CPU time.

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace gale::sim {
class UnsteadyWindSolver;
}

namespace gale::app {

/// A scene's unsteady solver for the live-step bench, and whatever keeps it alive.
struct LiveStepScene {
    std::string name;
    sim::UnsteadyWindSolver* solver = nullptr;
    std::shared_ptr<void> owner;
};

struct BenchLiveStepOptions {
    std::vector<std::string> scenes;  ///< scene files with wind.kind = "unsteady"
    int steps = 30;                   ///< timed steps per scene (after one untimed warm-up step)
    std::string advection;  ///< a scheme's name replacing every scene's unsteady.advection, or ""
    std::string precision;  ///< "single"/"double" replacing every scene's unsteady.precision, or ""
    double tolerance = 0;   ///< > 0: replaces every scene's unsteady.tolerance
    int iterations = 0;     ///< > 0: replaces every scene's unsteady.live_iterations
    std::string jsonPath;   ///< if set, the rows as JSON (atomically)
    /// Builds a scene (app/bench cannot read scenes itself); throws what scene loading throws.
    std::function<LiveStepScene(const std::string& path)> loader;
};

/// Prints one row per scene: box, steps, CPU ms per step, wall ms per step, the CPU split over
/// the phases, projection and viscosity iterations, the largest scaled divergence after a step's
/// projection (StepReport::maxDivergenceScaled, dimensionless), and the load average.
/// Returns EXIT_OK (a measurement, no target judged: the 30 Hz target is printed beside it).
/// Throws std::runtime_error if the JSON cannot be written.
int runBenchLiveStep(const BenchLiveStepOptions& options);

}  // namespace gale::app
