#pragma once
/// \file SolveRun.h
/// What `gale solve` hands its runs (app/CommandsSolve.cpp: the steady run and the verb;
/// app/CommandsSolveUnsteady.cpp: the unsteady run), and the output helpers both share. Private
/// to app/.

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/io/AtomicFile.h"
#include "app/io/OutputLock.h"
#include "app/scene/Scene.h"
#include "app/scene/SceneField.h"
#include "app/scene/WindRaster.h"
#include "sim/AirDomain.h"
#include "sim/AmbientWind.h"
#include "sim/Heightfield.h"
#include "sim/MomentumWind.h"
#include "sim/PoissonSolver.h"
#include "sim/SteadyWind.h"
#include "sim/UnsteadyWind.h"
#include "sim/VdbIO.h"

namespace gale::app {

/// wind.kind = "unsteady": the time stepping after the steady solve (docs/unsteady.md).
struct UnsteadySolveRequest {
    sim::UnsteadySettings settings;
    double duration_s = 10.0;    ///< simulated time, seconds
    double outputEvery_s = 1.0;  ///< a .vdb at t = 0, every this many seconds, and at duration_s
    UnsteadySection limits;      ///< the scene's bounds on work (max_output_gib for the sequence)
    std::string
        outputEveryWhere;  ///< FILE:LINE: unsteady.output_every_s, blamed for too many bytes
};

struct SolveRequest {
    const Scene* scene = nullptr;  ///< its wind, solver and unsteady keys (app/scene/SceneField.h)
    sim::Heightfield terrain;      ///< the scene's terrain (buildTerrain)
    std::string vdbPath;           ///< the field (grids "velocity" and "speed"); empty: not written
    std::string reportPath;        ///< the JSON report; empty: not written
    std::string sceneName;         ///< recorded in the report and the .vdb metadata
    std::string outputWhere = "-o";  ///< where the output path came from, for messages
    /// Set for unsteady scenes: vdbPath is then the stem of a sequence, <stem>_0000.vdb ..., and
    /// the report lists every step (CFL, iterations, divergence, kinetic energy, timings).
    std::optional<UnsteadySolveRequest> unsteady;
    Georeference georef;                ///< a DEM's coordinate system, for the rasters
    std::vector<double> gridHeights_m;  ///< rasters of the wind this high above ground (steady)
    double houdiniFps = 0.0;            ///< > 0: also the y-up .vdb sequence, frames at this rate
};

/// Builds the domain, solves, writes the .vdb and the JSON report (each atomically), prints a
/// summary to stdout and progress to stderr. Returns EXIT_OK when the solve converged, EXIT_UNMET
/// when it did not (both files are still written, and the report says so). Throws
/// std::invalid_argument naming the parameter on bad input (voxel size, top, memory limit, NaN
/// heights, wind, weights), and std::runtime_error when a file cannot be written.
int runSolve(const SolveRequest& request);

/// The unsteady run of an unsteady scene (runSolve calls it when request.unsteady is set): the
/// steady solve, then steps to duration_s writing the sequence; returns 0 when every solve
/// converged and the field stayed finite, EXIT_UNMET otherwise (files still written, the report
/// says so).
int runUnsteadySolve(const SolveRequest& request);

/// "<stem>_0003.vdb" for path "<stem>.vdb" and frame 3.
std::string sequencePath(const std::string& vdbPath, int frame);

/// "<stem>_houdini.0025.vdb": the y-up file of the scene frame at t_s (frame 1 at t = 0).
std::string houdiniPath(const std::string& vdbPath, double fps, double t_s);

/// The folder of `path` ("." for a bare name).
std::string folderOf(const std::string& path);
/// The name of the rasters of --grid-height-m height_m, without extension:
/// "<vdbPath without .vdb>_<height_m, %g>m" (e.g. "out/wind_10m").
std::string rasterStem(const std::string& vdbPath, double height_m);

/// Creates the folders of the .vdb and the report, takes the .vdb folder's lock and removes
/// temporaries a killed run left there. Returns the lock (null when no .vdb is written).
std::unique_ptr<OutputLock> prepareSolveOutputs(const SolveRequest& req);

/// Writes `field` to the staged temporary of `path` and seals it; returns its size in bytes and,
/// when `gridNames` is given, the names of the grids the written file holds (read back from it).
/// With tke_m2ps2 (one value per cell) the file also holds the "tke" grid (sim/VdbIO.h).
/// Throws std::runtime_error "PATH: cannot write: REASON".
double writeStagedVdb(StagedFiles& staged, const sim::WindField& field, const std::string& path,
                      const sim::VdbMetadata& meta, std::vector<std::string>* gridNames = nullptr,
                      const std::vector<double>& tke_m2ps2 = {});

/// The report's list of a .vdb's grids: each name with its type, units and placement.
nlohmann::json vdbGridDescriptions(const std::vector<std::string>& names);

/// The report's "domain": the cells, the box, the memory, the layers (cubic, or stretched with
/// first cell, ratio, largest cell and every level height) and the standard grids' voxels.
nlohmann::json domainJson(const sim::AirDomain& domain, const Scene& scene);

/// The report's "provenance" (FieldProvenance without the "gale_" of its metadata keys).
nlohmann::json provenanceJson(const FieldProvenance& provenance);

}  // namespace gale::app
