#include "coupling/TerrainMeshBuilder.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "base/Numbers.h"
#include "base/ParameterError.h"

namespace gale::coupling {
namespace {

// Sample indices 0, stride, 2 stride, ... and always the last one.
std::vector<int> strided(int n, int stride) {
    std::vector<int> idx;
    for (int i = 0; i < n - 1; i += stride) idx.push_back(i);
    idx.push_back(n - 1);
    return idx;
}

}  // namespace

render::TerrainMesh buildTerrainMesh(const sim::Heightfield& field, float tile_m, int stride) {
    if (stride < 1)
        throw ParameterError("terrain.mesh_stride", std::to_string(stride), "must be >= 1");
    if (!std::isfinite(tile_m) || tile_m <= 0.0f)
        throw ParameterError("grass.tile_m", formatG(tile_m), "must be finite and > 0");
    if (field.nx < 2 || field.ny < 2) throw std::logic_error("heightfield smaller than 2x2");
    const std::vector<int> is = strided(field.nx, stride), js = strided(field.ny, stride);
    render::TerrainMesh mesh;
    mesh.nx = static_cast<int>(is.size());
    mesh.ny = static_cast<int>(js.size());
    const size_t count = is.size() * js.size();
    mesh.wsPosition_m.reserve(count);
    mesh.wsNormal.reserve(count);
    mesh.uv.reserve(count);
    for (int j : js) {
        for (int i : is) {
            const double x = field.originX_m + i * field.spacing_m;
            const double y = field.originY_m + j * field.spacing_m;
            const auto n = field.normalAt(i, j);
            mesh.wsPosition_m.emplace_back(x, y, field.at(i, j));
            mesh.wsNormal.emplace_back(n[0], n[1], n[2]);
            mesh.uv.emplace_back(x / tile_m, y / tile_m);
        }
    }
    return mesh;
}

}  // namespace gale::coupling
