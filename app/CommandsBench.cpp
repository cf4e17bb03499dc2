/// \file CommandsBench.cpp
/// `gale bench VERB`: the command lines of the benchmarks in app/bench. A benchmark returns
/// EXIT_UNMET when a full run misses its stated target; a bad option (std::invalid_argument from
/// the benchmark) is bad input, exit 2.

#include <array>
#include <cstdio>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/Cli.h"
#include "app/bench/BenchCoupling.h"
#include "app/bench/BenchMemory.h"
#include "app/bench/BenchRender.h"
#include "app/bench/BenchRough.h"
#include "app/bench/BenchSolve.h"
#include "app/bench/BenchUnsteady.h"
#include "app/io/Errors.h"
#include "app/scene/SceneParser.h"

namespace gale::app {
namespace {

/// Runs a benchmark, turning its "bad options" into bad input.
int runBench(const std::function<int()>& bench) {
    try {
        return bench();
    } catch (const std::invalid_argument& e) {
        throw InputError(e.what());
    }
}

/// "64x64x32" to {64, 64, 32}; throws InputError naming --size.
std::array<int, 3> parseBoxSize(const std::string& text) {
    std::array<int, 3> n{};
    char x1 = 0, x2 = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c%d", &n[0], &x1, &n[1], &x2, &n[2]) != 5 || x1 != 'x' ||
        x2 != 'x' || n[0] < 2 || n[1] < 2 || n[2] < 2 || n[0] > 4096 || n[1] > 4096 || n[2] > 4096)
        throw InputError("--size: expected NXxNYxNZ with 2..4096 cells per side (got '" + text +
                         "')");
    return n;
}

void addRender(CLI::App& bench, VerbTable& verbs) {
    auto o = std::make_shared<BenchRenderOptions>();
    CLI::App* verb = bench.add_subcommand("render",
                                          "Time the shell renderer (the paper's Table 2) "
                                          "against a trivial fill of the same geometry");
    verb->add_option("--frames", o->frames, "Timed frames per row and pass")
        ->capture_default_str()
        ->check(CLI::Range(1, MAX_FRAMES));
    verb->add_flag("--quick", o->quick,
                   "2 frames and 1 warm-up per row: a smoke run, not a measurement (targets "
                   "printed, not judged)");
    verb->add_option("--json", o->jsonPath, "Also write the results as JSON here");
    verb->footer(EXIT_CODES_FOOTER);
    verbs.add(verb, [o] { return runBench([o] { return runBenchRender(*o); }); });
}

void addAccuracy(CLI::App& bench, VerbTable& verbs) {
    auto o = std::make_shared<BenchAccuracyOptions>();
    CLI::App* verb = bench.add_subcommand(
        "accuracy",
        "Error against run time of the steady solver on the exact hemisphere (potential flow "
        "past a sphere): CSV, SVG plot and convergence order");
    verb->add_option("--out", o->outputFolder, "Folder for accuracy.csv and accuracy.svg")
        ->capture_default_str();
    verb->add_flag("--quick", o->quick,
                   "4, 8, 16 cells per radius at one tolerance (a CI smoke run)");
    verb->add_option("--json", o->jsonPath, "Also write the table as JSON");
    verb->footer(EXIT_CODES_FOOTER);
    verbs.add(verb, [o] { return runBench([o] { return runBenchAccuracy(*o); }); });
}

void addSolve(CLI::App& bench, VerbTable& verbs) {
    auto o = std::make_shared<BenchSolveOptions>();
    auto sizes = std::make_shared<std::vector<std::string>>();
    auto noOpenVdb = std::make_shared<bool>(false);
    CLI::App* verb = bench.add_subcommand(
        "solve",
        "Our MGPCG against OpenVDB's PCG on the same elliptic problem, with memory and "
        "the bandwidth floor");
    verb->add_option("--size", *sizes,
                     "Box NXxNYxNZ (repeatable; default 64x64x32 128x128x64 256x256x64)");
    verb->add_flag("--quick", o->quick, "Only the first size (a CI smoke run)");
    verb->add_flag("--no-openvdb", *noOpenVdb, "Skip OpenVDB's solver (ours only)");
    verb->add_option("--tolerance", o->relativeTolerance,
                     "Max-norm relative residual for both solvers")
        ->capture_default_str()
        ->check(CLI::Range(1e-14, 0.5));
    verb->add_option("--json", o->jsonPath, "Also write the table as JSON");
    verb->footer(EXIT_CODES_FOOTER);
    verbs.add(verb, [o, sizes, noOpenVdb] {
        o->openVdb = !*noOpenVdb;
        for (const std::string& text : *sizes) o->sizes.push_back(parseBoxSize(text));
        return runBench([o] { return runBenchSolve(*o); });
    });
}

void addCoupling(CLI::App& bench, VerbTable& verbs) {
    auto o = std::make_shared<BenchCouplingOptions>();
    CLI::App* verb = bench.add_subcommand(
        "coupling",
        "Grouped against exact bends as the group count grows, and the coupling's "
        "cost per field step and per frame at 100k and 1M vertices");
    verb->add_option("--out", o->outputFolder, "Folder for coupling.csv and coupling.svg")
        ->capture_default_str();
    verb->add_flag("--quick", o->quick, "10k and 100k vertices (a CI smoke run)");
    verb->add_option("--json", o->jsonPath, "Also write the tables as JSON");
    verb->footer(EXIT_CODES_FOOTER);
    verbs.add(verb, [o] { return runBench([o] { return runBenchCoupling(*o); }); });
}

void addRough(CLI::App& bench, VerbTable& verbs) {
    auto o = std::make_shared<BenchRoughOptions>();
    CLI::App* verb = bench.add_subcommand(
        "rough",
        "Steady-solve iterations on a fractal and a sharp-feature terrain at 20, 10 and 5 m "
        "cells (target: <= 20 at every resolution)");
    verb->add_flag("--quick", o->quick, "A 320 m square instead of 1280 m (a CI smoke run)");
    verb->add_option("--json", o->jsonPath, "Also write the table as JSON");
    verb->footer(EXIT_CODES_FOOTER);
    verbs.add(verb, [o] { return runBench([o] { return runBenchRough(*o); }); });
}

void addStability(CLI::App& bench, VerbTable& verbs) {
    auto o = std::make_shared<BenchStabilityOptions>();
    CLI::App* verb = bench.add_subcommand(
        "stability",
        "The unsteady wind's stability suite: CFL 5/20/50 over a ridge, 0 and 100 m/s, "
        "cliff, spike, sub-cell vortex, nu dt/h^2 = 1000, gusts (energy budgets, "
        "deviation from the steady start); the translating Lamb-Oseen vortex's orders "
        "and Burgers' vortex against their exact solutions");
    verb->add_flag("--quick", o->quick, "Only the fast subset (what sim_tests runs)");
    verb->add_option("--json", o->jsonPath, "Also write the table as JSON");
    verb->footer(EXIT_CODES_FOOTER);
    verbs.add(verb, [o] { return runBench([o] { return runBenchStability(*o); }); });
}

void addUnsteady(CLI::App& bench, VerbTable& verbs) {
    auto o = std::make_shared<BenchUnsteadyOptions>();
    CLI::App* verb = bench.add_subcommand(
        "unsteady",
        "Error against run time of the unsteady solver on the exact viscous "
        "Lamb-Oseen vortex (CSV, SVG, orders) per advection scheme, and the time per "
        "step and its parts");
    verb->add_option("--out", o->outputFolder,
                     "Folder for unsteady_accuracy.csv and unsteady_accuracy.svg")
        ->capture_default_str();
    verb->add_flag("--quick", o->quick,
                   "2 and 4 cells per core, a 48x48x16 timing box (a CI smoke run)");
    verb->add_option("--json", o->jsonPath, "Also write the tables as JSON");
    verb->footer(EXIT_CODES_FOOTER);
    verbs.add(verb, [o] { return runBench([o] { return runBenchUnsteady(*o); }); });
}

void addMemory(CLI::App& bench, VerbTable& verbs) {
    auto o = std::make_shared<BenchMemoryOptions>();
    CLI::App* verb = bench.add_subcommand(
        "memory",
        "The memory estimate against the measured peak resident memory of child solve and "
        "render runs, from thin tall boxes to wide flat ones (target: within 1.3x)");
    verb->add_flag("--quick", o->quick, "4 small shapes (the CI check of the bound)");
    verb->add_option("--json", o->jsonPath, "Also write the table as JSON");
    verb->footer(EXIT_CODES_FOOTER);
    verbs.add(verb, [o] { return runBench([o] { return runBenchMemory(*o); }); });
}

}  // namespace

void addBenchVerbs(CLI::App& app, VerbTable& verbs) {
    CLI::App* bench = app.add_subcommand("bench", "Benchmarks");
    bench->require_subcommand(1);
    bench->footer(EXIT_CODES_FOOTER);
    addRender(*bench, verbs);
    addAccuracy(*bench, verbs);
    addSolve(*bench, verbs);
    addCoupling(*bench, verbs);
    addRough(*bench, verbs);
    addStability(*bench, verbs);
    addUnsteady(*bench, verbs);
    addMemory(*bench, verbs);
}

}  // namespace gale::app
