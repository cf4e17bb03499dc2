#pragma once
/// \file ShadowMap.h
/// The key light's shadow of the terrain (docs/render.md, "Shadows"): a depth map of the terrain
/// seen from the first light, rendered once for a terrain and a light (neither moves while the
/// grass does) and read back, and from it each terrain vertex's share of the key light, which
/// shell.vert reads as a vertex attribute: a hill's shadow darkens the ground and the grass it
/// covers at no cost per frame (a shadow-map fetch per vertex and shell cost 15-20 % of a frame
/// on llvmpipe, which shades vertices on one thread). Internal to render/.
///
/// The map covers the terrain's box grown by the grass height. A light more than
/// DIRECTIONAL_DISTANCE_RATIO box radii away is a direction (an orthographic map fitted to the
/// box's corners); a nearer one is a point (a perspective map from it, its cone around the box's
/// bounding sphere); a light inside 1.05 radii of the box's centre casts no shadow map (one
/// perspective map cannot hold every direction).

#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <vector>

namespace gale::render::detail {

/// Side of the shadow map, texels: 2048 puts a texel at 0.1 m over a 200 m meadow, 0.6 m over the
/// 1.28 km landscape; 16 MiB of 32-bit depth.
constexpr int SHADOW_MAP_PX = 2048;
/// A light farther than this many box radii from the box's centre is treated as a direction.
constexpr float DIRECTIONAL_DISTANCE_RATIO = 100.0f;

/// The key light's view of the box [lo, hi] (world, metres).
struct ShadowView {
    /// World to the map's texture space: x, y in [0, 1] across the map, z the depth in [0, 1].
    glm::mat4 textureFromWorld{1.0f};
    /// World to the map's clip space (what the depth pass draws with).
    glm::mat4 clipFromWorld{1.0f};
    /// Metres one texel spans at the box's centre.
    float texel_m = 0.0f;
};

/// The share of light reaching texture-space point t (textureFromWorld of a world point) from a
/// depth map `sizePx` a side, row 0 at t.y = 0: the four nearest texels' depths compared with
/// t.z (lit where t.z <= depth) and blended bilinearly, as GL's linear sampler2DShadow does
/// (percentage-closer filtering); texels beyond the map are lit.
float mapVisibility(const std::vector<float>& depth, int sizePx, const glm::vec3& t);

/// The offset, metres along the terrain normal, of a vertex's lookup (normal offset): 1.5 texels,
/// so a slope the light grazes does not shadow itself between texels.
constexpr float SHADOW_NORMAL_OFFSET_TEXELS = 1.5f;

/// The view of a map `sizePx` texels a side for a light at `light_m`; nullopt when the light is
/// within 1.05 box radii of the box's centre, the box is empty or a value is not finite.
std::optional<ShadowView> keyLightView(const glm::vec3& light_m, const glm::vec3& lo,
                                       const glm::vec3& hi, int sizePx);

/// The visibility a vertex shows when the terrain is drawn at mesh level l (render/TerrainChunks.h:
/// every 2^l-th vertex), for l = 0..levels-1, `levels` values per vertex: level 0 the vertex's own;
/// level l >= 1 the mean over the (2^l + 1)^2 grid vertices around it (clipped to the grid), so a
/// coarse cell shows the share of light its ground gets instead of its corners' (a point sample
/// at a coarse vertex spread the knoll's shadow on the far meadow by 18.5 levels in a 32 x 32
/// tile). Vertices on a chunk border (every `chunkQuads`-th row and column, and the grid's edge)
/// keep their own value at every level: borders stay at full resolution in every level.
std::vector<float> levelVisibility(const std::vector<float>& visible, int nx, int ny, int levels,
                                   int chunkQuads);

/// Draws the terrain's depth (the first `indexCount` of `indices`, triangles over `positions_m`,
/// world metres) as view.clipFromWorld sees it into a SHADOW_MAP_PX map, reads it back and
/// returns, for each vertex, mapVisibility at the point SHADOW_NORMAL_OFFSET_TEXELS texels off
/// the surface along its unit normal. Requires a current context; every GL object it makes is
/// deleted before it returns (the map is 16 MiB), and it leaves the default framebuffer, no
/// vertex array and no program bound, polygon offset off (the caller sets its own viewport).
std::vector<float> vertexVisibility(const ShadowView& view,
                                    const std::vector<glm::vec3>& positions_m,
                                    const std::vector<glm::vec3>& normals,
                                    const std::vector<uint32_t>& indices, size_t indexCount);

}  // namespace gale::render::detail
