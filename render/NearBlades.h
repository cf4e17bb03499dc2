#pragma once
/// \file NearBlades.h
/// True blade geometry near the camera, the near level of Boulanger, Pattanaik and Bouatouch
/// (2006): within a distance chosen each frame for a blade budget, blades stand on the terrain as
/// bent ribbons in place of the shells (docs/render.md, "Near blades"). This file places them on
/// the CPU; shell.vert's BLADES variant bends and lights each one with the shells' own tables, so a
/// blade follows the same length-preserving curve as the shells at its root.
///
/// Placement. Blades sit on a world-aligned lattice of spacing a = 1 / sqrt(rho), one per lattice
/// cell at a hashed position inside it (rho the grass texture's blade count per square metre,
/// BladeStatistics), so a blade is the same blade in every frame: moving the camera never
/// reshuffles them. Each blade's height fraction, width, facing, colour tint and stiffness are
/// hashes of its cell; its height follows the texture's blade heights (the alpha histogram), its
/// colour the texture's blade colour at that height as a shell shows it (filtered over a texel,
/// soil included: BladeStatistics::colorByHeight). A density map removes a blade exactly
/// where it removes the shells' blades: when its height is below the map's cut at its root
/// (render/DensityMap.h), so a path is bare in both.
///
/// Distance. The lattice blades whose bounding sphere meets the frustum are gathered from the
/// terrain quads nearest first; R is the distance of the budget's farthest (the cap when fewer
/// are in view), so the budget buys the nearest visible blades whatever the quad size. Blades
/// thin out over the farthest 30 % of the distances they span, from R_in = d0 + 0.7 (R - d0) (d0
/// the nearest visible blade's distance) to R: each blade has a hashed key and stays while its
/// key is below the fade, so the edge of the near level is a gradual thinning, never a line. The
/// shells thin in over the same band (shell.vert uNearIn, uNearR) and are clipped away inside
/// R_in, where the blades alone stand on the ground. (A band of 0.7 R .. R would hold all of a
/// view's blades when the nearest ground in view is beyond 0.7 R, as from human height looking
/// at the horizon.) R never exceeds the distance at which a blade is 2 pixels wide
/// (beyond it a blade is a sliver the shells draw as well).
///
/// @code
///   detail::BladeStatistics stats = detail::bladeStatistics(texture.levels[0], params.tile_m);
///   detail::NearBladeSet set = detail::placeNearBlades(ground, stats, view);
///   upload(set.blades);  // one instance per blade, drawn as a strip of BLADE_STRIP_VERTICES
/// @endcode

#include <array>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "render/DensityMap.h"
#include "render/GrassInput.h"

namespace gale::render::detail {

/// Segments of a blade's strip (shell.vert BLADES_SEGMENTS): two vertices at each of the
/// segments' lower ends, one at the tip.
constexpr int BLADE_SEGMENTS = 4;
constexpr int BLADE_STRIP_VERTICES = 2 * BLADE_SEGMENTS + 1;

/// A blade is drawn as geometry only while it is at least this many pixels wide: narrower, the
/// shells draw it as well, and blades of 1-2 pixels 7-18 m away cost the examples' frames
/// 0.2-0.5 of the fill floor for no visible gain (docs/render.md, "Near blades").
constexpr float MIN_BLADE_PX = 2.0f;

/// Bins of the blade colour by height (BladeStatistics::colorByHeight).
constexpr int BLADE_COLOR_BINS = 16;

/// Spread of the per-blade stiffness: a blade's tip tilt is the group's times a factor in
/// [1 - s, 1 + s] (a stiffer blade bends less), s = BLADE_STIFFNESS_SPREAD.
constexpr float BLADE_STIFFNESS_SPREAD = 0.2f;
/// Spread of the per-blade brightness about the texture's colour at its height.
constexpr float BLADE_TINT_SPREAD = 0.12f;

/// What the grass texture says about its blades, measured on its level 0 (alpha = height).
struct BladeStatistics {
    /// Blades of the texture per square metre of ground: its blade footprints (4-connected
    /// regions of one alpha, the texture wrapping) over the area one repeat covers, tile_m^2.
    float bladesPerM2 = 0.0f;
    /// A blade's width, metres: the square root of the mean footprint's area in texels times
    /// the texel's size (tile_m / width).
    float width_m = 0.0f;
    /// Height fraction of the blade at quantile q = k / 255 of the texture's blade texels
    /// (inverse of their alpha histogram), k = 0..255.
    std::array<float, 256> heightAtQuantile{};
    /// Mean colour (linear RGB in [0, 1]) of the blade texels whose height falls in bin b of
    /// BLADE_COLOR_BINS equal bins over (0, 1], each texel filtered as a shell fragment reads it
    /// (a 3 x 3 tent, weights 1/4, 1/2, 1/4 each way, soil included); an empty bin takes its
    /// nearest non-empty one.
    std::array<glm::vec3, BLADE_COLOR_BINS> colorByHeight{};
};

/// Measures a grass texture's level 0. A texture without blades gives bladesPerM2 = 0 (no near
/// blades). Requires tile_m > 0 and a square level 0 (std::logic_error otherwise).
BladeStatistics bladeStatistics(const Image& level0, float tile_m);

/// One blade as the BLADES program reads it (one instance; shell.vert's attribute locations).
struct BladeInstance {
    float root[3];        ///< on the terrain's triangle, world metres
    float normal[3];      ///< unit terrain normal at the root (barycentric, normalised)
    float blade[4];       ///< height fraction of the grass height, width m, facing about the
                          ///< normal rad, tilt factor
    float windDir[3];     ///< tangent-plane wind direction (barycentric of the vertices'), or 0
    uint32_t group;       ///< the group of the root's nearest vertex
    float groupCoord[2];  ///< barycentric of the vertices' group coordinates (blending), or 0
    float flutter_rad;    ///< barycentric of the vertices' flutter amplitudes
    float color[4];       ///< linear RGB, then the key light's share at the root
};

/// The ground the blades stand on: the renderer's copy of the terrain grid and its wind.
struct BladeGround {
    int nx = 0, ny = 0;
    /// The grid's plan layout (planRegular): vertex (i, j) at origin + (i, j) * spacing.
    bool planRegular = false;
    glm::vec2 origin_m{0.0f}, spacing_m{1.0f};
    /// nx * ny vertices, `stride` floats apart: the position (world metres) at float
    /// positionAt, the unit normal at normalAt, the key light's share past the terrain at
    /// keyLightAt (< 0: 1 everywhere). The renderer's interleaved terrain buffer.
    const float* vertices = nullptr;
    size_t stride = 0;
    int positionAt = 0, normalAt = 3, keyLightAt = -1;
    const VertexWind* wind = nullptr;                 ///< null: no wind
    const DensityMap* density = nullptr;              ///< null or width 0: density 1
    const std::vector<float>* densityCuts = nullptr;  ///< render/DensityMap.h densityCuts
};

/// The frame the blades are chosen for.
struct BladeView {
    glm::mat4 clipFromWorld{1.0f};
    glm::vec3 wsEye_m{0.0f};
    float focal_px = 1.0f;       ///< focal length in pixels (the viewport's height over 2 tan)
    float grassHeight_m = 0.5f;  ///< GrassParams::height_m
    int budget = 0;              ///< blades at most; 0: none
};

struct NearBladeSet {
    std::vector<BladeInstance> blades;  ///< at most the budget, nearest first
    float radius_m = 0.0f;              ///< R: blades thin out over R_in .. R; 0: none
    float innerRadius_m = 0.0f;         ///< R_in: every blade stands inside it
    float capRadius_m = 0.0f;           ///< the 2-pixel distance R never exceeds
};

/// Whether the grid's plan positions are regular: x = x0 + i dx, y = y0 + j dy to within 1e-4 of
/// a quad (placement finds a blade's quad from its plan position). Writes the origin and spacing.
bool planRegular(int nx, int ny, const std::vector<glm::vec3>& wsPosition_m, glm::vec2& origin_m,
                 glm::vec2& spacing_m);

/// The blades of one frame (see the file comment). Requires ground.planRegular and
/// stats.bladesPerM2 > 0 for any blade; returns none otherwise.
NearBladeSet placeNearBlades(const BladeGround& ground, const BladeStatistics& stats,
                             const BladeView& view);

/// The fade of the near level at distance d from the eye: 1 inside R_in, 0 beyond R, smoothstep
/// between (shell.vert's fade has the same shape). R <= 0 gives 0.
float nearBladeFade(float d_m, float innerRadius_m, float radius_m);

}  // namespace gale::render::detail
