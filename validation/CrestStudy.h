#pragma once
/// \file CrestStudy.h
/// Which part of the momentum model loses the speed-up over the crest of the Cao and Tamura
/// (2006) ridge (docs/validation.md, section 3, "The crest experiments"): one case changes one
/// thing of the set-up of CaoTamuraRidge.h (the model: potential flow, Euler, the eddy viscosity,
/// the wall stress; the inflow; the top's height; the sides), is solved at H / h = cellsPerH and
/// read over the crest and at the windward foot.

#include <cmath>
#include <optional>
#include <string>

#include "sim/AmbientWind.h"
#include "validation/CaoTamuraRidge.h"

namespace gale::validation {

/// One experiment: which model, which inflow, which stresses, which top, which sides.
struct CrestCase {
    std::string name;
    bool momentum = false;                            ///< false: mass-consistent (a_h = a_v)
    ridge::Inflow inflow = ridge::Inflow::Published;  ///< the approach flow (CaoTamuraRidge.h)
    bool eddyViscosity = true, wallStress = true;
    double topOverH = ridge::TOP_OVER_H;  ///< the box's top, in ridge heights
    bool closedSides = true;  ///< free-slip y sides (DomainSpec::closedSidesY); false: open
};

/// The measured windward-foot profile below H (validation/data/cao-tamura-2006-ridge.csv,
/// x = -2.5 H): dz / H and u / U_inf.
constexpr double FOOT_DZ_OVER_H[5] = {0.103, 0.241, 0.490, 0.738, 1.000};
constexpr double FOOT_U_OVER_UINF[5] = {0.251, 0.377, 0.448, 0.533, 0.562};
/// The pseudo-time steps per level at most (the set-up's 205 steps converge well within it).
constexpr int CREST_MAX_ITERATIONS = 1000;

struct CrestOptions {
    CrestCase crestCase;
    int cellsPerH = 5;  ///< H / h (>= 1)
    /// The inflow; unset: ridge::wind(crestCase.inflow). The sensitivity study re-fits it.
    std::optional<sim::AmbientWind> wind;
};

/// The crest's figures at ridge::CREST_DZ_OVER_H, and the foot at FOOT_DZ_OVER_H.
struct CrestStudy {
    int steps = 0;  ///< solver iterations (pseudo-time steps over all levels)
    bool converged = false;
    double seconds = 0;
    double crestUinf[3] = {NAN, NAN, NAN};  ///< u / U_inf over the crest
    /// Speed-up against the same run's windward foot (x = -2.5 H) at the same height.
    double crestSpeedup[3] = {NAN, NAN, NAN};
    /// The mixing-length closure's nu_t = l^2 |du/dz| from the field's own shear over the crest,
    /// against the log layer's kappa u* z of the inflow (momentum with eddy viscosity only).
    double nuRatio[3] = {NAN, NAN, NAN};
    double footU_mps[5] = {NAN, NAN, NAN, NAN, NAN};  ///< u at the windward foot
    double uInf_mps = NAN;  ///< the free stream u / U_inf is taken against
};

/// Solves the case. Throws what the solvers throw; std::invalid_argument if cellsPerH < 1.
CrestStudy runCrest(const CrestOptions& options);

}  // namespace gale::validation
