#pragma once
/// \file MomentumWind.h
/// The steady momentum model of the wind: incompressible Reynolds-averaged flow with a
/// mixing-length eddy viscosity and a log-law wall stress (sim/MomentumTurbulence.h) on the
/// AirDomain's cut-cell MAC grid, driven to a steady state by pseudo-time stepping. docs/solver.md
/// compares it with the mass-consistent model; docs/validation.md measures it.
///
/// Method. Start from the mass-consistent field (sim/SteadyWind.h) for the same ambient wind,
/// then repeat the unsteady solver's step (sim/UnsteadyWind.h: semi-Lagrangian advection, the
/// implicit stress step, projection warm-started from the last potential with PoissonSolver) with
/// one fixed step dt = cfl h / U_max until the field stops changing. A fixed dt makes a fixed point
/// of the step a steady solution: the projection's potential is then -dt times the pressure (up to
/// the splitting error of the advection, O(dt), which the report's dt lets a reader judge;
/// docs/validation.md derives it: a streamwise numerical viscosity of about cfl U h / 2).
/// MomentumSettings::advection = Eulerian replaces the semi-Lagrangian advection by an explicit
/// Eulerian step (sim/MomentumAdvection.h) whose steady residual contains no dt, with the step
/// dt = eulerianCfl / (|u| / h + |v| / h + |w| / dz)_max below its stability limit of 1/2.
/// Coarse-grid start (MomentumSettings::coarseLevels): the same iteration on boxes of 2h, 4h, ...
/// cells first, where a step costs 1/8, 1/64, ... and the wind's first crossing of the box is
/// made; each finer level starts from the coarser level's correction to the mass-consistent
/// field, prolonged, and needs only to converge (docs/validation.md, "Run time"). On stretched
/// layers the coarse levels have cubic cells of 2h, 4h, ... and their correction is sampled at
/// the fine layout's world positions (its layer centres and levels).
/// Boundaries: the start field is the inflow wherever air enters the box (it carries the log
/// profile over the sides), outflow is zero-gradient (the advection reads the box), the top is
/// open (p = 0) with the ambient profile's shear stress, the ground has the wall function.
///
/// Convergence. Each iteration records the momentum residual, the RMS over open faces, weighted
/// by their open fractions, of (u^{n+1} - u^n) / dt scaled by h / U^2 (U = the ambient speed; the
/// steady momentum equations' imbalance in units of the advective acceleration U^2 / h), its
/// maximum, and the largest divergence after the projection, max |div u| h / U. Converged: the RMS
/// residual at or below residualTolerance with a converged projection, and at least as many steps
/// as the ambient wind needs to cross the box once (MomentumReport::minIterations; a low hill's
/// small disturbance changes the field little per step from the start), within the level's step
/// limit. A level, coarse or fine, that takes maxIterations steps without that is not converged,
/// and neither is the solve (a coarse level's unconverged start may leave the finest level a
/// slowly drifting field whose change per step is already small). Otherwise the report says
/// why, and the field is the last iterate, except when the finest level's residual cycles (a
/// periodic wake that the pseudo-time iteration follows instead of settling: residualCyclePeriod
/// finds a period of P steps): then whole periods more are stepped and their mean field is
/// returned (MomentumSettings::averageCycles; MomentumReport::averagedSteps says so, and the
/// report stays "not converged").
///
/// @code
///   gale::sim::AirDomain domain(terrain, {/*voxelSize_m=*/5.0});
///   gale::sim::MomentumWindResult res = gale::sim::solveMomentumWind(domain, ambient, {});
///   if (!res.report.converged) std::cerr << res.report.message << "\n";
///   for (const auto& it : res.report.history) plot(it.iteration, it.momentumResidual);
/// @endcode

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "sim/AirDomain.h"
#include "sim/AmbientWind.h"
#include "sim/MomentumTurbulence.h"
#include "sim/PoissonSolver.h"
#include "sim/WindField.h"

namespace gale::sim {

/// The advection of the pseudo-time step (docs/validation.md, "Pseudo-time step and its error").
enum class PseudoTimeAdvection {
    /// The unsteady solver's semi-Lagrangian step: stable at any cfl, but its fixed point carries
    /// a streamwise numerical viscosity that grows with the step (the steady state depends on cfl).
    SemiLagrangian,
    /// Explicit Eulerian upwind with van Leer slopes (sim/MomentumAdvection.h): a steady residual
    /// without dt, stable for eulerianCfl <= EULERIAN_MAX_CFL.
    Eulerian,
};

/// "semi_lagrangian", "eulerian" and back; fromName throws gale::ParameterError
/// (solver.momentum_advection) listing the valid names.
const char* pseudoTimeAdvectionName(PseudoTimeAdvection a);
PseudoTimeAdvection pseudoTimeAdvectionFromName(const std::string& name);

struct MomentumIteration;

/// Called after every recorded pseudo-time step (MomentumSettings::onStep): the step, its level's
/// step budget and the number of levels the solve runs (coarse levels and the finest). Return
/// false to stop the solve after this step: the report then has stopped = true and says where.
using MomentumStepCallback =
    std::function<bool(const MomentumIteration& step, int levelMaxIterations, int levelCount)>;

struct MomentumSettings {
    PseudoTimeAdvection advection = PseudoTimeAdvection::SemiLagrangian;
    /// The closure of the Reynolds stresses (solver.turbulence; sim/MomentumTurbulence.h).
    TurbulenceClosure turbulence = TurbulenceClosure::MixingLength;
    /// Semi-Lagrangian pseudo-time step: dt = cfl h / U_max (U_max the start field's largest face
    /// speed), > 0. Stable at any cfl; larger steps converge in fewer iterations with a larger
    /// error.
    double cfl = 2.0;
    /// Eulerian pseudo-time step: dt = eulerianCfl / R, R = eulerianRate_ps() of each level's
    /// start field (max over faces of |u| / h + |v| / h + |w| / dz), in (0, EULERIAN_MAX_CFL];
    /// below the limit by a margin for the iterate's speeds above the start's.
    double eulerianCfl = 0.4;
    /// With the Eulerian step: the incremental pressure correction (Goda 1979; UnsteadySettings::
    /// incrementalPressure), which takes the implicit stress step's action on the pressure
    /// gradient out of the fixed point. Off: on a cliff it diverges within 30 steps at any step
    /// size (docs/validation.md, "Pseudo-time step and its error"). A diagnostic, no scene key;
    /// its 24 B per cell (the summed gradient) are not in MOMENTUM_EXTRA_BYTES_PER_CELL.
    bool incrementalPressure = false;
    int maxIterations = 300;          ///< pseudo-time steps at most, >= 1
    double residualTolerance = 1e-4;  ///< converged when the RMS momentum residual is <= this, > 0
    double displacementHeight_m = 0.0;  ///< d of the log law (about 2/3 of tall grass), m, >= 0
    double mixingLengthMax_m = surface::BLACKADAR_MAX_MIXING_LENGTH_M;  ///< l_max, metres, > 0
    /// Projection of each pseudo-time step: loose, since every step projects the whole current
    /// divergence again (what one step leaves is removed by the next), warm-started.
    SolverSettings projection{/*relativeTolerance=*/1e-3, /*maxIterations=*/60};
    /// The projection of the converged field, once: its tolerance is the divergence the result
    /// keeps (max |div u| h / U <= relativeTolerance times the last step's).
    SolverSettings finalProjection{/*relativeTolerance=*/1e-6, /*maxIterations=*/100};
    SolverSettings start;  ///< the mass-consistent start solve (on every level)
    /// Coarse-grid start: at most this many coarser levels (cells 2h, 4h, ...) are solved first,
    /// coarsest first; each finer level starts from its own mass-consistent field plus the
    /// prolonged correction (steady minus mass-consistent) of the next coarser one; a level
    /// exists only while its grid keeps COARSE_MIN_CELLS_XY cells along its longer side, one
    /// across and COARSE_MIN_CELLS_Z up. 0: the finest level alone, from the mass-consistent
    /// field. >= 0.
    int coarseLevels = 3;
    /// A level started from a coarser level's steady state need not wait for the wind to cross
    /// its box (the coarse level did), only for this many steps, >= 1.
    int minIterationsAfterProlongation = 10;
    /// When the finest level stops unconverged and its residual cycles (a periodic wake: the
    /// pseudo-time iteration follows the shedding), run whole periods more and return their mean
    /// field (MomentumReport::averagedSteps). false: the last iterate.
    bool averageCycles = true;
    /// Steps the mean covers at least (a whole number of periods, at least one), >= 1.
    int averageMinSteps = 24;
    /// Diagnostics (no scene key reaches them; docs/validation.md, the crest experiments):
    /// false turns off the mixing-length eddy viscosity (then also the wall stress must be off)
    /// or the log-law wall stress (a free-slip ground). Either off also drops the balance force
    /// and top stress of the ambient profile (they balance exactly the stresses turned off); both
    /// off is the Euler equations, for which the wind may have any profile. validate() throws
    /// std::logic_error for the wall stress without the eddy viscosity.
    bool eddyViscosity = true;
    bool wallStress = true;
    /// Progress and cancellation (app/scene/SceneField.cpp prints it and stops on a signal);
    /// empty: no calls. Not part of the model: it never changes the field of a solve it lets run.
    MomentumStepCallback onStep;
    static constexpr int COARSE_MIN_CELLS_XY = 16;
    static constexpr int COARSE_MIN_CELLS_Z = 8;

    /// Throws gale::ParameterError naming the scene key (solver.momentum_max_iterations, ...),
    /// std::logic_error for a setting no scene key reaches (cfl, residualTolerance, ...).
    void validate() const;
};

/// One pseudo-time step of the history.
struct MomentumIteration {
    int level = 0;      ///< 0: the domain's own cells; n: cells 2^n times larger (coarse start)
    int iteration = 0;  ///< 1, 2, ... within its level
    double momentumResidual = 0;  ///< open-fraction weighted RMS over faces of |du| / dt * h / U^2
    double maxMomentumResidual = 0;  ///< max over faces of theta |du| / dt * h / U^2
    double maxDivergenceScaled = 0;  ///< max over air cells |div u| h / U after the projection
    int projectionIterations = 0;
    bool projectionConverged = false;
    double seconds = 0;                                      ///< wall time of the step
    double advection_s = 0, stress_s = 0, projection_s = 0;  ///< its parts' wall times
};

/// What one level of the coarse-grid start (or the finest level) did.
struct MomentumLevel {
    int level = 0;               ///< 0: the domain's cells; n: 2^n times larger
    double voxelSize_m = 0;      ///< its cell edge, metres
    std::array<int, 3> cells{};  ///< nx, ny, nz
    double dt_s = 0;             ///< its pseudo-time step (cfl h / U_max on its own h)
    int iterations = 0;
    /// Steps it had to take at least: the ambient wind's crossing of the box for a level started
    /// from the mass-consistent field, MomentumSettings::minIterationsAfterProlongation otherwise.
    int minIterations = 0;
    double momentumResidual = 0;  ///< of its last iteration (RMS)
    /// The residual at or below the tolerance within the level's step budget. A level, coarse or
    /// fine, that takes MomentumSettings::maxIterations steps without that is not converged, and
    /// neither is the solve (MomentumReport::converged).
    bool converged = false;
    bool atStepLimit = false;  ///< it took maxIterations steps without converging
    bool finite = true;
    double seconds = 0;  ///< wall time, its mass-consistent solve included
    std::string message;
};

struct [[nodiscard]] MomentumReport {
    /// Every level converged (MomentumLevel::converged): a coarse level stopped at its step
    /// limit hands the next level an unconverged start, and the message names it.
    bool converged = false;
    bool finite = true;  ///< no NaN/Inf in the field
    /// MomentumSettings::onStep returned false: the solve stopped after the last history entry,
    /// not converged; the field is the last iterate of the finest level, or the mass-consistent
    /// start when it stopped on a coarse level.
    bool stopped = false;
    int iterations = 0;                  ///< pseudo-time steps over all levels
    int fineIterations = 0;              ///< of them, steps on the domain's own cells
    int minIterations = 0;               ///< the finest level's (MomentumLevel::minIterations)
    double momentumResidual = 0;         ///< of the last iteration (RMS)
    double maxDivergenceScaled = 0;      ///< max |div u| h / U after the final projection
    SolveReport finalProjection;         ///< the final projection's solve
    double dt_s = 0;                     ///< the finest level's pseudo-time step
    double maxEddyViscosity_m2ps = 0;    ///< of the last iteration
    double maxFrictionVelocity_mps = 0;  ///< of the last iteration
    double seconds = 0;                  ///< wall time including the start solve
    std::string message;                 ///< why it stopped, in words
    SolveReport start;                   ///< the mass-consistent solve on the domain's own cells
    std::vector<MomentumLevel> levels;   ///< coarsest first, the domain's own cells last
    std::vector<MomentumIteration> history;  ///< every step of every level, in order
    /// Cycle average (MomentumSettings::averageCycles): the period of the finest level's residual
    /// in steps (0: none found), the autocorrelation of the residual at that lag, and the steps
    /// (whole periods, after the last history entry of the unconverged run) whose mean field was
    /// returned (0: the field is the last iterate).
    int cyclePeriod = 0;
    double cycleCorrelation = 0;
    int averagedSteps = 0;
};

/// The dominant period, in steps, of a residual history that cycles: over the last `window`
/// values (n, at most the series), the first lag in [MIN_CYCLE_LAG, n / 2] where the
/// autocorrelation of the mean-removed series has a local maximum of at least
/// MIN_CYCLE_CORRELATION, provided the series does not trend (its last half's mean within 25 % of
/// its first half's), varies by more than 0.1 % of its mean and is finite; else 0. correlation
/// receives the value at that lag (0 when none). Pure function, no throws.
int residualCyclePeriod(const std::vector<double>& residuals, int window, double& correlation);
inline constexpr int MIN_CYCLE_LAG = 2;
inline constexpr double MIN_CYCLE_CORRELATION = 0.5;

struct MomentumWindResult {
    WindField field;
    MomentumReport report;
    /// Turbulent kinetic energy k (m^2/s^2) on the domain's cells (GridIndex's cell layout, 0 in
    /// solid cells) after the finest level's last pseudo-time step
    /// (TurbulentStress::turbulentKineticEnergy_m2ps2: the closure's k); empty when the eddy
    /// viscosity is off or no step of the finest level ran.
    std::vector<double> tke_m2ps2;
};

/// Extra bytes per cell of the box a momentum solve holds beyond the mass-consistent solve
/// (AirDomain's memory estimate adds it when DomainSpec::momentumModel is set): the unsteady
/// solver's mean field, step copies and masks, the previous iterate, the cycle average's sum, the
/// stress step's arrays,
/// and the coarse start's two kept fields, its steady field and its mass-consistent start (24 B
/// per coarse cell each, an eighth of a cell's; the coarse levels' own solves, at most 1/7 of the
/// finest level's, are freed before it starts).
inline constexpr double MOMENTUM_EXTRA_BYTES_PER_CELL =
    24.0 * 6 + 3.0 + TurbulentStress::BYTES_PER_CELL + 2 * 24.0 / 8;

/// The checks solveMomentumWind makes before any work: the settings, the wind, its profile (the
/// log law) and the surface layer of its steps (a displacement height plus roughness below the
/// wind's reference height). Throws as solveMomentumWind does; `gale check` calls it to refuse
/// what the solve would refuse.
void validateMomentumWind(const AmbientWind& ambient, const MomentumSettings& settings);

/// Solves the momentum model for an ambient wind with a log profile (its roughness_m is z0).
/// Build the domain with DomainSpec::momentumModel set, so that its memory check (made before
/// anything is allocated) counts the model's arrays.
/// Throws gale::ParameterError naming the scene key for a bad wind or settings, or a wind whose
/// profile is not the log law (wind.profile: the model's inflow and wall stress need the
/// roughness; the Euler diagnostic, both stresses off, takes any profile); std::logic_error for a
/// setting no scene key reaches (cfl, residualTolerance). Non-convergence is in the report, never
/// thrown.
[[nodiscard]] MomentumWindResult solveMomentumWind(const AirDomain& domain,
                                                   const AmbientWind& ambient,
                                                   const MomentumSettings& settings);

}  // namespace gale::sim
