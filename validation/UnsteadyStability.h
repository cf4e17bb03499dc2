#pragma once
/// \file UnsteadyStability.h
/// The stability suite of the unsteady wind (docs/unsteady.md): named extreme cases that
/// exercise what they name, run and measured here, judged by the callers (the tests, with their
/// own oracles: exact solutions and invariants; `gale bench stability`, which prints the table).
/// This file computes no verdicts.
///
/// Cases (stabilityCaseNames):
///  - cfl5, cfl20, cfl50 (semi-Lagrangian) and cfl20_maccormack, cfl20_bfecc: 10 m/s over a
///    Gaussian ridge across the flow, at a fixed step of CFL U dt / h, in a box at least 10 U dt
///    long (12 CFL cells), for 12 steps. The steady potential flow the run starts from is an exact
///    steady solution of the Euler equations (irrotational: (u.grad)u = grad |u|^2/2 goes into the
///    pressure), so the field should stay where it started: its deviation and its kinetic energy
///    change are the advection's and projection's numerical error. Traces cross 5-50 cells per
///    step over the terrain (substepped, stopped at the surface: sim/Advection.h).
///  - wind_0, wind_100, vertical_cliff, one_voxel_spike: calm air, 100 m/s, a 10 m cliff, a
///    one-voxel spike 12 voxels tall, each started from its steady potential flow (same reference).
///  - subcell_vortex: a Lamb-Oseen core of 0.3 cells in calm air; the grid cannot hold it, and the
///    energy it loses is measured (reference: the field after the seeding step).
///  - viscosity_nu_dt_h2_1000: implicit viscosity at nu dt / h^2 = 1000 on a resolved vortex.
///  - step_gust, forced_whirlwind: forcing; energy is budgeted against what enters.
/// Studies with exact solutions (separate runners, the same StabilityRun):
///  - runTranslatingVortex: an inviscid Lamb-Oseen vortex carried by a uniform wind U over flat
///    ground under a lid. Any axisymmetric swirl is a steady Euler solution, so by Galilean
///    invariance u(x, t) = U e_x + v_theta(|x - x0 - U t|) e_theta exactly; the seeded window
///    makes the swirl compactly supported, so the uniform inflow is exact too.
///  - runBurgersVortex: Burgers' (1948) vortex, a Lamb-Oseen swirl of core r_c held steady in
///    the axisymmetric strain u_r = -a r / 2, w = a z by viscosity nu with r_c^2 = 4 nu / a; the
///    strain is the run's mean flow (and far field), with an open top for its outflow.
///    Variants without viscosity (the core contracts as r_c^2 e^{-a t}) and without strain (it
///    spreads as r_c^2 + 4 nu t) show the balance is what holds it. The boundaries hold the
///    exact solution: the strain's pressure on the open sides, its outflow through the top
///    (with p = 0 there the strain decays inside the box).

#include <memory>
#include <string>
#include <vector>

#include "sim/AirDomain.h"
#include "sim/UnsteadyWind.h"
#include "sim/WindField.h"

namespace gale::validation {

/// One case after its run: the solver (with the final field) and what was measured on the way.
struct StabilityRun {
    std::string name, description;
    std::unique_ptr<sim::AirDomain> domain;  ///< declared before solver: outlives it
    std::unique_ptr<sim::UnsteadyWindSolver> solver;
    /// The field the case starts from once everything is seeded: the steady potential flow, or
    /// the field after the first step where a vortex is seeded in that step.
    sim::WindField start;
    double referenceSpeed_mps = 1.0;  ///< U of the divergence scaling, m/s
    bool forced = false;              ///< gusts or forcing add energy
    int steps = 0;
    double dt_s = 0;
    double maxCfl = 0;  ///< max |u| dt / h over the steps (StepReport::cfl)
    double maxSpeed_mps = 0;
    double maxDivergenceScaled = 0;  ///< max over steps of the solver's max |div u| h / U
    double keStart_m5ps2 = 0, keEnd_m5ps2 = 0, keMax_m5ps2 = 0;  ///< 1/2 sum theta u^2 h^3
    double forcingEnergy_m5ps2 = 0;  ///< sum over steps of the energy the forces added (>= 0 part)
    /// sqrt(sum theta (u - u_start)^2 / sum theta u_start^2) over all faces at the end: how far
    /// the field moved from its start (the numerical error where the start is steady).
    double deviationFromStart = 0;
    bool finite = true;  ///< every StepReport finite
    int maxProjectionIterations = 0;
    double wall_s = 0;
};

/// Names of every case, in table order; fastOnly: the subset sim_tests runs (about a second
/// each in Release).
std::vector<std::string> stabilityCaseNames(bool fastOnly = false);
/// Description of a case (throws std::invalid_argument for an unknown name).
std::string stabilityCaseDescription(const std::string& name);
/// Runs one case with the advection in `precision` (sim::AdvectionPrecision). Throws
/// std::invalid_argument for an unknown name.
StabilityRun runStabilityCase(const std::string& name,
                              sim::AdvectionPrecision precision = sim::AdvectionPrecision::Single);

/// The translating vortex of the file comment (parameters in metres, m/s and seconds).
struct TranslatingVortexSpec {
    static constexpr double CORE_M = 4.0, PEAK_MPS = 2.0, WIND_MPS = 2.0, TIME_S = 4.0;
    static constexpr double START_X_M = 14.0, START_Y_M = 16.0;  ///< axis at t = 0, world metres
    static constexpr double SEED_CORES = 2.5;  ///< full swirl out to this many cores (then tapered)
};
/// Runs it with cells of CORE_M / cellsPerCore and steps of courant h / (WIND_MPS + PEAK_MPS) up to
/// TIME_S. Throws std::invalid_argument if cellsPerCore < 1 or courant <= 0.
StabilityRun runTranslatingVortex(int cellsPerCore, double courant);

enum class BurgersVariant { Balanced, NoViscosity, NoStrain };
/// Burgers' vortex of the file comment (metres, m/s, 1/s, seconds): core CORE_M, strain
/// STRAIN_PER_S, run for TIME_S in a box 2 HALF_WIDTH_CORES cores wide and HEIGHT_CORES tall.
struct BurgersSpec {
    static constexpr double CORE_M = 4.0, PEAK_MPS = 2.0, STRAIN_PER_S = 0.25, TIME_S = 4.0;
    static constexpr double HALF_WIDTH_CORES = 5.0, HEIGHT_CORES = 3.0;
    /// nu = a r_c^2 / 4 (Burgers 1948): the viscosity that holds the core.
    static constexpr double viscosity_m2ps() { return STRAIN_PER_S * CORE_M * CORE_M / 4.0; }
};
/// Runs a variant at CFL 1 (of the strain's side inflow plus the peak swirl) with cells of
/// CORE_M / cellsPerCore. exactBoundaries (strained variants): the open sides hold the strain's
/// exact pressure p / rho = -a^2 (r^2 / 8 + z^2 / 2) (UnsteadySettings::boundaryPressure_m2ps2)
/// and the top its exact outflow w = a z_top (UnsteadySettings::lidVelocity_mps); false: the
/// old open boundary, p = 0 on the sides and an open top, which cannot carry that pressure.
/// Throws std::invalid_argument if cellsPerCore < 1.
StabilityRun runBurgersVortex(BurgersVariant variant, int cellsPerCore,
                              bool exactBoundaries = true);
/// The strain's kinematic pressure p / rho (m^2/s^2) at a world point, for strain a_per_s about
/// the vertical axis through (axisX_m, axisY_m) with its stagnation plane at z = 0: the Euler
/// balance (u . grad) u = -grad p / rho of u_r = -a r / 2, w = a z.
double burgersStrainPressure_m2ps2(double a_per_s, double axisX_m, double axisY_m,
                                   const sim::Vec3d& wsPos_m);
/// Core radius of the final swirl at mid-height, metres: the radius of the peak azimuthal speed
/// (circulation around rings) divided by 1.1209 (Lamb-Oseen's peak), for the bench.
double burgersCoreRadius_m(const StabilityRun& run);

}  // namespace gale::validation
