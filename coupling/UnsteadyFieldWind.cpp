/// \file UnsteadyFieldWind.cpp
#include "coupling/UnsteadyFieldWind.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <glm/geometric.hpp>

#include "coupling/Flutter.h"

namespace gale::coupling {

NearGround nearGroundOf(const sim::UnsteadySettings& settings) {
    if (!settings.surfaceLayer.enabled) return {NearGroundModel::Tangential};
    return {NearGroundModel::LogLaw, settings.surfaceLayer.roughness_m,
            settings.surfaceLayer.displacementHeight_m};
}

UnsteadyFieldWind::UnsteadyFieldWind(const render::TerrainMesh& mesh,
                                     std::unique_ptr<sim::AirDomain> domain,
                                     const sim::WindField& steady,
                                     const sim::UnsteadySettings& settings,
                                     double referenceSpeed_mps, const FieldWindSpec& response,
                                     double sampleHeight_m)
    : mDomain(std::move(domain)),
      mWind(mesh, response),
      mSampler(mesh, sampleHeight_m, nearGroundOf(settings)) {
    mSolver =
        std::make_unique<sim::UnsteadyWindSolver>(*mDomain, steady, settings, referenceSpeed_mps);
    mBendSpeed_mps = response.bendSpeed_mps;
    // The mean flow's shear k at grass height: the steady field at the sample height and at twice
    // it (coupling/Flutter.h); calm air (the speed at both heights 0) gives 0.
    mMean_mps = mSampler.sample(steady);
    const double zLow_m = std::max(sampleHeight_m, 0.05);
    GrassSampler above(mesh, 2.0 * zLow_m, nearGroundOf(settings));
    const std::vector<glm::vec3> high = above.sample(steady);
    mShearTke_m2ps2.resize(mMean_mps.size());
    for (size_t v = 0; v < mMean_mps.size(); ++v)
        mShearTke_m2ps2[v] =
            shearTke_m2ps2(glm::length(mMean_mps[v]), glm::length(high[v]), zLow_m, 2.0 * zLow_m);
    std::vector<glm::vec3> first = mSampler.sample(mSolver->field());
    setFlutterFor(first);
    mWind.addFieldStep(0.0, std::move(first));
}

void UnsteadyFieldWind::setFlutterFor(const std::vector<glm::vec3>& wsVelocity_mps) {
    // k = the mean flow's shear k + the resolved fluctuation's about it (coupling/Flutter.h).
    std::vector<double> k = resolvedTke_m2ps2(wsVelocity_mps, mMean_mps);
    for (size_t v = 0; v < k.size(); ++v) k[v] += mShearTke_m2ps2[v];
    mWind.setFlutter(flutterFromTke(k, wsVelocity_mps, mBendSpeed_mps));
}

void UnsteadyFieldWind::advanceTo(double t_s, const std::function<bool()>& stop) {
    using Clock = std::chrono::steady_clock;
    while (mSolver->time_s() < t_s) {
        if (stop && stop()) break;
        const auto t0 = Clock::now();
        const sim::StepReport r = mSolver->step(mSolver->nextDt_s());
        const auto t1 = Clock::now();
        std::vector<glm::vec3> velocity = mWind.spareStepBuffer();
        mSampler.sample(mSolver->field(), velocity);
        setFlutterFor(velocity);
        mWind.addFieldStep(r.t_s, std::move(velocity));
        mStats.sampling_s += std::chrono::duration<double>(Clock::now() - t1).count();
        mStats.solve_s += std::chrono::duration<double>(t1 - t0).count();
        ++mStats.steps;
        mStats.simulated_s = r.t_s;
        mStats.maxCfl = std::max(mStats.maxCfl, r.cfl);
        mStats.maxDivergenceScaled = std::max(mStats.maxDivergenceScaled, r.maxDivergenceScaled);
        mStats.maxProjectionIterations =
            std::max(mStats.maxProjectionIterations, r.projection.iterations);
        mStats.maxProjectionResidual =
            std::max(mStats.maxProjectionResidual, r.projection.relativeResidual);
        mStats.allConverged = mStats.allConverged && r.projection.converged;
        if (!r.finite) {
            // A non-finite field would freeze the grass with garbage; stop stepping and say so.
            mStats.allFinite = false;
            std::fprintf(stderr,
                         "unsteady wind: non-finite velocity at t = %.3f s; the field stops here\n",
                         r.t_s);
            break;
        }
    }
}

sim::SolveReport UnsteadyFieldWind::moveToGrid(std::unique_ptr<sim::AirDomain> domain,
                                               const sim::WindField& steady,
                                               const sim::UnsteadySettings& settings,
                                               double referenceSpeed_mps) {
    auto solver =
        std::make_unique<sim::UnsteadyWindSolver>(*domain, steady, settings, referenceSpeed_mps);
    const sim::SolveReport rep = solver->continueFrom(*mSolver);
    mSolver = std::move(solver);  // the old solver goes before its domain
    mDomain = std::move(domain);
    resampleCurrentField();
    return rep;
}

void UnsteadyFieldWind::resampleCurrentField() {
    std::vector<glm::vec3> velocity = mWind.spareStepBuffer();
    mSampler.sample(mSolver->field(), velocity);
    mWind.replaceLastStep(std::move(velocity));
}

void UnsteadyFieldWind::update(double t_s, render::GrassWind& wind) {
    (void)updateUntil(t_s, wind, {});
}

double UnsteadyFieldWind::updateUntil(double t_s, render::GrassWind& wind,
                                      const std::function<bool()>& stop) {
    const UnsteadyRunStats before = mStats;
    if (mStats.allFinite) advanceTo(t_s, stop);
    mLastUpdate = mStats;
    mLastUpdate.steps = mStats.steps - before.steps;
    mLastUpdate.solve_s = mStats.solve_s - before.solve_s;
    mLastUpdate.sampling_s = mStats.sampling_s - before.sampling_s;
    // Stopped short (not for a non-finite field, which stays where it stopped): show the time
    // reached, which the next update carries on from.
    const double shown_s = mStats.allFinite && mSolver->time_s() < t_s ? mSolver->time_s() : t_s;
    mWind.dropStepsBefore(shown_s);
    mWind.update(shown_s, wind);
    return shown_s;
}

std::string UnsteadyFieldWind::stepReport() const {
    if (mLastUpdate.steps == 0) return "no solver step this frame";
    char buf[200];
    std::snprintf(
        buf, sizeof buf,
        "%d step%s, <= %d projection its (residual <= %.1e%s), CFL <= %.2f, div %.1e, %.0f ms "
        "solve + %.0f ms sampling",
        mLastUpdate.steps, mLastUpdate.steps == 1 ? "" : "s", mStats.maxProjectionIterations,
        mStats.maxProjectionResidual, mStats.allConverged ? "" : ", not all converged",
        mStats.maxCfl, mStats.maxDivergenceScaled, mLastUpdate.solve_s * 1e3,
        mLastUpdate.sampling_s * 1e3);
    return buf;
}

std::string UnsteadyFieldWind::describe() const {
    const sim::UnsteadySettings& s = mSolver->settings();
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "unsteady field (%s advection, %s, %zu gusts, %zu whirlwinds); grass: %s",
                  sim::advectionSchemeName(s.advection),
                  s.dt_s > 0 ? ("dt " + std::to_string(s.dt_s) + " s").c_str()
                             : ("CFL " + std::to_string(s.cfl)).c_str(),
                  s.gusts.size(), s.whirlwinds.size(), mWind.describe().c_str());
    return buf;
}

}  // namespace gale::coupling
