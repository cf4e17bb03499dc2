#pragma once
/// \file GroupOscillators.h
/// One damped oscillator per animation-step group: the blade's bend x follows its drive u(t)
/// (the static intensity) as x'' + 2 zeta omega x' + omega^2 x = omega^2 u(t), so a gust
/// overshoots and the grass recovers and sways (after Sousa 2008, GPU Gems 3 ch. 16, stiffness and
/// damping per instance). Per frame the cost is O(groups).

#include <algorithm>
#include <cmath>
#include <vector>

#include "base/Numbers.h"

namespace gale::coupling {

class GroupOscillators {
  public:
    /// Oscillator sub-steps per natural period: the trapezoidal rule's phase error is about
    /// (omega h)^2 / 12 per step, under 0.2 % at 40 steps per period.
    static constexpr double STEPS_PER_PERIOD = 40.0;
    /// Cap on sub-steps per advance: after a long gap (seeking, a paused viewer) older motion has
    /// decayed, and the trapezoidal rule is stable at any step.
    static constexpr int MAX_SUBSTEPS = 4000;

    /// frequency_hz = omega / (2 pi) > 0, dampingRatio = zeta > 0 (validated by the callers).
    GroupOscillators(double frequency_hz, double dampingRatio)
        : mFrequency_hz(frequency_hz), mZeta(dampingRatio) {}

    /// Bend of every group after the last advance.
    const std::vector<double>& bend() const { return mX; }

    /// Brings every group to time t_s. drive(g, t) is group g's static intensity at time t. The
    /// first call, and any call going back in time, starts the groups at rest in their static
    /// bend. Integrated with the trapezoidal rule (A-stable: bounded for any step).
    template <class Drive>
    void advance(double t_s, int groups, const Drive& drive) {
        if (!mStarted || t_s < mTime_s || static_cast<int>(mX.size()) != groups) {
            mX.resize(groups);
            mV.assign(groups, 0.0);
            for (int g = 0; g < groups; ++g) mX[g] = drive(g, t_s);
            mTime_s = t_s;
            mStarted = true;
            return;
        }
        const double total = t_s - mTime_s;
        if (total <= 0.0) return;
        const int substeps = static_cast<int>(std::clamp(
            std::ceil(total * mFrequency_hz * STEPS_PER_PERIOD), 1.0, double(MAX_SUBSTEPS)));
        const double h = total / substeps;
        // y = (x, v), y' = M y + omega^2 u e2, M = [[0, 1], [-w2, -c]], w2 = omega^2,
        // c = 2 zeta omega. Trapezoidal: (I - a M) y1 = (I + a M) y0 + a w2 (u0 + u1) e2, a = h/2,
        // with (I - a M)^-1 = [[1 + a c, a], [-a w2, 1]] / (1 + a c + a^2 w2).
        const double omega = 2.0 * PI * mFrequency_hz;
        const double a = 0.5 * h, w2 = omega * omega, c = 2.0 * mZeta * omega;
        const double det = 1.0 + a * c + a * a * w2;
        for (int g = 0; g < groups; ++g) {
            double x = mX[g], v = mV[g];
            double u0 = drive(g, mTime_s);
            for (int s = 0; s < substeps; ++s) {
                const double u1 = drive(g, mTime_s + (s + 1) * h);
                const double rx = x + a * v;
                const double rv = v + a * (-w2 * x - c * v) + a * w2 * (u0 + u1);
                x = ((1.0 + a * c) * rx + a * rv) / det;
                v = (-a * w2 * rx + rv) / det;
                u0 = u1;
            }
            mX[g] = x;
            mV[g] = v;
        }
        mTime_s = t_s;
    }

  private:
    double mFrequency_hz, mZeta;
    bool mStarted = false;
    double mTime_s = 0.0;
    std::vector<double> mX, mV;
};

}  // namespace gale::coupling
