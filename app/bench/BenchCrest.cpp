/// \file BenchCrest.cpp
/// `gale bench models --crest`: which part of the momentum model loses the speed-up over the
/// crest of the Cao and Tamura (2006) ridge (docs/validation.md, section 3, "The crest
/// experiments"). Each case changes one thing of the set-up: the model (potential flow, Euler,
/// the eddy viscosity, the wall stress), the inflow (uniform or the log fit) or the top height.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/bench/BenchModels.h"
#include "app/bench/CaoTamuraRidge.h"
#include "app/io/Errors.h"
#include "app/io/Timing.h"
#include "sim/MomentumWind.h"
#include "sim/SteadyWind.h"
#include "sim/SurfaceLayer.h"

namespace gale::app {
namespace {

/// One experiment: which model, which inflow, which stresses, which top.
struct CrestCase {
    std::string name;
    bool momentum = false;  ///< false: mass-consistent (a_h = a_v)
    bool uniform = false;   ///< uniform inflow instead of the log fit
    bool eddyViscosity = true, wallStress = true;
    double topOverH = 6.0;    ///< the box's top, in ridge heights
    bool closedSides = true;  ///< free-slip y sides (DomainSpec::closedSidesY); false: open
};

/// Heights above the crest the study reports (the measured crest profile's, docs/validation.md).
constexpr double CREST_DZ_OVER_H[3] = {0.25, 0.48, 0.98};
/// The pseudo-time steps per level at most (the set-up's 205 steps converge well within it).
constexpr int CREST_MAX_ITERATIONS = 1000;

}  // namespace

int runCrestStudy(int cellsPerH) {
    const double h = ridge::H_M / cellsPerH;
    const sim::Heightfield terrain = ridge::terrain(h);
    std::vector<CrestCase> cases = {
        {"potential, uniform, OPEN sides", false, true, false, false, 6.0, false},
        {"momentum model, OPEN sides", true, false, true, true, 6.0, false},
        {"potential flow, uniform start", false, true, false, false, 6.0},
        {"potential flow, uniform start", false, true, false, false, 12.0},
        {"mass-consistent, log start", false, false, false, false, 6.0},
        {"Euler, uniform inflow", true, true, false, false, 6.0},
        {"Euler, uniform inflow", true, true, false, false, 12.0},
        {"Euler, log inflow", true, false, false, false, 6.0},
        {"eddy viscosity, free slip", true, false, true, false, 6.0},
        {"eddy viscosity and wall", true, false, true, true, 6.0},
        {"eddy viscosity and wall", true, false, true, true, 12.0},
    };
    std::printf(
        "Crest of the Cao and Tamura ridge, H/h = %d: u/U_inf at the crest and speed-up "
        "against the windward foot (x = -2.5 H) at the same height above the ground\n",
        cellsPerH);
    std::printf("%-32s %4s %6s %5s %8s   %-23s   %-23s  %s\n", "case", "top", "steps", "conv",
                "seconds", "u/U_inf 0.25/0.48/0.98H", "speed-up 0.25/0.48/0.98H",
                "nu_t / (kappa u* z) 0.25/0.48/0.98H");
    const double y = terrain.sizeY_m() / 2;
    bool ok = true;
    for (const CrestCase& c : cases) {
        sim::DomainSpec spec;
        spec.voxelSize_m = h;
        spec.top_m = c.topOverH * ridge::H_M;
        spec.momentumModel = c.momentum;
        spec.closedSidesY = c.closedSides;
        const sim::AmbientWind wind = ridge::wind(c.uniform);
        const auto t0 = Clock::now();
        const sim::AirDomain domain(terrain, spec);
        sim::SolverSettings start;
        start.maxIterations = 200;
        sim::WindField field;
        int steps = 0;
        bool converged = false;
        if (c.momentum) {
            sim::MomentumSettings ms;
            ms.maxIterations = CREST_MAX_ITERATIONS;
            ms.eddyViscosity = c.eddyViscosity, ms.wallStress = c.wallStress;
            ms.start = start;
            sim::MomentumWindResult r = sim::solveMomentumWind(domain, wind, ms);
            field = std::move(r.field), steps = r.report.iterations;
            converged = r.report.converged;
        } else {
            sim::SteadyWindResult r =
                sim::solveSteadyWind(domain, wind, sim::MassConsistentWeights{}, start);
            field = std::move(r.field), steps = r.report.iterations;
            converged = r.report.converged;
        }
        const double seconds = secondsSince(t0);
        ok = ok && converged;
        auto u = [&](double xOverH, double dz_m) {
            const double x = xOverH * ridge::H_M;
            return field.velocityAt_mps(x + ridge::UPWIND_M, y, ridge::height_m(x) + dz_m)[0];
        };
        const double uInf = ridge::freeStream_mps(c.uniform);
        // The inflow fit's friction velocity: u* = kappa U(H) / ln(H / z0).
        const double uStar =
            sim::surface::frictionVelocity_mps(ridge::REFERENCE_SPEED_MPS, ridge::H_M, ridge::Z0_M);
        std::string uinf, speedup, nu;
        char buf[32];
        for (double dzH : CREST_DZ_OVER_H) {
            const double dz = dzH * ridge::H_M;
            std::snprintf(buf, sizeof buf, "%s%.3f", uinf.empty() ? "" : " / ", u(0, dz) / uInf);
            uinf += buf;
            std::snprintf(buf, sizeof buf, "%s%.3f", speedup.empty() ? "" : " / ",
                          u(0, dz) / u(-2.5, dz) - 1.0);
            speedup += buf;
            // The mixing-length closure's nu_t = l^2 |du/dz| from the field's own shear over the
            // crest (the dominant strain there), against the log layer's kappa u* z.
            const double shear = (u(0, dz + 0.5 * h) - u(0, dz - 0.5 * h)) / h;
            const double l =
                sim::surface::mixingLength_m(dz, sim::surface::BLACKADAR_MAX_MIXING_LENGTH_M, 0.0);
            std::snprintf(buf, sizeof buf, "%s%.2f", nu.empty() ? "" : " / ",
                          l * l * std::abs(shear) / (sim::surface::KAPPA * uStar * dz));
            nu += buf;
        }
        const bool closure = c.momentum && c.eddyViscosity;
        std::printf("%-32s %3.0fH %6d %5s %8.2f   %-23s   %-24s  %s\n", c.name.c_str(), c.topOverH,
                    steps, converged ? "yes" : "NO", seconds, uinf.c_str(), speedup.c_str(),
                    closure ? nu.c_str() : "");
        std::fflush(stdout);
    }
    std::printf(
        "measured (Cao and Tamura 2006): u/U_inf 0.884 / 0.885 / 0.889, "
        "speed-up 1.33 / 0.99 / 0.59\n");
    return ok ? EXIT_OK : EXIT_UNMET;
}

}  // namespace gale::app
