#pragma once
/// \file PseudoTimeStudy.h
/// Does the momentum model's steady state depend on its pseudo-time step? (docs/validation.md,
/// "Pseudo-time step and its error"). A Gaussian ridge across the wind in a two-dimensional box
/// (4 m cells, 3 across between free-slip side walls, 500 m long, top 200 m, crest 150 m from
/// the inflow face, log inflow z0 = 0.03 m, 10 m/s at 10 m, residual tolerance 1e-5), solved with
/// one pseudo-time step; the speed 10 m above the ground in the lee and over the crest is the
/// measure.

#include <cmath>

#include "sim/MomentumWind.h"

namespace gale::validation {

namespace pseudotime {
constexpr double CELL_M = 4.0;                     ///< the cell size
constexpr double LENGTH_M = 500.0, TOP_M = 200.0;  ///< the box
constexpr double CREST_X_M = 150.0;                ///< the crest's distance from the inflow face
constexpr double Z0_M = 0.03, SPEED_MPS = 10.0, REFERENCE_HEIGHT_M = 10.0;  ///< the log inflow
constexpr double PROBE_HEIGHT_M = 10.0;      ///< the probes' height above the ground
constexpr double RESIDUAL_TOLERANCE = 1e-5;  ///< tight, so the fixed point is what is read
/// The page's two ridges: height, sigma, the lee probe's distance behind the crest (m) and the
/// pseudo-time steps per level at most.
struct Ridge {
    const char* name;
    double H_m, sigma_m, leeFromCrest_m;
    int maxIterations;
};
constexpr Ridge GENTLE{"Gentle ridge", 8.0, 50.0, 100.0, 3000};
constexpr Ridge STEEP{"Steep ridge", 40.0, 40.0, 200.0, 1500};
}  // namespace pseudotime

/// One solve: which ridge, which step (the semi-Lagrangian cfl or the Eulerian eulerianCfl).
struct PseudoTimeOptions {
    pseudotime::Ridge ridge = pseudotime::GENTLE;
    sim::PseudoTimeAdvection advection = sim::PseudoTimeAdvection::Eulerian;
    double step = 0.4;
    bool incrementalPressure = false;  ///< Goda (1979); a diagnostic switch
};

struct PseudoTimeStudy {
    double lee_mps = NAN, crest_mps = NAN;  ///< u 10 m above the ground, lee probe and crest
    double dt_s = 0, seconds = 0;
    int iterations = 0;
    bool converged = false;
};

/// Solves the ridge with the options. Throws what the momentum solver throws.
PseudoTimeStudy runPseudoTime(const PseudoTimeOptions& options);

}  // namespace gale::validation
