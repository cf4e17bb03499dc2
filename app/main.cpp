/// \file main.cpp
/// The gale program: verbs over the scene format (docs/cli.md). The only place that catches
/// exceptions: bad input exits 2, internal failures exit 1, each with one line on stderr.

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>

#include "app/BenchRender.h"
#include "app/BenchCoupling.h"
#include "app/BenchUnsteady.h"
#include "app/BenchSolve.h"
#include "app/Commands.h"
#include "app/Errors.h"
#include "app/SceneParser.h"
#include "app/Version.h"

namespace {

using namespace gale::app;

int reportError(const std::string& message, int code) {
    std::string line = message;
    std::replace(line.begin(), line.end(), '\n', ' ');
    std::fflush(stdout);
    std::fprintf(stderr, "gale: error: %s\n", line.c_str());
    return code;
}

/// A path option given as "": refused, since an empty path would silently mean "the default".
const CLI::Validator NOT_EMPTY(
    [](std::string& s) { return s.empty() ? std::string("must not be empty") : std::string(); },
    "NOT EMPTY", "not empty");

/// GALE_THREADS=N caps the worker threads of TBB (solver, field sampling), e.g. to show that
/// results do not depend on the thread count (docs/reliability.md); unset: all cores.
std::unique_ptr<tbb::global_control> threadLimitFromEnvironment() {
    const char* text = std::getenv("GALE_THREADS");
    if (!text) return nullptr;
    char* end = nullptr;
    const long n = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || n < 1 || n > 4096)
        throw InputError(std::string("GALE_THREADS: must be an integer in 1..4096 (got '") + text +
                         "')");
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                 static_cast<size_t>(n));
}

void addSceneOptions(CLI::App* verb, SceneRunOptions& o) {
    verb->add_option("scene", o.scenePath, "Scene file (TOML; see docs/scene-format.md)")
        ->required();
    verb->add_option("-o,--output", o.folder,
                     "Output folder, relative to the current directory (default: the scene's "
                     "output.folder)")
        ->check(NOT_EMPTY);
    verb->add_option("--frames", o.frames, "Number of frames (overrides output.frames)")
        ->check(CLI::Range(1, MAX_FRAMES));
    verb->add_option("--width", o.width, "Image width in pixels (overrides output.width)")
        ->check(CLI::Range(1, MAX_IMAGE_SIDE_PX));
    verb->add_option("--height", o.height, "Image height in pixels (overrides output.height)")
        ->check(CLI::Range(1, MAX_IMAGE_SIDE_PX));
}

const char* EXIT_CODES_FOOTER =
    "\nExit codes: 0 ok, 1 internal or runtime failure (e.g. no GL context), 2 bad input (scene, "
    "image, arguments, output folder).";

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "gale: wind over terrain, rendered as real-time shell grass (Bakay, Lalonde, "
        "Heidrich 2002).",
        "gale"};
    app.set_version_flag("--version", std::string("gale ") + GALE_VERSION);
    app.footer(
        std::string("\nRun 'gale VERB --help' for a verb's options; docs/cli.md has them all.") +
        EXIT_CODES_FOOTER);
    app.require_subcommand(1);

    SceneRunOptions checkOptions;
    CLI::App* check = app.add_subcommand(
        "check", "Validate a scene and print what a render would build and what it leaves out");
    addSceneOptions(check, checkOptions);
    check->footer(EXIT_CODES_FOOTER);

    SceneRunOptions renderOptions;
    CLI::App* render = app.add_subcommand(
        "render", "Render a scene headless to PNG frames, with a JSON run report");
    addSceneOptions(render, renderOptions);
    render->footer(std::string("\nFrames go to FOLDER/<prefix>_0000.png ..., the report to "
                               "FOLDER/<prefix>_report.json.") +
                   EXIT_CODES_FOOTER);

    ViewOptions viewOptions;
    CLI::App* view = app.add_subcommand(
        "view", "Show a scene in a window: mouse camera, play/pause, overlays (needs a display)");
    view->add_option("scene", viewOptions.scenePath, "Scene file")->required();
    view->add_option("--frames", viewOptions.frames,
                     "Draw this many frames at the scene's frame times, then exit")
        ->check(CLI::Range(1, MAX_FRAMES));
    view->add_option("--screenshot", viewOptions.screenshotPath,
                     "Save the last frame (without the heads-up line) to this PNG");
    view->add_option("--keys", viewOptions.keys,
                     "Replay key presses, one character per frame ('>' right arrow, ' ' space, "
                     "'.' none): for tests and demos");
    view->add_option("--width", viewOptions.width, "Window width in pixels (default output.width)")
        ->check(CLI::Range(1, MAX_IMAGE_SIDE_PX));
    view->add_option("--height", viewOptions.height,
                     "Window height in pixels (default output.height)")
        ->check(CLI::Range(1, MAX_IMAGE_SIDE_PX));
    view->footer(std::string("\nKeys: space play/pause, right arrow step, +/- speed, R reset camera, "
                             "G grass, T terrain, O overlays, [ ] shells, S screenshot, H heads-up, "
                             "Esc/Q quit. Mouse: left drag orbit, right drag pan, scroll zoom. "
                             "Without a display: exit 1, use 'gale render'.") +
                 EXIT_CODES_FOOTER);

    BladeOptions bladeOptions;
    CLI::App* blade = app.add_subcommand(
        "blade",
        "Print the length-preserving bend of one blade as CSV (i,n_m,w_m); --svg draws it");
    blade->add_option("--shells", bladeOptions.shells, "Shells above the ground, N")
        ->required()
        ->check(CLI::Range(1, MAX_SHELLS));
    blade
        ->add_option("--intensity", bladeOptions.intensity,
                     "Wind intensity I (1 lays the tip flat; negative bends the other way)")
        ->required()
        ->check(CLI::Range(-4.0, 4.0));
    blade
        ->add_option("--stiffness", bladeOptions.stiffness,
                     "Stiffness gamma in theta_j = (pi/2) I (j/N)^gamma (1 is the paper's)")
        ->required()
        ->check(CLI::Range(1e-6, 100.0));
    blade->add_option("--height-m", bladeOptions.height_m, "Blade height in metres")
        ->capture_default_str()
        ->check(CLI::Range(1e-6, 100.0));
    blade->add_option("--svg", bladeOptions.svgPath, "Also write an SVG drawing of the blade here");
    blade->footer(EXIT_CODES_FOOTER);

    BenchRenderOptions benchOptions;
    CLI::App* bench = app.add_subcommand("bench", "Benchmarks");
    bench->require_subcommand(1);
    CLI::App* benchRender = bench->add_subcommand("render",
                                                  "Time the shell renderer (the paper's Table 2) "
                                                  "against a trivial fill of the same geometry");
    benchRender->add_option("--frames", benchOptions.frames, "Timed frames per row and pass")
        ->capture_default_str()
        ->check(CLI::Range(1, MAX_FRAMES));
    benchRender->add_flag("--quick", benchOptions.quick,
                          "2 frames and 1 warm-up per row: a smoke run, not a measurement");
    benchRender->add_option("--json", benchOptions.jsonPath, "Also write the results as JSON here");
    benchRender->footer(EXIT_CODES_FOOTER);

    BenchAccuracyOptions accuracyOptions;
    CLI::App* benchAccuracy = bench->add_subcommand(
        "accuracy",
        "Error against run time of the steady solver on the exact hemisphere (potential flow "
        "past a sphere): CSV, SVG plot and convergence order");
    benchAccuracy->add_option("--out", accuracyOptions.outputFolder,
                              "Folder for accuracy.csv and accuracy.svg")
        ->capture_default_str();
    benchAccuracy->add_flag("--quick", accuracyOptions.quick,
                            "4, 8, 16 cells per radius at one tolerance (a CI smoke run)");
    benchAccuracy->add_option("--json", accuracyOptions.jsonPath, "Also write the table as JSON");
    benchAccuracy->footer(EXIT_CODES_FOOTER);

    BenchSolveOptions solveBenchOptions;
    std::vector<std::string> solveBenchSizes;
    bool noOpenVdb = false;
    CLI::App* benchSolve = bench->add_subcommand(
        "solve", "Our MGPCG against OpenVDB's PCG on the same elliptic problem, with memory and "
                 "the bandwidth floor");
    benchSolve->add_option("--size", solveBenchSizes,
                           "Box NXxNYxNZ (repeatable; default 64x64x32 128x128x64 256x256x64)");
    benchSolve->add_flag("--quick", solveBenchOptions.quick, "Only the first size (a CI smoke run)");
    benchSolve->add_flag("--no-openvdb", noOpenVdb, "Skip OpenVDB's solver (ours only)");
    benchSolve->add_option("--tolerance", solveBenchOptions.relativeTolerance,
                           "Max-norm relative residual for both solvers")
        ->capture_default_str()
        ->check(CLI::Range(1e-14, 0.5));
    benchSolve->add_option("--json", solveBenchOptions.jsonPath, "Also write the table as JSON");
    benchSolve->footer(EXIT_CODES_FOOTER);

    BenchCouplingOptions couplingOptions;
    CLI::App* benchCoupling = bench->add_subcommand(
        "coupling", "Grouped against exact bends as the group count grows, and the coupling's cost "
                    "per field step and per frame at 100k and 1M vertices");
    benchCoupling->add_option("--out", couplingOptions.outputFolder,
                              "Folder for coupling.csv and coupling.svg")
        ->capture_default_str();
    benchCoupling->add_flag("--quick", couplingOptions.quick, "10k and 100k vertices (a CI smoke run)");
    benchCoupling->add_option("--json", couplingOptions.jsonPath, "Also write the tables as JSON");
    benchCoupling->footer(EXIT_CODES_FOOTER);

    BenchStabilityOptions stabilityOptions;
    CLI::App* benchStability = bench->add_subcommand(
        "stability", "The unsteady wind's extreme cases (CFL 50, 0 and 100 m/s, cliff, spike, sub-cell "
                     "vortex, nu dt/h^2 = 1000, step gust): finite, divergence-free, energy bounded");
    benchStability->add_flag("--quick", stabilityOptions.quick, "Only the fast subset (what sim_tests runs)");
    benchStability->add_option("--json", stabilityOptions.jsonPath, "Also write the table as JSON");
    benchStability->footer(EXIT_CODES_FOOTER);

    BenchUnsteadyOptions unsteadyOptions;
    CLI::App* benchUnsteady = bench->add_subcommand(
        "unsteady", "Error against run time of the unsteady solver on the exact viscous Lamb-Oseen vortex "
                    "(CSV, SVG, orders) per advection scheme, and the time per step and its parts");
    benchUnsteady->add_option("--out", unsteadyOptions.outputFolder,
                              "Folder for unsteady_accuracy.csv and unsteady_accuracy.svg")
        ->capture_default_str();
    benchUnsteady->add_flag("--quick", unsteadyOptions.quick,
                            "2 and 4 cells per core, a 48x48x16 timing box (a CI smoke run)");
    benchUnsteady->add_option("--json", unsteadyOptions.jsonPath, "Also write the tables as JSON");
    benchUnsteady->footer(EXIT_CODES_FOOTER);

    SolveVerbOptions solveOptions;
    CLI::App* solve = app.add_subcommand(
        "solve", "Solve a scene's wind over its terrain (steady; unsteady scenes as a .vdb "
                 "sequence); write the field as .vdb and a JSON report");
    solve->add_option("scene", solveOptions.scenePath, "Scene file")->required();
    solve->add_option("-o,--output", solveOptions.vdbPath,
                      "The .vdb file (default: <output.folder>/<prefix>_wind.vdb)")
        ->check(NOT_EMPTY);
    solve->add_option("--report", solveOptions.reportPath,
                      "The JSON report (default: the .vdb path with .json)")
        ->check(NOT_EMPTY);
    solve->footer(std::string("\nThe .vdb holds a Vec3s grid 'velocity' (m/s, world axes, cell "
                              "centres) and a float grid 'speed'; docs/solver.md says more.") +
                  EXIT_CODES_FOOTER);

    TerrainExportOptions terrainOptions;
    CLI::App* terrain = app.add_subcommand(
        "terrain",
        "Export a scene's heightfield as a 16-bit grey PNG (a heightmap scene reads it)");
    terrain->add_option("scene", terrainOptions.scenePath, "Scene file")->required();
    terrain->add_option("-o,--output", terrainOptions.imagePath, "PNG file to write")->required();
    terrain->footer(EXIT_CODES_FOOTER);

    if (argc > 1 && argv[1][0] != '-') {
        const std::string verb = argv[1];
        bool known = false;
        for (CLI::App* v : {check, render, view, solve, blade, bench, terrain})
            known |= v->get_name() == verb;
        if (!known)
            return reportError("unknown verb '" + verb +
                                   "' (expected check, render, view, solve, blade, bench or terrain; see 'gale "
                                   "--help')",
                               EXIT_BAD_INPUT);
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        std::string hint = " (see 'gale --help')";
        for (CLI::App* verb : {check, render, view, solve, blade, bench, terrain})
            if (verb->parsed()) hint = " (see 'gale " + verb->get_name() + " --help')";
        for (CLI::App* verb : {benchRender, benchAccuracy, benchSolve, benchCoupling, benchStability, benchUnsteady})
            if (verb->parsed()) hint = " (see 'gale bench " + verb->get_name() + " --help')";
        return reportError(e.what() + hint, EXIT_BAD_INPUT);
    }

    try {
        const auto threadLimit = threadLimitFromEnvironment();
        if (check->parsed()) return runCheck(checkOptions);
        if (render->parsed()) return runRender(renderOptions);
        if (view->parsed()) return runView(viewOptions);
        if (blade->parsed()) return runBlade(bladeOptions);
        if (benchRender->parsed()) {
            try {
                return runBenchRender(benchOptions);
            } catch (const std::invalid_argument& e) {
                throw InputError(e.what());  // the bench's "bad options"
            }
        }
        if (terrain->parsed()) return runTerrainExport(terrainOptions);
        if (solve->parsed()) return runSolveVerb(solveOptions);
        if (benchAccuracy->parsed()) return runBenchAccuracy(accuracyOptions);
        if (benchCoupling->parsed()) return runBenchCoupling(couplingOptions);
        if (benchStability->parsed()) return runBenchStability(stabilityOptions);
        if (benchUnsteady->parsed()) return runBenchUnsteady(unsteadyOptions);
        if (benchSolve->parsed()) {
            solveBenchOptions.openVdb = !noOpenVdb;
            for (const std::string& text : solveBenchSizes) {
                std::array<int, 3> n{};
                char x1 = 0, x2 = 0;
                if (std::sscanf(text.c_str(), "%d%c%d%c%d", &n[0], &x1, &n[1], &x2, &n[2]) != 5 ||
                    x1 != 'x' || x2 != 'x' || n[0] < 2 || n[1] < 2 || n[2] < 2 || n[0] > 4096 ||
                    n[1] > 4096 || n[2] > 4096)
                    throw InputError("--size: expected NXxNYxNZ with 2..4096 cells per side (got '" +
                                     text + "')");
                solveBenchOptions.sizes.push_back(n);
            }
            try {
                return runBenchSolve(solveBenchOptions);
            } catch (const std::invalid_argument& e) {
                throw InputError(e.what());
            }
        }
        return reportError("no verb given (see 'gale --help')", EXIT_BAD_INPUT);
    } catch (const InputError& e) {
        return reportError(e.what(), EXIT_BAD_INPUT);
    } catch (const std::bad_alloc&) {
        return reportError("out of memory", EXIT_FAILURE_INTERNAL);
    } catch (const std::exception& e) {
        return reportError(e.what(), EXIT_FAILURE_INTERNAL);
    }
}
