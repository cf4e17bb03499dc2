/// \file BenchModels.cpp
/// `gale bench models` (BenchModels.h).
#include "app/bench/BenchModels.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "app/bench/SvgPlot.h"
#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/io/Timing.h"
#include "base/Numbers.h"
#include "sim/MomentumWind.h"
#include "sim/SteadyWind.h"
#include "validation/CaoTamuraStudy.h"
#include "validation/HemisphereStudy.h"

namespace gale::app {
namespace {

using validation::RidgeMeasurement;
namespace ridge = validation::ridge;

/// The validation line: the copy embedded in the program, or the file given by --data.
std::vector<RidgeMeasurement> readValidation(const std::string& path) {
    try {
        if (path.empty()) return validation::caoTamuraMeasurements();
        std::ifstream in(path);
        if (!in) throw InputError("--data: " + path + ": cannot read the validation data");
        std::ostringstream text;
        text << in.rdbuf();
        return validation::parseRidgeMeasurements(text.str(), path);
    } catch (const std::invalid_argument& e) {
        throw InputError(e.what());
    }
}

/// One row of the table.
struct Row {
    std::string model, testCase, resolution;
    int nx = 0, ny = 0, nz = 0;
    int iterations = 0;
    bool converged = false;
    double seconds = 0;
    double error = 0;           ///< the case's error measure (see errorName)
    std::string errorName;      ///< what error is
    double crestSpeedup = NAN;  ///< ridge only: model's speed-up at the crest, dz = 0.25 H
    double leeSpeedup = NAN;    ///< ridge only: at the lee foot (2.5 H), dz = 1.0 H
    double cfl = NAN;           ///< momentum only: the pseudo-time step's cfl
    /// Ridge only, against the free stream instead of the windward foot: u / U_inf of the model
    /// at the crest and at the windward foot (dz = 0.25 H), and the RMS of model minus measured
    /// u / U_inf over every measured point, the foot's included.
    double crestUinf = NAN, footUinf = NAN, rmsUinf = NAN;
    /// Flat only: |u - log law| / log law of the field read (WindField::velocityAt_mps) 1 m and
    /// 2 m above the ground.
    double error1m = NAN, error2m = NAN;
    /// Ridge only: measured lee deficits (x > 0, speed-up < 0), of them the model's of the same
    /// sign, and of them within LEE_DEFICIT_TOLERANCE of the measurement.
    int leePoints = 0, leeSameSign = 0, leeWithin = 0;
    /// Ridge only: the crest's speed-up at 0.25, 0.48 and 0.98 H (the measured crest heights).
    double crestSpeedups[3] = {NAN, NAN, NAN};
    /// Ridge only: the RMS speed-up error split at the crest, over the windward points and crest
    /// (x <= 0) and over the lee points (x > 0).
    double rmsWindward = NAN, rmsLee = NAN;
};

using validation::MEASURED_CREST_SPEEDUP;
using validation::MEASURED_CREST_UINF_025H;
using validation::MEASURED_FOOT_UINF_025H;
using validation::MEASURED_LEE_FOOT_SPEEDUP;

// ---- the ridge of Cao and Tamura (2006), scaled to H = 40 m (validation/CaoTamuraStudy.h) ------

/// Runs one model on the ridge at H / h = cellsPerH (momentum: pseudo-time step cfl) with the
/// given inflow (the published one unless stated), compares with the measured line.
Row runRidge(bool momentum, int cellsPerH, const std::vector<RidgeMeasurement>& data,
             int maxIterations, double cfl = 2.0, ridge::Inflow inflow = ridge::Inflow::Published,
             sim::PseudoTimeAdvection advection = sim::PseudoTimeAdvection::SemiLagrangian,
             sim::TurbulenceClosure closure = sim::TurbulenceClosure::MixingLength) {
    validation::CaoTamuraOptions o;
    o.momentum = momentum, o.cellsPerH = cellsPerH, o.maxIterations = maxIterations;
    o.cfl = cfl, o.inflow = inflow, o.advection = advection, o.turbulence = closure;
    const validation::CaoTamuraStudy s = validation::runCaoTamura(o, data);
    Row r;
    r.seconds = s.seconds;
    r.model = momentum ? "momentum" : "mass_consistent";
    r.testCase = inflow == ridge::Inflow::Published ? "ridge (Cao, Tamura 2006)"
                                                    : "ridge, foot-fit inflow (history)";
    if (advection == sim::PseudoTimeAdvection::Eulerian) r.testCase = "ridge, Eulerian step";
    if (closure != sim::TurbulenceClosure::MixingLength)
        r.testCase += std::string(", ") + sim::turbulenceClosureName(closure);
    r.resolution = "H/h=" + std::to_string(cellsPerH);
    r.nx = s.nx, r.ny = s.ny, r.nz = s.nz;
    r.iterations = s.iterations;
    r.converged = s.converged;
    r.cfl = s.cfl;
    for (const validation::CaoTamuraStudy::Level& l : s.levels)
        std::fprintf(stderr, "  level %d (%g m): %d steps, residual %.2e, %s\n", l.level,
                     l.voxelSize_m, l.iterations, l.momentumResidual,
                     l.converged ? "converged" : "not converged");
    r.error = s.rmsSpeedupError;
    r.rmsLee = s.rmsLee, r.rmsWindward = s.rmsWindward;
    r.errorName = "RMS speed-up error, " + std::to_string(s.points) + " points";
    r.crestSpeedup = s.crestSpeedup, r.leeSpeedup = s.leeSpeedup;
    r.leePoints = s.leePoints, r.leeSameSign = s.leeSameSign, r.leeWithin = s.leeWithin;
    r.rmsUinf = s.rmsUinf, r.crestUinf = s.crestUinf, r.footUinf = s.footUinf;
    for (int i = 0; i < 3; ++i) r.crestSpeedups[i] = s.crestSpeedups[i];
    return r;
}

// ---- flat rough ground: the log law (momentum) --------------------------------------------------

/// The flat case in cells of edge h; with first_m, on stretched layers from that thickness
/// (ratio 1.2), h horizontally.
Row runFlat(double h, std::optional<double> first_m = std::nullopt) {
    const double z0 = 0.03, uRef = 5.0, zRef = 10.0;
    sim::TerrainSpec t;
    t.kind = sim::TerrainKind::Flat;
    t.sizeX_m = 120, t.sizeY_m = 4 * h, t.spacing_m = h / 2;
    const sim::Heightfield terrain = sim::makeTerrain(t);
    sim::DomainSpec spec;
    spec.voxelSize_m = h;
    spec.top_m = 60.0;
    spec.momentumModel = true;
    spec.firstCell_m = first_m;
    sim::AmbientWind wind;
    wind.profile = sim::WindProfile::LogLaw;
    wind.speed_mps = uRef, wind.referenceHeight_m = zRef, wind.roughness_m = z0;
    const auto t0 = Clock::now();
    const sim::AirDomain domain(terrain, spec);
    const sim::MomentumWindResult res = sim::solveMomentumWind(domain, wind, {});
    Row r;
    r.seconds = secondsSince(t0);
    r.model = "momentum", r.testCase = "flat log law";
    r.resolution = "h=" + formatG(h, 3) + " m" + (first_m ? ", dz0=" + formatG(*first_m, 3) : "");
    r.nx = domain.nx(), r.ny = domain.ny(), r.nz = domain.nz();
    r.iterations = res.report.iterations, r.converged = res.report.converged;
    const double uStar = sim::surface::frictionVelocity_mps(uRef, zRef, z0);
    const double x = terrain.sizeX_m() / 2, y = terrain.sizeY_m() / 2;
    for (int k = 0; k < domain.nz(); ++k) {
        const double zc = domain.layout().zCentre_m(k);  // the x-faces' height: no interpolation
        if (zc < 1.0 || zc > 50.0) continue;
        const double exact = sim::surface::logLawSpeed_mps(uStar, zc, z0);
        r.error =
            std::max(r.error, std::abs(res.field.velocityAt_mps(x, y, zc)[0] - exact) / exact);
    }
    r.errorName = "max |u - log law| / log law, 1-50 m";
    auto errorAt = [&](double z) {
        const double exact = sim::surface::logLawSpeed_mps(uStar, z, z0);
        return std::abs(res.field.velocityAt_mps(x, y, z)[0] - exact) / exact;
    };
    r.error1m = errorAt(1.0), r.error2m = errorAt(2.0);
    return r;
}

// ---- hemisphere: exact potential flow (mass-consistent) -----------------------------------------

Row runHemisphere(int cellsPerRadius) {
    const validation::HemisphereStudy s = validation::runHemisphere({cellsPerRadius});
    Row r;
    r.seconds = s.seconds;
    r.model = "mass_consistent", r.testCase = "hemisphere potential flow";
    r.resolution = "R/h=" + std::to_string(cellsPerRadius);
    r.nx = s.nx, r.ny = s.ny, r.nz = s.nz;
    r.iterations = s.iterations, r.converged = s.converged;
    r.error = s.nearL2;
    r.errorName = "near-surface L2 / |u|, 193 points 0.1 R up";
    return r;
}

}  // namespace

int runBenchModels(const BenchModelsOptions& opt) {
    if (opt.crestStudy) return runCrestStudy(/*cellsPerH=*/5);
    if (opt.jacksonHunt) return runJacksonHuntStudy();
    if (opt.pseudoTime) return runPseudoTimeStudy();
    if (opt.separation) return runSeparationStudy(opt);
    const std::vector<RidgeMeasurement> data = readValidation(opt.validationCsv);
    const std::vector<int> ridgeRes = !opt.ridgeCellsPerH.empty() ? opt.ridgeCellsPerH
                                      : opt.quick                 ? std::vector<int>{5}
                                                                  : std::vector<int>{5, 10};
    // Pseudo-time steps per level at most: the quick run is a smoke test of the table.
    const int ridgeIterations = opt.ridgeIterations > 0 ? opt.ridgeIterations
                                : opt.quick             ? 300
                                                        : 1000;
    const std::vector<int> hemiRes = opt.quick ? std::vector<int>{4} : std::vector<int>{4, 8, 16};
    const std::vector<double> flatRes =
        opt.quick ? std::vector<double>{4.0} : std::vector<double>{4.0, 2.0, 1.0};

    std::vector<Row> rows;
    auto add = [&](Row r) {
        std::fprintf(stderr, "bench models: %s, %s, %s: %d iterations, %.2f s, error %.3g\n",
                     r.model.c_str(), r.testCase.c_str(), r.resolution.c_str(), r.iterations,
                     r.seconds, r.error);
        rows.push_back(std::move(r));
    };
    for (int n : hemiRes) add(runHemisphere(n));
    for (double h : flatRes) add(runFlat(h));
    // The near-ground gain of stretched layers: 4 m cells with a 1 m first layer.
    add(runFlat(4.0, 1.0));
    std::vector<sim::TurbulenceClosure> closures = {sim::TurbulenceClosure::MixingLength};
    if (opt.closures)
        closures.insert(closures.end(),
                        {sim::TurbulenceClosure::KEpsilon, sim::TurbulenceClosure::KOmegaSst});
    for (int n : ridgeRes) {
        add(runRidge(false, n, data, ridgeIterations));
        for (sim::TurbulenceClosure c : closures) {
            add(runRidge(true, n, data, ridgeIterations, 2.0, ridge::Inflow::Published,
                         sim::PseudoTimeAdvection::SemiLagrangian, c));
            if (opt.eulerianRidge)
                add(runRidge(true, n, data, ridgeIterations, 2.0, ridge::Inflow::Published,
                             sim::PseudoTimeAdvection::Eulerian, c));
        }
    }
    // History: the earlier inflow, a log fit to the measured (already slowed) windward foot (the
    // full run only: the CI smoke run stays as short as before).
    if (!opt.quick) add(runRidge(true, 5, data, ridgeIterations, 2.0, ridge::Inflow::FootFit));

    std::printf("Both steady models: error against run time (docs/validation.md).\n");
    std::printf("%-16s %-33s %-12s %11s %6s %5s %9s %10s %6s %6s  %s\n", "model", "case", "res.",
                "cells", "iters", "conv", "seconds", "error", "crest", "lee", "error measure");
    bool ok = true;
    std::ostringstream csv;
    csv << "model,case,resolution,nx,ny,nz,iterations,converged,seconds,error,error_measure,"
           "crest_speedup\n";
    nlohmann::json jrows = nlohmann::json::array();
    for (const Row& r : rows) {
        if (r.model == "momentum" && (!r.converged || !std::isfinite(r.error))) ok = false;
        char cells[48];
        std::snprintf(cells, sizeof cells, "%dx%dx%d", r.nx, r.ny, r.nz);
        const std::string crest = std::isnan(r.crestSpeedup) ? "" : formatFixed(r.crestSpeedup, 2);
        const std::string lee = std::isnan(r.leeSpeedup) ? "" : formatFixed(r.leeSpeedup, 2);
        std::printf("%-16s %-33s %-12s %11s %6d %5s %9.2f %10.3e %6s %6s  %s\n", r.model.c_str(),
                    r.testCase.c_str(), r.resolution.c_str(), cells, r.iterations,
                    r.converged ? "yes" : "NO", r.seconds, r.error, crest.c_str(), lee.c_str(),
                    r.errorName.c_str());
        csv << r.model << ',' << r.testCase << ',' << r.resolution << ',' << r.nx << ',' << r.ny
            << ',' << r.nz << ',' << r.iterations << ',' << (r.converged ? 1 : 0) << ','
            << r.seconds << ',' << r.error << ",\"" << r.errorName << "\"," << crest << '\n';
        jrows.push_back(
            {{"model", r.model},
             {"case", r.testCase},
             {"resolution", r.resolution},
             {"cells", {r.nx, r.ny, r.nz}},
             {"iterations", r.iterations},
             {"converged", r.converged},
             {"seconds", r.seconds},
             {"error", r.error},
             {"error_measure", r.errorName},
             {"crest_speedup", std::isnan(r.crestSpeedup) ? nlohmann::json(nullptr)
                                                          : nlohmann::json(r.crestSpeedup)}});
    }
    std::printf("measured crest speed-up at 0.25 H: %.2f\n", MEASURED_CREST_SPEEDUP);
    std::printf(
        "\nFlat log law near the ground (the field read at 1 m and 2 m; below the first "
        "centre the reader holds its value)\n");
    std::printf("%-20s %14s %9s %12s %12s\n", "res.", "cells", "seconds", "error 1 m", "error 2 m");
    for (const Row& r : rows)
        if (!std::isnan(r.error1m))
            std::printf("%-20s %8dx%dx%d %9.3f %12.4f %12.4f\n", r.resolution.c_str(), r.nx, r.ny,
                        r.nz, r.seconds, r.error1m, r.error2m);
    std::printf(
        "\nRidge against the free stream (u / U_inf at dz = 0.25 H; measured: foot %.3f, "
        "crest %.3f)\n",
        MEASURED_FOOT_UINF_025H, MEASURED_CREST_UINF_025H);
    std::printf("%-16s %-33s %-9s %8s %8s %14s   %-20s   %s\n", "model", "case", "res.", "foot",
                "crest", "RMS u/U_inf", "crest speed-up 0.25/0.48/0.98H",
                "RMS speed-up windward+crest / lee; lee deficits: points, same sign, within 0.15");
    for (const Row& r : rows)
        if (!std::isnan(r.rmsUinf))
            std::printf(
                "%-16s %-33s %-9s %8.3f %8.3f %14.3f   %.2f / %.2f / %.2f       %.3f / %.3f; %d, "
                "%d, %d\n",
                r.model.c_str(), r.testCase.c_str(), r.resolution.c_str(), r.footUinf, r.crestUinf,
                r.rmsUinf, r.crestSpeedups[0], r.crestSpeedups[1], r.crestSpeedups[2],
                r.rmsWindward, r.rmsLee, r.leePoints, r.leeSameSign, r.leeWithin);
    std::printf("measured: crest speed-up %.2f / 0.99 / 0.59\n", MEASURED_CREST_SPEEDUP);

    // The pseudo-time step's effect on the momentum model's steady state (docs/validation.md):
    // a semi-Lagrangian fixed point carries a streamwise numerical viscosity of about
    // cfl U h / 2, so the state depends on cfl at fixed h and the dependence shrinks with h.
    nlohmann::json jcfl = nlohmann::json::array();
    if (!opt.quick) {
        std::printf("\nMomentum model on the ridge: the pseudo-time step's cfl at two grids\n");
        std::printf("%-9s %5s %6s %5s %9s %8s %8s %10s\n", "res.", "cfl", "iters", "conv",
                    "seconds", "crest", "lee foot", "RMS error");
        for (int n : {5, 10})
            for (double cfl : {1.0, 2.0, 4.0}) {
                const Row r = runRidge(true, n, data, ridgeIterations, cfl);
                std::fprintf(stderr, "bench models: ridge H/h=%d cfl %.0f: %d iterations\n", n, cfl,
                             r.iterations);
                std::printf("%-9s %5.1f %6d %5s %9.2f %8.2f %8.2f %10.3e\n", r.resolution.c_str(),
                            cfl, r.iterations, r.converged ? "yes" : "NO", r.seconds,
                            r.crestSpeedup, r.leeSpeedup, r.error);
                jcfl.push_back({{"resolution", r.resolution},
                                {"cfl", cfl},
                                {"iterations", r.iterations},
                                {"converged", r.converged},
                                {"seconds", r.seconds},
                                {"crest_speedup", r.crestSpeedup},
                                {"lee_foot_speedup", r.leeSpeedup},
                                {"rms_error", r.error}});
            }
        std::printf("measured: crest %.2f, lee foot (2.5 H, 1.0 H) %.2f\n", MEASURED_CREST_SPEEDUP,
                    MEASURED_LEE_FOOT_SPEEDUP);
    }

    // One series per model and case: error against seconds.
    std::vector<Series> series;
    const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"};
    for (const Row& r : rows) {
        const std::string name = r.model + ": " + r.testCase;
        auto it = std::find_if(series.begin(), series.end(),
                               [&](const Series& s) { return s.name == name; });
        if (it == series.end()) {
            series.push_back(
                {name, colours[series.size() % 5], r.model == "mass_consistent", {}, {}});
            it = series.end() - 1;
        }
        it->xy.push_back({r.seconds, r.error});
        it->labels.push_back(r.resolution);
    }
    const std::string svg = logLogSvg("Steady models: error against wall time", "wall time, s",
                                      "error (each case's own measure)", series);
    std::filesystem::create_directories(opt.outputFolder);
    writeTextAtomic(opt.outputFolder + "/models.csv", csv.str());
    writeTextAtomic(opt.outputFolder + "/models.svg", svg);
    std::printf("wrote %s/models.csv and %s/models.svg\n", opt.outputFolder.c_str(),
                opt.outputFolder.c_str());
    if (!opt.jsonPath.empty())
        writeTextAtomic(
            opt.jsonPath,
            nlohmann::json{{"rows", jrows}, {"cfl_study", jcfl}, {"all_momentum_converged", ok}}
                    .dump(2) +
                "\n");
    return ok ? EXIT_OK : EXIT_UNMET;
}

}  // namespace gale::app
