/// \file MomentumJson.cpp
/// `gale solve`'s momentum report (MomentumJson.h).
#include "app/MomentumJson.h"

namespace gale::app {

nlohmann::json momentumJson(const sim::MomentumReport& m, const sim::MomentumSettings& s) {
    nlohmann::json history = nlohmann::json::array();
    for (const sim::MomentumIteration& it : m.history)
        history.push_back({{"level", it.level},
                           {"iteration", it.iteration},
                           {"momentum_residual", it.momentumResidual},
                           {"max_momentum_residual", it.maxMomentumResidual},
                           {"max_div_u_h_over_U", it.maxDivergenceScaled},
                           {"projection_iterations", it.projectionIterations},
                           {"projection_converged", it.projectionConverged},
                           {"step_s", it.seconds},
                           {"advection_s", it.advection_s},
                           {"stress_s", it.stress_s},
                           {"projection_s", it.projection_s}});
    nlohmann::json levels = nlohmann::json::array();
    for (const sim::MomentumLevel& l : m.levels)
        levels.push_back({{"level", l.level},
                          {"voxel_size_m", l.voxelSize_m},
                          {"cells", l.cells},
                          {"pseudo_dt_s", l.dt_s},
                          {"iterations", l.iterations},
                          {"min_iterations", l.minIterations},
                          {"momentum_residual", l.momentumResidual},
                          {"converged", l.converged},
                          {"at_step_limit", l.atStepLimit},
                          {"message", l.message},
                          {"seconds", l.seconds}});
    return {
        {"closure", sim::turbulenceClosureName(s.turbulence)},
        {"advection", sim::pseudoTimeAdvectionName(s.advection)},
        {"stopped", m.stopped},
        {"converged", m.converged},
        {"finite", m.finite},
        {"iterations", m.iterations},
        {"fine_iterations", m.fineIterations},
        {"levels", levels},
        {"momentum_residual", m.momentumResidual},
        {"residual_definition",
         "open-fraction weighted RMS over faces of |u(n+1) - u(n)| / dt * h / U^2"},
        {"tolerance", s.residualTolerance},
        {"max_div_u_h_over_U", m.maxDivergenceScaled},
        {"pseudo_dt_s", m.dt_s},
        {"cfl", s.cfl},
        {"mixing_length_max_m", s.mixingLengthMax_m},
        {"displacement_height_m", s.displacementHeight_m},
        {"max_eddy_viscosity_m2ps", m.maxEddyViscosity_m2ps},
        {"max_friction_velocity_mps", m.maxFrictionVelocity_mps},
        {"start_iterations", m.start.iterations},
        {"cycle_period_steps", m.cyclePeriod},
        {"cycle_autocorrelation", m.cycleCorrelation},
        {"averaged_steps", m.averagedSteps},
        {"field", m.averagedSteps > 0
                      ? "mean of the last averaged_steps iterates (whole cycles of a periodic wake)"
                      : "last iterate"},
        {"message", m.message},
        {"seconds", m.seconds},
        {"history", history}};
}

}  // namespace gale::app
