/// \file UnsteadyDiagnostics.cpp
/// What a step of the unsteady solver reports about its field (UnsteadyWind.h, StepReport): the
/// largest speed, the kinetic energy and the largest divergence, each per layer in parallel and
/// reduced in layer order, so the answers are the serial loops'.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "sim/UnsteadyWind.h"

namespace gale::sim {

namespace {

/// f(k) for every k in [0, n), in parallel, the answers in k order: a reduction over them in
/// that order gives the serial loop's answer whatever the threads did.
template <class F>
std::vector<double> perLayer(int n, const F& f) {
    std::vector<double> r(size_t(std::max(n, 0)));
    tbb::parallel_for(0, n, [&](int k) { r[size_t(k)] = f(k); });
    return r;
}

/// The larger of a and b, NaN if either is NaN (a field that blew up is never hidden).
double maxKeepingNaN(double a, double b) {
    if (std::isnan(a) || std::isnan(b)) return std::numeric_limits<double>::quiet_NaN();
    return a > b ? a : b;
}

}  // namespace

double UnsteadyWindSolver::maxSpeed_mps() const {
    const std::vector<double> layers = perLayer(mGrid.nz, [&](int k) {
        double m = 0.0;
        for (int j = 0; j < mGrid.ny; ++j)
            for (int i = 0; i < mGrid.nx; ++i) {
                if (!mDomain.isAir(i, j, k)) continue;
                const auto c = mField.cellVelocity_mps(i, j, k);
                m = maxKeepingNaN(m, std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]));
            }
        return m;
    });
    double m = 0.0;
    for (double x : layers) m = maxKeepingNaN(m, x);
    return m;
}

double UnsteadyWindSolver::kineticEnergy_m5ps2() const {
    const double h = mGrid.voxelSize_m;
    double e = 0.0;
    const std::vector<double>* a[3] = {&mField.u_mps(), &mField.v_mps(), &mField.w_mps()};
    const std::vector<float>* th[3] = {&mDomain.openFractionsX(), &mDomain.openFractionsY(),
                                       &mDomain.openFractionsZ()};
    for (int c = 0; c < 3; ++c) {
        const Placement p = Placement(c);
        // Each layer's sum in parallel, the layers added in order: the serial loop's answer.
        const std::vector<double> layers = perLayer(mGrid.dims(p)[2], [&](int k) {
            double layer = 0.0;
            for (size_t f = mGrid.index(p, 0, 0, k); f < mGrid.index(p, 0, 0, k + 1); ++f)
                layer += double((*th[c])[f]) * (*a[c])[f] * (*a[c])[f];
            return layer;
        });
        for (int k = 0; k < mGrid.dims(p)[2]; ++k) {
            // The face's control volume: h^2 times its layer (x, y) or the centre gap (z).
            const double volume = h * h * (c == 2 ? mGrid.centreGap_m(k) : mGrid.dz_m(k));
            e += layers[size_t(k)] * volume;
        }
    }
    return 0.5 * e;
}

double UnsteadyWindSolver::maxDivergenceScaled() const {
    const auto &U = mField.u_mps(), &V = mField.v_mps(), &W = mField.w_mps();
    const std::vector<double> layers = perLayer(mGrid.nz, [&](int k) {
        double m = 0.0;
        for (int j = 0; j < mGrid.ny; ++j)
            for (int i = 0; i < mGrid.nx; ++i)
                if (mDomain.isAir(i, j, k))
                    m = maxKeepingNaN(m, std::abs(mDomain.openOutflux(U, V, W, i, j, k)));
        return m;
    });
    double maxDiv = 0.0;
    for (double x : layers) maxDiv = maxKeepingNaN(maxDiv, x);
    return maxDiv / mRefSpeed_mps;
}

}  // namespace gale::sim
