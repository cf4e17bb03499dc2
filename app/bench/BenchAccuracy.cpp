/// \file BenchAccuracy.cpp
/// `gale bench accuracy`: error against run time of the steady solver on the exact hemisphere
/// (docs/solver.md, "Accuracy against run time"). Declared in BenchSolve.h.

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

#include "app/bench/BenchSolve.h"
#include "app/bench/SvgPlot.h"
#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/io/Timing.h"
#include "base/Numbers.h"
#include "sim/SteadyWind.h"
#include "validation/AcceptanceLimits.h"
#include "validation/ExactSolutions.h"

namespace gale::app {
namespace {

namespace exact = validation::exact;

using gale::PI;

// =================================================================================================
// Hemisphere of radius R on flat ground in a uniform wind U along +x: by symmetry the sphere in a
// free stream, u = U e_x + grad(phi), phi = U R^3 cos(theta) / (2 r^2) = U R^3 X / (2 r^3)
// (Sherman 1978 with equal weights). The box [0, 2L]^2 x [0, T] carries the exact potential on
// its open faces (Dirichlet psi = phi), so the box size adds no truncation error; the ground is
// the symmetry plane.
struct Hemisphere {
    double R = 1.0;          ///< radius, m
    double U = 1.0;          ///< free stream, m/s
    double halfWidth = 3.0;  ///< L, m (3 R)
    double top = 3.0;        ///< T, m (3 R)
    double c() const { return halfWidth; }
    exact::HemisphereFlow flow() const { return {R, U, c(), c()}; }
    double phi(double x, double y, double z) const { return flow().phi(x, y, z); }
    std::array<double, 3> velocity(double x, double y, double z) const {
        return flow().velocity(x, y, z);
    }
    std::vector<std::array<double, 3>> nearPoints() const { return flow().nearPoints(); }
};

struct AccuracyRow {
    int cellsPerRadius = 0;
    bool cutCells = true;  ///< false: the stair-step comparison rows
    double tolerance = 0;
    size_t boxCells = 0, activeCells = 0;
    int iterations = 0;
    bool converged = false;
    double relativeResidual = 0, maxDivergenceScaled = 0;
    double domainSeconds = 0, setupSeconds = 0, solveSeconds = 0, assemblySeconds = 0,
           totalSeconds = 0;
    double nearL2 = 0, nearMax = 0, domainL2 = 0, domainMax = 0;
    size_t nearPoints = 0, domainFaces = 0;
};

/// Least-squares slope of log(error) against log(cells per radius): the observed order.
double observedOrder(const std::vector<std::pair<int, double>>& nErr) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double n = double(nErr.size());
    for (const auto& [N, e] : nErr) {
        const double x = std::log(double(N)), y = std::log(e);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace

int runBenchAccuracy(const BenchAccuracyOptions& opt) {
    const Hemisphere H;
    const std::vector<int> resolutions =
        opt.quick ? std::vector<int>{4, 8, 16} : std::vector<int>{4, 8, 16, 32};
    const std::vector<double> tolerances =
        opt.quick ? std::vector<double>{1e-6} : std::vector<double>{1e-1, 1e-3, 1e-6};
    // Terrain: the verification kind, sampled at R/256 (finer than the fraction sub-samples at
    // 32 cells per radius, h/8 = R/256), the same heightfield at every resolution.
    sim::TerrainSpec ts;
    ts.kind = sim::TerrainKind::Hemisphere;
    ts.sizeX_m = ts.sizeY_m = 2 * H.halfWidth;
    ts.spacing_m = H.R / 256;
    ts.radius_m = H.R;
    ts.centerX_m = ts.centerY_m = H.c();
    const sim::Heightfield hf = sim::makeTerrain(ts);
    const auto points = H.nearPoints();
    sim::AmbientWind ambient;
    ambient.profile = sim::WindProfile::Uniform;
    ambient.speed_mps = H.U;
    const sim::BoundaryPotential farField = [&](double x, double y, double z) {
        return H.phi(x, y, z);
    };

    std::vector<AccuracyRow> rows;
    // The full run adds stair-step rows (every open fraction rounded to 0 or 1) at the tightest
    // tolerance: the same study without cut cells.
    const std::vector<bool> boundaryModes =
        opt.quick ? std::vector<bool>{true} : std::vector<bool>{true, false};
    for (bool cut : boundaryModes)
        for (int N : resolutions) {
            const auto t0 = Clock::now();
            sim::DomainSpec spec{H.R / N, /*top_m=*/H.top, /*memoryLimit_bytes=*/8e9};
            spec.cutCells = cut;
            sim::AirDomain domain(hf, spec);
            const double domainSeconds = secondsSince(t0);
            sim::SteadyWindSolver solver(domain);
            for (double tol : tolerances) {
                if (!cut && tol != tolerances.back()) continue;
                solver.setWarmStart({});  // every row from a cold start: its time is its own
                sim::SolverSettings set;
                set.relativeTolerance = tol;
                set.maxIterations = 200;
                const sim::SteadyWindResult res = solver.solve(ambient, set, farField);
                AccuracyRow r;
                r.cellsPerRadius = N, r.tolerance = tol, r.cutCells = cut;
                r.boxCells = domain.boxCellCount(), r.activeCells = domain.activeCellCount();
                r.iterations = res.report.iterations, r.converged = res.report.converged;
                r.relativeResidual = res.report.relativeResidual,
                r.maxDivergenceScaled = res.report.maxDivergenceScaled;
                r.domainSeconds = domainSeconds, r.setupSeconds = res.report.setupSeconds;
                r.solveSeconds = res.report.solveSeconds, r.assemblySeconds = res.assemblySeconds;
                r.totalSeconds =
                    r.domainSeconds + r.setupSeconds + r.solveSeconds + r.assemblySeconds;
                // Near the surface, at the fixed points.
                double e2 = 0, n2 = 0;
                for (const auto& p : points) {
                    const auto u = res.field.velocityAt_mps(p[0], p[1], p[2]);
                    const auto ue = H.velocity(p[0], p[1], p[2]);
                    double d = 0;
                    for (int q = 0; q < 3; ++q)
                        d += (u[q] - ue[q]) * (u[q] - ue[q]), n2 += ue[q] * ue[q];
                    e2 += d;
                    r.nearMax = std::max(r.nearMax, std::sqrt(d) / H.U);
                }
                r.nearL2 = std::sqrt(e2 / n2), r.nearPoints = points.size();
                // Whole domain: every fully open interior face, its own component at its centre.
                const double h = domain.voxelSize_m();
                const auto o = domain.wsMin_m();
                const sim::PoissonSystem& S = solver.system();
                double d2 = 0, m2 = 0;
                size_t faces = 0;
                auto face = [&](double value, double exact) {
                    d2 += (value - exact) * (value - exact), m2 += exact * exact, ++faces;
                    r.domainMax = std::max(r.domainMax, std::abs(value - exact) / H.U);
                };
                for (int k = 0; k < domain.nz(); ++k)
                    for (int j = 0; j < domain.ny(); ++j)
                        for (int i = 0; i < domain.nx(); ++i) {
                            const double x = o[0] + (i + 0.5) * h, y = o[1] + (j + 0.5) * h,
                                         z = o[2] + (k + 0.5) * h;
                            if (i > 0 && domain.openFractionX(i, j, k) == 1.f)
                                face(res.field.u_mps()[S.faceXIndex(i, j, k)],
                                     H.velocity(x - 0.5 * h, y, z)[0]);
                            if (j > 0 && domain.openFractionY(i, j, k) == 1.f)
                                face(res.field.v_mps()[S.faceYIndex(i, j, k)],
                                     H.velocity(x, y - 0.5 * h, z)[1]);
                            if (k > 0 && domain.openFractionZ(i, j, k) == 1.f)
                                face(res.field.w_mps()[S.faceZIndex(i, j, k)],
                                     H.velocity(x, y, z - 0.5 * h)[2]);
                        }
                r.domainL2 = std::sqrt(d2 / m2), r.domainFaces = faces;
                rows.push_back(r);
                std::fprintf(
                    stderr,
                    "bench accuracy: %s, %d cells/R, tol %.0e: %d its, near L2 %.2e, %.2f s\n",
                    cut ? "cut cells" : "stair-steps", N, tol, r.iterations, r.nearL2,
                    r.totalSeconds);
            }
        }

    // ---- tables --------------------------------------------------------------------------------
    std::printf(
        "Hemisphere R = 1 m on flat ground, uniform U = 1 m/s, potential flow (a_h = a_v);\n"
        "box 6R x 6R x 3R with the exact potential on its open faces; cut cells (stair-step rows "
        "for comparison).\n"
        "near = 193 fixed points 0.1 R above the surface; domain = every fully open face.\n\n");
    std::printf("%-6s %5s %7s %9s %4s %9s %10s %10s %10s %10s %8s %8s\n", "bound.", "N/R", "tol",
                "cells", "its", "rel.res", "near L2", "near max", "dom L2", "dom max", "solve s",
                "total s");
    for (const AccuracyRow& r : rows)
        std::printf("%-6s %5d %7.0e %9zu %4d %9.1e %10.3e %10.3e %10.3e %10.3e %8.3f %8.3f%s\n",
                    r.cutCells ? "cut" : "stair", r.cellsPerRadius, r.tolerance, r.boxCells,
                    r.iterations, r.relativeResidual, r.nearL2, r.nearMax, r.domainL2, r.domainMax,
                    r.setupSeconds + r.solveSeconds, r.totalSeconds,
                    r.converged ? "" : "  NOT CONVERGED");
    // Orders at the tightest tolerance.
    const double tightest = tolerances.back();
    std::vector<std::pair<int, double>> nearL2, nearMax, domL2, domMax, stairL2;
    for (const AccuracyRow& r : rows)
        if (!r.cutCells) stairL2.push_back({r.cellsPerRadius, r.nearL2});
    for (const AccuracyRow& r : rows)
        if (r.tolerance == tightest && r.cutCells) {
            nearL2.push_back({r.cellsPerRadius, r.nearL2}),
                nearMax.push_back({r.cellsPerRadius, r.nearMax});
            domL2.push_back({r.cellsPerRadius, r.domainL2}),
                domMax.push_back({r.cellsPerRadius, r.domainMax});
        }
    std::printf("\nObserved order (tol %.0e), pairwise and least squares over all resolutions:\n",
                tightest);
    auto printOrders = [&](const char* name, const std::vector<std::pair<int, double>>& v) {
        std::printf("  %-9s", name);
        for (size_t n = 1; n < v.size(); ++n)
            std::printf("  %d->%d: %.2f", v[n - 1].first, v[n].first,
                        std::log(v[n - 1].second / v[n].second) /
                            std::log(double(v[n].first) / v[n - 1].first));
        std::printf("  | fit: %.2f\n", observedOrder(v));
    };
    printOrders("near L2", nearL2);
    printOrders("near max", nearMax);
    printOrders("dom L2", domL2);
    printOrders("dom max", domMax);
    if (!stairL2.empty()) {
        std::printf("Stair-steps (every fraction rounded to 0 or 1), same tolerance:\n");
        printOrders("near L2", stairL2);
    }
    double nearAt16 = -1;
    for (const auto& [N, e] : nearL2)
        if (N == 16) nearAt16 = e;
    const double order = observedOrder(nearL2);
    // The targets and their reasons: validation/AcceptanceLimits.h.
    const double target16 = validation::limits::TARGET_HEMISPHERE_ERROR_AT_16;
    const double minOrder = validation::limits::MIN_HEMISPHERE_ORDER;
    const bool ok = nearAt16 >= 0 && nearAt16 <= target16 && order >= minOrder;
    std::printf(
        "\nTargets: near-surface rel. L2 <= %.0f%% at 16 cells/R: %.3f%% %s; observed order >= "
        "%.1f: %.2f %s\n",
        100 * target16, 100 * nearAt16, nearAt16 <= target16 ? "(met)" : "(MISSED)", minOrder,
        order, order >= minOrder ? "(met)" : "(MISSED)");

    // ---- files ---------------------------------------------------------------------------------
    std::filesystem::create_directories(opt.outputFolder);
    std::ostringstream csv;
    csv << "boundary,cells_per_radius,tolerance,box_cells,active_cells,iterations,converged,"
           "relative_residual,"
           "max_div_scaled,near_rel_l2,near_max_rel,domain_rel_l2,domain_max_rel,domain_s,setup_s,"
           "solve_s,"
           "assembly_s,total_s\n";
    for (const AccuracyRow& r : rows)
        csv << (r.cutCells ? "cut" : "stair") << "," << r.cellsPerRadius << "," << r.tolerance
            << "," << r.boxCells << "," << r.activeCells << "," << r.iterations << ","
            << r.converged << "," << r.relativeResidual << "," << r.maxDivergenceScaled << ","
            << r.nearL2 << "," << r.nearMax << "," << r.domainL2 << "," << r.domainMax << ","
            << r.domainSeconds << "," << r.setupSeconds << "," << r.solveSeconds << ","
            << r.assemblySeconds << "," << r.totalSeconds << "\n";
    writeTextAtomic(opt.outputFolder + "/accuracy.csv", csv.str());
    const char* colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd"};
    std::vector<Series> series;
    for (size_t t = 0; t < tolerances.size(); ++t) {
        Series l2{"near L2, tol " + formatG(tolerances[t], 1), colours[t % 5], false, {}, {}};
        Series mx{"near max, tol " + formatG(tolerances[t], 1), colours[t % 5], true, {}, {}};
        for (const AccuracyRow& r : rows)
            if (r.tolerance == tolerances[t] && r.cutCells) {
                l2.xy.push_back({r.totalSeconds, r.nearL2}),
                    l2.labels.push_back(std::to_string(r.cellsPerRadius) + "/R");
                mx.xy.push_back({r.totalSeconds, r.nearMax});
            }
        series.push_back(l2), series.push_back(mx);
    }
    Series dom{"domain L2, tol " + formatG(tightest, 1), colours[3], false, {}, {}};
    for (const AccuracyRow& r : rows)
        if (r.tolerance == tightest && r.cutCells) dom.xy.push_back({r.totalSeconds, r.domainL2});
    series.push_back(dom);
    Series stair{"near L2, stair-steps, tol " + formatG(tightest, 1), colours[4], true, {}, {}};
    for (const AccuracyRow& r : rows)
        if (!r.cutCells)
            stair.xy.push_back({r.totalSeconds, r.nearL2}),
                stair.labels.push_back(std::to_string(r.cellsPerRadius) + "/R");
    if (!stair.xy.empty()) series.push_back(stair);
    writeTextAtomic(opt.outputFolder + "/accuracy.svg",
                    logLogSvg("Hemisphere: velocity error against wall time",
                              "wall time (domain + solve), s", "relative error", series));
    std::fprintf(stderr, "bench accuracy: wrote %s/accuracy.csv and accuracy.svg\n",
                 opt.outputFolder.c_str());
    if (!opt.jsonPath.empty()) {
        nlohmann::json j;
        j["case"] = "hemisphere R=1 m, U=1 m/s, box 6R x 6R x 3R, exact far field on open faces";
        j["observed_order_near_l2"] = order;
        j["observed_order_near_max"] = observedOrder(nearMax);
        j["observed_order_domain_l2"] = observedOrder(domL2);
        if (!stairL2.empty()) j["observed_order_near_l2_stair_steps"] = observedOrder(stairL2);
        j["near_l2_at_16"] = nearAt16;
        j["targets_met"] = ok;
        for (const AccuracyRow& r : rows)
            j["rows"].push_back({{"boundary", r.cutCells ? "cut" : "stair"},
                                 {"cells_per_radius", r.cellsPerRadius},
                                 {"tolerance", r.tolerance},
                                 {"box_cells", r.boxCells},
                                 {"active_cells", r.activeCells},
                                 {"iterations", r.iterations},
                                 {"converged", r.converged},
                                 {"relative_residual", r.relativeResidual},
                                 {"max_div_scaled", r.maxDivergenceScaled},
                                 {"near_rel_l2", r.nearL2},
                                 {"near_max_rel", r.nearMax},
                                 {"domain_rel_l2", r.domainL2},
                                 {"domain_max_rel", r.domainMax},
                                 {"total_s", r.totalSeconds},
                                 {"solve_s", r.solveSeconds},
                                 {"setup_s", r.setupSeconds}});
        writeTextAtomic(opt.jsonPath, j.dump(2) + "\n");
    }
    return ok ? EXIT_OK : EXIT_UNMET;
}

}  // namespace gale::app
