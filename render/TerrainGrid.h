#pragma once
/// \file TerrainGrid.h
/// Index lists of the terrain's regular vertex grid (render::TerrainMesh). Internal to render/.

#include <cstdint>
#include <vector>

namespace gale::render::detail {

/// Two triangles per quad of the sub-grid [i0, i1] x [j0, j1] (vertex indices, inclusive, i
/// fastest) of a grid nx vertices wide, taking every `step`-th vertex (the last row and column
/// always). Requires 0 <= i0 < i1 < nx, 0 <= j0 < j1, step >= 1.
inline std::vector<uint32_t> gridTriangleIndices(int nx, int i0, int i1, int j0, int j1,
                                                 int step = 1) {
    std::vector<int> is, js;
    for (int i = i0; i < i1; i += step) is.push_back(i);
    is.push_back(i1);
    for (int j = j0; j < j1; j += step) js.push_back(j);
    js.push_back(j1);
    std::vector<uint32_t> indices;
    indices.reserve((is.size() - 1) * (js.size() - 1) * 6u);
    for (size_t b = 0; b + 1 < js.size(); ++b) {
        for (size_t a = 0; a + 1 < is.size(); ++a) {
            const auto v00 = static_cast<uint32_t>(js[b] * nx + is[a]);
            const auto v10 = static_cast<uint32_t>(js[b] * nx + is[a + 1]);
            const auto v01 = static_cast<uint32_t>(js[b + 1] * nx + is[a]);
            const auto v11 = static_cast<uint32_t>(js[b + 1] * nx + is[a + 1]);
            indices.insert(indices.end(), {v00, v10, v11, v00, v11, v01});
        }
    }
    return indices;
}

}  // namespace gale::render::detail
