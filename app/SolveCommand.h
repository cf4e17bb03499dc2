#pragma once
/// \file SolveCommand.h
/// `gale solve`: the steady wind over a scene's terrain, written as a .vdb field and a JSON report
/// (docs/solver.md). The CLI builds the request from the scene; this file does the work.

#include <string>

#include "sim/AirDomain.h"
#include "sim/AmbientWind.h"
#include "sim/Heightfield.h"
#include "sim/PoissonSolver.h"
#include "sim/SteadyWind.h"

namespace gale::app {

struct SolveRequest {
    sim::Heightfield terrain;
    sim::AmbientWind ambient;
    sim::DomainSpec domain;
    sim::MassConsistentWeights weights;
    sim::SolverSettings solver;
    std::string vdbPath;     ///< the field (grids "velocity" and "speed"); empty: not written
    std::string reportPath;  ///< the JSON report; empty: not written
    std::string sceneName;   ///< recorded in the report and the .vdb metadata
};

/// Builds the domain, solves, writes the .vdb and the JSON report (each atomically), prints a
/// summary to stdout and progress to stderr. Returns 0 when the solve converged, 2 when it did not
/// (both files are still written, and the report says so). Throws std::invalid_argument naming
/// the parameter on bad input (voxel size, top, memory limit, NaN heights, wind, weights), and
/// std::runtime_error when a file cannot be written.
int runSolve(const SolveRequest& request);

}  // namespace gale::app
