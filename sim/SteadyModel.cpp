/// \file SteadyModel.cpp
/// The steady-model names and the dispatcher between the mass-consistent and momentum models.
#include "sim/SteadyModel.h"

#include <utility>

#include "base/ParameterError.h"
#include "sim/SteadyWind.h"

namespace gale::sim {

const char* steadyModelName(SteadyModel model) {
    return model == SteadyModel::Momentum ? "momentum" : "mass_consistent";
}

SteadyModel steadyModelFromName(const std::string& name) {
    if (name == "mass_consistent") return SteadyModel::MassConsistent;
    if (name == "momentum") return SteadyModel::Momentum;
    throw ParameterError("solver.model", "\"" + name + "\"",
                         "expected one of: mass_consistent, momentum");
}

SteadyModelResult solveSteadyModel(const AirDomain& domain, const AmbientWind& ambient,
                                   SteadyModel model, const MassConsistentWeights& weights,
                                   const SolverSettings& settings,
                                   const MomentumSettings& momentum) {
    SteadyModelResult out;
    if (model == SteadyModel::MassConsistent) {
        SteadyWindResult r = solveSteadyWind(domain, ambient, weights, settings);
        out.field = std::move(r.field);
        out.report = r.report;
        return out;
    }
    MomentumSettings ms = momentum;
    ms.start = settings;
    MomentumWindResult r = solveMomentumWind(domain, ambient, ms);
    out.field = std::move(r.field);
    SolveReport& s = out.report;
    s.converged = r.report.converged && r.report.finite;
    s.iterations = r.report.iterations;
    s.relativeResidual = r.report.momentumResidual;
    s.initialRelativeResidual =
        r.report.history.empty() ? 0.0 : r.report.history.front().momentumResidual;
    s.solveSeconds = r.report.seconds;
    s.setupSeconds = r.report.start.setupSeconds;
    s.levels = r.report.finalProjection.levels;
    s.message = r.report.message;
    s.maxDivergenceScaled = r.report.maxDivergenceScaled;
    out.momentum = std::move(r.report);
    out.tke_m2ps2 = std::move(r.tke_m2ps2);
    return out;
}

}  // namespace gale::sim
