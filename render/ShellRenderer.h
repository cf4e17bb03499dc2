#pragma once
/// \file ShellRenderer.h
/// Draws the terrain and N + 1 grass shells (Bakay 2003, chapter 3) with the length-preserving bend
/// and Kajiya-Kay / Banks lighting, into the current GlContext's framebuffer.

#include <memory>

#include "render/DensityMap.h"
#include "render/GlContext.h"
#include "render/GrassInput.h"
#include "render/GrassTexture.h"
#include "render/NearBlades.h"
#include "render/RenderLimits.h"

namespace gale::render {

struct FrameStats {
    double cpu_ms = 0.0;      ///< table building and uploads on the CPU
    double gpu_ms = 0.0;      ///< draw calls through glFinish
    int chunks = 0;           ///< terrain chunks in the frustum (render/TerrainChunks.h)
    int chunksCulled = 0;     ///< chunks outside it, not drawn
    long long layers = 0;     ///< layers drawn: over the chunks' row bands, the shells each drew
    long long triangles = 0;  ///< triangles drawn: over chunks, mesh triangles x layers
    int blades = 0;           ///< near blades drawn (render/NearBlades.h)
    float bladeRadius_m = 0;  ///< their distance R (they thin out over R_in .. R); 0: none
};

/// What draw() shows; the viewer's toggles. Both off draws only the sky.
struct DrawOptions {
    bool terrain = true;  ///< shell 0, the ground
    bool grass = true;    ///< shells 1..N
    /// The grass texture read with GL_NEAREST_MIPMAP_NEAREST (one texel of the nearest level)
    /// instead of its trilinear filtering: about twice the fill rate on a software rasteriser,
    /// at the price of blockier blades close up and visible MIP-level steps.
    bool nearestTexels = false;
};

/// The near blades of one frame as the GPU builds them (ShellRenderer::captureNearBlades).
struct NearBladeCapture {
    std::vector<detail::BladeInstance> blades;  ///< as placed (render/NearBlades.h)
    float radius_m = 0.0f;                      ///< their distance R
    float innerRadius_m = 0.0f;                 ///< R_in, where they start to thin out
    /// Every blade's strip vertices as shell.vert places them, world metres, blade by blade,
    /// detail::BLADE_STRIP_VERTICES each: vertices 2k and 2k + 1 the edges of level k, the last
    /// the tip.
    std::vector<glm::vec3> vertices;
};

class ShellRenderer {
  public:
    /// Compiles the shaders (throws std::runtime_error naming the shader file and its log).
    /// The context must be current and stay alive while the renderer is used.
    explicit ShellRenderer(GlContext& context);
    ~ShellRenderer();
    ShellRenderer(const ShellRenderer&) = delete;
    ShellRenderer& operator=(const ShellRenderer&) = delete;

    /// Uploads the terrain grid (world space, metres): nx, ny >= 2, one position, unit normal and
    /// uv per vertex, two triangles per quad. Throws std::logic_error (the caller's bug: coupling
    /// builds the mesh) on wrong sizes or non-finite values. Forces the wind directions and groups
    /// to be re-uploaded.
    void setTerrain(const TerrainMesh& mesh);
    /// Uploads the grass texture with its blade-keeping MIP chain (thesis 3.4; GL_TEXTURE_MAX_LEVEL
    /// is the last level the chain kept). params.height_m > 0; params.shells in 0..MAX_SHELLS
    /// (0 draws the ground only, the paper's one-shell row); stiffness > 0; tile_m > 0;
    /// nearBlades in 0..MAX_NEAR_BLADES. Texture levels must be square, halving from a power of
    /// two. Throws gale::ParameterError naming grass.height_m, grass.shells, grass.lod_pixels,
    /// grass.stiffness, grass.tile_m or grass.near_blades, std::logic_error for bad texture
    /// levels.
    void setGrass(const GrassParams& params, const GrassTexture& texture);
    /// Thins the grass by a density map (render/DensityMap.h); a map of width 0 removes it
    /// (density 1 everywhere). Requires density.size() == width * height, values finite, width
    /// and height within GL_MAX_TEXTURE_SIZE; throws std::invalid_argument naming the field.
    void setDensityMap(const DensityMap& map);
    /// At most MAX_LIGHTS point lights (RenderLimits.h); attenuation coefficients >= 0 with
    /// k_c + k_l + k_q > 0; specularPower >= 0; selfShadowMin in [0, 1]. Throws
    /// gale::ParameterError naming the scene key (lighting.light[l].attenuation,
    /// lighting.self_shadow_min, ...) otherwise.
    void setLighting(const Lighting& lighting);

    /// Draws one frame: per-group (n_i, w_i) tables are built on the CPU from wind.groupIntensity
    /// (once per group per shell, never per vertex), directions and groups are re-uploaded only
    /// when wind.revision changed.
    /// Requires setTerrain and setGrass first (std::logic_error otherwise). wind.wsDirection() and
    /// wind.group() must each hold one entry per terrain vertex and every group must be below
    /// wind.groupIntensity.size(); an empty groupIntensity means no wind (then the per-vertex
    /// arrays may be empty). Intensities must be finite. Throws std::logic_error naming the
    /// field (the wind comes from coupling, not from a scene value). Clears to the sky colour,
    /// draws, and ends with glFinish.
    FrameStats draw(const Camera& camera, const GrassWind& wind);
    /// draw() with parts left out (the viewer's terrain and grass toggles); same preconditions.
    FrameStats draw(const Camera& camera, const GrassWind& wind, const DrawOptions& options);
    /// The near blades draw() would draw for this camera and wind, with their vertices recorded
    /// by transform feedback from the drawing shader (no pixels are written): what the tests
    /// hold against the bend's invariants. Same preconditions as draw.
    NearBladeCapture captureNearBlades(const Camera& camera, const GrassWind& wind);
    /// Changes N without re-uploading the texture: 0..MAX_SHELLS, else gale::ParameterError
    /// (grass.shells).
    /// Requires setGrass first (std::logic_error otherwise).
    void setShellCount(int shells);
    /// The current N.
    int shellCount() const;

    /// Benchmark baseline: the same terrain, shell count and texture with a minimal shader
    /// (shells extruded straight along the normal, texture fetch and alpha test, no bend, no
    /// lighting). Same preconditions as draw; ends with glFinish. nearestSampling: the texture read
    /// with GL_NEAREST_MIPMAP_NEAREST instead of the grass texture's trilinear filtering (the
    /// floor of a fill on a software rasteriser, where trilinear filtering dominates the cost).
    FrameStats drawFillBaseline(const Camera& camera, bool nearestSampling = false);

    /// Sky (clear) colour, linear RGB in [0, 1].
    static constexpr float SKY_COLOR[3] = {0.60f, 0.75f, 0.92f};

  private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

}  // namespace gale::render
