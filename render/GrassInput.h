#pragma once
/// \file GrassInput.h
/// The plain data the renderer draws from. Everything the renderer knows of the world arrives in
/// these structs; it never calls into sim/ or coupling/ (STYLE, module boundaries). All positions
/// are world space, metres, z up.

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <string>
#include <vector>

namespace gale::render {

/// The terrain as a regular grid of vertices (nx * ny, i fastest), triangulated two per quad.
struct TerrainMesh {
    int nx = 0;
    int ny = 0;
    std::vector<glm::vec3> wsPosition_m;  ///< vertex positions
    std::vector<glm::vec3> wsNormal;      ///< unit upward normals
    std::vector<glm::vec2> uv;  ///< grass texture coordinates (repeats across the terrain)
};

/// Per-vertex wind, one entry per terrain vertex.
struct VertexWind {
    /// Unit wind direction in the vertex's tangent plane, or zero where undefined (wind along the
    /// normal, no wind). The bend moves the vertex along it.
    std::vector<glm::vec3> wsDirection;
    /// Animation-step group in [0, GrassWind::groupIntensity.size()).
    std::vector<uint32_t> group;
    /// Width of the group grid: group g sits at column g % groupColumns, row g / groupColumns.
    /// 0: the renderer chooses (rows of 1024). Sources whose groups are bins of one or two
    /// quantities (intensity levels, arrival bands x levels, plan tiles) lay them out so grid
    /// neighbours are neighbouring bins.
    int groupColumns = 0;
    /// Optional, empty or one per vertex: the vertex's continuous position in the group grid, in
    /// group units (group g's bin centre at (g % groupColumns, g / groupColumns)). With it the
    /// renderer blends the tip tilts of the four nearest groups bilinearly, so no stripes show
    /// where groups change; without it each vertex takes its group's tilt alone.
    std::vector<glm::vec2> groupCoord;
    /// Optional, empty or one per vertex: the amplitude, radians, of the turbulent flutter added
    /// to the tip tilt of the blades at this vertex (shell.vert, after the detail bending of
    /// Sousa 2008, GPU Gems 3 ch. 16): >= 0, 0 in calm air; coupling/Flutter.h derives it from
    /// the turbulent kinetic energy. Empty: no flutter.
    std::vector<float> flutter_rad;
};

/// The wind as the shell renderer consumes it (paper section 3, Table 1): a tangent-plane wind
/// direction and an animation-step group per vertex, and one intensity per group per frame. Both
/// the paper's point source and the solved field produce this; the renderer cannot tell them apart.
///
/// The per-vertex part is shared, read-only: a source hands one VertexWind to every GrassWind it
/// fills and never writes into one it has handed out, so passing a million vertices' wind from
/// the source to the renderer (or to the viewer's render thread) copies a pointer, not 16 MB.
struct GrassWind {
    /// Null: no per-vertex wind (every blade stands still).
    std::shared_ptr<const VertexWind> vertex;
    /// Changes whenever `vertex` changes, so the renderer re-uploads it only then.
    uint64_t revision = 0;
    /// Per group: intensity I this frame (unitless). The tip tilts by (pi/2) I up to |I| = 1/2
    /// and saturates smoothly above, short of the ground (render/Bend.h, tipTilt_rad).
    std::vector<float> groupIntensity;
    /// The time this wind is for, seconds: the phase of the flutter (VertexWind::flutter_rad).
    double time_s = 0.0;

    /// The per-vertex arrays; empty when `vertex` is null.
    const std::vector<glm::vec3>& wsDirection() const {
        return vertex ? vertex->wsDirection : none().wsDirection;
    }
    const std::vector<uint32_t>& group() const { return vertex ? vertex->group : none().group; }

  private:
    static const VertexWind& none() {
        static const VertexWind empty;
        return empty;
    }
};

/// A point light (thesis 3.3): radiance scaled by 1 / (k_c + k_l d + k_q d^2), d in metres.
struct PointLight {
    glm::vec3 wsPosition_m{0.0f};
    glm::vec3 color{1.0f};
    glm::vec3 attenuation{1.0f, 0.0f, 0.0f};  ///< (k_c, k_l [1/m], k_q [1/m^2])
};

struct Lighting {
    glm::vec3 ambient{0.25f};        ///< added after attenuation (thesis 3.3.4)
    std::vector<PointLight> lights;  ///< any number, including none
    float specularPower = 32.0f;     ///< Kajiya-Kay specular exponent p
    float specularStrength = 0.3f;   ///< weight of the specular term
    float selfShadowMin = 0.25f;     ///< Banks self-shadowing floor S_min at the ground
    /// The first light (the key light) is shadowed by the terrain: a shadow map of the terrain
    /// seen from it, looked up per vertex (render/ShadowMap.h). No effect without lights or
    /// when the key light is inside the terrain's box.
    bool shadows = true;
};

struct Camera {
    glm::vec3 wsPosition_m{0.0f, -50.0f, 30.0f};
    glm::vec3 wsTarget_m{0.0f};
    float fovY_deg = 45.0f;
    float near_m = 0.1f;
    float far_m = 1000.0f;
};

/// Shell grass parameters (Bakay 2003, chapter 3; docs/render.md).
struct GrassParams {
    float height_m = 0.5f;   ///< full blade height
    int shells = 16;         ///< N: shells above the ground (N + 1 drawn with the ground), 1..256
    float stiffness = 1.0f;  ///< gamma in theta_j = (pi/2) I (j/N)^gamma; 1 is the paper's
    float tile_m = 3.0f;     ///< metres one repeat of the grass texture spans
    /// Lay the texture aperiodically: each cell of a jittered grid (one texture repeat wide) shows
    /// it turned, mirrored and shifted at random, so no repeat shows (docs/render.md). false: the
    /// plain repeat.
    bool aperiodic = false;
    /// Level of detail (render/TerrainChunks.h): shells are dropped, thinning out first, where
    /// the shells that remain are at most this many pixels apart on screen; 0 draws every shell
    /// everywhere. >= 0.
    float lodPixels = 3.0f;
    /// Near blades (render/NearBlades.h): true blade geometry above the shells within the
    /// distance where the frame holds this many blades, at the texture's own blade density,
    /// thinning out towards that distance; 0: shells only (the paper's grass). 0..MAX_NEAR_BLADES.
    int nearBlades = 6000;
};

/// An RGBA8 image, rows top-down.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;  ///< width * height * 4
};

}  // namespace gale::render
