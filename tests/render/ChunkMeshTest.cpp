// Coarser meshes for distant terrain chunks (render/TerrainChunks.h): every level covers its chunk
// exactly once, neighbours at any two levels share their border heights (no crack), and the level
// follows the distance.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/vector_relational.hpp>
#include <map>
#include <utility>
#include <vector>

#include "RenderTestUtil.h"
#include "render/TerrainChunks.h"

namespace gale::render {
namespace {

// Rough ground, so that a coarse mesh's interior differs from the full mesh's and a crack would
// show as a height difference: 97 x 65 vertices, 1 m apart (chunks of 32 quads: 3 x 2).
float bumpy(float x, float y) { return 2.0f * std::sin(0.9f * x) * std::cos(0.7f * y) + 0.05f * x; }

struct ChunkedGrid {
    TerrainMesh mesh = test::makeGridMesh(97, 65, 48.0f, 1.0f, [](float x, float y) {
        return bumpy(x, y * 32.0f / 48.0f);  // 1 m spacing on both axes
    });
    std::vector<uint32_t> indices;
    std::vector<detail::TerrainChunk> chunks =
        detail::buildChunks(mesh.nx, mesh.ny, mesh.wsPosition_m, indices);
};

double planArea(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    return 0.5 * (double(b.x - a.x) * (c.y - a.y) - double(b.y - a.y) * (c.x - a.x));
}

TEST(ChunkMesh, EveryLevelCoversItsChunkOnceCounterClockwise) {
    const ChunkedGrid g;
    ASSERT_EQ(g.chunks.size(), 6u);
    // Plan areas in square metres of float coordinates: sums of ~2000 terms.
    constexpr double AREA_TOLERANCE = 1e-3;
    for (const detail::TerrainChunk& c : g.chunks) {
        EXPECT_EQ(c.levelCount, detail::MESH_LEVELS);  // 32 x 32 quads: steps 1 .. 32
        const double chunkArea =
            double(c.wsMax_m.x - c.wsMin_m.x) * double(c.wsMax_m.y - c.wsMin_m.y);
        for (int l = 0; l < c.levelCount; ++l) {
            const detail::IndexRange r = c.levels[l];
            ASSERT_EQ(r.count % 3, 0u);
            double sum = 0.0;
            for (uint32_t t = r.first; t < r.first + r.count; t += 3) {
                const double a = planArea(g.mesh.wsPosition_m[g.indices[t]],
                                          g.mesh.wsPosition_m[g.indices[t + 1]],
                                          g.mesh.wsPosition_m[g.indices[t + 2]]);
                EXPECT_GT(a, 0.0) << "level " << l << ": a flipped or degenerate triangle";
                sum += a;
            }
            // All triangles counter-clockwise and their areas adding up to the chunk's: no
            // overlap and no hole.
            EXPECT_NEAR(sum, chunkArea, AREA_TOLERANCE) << "level " << l;
            if (l > 0) {
                EXPECT_LT(r.count, c.levels[l - 1].count) << "level " << l;
            }
        }
    }
}

// The border of one chunk level: each edge used by exactly one of its triangles, as a segment
// with its end heights.
std::vector<std::pair<glm::vec3, glm::vec3>> borderEdges(const ChunkedGrid& g,
                                                         const detail::IndexRange& r) {
    std::map<std::pair<uint32_t, uint32_t>, int> uses;
    for (uint32_t t = r.first; t < r.first + r.count; t += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = g.indices[t + k], b = g.indices[t + (k + 1) % 3];
            ++uses[{std::min(a, b), std::max(a, b)}];
        }
    std::vector<std::pair<glm::vec3, glm::vec3>> edges;
    for (const auto& [edge, n] : uses)
        if (n == 1)
            edges.emplace_back(g.mesh.wsPosition_m[edge.first], g.mesh.wsPosition_m[edge.second]);
    return edges;
}

// Height of the border at plan point (x, y) from the border edge through it (NaN if none).
float borderHeight(const std::vector<std::pair<glm::vec3, glm::vec3>>& edges, float x, float y) {
    constexpr float ON_EDGE_M = 1e-4f;  // float plan coordinates of a 96 m grid
    for (const auto& [a, b] : edges) {
        const glm::vec2 ab(b.x - a.x, b.y - a.y), ap(x - a.x, y - a.y);
        const float len2 = glm::dot(ab, ab);
        const float t = glm::dot(ap, ab) / len2;
        if (t < -ON_EDGE_M || t > 1.0f + ON_EDGE_M) continue;
        if (std::abs(ab.x * ap.y - ab.y * ap.x) / std::sqrt(len2) > ON_EDGE_M) continue;
        return a.z + std::clamp(t, 0.0f, 1.0f) * (b.z - a.z);
    }
    return NAN;
}

TEST(ChunkMesh, CoarseChunksMeetTheirNeighboursWithoutCracks) {
    // Along every side two chunks share, the border of each at every level has the heights of
    // the full-resolution grid, so any two levels meet exactly: no crack. The oracle is the
    // grid's own vertices and, between them, the straight full-resolution edge.
    const ChunkedGrid g;
    constexpr float HEIGHT_TOLERANCE_M = 1e-5f;  // float interpolation on heights up to 4.5 m
    const auto gridHeight = [&](int i, int j, float t, bool alongX) {
        const glm::vec3& a = g.mesh.wsPosition_m[size_t(j) * g.mesh.nx + i];
        const glm::vec3& b =
            g.mesh.wsPosition_m[size_t(j + (alongX ? 0 : 1)) * g.mesh.nx + i + (alongX ? 1 : 0)];
        return std::pair<glm::vec2, float>(glm::vec2(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)),
                                           a.z + t * (b.z - a.z));
    };
    // Chunk (ci, cj) is chunks[cj * 3 + ci]; shared sides: x = 32, 64 (vertex columns), y = 32.
    struct Side {
        int chunkA, chunkB;
        bool vertical;  // a line of constant i (else constant j)
        int line, from, to;
    };
    const Side sides[] = {{0, 1, true, 32, 0, 32},  {1, 2, true, 64, 0, 32},
                          {3, 4, true, 32, 32, 64}, {4, 5, true, 64, 32, 64},
                          {0, 3, false, 32, 0, 32}, {1, 4, false, 32, 32, 64},
                          {2, 5, false, 32, 64, 96}};
    int compared = 0;
    for (const Side& side : sides)
        for (int la = 0; la < detail::MESH_LEVELS; ++la)
            for (int lb = 0; lb < detail::MESH_LEVELS; ++lb) {
                const auto ea = borderEdges(g, g.chunks[side.chunkA].levels[la]);
                const auto eb = borderEdges(g, g.chunks[side.chunkB].levels[lb]);
                for (int k = side.from; k < side.to; ++k)
                    for (float t : {0.0f, 0.37f, 0.5f}) {
                        const auto [p, z] = side.vertical ? gridHeight(side.line, k, t, false)
                                                          : gridHeight(k, side.line, t, true);
                        const float za = borderHeight(ea, p.x, p.y);
                        const float zb = borderHeight(eb, p.x, p.y);
                        ASSERT_FALSE(std::isnan(za) || std::isnan(zb))
                            << "no border edge at (" << p.x << ", " << p.y << ")";
                        EXPECT_NEAR(za, z, HEIGHT_TOLERANCE_M) << "levels " << la << ", " << lb;
                        EXPECT_NEAR(zb, z, HEIGHT_TOLERANCE_M) << "levels " << la << ", " << lb;
                        ++compared;
                    }
            }
    EXPECT_EQ(compared, 7 * 36 * 32 * 3);
}

TEST(ChunkMesh, TheLevelCoarsensWithDistanceAndKeepsCellsWithinThePixelBudget) {
    const ChunkedGrid g;
    const detail::TerrainChunk& c = g.chunks[0];
    // 1 m apart in plan; the bumps' slope is at most 1.8 + 0.05 (bumpy's gradient).
    EXPECT_GE(c.quad_m, 1.0f);
    EXPECT_LE(c.quad_m, std::hypot(1.0f, 1.85f));
    const float focal_px = 500.0f, lodPixels = 2.0f;
    const float budget_px = detail::MESH_CELL_PER_LOD_PIXEL * lodPixels;
    int previous = 0;
    for (float d : {0.0f, 1.0f, 10.0f, 50.0f, 100.0f, 300.0f, 1000.0f, 1e6f}) {
        const int l = detail::meshLevel(c, focal_px, lodPixels, d);
        ASSERT_GE(l, 0);
        ASSERT_LT(l, c.levelCount);
        EXPECT_GE(l, previous) << d << " m";
        if (l > 0) {
            EXPECT_LE(float(1 << l) * c.quad_m * focal_px / d, budget_px) << d << " m";
        }
        // One level coarser would not fit: the coarsest that fits is taken.
        if (l + 1 < c.levelCount) {
            EXPECT_GT(float(2 << l) * c.quad_m * focal_px, budget_px * d) << d << " m";
        }
        previous = l;
    }
    EXPECT_EQ(detail::meshLevel(c, focal_px, lodPixels, 1e6f), detail::MESH_LEVELS - 1);
    EXPECT_EQ(detail::meshLevel(c, focal_px, 0.0f, 1e6f), 0);  // no level of detail
}

TEST(ChunkMesh, RowBandsSplitEveryLevelInOrderAndBoundTheirTriangles) {
    const ChunkedGrid g;
    for (const detail::TerrainChunk& c : g.chunks)
        for (int l = 0; l < c.levelCount; ++l) {
            const int bands = c.bandCount[l];
            ASSERT_GE(bands, 1);
            ASSERT_LE(bands, detail::CHUNK_BANDS);
            // 32 cell rows at level 0: four bands of 8 rows, 32 x 8 quads of 2 triangles each.
            if (l == 0) {
                EXPECT_EQ(bands, detail::CHUNK_BANDS);
                for (int b = 0; b < bands; ++b) EXPECT_EQ(c.bands[0][b].range.count, 32u * 8u * 6u);
            }
            uint32_t next = c.levels[l].first;
            for (int b = 0; b < bands; ++b) {
                const detail::ChunkBand& band = c.bands[l][b];
                EXPECT_EQ(band.range.first, next) << "level " << l << " band " << b;
                next = band.range.first + band.range.count;
                for (uint32_t t = band.range.first; t < next; ++t) {
                    const glm::vec3& p = g.mesh.wsPosition_m[g.indices[t]];
                    EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, band.wsMin_m)) &&
                                glm::all(glm::lessThanEqual(p, band.wsMax_m)))
                        << "level " << l << " band " << b;
                }
                if (b > 0) {
                    EXPECT_LE(c.bands[l][b - 1].wsMin_m.y, band.wsMin_m.y);  // south first
                }
            }
            EXPECT_EQ(next, c.levels[l].first + c.levels[l].count) << "level " << l;
        }
}

// A 33 x 33 grid, 1 m apart: one chunk, levels 0..5.
TerrainMesh singleChunk(float (*height)(float, float)) {
    return test::makeGridMesh(33, 33, 16.0f, 1.0f, height);
}

TEST(ChunkMesh, LevelErrorIsZeroOnAPlaneAndTheSpikeHeightWhereASpikeIsCut) {
    // A tilted plane is reproduced exactly by every level; a single raised vertex (at grid
    // index (3, 5): odd, so no coarse level keeps it and every coarse triangle over it lies in
    // the flat ground) is missed by exactly its height.
    constexpr float SPIKE_M = 0.75f;
    // Heights of tens of centimetres interpolated in float: a few ulps.
    constexpr float ERROR_TOLERANCE_M = 1e-5f;
    const TerrainMesh plane = singleChunk([](float x, float y) { return 0.1f * x - 0.05f * y; });
    const TerrainMesh spike = singleChunk([](float x, float y) {
        return (std::abs(x - (-13.0f)) < 0.1f && std::abs(y - (-11.0f)) < 0.1f) ? SPIKE_M : 0.0f;
    });
    for (const TerrainMesh* mesh : {&plane, &spike}) {
        std::vector<uint32_t> indices;
        const auto chunks = detail::buildChunks(mesh->nx, mesh->ny, mesh->wsPosition_m, indices);
        ASSERT_EQ(chunks.size(), 1u);
        ASSERT_EQ(chunks[0].levelCount, detail::MESH_LEVELS);
        EXPECT_EQ(chunks[0].levelError_m[0], 0.0f);
        for (int l = 1; l < detail::MESH_LEVELS; ++l) {
            const float expected = mesh == &plane ? 0.0f : SPIKE_M;
            EXPECT_NEAR(chunks[0].levelError_m[l], expected, ERROR_TOLERANCE_M) << "level " << l;
            EXPECT_NEAR(
                detail::meshLevelError(mesh->nx, mesh->wsPosition_m, indices, chunks[0].levels[l]),
                expected, ERROR_TOLERANCE_M);
        }
    }
}

TEST(ChunkMesh, FlatGroundTakesCellsUpToTheFlatBudgetAndRoughGroundDoesNot) {
    const float focal_px = 500.0f, lodPixels = 2.0f;
    const TerrainMesh flat = singleChunk([](float, float) { return 0.0f; });
    std::vector<uint32_t> indices;
    const auto chunks = detail::buildChunks(flat.nx, flat.ny, flat.wsPosition_m, indices);
    const detail::TerrainChunk& f = chunks[0];
    const ChunkedGrid rough;
    const detail::TerrainChunk& r = rough.chunks[0];
    for (float d : {5.0f, 20.0f, 60.0f, 150.0f}) {
        const int lf = detail::meshLevel(f, focal_px, lodPixels, d);
        // Flat: the coarsest level whose cells span at most the flat budget on screen.
        int expected = 0;
        while (expected + 1 < f.levelCount && float(2 << expected) * f.quad_m * focal_px / d <=
                                                  detail::MESH_FLAT_CELL_PER_LOD_PIXEL * lodPixels)
            ++expected;
        EXPECT_EQ(lf, expected) << d << " m";
        // Rough (bumps 2 m high, 1 m apart): only the small-cell rule, as before.
        const int lr = detail::meshLevel(r, focal_px, lodPixels, d);
        if (lr > 0) {
            EXPECT_LE(float(1 << lr) * r.quad_m * focal_px / d,
                      detail::MESH_CELL_PER_LOD_PIXEL * lodPixels)
                << d << " m";
        }
        EXPECT_LE(lr, lf) << d << " m";
    }
    EXPECT_GT(detail::meshLevel(f, focal_px, lodPixels, 20.0f),
              detail::meshLevel(r, focal_px, lodPixels, 20.0f));
}

}  // namespace
}  // namespace gale::render
