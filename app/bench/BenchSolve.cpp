/// \file BenchSolve.cpp
/// `gale bench solve`: our MGPCG against OpenVDB's PCG on the same elliptic problem
/// (docs/solver.md, "Speed"). The accuracy study is in BenchAccuracy.cpp.

#include "app/bench/BenchSolve.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/PoissonSolver.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "app/bench/SvgPlot.h"
#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/io/Timing.h"
#include "base/Numbers.h"
#include "sim/SteadyWind.h"
#include "validation/ExactSolutions.h"

namespace gale::app {

// =================================================================================================
// Solver speed: the same elliptic problem for ours and OpenVDB's (and bench scale's).

std::vector<double> benchRhs(size_t n) {
    std::vector<double> b(n);
    uint64_t s = 0x9E3779B97F4A7C15ull;
    for (double& v : b) {
        s ^= s << 13, s ^= s >> 7, s ^= s << 17;
        v = double(s >> 11) / 9007199254740992.0 - 0.5;
    }
    return b;
}

sim::PoissonSystem benchSystem(int nx, int ny, int nz) {
    sim::PoissonSystem s = sim::PoissonSystem::uniformBox(nx, ny, nz);
    s.sides[sim::SIDE_ZMIN] = sim::BoundaryKind::Neumann;
    return s;
}

namespace {

/// What a child process reports back through a pipe (plain data).
struct RunResult {
    int ok = 0, converged = 0, iterations = 0, levels = 0;
    double relativeResidual = 0, setupSeconds = 0, solveSeconds = 0, totalSeconds = 0;
    double baselineRss_bytes = 0, peakRss_bytes = 0, heldBytes = 0;
    double solutionDifference = -1;  // max |x - x_ours| / max |x_ours|, OpenVDB runs only
    double triad_Bps = 0;
    double bytesPerCellIteration = 0;  // our traffic model for this problem
    char message[160] = {0};
};

double residentBytes() {
    std::ifstream f("/proc/self/statm");
    double pages = 0, resident = 0;
    f >> pages >> resident;
    return resident * double(sysconf(_SC_PAGESIZE));
}

double peakRssBytes() {
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return double(ru.ru_maxrss) * 1024.0;
}

/// Runs f in a forked child (so its peak memory is its own) and returns its RunResult; without
/// fork, runs in this process.
template <class F>
RunResult inChild(F&& f) {
    int fd[2];
    if (pipe(fd) != 0) return f();
    const pid_t pid = fork();
    if (pid < 0) {
        close(fd[0]), close(fd[1]);
        return f();
    }
    if (pid == 0) {
        close(fd[0]);
        RunResult r;
        try {
            r = f();
        } catch (const std::exception& e) {
            r.ok = 0;
            std::snprintf(r.message, sizeof r.message, "%s", e.what());
        }
        const char* p = reinterpret_cast<const char*>(&r);
        size_t left = sizeof r;
        while (left > 0) {
            const ssize_t w = write(fd[1], p, left);
            if (w <= 0) break;
            p += w, left -= size_t(w);
        }
        _exit(0);
    }
    close(fd[1]);
    RunResult r;
    char* p = reinterpret_cast<char*>(&r);
    size_t got = 0;
    while (got < sizeof r) {
        const ssize_t n = read(fd[0], p + got, sizeof r - got);
        if (n <= 0) break;
        got += size_t(n);
    }
    close(fd[0]);
    int status = 0;
    rusage ru{};
    wait4(pid, &status, 0, &ru);
    if (got != sizeof r) {
        r = RunResult{};
        std::snprintf(r.message, sizeof r.message, "child process failed (status %d)", status);
    }
    r.peakRss_bytes = double(ru.ru_maxrss) * 1024.0;
    return r;
}

RunResult runOurs(int nx, int ny, int nz, double tol) {
    RunResult r;
    r.baselineRss_bytes = residentBytes();
    const sim::PoissonSystem sys = benchSystem(nx, ny, nz);
    const std::vector<double> b = benchRhs(sys.cellCount());
    const auto t0 = Clock::now();
    sim::PoissonSolver solver(sys);
    std::vector<double> x;
    sim::SolverSettings set;
    set.relativeTolerance = tol;
    const sim::SolveReport rep = solver.solve(b, x, set);
    r.totalSeconds = secondsSince(t0);
    r.ok = 1, r.converged = rep.converged, r.iterations = rep.iterations, r.levels = rep.levels;
    r.relativeResidual = rep.relativeResidual, r.setupSeconds = rep.setupSeconds,
    r.solveSeconds = rep.solveSeconds;
    r.heldBytes = double(solver.memory_bytes());
    r.bytesPerCellIteration = sim::PoissonSolver::bytesPerCellPerIteration(
        set.smoothingSweeps, solver.uniformCellFraction());
    std::snprintf(r.message, sizeof r.message, "%s", rep.message.c_str());
    return r;
}

enum class VdbPrecond { Jacobi, IncompleteCholesky };

RunResult runOpenVdb(int nx, int ny, int nz, double tol, VdbPrecond pc) {
    using namespace openvdb;
    RunResult r;
    initialize();
    r.baselineRss_bytes = residentBytes();
    const sim::PoissonSystem sys = benchSystem(nx, ny, nz);
    const std::vector<double> b = benchRhs(sys.cellCount());
    const auto t0 = Clock::now();
    // OpenVDB solves L x = source with L the negative-definite Laplacian; ours is A = -L, so the
    // source is -b for the same x.
    DoubleTree source(0.0);
    {
        tree::ValueAccessor<DoubleTree> acc(source);
        for (int k = 0; k < nz; ++k)
            for (int j = 0; j < ny; ++j)
                for (int i = 0; i < nx; ++i)
                    acc.setValueOn(Coord(i, j, k), -b[sys.cellIndex(i, j, k)]);
    }
    // staggered = true selects OpenVDB's compact 7-point Laplacian (ours); its collocated variant
    // uses neighbours two voxels away (OPENVDB_TOOLS_POISSON_LAPLACIAN_STENCIL 2), another problem.
    // Out-of-domain neighbours: below the ground Neumann (the ghost equals the cell: nothing to
    // add); elsewhere Dirichlet 0 on the face, half a cell away (ghost = -x: diagonal -= 2).
    auto boundary = [](const Coord&, const Coord& nb, double&, double& diagonal) {
        if (nb.z() < 0) return;
        diagonal -= 2.0;
    };
    math::pcg::State state = math::pcg::terminationDefaults<double>();
    state.iterations = 20000;
    state.relativeError = tol;
    state.absoluteError = 0.0;
    util::NullInterrupter interrupter;
    DoubleTree::Ptr x;
    if (pc == VdbPrecond::Jacobi) {
        x = tools::poisson::solveWithBoundaryConditionsAndPreconditioner<
            math::pcg::JacobiPreconditioner<tools::poisson::LaplacianMatrix>>(source, boundary,
                                                                              state, interrupter,
                                                                              /*staggered=*/true);
    } else {
        x = tools::poisson::solveWithBoundaryConditions(source, boundary, state, interrupter,
                                                        /*staggered=*/true);
    }
    r.totalSeconds = r.solveSeconds = secondsSince(t0);
    r.peakRss_bytes = peakRssBytes();  // before our comparison solve below
    r.ok = 1, r.converged = state.success, r.iterations = state.iterations;
    r.relativeResidual = state.relativeError;
    // Same problem? Compare with ours solved tightly.
    sim::PoissonSolver ours(sys);
    std::vector<double> xo;
    sim::SolverSettings set;
    set.relativeTolerance = std::min(tol, 1e-8);
    (void)ours.solve(b, xo, set);
    double diff = 0, norm = 0;
    tree::ValueAccessor<const DoubleTree> acc(*x);
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const double v = xo[sys.cellIndex(i, j, k)];
                diff = std::max(diff, std::abs(acc.getValue(Coord(i, j, k)) - v));
                norm = std::max(norm, std::abs(v));
            }
    r.solutionDifference = diff / norm;
    std::snprintf(r.message, sizeof r.message, "%s",
                  state.success ? "converged" : "stopped (divergence guard or limit)");
    return r;
}

/// Best-of-5 STREAM-style triad a = b + s c over 3 x 128 MB, on all TBB threads.
RunResult runTriad() {
    RunResult r;
    const size_t n = size_t(1) << 24;
    std::vector<double> a(n, 1.0), b(n, 2.0), c(n, 3.0);
    double best = 0;
    for (int rep = 0; rep < 5; ++rep) {
        const auto t0 = Clock::now();
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 16),
                          [&](const tbb::blocked_range<size_t>& q) {
                              for (size_t i = q.begin(); i < q.end(); ++i) a[i] = b[i] + 1.5 * c[i];
                          });
        best = std::max(best, 3.0 * 8.0 * double(n) / secondsSince(t0));
    }
    r.ok = a[7] == 6.5;
    r.triad_Bps = best;
    return r;
}

}  // namespace

int runBenchSolve(const BenchSolveOptions& optIn) {
    BenchSolveOptions opt = optIn;
    if (opt.sizes.empty()) opt.sizes = {{64, 64, 32}, {128, 128, 64}, {256, 256, 64}};
    if (opt.quick) opt.sizes.resize(1);
    for (const auto& s : opt.sizes)
        if (s[0] < 2 || s[1] < 2 || s[2] < 2)
            throw std::invalid_argument("bench solve: sizes must be at least 2 cells per axis");
    if (!(opt.relativeTolerance > 0 && opt.relativeTolerance < 1))
        throw std::invalid_argument("bench solve: relativeTolerance must be in (0, 1)");
    const int sweeps = sim::SolverSettings{}.smoothingSweeps;
    const double bytesGeneral = sim::PoissonSolver::bytesPerCellPerIteration(sweeps, 0.0);

    // Timings on a shared machine mean little without its load: report it before and after.
    auto loadAverage = [] {
        std::ifstream f("/proc/loadavg");
        double l1 = -1;
        f >> l1;
        return l1;
    };
    const double loadBefore = loadAverage();
    std::fprintf(stderr, "bench solve: measuring triad bandwidth...\n");
    const RunResult triad = inChild(runTriad);
    const double bw = triad.triad_Bps > 0 ? triad.triad_Bps : 1e10;
    const double baseline = inChild([] {
                                RunResult r;
                                r.ok = 1;
                                return r;
                            }).peakRss_bytes;

    struct Row {
        std::array<int, 3> size;
        std::string solver;
        RunResult r;
    };
    std::vector<Row> rows;
    for (const auto& s : opt.sizes) {
        const std::string name =
            std::to_string(s[0]) + "x" + std::to_string(s[1]) + "x" + std::to_string(s[2]);
        std::fprintf(stderr, "bench solve: %s ours (MGPCG)...\n", name.c_str());
        rows.push_back({s, "gale MGPCG",
                        inChild([&] { return runOurs(s[0], s[1], s[2], opt.relativeTolerance); })});
        if (opt.openVdb) {
            std::fprintf(stderr, "bench solve: %s OpenVDB Jacobi-PCG...\n", name.c_str());
            rows.push_back({s, "openvdb Jacobi-PCG", inChild([&] {
                                return runOpenVdb(s[0], s[1], s[2], opt.relativeTolerance,
                                                  VdbPrecond::Jacobi);
                            })});
            std::fprintf(stderr, "bench solve: %s OpenVDB IC-PCG (poisson::solve default)...\n",
                         name.c_str());
            rows.push_back({s, "openvdb IC-PCG", inChild([&] {
                                return runOpenVdb(s[0], s[1], s[2], opt.relativeTolerance,
                                                  VdbPrecond::IncompleteCholesky);
                            })});
        }
    }

    std::printf(
        "Same elliptic problem for every solver: box of unit cells, 7-point Laplacian, Dirichlet 0 "
        "on the\n"
        "faces of the sides and top, Neumann ground, pseudo-random right-hand side; stop at "
        "max-norm\n"
        "relative residual %.0e. Peak memory = the solver process's peak RSS minus an idle child's "
        "(%.0f MB).\n"
        "Triad bandwidth %.1f GB/s. Floor = our traffic model (bytes per cell per iteration, "
        "V(%d,%d): %.0f with\n"
        "every weight read, less on full-open cells; per row below) x cells x iterations / triad "
        "bandwidth.\n\n",
        opt.relativeTolerance, baseline / 1e6, bw / 1e9, sweeps, sweeps, bytesGeneral);
    std::printf("%-12s %-19s %5s %5s %9s %8s %8s %8s %8s %10s %9s %8s %9s\n", "size", "solver",
                "its", "conv", "rel.res", "setup s", "solve s", "total s", "peak MB", "MiB/Mcell",
                "vs gale", "floor s", "x floor");
    nlohmann::json j;
    j["triad_GBps"] = bw / 1e9;
    j["bytes_per_cell_per_iteration_all_weights"] = bytesGeneral;
    j["relative_tolerance"] = opt.relativeTolerance;
    bool allConverged = true;
    int itsFirst = -1, itsLast = -1;
    double oursTotal = 0;
    for (const Row& row : rows) {
        const RunResult& r = row.r;
        const double cells = double(row.size[0]) * row.size[1] * row.size[2];
        const bool ours = row.solver == "gale MGPCG";
        const std::string name = std::to_string(row.size[0]) + "x" + std::to_string(row.size[1]) +
                                 "x" + std::to_string(row.size[2]);
        double floorS = 0;
        if (ours) {
            oursTotal = r.totalSeconds;
            floorS = r.bytesPerCellIteration * cells * r.iterations / bw;
            allConverged = allConverged && r.converged;
            if (itsFirst < 0) itsFirst = r.iterations;
            itsLast = r.iterations;
        }
        const double peakMB = std::max(0.0, r.peakRss_bytes - baseline) / 1e6;
        // The peak per million cells of the box, in MiB: comparable across sizes and solvers.
        const double peakMiBPerMillionCells = peakMB * 1e6 / MIB / (cells / 1e6);
        std::printf("%-12s %-19s %5d %5s %9.1e %8.3f %8.3f %8.3f %8.0f %10.1f %9s %8s %9s%s\n",
                    name.c_str(), row.solver.c_str(), r.iterations, r.converged ? "yes" : "NO",
                    r.relativeResidual, r.setupSeconds, r.solveSeconds, r.totalSeconds, peakMB,
                    peakMiBPerMillionCells,
                    ours ? "1" : (formatG(r.totalSeconds / oursTotal, 3) + "x").c_str(),
                    ours ? formatG(floorS, 3).c_str() : "",
                    ours ? formatG(r.solveSeconds / floorS, 3).c_str() : "",
                    r.ok ? "" : (std::string("  FAILED: ") + r.message).c_str());
        if (ours)
            std::printf("%-12s %-19s traffic model %.0f B/cell/iteration, %.0f ms/iteration\n", "",
                        "", r.bytesPerCellIteration,
                        1e3 * r.solveSeconds / std::max(1, r.iterations));
        if (!ours && r.solutionDifference >= 0 && !std::isnan(r.solutionDifference))
            std::printf("%-12s %-19s max |x - x_gale| / max |x_gale| = %.1e (%s)\n", "", "",
                        r.solutionDifference, r.message);
        j["rows"].push_back({{"size", row.size},
                             {"solver", row.solver},
                             {"iterations", r.iterations},
                             {"converged", bool(r.converged)},
                             {"relative_residual", r.relativeResidual},
                             {"setup_s", r.setupSeconds},
                             {"solve_s", r.solveSeconds},
                             {"total_s", r.totalSeconds},
                             {"peak_rss_MB", peakMB},
                             {"peak_mib_per_million_cells", peakMiBPerMillionCells},
                             {"held_MB", r.heldBytes / 1e6},
                             {"ratio_to_gale_total", ours ? 1.0 : r.totalSeconds / oursTotal},
                             {"floor_s", floorS},
                             {"bytes_per_cell_per_iteration", r.bytesPerCellIteration},
                             {"solution_difference", r.solutionDifference},
                             {"message", r.message}});
    }
    const double loadAfter = loadAverage();
    std::printf(
        "\nLoad average (1 min) before / after: %.2f / %.2f on %ld cores: above the core count, "
        "times are\n"
        "inflated for every solver alike, and the floor ratio grows.\n",
        loadBefore, loadAfter, sysconf(_SC_NPROCESSORS_ONLN));
    j["load_average_before"] = loadBefore;
    j["load_average_after"] = loadAfter;
    if (itsFirst > 0)
        std::printf("\nIteration growth smallest -> largest: %d -> %d (%.2fx; target <= 1.5x)\n",
                    itsFirst, itsLast, double(itsLast) / itsFirst);
    j["iteration_growth"] = itsFirst > 0 ? double(itsLast) / itsFirst : 0.0;
    if (!opt.jsonPath.empty()) writeTextAtomic(opt.jsonPath, j.dump(2) + "\n");
    return allConverged ? EXIT_OK : EXIT_UNMET;
}

}  // namespace gale::app
