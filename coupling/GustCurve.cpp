#include "coupling/GustCurve.h"

#include <cmath>
#include <stdexcept>

#include "base/Numbers.h"
#include "base/ParameterError.h"

namespace gale::coupling {
namespace {

[[noreturn]] void badKey(size_t k, const GustKey& key, const std::string& why) {
    throw ParameterError("wind.gust.keys[" + std::to_string(k) + "]",
                         "[" + formatG(key.t_s) + ", " + formatG(key.intensity) + "]", why);
}

}  // namespace

GustCurve::GustCurve(double period_s, std::vector<GustKey> keys)
    : mPeriod_s(period_s), mKeys(std::move(keys)) {
    if (!std::isfinite(period_s) || period_s <= 0.0)
        throw ParameterError("wind.gust.period_s", formatG(period_s), "must be finite and > 0");
    if (mKeys.empty())
        throw ParameterError("wind.gust.keys", "[]",
                             "must hold at least one [t_s, intensity] pair");
    for (size_t k = 0; k < mKeys.size(); ++k) {
        const GustKey& key = mKeys[k];
        if (!std::isfinite(key.t_s) || !std::isfinite(key.intensity))
            badKey(k, key, "time and intensity must be finite");
        if (key.t_s < 0.0 || key.t_s >= period_s)
            badKey(k, key, "time must be in [0, period_s = " + formatG(period_s) + ")");
        if (k > 0 && key.t_s <= mKeys[k - 1].t_s)
            badKey(k, key,
                   "times must increase strictly (previous key is at " + formatG(mKeys[k - 1].t_s) +
                       " s)");
    }
    // Tangents of a monotone piecewise-cubic Hermite interpolant (Fritsch and Butland 1984):
    // zero at a local extremum of the keys, else a weighted harmonic mean of the neighbouring
    // secants, which keeps every segment within its end values. The keys wrap around the period.
    const size_t n = mKeys.size();
    mSlope.assign(n, 0.0);
    if (n < 2) return;
    auto interval = [&](size_t k) {  // length of the segment from key k to key k + 1 (wrapped)
        const double t1 = (k + 1 < n) ? mKeys[k + 1].t_s : mKeys[0].t_s + mPeriod_s;
        return t1 - mKeys[k].t_s;
    };
    auto secant = [&](size_t k) {
        return (mKeys[(k + 1) % n].intensity - mKeys[k].intensity) / interval(k);
    };
    for (size_t k = 0; k < n; ++k) {
        const size_t prev = (k + n - 1) % n;
        const double d0 = secant(prev), d1 = secant(k);
        if (d0 * d1 <= 0.0) continue;
        const double h0 = interval(prev), h1 = interval(k);
        const double w0 = 2.0 * h1 + h0, w1 = h1 + 2.0 * h0;
        mSlope[k] = (w0 + w1) / (w0 / d0 + w1 / d1);
    }
}

GustCurve GustCurve::attackDecay(double period_s, double base, double peak, double attack_s,
                                 double decay_s) {
    if (!std::isfinite(attack_s) || attack_s <= 0.0)
        throw ParameterError("wind.gust.attack_s", formatG(attack_s), "must be finite and > 0");
    if (!std::isfinite(decay_s) || decay_s <= 0.0)
        throw ParameterError("wind.gust.decay_s", formatG(decay_s), "must be finite and > 0");
    if (!(attack_s + decay_s < period_s))
        throw ParameterError("wind.gust.decay_s", formatG(decay_s),
                             "attack_s + decay_s = " + formatG(attack_s + decay_s) +
                                 " s must be shorter than period_s = " + formatG(period_s) + " s");
    return GustCurve(period_s, {{0.0, base}, {attack_s, peak}, {attack_s + decay_s, base}});
}

double GustCurve::operator()(double t_s) const {
    const size_t n = mKeys.size();
    if (n == 1) return mKeys[0].intensity;
    double t = std::fmod(t_s, mPeriod_s);
    if (t < 0.0) t += mPeriod_s;
    // Segment k runs from key k to key k + 1; before the first key we are in the wrapped last one.
    size_t k = n - 1;
    for (size_t i = 0; i + 1 < n; ++i)
        if (t >= mKeys[i].t_s && t < mKeys[i + 1].t_s) k = i;
    double t0 = mKeys[k].t_s;
    if (t < t0) t0 -= mPeriod_s;
    const double t1 =
        (k + 1 < n) ? mKeys[k + 1].t_s : mKeys[0].t_s + (t0 < mKeys[k].t_s ? 0.0 : mPeriod_s);
    const double h = t1 - t0;
    const double s = (t - t0) / h;
    const double y0 = mKeys[k].intensity, y1 = mKeys[(k + 1) % n].intensity;
    const double m0 = mSlope[k] * h, m1 = mSlope[(k + 1) % n] * h;
    // Cubic Hermite basis on s in [0, 1].
    const double s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * y1 +
           (s3 - s2) * m1;
}

}  // namespace gale::coupling
