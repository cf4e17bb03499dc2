/// \file CommandsBench.cpp
/// `gale bench VERB`: the command lines of the benchmarks in app/bench. A benchmark returns
/// EXIT_UNMET when a full run misses its stated target; a bad option (std::invalid_argument from
/// the benchmark) is bad input, exit 2.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "app/Cli.h"
#include "app/Commands.h"
#include "app/bench/BenchCoupling.h"
#include "app/bench/BenchLiveStep.h"
#include "app/bench/BenchMemory.h"
#include "app/bench/BenchModels.h"
#include "app/bench/BenchRender.h"
#include "app/bench/BenchRough.h"
#include "app/bench/BenchScale.h"
#include "app/bench/BenchSolve.h"
#include "app/bench/BenchUnsteady.h"
#include "app/bench/BenchView.h"
#include "app/io/Errors.h"
#include "app/io/Timing.h"
#include "app/scene/LoadScene.h"
#include "app/scene/SceneBuilder.h"
#include "app/scene/SceneParser.h"
#include "base/Numbers.h"
#include "coupling/UnsteadyFieldWind.h"
#include "sim/Advection.h"

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

/// One `gale bench NAME` verb: its options, the --quick and --json every benchmark has, the exit
/// codes footer, and its entry in the verb table, which runs `run` on the parsed options (bad
/// options become bad input). Returns the verb and its options for the verb's own flags.
template <class Options>
std::pair<CLI::App*, std::shared_ptr<Options>> addBench(CLI::App& bench, VerbTable& verbs,
                                                        const std::string& name,
                                                        const std::string& description,
                                                        const std::string& quickHelp,
                                                        std::function<int(Options&)> run) {
    auto o = std::make_shared<Options>();
    CLI::App* verb = bench.add_subcommand(name, description);
    verb->add_flag("--quick", o->quick, quickHelp);
    verb->add_option("--json", o->jsonPath, "Also write the results as JSON here");
    verb->footer(EXIT_CODES_FOOTER);
    verbs.add(verb, [o, run] { return runBench([&] { return run(*o); }); });
    return {verb, o};
}

void addRender(CLI::App& bench, VerbTable& verbs) {
    auto [verb, o] = addBench<BenchRenderOptions>(
        bench, verbs, "render",
        "Time the shell renderer (the paper's Table 2) against a trivial fill of the same "
        "geometry",
        "2 frames and 1 warm-up per row: a smoke run, not a measurement (targets printed, not "
        "judged)",
        [](BenchRenderOptions& options) { return runBenchRender(options); });
    verb->add_option("--frames", o->frames, "Timed frames per row and pass")
        ->capture_default_str()
        ->check(CLI::Range(1, MAX_FRAMES));
    verb->add_flag(
        "--profile", o->profile,
        "Instead of the table: where a shell fragment's time goes (17 layers at 640x480, "
        "one thing changed at a time: filter, fetches, arithmetic, alpha test, depth "
        "test, order), CPU ms per frame against the trivial fill");
}

void addAccuracy(CLI::App& bench, VerbTable& verbs) {
    auto [verb, o] = addBench<BenchAccuracyOptions>(
        bench, verbs, "accuracy",
        "Error against run time of the steady solver on the exact hemisphere (potential flow "
        "past a sphere): CSV, SVG plot and convergence order",
        "4, 8, 16 cells per radius at one tolerance (a CI smoke run)",
        [](BenchAccuracyOptions& options) { return runBenchAccuracy(options); });
    verb->add_option("--out", o->outputFolder, "Folder for accuracy.csv and accuracy.svg")
        ->capture_default_str();
}

void addSolve(CLI::App& bench, VerbTable& verbs) {
    auto sizes = std::make_shared<std::vector<std::string>>();
    auto noOpenVdb = std::make_shared<bool>(false);
    auto [verb, o] = addBench<BenchSolveOptions>(
        bench, verbs, "solve",
        "Our MGPCG against OpenVDB's PCG on the same elliptic problem, with memory and the "
        "bandwidth floor",
        "Only the first size (a CI smoke run)", [sizes, noOpenVdb](BenchSolveOptions& options) {
            options.openVdb = !*noOpenVdb;
            for (const std::string& text : *sizes) options.sizes.push_back(parseBoxSize(text));
            return runBenchSolve(options);
        });
    verb->add_option("--size", *sizes,
                     "Box NXxNYxNZ (repeatable; default 64x64x32 128x128x64 256x256x64)");
    verb->add_flag("--no-openvdb", *noOpenVdb, "Skip OpenVDB's solver (ours only)");
    verb->add_option("--tolerance", o->relativeTolerance,
                     "Max-norm relative residual for both solvers")
        ->capture_default_str()
        ->check(CLI::Range(1e-14, 0.5));
}

void addScale(CLI::App& bench, VerbTable& verbs) {
    auto size = std::make_shared<std::string>();
    auto ranks = std::make_shared<std::vector<int>>();
    auto noGamg = std::make_shared<bool>(false);
    auto [verb, o] = addBench<BenchScaleOptions>(
        bench, verbs, "scale",
        "Strong scaling of the distributed solve (mpirun, 1, 2, 4 ranks) on the 256x256x64 box: "
        "per-iteration compute, halo exchange, coarse solve, bytes exchanged; one process at 1 "
        "and 2 threads and PETSc GAMG as anchors (docs/scale.md)",
        "A 64x64x32 box (a CI smoke run)", [size, ranks, noGamg](BenchScaleOptions& options) {
            if (!size->empty()) options.size = parseBoxSize(*size);
            if (!ranks->empty()) options.ranks = *ranks;
            options.gamg = !*noGamg;
            return runBenchScale(options);
        });
    verb->add_option("--size", *size, "Box NXxNYxNZ (default 256x256x64)");
    verb->add_option("--ranks", *ranks, "Rank counts (default 1 2 4)")->check(CLI::Range(1, 1024));
    verb->add_option("--tolerance", o->relativeTolerance, "Max-norm relative residual")
        ->capture_default_str()
        ->check(CLI::Range(1e-14, 0.5));
    verb->add_flag("--no-gamg", *noGamg, "Skip PETSc GAMG");
    verb->add_flag("--worker", o->worker, "Internal: one rank count's child run");
    verb->add_option("--shared-threads", o->sharedThreads,
                     "Internal: the child runs sim's one-process solver");
}

void addCoupling(CLI::App& bench, VerbTable& verbs) {
    auto [verb, o] = addBench<BenchCouplingOptions>(
        bench, verbs, "coupling",
        "Grouped against exact bends as the group count grows, and the coupling's cost per "
        "field step and per frame at 100k and 1M vertices, and the near-ground read's step and "
        "plan against plain trilinear sampling",
        "10k and 100k vertices (a CI smoke run)",
        [](BenchCouplingOptions& options) { return runBenchCoupling(options); });
    verb->add_option("--out", o->outputFolder, "Folder for coupling.csv and coupling.svg")
        ->capture_default_str();
}

void addModels(CLI::App& bench, VerbTable& verbs) {
    auto o = std::make_shared<BenchModelsOptions>();
    CLI::App* verb = bench.add_subcommand(
        "models",
        "Error against run time of both steady models: the hemisphere's potential flow "
        "(mass-consistent), the flat log law (momentum) and the steep ridge of Cao and Tamura "
        "(2006) (both), at two or three resolutions");
    verb->add_option("--out", o->outputFolder, "Folder for models.csv and models.svg")
        ->capture_default_str();
    verb->add_flag("--quick", o->quick, "The coarsest resolution of each case (a CI smoke run)");
    verb->add_option("--data", o->validationCsv,
                     "The validation data (default: validation/data/"
                     "cao-tamura-2006-ridge.csv as built into the program)");
    verb->add_option("--json", o->jsonPath, "Also write the table as JSON");
    verb->add_flag("--crest", o->crestStudy,
                   "Instead: the crest experiments on the ridge (potential flow, Euler, eddy "
                   "viscosity, wall stress, box height; docs/validation.md section 3)");
    verb->add_flag("--jackson-hunt", o->jacksonHunt,
                   "Instead: the low cos^2 ridges (H / L = 0.025, 0.05, 0.1) against Jackson and "
                   "Hunt (1975), in a 2-D box with free-slip side walls (docs/validation.md "
                   "section 2)");
    verb->add_flag(
        "--pseudo-time", o->pseudoTime,
        "Instead: the momentum model's steady state on a gentle and a steep ridge "
        "against its pseudo-time step, semi-Lagrangian and Eulerian (docs/validation.md, "
        "\"Pseudo-time step and its error\")");
    verb->add_flag("--separation", o->separation,
                   "Instead: the separation benchmarks (the ERCOFTAC periodic hill against the "
                   "DNS of Xiao et al. 2020) for every closure and both pseudo-time steps, with "
                   "their run times (docs/validation.md section 4); --quick: h / 5 only");
    verb->add_flag("--eulerian-ridge", o->eulerianRidge,
                   "The table also solves the Cao and Tamura ridge with the Eulerian pseudo-time "
                   "step (solver.momentum_advection = \"eulerian\")");
    verb->add_flag("--closures", o->closures,
                   "The table also solves the Cao and Tamura ridge with every two-equation closure "
                   "(solver.turbulence = \"k_epsilon\", \"k_omega_sst\"), beside the mixing "
                   "length");
    verb->add_option("--ridge-resolution", o->ridgeCellsPerH,
                     "H / h of the Cao and Tamura ridge's solves, one or more (default 5 10; "
                     "--quick 5)")
        ->check(CLI::Range(1, 40));
    verb->add_option("--ridge-iterations", o->ridgeIterations,
                     "Pseudo-time steps per level at most for the ridge's momentum solves "
                     "(default 1000; --quick 300)")
        ->check(CLI::Range(1, 100000));
    verb->footer(EXIT_CODES_FOOTER);
    verbs.add(verb, [o] { return runBench([o] { return runBenchModels(*o); }); });
}

void addRough(CLI::App& bench, VerbTable& verbs) {
    (void)addBench<BenchRoughOptions>(
        bench, verbs, "rough",
        "Steady-solve iterations on a fractal and a sharp-feature terrain at 20, 10 and 5 m "
        "cells (target: <= 20 at every resolution)",
        "A 320 m square instead of 1280 m (a CI smoke run)",
        [](BenchRoughOptions& options) { return runBenchRough(options); });
}

void addStability(CLI::App& bench, VerbTable& verbs) {
    (void)addBench<BenchStabilityOptions>(
        bench, verbs, "stability",
        "The unsteady wind's stability suite: CFL 5/20/50 over a ridge, 0 and 100 m/s, cliff, "
        "spike, sub-cell vortex, nu dt/h^2 = 1000, gusts (energy budgets, deviation from the "
        "steady start); the translating Lamb-Oseen vortex's orders and Burgers' vortex against "
        "their exact solutions",
        "Only the fast subset (what sim_tests runs)",
        [](BenchStabilityOptions& options) { return runBenchStability(options); });
}

/// A scene's unsteady solver as `gale view` builds it (the step limited to an output frame), for
/// `gale bench unsteady --live`; a non-empty `advection` (a scheme's name) replaces the scene's
/// unsteady.advection, a non-empty `precision` its unsteady.precision, a `tolerance` > 0 its
/// unsteady.tolerance, `iterations` > 0 its unsteady.live_iterations. Throws what scene loading
/// throws, and std::invalid_argument (exit 2, naming FILE:LINE of wind.kind) when the scene's
/// wind is not unsteady.
LiveStepScene loadLiveStepScene(const std::string& path, const std::string& advection,
                                const std::string& precision, double tolerance, int iterations) {
    struct Owned {
        Scene scene;
        BuiltScene built;
    };
    SceneRunOptions run;
    run.scenePath = path;
    auto owned = std::make_shared<Owned>();
    owned->scene = loadScene(run);
    if (owned->scene.wind.kind != WindKind::Unsteady)  // before the steady solve a build runs
        throw std::invalid_argument(owned->scene.where("wind.kind") +
                                    ": bench unsteady --live needs \"unsteady\" (got \"" +
                                    windKindName(owned->scene.wind.kind) + "\")");
    limitUnsteadyStepToAFrame(owned->scene);  // as gale view does
    if (!advection.empty())
        owned->scene.unsteady.settings.advection = sim::advectionSchemeFromName(advection);
    if (!precision.empty())
        owned->scene.unsteady.settings.precision = sim::advectionPrecisionFromName(precision);
    if (tolerance > 0.0) owned->scene.unsteady.settings.projection.relativeTolerance = tolerance;
    if (iterations > 0) owned->scene.unsteady.settings.projection.maxIterations = iterations;
    BuildOptions build;
    build.progress = [](const std::string& text) {
        std::fprintf(stderr, "gale: %s\n", text.c_str());
    };
    owned->built = buildScene(owned->scene, build);
    auto* unsteady = dynamic_cast<coupling::UnsteadyFieldWind*>(owned->built.wind.get());
    if (!unsteady)
        throw std::logic_error("bench unsteady --live: the unsteady scene built no solver");
    std::string name = std::filesystem::path(path).stem().string();
    if (!advection.empty()) name += " (" + advection + ")";
    if (!precision.empty()) name += " (" + precision + ")";
    if (tolerance > 0.0) name += " (tol " + std::to_string(tolerance).substr(0, 8) + ")";
    if (iterations > 0) name += " (its " + std::to_string(iterations) + ")";
    return {name, &unsteady->solver(), owned};
}

void addUnsteady(CLI::App& bench, VerbTable& verbs) {
    auto live = std::make_shared<BenchLiveStepOptions>();
    auto [verb, o] = addBench<BenchUnsteadyOptions>(
        bench, verbs, "unsteady",
        "Error against run time of the unsteady solver on the exact viscous Lamb-Oseen vortex "
        "(CSV, SVG, orders) per advection scheme, and the time per step and its parts",
        "2 and 4 cells per core, a 48x48x16 timing box (a CI smoke run)",
        [live](BenchUnsteadyOptions& options) {
            if (live->scenes.empty()) return runBenchUnsteady(options);
            live->jsonPath = options.jsonPath;
            live->loader = [live](const std::string& path) {
                return loadLiveStepScene(path, live->advection, live->precision, live->tolerance,
                                         live->iterations);
            };
            return runBenchLiveStep(*live);
        });
    verb->add_option("--out", o->outputFolder,
                     "Folder for unsteady_accuracy.csv and unsteady_accuracy.svg")
        ->capture_default_str();
    verb->add_option("--live", live->scenes,
                     "Only the live-wind step: CPU ms per step and its parts of this unsteady "
                     "scene's solver as gale view runs it (repeatable)");
    verb->add_option("--advection", live->advection,
                     "With --live: step every scene with this advection scheme instead of its "
                     "unsteady.advection")
        ->check(CLI::IsMember({"semi_lagrangian", "maccormack", "bfecc"}));
    verb->add_option("--precision", live->precision,
                     "With --live: the advection's arithmetic instead of the scene's "
                     "unsteady.precision")
        ->check(CLI::IsMember({"single", "double"}));
    verb->add_option("--tolerance", live->tolerance,
                     "With --live: the projection's tolerance instead of the scene's "
                     "unsteady.tolerance")
        ->check(CLI::Range(1e-12, 0.5));
    verb->add_option("--iterations", live->iterations,
                     "With --live: the projection's budget (MGPCG iterations a step) instead of "
                     "the scene's unsteady.live_iterations")
        ->check(CLI::Range(1, 1000));
    verb->add_option("--steps", live->steps, "Timed steps per --live scene")
        ->capture_default_str()
        ->check(CLI::Range(1, 100000));
}

/// `gale bench view --quick`: momentum solves stop after this many pseudo-time steps.
constexpr int QUICK_MOMENTUM_ITERATIONS = 5;

/// The motion regions of `gale bench view --motion` (BenchView.h) from the scene's own geometry:
/// - a ridge under a solved wind: the crest within one half-width (terrain.radius_m) of the ridge
///   line, the lee 2 to 5 half-widths downwind of it (wind.direction_deg);
/// - whirlwinds (unsteady): the core tracked in the field at every frame (the largest vertical
///   vorticity, of the first whirlwind's sense, 1 m above the ground on a 1 m plan grid); agitated
///   within 2 core radii of the track, calm (the meadow around) 4 to 8 core radii from it.
/// Points within 2 m of the terrain's edge are neither. Empty for other scenes.
MotionRegions motionRegionsOf(const Scene& scene, const BuiltScene& built) {
    MotionRegions m;
    const sim::Heightfield& field = built.heightfield;
    const double x0 = field.originX_m, y0 = field.originY_m;
    const double x1 = x0 + field.sizeX_m(), y1 = y0 + field.sizeY_m();
    constexpr double EDGE_MARGIN_M = 2.0;
    const auto inside = [=](double x, double y) {
        return x > x0 + EDGE_MARGIN_M && x < x1 - EDGE_MARGIN_M && y > y0 + EDGE_MARGIN_M &&
               y < y1 - EDGE_MARGIN_M;
    };
    const sim::TerrainSpec& t = scene.terrain.spec;
    const std::vector<sim::Whirlwind>& whirlwinds = scene.unsteady.settings.whirlwinds;
    if (scene.wind.kind == WindKind::Unsteady && !whirlwinds.empty() && built.wind) {
        const sim::Whirlwind& ww = whirlwinds.front();
        const double sense = ww.peakSpeed_mps != 0.0 ? ww.peakSpeed_mps : ww.circulation_m2ps;
        const double rc_m = ww.coreRadius_m;
        auto track = std::make_shared<std::vector<std::array<double, 2>>>();
        const coupling::WindSource* source = built.wind.get();
        m.agitated = "core";
        m.calm = "meadow";
        m.onFrame = [=, &field](double) {
            const sim::WindField* f = source->currentField();
            if (!f) return;
            constexpr double H_M = 1.0;  // plan grid spacing and the height above the ground
            double best = -1e300;
            std::array<double, 2> at{ww.wsPosition_m};
            for (double y = y0 + H_M; y < y1 - H_M; y += H_M)
                for (double x = x0 + H_M; x < x1 - H_M; x += H_M) {
                    const double z = field.sample(x, y) + H_M;
                    const auto ue = f->velocityAt_mps(x + H_M, y, z);
                    const auto uw = f->velocityAt_mps(x - H_M, y, z);
                    const auto un = f->velocityAt_mps(x, y + H_M, z);
                    const auto us = f->velocityAt_mps(x, y - H_M, z);
                    const double wz = (ue[1] - uw[1] - un[0] + us[0]) / (2.0 * H_M);
                    const double s = sense < 0.0 ? -wz : wz;
                    if (s > best) {
                        best = s;
                        at = {x, y};
                    }
                }
            track->push_back(at);
        };
        m.classify = [=](double x, double y) {
            if (!inside(x, y) || track->empty()) return 0;
            double d2 = 1e300;
            for (const auto& c : *track)
                d2 = std::min(d2, (x - c[0]) * (x - c[0]) + (y - c[1]) * (y - c[1]));
            const double d = std::sqrt(d2) / rc_m;
            return d <= 2.0 ? 1 : (d >= 4.0 && d <= 8.0 ? -1 : 0);
        };
    } else if (scene.wind.kind == WindKind::Solved && t.kind == sim::TerrainKind::Ridge &&
               !scene.terrain.dem) {
        const double a = radiansFromDegrees(t.axis_deg);
        const double w = radiansFromDegrees(scene.wind.ambient.direction_deg);
        // The normal of the ridge line pointing downwind.
        double nx = -std::sin(a), ny = std::cos(a);
        if (nx * std::cos(w) + ny * std::sin(w) < 0.0) nx = -nx, ny = -ny;
        const double cx = t.centerX_m, cy = t.centerY_m, r_m = t.radius_m;
        m.agitated = "crest";
        m.calm = "lee";
        m.classify = [=](double x, double y) {
            if (!inside(x, y)) return 0;
            const double d = ((x - cx) * nx + (y - cy) * ny) / r_m;
            return std::abs(d) <= 1.0 ? 1 : (d >= 2.0 && d <= 5.0 ? -1 : 0);
        };
    }
    return m;
}

/// A scene as `gale view` builds it, for the view benchmark (which cannot read scenes itself:
/// app/bench sits beside app/scene).
ViewBenchScene loadViewScene(const std::string& path, int width, int height, int shells,
                             bool quick) {
    struct Owned {
        Scene scene;
        BuiltScene built;
    };
    const auto start = Clock::now();
    SceneRunOptions run;
    run.scenePath = path;
    run.width = width;
    run.height = height;
    auto owned = std::make_shared<Owned>();
    owned->scene = loadScene(run);
    owned->scene.grass.params.shells = shells;
    limitUnsteadyStepToAFrame(owned->scene);  // as gale view does
    // A smoke run times the frame loop, not the solve: the momentum model's pseudo-time stepping
    // (hundreds of iterations) is cut to a few.
    if (quick)
        owned->scene.solver.momentum.maxIterations =
            std::min(owned->scene.solver.momentum.maxIterations, QUICK_MOMENTUM_ITERATIONS);
    BuildOptions build;
    build.progress = [](const std::string& text) {
        std::fprintf(stderr, "gale: %s\n", text.c_str());
    };
    owned->built = buildScene(owned->scene, build);

    ViewBenchScene v;
    v.name = std::filesystem::path(path).stem().string();
    v.inputs.mesh = &owned->built.mesh;
    v.inputs.grass = &owned->scene.grass.params;
    v.inputs.texture = &owned->built.texture;
    v.inputs.densityMap = &owned->built.densityMap;
    v.inputs.lighting = &owned->scene.lighting;
    v.inputs.wind = owned->built.wind.get();
    v.camera = owned->built.camera;
    v.overlay = owned->scene.overlay;
    v.startTime_s = owned->scene.output.startTime_s;
    v.fps = owned->scene.output.fps;
    v.motion = motionRegionsOf(owned->scene, owned->built);
    v.owner = owned;
    v.build_ms = msSince(start);
    return v;
}

void addView(CLI::App& bench, VerbTable& verbs) {
    auto o = std::make_shared<BenchViewOptions>();
    CLI::App* verb = bench.add_subcommand(
        "view",
        "Frame rate of each scene through gale view's frame loop (headless by default), each "
        "frame split into wind, upload, draw and present (target: 30 fps at 640x480, 17 shells)");
    verb->add_option("scenes", o->scenes, "Scene files or folders of them")
        ->default_str("examples");
    verb->add_option("--frames", o->frames, "Timed frames per scene")
        ->capture_default_str()
        ->check(CLI::Range(1, MAX_FRAMES));
    verb->add_option("--width", o->width, "Frame width in pixels")
        ->capture_default_str()
        ->check(CLI::Range(1, MAX_IMAGE_SIDE_PX));
    verb->add_option("--height", o->height, "Frame height in pixels")
        ->capture_default_str()
        ->check(CLI::Range(1, MAX_IMAGE_SIDE_PX));
    verb->add_option("--shells", o->shells, "Shells for every scene")->capture_default_str();
    verb->add_flag("--window", o->window,
                   "Draw in a GLFW window (needs a display), so present is the copy to the screen");
    verb->add_flag(
        "--quick", o->quick,
        "3 frames per scene after 1 warm-up, momentum solves cut to 5 steps: a smoke run "
        "(targets printed, not judged)");
    verb->add_option("--json", o->jsonPath, "Also write the table as JSON here");
    verb->add_flag(
        "--motion", o->motion,
        "Measure the wind's readability instead: the grass's temporal standard deviation "
        "where the scene's geometry says the air is agitated (a ridge's crest, a "
        "whirlwind's core) against where it is calm (target: >= 2x)");
    verb->add_option("--motion-frames", o->motionFrames, "Frames of the --motion measurement")
        ->capture_default_str()
        ->check(CLI::Range(2, MAX_FRAMES));
    verb->footer(EXIT_CODES_FOOTER);
    verbs.add(verb, [o] {
        o->loader = loadViewScene;
        o->beforeRenderer = [](const std::vector<std::string>& files) {
            // gale view's policy for live wind (each file read once more, not built). One
            // renderer serves the whole run, so the policy holds for all its scenes or none:
            // it is applied when every scene steps live wind, so that static scenes keep the
            // rasteriser's every core as gale view gives them.
            size_t live = 0;
            for (const std::string& f : files) {
                SceneRunOptions run;
                run.scenePath = f;
                live += loadScene(run).wind.kind == WindKind::Unsteady;
            }
            if (live == files.size()) {
                shareCoresWithLiveWind();
            } else if (live > 0) {
                std::fprintf(stderr,
                             "bench view: %zu of %zu scenes step live wind; gale view gives "
                             "those llvmpipe half the cores (bench them on their own to see "
                             "it), this run gives every scene all of them\n",
                             live, files.size());
            }
        };
        return runBench([o] { return runBenchView(*o); });
    });
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
    addScale(*bench, verbs);
    addCoupling(*bench, verbs);
    addRough(*bench, verbs);
    addModels(*bench, verbs);
    addStability(*bench, verbs);
    addUnsteady(*bench, verbs);
    addView(*bench, verbs);
    addMemory(*bench, verbs);
}

}  // namespace gale::app
