#pragma once
/// \file UnsteadyStability.h
/// The stability suite of the unsteady wind (DESIGN 4.4): named extreme cases, each run for a
/// few steps and judged by the same rules. `gale bench stability` prints them all; sim_tests runs
/// the cases marked fast.
///
/// Pass means:
///  - no NaN or Inf in any velocity after any step (or a clear refusal where the case asks for
///    something the solver does not support: anisotropic cells);
///  - after every projection, max |div u| h / U <= DIVERGENCE_TOLERANCE;
///  - kinetic energy: without forcing it never grows from one step to the next by more than
///    ENERGY_GROWTH_TOLERANCE (relative; inflow cases: relative to the mean flow's energy, which
///    the inflow keeps supplying); with forcing (gusts, forced whirlwinds) it stays below the
///    energy of the mean flow plus the gusts at their peak plus the energy the forcing reports.

#include <string>
#include <vector>

namespace gale::sim {

struct StabilityResult {
    std::string name, description;
    int steps = 0;
    double maxSpeed_mps = 0;
    double keStart_m5ps2 = 0, keEnd_m5ps2 = 0, keMax_m5ps2 = 0;
    double keBound_m5ps2 = 0;       ///< the bound the energy rule used (see the file comment)
    double maxGrowth = 0;           ///< largest step-to-step relative energy growth (unforced cases)
    double maxDivergenceScaled = 0; ///< max over steps of max |div u| h / U
    double maxCfl = 0;
    bool forced = false;            ///< gusts or forcing: the bounded-energy rule applies
    bool finite = true;
    bool refused = false;           ///< the solver refused the setup with a clear error
    std::string refusal;            ///< that error
    bool pass = false;
    std::string why;                ///< what failed, empty on pass
    double wall_s = 0;
};

/// Largest max|div u| h / U accepted after a projection (the projection solves to 1e-7).
constexpr double STABILITY_DIVERGENCE_TOLERANCE = 1e-4;
/// Largest step-to-step relative growth of kinetic energy accepted without forcing: the
/// projection's tolerance and the limiter-free interpolation leave round-off of this order.
constexpr double STABILITY_ENERGY_GROWTH_TOLERANCE = 1e-3;

/// Names of every case, in table order; `fastOnly`: the subset sim_tests runs (< 1 s each).
std::vector<std::string> stabilityCaseNames(bool fastOnly = false);
/// Runs one case. Throws std::invalid_argument for an unknown name.
StabilityResult runStabilityCase(const std::string& name);

}  // namespace gale::sim
