/// \file HemisphereStudy.cpp
/// The hemisphere study (HemisphereStudy.h).
#include "validation/HemisphereStudy.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/SteadyWind.h"
#include "validation/ExactSolutions.h"

namespace gale::validation {

HemisphereStudy runHemisphere(const HemisphereOptions& o) {
    if (o.cellsPerRadius < 1)
        throw std::invalid_argument("runHemisphere: cellsPerRadius must be >= 1, got " +
                                    std::to_string(o.cellsPerRadius));
    const exact::HemisphereFlow flow{1.0, 1.0, 3.0, 3.0};
    sim::TerrainSpec ts;
    ts.kind = sim::TerrainKind::Hemisphere;
    ts.sizeX_m = ts.sizeY_m = 6.0;
    ts.spacing_m = flow.R_m / 128;
    ts.radius_m = flow.R_m;
    ts.centerX_m = ts.centerY_m = 3.0;
    const sim::Heightfield hf = sim::makeTerrain(ts);
    sim::AmbientWind ambient;
    ambient.profile = sim::WindProfile::Uniform;
    ambient.speed_mps = flow.U_mps;
    const sim::BoundaryPotential farField = [&](double x, double y, double z) {
        return flow.phi(x, y, z);
    };
    const auto t0 = std::chrono::steady_clock::now();
    const sim::AirDomain domain(hf, sim::DomainSpec{flow.R_m / o.cellsPerRadius, /*top_m=*/3.0});
    sim::SteadyWindSolver solver(domain);
    sim::SolverSettings set;
    set.maxIterations = 200;
    const sim::SteadyWindResult res = solver.solve(ambient, set, farField);
    HemisphereStudy r;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.nx = domain.nx(), r.ny = domain.ny(), r.nz = domain.nz();
    r.iterations = res.report.iterations, r.converged = res.report.converged;
    double e2 = 0, n2 = 0;
    for (const auto& p : flow.nearPoints()) {
        const auto u = res.field.velocityAt_mps(p[0], p[1], p[2]);
        const auto ue = flow.velocity(p[0], p[1], p[2]);
        for (int q = 0; q < 3; ++q) e2 += (u[q] - ue[q]) * (u[q] - ue[q]), n2 += ue[q] * ue[q];
    }
    r.nearL2 = std::sqrt(e2 / n2);
    return r;
}

double observedOrder(const std::vector<int>& cells, const std::vector<double>& errors) {
    if (cells.size() != errors.size() || cells.size() < 2)
        throw std::invalid_argument("observedOrder: needs two or more (cells, error) pairs");
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double n = double(cells.size());
    for (size_t i = 0; i < cells.size(); ++i) {
        if (!(errors[i] > 0) || cells[i] < 1)
            throw std::invalid_argument("observedOrder: errors must be > 0, cells >= 1");
        const double x = std::log(double(cells[i])), y = std::log(errors[i]);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace gale::validation
