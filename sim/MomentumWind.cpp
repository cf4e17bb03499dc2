/// \file MomentumWind.cpp
/// Pseudo-time stepping of the unsteady solver with surface-layer stresses to a steady state.
#include "sim/MomentumWind.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/Format.h"
#include "sim/MomentumAdvection.h"
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

const char* pseudoTimeAdvectionName(PseudoTimeAdvection a) {
    return a == PseudoTimeAdvection::Eulerian ? "eulerian" : "semi_lagrangian";
}

PseudoTimeAdvection pseudoTimeAdvectionFromName(const std::string& name) {
    for (PseudoTimeAdvection a :
         {PseudoTimeAdvection::SemiLagrangian, PseudoTimeAdvection::Eulerian})
        if (name == pseudoTimeAdvectionName(a)) return a;
    throw ParameterError("solver.momentum_advection", "\"" + name + "\"",
                         "one of \"semi_lagrangian\", \"eulerian\"");
}

void MomentumSettings::validate() const {
    if (!(cfl > 0.0) || !std::isfinite(cfl))
        throw std::logic_error("MomentumSettings::cfl must be > 0 and finite, got " + num(cfl));
    if (!(eulerianCfl > 0.0) || !(eulerianCfl <= EULERIAN_MAX_CFL))
        throw std::logic_error("MomentumSettings::eulerianCfl must be in (0, " +
                               num(EULERIAN_MAX_CFL) + "], got " + num(eulerianCfl));
    if (maxIterations < 1)
        throw ParameterError("solver.momentum_max_iterations", std::to_string(maxIterations),
                             "must be >= 1");
    if (coarseLevels < 0)
        throw ParameterError("solver.momentum_coarse_levels", std::to_string(coarseLevels),
                             "must be >= 0");
    if (minIterationsAfterProlongation < 1)
        throw std::logic_error(
            "MomentumSettings::minIterationsAfterProlongation must be >= 1, got " +
            std::to_string(minIterationsAfterProlongation));
    if (!(residualTolerance > 0.0) || !std::isfinite(residualTolerance))
        throw std::logic_error("MomentumSettings::residualTolerance must be > 0, got " +
                               num(residualTolerance));
    validateWallAndMixing(displacementHeight_m, mixingLengthMax_m);
    if (wallStress && !eddyViscosity)
        throw std::logic_error("MomentumSettings: the wall stress needs the eddy viscosity");
}

int residualCyclePeriod(const std::vector<double>& residuals, int window, double& correlation) {
    correlation = 0.0;
    const int n = std::min(int(residuals.size()), std::max(window, 0));
    if (n < 4 * MIN_CYCLE_LAG) return 0;
    const double* r = residuals.data() + (residuals.size() - size_t(n));
    double mean = 0.0, firstHalf = 0.0, secondHalf = 0.0;
    for (int i = 0; i < n; ++i) {
        mean += r[i];
        (i < n / 2 ? firstHalf : secondHalf) += r[i];
    }
    mean /= n, firstHalf /= n / 2, secondHalf /= n - n / 2;
    if (!std::isfinite(mean) || !(std::abs(secondHalf - firstHalf) <= 0.25 * firstHalf)) return 0;
    double var = 0.0;
    for (int i = 0; i < n; ++i) var += (r[i] - mean) * (r[i] - mean);
    // A residual that varies by less than 0.1 % of its mean does not cycle (rounding noise).
    constexpr double MIN_RELATIVE_SPREAD = 1e-3;
    if (!(std::sqrt(var / n) > MIN_RELATIVE_SPREAD * std::abs(mean))) return 0;
    // Autocorrelation per lag, normalised by the pairs it has (longer lags are not penalised for
    // having fewer); the period is the first local maximum above the threshold (its multiples
    // correlate as well).
    std::vector<double> corr(size_t(n / 2) + 2, 0.0);
    for (int lag = MIN_CYCLE_LAG - 1; lag <= n / 2 + 1 && lag < n; ++lag) {
        double cov = 0.0;
        for (int i = lag; i < n; ++i) cov += (r[i] - mean) * (r[i - lag] - mean);
        corr[size_t(lag)] = cov / (n - lag) / (var / n);
    }
    for (int lag = MIN_CYCLE_LAG; lag <= n / 2; ++lag) {
        const double c = corr[size_t(lag)];
        if (c >= MIN_CYCLE_CORRELATION && c >= corr[size_t(lag - 1)] &&
            c >= corr[size_t(lag + 1)]) {
            correlation = c;
            return lag;
        }
    }
    return 0;
}

namespace {

/// Residuals of the finest level the cycle detection looks at (the last ones): several periods
/// of the lee example's 12-step cycle.
constexpr int CYCLE_WINDOW_STEPS = 96;

/// What one level leaves for the next: its steady field and its mass-consistent start.
struct LevelResult {
    WindField field, start;
    std::vector<double> tke_m2ps2;  ///< the closure's k after the level's last step
};

/// The coarse level's correction to its mass-consistent field, coarse.field - coarse.start,
/// sampled at each face centre of the fine domain (component by component, the point clamped into
/// the coarse box so that a fine box a little longer than the coarse one reads its edge), added
/// to the fine level's own mass-consistent field: the start of a fine level. Prolonging the
/// correction rather than the field keeps what the fine grid resolves better (the log profile in
/// its first cells) and carries over what the coarse level learnt (the wake, the crest's
/// speed-up); over flat ground, where the correction is zero, the fine level starts on its fixed
/// point.
WindField prolong(const LevelResult& coarseLevel, const WindField& fine) {
    WindField coarse = coarseLevel.field;
    for (int c = 0; c < 3; ++c) {
        std::vector<double>& a = c == 0 ? coarse.u_mps() : c == 1 ? coarse.v_mps() : coarse.w_mps();
        const std::vector<double>& b = c == 0   ? coarseLevel.start.u_mps()
                                       : c == 1 ? coarseLevel.start.v_mps()
                                                : coarseLevel.start.w_mps();
        for (size_t f = 0; f < a.size(); ++f) a[f] -= b[f];
    }
    WindField out = fine;
    const auto co = coarse.wsMin_m();
    const double ch = coarse.voxelSize_m();
    const double hi[3] = {co[0] + coarse.nx() * ch, co[1] + coarse.ny() * ch, coarse.wsTop_m()};
    // World positions from the fine layout (its stretched layers, if any); the coarse levels
    // have cubic cells and are sampled at those positions.
    const GridLayout& G = fine.layout();
    std::vector<double>* comp[3] = {&out.u_mps(), &out.v_mps(), &out.w_mps()};
    for (int c = 0; c < 3; ++c) {
        const Placement pl = Placement(c);
        const auto n = G.dims(pl);
        const int n0 = n[0], n1 = n[1], n2 = n[2];
        std::vector<double>& a = *comp[c];
        tbb::parallel_for(0, n2, [&](int k) {
            for (int j = 0; j < n1; ++j)
                for (int i = 0; i < n0; ++i) {
                    Vec3d p = G.wsPosition(pl, i, j, k);
                    for (int e = 0; e < 3; ++e)
                        p[e] = std::clamp(p[e], co[e] + 1e-9 * ch, hi[e] - 1e-9 * ch);
                    a[G.index(pl, i, j, k)] +=
                        coarse.velocityAboveTerrainAt_mps(p[0], p[1], p[2])[size_t(c)];
                }
        });
    }
    return out;
}

/// The cycle average of an unconverged finest level (MomentumSettings::averageCycles): when the
/// residual of the level's steps cycles with a period of P steps, take whole periods more
/// (at least averageMinSteps) and leave their mean field in the solver. Each extra step is in
/// the history; lv.message receives the note the report's message ends with.
template <class Step>
void averageOverCycles(UnsteadyWindSolver& solver, const MomentumSettings& settings,
                       MomentumLevel& lv, MomentumReport& rep, Step& stepOnce) {
    std::vector<double> residuals;
    for (const MomentumIteration& m : rep.history)
        if (m.level == lv.level) residuals.push_back(m.momentumResidual);
    const int period = residualCyclePeriod(residuals, CYCLE_WINDOW_STEPS, rep.cycleCorrelation);
    rep.cyclePeriod = period;
    if (period == 0) return;
    const int steps = period * std::max(1, (settings.averageMinSteps + period - 1) / period);
    std::vector<double> sum[3];
    for (int n = 1; n <= steps; ++n) {
        if (!stepOnce(lv.iterations + n) || rep.stopped) return;
        const WindField& F = solver.field();
        const std::vector<double>* q[3] = {&F.u_mps(), &F.v_mps(), &F.w_mps()};
        for (int c = 0; c < 3; ++c) {
            if (sum[c].empty()) sum[c].assign(q[c]->size(), 0.0);
            for (size_t f = 0; f < sum[c].size(); ++f) sum[c][f] += (*q[c])[f];
        }
    }
    WindField mean = solver.field();
    std::vector<double>* out[3] = {&mean.u_mps(), &mean.v_mps(), &mean.w_mps()};
    for (int c = 0; c < 3; ++c)
        for (size_t f = 0; f < sum[c].size(); ++f) (*out[c])[f] = sum[c][f] / steps;
    solver.resetState(mean);
    rep.averagedSteps = steps;
    lv.message = "; the residual cycles with a period of " + std::to_string(period) +
                 " steps (autocorrelation " + num(rep.cycleCorrelation) +
                 "), so the field is the mean of " + std::to_string(steps) + " more steps (" +
                 std::to_string(steps / period) + " periods)";
}

/// The pseudo-time iteration on one level: from `initial` (nullptr: the mass-consistent field),
/// with the mass-consistent field as the far field. Appends to rep's history (tagged with level).
/// The surface layer of every pseudo-time step: the wind's roughness, the model's displacement
/// and mixing length, the ambient log profile held in balance when both stresses are on.
SurfaceLayerSettings momentumSurfaceLayer(const AmbientWind& ambient,
                                          const MomentumSettings& settings) {
    SurfaceLayerSettings s;
    s.enabled = settings.eddyViscosity || settings.wallStress;
    s.closure = settings.turbulence;
    s.roughness_m = ambient.roughness_m;
    s.displacementHeight_m = settings.displacementHeight_m;
    s.mixingLengthMax_m = settings.mixingLengthMax_m;
    s.eddyViscosity = settings.eddyViscosity;
    s.wallStress = settings.wallStress;
    if (settings.eddyViscosity && settings.wallStress) s.balanced = ambient;
    return s;
}

LevelResult iterateLevel(const AirDomain& domain, const AmbientWind& ambient,
                         const MomentumSettings& settings, const LevelResult* initial, int level,
                         int levelCount, MomentumReport& rep) {
    const auto t0 = Clock::now();
    MomentumLevel lv;
    lv.level = level;
    lv.voxelSize_m = domain.voxelSize_m();
    lv.cells = {domain.nx(), domain.ny(), domain.nz()};
    SteadyWindResult start =
        solveSteadyWind(domain, ambient, MassConsistentWeights{}, settings.start);
    if (level == 0) rep.start = start.report;
    const double uRef = ambient.speed_mps > 0.0 ? ambient.speed_mps : 1.0;
    double uMax = ambient.speed_mps;
    for (const auto* a : {&start.field.u_mps(), &start.field.v_mps(), &start.field.w_mps()})
        for (double x : *a) uMax = std::max(uMax, std::abs(x));
    if (!(uMax > 0.0) || !std::isfinite(uMax)) uMax = uRef;
    const double h = domain.voxelSize_m();
    const bool eulerian = settings.advection == PseudoTimeAdvection::Eulerian;
    if (eulerian) {
        const MacGrid grid(domain.layout(), &domain.terrain());
        const WindField& F = start.field;
        const double rate = eulerianRate_ps(grid, {&F.u_mps(), &F.v_mps(), &F.w_mps()});
        lv.dt_s = settings.eulerianCfl / (rate > 0.0 && std::isfinite(rate) ? rate : uMax / h);
    } else {
        lv.dt_s = settings.cfl * h / uMax;
    }

    UnsteadySettings us;
    us.dt_s = lv.dt_s;
    us.openTop = true;
    us.eulerianAdvection = eulerian;
    us.precision = AdvectionPrecision::Double;  // the validated figures (docs/validation.md)
    us.incrementalPressure = eulerian && settings.incrementalPressure;
    us.projection = settings.projection;
    us.surfaceLayer = momentumSurfaceLayer(ambient, settings);
    UnsteadyWindSolver solver(domain, start.field, us, uRef);
    if (initial) solver.resetState(prolong(*initial, start.field));
    LevelResult out;
    if (level > 0) out.start = std::move(start.field);  // the next level's prolongation needs it
    start = SteadyWindResult{};                         // the solver holds its own copy

    const double scale = h / (uRef * uRef * lv.dt_s);
    if (initial) {
        // Started from a coarser level's steady state, whose wake has already crossed the box.
        lv.minIterations = settings.minIterationsAfterProlongation;
    } else {
        // No convergence before the inflow has crossed the box once at the ambient speed: a small
        // disturbance (a low hill) changes the field little per step from the start, so the
        // residual alone would stop before the wake has formed. A calm wind has nothing to carry.
        const double dirRad = gale::radiansFromDegrees(ambient.direction_deg);
        const double crossing_m = std::abs(std::cos(dirRad)) * domain.nx() * h +
                                  std::abs(std::sin(dirRad)) * domain.ny() * h;
        lv.minIterations = ambient.speed_mps > 0.0
                               ? int(std::ceil(crossing_m / (ambient.speed_mps * lv.dt_s)))
                               : 1;
    }
    std::vector<double> prevU, prevV, prevW;
    // One pseudo-time step, recorded in the history; false when the field became non-finite.
    auto stepOnce = [&](int it) {
        prevU = solver.field().u_mps(), prevV = solver.field().v_mps(),
        prevW = solver.field().w_mps();
        const StepReport sr = solver.step(lv.dt_s);
        const WindField& F = solver.field();
        Change c = changeOver(F.u_mps(), prevU, domain.openFractionsX());
        const Change cv = changeOver(F.v_mps(), prevV, domain.openFractionsY());
        const Change cw = changeOver(F.w_mps(), prevW, domain.openFractionsZ());
        c.sumSq += cv.sumSq + cw.sumSq, c.weight += cv.weight + cw.weight;
        c.max = std::max({c.max, cv.max, cw.max});
        MomentumIteration m;
        m.level = level;
        m.iteration = it;
        m.momentumResidual = c.weight > 0.0 ? std::sqrt(c.sumSq / c.weight) * scale : 0.0;
        m.maxMomentumResidual = c.max * scale;
        m.maxDivergenceScaled = sr.maxDivergenceScaled;
        m.projectionIterations = sr.projection.iterations;
        m.projectionConverged = sr.projection.converged;
        m.seconds = sr.total_s;
        m.advection_s = sr.advection_s, m.stress_s = sr.viscosity_s,
        m.projection_s = sr.projection_s;
        rep.history.push_back(m);
        if (settings.onStep && !settings.onStep(m, settings.maxIterations, levelCount)) {
            rep.stopped = true;
            lv.message = "stopped after pseudo-time step " + std::to_string(it) + " of level " +
                         std::to_string(level);
        }
        if (level == 0) {
            rep.maxDivergenceScaled = m.maxDivergenceScaled;
            rep.maxEddyViscosity_m2ps = sr.turbulence.maxEddyViscosity_m2ps;
            rep.maxFrictionVelocity_mps = sr.turbulence.maxFrictionVelocity_mps;
        }
        if (!sr.finite || !std::isfinite(m.maxMomentumResidual)) {
            lv.finite = false;
            lv.message = "the field became non-finite at iteration " + std::to_string(it);
            return false;
        }
        return true;
    };
    for (int it = 1; it <= settings.maxIterations; ++it) {
        if (!stepOnce(it)) break;
        const MomentumIteration& m = rep.history.back();
        lv.iterations = it;
        lv.momentumResidual = m.momentumResidual;
        if (rep.stopped) break;
        if (m.momentumResidual <= settings.residualTolerance && m.projectionConverged &&
            it >= lv.minIterations) {
            lv.converged = true;
            lv.message = "momentum residual " + num(m.momentumResidual) +
                         " <= " + num(settings.residualTolerance) + " after " + std::to_string(it) +
                         " iterations";
            break;
        }
    }
    lv.atStepLimit =
        lv.finite && !lv.converged && !rep.stopped && lv.iterations == settings.maxIterations;
    if (level == 0 && lv.finite && !lv.converged && !rep.stopped && settings.averageCycles)
        averageOverCycles(solver, settings, lv, rep, stepOnce);
    if (lv.message.empty() || rep.averagedSteps > 0)
        lv.message = "not converged: momentum residual " + num(lv.momentumResidual) + " > " +
                     num(settings.residualTolerance) + " after " + std::to_string(lv.iterations) +
                     " iterations, the step limit (raise solver.momentum_max_iterations)" +
                     lv.message;
    lv.iterations += rep.averagedSteps;
    if (level == 0 && lv.finite) {
        rep.finalProjection = solver.project(settings.finalProjection);
        rep.maxDivergenceScaled = solver.maxDivergenceScaled();
    }
    lv.seconds = since(t0);
    rep.levels.push_back(lv);
    out.field = solver.field();
    out.tke_m2ps2 = solver.turbulentKineticEnergy_m2ps2();
    return out;
}

/// Levels below the finest (each doubles the cell edge): while the coarser grid keeps at least
/// COARSE_MIN_CELLS_XY cells along its longer side, COARSE_MIN_CELLS_Z up and one across (a
/// two-dimensional case a few cells wide coarsens to one cell across), at most maxLevels.
int coarseLevelCount(const AirDomain& d, int maxLevels) {
    int n = 0;
    int nx = d.nx(), ny = d.ny(), nz = d.nz();
    while (n < maxLevels && std::max(nx, ny) / 2 >= MomentumSettings::COARSE_MIN_CELLS_XY &&
           std::min(nx, ny) / 2 >= 1 && nz / 2 >= MomentumSettings::COARSE_MIN_CELLS_Z)
        nx /= 2, ny /= 2, nz /= 2, ++n;
    return n;
}

}  // namespace

void validateMomentumWind(const AmbientWind& ambient, const MomentumSettings& settings) {
    settings.validate();
    ambient.validate();
    if (ambient.profile != WindProfile::LogLaw && (settings.eddyViscosity || settings.wallStress))
        throw ParameterError("wind.profile",
                             "\"" + std::string(windProfileName(ambient.profile)) + "\"",
                             "\"log\" for solver.model = \"momentum\" (its inflow and wall "
                             "stress need the roughness)");
    const SurfaceLayerSettings layer = momentumSurfaceLayer(ambient, settings);
    if (layer.enabled) layer.validate();
}

MomentumWindResult solveMomentumWind(const AirDomain& domain, const AmbientWind& ambient,
                                     const MomentumSettings& settings) {
    validateMomentumWind(ambient, settings);
    const auto t0 = Clock::now();
    MomentumWindResult res;
    MomentumReport& rep = res.report;

    // Coarse-grid start: solve on 2^n h first (coarsest first), each level started from the
    // prolonged solution of the one below it. The coarse domains cover the same terrain and top.
    const int levels = coarseLevelCount(domain, settings.coarseLevels);
    LevelResult previous;
    for (int l = levels; l >= 1; --l) {
        DomainSpec spec;
        spec.voxelSize_m = domain.voxelSize_m() * double(1 << l);
        spec.top_m = domain.wsTop_m();
        spec.closedSidesY = domain.closedSidesY();
        spec.memoryLimit_bytes = 1e18;  // 1/8 of the finest level's arrays per level: counted there
        const AirDomain coarse(domain.terrain(), spec);
        previous = iterateLevel(coarse, ambient, settings, l == levels ? nullptr : &previous, l,
                                levels + 1, rep);
        if (!rep.levels.back().finite || rep.stopped) break;
    }
    if (rep.stopped) {
        // Stopped on a coarse level: its field is the last iterate there, prolonged to the
        // domain's cells through the fine level's own start (no fine step taken).
        const MomentumLevel& lv = rep.levels.back();
        rep.iterations = 0;
        for (const MomentumLevel& l : rep.levels) rep.iterations += l.iterations;
        rep.momentumResidual = lv.momentumResidual;
        rep.message = lv.message + " (a coarse level: the field is the mass-consistent start)";
        res.field = solveSteadyWind(domain, ambient, MassConsistentWeights{}, settings.start).field;
        rep.seconds = since(t0);
        return res;
    }
    // A coarse level that went non-finite is no start: the finest level then starts afresh.
    const bool fromCoarse = levels > 0 && rep.levels.back().finite;
    LevelResult finest = iterateLevel(domain, ambient, settings, fromCoarse ? &previous : nullptr,
                                      0, levels + 1, rep);
    res.field = std::move(finest.field);
    res.tke_m2ps2 = std::move(finest.tke_m2ps2);
    const MomentumLevel& fine = rep.levels.back();
    rep.iterations = 0;
    for (const MomentumLevel& lv : rep.levels) rep.iterations += lv.iterations;
    rep.fineIterations = fine.iterations;
    rep.minIterations = fine.minIterations;
    rep.momentumResidual = fine.momentumResidual;
    rep.dt_s = fine.dt_s;
    rep.finite = fine.finite;
    rep.converged = fine.converged;
    rep.message = fine.message;
    if (levels > 0 && !fromCoarse) rep.message += " (a coarse level became non-finite)";
    // A coarse level at its step limit is no converged start: the solve is not converged, and
    // the message names the level (the finest level's own verdict stays in its MomentumLevel).
    for (const MomentumLevel& lv : rep.levels) {
        if (lv.level == 0 || lv.converged) continue;
        rep.converged = false;
        rep.message += "; level " + std::to_string(lv.level) + " (" + num(lv.voxelSize_m) +
                       " m cells) " + lv.message;
    }
    if (rep.finite && !rep.finalProjection.converged) {
        rep.converged = false;
        rep.message += "; the final projection did not converge: " + rep.finalProjection.message;
    }
    rep.seconds = since(t0);
    return res;
}

}  // namespace gale::sim
