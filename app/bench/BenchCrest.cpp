/// \file BenchCrest.cpp
/// `gale bench models --crest`: which part of the momentum model loses the speed-up over the
/// crest of the Cao and Tamura (2006) ridge (docs/validation.md, section 3, "The crest
/// experiments"). Each case changes one thing of the set-up: the model (potential flow, Euler,
/// the eddy viscosity, the wall stress), the inflow (uniform, the published log law or the
/// earlier fit to the measured foot) or the top height. The solve and its figures are
/// validation/CrestStudy.h's; this file prints the tables and re-fits the sensitivity's inflow.
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "app/bench/BenchModels.h"
#include "app/io/Errors.h"
#include "validation/CrestStudy.h"

namespace gale::app {
namespace {

namespace ridge = validation::ridge;
using validation::CrestCase;
using validation::FOOT_DZ_OVER_H;
using validation::FOOT_U_OVER_UINF;

/// values joined as "a / b / c", each with printf format fmt.
std::string joined(const double (&values)[3], const char* fmt) {
    std::string out;
    char buf[32];
    for (double v : values) {
        if (!out.empty()) out += " / ";
        std::snprintf(buf, sizeof buf, fmt, v);
        out += buf;
    }
    return out;
}

/// Inflow re-fits of the foot experiment (each one solve of the model).
constexpr int FOOT_FITS = 5;

}  // namespace

int runCrestStudy(int cellsPerH) {
    using ridge::Inflow;
    constexpr double TOP = ridge::TOP_OVER_H;
    const std::vector<CrestCase> cases = {
        {"potential, OPEN sides", false, Inflow::Uniform, false, false, TOP, false},
        {"momentum model, OPEN sides", true, Inflow::Published, true, true, TOP, false},
        {"potential flow", false, Inflow::Uniform, false, false, TOP},
        {"potential flow", false, Inflow::Uniform, false, false, 2 * TOP},
        {"mass-consistent", false, Inflow::Published, false, false, TOP},
        {"Euler", true, Inflow::Uniform, false, false, TOP},
        {"Euler", true, Inflow::Uniform, false, false, 2 * TOP},
        {"Euler", true, Inflow::Published, false, false, TOP},
        {"eddy viscosity, free slip", true, Inflow::Published, true, false, TOP},
        {"eddy viscosity and wall", true, Inflow::Published, true, true, TOP},
        {"eddy viscosity and wall", true, Inflow::Published, true, true, 2 * TOP},
        {"eddy viscosity and wall", true, Inflow::FootFit, true, true, TOP},
    };
    std::printf(
        "Crest of the Cao and Tamura ridge, H/h = %d: u/U_inf at the crest and speed-up "
        "against the windward foot (x = -2.5 H) at the same height above the ground\n",
        cellsPerH);
    std::printf("%-27s %-18s %4s %6s %5s %8s   %-23s   %-23s  %s\n", "case", "inflow", "top",
                "steps", "conv", "seconds", "u/U_inf 0.25/0.48/0.98H", "speed-up 0.25/0.48/0.98H",
                "nu_t / (kappa u* z) 0.25/0.48/0.98H");
    bool ok = true;
    for (const CrestCase& c : cases) {
        const validation::CrestStudy r = validation::runCrest({c, cellsPerH, std::nullopt});
        // The open-sided rows are diagnostics of a wrong set-up: their wake need not settle.
        if (c.closedSides) ok = ok && r.converged;
        const bool closure = c.momentum && c.eddyViscosity;
        std::printf("%-27s %-18s %3.0fH %6d %5s %8.2f   %-23s   %-24s  %s\n", c.name.c_str(),
                    ridge::inflowName(c.inflow), c.topOverH, r.steps, r.converged ? "yes" : "NO",
                    r.seconds, joined(r.crestUinf, "%.3f").c_str(),
                    joined(r.crestSpeedup, "%.3f").c_str(),
                    closure ? joined(r.nuRatio, "%.2f").c_str() : "");
        std::fflush(stdout);
    }
    // A sensitivity, not the validation result: the inflow's log profile re-fitted so that the
    // model's own windward foot matches the measured foot profile below H. Each fit divides the
    // measured foot speeds by the last run's foot / inflow ratio at the same heights and fits
    // u = a ln z + b to them by least squares (a = u* / kappa, z0 = exp(-b / a)); U_inf stays
    // the published set-up's, so u / U_inf is comparable with the measurement. Fit 0 is the
    // published inflow.
    std::printf(
        "\nSensitivity (not the validation set-up): the model (eddy viscosity and wall, 6 H) with "
        "its log inflow re-fitted so that its windward foot matches the measured foot below H\n");
    std::printf("%-5s %9s %8s %6s %5s %8s   %-23s   %-23s\n", "fit", "U(H) m/s", "z0 m", "steps",
                "conv", "foot RMS", "u/U_inf 0.25/0.48/0.98H", "speed-up 0.25/0.48/0.98H");
    const CrestCase model{"eddy viscosity and wall", true, Inflow::Published, true, true, TOP};
    const double uInf = ridge::freeStream_mps(Inflow::Published);
    sim::AmbientWind inflow = ridge::wind(Inflow::Published);
    for (int fit = 0; fit <= FOOT_FITS; ++fit) {
        const validation::CrestStudy r = validation::runCrest({model, cellsPerH, inflow});
        ok = ok && r.converged;
        auto inflowAt = [&](double z_m) {
            return inflow.speed_mps * std::log(z_m / inflow.roughness_m) /
                   std::log(inflow.referenceHeight_m / inflow.roughness_m);
        };
        double sumSq = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
        for (int i = 0; i < 5; ++i) {
            const double z = FOOT_DZ_OVER_H[i] * ridge::H_M, foot = r.footU_mps[i];
            sumSq += std::pow(foot / uInf - FOOT_U_OVER_UINF[i], 2);
            const double target = FOOT_U_OVER_UINF[i] * uInf * inflowAt(z) / foot;
            sx += std::log(z), sy += target, sxx += std::log(z) * std::log(z);
            sxy += std::log(z) * target;
        }
        std::printf("%-5d %9.2f %8.4f %6d %5s %8.3f   %-23s   %-23s\n", fit,
                    inflow.speedAt_mps(ridge::H_M), inflow.roughness_m, r.steps,
                    r.converged ? "yes" : "NO", std::sqrt(sumSq / 5),
                    joined(r.crestUinf, "%.3f").c_str(), joined(r.crestSpeedup, "%.3f").c_str());
        std::fflush(stdout);
        const double a = (5 * sxy - sx * sy) / (5 * sxx - sx * sx), b = (sy - a * sx) / 5;
        if (!(a > 0) || !std::isfinite(b)) break;  // no log profile fits: stop re-fitting
        inflow.roughness_m = std::exp(-b / a);
        inflow.speed_mps = a * std::log(inflow.referenceHeight_m / inflow.roughness_m);
    }
    std::printf(
        "measured (Cao and Tamura 2006): u/U_inf 0.884 / 0.885 / 0.889, "
        "speed-up 1.33 / 0.99 / 0.59\n");
    return ok ? EXIT_OK : EXIT_UNMET;
}

}  // namespace gale::app
