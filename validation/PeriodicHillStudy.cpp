/// \file PeriodicHillStudy.cpp
/// The ERCOFTAC periodic hill study (PeriodicHillStudy.h).
#include "validation/PeriodicHillStudy.h"

#include <algorithm>
#include <chrono>
#include <sstream>
#include <stdexcept>

#include "sim/SteadyModel.h"
#include "sim/SteadyWind.h"
#include "sim/SurfaceLayer.h"
#include "validation/PeriodicHill.h"
#include "validation/ValidationData.h"

namespace gale::validation {
namespace {

namespace ph = periodichill;

/// The rows of a CSV text after its header, each split at commas into at least minFields
/// numbers. Throws std::invalid_argument naming sourceName and the line.
std::vector<std::vector<double>> numberRows(const std::string& text, const std::string& sourceName,
                                            size_t minFields) {
    std::istringstream in(text);
    std::string line;
    std::getline(in, line);  // header
    std::vector<std::vector<double>> rows;
    int lineNo = 1;
    while (std::getline(in, line)) {
        ++lineNo;
        if (line.empty()) continue;
        std::vector<double> f;
        std::stringstream ss(line);
        try {
            for (std::string c; std::getline(ss, c, ',');) f.push_back(std::stod(c));
        } catch (const std::exception&) {
            throw std::invalid_argument(sourceName + ":" + std::to_string(lineNo) +
                                        ": expected a number in every field");
        }
        if (f.size() < minFields)
            throw std::invalid_argument(sourceName + ":" + std::to_string(lineNo) + ": expected " +
                                        std::to_string(minFields) + " fields, got " +
                                        std::to_string(f.size()));
        rows.push_back(std::move(f));
    }
    if (rows.empty()) throw std::invalid_argument(sourceName + ": no rows after the header");
    return rows;
}

}  // namespace

std::vector<double> PeriodicHillData::stations() const {
    std::vector<double> xs;
    for (const HillProfilePoint& p : profiles)
        if (xs.empty() || std::abs(xs.back() - p.x_h) > 1e-9) xs.push_back(p.x_h);
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end(),
                         [](double a, double b) { return std::abs(a - b) <= 1e-9; }),
             xs.end());
    return xs;
}

PeriodicHillData parsePeriodicHillData(const std::string& profilesCsv,
                                       const std::string& profilesName, const std::string& wallCsv,
                                       const std::string& wallName) {
    PeriodicHillData d;
    for (const std::vector<double>& r : numberRows(profilesCsv, profilesName, 5))
        d.profiles.push_back({r[0], r[1], r[2], r[3], r[4]});
    for (const std::vector<double>& r : numberRows(wallCsv, wallName, 3))
        d.wall.push_back({r[0], r[2]});
    std::sort(d.wall.begin(), d.wall.end(),
              [](const WallSample& a, const WallSample& b) { return a.x_h < b.x_h; });
    const Bubble b = bubbleOf(d.wall);
    d.separation_h = b.separation_h, d.reattachment_h = b.reattachment_h;
    return d;
}

PeriodicHillData periodicHillReference() {
    const char* profiles = "periodic-hill-xiao-2020-profiles.csv";
    const char* wall = "periodic-hill-xiao-2020-wall.csv";
    const char* p = embeddedData(profiles);
    const char* w = embeddedData(wall);
    if (!p || !w)
        throw std::logic_error(std::string(p ? wall : profiles) +
                               " was not embedded at build time");
    return parsePeriodicHillData(p, std::string("(embedded) ") + profiles, w,
                                 std::string("(embedded) ") + wall);
}

Bubble bubbleOf(const std::vector<WallSample>& line, double searchFrom_h) {
    Bubble b;
    auto crossing = [](const WallSample& a, const WallSample& c) {
        return a.x_h + (c.x_h - a.x_h) * a.u_Ub / (a.u_Ub - c.u_Ub);
    };
    for (size_t i = 1; i < line.size(); ++i) {
        const WallSample &a = line[i - 1], &c = line[i];
        if (c.x_h <= searchFrom_h) continue;
        if (!b.exists()) {
            if (a.u_Ub > 0 && c.u_Ub <= 0) b.separation_h = crossing(a, c);
        } else if (a.u_Ub < 0 && c.u_Ub >= 0) {
            b.reattachment_h = crossing(a, c);
            break;
        }
    }
    return b;
}

double rmsDifference(const std::vector<double>& model, const std::vector<double>& reference) {
    if (model.size() != reference.size() || model.empty())
        throw std::invalid_argument("rmsDifference: expected two equal, non-empty series, got " +
                                    std::to_string(model.size()) + " and " +
                                    std::to_string(reference.size()) + " values");
    double sum2 = 0;
    for (size_t i = 0; i < model.size(); ++i)
        sum2 += (model[i] - reference[i]) * (model[i] - reference[i]);
    return std::sqrt(sum2 / double(model.size()));
}

PeriodicHillStudy runPeriodicHill(const PeriodicHillOptions& o, const PeriodicHillData& ref) {
    if (o.cellsPerH < 1 || o.hills < 2 || o.measuredHill < 1 || o.measuredHill >= o.hills ||
        !(o.h_m > 0) || !(o.bulkSpeed_mps > 0))
        throw std::invalid_argument(
            "runPeriodicHill: expected cellsPerH >= 1, hills >= 2, 1 <= measuredHill < hills, "
            "h_m > 0 and bulkSpeed_mps > 0, got " +
            std::to_string(o.cellsPerH) + ", " + std::to_string(o.hills) + ", " +
            std::to_string(o.measuredHill) + ", " + std::to_string(o.h_m) + ", " +
            std::to_string(o.bulkSpeed_mps));
    if (ref.profiles.empty() || ref.wall.empty())
        throw std::invalid_argument("runPeriodicHill: no reference data");
    const double h = o.h_m, cell_m = h / o.cellsPerH, ub = o.bulkSpeed_mps;

    // The chain of hills, from the first crest to the crest after the last period, sampled every
    // half cell, 3 cells across.
    const double spacing = cell_m / 2, length = o.hills * ph::PERIOD_OVER_H * h;
    const int tnx = int(std::lround(length / spacing)) + 1, tny = 7;
    std::vector<float> z(size_t(tnx) * tny);
    for (int j = 0; j < tny; ++j)
        for (int i = 0; i < tnx; ++i)
            z[size_t(j) * tnx + i] = float(ph::floorHeight_h(i * spacing / h) * h);
    const sim::Heightfield terrain = sim::makeHeightfield(tnx, tny, spacing, std::move(z));

    sim::DomainSpec spec;
    spec.voxelSize_m = cell_m;
    spec.top_m = ph::CHANNEL_TOP_OVER_H * h;
    spec.momentumModel = true;
    spec.closedSidesY = true;  // a two-dimensional flow: free-slip side walls

    // The inflow over the first crest: the log law over the smooth wall's equivalent z0, its
    // speed at the upper wall (the crest gap G above the crest) chosen so that its mean over the
    // gap, u*/kappa (ln(G / z0) - 1), is Ub.
    const double z0_m = ph::smoothWallZ0_h(sim::surface::KAPPA) * h;
    const double gap_m = ph::CREST_GAP_OVER_H * h, logGap = std::log(gap_m / z0_m);
    sim::AmbientWind wind;
    wind.profile = sim::WindProfile::LogLaw;
    wind.roughness_m = z0_m;
    wind.referenceHeight_m = gap_m;
    wind.speed_mps = ub * logGap / (logGap - 1.0);

    sim::SolverSettings start;
    start.maxIterations = 200;
    sim::MomentumSettings ms;
    ms.cfl = o.cfl;
    ms.advection = o.advection;
    ms.turbulence = o.closure;
    ms.maxIterations = o.maxIterations;
    const auto t0 = std::chrono::steady_clock::now();
    const sim::AirDomain domain(terrain, spec);
    const sim::SteadyModelResult res = sim::solveSteadyModel(
        domain, wind, sim::SteadyModel::Momentum, sim::MassConsistentWeights{}, start, ms);

    PeriodicHillStudy r;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.nx = domain.nx(), r.ny = domain.ny(), r.nz = domain.nz();
    r.iterations = res.report.iterations;
    r.converged = res.report.converged;
    r.z0_h = z0_m / h;
    if (res.momentum) {
        r.levels = studyLevels(*res.momentum);
        r.cyclePeriod = res.momentum->cyclePeriod, r.averagedSteps = res.momentum->averagedSteps;
    }

    const double y = terrain.sizeY_m() / 2;
    const double period_m = ph::PERIOD_OVER_H * h;
    const double x0 = o.measuredHill * period_m;  // the measured period's first crest
    auto velocity = [&](double xFromCrest_h, double y_h, double offset_m) {
        return res.field.velocityAt_mps(x0 + offset_m + xFromCrest_h * h, y, y_h * h);
    };
    // The bulk velocity through a period's first crest gap over Ub (midpoint rule, 200 layers):
    // the steady model's open top lets the flux drift along the chain, so each period's
    // velocities are made dimensionless by its own bulk, as the DNS's are by its own.
    auto bulk = [&](double offset_m) {
        const int n = 200;
        double flux = 0;
        for (int i = 0; i < n; ++i)
            flux += velocity(0.0, 1.0 + (i + 0.5) * ph::CREST_GAP_OVER_H / n, offset_m)[0];
        return flux / n / ub;
    };
    r.bulkOverUb = bulk(0.0), r.previousBulkOverUb = bulk(-period_m);
    const double ubHere = ub * r.bulkOverUb, ubBefore = ub * r.previousBulkOverUb;
    // The along-wall line: WALL_SAMPLE_CELLS cells above the floor, projected on its tangent.
    auto wallLine = [&](double offset_m, double scale_mps) {
        std::vector<WallSample> line;
        const int n = int(std::lround(ph::PERIOD_OVER_H / WALL_LINE_STEP_H));
        for (int i = 0; i <= n; ++i) {
            const double s = i * WALL_LINE_STEP_H, ds = 1e-3;
            const double g = ph::floorHeight_h(s);
            const double slope = (ph::floorHeight_h(s + ds) - ph::floorHeight_h(s - ds)) / (2 * ds);
            const sim::Vec3d v = velocity(s, g + WALL_SAMPLE_CELLS / o.cellsPerH, offset_m);
            line.push_back({s, (v[0] + slope * v[2]) / std::sqrt(1 + slope * slope) / scale_mps});
        }
        return line;
    };
    r.wall = wallLine(0.0, ubHere);
    r.bubble = bubbleOf(r.wall);
    r.previousBubble = bubbleOf(wallLine(-period_m, ubBefore));
    r.minFloorU_Ub = r.wall.front().u_Ub;
    for (const WallSample& s : r.wall) r.minFloorU_Ub = std::min(r.minFloorU_Ub, s.u_Ub);
    if (r.bubble.exists() && std::isfinite(ref.reattachment_h))
        r.reattachmentRelativeError = std::abs(r.bubble.reattachment_h / ref.reattachment_h - 1);

    // k on the cells (the nearest cell's value; solid cells are skipped), over the bulk squared.
    const sim::GridLayout& layout = domain.layout();
    auto k = [&](double xFromCrest_h, double y_h) {
        if (res.tke_m2ps2.empty()) return double(NAN);
        const sim::Vec3d is = layout.isFromWs({x0 + xFromCrest_h * h, y, y_h * h});
        const int i = std::clamp(int(std::floor(is[0])), 0, domain.nx() - 1);
        const int j = std::clamp(int(std::floor(is[1])), 0, domain.ny() - 1);
        const int kk = std::clamp(int(std::floor(is[2])), 0, domain.nz() - 1);
        if (!domain.isAir(i, j, kk)) return double(NAN);
        return res.tke_m2ps2[layout.cellIndex(i, j, kk)] / (ubHere * ubHere);
    };

    std::vector<double> allM, allR, allKM, allKR, allP;
    for (double xs : ref.stations()) {
        PeriodicHillStudy::Station st;
        st.x_h = xs;
        std::vector<double> m, rf, km, kr, prev;
        for (const HillProfilePoint& p : ref.profiles) {
            if (std::abs(p.x_h - xs) > 1e-9) continue;
            m.push_back(velocity(p.x_h, p.y_h, 0.0)[0] / ubHere);
            rf.push_back(p.u_Ub);
            prev.push_back(velocity(p.x_h, p.y_h, -period_m)[0] / ubBefore);
            const double kv = k(p.x_h, p.y_h);
            st.modelK.push_back(kv);
            if (std::isfinite(kv)) km.push_back(kv), kr.push_back(p.k_Ub2);
        }
        st.points = int(m.size());
        st.modelU = m;
        st.rmsU = rmsDifference(m, rf);
        st.repeatRmsU = rmsDifference(m, prev);
        if (!km.empty()) st.rmsK = rmsDifference(km, kr);
        allM.insert(allM.end(), m.begin(), m.end());
        allR.insert(allR.end(), rf.begin(), rf.end());
        allP.insert(allP.end(), prev.begin(), prev.end());
        allKM.insert(allKM.end(), km.begin(), km.end());
        allKR.insert(allKR.end(), kr.begin(), kr.end());
        r.stations.push_back(st);
    }
    r.rmsU = rmsDifference(allM, allR);
    r.repeatRmsU = rmsDifference(allM, allP);
    if (!allKM.empty()) r.rmsK = rmsDifference(allKM, allKR);
    return r;
}

}  // namespace gale::validation
