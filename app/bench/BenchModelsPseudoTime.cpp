/// \file BenchModelsPseudoTime.cpp
/// `gale bench models --pseudo-time`: does the momentum model's steady state depend on its
/// pseudo-time step? (docs/validation.md, "Pseudo-time step and its error"). Two Gaussian ridges
/// across the wind in a 2-D box (validation/PseudoTimeStudy.h, one solve each), each solved with
/// the semi-Lagrangian step at several cfl and with the Eulerian step (sim/MomentumAdvection.h)
/// at several steps below its stability limit; the speed 10 m above the lee's ground is the
/// measure. This file prints the tables.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/bench/BenchModels.h"
#include "app/io/Errors.h"
#include "sim/MomentumAdvection.h"
#include "validation/PseudoTimeStudy.h"

namespace gale::app {
namespace {

using namespace validation::pseudotime;

using Run = validation::PseudoTimeStudy;

/// One momentum solve; step: the semi-Lagrangian cfl or the Eulerian eulerianCfl.
Run solve(const Ridge& ridge, sim::PseudoTimeAdvection advection, double step,
          bool incremental = false) {
    validation::PseudoTimeOptions o;
    o.ridge = ridge, o.advection = advection, o.step = step, o.incrementalPressure = incremental;
    return validation::runPseudoTime(o);
}

/// Both steps on one ridge (at most maxIterations steps per level), and the Eulerian step
/// with the incremental pressure (Goda 1979) at the smallest and largest of its steps; returns
/// false when a solve did not converge.
bool study(const Ridge& ridge, const std::vector<double>& cfls,
           const std::vector<double>& eulerianCfls) {
    const char* name = ridge.name;
    const double H_m = ridge.H_m, sigma_m = ridge.sigma_m, leeFromCrest_m = ridge.leeFromCrest_m;
    const int maxIterations = ridge.maxIterations;
    std::printf(
        "\n%s: H = %.0f m, sigma = %.0f m (slope %.2f); u (m/s) %.0f m above the ground "
        "%.0f m behind the crest and above the crest; at most %d steps per level\n",
        name, H_m, sigma_m, 0.607 * H_m / sigma_m, PROBE_HEIGHT_M, leeFromCrest_m, maxIterations);
    std::printf("%-28s %6s %9s %9s %9s %7s %5s %9s\n", "step", "cfl", "dt (s)", "lee", "crest",
                "iters", "conv", "seconds");
    bool ok = true;
    auto row = [&](sim::PseudoTimeAdvection a, double step, bool incremental, double& lo,
                   double& hi) {
        const Run r = solve(ridge, a, step, incremental);
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
    bool ok = study(GENTLE, {0.25, 0.5, 1.0, 2.0, 4.0}, {0.1, 0.2, 0.3, 0.4, 0.5});
    ok = study(STEEP, {1.0, 2.0, 4.0, 8.0}, {0.2, 0.4}) && ok;
    return ok ? EXIT_OK : EXIT_UNMET;
}

}  // namespace gale::app
