/// \file JacksonHuntStudy.cpp
/// The low-ridge study (JacksonHuntStudy.h). Each ridge is solved in a box a few cells across
/// with free-slip side walls (DomainSpec::closedSidesY), the two-dimensional flow the theory
/// describes.
#include "validation/JacksonHuntStudy.h"

#include <chrono>
#include <vector>

#include "base/Numbers.h"
#include "sim/MomentumWind.h"
#include "sim/SteadyWind.h"
#include "validation/RidgeBox.h"

namespace gale::validation {
namespace {

using namespace jacksonhunt;

/// Ground height (m) of the cos^2 ridge of height H_m at xFromCrest_m: H cos^2(pi x / 4 L) for
/// |x| < 2 L (half height at x = L), 0 beyond.
double ridgeHeight_m(double H_m, double xFromCrest_m) {
    if (std::abs(xFromCrest_m) >= 2 * L_M) return 0.0;
    const double c = std::cos(PI * xFromCrest_m / (4 * L_M));
    return H_m * c * c;
}

/// The ridge sampled every CELL_M / 2 m, 3 cells across, placed at the options' offset.
sim::Heightfield terrain(const JacksonHuntOptions& o) {
    const double spacing = CELL_M / 2;
    const int nx = int(std::lround(LENGTH_M / spacing)) + 1, ny = 7;
    std::vector<float> z(size_t(nx) * ny);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            z[size_t(j) * nx + i] =
                float(o.base_m + ridgeHeight_m(o.H_m, i * spacing - CREST_X_M - o.shift_m));
    return sim::makeHeightfield(nx, ny, spacing, std::move(z));
}

}  // namespace

JacksonHuntStudy runJacksonHunt(const JacksonHuntOptions& o) {
    const sim::Heightfield hf = terrain(o);
    const sim::DomainSpec spec = ridgebox::spec(CELL_M, TOP_M + o.base_m, o.momentum);
    const sim::AmbientWind wind = ridgebox::logLaw(SPEED_MPS, REFERENCE_HEIGHT_M, Z0_M);
    const auto t0 = std::chrono::steady_clock::now();
    const sim::AirDomain domain(hf, spec);
    sim::SolverSettings start;
    start.maxIterations = 200;
    sim::MomentumSettings ms;
    ms.maxIterations = MAX_ITERATIONS;
    const sim::SteadyModelResult res = sim::solveSteadyModel(
        domain, wind, o.momentum ? sim::SteadyModel::Momentum : sim::SteadyModel::MassConsistent,
        sim::MassConsistentWeights{}, start, ms);
    JacksonHuntStudy r;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.iterations = res.report.iterations;
    r.converged = res.report.converged;
    const double y = hf.sizeY_m() / 2, zCrest = o.base_m + ridgeHeight_m(o.H_m, 0.0);
    const double xCrest = CREST_X_M + o.shift_m;
    auto speed = [&](double x, double z) {
        const auto u = res.field.velocityAt_mps(x, y, z);
        return std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    };
    for (int k = 0; k < 3; ++k) {
        const double upwind = speed(REFERENCE_X_M, o.base_m + DZ_M[k]);
        r.speedup[k] = (speed(xCrest, zCrest + DZ_M[k]) - upwind) / upwind;
    }
    return r;
}

}  // namespace gale::validation
