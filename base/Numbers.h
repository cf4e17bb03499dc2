#pragma once
/// \file Numbers.h
/// The one home of pi and of numbers written as text, for every module (sim, render, coupling,
/// app, tests). Header-only, standard library only: it sits below every other folder.

#include <cstdio>
#include <string>

namespace gale {

inline constexpr double PI = 3.14159265358979323846;

/// Bytes in a mebibyte: every size gale prints or reads (memory limits, estimates, files) is in
/// MiB.
inline constexpr double MIB = 1024.0 * 1024.0;

/// Degrees to radians, and back: the one conversion of angles in gale (every `_deg` value a scene
/// or a camera holds becomes radians here, and every angle printed in degrees comes back here).
inline constexpr double radiansFromDegrees(double deg) { return deg * (PI / 180.0); }
inline constexpr double degreesFromRadians(double rad) { return rad * (180.0 / PI); }

/// `v` with `digits` significant digits, shortest form ("%.*g": 0.5, 1e-06, 12.3, nan, inf): the
/// form of numbers in messages, reports and tables.
inline std::string formatG(double v, int digits = 6) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

/// `v` with `decimals` digits after the point ("%.*f").
inline std::string formatFixed(double v, int decimals = 2) {
    char buf[400];  // %f of the largest double needs 309 digits before the point
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

}  // namespace gale
