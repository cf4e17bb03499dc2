#pragma once
/// \file SvgPlot.h
/// Log-log line plots as SVG, for the benchmarks' error-against-run-time studies (a person would
/// rather look at the curve than read the CSV beside it).

#include <array>
#include <string>
#include <vector>

namespace gale::app {

/// One line of a plot: points (x, y) > 0, optional per-point labels.
struct Series {
    std::string name, colour;
    bool dashed = false;
    std::vector<std::array<double, 2>> xy;
    std::vector<std::string> labels;
};

/// A 760 x 500 SVG with decade grid lines and a legend; points with x or y <= 0 are skipped when
/// fitting the axes.
std::string logLogSvg(const std::string& title, const std::string& xLabel,
                      const std::string& yLabel, const std::vector<Series>& series);

}  // namespace gale::app
