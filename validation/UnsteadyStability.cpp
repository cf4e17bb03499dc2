/// \file UnsteadyStability.cpp
/// The stability suite and the exact-solution vortex studies of the unsteady wind
/// (UnsteadyStability.h): set-ups, runs and measurements; no verdicts.
#include "validation/UnsteadyStability.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>
#include <stdexcept>

#include "base/Numbers.h"
#include "sim/SteadyWind.h"

namespace gale::validation {
using namespace gale::sim;  // the solvers these cases set up and run
namespace {

using gale::PI;
/// Lamb-Oseen's peak swirl sits at this many core radii (the root of d/dr[(1 - e^{-r^2}) / r]).
constexpr double LAMB_OSEEN_PEAK_CORES = 1.1209;

Heightfield flatTerrain(double sx, double sy, double spacing) {
    TerrainSpec s;
    s.kind = TerrainKind::Flat;
    s.sizeX_m = sx, s.sizeY_m = sy, s.spacing_m = spacing;
    return makeTerrain(s);
}

Heightfield hill(double sx, double sy, double height, double radius) {
    TerrainSpec s;
    s.kind = TerrainKind::GaussianHill;
    s.sizeX_m = sx, s.sizeY_m = sy, s.spacing_m = 1.0;
    s.height_m = height, s.radius_m = radius, s.centerX_m = sx / 2, s.centerY_m = sy / 2;
    return makeTerrain(s);
}

/// A Gaussian ridge across the wind (axis along y) at x = centre.
Heightfield ridge(double sx, double sy, double height, double halfWidth, double centreX) {
    TerrainSpec s;
    s.kind = TerrainKind::Ridge;
    s.sizeX_m = sx, s.sizeY_m = sy, s.spacing_m = 1.0;
    s.height_m = height, s.radius_m = halfWidth, s.centerX_m = centreX, s.centerY_m = sy / 2,
    s.axis_deg = 90.0;
    return makeTerrain(s);
}

AmbientWind uniformWind(double speed) {
    AmbientWind a;
    a.profile = WindProfile::Uniform;
    a.speed_mps = speed;
    return a;
}

Whirlwind vortex(double x, double y, double rc, double peak) {
    Whirlwind w;
    w.wsPosition_m = {x, y};
    w.coreRadius_m = rc;
    w.peakSpeed_mps = peak;
    return w;
}

/// The advection's arithmetic of the case runStabilityCase is running (its argument): every
/// case builds its solver through setUp, which applies it, so the cases' definitions need not
/// carry it.
thread_local AdvectionPrecision gCasePrecision = AdvectionPrecision::Single;

/// The domain, its steady potential flow (the start and the far field) and the solver.
StabilityRun setUp(const Heightfield& terrain, double voxel_m, std::optional<double> top_m,
                   const AmbientWind& wind, UnsteadySettings settings) {
    StabilityRun r;
    settings.precision = gCasePrecision;
    settings.projection.relativeTolerance = 1e-7;
    settings.projection.maxIterations = 200;
    r.domain = std::make_unique<AirDomain>(terrain, DomainSpec{voxel_m, top_m, 2e9});
    SolverSettings tight;
    tight.relativeTolerance = 1e-9;
    tight.maxIterations = 300;
    const SteadyWindResult steady = solveSteadyWind(*r.domain, wind, {}, tight);
    r.referenceSpeed_mps = wind.speed_mps > 0 ? wind.speed_mps : 1.0;
    r.solver =
        std::make_unique<UnsteadyWindSolver>(*r.domain, steady.field, settings, wind.speed_mps);
    r.start = steady.field;
    return r;
}

/// Runs `steps` steps of dt_s and records the measurements; a vortex seeded in the first step
/// moves the start (field and energy) to after that step.
void advance(StabilityRun& r, int steps, double dt_s) {
    const auto t0 = std::chrono::steady_clock::now();
    const UnsteadySettings& s = r.solver->settings();
    r.forced = !s.gusts.empty() || s.vorticityConfinement > 0.0 ||
               std::any_of(s.whirlwinds.begin(), s.whirlwinds.end(),
                           [](const Whirlwind& w) { return w.forced; });
    const bool seeded = !s.whirlwinds.empty();
    r.dt_s = dt_s;
    r.keStart_m5ps2 = r.solver->kineticEnergy_m5ps2();
    for (int n = 0; n < steps; ++n) {
        const StepReport rep = r.solver->step(dt_s);
        ++r.steps;
        r.finite = r.finite && rep.finite;
        r.maxSpeed_mps = std::max(r.maxSpeed_mps, rep.maxSpeed_mps);
        r.maxDivergenceScaled = std::max(r.maxDivergenceScaled, rep.maxDivergenceScaled);
        r.maxCfl = std::max(r.maxCfl, rep.cfl);
        r.maxProjectionIterations = std::max(r.maxProjectionIterations, rep.projection.iterations);
        r.forcingEnergy_m5ps2 += std::max(0.0, rep.forcingEnergy_m5ps2);
        if (n == 0 && seeded) {
            r.start = r.solver->field();
            r.keStart_m5ps2 = rep.kineticEnergy_m5ps2;
        }
        r.keEnd_m5ps2 = rep.kineticEnergy_m5ps2;
        r.keMax_m5ps2 = std::max(r.keMax_m5ps2, rep.kineticEnergy_m5ps2);
        if (!rep.finite) break;
    }
    const WindField& f = r.solver->field();
    const AirDomain& d = *r.domain;
    const std::vector<double>* now[3] = {&f.u_mps(), &f.v_mps(), &f.w_mps()};
    const std::vector<double>* was[3] = {&r.start.u_mps(), &r.start.v_mps(), &r.start.w_mps()};
    const std::vector<float>* open[3] = {&d.openFractionsX(), &d.openFractionsY(),
                                         &d.openFractionsZ()};
    double changed = 0.0, held = 0.0;
    for (int c = 0; c < 3; ++c)
        for (size_t i = 0; i < now[c]->size(); ++i) {
            const double diff = (*now[c])[i] - (*was[c])[i];
            changed += (*open[c])[i] * diff * diff;
            held += (*open[c])[i] * (*was[c])[i] * (*was[c])[i];
        }
    r.deviationFromStart = held > 0.0 ? std::sqrt(changed / held) : std::sqrt(changed);
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// 10 m/s over a 4-cell ridge at a fixed step of CFL `cfl` (U dt / h), in a box 12 CFL cells long.
StabilityRun ridgeAtCfl(double cfl, AdvectionScheme scheme) {
    constexpr double H = 2.0, U = 10.0;
    const double length = std::max(48.0, 12.0 * cfl * H);  // >= 10 U dt (U dt = cfl h)
    UnsteadySettings s;
    s.advection = scheme;
    s.dt_s = cfl * H / U;
    s.openTop = true;  // the steady start has an open top: with a lid it would not be steady
    StabilityRun r = setUp(ridge(length, 12, 8, 12, std::min(0.5 * length, 36.0 + 2.0 * cfl * H)),
                           H, {}, uniformWind(U), s);
    advance(r, 12, s.dt_s);
    return r;
}

struct CaseDef {
    std::string name, description;
    bool fast;
    std::function<StabilityRun()> run;
};

const std::vector<CaseDef>& cases() {
    static const std::vector<CaseDef> list = {
        {"cfl5", "CFL 5, semi-Lagrangian, 10 m/s over a ridge, box 12 U dt long", true,
         [] { return ridgeAtCfl(5.0, AdvectionScheme::SemiLagrangian); }},
        {"cfl20", "CFL 20, semi-Lagrangian, 10 m/s over a ridge, box 12 U dt long", true,
         [] { return ridgeAtCfl(20.0, AdvectionScheme::SemiLagrangian); }},
        {"cfl50", "CFL 50, semi-Lagrangian, 10 m/s over a ridge, box 12 U dt long", false,
         [] { return ridgeAtCfl(50.0, AdvectionScheme::SemiLagrangian); }},
        {"cfl20_maccormack", "CFL 20, MacCormack (limited), 10 m/s over a ridge", false,
         [] { return ridgeAtCfl(20.0, AdvectionScheme::MacCormack); }},
        {"cfl20_bfecc", "CFL 20, BFECC (limited), 10 m/s over a ridge", false,
         [] { return ridgeAtCfl(20.0, AdvectionScheme::Bfecc); }},
        {"wind_0", "calm air, 0 m/s, over a hill", true,
         [] {
             UnsteadySettings s;
             s.dt_s = 1.0;
             StabilityRun r = setUp(hill(32, 32, 6, 5), 2.0, {}, uniformWind(0.0), s);
             advance(r, 10, 1.0);
             return r;
         }},
        {"wind_100", "100 m/s over a hill, CFL 4", true,
         [] {
             UnsteadySettings s;
             s.dt_s = 4.0 * 2.0 / 100.0;
             StabilityRun r = setUp(hill(96, 32, 8, 6), 2.0, {}, uniformWind(100.0), s);
             advance(r, 12, s.dt_s);
             return r;
         }},
        {"vertical_cliff", "a 10 m vertical cliff across the wind, 10 m/s, CFL 2", true,
         [] {
             Heightfield h = flatTerrain(48, 32, 1.0);
             for (int j = 0; j < h.ny; ++j)
                 for (int i = 0; i < h.nx; ++i)
                     h.height_m[size_t(j) * h.nx + i] = i >= h.nx / 2 ? 10.0f : 0.0f;
             UnsteadySettings s;
             s.dt_s = 2.0 * 2.0 / 10.0;
             StabilityRun r = setUp(h, 2.0, {}, uniformWind(10.0), s);
             advance(r, 15, s.dt_s);
             return r;
         }},
        {"one_voxel_spike", "a one-voxel spike 12 voxels tall in flat ground, 10 m/s, CFL 2", true,
         [] {
             Heightfield h = flatTerrain(48, 32, 1.0);
             h.height_m[size_t(16) * h.nx + 24] = 24.0f;
             UnsteadySettings s;
             s.dt_s = 2.0 * 2.0 / 10.0;
             StabilityRun r = setUp(h, 2.0, {}, uniformWind(10.0), s);
             advance(r, 15, s.dt_s);
             return r;
         }},
        {"subcell_vortex", "a Lamb-Oseen core of 0.3 cells in calm air", true,
         [] {
             UnsteadySettings s;
             s.dt_s = 0.5;
             s.whirlwinds.push_back(vortex(16, 16, 0.6, 5.0));
             StabilityRun r = setUp(flatTerrain(32, 32, 1.0), 2.0, 8.0, uniformWind(0.0), s);
             advance(r, 12, 0.5);
             return r;
         }},
        {"viscosity_nu_dt_h2_1000", "nu dt / h^2 = 1000 (implicit viscosity) on a vortex", true,
         [] {
             UnsteadySettings s;
             s.dt_s = 1.0, s.viscosity_m2ps = 4000.0;  // h = 2 m: 4000 * 1 / 4 = 1000
             s.whirlwinds.push_back(vortex(16, 16, 4.0, 5.0));
             StabilityRun r = setUp(flatTerrain(32, 32, 1.0), 2.0, 8.0, uniformWind(0.0), s);
             advance(r, 8, 1.0);
             return r;
         }},
        {"step_gust", "a gust with a step envelope (infinitely sharp attack), +10 m/s on 5 m/s",
         true,
         [] {
             UnsteadySettings s;
             s.dt_s = 2.0 * 2.0 / 15.0;
             GustEvent g;
             g.envelope = GustEnvelope::Step, g.peak_mps = 10.0, g.duration_s = 3.0,
             g.start_s = 0.5;
             s.gusts.push_back(g);
             StabilityRun r = setUp(hill(48, 32, 8, 6), 2.0, {}, uniformWind(5.0), s);
             advance(r, 20, s.dt_s);
             return r;
         }},
        {"forced_whirlwind", "a forced whirlwind with updraft carried over a hill at CFL 5", false,
         [] {
             UnsteadySettings s;
             s.dt_s = 5.0 * 2.0 / 12.0, s.vorticityConfinement = 0.3;
             Whirlwind w = vortex(12, 16, 4.0, 8.0);
             w.forced = true, w.updraft_mps = 2.0, w.height_m = 10.0;
             s.whirlwinds.push_back(w);
             StabilityRun r = setUp(hill(96, 32, 6, 6), 2.0, {}, uniformWind(4.0), s);
             advance(r, 20, s.dt_s);
             return r;
         }},
    };
    return list;
}

const CaseDef& caseNamed(const std::string& name) {
    for (const CaseDef& c : cases())
        if (c.name == name) return c;
    throw std::invalid_argument("no stability case named \"" + name + "\"");
}

/// Azimuthal speed averaged around a ring of radius r (metres) at height z about axis (cx, cy).
double ringSwirl_mps(const StabilityRun& run, double cx, double cy, double r, double z) {
    return circulationAround(run.solver->grid(), run.solver->velocity(), {cx, cy}, r, z) /
           (2 * PI * r);
}

}  // namespace

std::vector<std::string> stabilityCaseNames(bool fastOnly) {
    std::vector<std::string> out;
    for (const CaseDef& c : cases())
        if (!fastOnly || c.fast) out.push_back(c.name);
    return out;
}

std::string stabilityCaseDescription(const std::string& name) {
    return caseNamed(name).description;
}

StabilityRun runStabilityCase(const std::string& name, AdvectionPrecision precision) {
    const CaseDef& c = caseNamed(name);
    const AdvectionPrecision before = gCasePrecision;
    gCasePrecision = precision;
    StabilityRun r;
    try {
        r = c.run();
    } catch (...) {
        gCasePrecision = before;
        throw;
    }
    gCasePrecision = before;
    r.name = c.name, r.description = c.description;
    return r;
}

StabilityRun runTranslatingVortex(int cellsPerCore, double courant) {
    using S = TranslatingVortexSpec;
    if (cellsPerCore < 1 || !(courant > 0.0))
        throw std::invalid_argument(
            "runTranslatingVortex: cellsPerCore must be >= 1 and courant > 0");
    const double h = S::CORE_M / cellsPerCore;
    UnsteadySettings s;
    const int steps =
        std::max(1, int(std::ceil(S::TIME_S * (S::WIND_MPS + S::PEAK_MPS) / (courant * h))));
    s.dt_s = S::TIME_S / steps;
    Whirlwind w = vortex(S::START_X_M, S::START_Y_M, S::CORE_M, S::PEAK_MPS);
    w.outerRadiusFactor = S::SEED_CORES;
    s.whirlwinds.push_back(w);
    // Box: the tapered swirl (1.5 SEED_CORES cores) stays clear of the sides over the run.
    const double length = S::START_X_M + S::WIND_MPS * S::TIME_S + S::START_X_M,
                 width = 2 * S::START_Y_M;
    StabilityRun r =
        setUp(flatTerrain(length, width, std::min(h, 1.0)), h, 4 * h, uniformWind(S::WIND_MPS), s);
    r.name = "translating_lamb_oseen_" + std::to_string(cellsPerCore) + "_cells_cfl_" +
             std::to_string(courant);
    // The seeding step is step 1: its start is the seeded field, so measure from t = 0 with the
    // energy after seeding (advance moves the start there).
    advance(r, steps, s.dt_s);
    return r;
}

double burgersStrainPressure_m2ps2(double a, double cx, double cy, const Vec3d& ws) {
    // Burgers 1948: u_r = -a r / 2 gives (u . grad) u_r = a^2 r / 4, w = a z gives a^2 z; both
    // are -grad p / rho of p / rho = -a^2 (r^2 / 8 + z^2 / 2).
    const double dx = ws[0] - cx, dy = ws[1] - cy;
    return -a * a * ((dx * dx + dy * dy) / 8.0 + ws[2] * ws[2] / 2.0);
}

namespace {

/// The swirl's kinematic pressure (m^2/s^2) at radius r_m of a vortex, 0 at infinity.
double swirlPressure_m2ps2(const Whirlwind& w, double r) {
    // Radial balance dp/dr = rho v^2 / r integrated inwards from infinity (Lamb 1932): Simpson's
    // rule in ln r' from r to R = 64 r_c, plus the potential tail Gamma^2 / (8 pi^2 R^2) beyond.
    constexpr int INTERVALS = 256;  // even; error far below the runs' (checked against 1024)
    const double R = 64.0 * w.coreRadius_m, rr = std::max(r, 1e-6 * w.coreRadius_m);
    if (rr >= R) {
        const double G = w.circulation();
        return -G * G / (8.0 * PI * PI * rr * rr);
    }
    const double l0 = std::log(rr), l1 = std::log(R), dl = (l1 - l0) / INTERVALS;
    double sum = 0.0;
    for (int n = 0; n <= INTERVALS; ++n) {
        const double v = w.tangentialSpeed_mps(std::exp(l0 + n * dl));
        sum += (n == 0 || n == INTERVALS ? 1.0
                : n % 2                  ? 4.0
                                         : 2.0) *
               v * v;  // v^2 / r' dr' = v^2 dl
    }
    const double G = w.circulation();
    return -(sum * dl / 3.0 + G * G / (8.0 * PI * PI * R * R));
}

}  // namespace

StabilityRun runBurgersVortex(BurgersVariant variant, int cellsPerCore, bool exactBoundaries) {
    using S = BurgersSpec;
    if (cellsPerCore < 1)
        throw std::invalid_argument("runBurgersVortex: cellsPerCore must be >= 1");
    const double h = S::CORE_M / cellsPerCore, half = S::HALF_WIDTH_CORES * S::CORE_M;
    const double a = variant == BurgersVariant::NoStrain ? 0.0 : S::STRAIN_PER_S;
    StabilityRun r;
    const Heightfield terrain = flatTerrain(2 * half, 2 * half, std::min(h, 1.0));
    r.domain =
        std::make_unique<AirDomain>(terrain, DomainSpec{h, S::HEIGHT_CORES * S::CORE_M, 2e9});
    const AirDomain& d = *r.domain;
    // The strain flow u_r = -a r / 2, w = a z as the mean flow (and far field): linear, so
    // discretely divergence-free on the MAC grid. With exact boundaries (strained variants) the
    // mean flow is the whole Burgers solution, strain plus the unwindowed Lamb-Oseen swirl, so
    // the air the strain draws in through the sides carries the swirl's circulation as it does
    // in the exact solution (a windowed swirl would let circulation-free air reach the core
    // after about a t = 2).
    const Whirlwind swirl = vortex(half, half, S::CORE_M, S::PEAK_MPS);
    const bool exactSwirl = exactBoundaries && a > 0.0;
    WindField mean(d.nx(), d.ny(), d.nz(), h, d.wsMin_m(), d.terrainShared(), d.airFlags());
    const MacGrid g{d.nx(), d.ny(), d.nz(), h, d.wsMin_m()};
    std::vector<double>* arrays[3] = {&mean.u_mps(), &mean.v_mps(), &mean.w_mps()};
    for (int c = 0; c < 3; ++c) {
        const auto n = g.dims(Placement(c));
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    const Vec3d ws = g.wsPosition(Placement(c), i, j, k);
                    const double dx = ws[0] - half, dy = ws[1] - half;
                    double v = c == 0 ? -0.5 * a * dx : c == 1 ? -0.5 * a * dy : a * ws[2];
                    const double rho = std::hypot(dx, dy);
                    if (exactSwirl && c < 2 && rho > 0.0)  // e_theta = (-dy, dx) / rho
                        v += swirl.tangentialSpeed_mps(rho) * (c == 0 ? -dy : dx) / rho;
                    (*arrays[c])[g.index(Placement(c), i, j, k)] = v;
                }
    }
    UnsteadySettings s;
    // Boundaries (exactBoundaries false: the old set-up). The strain leaves through the top:
    // open with p = 0 there and on the sides, which cannot carry the strain's pressure, so the
    // strain decays inside the box. Without strain nothing leaves, and the lid keeps the open
    // top's known artefact (the core's low pressure drawing air in through the top,
    // docs/unsteady.md) out of the viscous-spreading contrast.
    s.openTop = variant != BurgersVariant::NoStrain && !exactBoundaries;
    s.viscosity_m2ps = variant == BurgersVariant::NoViscosity ? 0.0 : S::viscosity_m2ps();
    // MacCormack: at 4 cells per core semi-Lagrangian's numerical viscosity is about half of nu
    // (measured: the balanced core settles towards 1.22 r_c), MacCormack's about a sixth.
    s.advection = AdvectionScheme::MacCormack;
    if (exactBoundaries && a > 0.0) {
        // The exact solution on the boundary: its pressure (strain plus swirl) on the open
        // sides, and its outflow w = a z through the top as a prescribed normal velocity, so
        // the core's low pressure cannot draw air in there.
        s.boundaryPressure_m2ps2 = [a, half, swirl](const Vec3d& ws) {
            return burgersStrainPressure_m2ps2(a, half, half, ws) +
                   swirlPressure_m2ps2(swirl, std::hypot(ws[0] - half, ws[1] - half));
        };
        const double top = d.wsTop_m();
        s.lidVelocity_mps = [a, top](double, double) { return a * top; };
    }
    const double umax = 0.5 * S::STRAIN_PER_S * half + S::PEAK_MPS;
    const int steps = std::max(1, int(std::ceil(S::TIME_S * umax / h)));  // CFL 1
    s.dt_s = S::TIME_S / steps;
    s.projection.relativeTolerance = 1e-7;
    s.projection.maxIterations = 200;
    if (!exactSwirl) {  // seeded in the first step, windowed to 3 cores
        Whirlwind w = swirl;
        w.outerRadiusFactor = 3.0;
        s.whirlwinds.push_back(w);
    }
    r.referenceSpeed_mps = S::PEAK_MPS;
    r.solver = std::make_unique<UnsteadyWindSolver>(d, mean, s, S::PEAK_MPS);
    r.start = mean;
    r.name = std::string("burgers_") + (variant == BurgersVariant::Balanced      ? "balanced"
                                        : variant == BurgersVariant::NoViscosity ? "no_viscosity"
                                                                                 : "no_strain");
    advance(r, steps, s.dt_s);
    return r;
}

double burgersCoreRadius_m(const StabilityRun& run) {
    using S = BurgersSpec;
    const double half = S::HALF_WIDTH_CORES * S::CORE_M, z = 0.5 * S::HEIGHT_CORES * S::CORE_M;
    // The peak of the ring-averaged swirl, refined by a parabola through the best three rings.
    constexpr int RINGS = 64;
    const double dr = 3.0 * S::CORE_M / RINGS;
    std::vector<double> v(RINGS + 1, 0.0);
    int best = 1;
    for (int n = 1; n <= RINGS; ++n) {
        v[n] = ringSwirl_mps(run, half, half, n * dr, z);
        if (v[n] > v[best]) best = n;
    }
    double rPeak = best * dr;
    if (best > 1 && best < RINGS) {
        const double den = v[best - 1] - 2 * v[best] + v[best + 1];
        if (den < 0) rPeak += 0.5 * dr * (v[best - 1] - v[best + 1]) / den;
    }
    return rPeak / LAMB_OSEEN_PEAK_CORES;
}

}  // namespace gale::validation
