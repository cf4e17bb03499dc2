#pragma once
/// \file Timing.h
/// Wall-clock intervals for the program's reports, progress lines and benchmarks (steady clock,
/// never adjusted).

#include <chrono>

namespace gale::app {

using Clock = std::chrono::steady_clock;

/// Seconds from `start` to now.
inline double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Milliseconds from `start` to now.
inline double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace gale::app
