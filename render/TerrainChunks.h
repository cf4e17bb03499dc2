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
/// highest multiple of 2^k down to the ground. The shells drawn shade the blades of the dropped
/// ones where they were seen, and the ground what they hid (shell.frag; tests/render/SeamTest.cpp
/// holds the result to the full stack per 32 x 32 tile): a thinned stack drawn plainly is darker
/// and draws a band.

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

/// The shells a chunk at distance d draws: every `stride`-th shell from `top` down to 0.
struct ShellRange {
    int top = 0;
    int stride = 1;
    int count() const { return top / stride + 1; }
};

/// For N shells, drop distance D1 (metres, > 0; infinite = no LOD) and chunk distance d:
/// the smallest stride 2^k with D1 2^k > d, and the highest multiple of it <= N.
ShellRange shellRange(int shells, float d1_m, float distance_m);

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

/// True if a chunk whose ground reaches `far_m` metres from the eye needs the level of detail's
/// program (shell.vert's FADE): when `range` drops shells (stride > 1), since the shells drawn
/// then shade the dropped shells' blades where they were seen, and when every shell is drawn but
/// the chunk reaches LOD_FADE_START D1, where the odd shells (the first to go) start to thin out.
/// False when D1 is 0 (no level of detail) or N = `shells` is 0. A chunk for which this is false
/// is drawn with every shell and self-shadowing per vertex.
bool chunkMayFade(const ShellRange& range, int shells, float d1_m, float far_m);

}  // namespace gale::render::detail
