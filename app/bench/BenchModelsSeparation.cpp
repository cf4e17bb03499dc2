/// \file BenchModelsSeparation.cpp
/// `gale bench models --separation`: the separation benchmarks as a table of error against run
/// time (docs/validation.md, section 4): the ERCOFTAC periodic hill (validation/
/// PeriodicHillStudy.h) solved by every closure (the mixing length and the two-equation
/// closure) with both pseudo-time steps at two resolutions. A closure that is not built yet (the
/// solver throws std::logic_error for it) gets a "not built" row, so the table fills itself once
/// it lands. This file prints the tables.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/bench/BenchModels.h"
#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "sim/MomentumTurbulence.h"
#include "sim/SurfaceLayer.h"
#include "validation/AcceptanceLimits.h"
#include "validation/PeriodicHill.h"
#include "validation/PeriodicHillStudy.h"

namespace gale::app {
namespace {

namespace L = validation::limits;

/// A number, or an empty column for NaN.
std::string fixed(double v, int digits) {
    if (!std::isfinite(v)) return "-";
    char b[32];
    std::snprintf(b, sizeof b, "%.*f", digits, v);
    return b;
}

/// --quick: pseudo-steps per level at most (a smoke run of the table, not its figures).
constexpr int QUICK_MAX_ITERATIONS = 300;

struct Run {
    sim::TurbulenceClosure closure{};
    sim::PseudoTimeAdvection advection{};
    int cellsPerH = 0;
    bool built = false;
    std::string whyNot;
    validation::PeriodicHillStudy s;
};

}  // namespace

int runSeparationStudy(const BenchModelsOptions& opt) {
    namespace ph = validation::periodichill;
    const validation::PeriodicHillData ref = validation::periodicHillReference();
    validation::PeriodicHillOptions base;
    std::printf(
        "The ERCOFTAC periodic hill (UFR 3-30; docs/validation.md, section 4): Re_h = %.0f, "
        "%d hills in a row, the period from x = %.0f h to %.0f h compared with the DNS of Xiao et "
        "al. (2020); smooth walls as z0 = %.3g h (log law B = %.1f, u_tau from Dean's law); h = "
        "%.0f m, Ub = %.0f m/s; the along-wall line %.1f cells above the floor; at most %d "
        "pseudo-steps per level.\n",
        ph::REYNOLDS_H, base.hills, base.measuredHill * ph::PERIOD_OVER_H,
        (base.measuredHill + 1) * ph::PERIOD_OVER_H, ph::smoothWallZ0_h(sim::surface::KAPPA),
        ph::SMOOTH_WALL_B, base.h_m, base.bulkSpeed_mps, validation::WALL_SAMPLE_CELLS,
        opt.quick ? QUICK_MAX_ITERATIONS : base.maxIterations);
    std::printf(
        "reference: separation %.2f h, reattachment %.2f h; target: reattachment within "
        "%.0f %%\n\n",
        ref.separation_h, ref.reattachment_h, 100 * L::TARGET_PERIODIC_HILL_REATTACHMENT_ERROR);

    const std::vector<int> resolutions = opt.quick ? std::vector<int>{5} : std::vector<int>{5, 10};
    const std::vector<sim::PseudoTimeAdvection> steps = {sim::PseudoTimeAdvection::SemiLagrangian,
                                                         sim::PseudoTimeAdvection::Eulerian};
    std::vector<Run> runs;
    for (sim::TurbulenceClosure c :
         {sim::TurbulenceClosure::MixingLength, sim::TurbulenceClosure::KEpsilon,
          sim::TurbulenceClosure::KOmegaSst})
        for (sim::PseudoTimeAdvection a : steps)
            for (int n : resolutions) {
                Run r;
                r.closure = c, r.advection = a, r.cellsPerH = n;
                validation::PeriodicHillOptions o = base;
                o.cellsPerH = n, o.closure = c, o.advection = a;
                o.maxIterations = opt.quick ? QUICK_MAX_ITERATIONS : base.maxIterations;
                try {
                    r.s = validation::runPeriodicHill(o, ref);
                    r.built = true;
                } catch (const std::logic_error& e) {
                    // The closure refuses to run until it is built (sim/MomentumTurbulence.h).
                    r.whyNot = e.what();
                }
                std::fprintf(stderr, "bench models --separation: %s, %s, h/%d: %s\n",
                             sim::turbulenceClosureName(c), sim::pseudoTimeAdvectionName(a), n,
                             r.built ? (std::to_string(r.s.iterations) + " steps, " +
                                        fixed(r.s.seconds, 1) + " s")
                                           .c_str()
                                     : "not built");
                runs.push_back(std::move(r));
            }

    std::printf("%-14s %-16s %5s %10s %6s %5s %8s %6s %6s %7s %7s %7s %7s %6s\n", "closure", "step",
                "res.", "cells", "iters", "conv", "seconds", "sep", "reatt", "error", "RMS u",
                "RMS k", "repeat", "bulk");
    bool ok = true;
    nlohmann::json jrows = nlohmann::json::array();
    for (const Run& r : runs) {
        const std::string res = "h/" + std::to_string(r.cellsPerH);
        if (!r.built) {
            std::printf("%-14s %-16s %5s  not built (%s)\n", sim::turbulenceClosureName(r.closure),
                        sim::pseudoTimeAdvectionName(r.advection), res.c_str(), r.whyNot.c_str());
            jrows.push_back({{"closure", sim::turbulenceClosureName(r.closure)},
                             {"advection", sim::pseudoTimeAdvectionName(r.advection)},
                             {"resolution", res},
                             {"built", false},
                             {"why_not", r.whyNot}});
            continue;
        }
        const validation::PeriodicHillStudy& s = r.s;
        const bool met = s.converged && std::isfinite(s.reattachmentRelativeError) &&
                         s.reattachmentRelativeError <= L::TARGET_PERIODIC_HILL_REATTACHMENT_ERROR;
        ok = ok && met;
        char cells[48];
        std::snprintf(cells, sizeof cells, "%dx%dx%d", s.nx, s.ny, s.nz);
        std::printf("%-14s %-16s %5s %10s %6d %5s %8.1f %6s %6s %6s%% %7.3f %7s %7.3f %6.3f\n",
                    sim::turbulenceClosureName(r.closure),
                    sim::pseudoTimeAdvectionName(r.advection), res.c_str(), cells, s.iterations,
                    s.converged ? "yes" : "NO", s.seconds, fixed(s.bubble.separation_h, 2).c_str(),
                    fixed(s.bubble.reattachment_h, 2).c_str(),
                    fixed(100 * s.reattachmentRelativeError, 0).c_str(), s.rmsU,
                    fixed(s.rmsK, 4).c_str(), s.repeatRmsU, s.bulkOverUb);
        auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
        jrows.push_back({{"closure", sim::turbulenceClosureName(r.closure)},
                         {"advection", sim::pseudoTimeAdvectionName(r.advection)},
                         {"resolution", res},
                         {"built", true},
                         {"cells", {s.nx, s.ny, s.nz}},
                         {"iterations", s.iterations},
                         {"converged", s.converged},
                         {"seconds", s.seconds},
                         {"separation_h", num(s.bubble.separation_h)},
                         {"reattachment_h", num(s.bubble.reattachment_h)},
                         {"previous_reattachment_h", num(s.previousBubble.reattachment_h)},
                         {"reattachment_error", num(s.reattachmentRelativeError)},
                         {"rms_u", s.rmsU},
                         {"rms_k", num(s.rmsK)},
                         {"repeat_rms_u", s.repeatRmsU},
                         {"bulk_over_Ub", s.bulkOverUb},
                         {"meets_target", met}});
    }
    std::printf(
        "sep, reatt: x / h from the crest on the measured period; error: |reatt / %.2f - 1|; RMS "
        "u: model minus DNS u / Ub over the %zu profile points; RMS k: k / Ub^2 (the closure's "
        "k, nearest cell); repeat: RMS of u / Ub, measured period minus the one before; bulk: "
        "flux through the measured crest gap / (Ub gap)\n",
        ref.reattachment_h, ref.profiles.size());

    // Per station, every run that was built.
    std::printf("\nRMS of u / Ub per station (x / h), and the previous period's bubble\n");
    std::printf("%-14s %-16s %5s", "closure", "step", "res.");
    for (double x : ref.stations()) std::printf(" %6.1f", x);
    std::printf("   previous sep / reatt\n");
    for (const Run& r : runs) {
        if (!r.built) continue;
        std::printf("%-14s %-16s %5s", sim::turbulenceClosureName(r.closure),
                    sim::pseudoTimeAdvectionName(r.advection),
                    ("h/" + std::to_string(r.cellsPerH)).c_str());
        for (const validation::PeriodicHillStudy::Station& st : r.s.stations)
            std::printf(" %6.3f", st.rmsU);
        std::printf("   %s / %s\n", fixed(r.s.previousBubble.separation_h, 2).c_str(),
                    fixed(r.s.previousBubble.reattachment_h, 2).c_str());
    }
    std::printf("\nRMS of k / Ub^2 per station (x / h); the DNS's peak k / Ub^2 below each\n");
    std::printf("%-14s %-16s %5s", "closure", "step", "res.");
    for (double x : ref.stations()) std::printf(" %6.1f", x);
    std::printf("\n%-38s", "DNS peak");
    for (double x : ref.stations()) {
        double peak = 0;
        for (const validation::HillProfilePoint& p : ref.profiles)
            if (std::abs(p.x_h - x) < 1e-9) peak = std::max(peak, p.k_Ub2);
        std::printf(" %6.3f", peak);
    }
    std::printf("\n");
    for (const Run& r : runs) {
        if (!r.built) continue;
        std::printf("%-14s %-16s %5s", sim::turbulenceClosureName(r.closure),
                    sim::pseudoTimeAdvectionName(r.advection),
                    ("h/" + std::to_string(r.cellsPerH)).c_str());
        for (const validation::PeriodicHillStudy::Station& st : r.s.stations)
            std::printf(" %6s", fixed(st.rmsK, 3).c_str());
        std::printf("\n");
    }
    // What the bubble looks like: the along-wall velocity every half hill height, the DNS's
    // wall row interpolated linearly to the same places.
    auto lineAt = [](const std::vector<validation::WallSample>& line, double x) {
        for (size_t i = 1; i < line.size(); ++i)
            if (line[i].x_h >= x) {
                const validation::WallSample &a = line[i - 1], &b = line[i];
                return a.u_Ub + (b.u_Ub - a.u_Ub) * (x - a.x_h) / (b.x_h - a.x_h);
            }
        return double(NAN);
    };
    std::printf(
        "\nAlong-wall u / Ub on the measured floor (the model %.1f cells up; the DNS 0.001 h "
        "up)\n%-39s",
        validation::WALL_SAMPLE_CELLS, "x / h");
    for (int i = 1; i <= 17; ++i) std::printf(" %6.1f", 0.5 * i);
    std::printf("\n%-39s", "DNS (Xiao et al. 2020)");
    for (int i = 1; i <= 17; ++i) std::printf(" %6s", fixed(lineAt(ref.wall, 0.5 * i), 3).c_str());
    std::printf("\n");
    for (const Run& r : runs) {
        if (!r.built) continue;
        const std::string label = std::string(sim::turbulenceClosureName(r.closure)) + ", " +
                                  sim::pseudoTimeAdvectionName(r.advection) + ", h/" +
                                  std::to_string(r.cellsPerH);
        std::printf("%-39s", label.c_str());
        for (int i = 1; i <= 17; ++i)
            std::printf(" %6s", fixed(lineAt(r.s.wall, 0.5 * i), 3).c_str());
        std::printf("\n");
    }
    if (!opt.jsonPath.empty())
        writeTextAtomic(opt.jsonPath, nlohmann::json{{"periodic_hill", jrows},
                                                     {"reference",
                                                      {{"separation_h", ref.separation_h},
                                                       {"reattachment_h", ref.reattachment_h}}},
                                                     {"all_met", ok}}
                                              .dump(2) +
                                          "\n");
    return ok ? EXIT_OK : EXIT_UNMET;
}

}  // namespace gale::app
