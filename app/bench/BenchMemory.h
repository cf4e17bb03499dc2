#pragma once
/// \file BenchMemory.h
/// `gale bench memory`: the memory estimate against the peak resident memory the kernel measured,
/// for steady, unsteady and rendering runs from thin tall boxes to wide flat ones. Each shape is a
/// scene written to a private folder and run by a child `gale solve` or `gale render`; the
/// estimate is the one the child put in its report (the number its memory limit checks), the peak
/// is the child's ru_maxrss from wait4. Table to stdout, progress lines to stderr.

#include <string>

namespace gale::app {

struct BenchMemoryOptions {
    std::string jsonPath;  ///< if set, the table as JSON (atomically)
    bool quick = false;    ///< 4 small shapes (a few seconds each): the CI check of the bound
};

/// The bound the estimate must hold: peak / estimate within [1 / ratio, ratio].
inline constexpr double MEMORY_ESTIMATE_RATIO_BOUND = 1.3;

/// Runs every shape. Returns EXIT_OK when every ratio is within MEMORY_ESTIMATE_RATIO_BOUND and
/// every child exited 0, EXIT_UNMET otherwise (the table is written either way). Throws
/// std::runtime_error when the scratch folder or the JSON cannot be written.
int runBenchMemory(const BenchMemoryOptions& options);

}  // namespace gale::app
