#pragma once
/// \file SolveCommand.h
/// `gale solve`: the steady wind over a scene's terrain, written as a .vdb field and a JSON report
/// (docs/solver.md). The CLI builds the request from the scene; this file does the work.

#include <optional>
#include <string>

#include "sim/AirDomain.h"
#include "sim/AmbientWind.h"
#include "sim/Heightfield.h"
#include "sim/PoissonSolver.h"
#include "sim/SteadyWind.h"
#include "sim/UnsteadyWind.h"

namespace gale::app {

/// wind.kind = "unsteady": the time stepping after the steady solve (docs/unsteady.md).
struct UnsteadySolveRequest {
    sim::UnsteadySettings settings;
    double duration_s = 10.0;    ///< simulated time, seconds
    double outputEvery_s = 1.0;  ///< a .vdb at t = 0, every this many seconds, and at duration_s
};

struct SolveRequest {
    sim::Heightfield terrain;
    sim::AmbientWind ambient;
    sim::DomainSpec domain;
    sim::MassConsistentWeights weights;
    sim::SolverSettings solver;
    std::string vdbPath;     ///< the field (grids "velocity" and "speed"); empty: not written
    std::string reportPath;  ///< the JSON report; empty: not written
    std::string sceneName;   ///< recorded in the report and the .vdb metadata
    /// Set for unsteady scenes: vdbPath is then the stem of a sequence, <stem>_0000.vdb ..., and
    /// the report lists every step (CFL, iterations, divergence, kinetic energy, timings).
    std::optional<UnsteadySolveRequest> unsteady;
};

/// Builds the domain, solves, writes the .vdb and the JSON report (each atomically), prints a
/// summary to stdout and progress to stderr. Returns 0 when the solve converged, 2 when it did not
/// (both files are still written, and the report says so). Throws std::invalid_argument naming
/// the parameter on bad input (voxel size, top, memory limit, NaN heights, wind, weights), and
/// std::runtime_error when a file cannot be written.
int runSolve(const SolveRequest& request);

/// The unsteady run of an unsteady scene (runSolve calls it when request.unsteady is set): the
/// steady solve, then steps to duration_s writing the sequence; returns 0 when every solve
/// converged and the field stayed finite, 2 otherwise (files still written, the report says so).
int runUnsteadySolve(const SolveRequest& request);

/// "<stem>_0003.vdb" for path "<stem>.vdb" and frame 3.
std::string sequencePath(const std::string& vdbPath, int frame);

}  // namespace gale::app
