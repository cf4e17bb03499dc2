/// \file PseudoTimeStudy.cpp
/// The pseudo-time study's one solve (PseudoTimeStudy.h).
#include "validation/PseudoTimeStudy.h"

#include <chrono>
#include <vector>

#include "validation/RidgeBox.h"

namespace gale::validation {
namespace {

using namespace pseudotime;

/// A Gaussian ridge: H exp(-x^2 / (2 sigma^2)) about the crest, sampled every CELL_M / 2.
sim::Heightfield terrain(double H_m, double sigma_m) {
    const double spacing = CELL_M / 2;
    const int nx = int(std::lround(LENGTH_M / spacing)) + 1, ny = 7;
    std::vector<float> z(size_t(nx) * ny);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const double x = i * spacing - CREST_X_M;
            z[size_t(j) * nx + i] = float(H_m * std::exp(-x * x / (2 * sigma_m * sigma_m)));
        }
    return sim::makeHeightfield(nx, ny, spacing, std::move(z));
}

}  // namespace

PseudoTimeStudy runPseudoTime(const PseudoTimeOptions& o) {
    const sim::Heightfield hf = terrain(o.ridge.H_m, o.ridge.sigma_m);
    const double leeX_m = CREST_X_M + o.ridge.leeFromCrest_m;
    const sim::DomainSpec spec = ridgebox::spec(CELL_M, TOP_M, true);
    const sim::AmbientWind wind = ridgebox::logLaw(SPEED_MPS, REFERENCE_HEIGHT_M, Z0_M);
    const auto t0 = std::chrono::steady_clock::now();
    const sim::AirDomain domain(hf, spec);
    sim::MomentumSettings ms;
    ms.advection = o.advection;
    (o.advection == sim::PseudoTimeAdvection::Eulerian ? ms.eulerianCfl : ms.cfl) = o.step;
    ms.maxIterations = o.ridge.maxIterations;
    ms.residualTolerance = RESIDUAL_TOLERANCE;
    ms.averageCycles = true;  // a wake that cycles: the mean of whole periods
    ms.incrementalPressure = o.incrementalPressure;
    const sim::MomentumWindResult res = sim::solveMomentumWind(domain, wind, ms);
    PseudoTimeStudy r;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.iterations = res.report.iterations;
    r.converged = res.report.converged;
    r.dt_s = res.report.dt_s;
    const double y = hf.sizeY_m() / 2;
    r.lee_mps = res.field.velocityAt_mps(leeX_m, y, hf.sample(leeX_m, y) + PROBE_HEIGHT_M)[0];
    r.crest_mps =
        res.field.velocityAt_mps(CREST_X_M, y, hf.sample(CREST_X_M, y) + PROBE_HEIGHT_M)[0];
    return r;
}

}  // namespace gale::validation
