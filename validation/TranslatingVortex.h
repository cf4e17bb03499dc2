#pragma once
/// \file TranslatingVortex.h
/// The error of sim::runTranslatingVortex against its exact Galilean solution, for
/// `gale bench stability` and the tests (header-only; the exact flow comes from ExactSolutions.h,
/// not from the code under test). Units: metres, seconds, m/s.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "base/Numbers.h"
#include "validation/ExactSolutions.h"
#include "validation/UnsteadyStability.h"

namespace gale::validation::exact {

/// max over x of (1 - e^{-x^2}) / x: Lamb-Oseen's peak speed in units of Gamma / (2 pi r_c)
/// (0.6382 at x = 1.1209), found on a fine grid rather than taken from the code under test.
inline double lambOseenPeakFactor() {
    static const double factor = [] {
        double best = 0.0;
        for (double x = 0.5; x < 2.0; x += 1e-5) best = std::max(best, -std::expm1(-x * x) / x);
        return best;
    }();
    return factor;
}

/// RMS over the horizontal faces within 2 core radii of the exact axis of |u - u_exact| / v_peak,
/// at the run's final time t, with u_exact = U e_x + the Lamb-Oseen swirl about the axis carried
/// from (START_X_M, START_Y_M) at U (any axisymmetric swirl is a steady Euler solution; Galilean
/// invariance carries it).
inline double translatingVortexError(const StabilityRun& run) {
    using S = TranslatingVortexSpec;
    const double t = run.solver->time_s(), cx = S::START_X_M + S::WIND_MPS * t, cy = S::START_Y_M;
    const double gamma = S::PEAK_MPS * 2.0 * PI * S::CORE_M / lambOseenPeakFactor();
    const sim::MacGrid& g = run.solver->grid();
    const sim::WindField& f = run.solver->field();
    double sum = 0.0;
    size_t count = 0;
    for (int c = 0; c < 2; ++c) {
        const auto n = g.dims(sim::Placement(c));
        const std::vector<double>& a = c == 0 ? f.u_mps() : f.v_mps();
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    const auto p = g.wsPosition(sim::Placement(c), i, j, k);
                    const double dx = p[0] - cx, dy = p[1] - cy, r = std::hypot(dx, dy);
                    if (r > 2.0 * S::CORE_M) continue;
                    const double v =
                        r > 0 ? lambOseenSpeed_mps(gamma, S::CORE_M * S::CORE_M, r) / r : 0.0;
                    const double exact = c == 0 ? S::WIND_MPS - v * dy : v * dx;
                    const double d = a[g.index(sim::Placement(c), i, j, k)] - exact;
                    sum += d * d, ++count;
                }
    }
    return count ? std::sqrt(sum / double(count)) / S::PEAK_MPS : 0.0;
}

}  // namespace gale::validation::exact
