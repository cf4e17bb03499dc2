#pragma once
/// \file BenchCoupling.h
/// `gale bench coupling`: what the field-to-grass coupling costs and how much the paper's
/// animation-step economy gives up (docs/design.md 5, step 4):
///  - the error of the grouped bend against the exact per-vertex bend (tip displacement, in blade
///    lengths) and the per-frame cost, as the group count K goes 1, 4, 16, 64, 256: a table,
///    CSV and an SVG plot (error against per-frame cost);
///  - nanoseconds per vertex per field step (sampling the solved field at grass height, plus
///    directions, intensities and groups) and per frame, at 100k and 1M vertices.

#include <string>

namespace gale::app {

struct BenchCouplingOptions {
    std::string outputFolder = "out/bench";  ///< gets coupling.csv and coupling.svg
    std::string jsonPath;                    ///< if set, both tables as JSON
    bool quick = false;                      ///< 10k and 100k vertices, fewer frames (CI smoke)
};

/// Prints the tables; returns 0 when the targets hold (1M-vertex field step under 50 ms, per-frame
/// cost flat in the vertex count: within 3x between the sizes), 1 otherwise.
int runBenchCoupling(const BenchCouplingOptions& options);

}  // namespace gale::app
