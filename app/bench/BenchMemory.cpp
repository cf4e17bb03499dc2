/// \file BenchMemory.cpp
/// `gale bench memory` (BenchMemory.h).
#include "app/bench/BenchMemory.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/io/Timing.h"
#include "base/Numbers.h"

namespace gale::app {
namespace {

namespace fs = std::filesystem;

/// One run: a scene (its sections after [terrain]) and the verb that runs it.
struct Shape {
    const char* name;
    const char* verb;  ///< "solve" or "render"
    const char* what;  ///< one line for the table
    std::string scene;
    bool quick;  ///< also in --quick
};

/// A scene over a Gaussian hill of size_m x size_m at 1 m samples, with small grass (the
/// grass matters to renders only) and the given sections.
std::string hillScene(double sizeX_m, double sizeY_m, double height_m, const std::string& rest) {
    char head[512];
    std::snprintf(head, sizeof head,
                  "[terrain]\nkind = \"gaussian_hill\"\nsize_m = [%g, %g]\nspacing_m = 1.0\n"
                  "height_m = %g\nradius_m = %g\n\n[grass]\nheight_m = 0.4\nshells = 8\n"
                  "tile_m = 2.0\n\n[grass.generated]\nsize = 128\n\n",
                  sizeX_m, sizeY_m, height_m, 0.25 * std::min(sizeX_m, sizeY_m));
    return head + rest;
}

const char* SOLVED_WIND =
    "[wind]\nkind = \"solved\"\nspeed_mps = 5.0\nprofile = \"log\"\nroughness_m = 0.03\n\n";
const char* UNSTEADY_WIND =
    "[wind]\nkind = \"unsteady\"\nspeed_mps = 5.0\nprofile = \"log\"\nroughness_m = 0.03\n\n";

/// A [solver] section of cubic cells of voxel_m up to top_m, with a limit out of the way (the
/// bench measures the estimate; it does not test the refusal).
std::string solver(double voxel_m, double top_m) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "[solver]\nvoxel_size_m = %g\ntop_m = %g\nmemory_limit_mb = 100000\n", voxel_m,
                  top_m);
    return text;
}

std::vector<Shape> shapes() {
    return {
        {"steady_cube", "solve", "steady, 96 x 96 x 48 cells over a hill",
         hillScene(96, 96, 10, std::string(SOLVED_WIND) + solver(1.0, 48.0)), true},
        {"steady_wide_flat", "solve", "steady, 256 x 256 x 10 cells (wide and flat)",
         hillScene(512, 512, 6, std::string(SOLVED_WIND) + solver(2.0, 20.0)), false},
        {"steady_tall_thin", "solve", "steady, 8 x 8 x 8000 cells (a tall thin column)",
         hillScene(8, 8, 2, std::string(SOLVED_WIND) + solver(1.0, 8000.0)), false},
        {"steady_needle", "solve", "steady, 2 x 2 x 30000 cells (2 cells wide: OpenVDB's worst)",
         hillScene(8, 8, 2, std::string(SOLVED_WIND) + solver(4.0, 120000.0)), true},
        {"steady_momentum", "solve", "steady momentum model, 48 x 48 x 24 cells",
         hillScene(48, 48, 6,
                   std::string(SOLVED_WIND) + solver(1.0, 24.0) +
                       "model = \"momentum\"\nmomentum_max_iterations = 20\n"),
         false},
        {"unsteady_cube", "solve", "unsteady, 64 x 64 x 32 cells, semi-Lagrangian, 2 steps",
         hillScene(64, 64, 8,
                   std::string(UNSTEADY_WIND) + solver(1.0, 32.0) +
                       "\n[unsteady]\nduration_s = 0.5\noutput_every_s = 0.5\n"),
         true},
        {"unsteady_tall_maccormack", "solve",
         "unsteady, 8 x 8 x 3000 cells, MacCormack, viscosity, confinement",
         hillScene(8, 8, 2,
                   std::string(UNSTEADY_WIND) + solver(1.0, 3000.0) +
                       "\n[unsteady]\nduration_s = 0.5\noutput_every_s = 0.5\n"
                       "advection = \"maccormack\"\nviscosity_m2ps = 0.5\n"
                       "vorticity_confinement = 0.2\n"),
         false},
        {"render_point_source", "render", "render, point source, 1024 x 768, 2 frames",
         hillScene(32, 32, 3,
                   "[[lighting.light]]\nposition_m = [40.0, -20.0, 30.0]\n\n"
                   "[output]\nwidth = 1024\nheight = 768\nframes = 2\n"),
         true},
        {"render_big_terrain", "render", "render, 1024 x 1024 terrain samples, 640 x 480",
         hillScene(1024, 1024, 60,
                   "[[lighting.light]]\nposition_m = [1200.0, -200.0, 600.0]\n\n"
                   "[output]\nwidth = 640\nheight = 480\nframes = 2\n"),
         false},
        {"render_solved", "render", "render, solved wind on 96 x 96 x 32 cells, 640 x 480",
         hillScene(96, 96, 8,
                   std::string(SOLVED_WIND) + solver(1.0, 32.0) +
                       "\n[output]\nwidth = 640\nheight = 480\nframes = 2\n"),
         false},
    };
}

/// How one child run went.
struct Measured {
    int exitCode = -1;
    double peak_bytes = 0;  ///< ru_maxrss of the child
    double seconds = 0;
};

/// Runs this program with `args` in `folder`, stdout and stderr to files there; waits for it.
Measured runChild(const std::vector<std::string>& args, const fs::path& folder) {
    const std::string self = fs::read_symlink("/proc/self/exe").string();
    const std::string log = (folder / "child.log").string();
    const auto t0 = Clock::now();
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("bench memory: cannot start a child process");
    if (pid == 0) {
        const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd < 0 || ::chdir(folder.c_str()) != 0) ::_exit(126);
        ::dup2(fd, 1), ::dup2(fd, 2);
        std::vector<std::string> argv = {self};
        argv.insert(argv.end(), args.begin(), args.end());
        std::vector<char*> cargv;
        for (std::string& a : argv) cargv.push_back(a.data());
        cargv.push_back(nullptr);
        ::execv(self.c_str(), cargv.data());
        ::_exit(127);
    }
    Measured m;
    int status = 0;
    struct rusage usage {};
    while (::wait4(pid, &status, 0, &usage) < 0)
        if (errno != EINTR) throw std::runtime_error("bench memory: wait4 failed");
    m.seconds = secondsSince(t0);
    m.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    m.peak_bytes = double(usage.ru_maxrss) * 1024.0;  // Linux: kibibytes
    return m;
}

/// The memory estimate the child wrote into its report; 0 if there is none.
double reportedEstimate(const fs::path& report, bool render) {
    std::ifstream in(report);
    if (!in) return 0.0;
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded()) return 0.0;
    const nlohmann::json* v =
        render ? (j.contains("memory_estimate_bytes") ? &j["memory_estimate_bytes"] : nullptr)
               : (j.contains("domain") && j["domain"].contains("memory_estimate_bytes")
                      ? &j["domain"]["memory_estimate_bytes"]
                      : nullptr);
    return v && v->is_number() ? v->get<double>() : 0.0;
}

}  // namespace

int runBenchMemory(const BenchMemoryOptions& opt) {
    char pattern[] = "/tmp/gale-bench-memory-XXXXXX";
    if (!::mkdtemp(pattern)) throw std::runtime_error("bench memory: cannot make a scratch folder");
    const fs::path scratch(pattern);
    std::printf(
        "memory estimate against the peak resident memory (ru_maxrss of a child run); "
        "bound: peak / estimate within [1/%.2f, %.2f]\n",
        MEMORY_ESTIMATE_RATIO_BOUND, MEMORY_ESTIMATE_RATIO_BOUND);
    std::printf("%-26s %-7s %12s %12s %7s %8s  %s\n", "shape", "verb", "estimate MiB", "peak MiB",
                "ratio", "run s", "what");
    nlohmann::json rows = nlohmann::json::array();
    bool ok = true;
    for (const Shape& s : shapes()) {
        if (opt.quick && !s.quick) continue;
        std::fprintf(stderr, "bench memory: %s...\n", s.name);
        const fs::path folder = scratch / s.name;
        fs::create_directories(folder);
        {
            std::ofstream scene(folder / "scene.toml");
            scene << s.scene;
        }
        const bool render = std::string(s.verb) == "render";
        const fs::path report =
            render ? folder / "frames" / "frame_report.json" : folder / "r.json";
        const std::vector<std::string> args =
            render ? std::vector<std::string>{"render", "scene.toml", "-o", "frames"}
                   : std::vector<std::string>{"solve", "scene.toml", "-o",
                                              "w.vdb", "--report",   "r.json"};
        const Measured m = runChild(args, folder);
        const double estimate = reportedEstimate(report, render);
        const double ratio = estimate > 0 ? m.peak_bytes / estimate : 0.0;
        // A solve that ran but did not converge (exit 3) was measured all the same.
        const bool ran = m.exitCode == EXIT_OK || (!render && m.exitCode == EXIT_UNMET);
        const bool met = ran && estimate > 0 && ratio <= MEMORY_ESTIMATE_RATIO_BOUND &&
                         ratio >= 1.0 / MEMORY_ESTIMATE_RATIO_BOUND;
        ok = ok && met;
        std::printf("%-26s %-7s %12.1f %12.1f %7.3f %8.2f  %s%s\n", s.name, s.verb, estimate / MIB,
                    m.peak_bytes / MIB, ratio, m.seconds, s.what,
                    !ran  ? "  (FAILED: exit code, see the log)"
                    : met ? ""
                          : "  MISSED");
        if (!ran) std::fprintf(stderr, "bench memory: log in %s\n", folder.c_str());
        rows.push_back({{"shape", s.name},
                        {"verb", s.verb},
                        {"what", s.what},
                        {"exit_code", m.exitCode},
                        {"estimate_bytes", estimate},
                        {"peak_resident_bytes", m.peak_bytes},
                        {"peak_over_estimate", ratio},
                        {"seconds", m.seconds}});
        if (ran) fs::remove_all(folder);
    }
    std::error_code ec;
    if (ok) fs::remove_all(scratch, ec);
    std::printf("target: every peak within %.2fx of its estimate: %s\n",
                MEMORY_ESTIMATE_RATIO_BOUND, ok ? "met" : "MISSED");
    if (!opt.jsonPath.empty())
        writeTextAtomic(opt.jsonPath, nlohmann::json{{"rows", rows},
                                                     {"ratio_bound", MEMORY_ESTIMATE_RATIO_BOUND},
                                                     {"target_met", ok}}
                                              .dump(2) +
                                          "\n");
    return ok ? EXIT_OK : EXIT_UNMET;
}

}  // namespace gale::app
