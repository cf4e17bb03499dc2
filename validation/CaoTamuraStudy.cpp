/// \file CaoTamuraStudy.cpp
/// The Cao and Tamura (2006) ridge study (CaoTamuraStudy.h).
#include "validation/CaoTamuraStudy.h"

#include <algorithm>
#include <chrono>
#include <sstream>
#include <stdexcept>

#include "sim/MomentumWind.h"
#include "sim/SteadyWind.h"
#include "validation/ValidationData.h"

namespace gale::validation {

std::vector<RidgeMeasurement> parseRidgeMeasurements(const std::string& csvText,
                                                     const std::string& sourceName) {
    std::istringstream in(csvText);
    std::string line;
    std::getline(in, line);  // header
    std::vector<RidgeMeasurement> out;
    int lineNo = 1;
    while (std::getline(in, line)) {
        ++lineNo;
        std::vector<std::string> f;
        std::stringstream ss(line);
        for (std::string c; std::getline(ss, c, ',');) f.push_back(c);
        if (f.size() < 6 || f[5].empty()) continue;  // no reference below the lowest foot point
        try {
            out.push_back({std::stod(f[0]), std::stod(f[2]), std::stod(f[5]), std::stod(f[3])});
        } catch (const std::exception&) {
            throw std::invalid_argument(sourceName + ":" + std::to_string(lineNo) +
                                        ": expected numbers in x_over_H, dz_over_H, speedup");
        }
    }
    if (out.empty()) throw std::invalid_argument(sourceName + ": no measured speed-ups");
    return out;
}

std::vector<RidgeMeasurement> caoTamuraMeasurements() {
    const char* name = "cao-tamura-2006-ridge.csv";
    const char* text = embeddedData(name);
    if (!text) throw std::logic_error(std::string(name) + " was not embedded at build time");
    return parseRidgeMeasurements(text, std::string("(embedded) ") + name);
}

CaoTamuraStudy runCaoTamura(const CaoTamuraOptions& o, const std::vector<RidgeMeasurement>& data) {
    if (o.cellsPerH < 1)
        throw std::invalid_argument("runCaoTamura: cellsPerH must be >= 1, got " +
                                    std::to_string(o.cellsPerH));
    if (data.empty()) throw std::invalid_argument("runCaoTamura: no measured points");
    const double h = ridge::H_M / o.cellsPerH;
    const sim::Heightfield terrain = ridge::terrain(h);
    sim::DomainSpec spec;
    spec.voxelSize_m = h;
    spec.top_m = ridge::TOP_OVER_H * ridge::H_M;
    spec.momentumModel = o.momentum;
    spec.closedSidesY = true;  // a two-dimensional ridge: the tunnel's side walls, free slip
    const sim::AmbientWind wind = ridge::wind(o.inflow);
    const auto t0 = std::chrono::steady_clock::now();
    const sim::AirDomain domain(terrain, spec);
    sim::SolverSettings start;
    start.maxIterations = 200;
    sim::MomentumSettings ms;
    ms.cfl = o.cfl;
    ms.advection = o.advection;
    ms.turbulence = o.turbulence;
    ms.maxIterations = o.maxIterations;
    const sim::SteadyModelResult res = sim::solveSteadyModel(
        domain, wind, o.momentum ? sim::SteadyModel::Momentum : sim::SteadyModel::MassConsistent,
        sim::MassConsistentWeights{}, start, ms);
    CaoTamuraStudy r;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.nx = domain.nx(), r.ny = domain.ny(), r.nz = domain.nz();
    r.iterations = res.report.iterations;
    r.converged = res.report.converged;
    if (o.momentum)
        r.cfl = o.advection == sim::PseudoTimeAdvection::Eulerian ? ms.eulerianCfl : o.cfl;
    if (res.momentum) r.levels = studyLevels(*res.momentum);
    const double y = terrain.sizeY_m() / 2;
    auto u = [&](double xOverH, double dzOverH) {
        const double x = xOverH * ridge::H_M;
        return res.field.velocityAt_mps(x + ridge::UPWIND_M, y,
                                        ridge::height_m(x) + dzOverH * ridge::H_M)[0];
    };
    double sum2 = 0, sumLee2 = 0;
    int n = 0, nLee = 0;
    double crestDz = 1e9, leeDz = 1e9;
    for (const RidgeMeasurement& m : data) {
        if (m.xOverH <= -2.5 + 1e-9) continue;  // the reference itself
        const double model = u(m.xOverH, m.dzOverH) / u(-2.5, m.dzOverH) - 1.0;
        sum2 += (model - m.speedup) * (model - m.speedup), ++n;
        if (m.xOverH > 0) sumLee2 += (model - m.speedup) * (model - m.speedup), ++nLee;
        if (m.xOverH > 0 && m.speedup < 0) {
            ++r.leePoints;
            if (model < 0) ++r.leeSameSign;
            if (std::abs(model - m.speedup) <= LEE_DEFICIT_TOLERANCE) ++r.leeWithin;
        }
        if (std::abs(m.xOverH) < 1e-9 && std::abs(m.dzOverH - 0.25) < std::abs(crestDz - 0.25))
            crestDz = m.dzOverH, r.crestSpeedup = model;
        if (std::abs(m.xOverH - 2.5) < 1e-9 && std::abs(m.dzOverH - 1.0) < std::abs(leeDz - 1.0))
            leeDz = m.dzOverH, r.leeSpeedup = model;
    }
    r.points = n;
    r.rmsSpeedupError = std::sqrt(sum2 / std::max(n, 1));
    r.rmsLee = std::sqrt(sumLee2 / std::max(nLee, 1));
    r.rmsWindward = std::sqrt((sum2 - sumLee2) / std::max(n - nLee, 1));
    // Against the free stream: the model's U_inf is its inflow's (the published inflow's speed
    // at the top), not taken from the hill data.
    const double uInf = ridge::freeStream_mps(o.inflow);
    double sumInf = 0;
    for (const RidgeMeasurement& m : data) {
        const double d = u(m.xOverH, m.dzOverH) / uInf - m.uOverUinf;
        sumInf += d * d;
    }
    r.rmsUinf = std::sqrt(sumInf / double(data.size()));
    r.crestUinf = u(0.0, 0.25) / uInf, r.footUinf = u(-2.5, 0.25) / uInf;
    for (int i = 0; i < 3; ++i) {
        const double dz = ridge::CREST_DZ_OVER_H[i];
        r.crestSpeedups[i] = u(0.0, dz) / u(-2.5, dz) - 1.0;
    }
    return r;
}

}  // namespace gale::validation
