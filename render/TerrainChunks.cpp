#include "render/TerrainChunks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include "render/TerrainGrid.h"

namespace gale::render::detail {

namespace {

/// Level `step` of the chunk [i0, i1] x [j0, j1] (vertex indices, inclusive) of a grid nx wide:
/// interior cells as two triangles, border cells as fans around their centre through every
/// vertex of their border sides. Requires step >= 2 dividing i1 - i0 and j1 - j0.
std::vector<uint32_t> stitchedLevel(int nx, int i0, int i1, int j0, int j1, int step) {
    const auto at = [nx](int i, int j) { return static_cast<uint32_t>(j * nx + i); };
    std::vector<uint32_t> out;
    std::vector<uint32_t> ring;
    for (int y = j0; y < j1; y += step) {
        for (int x = i0; x < i1; x += step) {
            const int x1 = x + step, y1 = y + step;
            const bool south = y == j0, east = x1 == i1, north = y1 == j1, west = x == i0;
            if (!(south || east || north || west)) {
                out.insert(out.end(),
                           {at(x, y), at(x1, y), at(x1, y1), at(x, y), at(x1, y1), at(x, y1)});
                continue;
            }
            // Counter-clockwise round the cell; a side on the chunk's border keeps every vertex.
            ring.clear();
            for (int k = 0; k < step; k += south ? 1 : step) ring.push_back(at(x + k, y));
            for (int k = 0; k < step; k += east ? 1 : step) ring.push_back(at(x1, y + k));
            for (int k = 0; k < step; k += north ? 1 : step) ring.push_back(at(x1 - k, y1));
            for (int k = 0; k < step; k += west ? 1 : step) ring.push_back(at(x, y1 - k));
            const uint32_t centre = at(x + step / 2, y + step / 2);
            for (size_t k = 0; k < ring.size(); ++k)
                out.insert(out.end(), {centre, ring[k], ring[(k + 1) % ring.size()]});
        }
    }
    return out;
}

}  // namespace

std::vector<TerrainChunk> buildChunks(int nx, int ny, const std::vector<glm::vec3>& wsPosition_m,
                                      std::vector<uint32_t>& indices) {
    std::vector<TerrainChunk> chunks;
    std::vector<std::array<int, 4>> spans;  // i0, i1, j0, j1 of each chunk
    const auto position = [&](int i, int j) -> const glm::vec3& {
        return wsPosition_m[static_cast<size_t>(j) * nx + i];
    };
    for (int j0 = 0; j0 + 1 < ny; j0 += kChunkQuads) {
        for (int i0 = 0; i0 + 1 < nx; i0 += kChunkQuads) {
            const int i1 = std::min(i0 + kChunkQuads, nx - 1),
                      j1 = std::min(j0 + kChunkQuads, ny - 1);
            TerrainChunk chunk;
            chunk.wsMin_m = chunk.wsMax_m = position(i0, j0);
            for (int j = j0; j <= j1; ++j)
                for (int i = i0; i <= i1; ++i) {
                    const glm::vec3& p = position(i, j);
                    chunk.wsMin_m = glm::min(chunk.wsMin_m, p);
                    chunk.wsMax_m = glm::max(chunk.wsMax_m, p);
                    if (i < i1)
                        chunk.quad_m = std::max(chunk.quad_m, glm::distance(p, position(i + 1, j)));
                    if (j < j1)
                        chunk.quad_m = std::max(chunk.quad_m, glm::distance(p, position(i, j + 1)));
                }
            const std::vector<uint32_t> own = gridTriangleIndices(nx, i0, i1, j0, j1);
            chunk.levels[0] = {static_cast<uint32_t>(indices.size()),
                               static_cast<uint32_t>(own.size())};
            chunk.firstIndex = chunk.levels[0].first;
            chunk.indexCount = chunk.levels[0].count;
            indices.insert(indices.end(), own.begin(), own.end());
            chunks.push_back(chunk);
            spans.push_back({i0, i1, j0, j1});
        }
    }
    // The coarser levels after every chunk's full mesh, so the full mesh stays one contiguous
    // range (the whole terrain in one draw, as the benchmark's fill baseline draws it).
    for (size_t c = 0; c < chunks.size(); ++c) {
        const auto [i0, i1, j0, j1] = spans[c];
        for (int level = 1; level < kMeshLevels; ++level) {
            const int step = 1 << level;
            if ((i1 - i0) % step != 0 || (j1 - j0) % step != 0) break;
            const std::vector<uint32_t> own = stitchedLevel(nx, i0, i1, j0, j1, step);
            chunks[c].levels[level] = {static_cast<uint32_t>(indices.size()),
                                       static_cast<uint32_t>(own.size())};
            chunks[c].levelCount = level + 1;
            indices.insert(indices.end(), own.begin(), own.end());
        }
    }
    return chunks;
}

bool boxMayBeVisible(const glm::mat4& clipFromWorld, const glm::vec3& lo, const glm::vec3& hi) {
    // Count corners outside each of the six planes -w <= x, y, z <= w.
    int outside[6] = {0, 0, 0, 0, 0, 0};
    for (int c = 0; c < 8; ++c) {
        const glm::vec4 p = clipFromWorld * glm::vec4((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y,
                                                      (c & 4) ? hi.z : lo.z, 1.0f);
        outside[0] += p.x < -p.w;
        outside[1] += p.x > p.w;
        outside[2] += p.y < -p.w;
        outside[3] += p.y > p.w;
        outside[4] += p.z < -p.w;
        outside[5] += p.z > p.w;
    }
    for (int plane = 0; plane < 6; ++plane)
        if (outside[plane] == 8) return false;
    return true;
}

float distanceToBox(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi) {
    return glm::length(glm::max(glm::max(lo - p, p - hi), glm::vec3(0.0f)));
}

float farthestInBox(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi) {
    return glm::length(glm::max(glm::abs(p - lo), glm::abs(hi - p)));
}

ShellRange shellRange(int shells, float d1_m, float distance_m) {
    ShellRange range;
    range.top = shells;
    if (!(d1_m > 0.0f) || !std::isfinite(d1_m) || shells <= 0) return range;
    int stride = 1;
    // Strides beyond the shell count draw the ground alone; stop doubling there.
    while (stride <= shells && d1_m * static_cast<float>(stride) <= distance_m) stride *= 2;
    range.stride = stride;
    range.top = shells - shells % stride;
    return range;
}

int meshLevel(const TerrainChunk& chunk, float focal_px, float lodPixels, float near_m) {
    if (!(lodPixels > 0.0f) || !(focal_px > 0.0f) || !(chunk.quad_m > 0.0f)) return 0;
    // Cells of 2^l quads span 2^l quad_m focal_px / near_m pixels at the chunk's nearest point.
    const float budget_px = kMeshCellPerLodPixel * lodPixels;
    int level = 0;
    while (level + 1 < chunk.levelCount &&
           static_cast<float>(2 << level) * chunk.quad_m * focal_px <= budget_px * near_m)
        ++level;
    return level;
}

bool chunkMayFade(const ShellRange& range, int shells, float d1_m, float far_m) {
    if (!(d1_m > 0.0f) || !std::isfinite(d1_m) || shells <= 0) return false;
    int lastShell = 1;
    while (lastShell * 2 <= shells) lastShell *= 2;
    const int nearestDrop = range.top > 0 ? std::min(range.stride, lastShell) : lastShell;
    return far_m >= kLodFadeStart * d1_m * static_cast<float>(nearestDrop);
}

}  // namespace gale::render::detail
