#pragma once
/// \file BenchRender.h
/// `gale bench render [--json FILE]`: the paper's Table 2 (thesis Table 4.1) measured on this
/// machine, next to a trivial alpha-tested fill of the same geometry.

#include <string>

namespace gale::app {

struct BenchRenderOptions {
    std::string jsonPath;  ///< if set, the table is also written there as JSON (atomically)
    int frames = 20;       ///< timed frames per row and pass, >= 1
    bool quick = false;    ///< 2 frames and 1 warm-up per row: a smoke run, not a measurement
    /// Instead of the table: the fill profile (render::profileShellFill), 17 layers at 640 x 480,
    /// `frames` rounds of every variant.
    bool profile = false;
};

/// Runs every row (1, 9, 17, 33, 65 layers at 640x480 and 1024x768), prints the table to stdout
/// and a progress line per row to stderr; with `profile`, the fill profile's table instead. Returns
/// EXIT_OK, or EXIT_UNMET when a full table run misses a target (a profile is never judged).
/// Throws std::invalid_argument on bad options, std::runtime_error on GL or file failures.
int runBenchRender(const BenchRenderOptions& options);

}  // namespace gale::app
