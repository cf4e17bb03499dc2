/// \file CrestStudy.cpp
/// The crest experiments' one solve (CrestStudy.h).
#include "validation/CrestStudy.h"

#include <chrono>
#include <stdexcept>

#include "sim/MomentumWind.h"
#include "sim/SteadyWind.h"
#include "sim/SurfaceLayer.h"

namespace gale::validation {

CrestStudy runCrest(const CrestOptions& o) {
    if (o.cellsPerH < 1)
        throw std::invalid_argument("runCrest: cellsPerH must be >= 1, got " +
                                    std::to_string(o.cellsPerH));
    const CrestCase& c = o.crestCase;
    const double h = ridge::H_M / o.cellsPerH;
    const sim::Heightfield terrain = ridge::terrain(h);
    const sim::AmbientWind wind = o.wind ? *o.wind : ridge::wind(c.inflow);
    const auto t0 = std::chrono::steady_clock::now();
    sim::DomainSpec spec;
    spec.voxelSize_m = h;
    spec.top_m = c.topOverH * ridge::H_M;
    spec.momentumModel = c.momentum;
    spec.closedSidesY = c.closedSides;
    const sim::AirDomain domain(terrain, spec);
    sim::SolverSettings start;
    start.maxIterations = 200;
    sim::WindField field;
    CrestStudy r;
    if (c.momentum) {
        sim::MomentumSettings ms;
        ms.maxIterations = CREST_MAX_ITERATIONS;
        ms.eddyViscosity = c.eddyViscosity, ms.wallStress = c.wallStress;
        ms.start = start;
        sim::MomentumWindResult res = sim::solveMomentumWind(domain, wind, ms);
        field = std::move(res.field), r.steps = res.report.iterations;
        r.converged = res.report.converged;
    } else {
        sim::SteadyWindResult res =
            sim::solveSteadyWind(domain, wind, sim::MassConsistentWeights{}, start);
        field = std::move(res.field), r.steps = res.report.iterations;
        r.converged = res.report.converged;
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double y = terrain.sizeY_m() / 2;
    auto u = [&](double xOverH, double dz_m) {
        const double x = xOverH * ridge::H_M;
        return field.velocityAt_mps(x + ridge::UPWIND_M, y, ridge::height_m(x) + dz_m)[0];
    };
    r.uInf_mps = ridge::freeStream_mps(c.inflow);
    // The log inflow's friction velocity: u* = kappa U(z_ref) / ln(z_ref / z0).
    const double uStar = sim::surface::frictionVelocity_mps(wind.speed_mps, wind.referenceHeight_m,
                                                            wind.roughness_m);
    for (int i = 0; i < 3; ++i) {
        const double dz = ridge::CREST_DZ_OVER_H[i] * ridge::H_M;
        r.crestUinf[i] = u(0, dz) / r.uInf_mps;
        r.crestSpeedup[i] = u(0, dz) / u(-2.5, dz) - 1.0;
        if (c.momentum && c.eddyViscosity) {
            // nu_t = l^2 |du/dz| from the field's own shear over the crest (the dominant strain
            // there), against the log layer's kappa u* z.
            const double shear = (u(0, dz + 0.5 * h) - u(0, dz - 0.5 * h)) / h;
            const double l =
                sim::surface::mixingLength_m(dz, sim::surface::BLACKADAR_MAX_MIXING_LENGTH_M, 0.0);
            r.nuRatio[i] = l * l * std::abs(shear) / (sim::surface::KAPPA * uStar * dz);
        }
    }
    for (int i = 0; i < 5; ++i) r.footU_mps[i] = u(-2.5, FOOT_DZ_OVER_H[i] * ridge::H_M);
    return r;
}

}  // namespace gale::validation
