#pragma once
/// \file TerrainChunks.h
/// Level of detail by distance for shell grass, after Boulanger, Pattanaik and Bouatouch 2006
/// (geometry near, less far, the textured terrain alone farthest, with density-weighted
/// transitions). The terrain grid is cut into square chunks; each frame a chunk outside the view
/// frustum is skipped, and a visible chunk draws only the shells its distance needs.
///
/// The rule (docs/render.md): the whole stack of shells 1..N is dropped together beyond
/// D = 2 h f / P (h the grass height, f the focal length in pixels, P = GrassParams::lodPixels),
/// where the grass is P / 2 pixels tall on screen. Between 0.7 D and D every shell thins out blade
/// by blade (the density cut of render/DensityMap.h) while the ground (shell 0, never dropped)
/// takes over the look of the grass's top, so at D the shells are empty and dropping them changes
/// no pixel: no popping. Shells are not dropped one by one by distance (an earlier rule dropped
/// every other shell at D / 8, and so on): a thinner stack lets a ray reach the darker roots and
/// the soil, and drew a dark band across every hill seen from above (tests/render/SeamTest.cpp).
/// A chunk whose nearest point is nearer than D draws every shell; beyond D, the ground alone.

#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <vector>

namespace gale::render::detail {

/// Quads per chunk side.
constexpr int CHUNK_QUADS = 32;
/// A shell starts thinning at this fraction of its drop distance.
constexpr float LOD_FADE_START = 0.7f;
/// Mesh levels per chunk: level l takes every 2^l-th vertex inside the chunk (l = 5: one coarse
/// cell per 32-quad chunk).
constexpr int MESH_LEVELS = 6;
/// A chunk may always take a mesh level whose cells are at most this many times
/// GrassParams::lodPixels across on screen (default 2 px: 8-pixel cells; the ground is smooth at
/// that scale, and a software rasteriser pays per vertex and per small triangle).
constexpr float MESH_CELL_PER_LOD_PIXEL = 4.0f;
/// Where the ground is flat at the chunk's scale, larger cells: a level whose surface stays within
/// MESH_ERROR_PER_LOD_PIXEL lodPixels (on screen, at the chunk's nearest point) of the full mesh's
/// vertices, with cells up to MESH_FLAT_CELL_PER_LOD_PIXEL lodPixels across (default 1 px and 64
/// px). The cap keeps the per-vertex wind and light sampled finely enough near the camera: a cell
/// 64 px wide at 7 m is 0.9 m of ground, finer than the gust fronts and whirlwind cores of the
/// examples. Measured on examples/knoll.toml (docs/render.md, "Where a frame's time goes"): the
/// full mesh near the camera was 70 % of the frame's triangles and half its rasteriser time.
constexpr float MESH_ERROR_PER_LOD_PIXEL = 0.5f;
constexpr float MESH_FLAT_CELL_PER_LOD_PIXEL = 32.0f;

/// Row bands per chunk: each mesh level's index list is also cut into bands of whole rows, each
/// with its own box, so a chunk that spans the distance where a shell is dropped draws that shell
/// only over the bands that need it (the mesh level stays the chunk's, so no crack opens).
constexpr int CHUNK_BANDS = 4;

/// A range of the terrain's index buffer.
struct IndexRange {
    uint32_t first = 0;
    uint32_t count = 0;
};

/// Rows of one mesh level of a chunk: a contiguous part of the level's index list and the box
/// (world metres) of the vertices its triangles use.
struct ChunkBand {
    IndexRange range;
    glm::vec3 wsMin_m{0.0f}, wsMax_m{0.0f};
};

struct TerrainChunk {
    uint32_t firstIndex = 0;  ///< into the terrain's index buffer: the full mesh (level 0)
    uint32_t indexCount = 0;
    /// levels[l], l < levelCount: the mesh taking every 2^l-th vertex inside the chunk, with the
    /// chunk's border always at full resolution (stitched), so neighbours at any levels share
    /// the same border and no crack opens. levels[0] is the full mesh.
    IndexRange levels[MESH_LEVELS];
    int levelCount = 1;
    /// levelError_m[l]: the largest vertical distance, metres, between a full-mesh vertex of the
    /// chunk and level l's surface above or below it (0 for level 0).
    float levelError_m[MESH_LEVELS] = {};
    /// bands[l][b], b < bandCount[l]: level l cut into bands of whole (coarse) rows, south first,
    /// together exactly levels[l] (render/TerrainChunks.h, CHUNK_BANDS).
    ChunkBand bands[MESH_LEVELS][CHUNK_BANDS];
    int bandCount[MESH_LEVELS] = {};
    float quad_m = 0.0f;                     ///< the longest quad side in the chunk (3-D), metres
    glm::vec3 wsMin_m{0.0f}, wsMax_m{0.0f};  ///< bounds of the ground, before the grass margin
};

/// Chunks of the nx x ny grid, CHUNK_QUADS quads a side (fewer at the far edges), and their index
/// lists, appended to `indices`: every chunk's level 0 first (together one contiguous range, two
/// triangles per quad of the whole grid, in the order of TerrainGrid.h within each chunk), then
/// the coarser levels;
/// level l >= 1 exists when 2^l divides the chunk's quads on both sides, and takes every 2^l-th
/// vertex: a coarse cell inside the chunk is two triangles, a cell on the chunk's border a fan
/// around its centre vertex through every full-resolution vertex of its border side(s). All
/// triangles are counter-clockwise in plan. Requires nx, ny >= 2 and nx * ny positions.
std::vector<TerrainChunk> buildChunks(int nx, int ny, const std::vector<glm::vec3>& wsPosition_m,
                                      std::vector<uint32_t>& indices);

/// True if the box [lo, hi] (world metres) may be inside the frustum of clipFromWorld: false only
/// when all eight corners are outside one clip plane.
bool boxMayBeVisible(const glm::mat4& clipFromWorld, const glm::vec3& lo, const glm::vec3& hi);

/// Distance, metres, from p to the box [lo, hi] (0 inside).
float distanceToBox(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi);

/// Distance, metres, from p to the farthest point of the box [lo, hi] (its farthest corner).
float farthestInBox(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi);

/// The distance, metres, beyond which the ground stands in for the grass: 2 height_m focal_px /
/// lodPixels (the grass height is lodPixels / 2 pixels on screen there); 0 (no level of detail)
/// when lodPixels or height_m is not > 0.
float grassFarDistance_m(float height_m, float focal_px, float lodPixels);

/// The shells a chunk at distance d draws: every `stride`-th shell from `top` down to 0.
struct ShellRange {
    int top = 0;
    int stride = 1;
    int count() const { return top / stride + 1; }
};

/// For N shells, the grass's far distance D (metres, grassFarDistance_m; 0 or infinite = no LOD)
/// and a chunk's nearest distance d: all shells (top N, stride 1) when d < D, else the ground alone
/// (top 0).
ShellRange shellRange(int shells, float far_m, float distance_m);

/// The mesh level of a chunk whose nearest ground point is `near_m` metres from the eye (focal_px
/// the focal length in pixels), the coarser of two rules: the coarsest l < chunk.levelCount whose
/// cells (2^l quad_m) span at most MESH_CELL_PER_LOD_PIXEL lodPixels on screen at that distance;
/// and the coarsest l whose cells span at most MESH_FLAT_CELL_PER_LOD_PIXEL lodPixels and whose
/// levelError_m, and that of every finer level, spans at most MESH_ERROR_PER_LOD_PIXEL lodPixels. 0
/// when lodPixels is 0 (no level of detail).
int meshLevel(const TerrainChunk& chunk, float focal_px, float lodPixels, float near_m);

/// The largest vertical distance, metres, between a vertex of the nx-wide grid `wsPosition_m`
/// inside the triangles indices[range] (plan coordinates; the triangles' corners are grid
/// vertices) and those triangles' surface at the vertex's plan position.
float meshLevelError(int nx, const std::vector<glm::vec3>& wsPosition_m,
                     const std::vector<uint32_t>& indices, IndexRange range);

/// True if, somewhere in a chunk whose ground reaches `chunkFar_m` metres from the eye, the shells
/// may have started to thin out and the ground to stand in for them (shell.vert: beyond
/// LOD_FADE_START grassFar_m). False when grassFar_m is 0 (no level of detail) or N = `shells` is
/// 0. A chunk for which this is false can be drawn without the fade.
bool chunkMayFade(int shells, float grassFar_m, float chunkFar_m);

}  // namespace gale::render::detail
