/// \file BenchModelsPseudoTime.cpp
/// `gale bench models --pseudo-time`: does the momentum model's steady state depend on its
/// pseudo-time step? (docs/validation.md, "Pseudo-time step and its error"). Two Gaussian ridges
/// across the wind in a 2-D box (3 cells across, free-slip side walls), each solved with the
/// semi-Lagrangian step at several cfl and with the Eulerian step (sim/MomentumAdvection.h) at
/// several steps below its stability limit; the speed 10 m above the lee's ground is the measure.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/bench/BenchModels.h"
#include "app/bench/RidgeBox.h"
#include "app/io/Errors.h"
#include "app/io/Timing.h"
#include "sim/MomentumAdvection.h"
#include "sim/MomentumWind.h"

namespace gale::app {
namespace {

constexpr double CELL_M = 4.0;                     ///< the cell size
constexpr double LENGTH_M = 500.0, TOP_M = 200.0;  ///< the box
constexpr double CREST_X_M = 150.0;                ///< the crest's distance from the inflow face
constexpr double Z0_M = 0.03, SPEED_MPS = 10.0, REFERENCE_HEIGHT_M = 10.0;  ///< the log inflow
constexpr double PROBE_HEIGHT_M = 10.0;      ///< the lee probe's height above the ground
constexpr double RESIDUAL_TOLERANCE = 1e-5;  ///< tight, so the fixed point is what is read

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

struct Run {
    double lee_mps = NAN, crest_mps = NAN, dt_s = 0, seconds = 0;
    int iterations = 0;
    bool converged = false;
};

/// One momentum solve; step: the semi-Lagrangian cfl or the Eulerian eulerianCfl.
Run solve(const sim::Heightfield& hf, double leeX_m, sim::PseudoTimeAdvection advection,
          double step, int maxIterations, bool incremental = false) {
    const sim::DomainSpec spec = ridgebox::spec(CELL_M, TOP_M, true);
    const sim::AmbientWind wind = ridgebox::logLaw(SPEED_MPS, REFERENCE_HEIGHT_M, Z0_M);
    const auto t0 = Clock::now();
    const sim::AirDomain domain(hf, spec);
    sim::MomentumSettings ms;
    ms.advection = advection;
    (advection == sim::PseudoTimeAdvection::Eulerian ? ms.eulerianCfl : ms.cfl) = step;
    ms.maxIterations = maxIterations;
    ms.residualTolerance = RESIDUAL_TOLERANCE;
    ms.averageCycles = true;  // a wake that cycles: the mean of whole periods
    ms.incrementalPressure = incremental;
    const sim::MomentumWindResult res = sim::solveMomentumWind(domain, wind, ms);
    Run r;
    r.seconds = secondsSince(t0);
    r.iterations = res.report.iterations;
    r.converged = res.report.converged;
    r.dt_s = res.report.dt_s;
    const double y = hf.sizeY_m() / 2;
    r.lee_mps = res.field.velocityAt_mps(leeX_m, y, hf.sample(leeX_m, y) + PROBE_HEIGHT_M)[0];
    r.crest_mps =
        res.field.velocityAt_mps(CREST_X_M, y, hf.sample(CREST_X_M, y) + PROBE_HEIGHT_M)[0];
    return r;
}

/// Both steps on one ridge (at most maxIterations steps per level), and the Eulerian step
/// with the incremental pressure (Goda 1979) at the smallest and largest of its steps; returns
/// false when a solve did not converge.
bool study(const char* name, double H_m, double sigma_m, double leeFromCrest_m,
           const std::vector<double>& cfls, const std::vector<double>& eulerianCfls,
           int maxIterations) {
    const sim::Heightfield hf = terrain(H_m, sigma_m);
    std::printf(
        "\n%s: H = %.0f m, sigma = %.0f m (slope %.2f); u (m/s) %.0f m above the ground "
        "%.0f m behind the crest and above the crest; at most %d steps per level\n",
        name, H_m, sigma_m, 0.607 * H_m / sigma_m, PROBE_HEIGHT_M, leeFromCrest_m, maxIterations);
    std::printf("%-28s %6s %9s %9s %9s %7s %5s %9s\n", "step", "cfl", "dt (s)", "lee", "crest",
                "iters", "conv", "seconds");
    bool ok = true;
    auto row = [&](sim::PseudoTimeAdvection a, double step, bool incremental, double& lo,
                   double& hi) {
        const Run r = solve(hf, CREST_X_M + leeFromCrest_m, a, step, maxIterations, incremental);
        ok = ok && r.converged;
        lo = std::min(lo, r.lee_mps), hi = std::max(hi, r.lee_mps);
        const std::string label =
            std::string(sim::pseudoTimeAdvectionName(a)) + (incremental ? ", incr. pressure" : "");
        std::printf("%-28s %6.3f %9.4f %9.4f %9.4f %7d %5s %9.1f\n", label.c_str(), step, r.dt_s,
                    r.lee_mps, r.crest_mps, r.iterations, r.converged ? "yes" : "NO", r.seconds);
        std::fflush(stdout);
    };
    double slLo = INFINITY, slHi = -INFINITY, euLo = INFINITY, euHi = -INFINITY;
    double noLo = INFINITY, noHi = -INFINITY;
    for (double c : cfls) row(sim::PseudoTimeAdvection::SemiLagrangian, c, false, slLo, slHi);
    for (double c : eulerianCfls) row(sim::PseudoTimeAdvection::Eulerian, c, false, euLo, euHi);
    for (double c : {eulerianCfls.front(), eulerianCfls.back()})
        row(sim::PseudoTimeAdvection::Eulerian, c, true, noLo, noHi);
    std::printf(
        "lee spread over the steps: semi-Lagrangian %.4f m/s, Eulerian %.4f m/s "
        "(with the incremental pressure %.4f m/s)\n",
        slHi - slLo, euHi - euLo, noHi - noLo);
    return ok;
}

}  // namespace

int runPseudoTimeStudy() {
    std::printf(
        "The momentum model's steady state against its pseudo-time step (docs/validation.md,"
        " \"Pseudo-time step and its error\"): %.0f m cells, 3 across with free-slip side "
        "walls, %.0f m long, top %.0f m, log inflow z0 = %.2f m, %.0f m/s at %.0f m, "
        "residual tolerance %.0e. cfl: semi-Lagrangian U_max dt / h; Eulerian dt "
        "(|u| / h + |v| / h + |w| / dz)_max, stable up to %.1f\n",
        CELL_M, LENGTH_M, TOP_M, Z0_M, SPEED_MPS, REFERENCE_HEIGHT_M, RESIDUAL_TOLERANCE,
        sim::EULERIAN_MAX_CFL);
    bool ok = study("Gentle ridge", 8.0, 50.0, 100.0, {0.25, 0.5, 1.0, 2.0, 4.0},
                    {0.1, 0.2, 0.3, 0.4, 0.5}, 3000);
    ok = study("Steep ridge", 40.0, 40.0, 200.0, {1.0, 2.0, 4.0, 8.0}, {0.2, 0.4}, 1500) && ok;
    return ok ? EXIT_OK : EXIT_UNMET;
}

}  // namespace gale::app
