/// \file UnsteadyStability.cpp
/// The extreme cases of DESIGN 4.4 for the unsteady wind.
#include "sim/UnsteadyStability.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "sim/AirDomain.h"
#include "sim/SteadyWind.h"
#include "sim/UnsteadyWind.h"

namespace gale::sim {
namespace {

struct CaseDef {
    std::string name, description;
    bool fast;
    std::function<StabilityResult()> run;
};

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

AmbientWind uniformWind(double speed) {
    AmbientWind a;
    a.profile = WindProfile::Uniform;
    a.speed_mps = speed;
    return a;
}

/// Runs `steps` steps (fixed dt if dt_s > 0, else the settings' adaptive step) and judges them.
StabilityResult judge(const Heightfield& terrain, double voxel_m, std::optional<double> top_m, const AmbientWind& wind,
                      UnsteadySettings settings, int steps) {
    const auto t0 = std::chrono::steady_clock::now();
    StabilityResult r;
    settings.projection.relativeTolerance = 1e-7;
    settings.projection.maxIterations = 200;
    AirDomain domain(terrain, {voxel_m, top_m, 2e9});
    SolverSettings tight;
    tight.relativeTolerance = 1e-9;
    tight.maxIterations = 300;
    const SteadyWindResult steady = solveSteadyWind(domain, wind, {}, tight);
    UnsteadyWindSolver solver(domain, steady.field, settings, wind.speed_mps);
    r.forced = !settings.gusts.empty() ||
               std::any_of(settings.whirlwinds.begin(), settings.whirlwinds.end(), [](const Whirlwind& w) { return w.forced; });
    const bool seeded = !settings.whirlwinds.empty();
    double ke = solver.kineticEnergy_m5ps2();
    r.keStart_m5ps2 = ke;
    const double keMean = ke;
    double injected = 0.0;
    // Energy of the far field at the gusts' peak: (U + sum |peak|)^2 / U^2 times the mean's.
    double gustFactor = 1.0;
    if (!settings.gusts.empty()) {
        double g = 0.0;
        for (const GustEvent& e : settings.gusts) g += std::abs(e.peak_mps);
        const double U = std::max(wind.speed_mps, 1e-9);
        gustFactor = wind.speed_mps > 0 ? (U + g) * (U + g) / (U * U) : 1.0;
    }
    for (int n = 0; n < steps; ++n) {
        const StepReport rep = solver.step(settings.dt_s > 0 ? settings.dt_s : solver.nextDt_s());
        ++r.steps;
        r.finite = r.finite && rep.finite;
        r.maxSpeed_mps = std::max(r.maxSpeed_mps, rep.maxSpeed_mps);
        r.maxDivergenceScaled = std::max(r.maxDivergenceScaled, rep.maxDivergenceScaled);
        r.maxCfl = std::max(r.maxCfl, rep.cfl);
        injected += std::max(0.0, rep.forcingEnergy_m5ps2);
        if (!rep.finite) break;
        if (n == 0 && seeded) {
            // The vortex enters at the start of step 1: energy is judged from after it.
            r.keStart_m5ps2 = rep.kineticEnergy_m5ps2;
        } else {
            // Growth relative to the larger of the current energy and the mean flow's (the inflow
            // keeps supplying the mean flow's energy; calm cases have none).
            const double ref = std::max(ke, keMean);
            if (ref > 0) r.maxGrowth = std::max(r.maxGrowth, (rep.kineticEnergy_m5ps2 - ke) / ref);
            else if (rep.kineticEnergy_m5ps2 > 0) r.maxGrowth = std::max(r.maxGrowth, 1.0);
        }
        ke = rep.kineticEnergy_m5ps2;
        r.keMax_m5ps2 = std::max(r.keMax_m5ps2, ke);
    }
    r.keEnd_m5ps2 = ke;
    r.keBound_m5ps2 = std::max(r.keStart_m5ps2, keMean * gustFactor) + injected;
    r.pass = true;
    auto fail = [&](const std::string& why) {
        r.pass = false;
        r.why += (r.why.empty() ? "" : "; ") + why;
    };
    if (!r.finite) fail("NaN/Inf in the field");
    if (!(r.maxDivergenceScaled <= STABILITY_DIVERGENCE_TOLERANCE)) fail("divergence above tolerance");
    if (r.forced) {
        if (!(r.keMax_m5ps2 <= r.keBound_m5ps2 * (1.0 + STABILITY_ENERGY_GROWTH_TOLERANCE)))
            fail("kinetic energy above the injected bound");
    } else if (!(r.maxGrowth <= STABILITY_ENERGY_GROWTH_TOLERANCE)) {
        fail("kinetic energy grew without forcing");
    }
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

Whirlwind vortex(double x, double y, double rc, double peak) {
    Whirlwind w;
    w.wsPosition_m = {x, y};
    w.coreRadius_m = rc;
    w.peakSpeed_mps = peak;
    return w;
}

const std::vector<CaseDef>& cases() {
    static const std::vector<CaseDef> list = {
        {"cfl50_semi_lagrangian", "CFL 50, semi-Lagrangian, 10 m/s over a hill", true,
         [] {
             UnsteadySettings s;
             s.cfl = 50.0, s.maxDt_s = 1e3;
             return judge(hill(48, 32, 8, 6), 2.0, {}, uniformWind(10.0), s, 12);
         }},
        {"cfl10_maccormack", "CFL 10, MacCormack (limited), 10 m/s over a hill", false,
         [] {
             UnsteadySettings s;
             s.cfl = 10.0, s.maxDt_s = 1e3, s.advection = AdvectionScheme::MacCormack;
             return judge(hill(48, 32, 8, 6), 2.0, {}, uniformWind(10.0), s, 12);
         }},
        {"cfl10_bfecc", "CFL 10, BFECC (limited), 10 m/s over a hill", false,
         [] {
             UnsteadySettings s;
             s.cfl = 10.0, s.maxDt_s = 1e3, s.advection = AdvectionScheme::Bfecc;
             return judge(hill(48, 32, 8, 6), 2.0, {}, uniformWind(10.0), s, 12);
         }},
        {"wind_0", "calm air, 0 m/s, over a hill", true,
         [] {
             UnsteadySettings s;
             s.dt_s = 1.0;
             return judge(hill(32, 32, 6, 5), 2.0, {}, uniformWind(0.0), s, 10);
         }},
        {"wind_100", "100 m/s over a hill, CFL 4", true,
         [] {
             UnsteadySettings s;
             s.cfl = 4.0, s.maxDt_s = 1e3;
             return judge(hill(48, 32, 8, 6), 2.0, {}, uniformWind(100.0), s, 12);
         }},
        {"vertical_cliff", "a 10 m vertical cliff across the wind, 10 m/s", true,
         [] {
             Heightfield h = flatTerrain(48, 32, 1.0);
             for (int j = 0; j < h.ny; ++j)
                 for (int i = 0; i < h.nx; ++i) h.height_m[size_t(j) * h.nx + i] = i >= h.nx / 2 ? 10.0f : 0.0f;
             UnsteadySettings s;
             s.cfl = 2.0, s.maxDt_s = 1e3;
             return judge(h, 2.0, {}, uniformWind(10.0), s, 15);
         }},
        {"one_voxel_spike", "a one-voxel spike 12 voxels tall in flat ground, 10 m/s", true,
         [] {
             Heightfield h = flatTerrain(48, 32, 1.0);
             h.height_m[size_t(16) * h.nx + 24] = 24.0f;
             UnsteadySettings s;
             s.cfl = 2.0, s.maxDt_s = 1e3;
             return judge(h, 2.0, {}, uniformWind(10.0), s, 15);
         }},
        {"aspect_ratio_10", "cells 10 times wider than tall", true,
         [] {
             StabilityResult r;
             r.refused = true;
             r.refusal =
                 "refused: the air domain has cubic cells only (DomainSpec::voxelSize_m is one edge); anisotropic "
                 "cells would defeat the projection's point-smoothed multigrid (DESIGN 7: plain V-cycles diverge "
                 "at (dx/dz)^2 = 16)";
             r.pass = true;
             return r;
         }},
        {"subcell_vortex", "a Lamb-Oseen core of 0.3 cells in calm air", true,
         [] {
             UnsteadySettings s;
             s.dt_s = 0.5;
             s.whirlwinds.push_back(vortex(16, 16, 0.6, 5.0));
             return judge(flatTerrain(32, 32, 1.0), 2.0, 8.0, uniformWind(0.0), s, 12);
         }},
        {"viscosity_nu_dt_h2_1000", "nu dt / h^2 = 1000 (implicit viscosity) on a vortex", true,
         [] {
             UnsteadySettings s;
             s.dt_s = 1.0, s.viscosity_m2ps = 4000.0;  // h = 2 m: 4000 * 1 / 4 = 1000
             s.whirlwinds.push_back(vortex(16, 16, 4.0, 5.0));
             return judge(flatTerrain(32, 32, 1.0), 2.0, 8.0, uniformWind(0.0), s, 8);
         }},
        {"step_gust", "a gust with a step envelope (infinitely sharp attack), +10 m/s on 5 m/s", true,
         [] {
             UnsteadySettings s;
             s.cfl = 2.0, s.maxDt_s = 1e3;
             GustEvent g;
             g.envelope = GustEnvelope::Step, g.peak_mps = 10.0, g.duration_s = 3.0, g.start_s = 0.5;
             s.gusts.push_back(g);
             return judge(hill(48, 32, 8, 6), 2.0, {}, uniformWind(5.0), s, 20);
         }},
        {"forced_whirlwind", "a forced whirlwind with updraft carried over a hill at CFL 5", false,
         [] {
             UnsteadySettings s;
             s.cfl = 5.0, s.maxDt_s = 1e3, s.vorticityConfinement = 0.3;
             Whirlwind w = vortex(12, 16, 4.0, 8.0);
             w.forced = true, w.updraft_mps = 2.0, w.height_m = 10.0;
             s.whirlwinds.push_back(w);
             return judge(hill(48, 32, 6, 6), 2.0, {}, uniformWind(4.0), s, 20);
         }},
    };
    return list;
}

}  // namespace

std::vector<std::string> stabilityCaseNames(bool fastOnly) {
    std::vector<std::string> out;
    for (const CaseDef& c : cases())
        if (!fastOnly || c.fast) out.push_back(c.name);
    return out;
}

StabilityResult runStabilityCase(const std::string& name) {
    for (const CaseDef& c : cases())
        if (c.name == name) {
            StabilityResult r = c.run();
            r.name = c.name, r.description = c.description;
            return r;
        }
    throw std::invalid_argument("no stability case named \"" + name + "\"");
}

}  // namespace gale::sim
