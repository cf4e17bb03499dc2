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

/// Cuts level `level` of `chunk` (rows j0..j1 of a grid nx wide, cells `step` quads tall, its
/// index list in row order) into at most CHUNK_BANDS bands of whole cell rows, with their boxes.
void splitBands(TerrainChunk& chunk, int level, int nx, int j0, int j1, int step,
                const std::vector<glm::vec3>& wsPosition_m, const std::vector<uint32_t>& indices) {
    const IndexRange all = chunk.levels[level];
    const int cellRows = (j1 - j0 + step - 1) / step;
    const int bands = std::min(CHUNK_BANDS, cellRows);
    const int rowsPerBand = (cellRows + bands - 1) / bands;
    int count = 0;
    int current = -1;
    for (uint32_t t = all.first; t + 2 < all.first + all.count; t += 3) {
        // The cell row of a triangle: its lowest vertex row, rounded down to the cell grid.
        int lowest = j1;
        for (int k = 0; k < 3; ++k)
            lowest = std::min(lowest, static_cast<int>(indices[t + k] / static_cast<uint32_t>(nx)));
        const int band = std::min(((lowest - j0) / step) / rowsPerBand, bands - 1);
        if (band != current) {
            // Row order makes the bands contiguous; anything else keeps the level whole.
            if (band < current) {
                chunk.bands[level][0] = {all, chunk.wsMin_m, chunk.wsMax_m};
                chunk.bandCount[level] = 1;
                return;
            }
            current = band;
            chunk.bands[level][count] = {
                {t, 0u}, wsPosition_m[indices[t]], wsPosition_m[indices[t]]};
            ++count;
        }
        ChunkBand& b = chunk.bands[level][count - 1];
        b.range.count += 3;
        for (int k = 0; k < 3; ++k) {
            b.wsMin_m = glm::min(b.wsMin_m, wsPosition_m[indices[t + k]]);
            b.wsMax_m = glm::max(b.wsMax_m, wsPosition_m[indices[t + k]]);
        }
    }
    chunk.bandCount[level] = count;
}

}  // namespace

std::vector<TerrainChunk> buildChunks(int nx, int ny, const std::vector<glm::vec3>& wsPosition_m,
                                      std::vector<uint32_t>& indices) {
    std::vector<TerrainChunk> chunks;
    std::vector<std::array<int, 4>> spans;  // i0, i1, j0, j1 of each chunk
    const auto position = [&](int i, int j) -> const glm::vec3& {
        return wsPosition_m[static_cast<size_t>(j) * nx + i];
    };
    for (int j0 = 0; j0 + 1 < ny; j0 += CHUNK_QUADS) {
        for (int i0 = 0; i0 + 1 < nx; i0 += CHUNK_QUADS) {
            const int i1 = std::min(i0 + CHUNK_QUADS, nx - 1),
                      j1 = std::min(j0 + CHUNK_QUADS, ny - 1);
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
            splitBands(chunk, 0, nx, j0, j1, 1, wsPosition_m, indices);
            chunks.push_back(chunk);
            spans.push_back({i0, i1, j0, j1});
        }
    }
    // The coarser levels after every chunk's full mesh, so the full mesh stays one contiguous
    // range (the whole terrain in one draw, as the benchmark's fill baseline draws it).
    for (size_t c = 0; c < chunks.size(); ++c) {
        const auto [i0, i1, j0, j1] = spans[c];
        for (int level = 1; level < MESH_LEVELS; ++level) {
            const int step = 1 << level;
            if ((i1 - i0) % step != 0 || (j1 - j0) % step != 0) break;
            const std::vector<uint32_t> own = stitchedLevel(nx, i0, i1, j0, j1, step);
            chunks[c].levels[level] = {static_cast<uint32_t>(indices.size()),
                                       static_cast<uint32_t>(own.size())};
            chunks[c].levelCount = level + 1;
            indices.insert(indices.end(), own.begin(), own.end());
            chunks[c].levelError_m[level] =
                meshLevelError(nx, wsPosition_m, indices, chunks[c].levels[level]);
            splitBands(chunks[c], level, nx, j0, j1, step, wsPosition_m, indices);
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

float meshLevelError(int nx, const std::vector<glm::vec3>& wsPosition_m,
                     const std::vector<uint32_t>& indices, IndexRange range) {
    float error_m = 0.0f;
    for (uint32_t t = range.first; t + 2 < range.first + range.count; t += 3) {
        // The triangle in grid-index space, where the vertices inside it are the integer points.
        int gi[3], gj[3];
        float z[3];
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = indices[t + k];
            gi[k] = static_cast<int>(v % static_cast<uint32_t>(nx));
            gj[k] = static_cast<int>(v / static_cast<uint32_t>(nx));
            z[k] = wsPosition_m[v].z;
        }
        const int twiceArea = (gi[1] - gi[0]) * (gj[2] - gj[0]) - (gj[1] - gj[0]) * (gi[2] - gi[0]);
        if (twiceArea == 0) continue;
        const int iLo = std::min({gi[0], gi[1], gi[2]}), iHi = std::max({gi[0], gi[1], gi[2]});
        const int jLo = std::min({gj[0], gj[1], gj[2]}), jHi = std::max({gj[0], gj[1], gj[2]});
        for (int j = jLo; j <= jHi; ++j)
            for (int i = iLo; i <= iHi; ++i) {
                // Barycentric weights times twice the area, exact in integers.
                const int w0 = (gi[1] - i) * (gj[2] - j) - (gj[1] - j) * (gi[2] - i);
                const int w1 = (gi[2] - i) * (gj[0] - j) - (gj[2] - j) * (gi[0] - i);
                const int w2 = twiceArea - w0 - w1;
                if ((twiceArea > 0) ? (w0 < 0 || w1 < 0 || w2 < 0) : (w0 > 0 || w1 > 0 || w2 > 0))
                    continue;
                const float surface_m =
                    (static_cast<float>(w0) * z[0] + static_cast<float>(w1) * z[1] +
                     static_cast<float>(w2) * z[2]) /
                    static_cast<float>(twiceArea);
                const float vertex_m = wsPosition_m[static_cast<size_t>(j) * nx + i].z;
                error_m = std::max(error_m, std::abs(vertex_m - surface_m));
            }
    }
    return error_m;
}

int meshLevel(const TerrainChunk& chunk, float focal_px, float lodPixels, float near_m) {
    if (!(lodPixels > 0.0f) || !(focal_px > 0.0f) || !(chunk.quad_m > 0.0f)) return 0;
    // Cells of 2^l quads span 2^l quad_m focal_px / near_m pixels at the chunk's nearest point,
    // and a height error e spans e focal_px / near_m pixels there.
    const auto cellFits = [&](int level, float perLodPixel) {
        return static_cast<float>(1 << level) * chunk.quad_m * focal_px <=
               perLodPixel * lodPixels * near_m;
    };
    int level = 0;
    while (level + 1 < chunk.levelCount && cellFits(level + 1, MESH_CELL_PER_LOD_PIXEL)) ++level;
    int flat = 0;
    while (flat + 1 < chunk.levelCount && cellFits(flat + 1, MESH_FLAT_CELL_PER_LOD_PIXEL) &&
           chunk.levelError_m[flat + 1] * focal_px <= MESH_ERROR_PER_LOD_PIXEL * lodPixels * near_m)
        ++flat;
    return std::max(level, flat);
}

bool chunkMayFade(const ShellRange& range, int shells, float d1_m, float far_m) {
    if (!(d1_m > 0.0f) || !std::isfinite(d1_m) || shells <= 0) return false;
    // Dropped shells: the drawn ones shade their blades where they were seen (shell.frag). With
    // every shell drawn (stride 1, the ground drawn too), the first to thin out are the odd ones,
    // at LOD_FADE_START D1.
    if (range.stride > 1) return true;
    return far_m >= LOD_FADE_START * d1_m;
}

}  // namespace gale::render::detail
