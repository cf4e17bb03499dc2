#include "render/TerrainChunks.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include "render/TerrainGrid.h"

namespace gale::render::detail {

std::vector<TerrainChunk> buildChunks(int nx, int ny, const std::vector<glm::vec3>& wsPosition_m,
                                      std::vector<uint32_t>& indices) {
    std::vector<TerrainChunk> chunks;
    for (int j0 = 0; j0 + 1 < ny; j0 += kChunkQuads) {
        for (int i0 = 0; i0 + 1 < nx; i0 += kChunkQuads) {
            const int i1 = std::min(i0 + kChunkQuads, nx - 1),
                      j1 = std::min(j0 + kChunkQuads, ny - 1);
            const std::vector<uint32_t> own = gridTriangleIndices(nx, i0, i1, j0, j1);
            TerrainChunk chunk;
            chunk.firstIndex = static_cast<uint32_t>(indices.size());
            chunk.indexCount = static_cast<uint32_t>(own.size());
            chunk.wsMin_m = chunk.wsMax_m = wsPosition_m[static_cast<size_t>(j0) * nx + i0];
            for (int j = j0; j <= j1; ++j)
                for (int i = i0; i <= i1; ++i) {
                    const glm::vec3& p = wsPosition_m[static_cast<size_t>(j) * nx + i];
                    chunk.wsMin_m = glm::min(chunk.wsMin_m, p);
                    chunk.wsMax_m = glm::max(chunk.wsMax_m, p);
                }
            indices.insert(indices.end(), own.begin(), own.end());
            chunks.push_back(chunk);
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

bool chunkMayFade(const ShellRange& range, float d1_m, float far_m) {
    if (!(d1_m > 0.0f) || !std::isfinite(d1_m) || range.top <= 0) return false;
    return far_m >= kLodFadeStart * d1_m * static_cast<float>(range.stride);
}

}  // namespace gale::render::detail
