/// \file UnsteadyDiagnostics.cpp
/// What a step of the unsteady solver reports about its field (UnsteadyWind.h, StepReport): the
/// largest speed, the kinetic energy, the largest divergence and the rate at which the field
/// crosses cells, from one pass per layer in parallel reduced in layer order, so the answers are
/// the serial loops'.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "sim/UnsteadyWind.h"

namespace gale::sim {

namespace {

/// The larger of a and b, NaN if either is NaN (a field that blew up is never hidden).
double maxKeepingNaN(double a, double b) {
    if (std::isnan(a) || std::isnan(b)) return std::numeric_limits<double>::quiet_NaN();
    return a > b ? a : b;
}

/// The open fractions of component c's faces.
const std::vector<float>& openFractions(const AirDomain& domain, int c) {
    return c == 0   ? domain.openFractionsX()
           : c == 1 ? domain.openFractionsY()
                    : domain.openFractionsZ();
}

/// Over the faces [f0, f1) with open fractions th: returns sum theta_f u_f^2 (the energy before
/// the face volumes) in index order; raises `largest` to the largest |u_f| (NaN skipped:
/// std::max(m, NaN) keeps m) and clears `finite` at a NaN or Inf.
double faceRun(const double* f0, const double* f1, const float* th, double& largest, bool& finite) {
    double e = 0.0, m = largest;
    bool ok = true;
    for (const double* x = f0; x < f1; ++x, ++th) {
        e += double(*th) * *x * *x;
        m = std::max(m, std::abs(*x));
        ok &= std::isfinite(*x);
    }
    largest = m, finite = finite && ok;
    return e;
}

/// faceRun's energy of component c's faces in layer k.
double layerEnergy(const GridLayout& g, const AirDomain& domain, const std::vector<double>& a,
                   int c, int k) {
    const Placement p = Placement(c);
    const size_t f0 = g.index(p, 0, 0, k), f1 = g.index(p, 0, 0, k + 1);
    double unused = 0.0;
    bool alsoUnused = true;
    return faceRun(a.data() + f0, a.data() + f1, openFractions(domain, c).data() + f0, unused,
                   alsoUnused);
}

/// 1/2 sum over layers of the layer energies times the faces' control volumes: h^2 times the
/// layer (x, y) or the centre gap (z).
double energyFromLayers(const GridLayout& g, const std::vector<double> (&layers)[3]) {
    const double h = g.voxelSize_m;
    double e = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < g.dims(Placement(c))[2]; ++k) {
            const double volume = h * h * (c == 2 ? g.centreGap_m(k) : g.dz_m(k));
            e += layers[c][size_t(k)] * volume;
        }
    return 0.5 * e;
}

}  // namespace

UnsteadyWindSolver::FieldSummary UnsteadyWindSolver::summarise(const std::vector<double>& U,
                                                               const std::vector<double>& V,
                                                               const std::vector<double>& W) const {
    const GridLayout& g = mGrid;
    const int nx = g.nx, ny = g.ny, nz = g.nz;
    const std::vector<double>* a[3] = {&U, &V, &W};
    // Per layer k in [0, nz]: the x- and y-faces and cells of layer k (k < nz) and the z-faces
    // of level k.
    std::vector<double> energy[3] = {std::vector<double>(size_t(nz)),
                                     std::vector<double>(size_t(nz)),
                                     std::vector<double>(size_t(nz) + 1)};
    std::vector<double> horizontal(size_t(nz) + 1, 0.0), vertical(size_t(nz) + 1, 0.0),
        speed(size_t(nz) + 1, 0.0), outflux(size_t(nz) + 1, 0.0);
    std::vector<uint8_t> finite(size_t(nz) + 1, 1);
    const uint8_t* air = mDomain.airFlags().data();
    tbb::parallel_for(0, nz + 1, [&](int k) {
        bool ok = true;
        for (int c = 0; c < 3; ++c) {
            if (c < 2 && k == nz) continue;
            const Placement p = Placement(c);
            const size_t f0 = g.index(p, 0, 0, k), f1 = g.index(p, 0, 0, k + 1);
            double m = 0.0;
            energy[c][size_t(k)] = faceRun(a[c]->data() + f0, a[c]->data() + f1,
                                           openFractions(mDomain, c).data() + f0, m, ok);
            if (c < 2)
                horizontal[size_t(k)] = std::max(horizontal[size_t(k)], m);
            else  // w crosses the thinner of the two layers a z-face touches fastest
                vertical[size_t(k)] =
                    m / std::min(g.dz_m(std::max(k - 1, 0)), g.dz_m(std::min(k, nz - 1)));
        }
        finite[size_t(k)] = ok;
        if (k == nz) return;
        // The cells row by row, without branches: a solid cell counts 0, a NaN is kept apart.
        thread_local std::vector<double> flux;
        flux.resize(size_t(nx));
        double s2 = 0.0, d = 0.0;
        bool nanSpeed = false, nanFlux = false;
        for (int j = 0; j < ny; ++j) {
            const size_t x0 = g.faceXIndex(0, j, k), y0 = g.faceYIndex(0, j, k),
                         y1 = g.faceYIndex(0, j + 1, k), z0 = g.faceZIndex(0, j, k),
                         z1 = g.faceZIndex(0, j, k + 1);
            const uint8_t* inAir = air + g.cellIndex(0, j, k);
            mDomain.openOutfluxRow(U, V, W, j, k, flux.data());
            for (int i = 0; i < nx; ++i) {
                const double cu = 0.5 * (U[x0 + i] + U[x0 + i + 1]),
                             cv = 0.5 * (V[y0 + i] + V[y1 + i]), cw = 0.5 * (W[z0 + i] + W[z1 + i]);
                const double speed2 = inAir[i] ? cu * cu + cv * cv + cw * cw : 0.0;
                const double absFlux = inAir[i] ? std::abs(flux[size_t(i)]) : 0.0;
                nanSpeed |= std::isnan(speed2), nanFlux |= std::isnan(absFlux);
                s2 = std::max(s2, speed2), d = std::max(d, absFlux);
            }
        }
        const double q = std::numeric_limits<double>::quiet_NaN();
        // sqrt is monotonic and correctly rounded: the root of the largest square is the
        // largest root.
        speed[size_t(k)] = nanSpeed ? q : std::sqrt(s2), outflux[size_t(k)] = nanFlux ? q : d;
    });
    FieldSummary r;
    double h = 0.0, v = 0.0;
    for (int k = 0; k <= nz; ++k) {
        h = std::max(h, horizontal[size_t(k)]), v = std::max(v, vertical[size_t(k)]);
        r.maxSpeed_mps = maxKeepingNaN(r.maxSpeed_mps, speed[size_t(k)]);
        r.maxOutflux = maxKeepingNaN(r.maxOutflux, outflux[size_t(k)]);
        r.finite = r.finite && finite[size_t(k)];
    }
    r.cellRate_ps = std::max(h / g.voxelSize_m, v);
    r.kineticEnergy_m5ps2 = energyFromLayers(g, energy);
    return r;
}

double UnsteadyWindSolver::maxSpeed_mps() const {
    return summarise(mField.u_mps(), mField.v_mps(), mField.w_mps()).maxSpeed_mps;
}

double UnsteadyWindSolver::kineticEnergy_m5ps2() const {
    // The energy alone (the forcing's before and after): summarise's sums without the rest.
    std::vector<double> layers[3];
    const std::vector<double>* a[3] = {&mField.u_mps(), &mField.v_mps(), &mField.w_mps()};
    for (int c = 0; c < 3; ++c) layers[c].resize(size_t(mGrid.dims(Placement(c))[2]));
    // Every (component, layer) in one parallel loop: one fork and join, not three.
    const int nz = mGrid.nz;
    tbb::parallel_for(0, 3 * (nz + 1), [&](int n) {
        const int c = n / (nz + 1), k = n % (nz + 1);
        if (k < int(layers[c].size()))
            layers[c][size_t(k)] = layerEnergy(mGrid, mDomain, *a[c], c, k);
    });
    return energyFromLayers(mGrid, layers);
}

double UnsteadyWindSolver::maxDivergenceScaled() const {
    return summarise(mField.u_mps(), mField.v_mps(), mField.w_mps()).maxOutflux / mRefSpeed_mps;
}

}  // namespace gale::sim
