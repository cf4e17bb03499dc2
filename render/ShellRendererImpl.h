#pragma once
/// \file ShellRendererImpl.h
/// The shell renderer's GL state, shared by ShellRenderer.cpp (setup, uploads) and
/// ShellRendererDraw.cpp (frames). Internal to render/.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/gtc/type_ptr.hpp>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "render/Bend.h"
#include "render/BendTables.h"
#include "render/CameraMath.h"
#include "render/GlInfo.h"
#include "render/GlUtil.h"
#include "render/NearBlades.h"
#include "render/ShadowMap.h"
#include "render/ShellRenderer.h"
#include "render/TerrainChunks.h"

namespace gale::render {
namespace shell_detail {

using Clock = std::chrono::steady_clock;

inline double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

inline bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Vertex attribute locations shared with shaders/shell.vert and fill.vert.
constexpr GLuint POSITION_LOC = 0;
constexpr GLuint NORMAL_LOC = 1;
constexpr GLuint UV_LOC = 2;
constexpr GLuint WIND_DIR_LOC = 3;
constexpr GLuint GROUP_LOC = 4;
constexpr GLuint GROUP_COORD_LOC = 5;
constexpr GLuint FLUTTER_LOC = 6;
constexpr GLuint KEY_LIGHT_LOC = 7;  ///< levels 0-3; KEY_LIGHT_LOC + 1: levels 4-5

// Texture units.
constexpr GLint GRASS_UNIT = 0;
constexpr GLint BEND_UNIT = 1;
constexpr GLint GROUP_UNIT = 2;
constexpr GLint DENSITY_UNIT = 3;
constexpr GLint DENSITY_CUT_UNIT = 4;
constexpr GLint SHELL_PASS_UNIT = 5;

/// Static per-vertex data, interleaved.
struct TerrainVertex {
    float position[3];
    float normal[3];
    float uv[2];
    /// The key light's share past the terrain at each mesh level (render/ShadowMap.h,
    /// levelVisibility), 1 without a shadow map.
    float keyLight[detail::MESH_LEVELS];
};

/// Per-vertex wind data, re-uploaded only when GrassWind::revision changes.
struct WindVertex {
    float direction[3];
    uint32_t group;
    float groupCoord[2];  ///< position in the group grid (VertexWind::groupCoord), or unused
    float flutter_rad;    ///< VertexWind::flutter_rad, or 0
};

inline GLint uniform(GLuint program, const char* name) {
    return glGetUniformLocation(program, name);
}

/// Specialisations of shaders/shell.vert + shell.frag, one program per combination of these bits
/// (a branch on a uniform costs both sides on llvmpipe; docs/render.md).
enum ShellVariantBits : unsigned {
    VARIANT_APERIODIC = 1u,  ///< APERIODIC: the jittered-cell texture layout
    VARIANT_FADE = 2u,       ///< FADE: the level of detail thins shells near their drop distance
    VARIANT_DENSITY = 4u,    ///< DENSITY: a density map thins the blades
    VARIANT_BLEND = 8u,      ///< BLEND_GROUPS: the four nearest groups blended per vertex
    VARIANT_BLADES = 16u,    ///< BLADES: the near level's blade geometry (render/NearBlades.h)
};
constexpr unsigned SHELL_VARIANTS = 32;

/// Mean colour (linear RGB in [0, 1]) of the blade texels (alpha > 0) of a texture level; of all
/// texels if it has no blade.
glm::vec3 meanBladeColor(const Image& level);

/// The defines that select `bits` in the shell shaders.
std::string shellVariantDefines(unsigned bits);

/// Uniform locations of one shell program (-1 for a name the compiler dropped).
struct ShellLocations {
    GLint clipFromWorld, eyePos, shells, topShell, bend, grass, groups, groupColumns, maxTilt,
        shellPass, shellFocal, shellStride, lodD1, lastShell, time, bladeColor, density, densityCut,
        densityMin, densitySize, nearIn, nearR;
    GLint lightCount, lightPos, lightColor, lightAtten;
    GLint ambient, specularPower, specularStrength, shadowMin;
    GLint meshLevel;
};

struct ShellProgram {
    detail::Program program;
    ShellLocations loc{};
};

}  // namespace shell_detail

struct ShellRenderer::Impl {
    GlContext& context;

    /// Compiled on first use (ShellVariantBits); index = bits.
    std::array<std::unique_ptr<shell_detail::ShellProgram>, shell_detail::SHELL_VARIANTS>
        shellPrograms;
    detail::Program fillProgram;
    detail::VertexArray vao;
    detail::Buffer terrainVbo;
    detail::Buffer windVbo;
    detail::Buffer indexBuffer;
    /// The near blades (render/NearBlades.h): one BladeInstance per instance, refilled per frame.
    detail::VertexArray bladeVao;
    detail::Buffer bladeVbo;
    detail::BladeStatistics bladeStats;  ///< of the grass texture's level 0
    std::vector<float> bladeCuts;        ///< the texture's density cuts (render/DensityMap.h)
    DensityMap densityMap;               ///< the map the shells use, for the blades' own cut
    bool terrainPlanRegular = false;     ///< near blades need a plan-regular grid
    glm::vec2 terrainOrigin_m{0.0f}, terrainSpacing_m{1.0f};
    std::shared_ptr<const VertexWind> windVertex;  ///< the uploaded wind's per-vertex arrays
    detail::Texture grassTexture;
    detail::Sampler nearestSampler;  ///< overrides the grass texture's filtering (DrawOptions)
    std::unique_ptr<detail::BendTables> tables;
    std::unique_ptr<detail::DensityTables> density;
    /// The key light's view of the terrain when its shadow map is drawn (render/ShadowMap.h).
    std::optional<detail::ShadowView> shadowView;
    bool shadowDirty = true;  ///< terrain, grass height or lighting changed since the map
    /// The terrain buffer's contents, kept to rewrite TerrainVertex::keyLight with a shadow map.
    std::vector<shell_detail::TerrainVertex> terrainVertices;
    std::vector<uint32_t> terrainIndices;  ///< the full mesh's indices (the shadow's depth pass)
    int terrainNx = 0, terrainNy = 0;

    struct {
        GLint clipFromWorld, shells, shellSpacing, grass;
    } fillLoc{};

    int maxTextureSize = 0;

    // Terrain.
    bool haveTerrain = false;
    size_t vertexCount = 0;
    GLsizei indexCount = 0;  ///< indices of the full mesh, from the buffer's start
    std::vector<detail::TerrainChunk> chunks;
    glm::vec3 terrainMin_m{0.0f}, terrainMax_m{0.0f};  ///< the terrain's box, world metres

    // Grass.
    bool haveGrass = false;
    GrassParams grass;
    glm::vec3 bladeColor{0.0f};  ///< mean colour of the texture's blade texels, linear [0, 1]

    // Lighting (uploaded to the shell program on setLighting).
    Lighting lighting;

    // Wind state on the GPU.
    bool windUploaded = false;
    bool windWasNone = false;
    uint64_t windRevision = 0;
    uint32_t windMaxGroup = 0;
    int windColumns = 0;      ///< VertexWind::groupColumns of the uploaded wind
    bool windBlends = false;  ///< the uploaded wind carries groupCoord

    explicit Impl(GlContext& ctx) : context(ctx) {}

    void init();
    /// The program of `bits`, compiled (with its samplers and lighting set) on first use.
    shell_detail::ShellProgram& shellProgram(unsigned bits);
    /// A new program of `bits` whose transform feedback records `feedback` (shellProgram's
    /// set-up otherwise).
    std::unique_ptr<shell_detail::ShellProgram> makeShellProgram(
        unsigned bits, const std::vector<const char*>& feedback) const;
    /// The uniforms every program of a frame shares.
    struct FrameUniforms {
        glm::mat4 clipFromWorld{1.0f};
        glm::vec3 wsEye_m{0.0f};
        float lodD1_m = 0.0f;     ///< shell.vert uLodD1
        float shellFocal = 0.0f;  ///< shell.vert uShellFocal
        int lastShell = 0;        ///< shell.vert uLastShell
        float nearIn_m = 0.0f;    ///< shell.vert uNearIn: the near blades' R_in
        float nearR_m = 0.0f;     ///< shell.vert uNearR: the near blades' R, 0 without
        double time_s = 0.0;      ///< the wind's time
    };
    void setFrameUniforms(const shell_detail::ShellLocations& loc, const FrameUniforms& f) const;
    /// A frame's CPU side: makes the context current, uploads the wind if it changed, builds the
    /// bend, group and pass tables; returns the camera's clip-from-world matrix.
    glm::mat4 prepareFrame(const Camera& camera, const GrassWind& wind);
    /// The near blades of a frame (render/NearBlades.h) for this camera.
    detail::NearBladeSet placeBlades(const Camera& camera, const glm::mat4& clipFromWorld,
                                     float focal_px) const;
    /// Writes `blades` to the instance buffer.
    void uploadBlades(const std::vector<detail::BladeInstance>& blades);
    /// The blade program recording vBladeWorld, by BLEND_GROUPS (ShellRenderer::captureNearBlades).
    std::array<std::unique_ptr<shell_detail::ShellProgram>, 2> bladeCapturePrograms;
    void uploadLighting(const shell_detail::ShellProgram& program) const;
    void uploadWind(const GrassWind& wind);
    void requireReady(const char* what) const;
    void beginFrame();
    /// Redraws the key light's shadow map if shadowDirty (or drops it: no light, shadows off, a
    /// light inside the box).
    void updateShadow();
};

}  // namespace gale::render
