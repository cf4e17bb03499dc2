#pragma once
/// \file GroupGrid.h
/// Where a vertex sits between animation-step groups, so the renderer can blend neighbouring
/// groups instead of showing a stripe where the group changes (render::VertexWind::groupCoord).
/// Groups that are bins of a quantity (intensity levels, arrival bands, plan tiles, rings) have a
/// natural order; a vertex's coordinate along it is its value in bin units, with bin b's centre at
/// b. The renderer then interpolates the groups' intensities linearly between bin centres.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "render/GrassInput.h"
#include "sim/Interpolation.h"

namespace gale::coupling {

/// Continuous bin coordinate of `value` in `bins` equal bins over [lo, lo + span): bin b covers
/// [b, b + 1) in bin units and its centre is at b; clamped to [0, bins - 1] (outside the first and
/// last centres the end groups hold). span > 0, bins >= 1.
inline float binCoord(double value, double lo, double span, int bins) {
    const double c = (value - lo) / span * bins - 0.5;
    return static_cast<float>(std::clamp(c, 0.0, double(bins - 1)));
}

/// Gives every group with no members a value between its nearest populated neighbours in index
/// order (linear in the index; the nearest one's value beyond the first or last), so a blend
/// towards an empty group reads a value that continues its neighbours instead of zero. Groups
/// with members keep theirs. No group populated: values are left as they are.
inline void fillEmptyGroups(std::vector<double>& values, const std::vector<uint32_t>& members) {
    const int n = static_cast<int>(values.size());
    int previous = -1;
    for (int g = 0; g <= n; ++g) {
        if (g < n && members[g] == 0) continue;
        // Groups previous+1 .. g-1 are empty; previous and g (if < n) are populated.
        for (int e = previous + 1; e < g; ++e) {
            if (previous < 0 && g == n) return;  // nothing populated
            if (previous < 0)
                values[e] = values[g];
            else if (g == n)
                values[e] = values[previous];
            else
                values[e] = values[previous] + (values[g] - values[previous]) *
                                                   double(e - previous) / double(g - previous);
        }
        previous = g;
    }
}

/// Per-vertex intensity with neighbouring groups blended as the renderer blends them: bilinear in
/// wind.groupIntensity over the group grid (VertexWind::groupColumns wide, unused cells of the last
/// row repeating the last group) at VertexWind::groupCoord; each vertex's own group where the wind
/// has no coordinates. The renderer blends tip tilts, which equal (pi/2) I up to |I| = 1/2
/// (render/Bend.h): there the two agree exactly. O(vertices); for tests and error tables.
inline std::vector<float> blendedIntensity(const render::GrassWind& wind) {
    const std::vector<uint32_t>& group = wind.group();
    std::vector<float> out(group.size());
    const int groups = static_cast<int>(wind.groupIntensity.size());
    if (!wind.vertex || groups == 0) return out;
    const std::vector<glm::vec2>& coord = wind.vertex->groupCoord;
    const int columns =
        std::clamp(wind.vertex->groupColumns > 0 ? wind.vertex->groupColumns : groups, 1, groups);
    const int rows = (groups + columns - 1) / columns;
    auto at = [&](int i, int j) {
        return double(wind.groupIntensity[std::min(j * columns + i, groups - 1)]);
    };
    // One axis of the bilinear weights: the lower cell and the fraction towards the next.
    auto split = [](float c, int cells, int& lo, int& hi, double& f) {
        const double x = std::clamp(double(c), 0.0, double(cells - 1));
        lo = static_cast<int>(std::floor(x));
        hi = std::min(lo + 1, cells - 1);
        f = x - lo;
    };
    for (size_t v = 0; v < group.size(); ++v) {
        if (coord.size() != group.size()) {
            out[v] = wind.groupIntensity[group[v]];
            continue;
        }
        int x0, x1, y0, y1;
        double fx, fy;
        split(coord[v].x, columns, x0, x1, fx);
        split(coord[v].y, rows, y0, y1, fy);
        const double bottom = sim::linearBlend(at(x0, y0), at(x1, y0), fx);
        const double top = sim::linearBlend(at(x0, y1), at(x1, y1), fx);
        out[v] = static_cast<float>(sim::linearBlend(bottom, top, fy));
    }
    return out;
}

}  // namespace gale::coupling
