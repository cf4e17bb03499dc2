#pragma once
/// \file Format.h
/// Small helpers every sim/ file shares: numbers in messages (default stream formatting: "0.5",
/// "1e-06", "nan") and the smoothstep ramp.

#include <string>

#include "base/Numbers.h"

namespace gale::sim::detail {

inline std::string num(double v) { return formatG(v); }

/// Hermite smoothstep on [0, 1]: 0 below, 1 above, C1 in between.
inline double smoothstep(double x) { return x <= 0 ? 0.0 : x >= 1 ? 1.0 : x * x * (3.0 - 2.0 * x); }

}  // namespace gale::sim::detail
