/// \file MomentumWind.cpp
/// Pseudo-time stepping of the unsteady solver with surface-layer stresses to a steady state.
#include "sim/MomentumWind.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "base/Numbers.h"
#include "sim/Format.h"
#include "sim/SteadyWind.h"
#include "sim/UnsteadyWind.h"

namespace gale::sim {
namespace {

using detail::num;
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

struct Change {
    double sumSq = 0, max = 0, weight = 0;
};

/// Open-fraction weighted sum of squares, sum of weights and maximum of theta |a - b| over the
/// faces (the change of momentum in each face's open volume; a sliver of a cut face carries
/// almost none); NaN propagates into max.
Change changeOver(const std::vector<double>& a, const std::vector<double>& b,
                  const std::vector<float>& open) {
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, a.size(), 1 << 14), Change{},
        [&](const tbb::blocked_range<size_t>& r, Change c) {
            for (size_t f = r.begin(); f != r.end(); ++f) {
                if (!(open[f] > 0.f)) continue;
                const double d = std::abs(a[f] - b[f]), th = open[f];
                c.sumSq += th * d * d, c.weight += th;
                if (!(th * d <= c.max)) c.max = th * d;
            }
            return c;
        },
        [](Change x, const Change& y) {
            x.sumSq += y.sumSq, x.weight += y.weight;
            x.max = std::isnan(y.max) || y.max > x.max ? y.max : x.max;
            return x;
        });
}

}  // namespace

void MomentumSettings::validate() const {
    if (!(cfl > 0.0) || !std::isfinite(cfl))
        throw std::invalid_argument("solver.cfl must be > 0 and finite, got " + num(cfl));
    if (maxIterations < 1)
        throw std::invalid_argument("solver.max_iterations must be >= 1, got " +
                                    std::to_string(maxIterations));
    if (!(residualTolerance > 0.0) || !std::isfinite(residualTolerance))
        throw std::invalid_argument("solver.momentum_tolerance must be > 0, got " +
                                    num(residualTolerance));
    validateWallAndMixing(displacementHeight_m, mixingLengthMax_m);
}

MomentumWindResult solveMomentumWind(const AirDomain& domain, const AmbientWind& ambient,
                                     const MomentumSettings& settings) {
    settings.validate();
    ambient.validate();
    if (ambient.profile != WindProfile::LogLaw)
        throw std::invalid_argument(
            "wind.profile must be \"log\" for solver.model = \"momentum\" (its inflow and wall "
            "stress need the roughness), got \"" +
            std::string(windProfileName(ambient.profile)) + "\"");
    const auto t0 = Clock::now();
    MomentumWindResult res;
    MomentumReport& rep = res.report;

    SteadyWindResult start =
        solveSteadyWind(domain, ambient, MassConsistentWeights{}, settings.start);
    rep.start = start.report;
    const double uRef = ambient.speed_mps > 0.0 ? ambient.speed_mps : 1.0;
    double uMax = ambient.speed_mps;
    for (const auto* a : {&start.field.u_mps(), &start.field.v_mps(), &start.field.w_mps()})
        for (double x : *a) uMax = std::max(uMax, std::abs(x));
    if (!(uMax > 0.0) || !std::isfinite(uMax)) uMax = uRef;
    const double h = domain.voxelSize_m();
    rep.dt_s = settings.cfl * h / uMax;

    UnsteadySettings us;
    us.dt_s = rep.dt_s;
    us.openTop = true;
    us.projection = settings.projection;
    us.surfaceLayer.enabled = true;
    us.surfaceLayer.roughness_m = ambient.roughness_m;
    us.surfaceLayer.displacementHeight_m = settings.displacementHeight_m;
    us.surfaceLayer.mixingLengthMax_m = settings.mixingLengthMax_m;
    us.surfaceLayer.balanced = ambient;
    UnsteadyWindSolver solver(domain, start.field, us, uRef);
    start = SteadyWindResult{};  // the solver holds its own copy

    const double scale = h / (uRef * uRef * rep.dt_s);
    // No convergence before the inflow has crossed the box once at the ambient speed: a small
    // disturbance (a low hill) changes the field little per step from the start, so the residual
    // alone would stop before the wake has formed. A calm wind (speed 0) has nothing to carry.
    const double dirRad = ambient.direction_deg * gale::PI / 180.0;
    const double crossing_m =
        std::abs(std::cos(dirRad)) * domain.nx() * h + std::abs(std::sin(dirRad)) * domain.ny() * h;
    rep.minIterations =
        ambient.speed_mps > 0.0 ? int(std::ceil(crossing_m / (ambient.speed_mps * rep.dt_s))) : 1;
    std::vector<double> prevU, prevV, prevW;
    for (int it = 1; it <= settings.maxIterations; ++it) {
        prevU = solver.field().u_mps(), prevV = solver.field().v_mps(),
        prevW = solver.field().w_mps();
        const StepReport sr = solver.step(rep.dt_s);
        const WindField& F = solver.field();
        Change c = changeOver(F.u_mps(), prevU, domain.openFractionsX());
        const Change cv = changeOver(F.v_mps(), prevV, domain.openFractionsY());
        const Change cw = changeOver(F.w_mps(), prevW, domain.openFractionsZ());
        c.sumSq += cv.sumSq + cw.sumSq, c.weight += cv.weight + cw.weight;
        c.max = std::max({c.max, cv.max, cw.max});
        MomentumIteration m;
        m.iteration = it;
        m.momentumResidual = c.weight > 0.0 ? std::sqrt(c.sumSq / c.weight) * scale : 0.0;
        m.maxMomentumResidual = c.max * scale;
        m.maxDivergenceScaled = sr.maxDivergenceScaled;
        m.projectionIterations = sr.projection.iterations;
        m.projectionConverged = sr.projection.converged;
        m.seconds = sr.total_s;
        rep.history.push_back(m);
        rep.iterations = it;
        rep.momentumResidual = m.momentumResidual;
        rep.maxDivergenceScaled = m.maxDivergenceScaled;
        rep.maxEddyViscosity_m2ps = sr.turbulence.maxEddyViscosity_m2ps;
        rep.maxFrictionVelocity_mps = sr.turbulence.maxFrictionVelocity_mps;
        if (!sr.finite || !std::isfinite(m.maxMomentumResidual)) {
            rep.finite = false;
            rep.message = "the field became non-finite at iteration " + std::to_string(it);
            break;
        }
        if (m.momentumResidual <= settings.residualTolerance && m.projectionConverged &&
            it >= rep.minIterations) {
            rep.converged = true;
            rep.message = "momentum residual " + num(m.momentumResidual) +
                          " <= " + num(settings.residualTolerance) + " after " +
                          std::to_string(it) + " iterations";
            break;
        }
    }
    if (rep.message.empty())
        rep.message = "not converged: momentum residual " + num(rep.momentumResidual) + " > " +
                      num(settings.residualTolerance) + " after " + std::to_string(rep.iterations) +
                      " iterations (raise solver.max_iterations or the tolerance)";
    if (rep.finite) {
        rep.finalProjection = solver.project(settings.finalProjection);
        rep.maxDivergenceScaled = solver.maxDivergenceScaled();
        if (!rep.finalProjection.converged) {
            rep.converged = false;
            rep.message +=
                "; the final projection did not converge: " + rep.finalProjection.message;
        }
    }
    res.field = solver.field();
    rep.seconds = since(t0);
    return res;
}

}  // namespace gale::sim
