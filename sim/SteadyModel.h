#pragma once
/// \file SteadyModel.h
/// The steady model a scene chooses ([solver] model) and the one dispatcher that runs it: the
/// mass-consistent field of sim/SteadyWind.h, or the momentum model of sim/MomentumWind.h
/// started from it. Callers that only need one model include that model's header instead.
///
/// @code
///   const gale::sim::SteadyModel model = gale::sim::steadyModelFromName("momentum");
///   gale::sim::SteadyModelResult res = gale::sim::solveSteadyModel(
///       domain, ambient, model, gale::sim::MassConsistentWeights{}, gale::sim::SolverSettings{});
///   if (!res.report.converged) std::cerr << res.report.message << "\n";
/// @endcode

#include <optional>
#include <string>
#include <vector>

#include "sim/AirDomain.h"
#include "sim/AmbientWind.h"
#include "sim/MomentumWind.h"
#include "sim/PoissonSolver.h"
#include "sim/WindField.h"

namespace gale::sim {

struct MassConsistentWeights;  // sim/SteadyWind.h

/// The steady model a scene chooses ([solver] model).
enum class SteadyModel {
    MassConsistent,  ///< Sherman 1978: free slip, no drag (sim/SteadyWind.h)
    Momentum,        ///< RANS with a surface layer (sim/MomentumWind.h)
};

/// Name as written in scene files ("mass_consistent", "momentum"), and back; fromName throws
/// gale::ParameterError (solver.model) listing the valid names.
const char* steadyModelName(SteadyModel model);
SteadyModel steadyModelFromName(const std::string& name);

/// What either model produced. For the momentum model `report` summarises its run (converged,
/// iterations = pseudo-time steps, max divergence, message) and `momentum` holds the history.
struct SteadyModelResult {
    WindField field;
    SolveReport report;
    std::optional<MomentumReport> momentum;
    /// The momentum model's turbulent kinetic energy (MomentumWindResult::tke_m2ps2); empty for
    /// the mass-consistent model, which has no turbulence.
    std::vector<double> tke_m2ps2;
};

/// Solves the chosen steady model: the mass-consistent field with `weights` and `settings`, or
/// the momentum model started from the mass-consistent field solved with `settings`
/// (momentum.start is overwritten by them). Throws gale::ParameterError as the model does.
[[nodiscard]] SteadyModelResult solveSteadyModel(const AirDomain& domain,
                                                 const AmbientWind& ambient, SteadyModel model,
                                                 const MassConsistentWeights& weights,
                                                 const SolverSettings& settings,
                                                 const MomentumSettings& momentum = {});

}  // namespace gale::sim
