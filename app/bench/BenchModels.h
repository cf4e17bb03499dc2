#pragma once
/// \file BenchModels.h
/// `gale bench models`: error against run time of both steady models (docs/validation.md,
/// "Error against run time"). Each model is measured where an exact or measured answer exists:
///   - mass-consistent: the hemisphere's exact potential flow (near-surface L2 error at the 193
///     fixed points 0.1 R up of validation/ExactSolutions.h);
///   - momentum: the neutral log law over flat rough ground (largest relative error of u from 1 m
///     to 50 m against u*/kappa ln(z / z0));
///   - both: the steep ridge of Cao and Tamura (2006) (validation/data), RMS of the
///     fractional speed-up over the measured points off the windward foot, and the crest's
///     speed-up at 0.25 H against the measured 1.33;
/// each at two or three resolutions, with iterations and wall time. Table to stdout, CSV and a
/// log-log SVG (error against seconds) to the output folder, progress lines to stderr.
/// `--separation` runs the separation benchmarks instead (runSeparationStudy): the ERCOFTAC
/// periodic hill for every closure and both pseudo-time steps, error against run time.

#include <string>
#include <vector>

namespace gale::app {

struct BenchModelsOptions {
    std::string outputFolder = ".";  ///< models.csv and models.svg go here
    std::string jsonPath;            ///< if set, the table as JSON (atomically)
    bool quick = false;              ///< the coarsest resolution of each case: a CI smoke run
    /// The validation data (cao-tamura-2006-ridge.csv); empty: the copy embedded in the program
    /// (validation/ValidationData.h).
    std::string validationCsv;
    /// Instead of the table: the crest experiments on the ridge (runCrestStudy at H / h = 5).
    bool crestStudy = false;
    /// Instead of the table: the low ridges of Jackson and Hunt (1975) (runJacksonHuntStudy).
    bool jacksonHunt = false;
    /// Instead of the table: the steady state against the pseudo-time step (runPseudoTimeStudy).
    bool pseudoTime = false;
    /// The table also solves the ridge with the Eulerian pseudo-time step
    /// (solver.momentum_advection = "eulerian"), beside the default semi-Lagrangian one.
    bool eulerianRidge = false;
    /// The table also solves the ridge with every two-equation closure (solver.turbulence
    /// = "k_epsilon", "k_omega_sst"), beside the mixing length, with the steps above.
    bool closures = false;
    /// H / h of the ridge's solves (each > 0); empty: 5 and 10 (5 with quick).
    std::vector<int> ridgeCellsPerH;
    /// Pseudo-time steps per level at most for the ridge's momentum solves; 0: 1000 (300 with
    /// quick).
    int ridgeIterations = 0;
    /// Instead of the table: the separation benchmarks (runSeparationStudy).
    bool separation = false;
};

/// The crest experiments of docs/validation.md, section 3: the Cao and Tamura ridge at H / h =
/// cellsPerH (> 0) solved by potential flow, the Euler equations, the momentum model with the eddy
/// viscosity alone and with the wall stress, at two box heights; prints per case the crest's
/// u / U_inf and speed-up at 0.25, 0.48 and 0.98 H and the closure's nu_t there against kappa u* z.
/// Then a sensitivity: the model with its inflow's log profile re-fitted so that its windward foot
/// matches the measured foot below H, and the crest it gives.
/// Returns EXIT_OK when every solve converged, EXIT_UNMET otherwise. Throws what the solvers throw.
int runCrestStudy(int cellsPerH);

/// The low-hill check of docs/validation.md, section 2: cos^2 ridges (L = 200 m, H = 5, 10, 20 m)
/// in a 2-D box (4 m cells, 3 across, free-slip side walls, top 300 m, 1600 m long, log inflow
/// z0 = 0.03 m, 10 m/s at 10 m); prints per ridge both models' fractional speed-up at 6, 10 and
/// 20 m above the crest against the upwind column, and Delta S / (H / L). Returns EXIT_OK when
/// every momentum solve converged, EXIT_UNMET otherwise. Throws what the solvers throw.
int runJacksonHuntStudy();

/// The steady state against the pseudo-time step (docs/validation.md, "Pseudo-time step and its
/// error"): a gentle (H = 8 m, sigma = 50 m) and a steep (H = 40 m, sigma = 40 m) Gaussian ridge
/// in a 2-D box (4 m cells), each with the semi-Lagrangian step at several cfl and the Eulerian
/// step at several steps below its limit; prints u 10 m above the lee's ground and the crest, the
/// iterations and the spread of the lee value per scheme. Returns EXIT_OK when every solve
/// converged, EXIT_UNMET otherwise. Throws what the solvers throw.
int runPseudoTimeStudy();

/// The separation benchmarks of docs/validation.md, section 4: the ERCOFTAC periodic hill
/// (validation/PeriodicHillStudy.h) for every closure (sim::TurbulenceClosure) and both pseudo-time
/// steps at h / 5 and h / 10 (options.quick: h / 5 alone); prints per run the cells, steps, wall
/// time, separation and reattachment against the DNS, the profile RMS of u / Ub and k / Ub^2, the
/// repeat of the period before, and per station the RMS. A closure the solver refuses
/// (std::logic_error: not built yet) gets a "not built" row. options.jsonPath: the table as JSON.
/// Returns EXIT_OK when every built run converged with its reattachment within
/// limits::TARGET_PERIODIC_HILL_REATTACHMENT_ERROR, EXIT_UNMET otherwise. Throws what the solvers
/// throw otherwise, std::runtime_error when the JSON cannot be written.
int runSeparationStudy(const BenchModelsOptions& options);

/// Runs the study. Returns EXIT_OK when every momentum solve converged and stayed finite,
/// EXIT_UNMET otherwise (the table is written either way). Throws InputError (exit 2) when the
/// validation data cannot be read or parsed, std::runtime_error when an output cannot be
/// written.
int runBenchModels(const BenchModelsOptions& options);

}  // namespace gale::app
