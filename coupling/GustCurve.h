#pragma once
/// \file GustCurve.h
/// The user's wind intensity as a function of time: periodic and continuous, with a strong attack
/// and a gradual decay (Bakay 2003, 3.2: a spline after Neyret). We interpolate periodic keys with
/// a monotone cubic Hermite spline (Fritsch and Carlson 1980), so the curve never overshoots its
/// keys: a gust's peak is the peak the user wrote.

#include <vector>

namespace gale::coupling {

struct GustKey {
    double t_s;        ///< time within the period, seconds, in [0, period)
    double intensity;  ///< I at that time
};

class GustCurve {
  public:
    /// Keys must be finite with strictly increasing t in [0, period_s); period_s > 0. The curve
    /// wraps: after the last key it runs to the first key at t + period. Throws
    /// gale::ParameterError naming the offending scene key (wind.gust.period_s,
    /// wind.gust.keys[k], wind.gust.keys when there is none).
    GustCurve(double period_s, std::vector<GustKey> keys);

    /// A default gust: calm base, a sharp rise over `attack_s` to `peak`, a gradual fall over
    /// `decay_s` back to `base`, then calm until the period ends.
    static GustCurve attackDecay(double period_s, double base, double peak, double attack_s,
                                 double decay_s);

    /// I(t) for any t (negative too), periodic in period_s, C1-continuous.
    double operator()(double t_s) const;
    double period_s() const { return mPeriod_s; }
    const std::vector<GustKey>& keys() const { return mKeys; }

  private:
    double mPeriod_s;
    std::vector<GustKey> mKeys;
    std::vector<double> mSlope;  // Hermite tangents at the keys, intensity per second
};

}  // namespace gale::coupling
