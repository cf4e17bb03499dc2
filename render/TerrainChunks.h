#pragma once
/// \file TerrainChunks.h
/// Level of detail by distance for shell grass, after Boulanger, Pattanaik and Bouatouch 2006
/// (geometry near, less far, the textured terrain alone farthest, with density-weighted
/// transitions). The terrain grid is cut into square chunks; each frame a chunk outside the view
/// frustum is skipped, and a visible chunk draws only the shells its distance needs.
///
/// The rule (docs/render.md): shells i = 1..N are S = h / N apart. Shell i is dropped at distances
/// beyond D(i) = D1 2^v(i), with v(i) the number of trailing zero bits of i and D1 = 2 S f / P (f
/// the focal length in pixels, P = GrassParams::lodPixels): at D(i) the shells that remain are
/// P pixels apart on screen or less. Before it is dropped, a shell thins out blade by blade (the
/// density cut of render/DensityMap.h) between 0.7 D(i) and D(i), so at D(i) it is empty and
/// dropping it changes no pixel: no popping. The ground (shell 0) is never dropped. A chunk whose
/// nearest point is at distance d draws the shells with D(i) > d: every 2^k-th shell from the
/// highest multiple of 2^k down to the ground.

#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <vector>

namespace gale::render::detail {

/// Quads per chunk side.
constexpr int kChunkQuads = 32;
/// A shell starts thinning at this fraction of its drop distance.
constexpr float kLodFadeStart = 0.7f;

struct TerrainChunk {
    uint32_t firstIndex = 0;  ///< into the terrain's index buffer
    uint32_t indexCount = 0;
    glm::vec3 wsMin_m{0.0f}, wsMax_m{0.0f};  ///< bounds of the ground, before the grass margin
};

/// Chunks of the nx x ny grid, kChunkQuads quads a side (fewer at the far edges), and their index
/// list (two triangles per quad, the order of TerrainGrid.h), appended to `indices`.
std::vector<TerrainChunk> buildChunks(int nx, int ny, const std::vector<glm::vec3>& wsPosition_m,
                                      std::vector<uint32_t>& indices);

/// True if the box [lo, hi] (world metres) may be inside the frustum of clipFromWorld: false only
/// when all eight corners are outside one clip plane.
bool boxMayBeVisible(const glm::mat4& clipFromWorld, const glm::vec3& lo, const glm::vec3& hi);

/// Distance, metres, from p to the box [lo, hi] (0 inside).
float distanceToBox(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi);

/// Distance, metres, from p to the farthest point of the box [lo, hi] (its farthest corner).
float farthestInBox(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi);

/// The shells a chunk at distance d draws: every `stride`-th shell from `top` down to 0.
struct ShellRange {
    int top = 0;
    int stride = 1;
    int count() const { return top / stride + 1; }
};

/// For N shells, drop distance D1 (metres, > 0; infinite = no LOD) and chunk distance d:
/// the smallest stride 2^k with D1 2^k > d, and the highest multiple of it <= N.
ShellRange shellRange(int shells, float d1_m, float distance_m);

/// True if a shell of `range` may have started to thin out somewhere in a chunk whose ground
/// reaches `far_m` metres from the eye: the nearest drop distance among the drawn shells above
/// the ground is D1 stride (an odd multiple of the stride has no more trailing zero bits), and
/// thinning starts at kLodFadeStart of it. False when D1 is 0 (no level of detail) or only the
/// ground is drawn. A chunk for which this is false can be drawn without the fade.
bool chunkMayFade(const ShellRange& range, float d1_m, float far_m);

}  // namespace gale::render::detail
