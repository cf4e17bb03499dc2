#pragma once
/// \file BendTables.h
/// The two small textures the shell vertex shader bends blades with (Bakay 2003, Table 3.2, in a
/// form that lets neighbouring groups blend). Internal to render/.
///
/// - The bend table: texel (i, l) holds (n_i, w_i, n_i - n_{i-1}, w_i - w_{i-1}), metres, of
///   shell i (the last two: segment i, whose direction is the strand tangent; (1, 0) for the
///   ground) for the tip tilt
///   theta_l = -max + 2 max l / (L - 1), max = MAX_TIP_TILT_RAD, L = TILT_LEVELS (render/Bend.h).
///   It depends on the blade alone (N, height, stiffness), so it is built when they change, not
///   per frame. The shader interpolates linearly between tilt rows: a blade between two rows is
///   within (L0 dtheta^2 / 8) of a length-preserving one (L0 the blade length), under 4e-6 of
///   its length at L = 513.
/// - The group table: one texel per group, its tip tilt this frame (radians), groups row by row in
///   a grid `columns` wide. Per frame: O(K) tilts computed and uploaded. Vertices read their
///   group's texel, or (VertexWind::groupCoord) a bilinear blend of the four nearest groups.

#include <GL/gl.h>

#include <array>
#include <glm/vec2.hpp>
#include <vector>

#include "render/DensityMap.h"
#include "render/GlUtil.h"
#include "render/GrassInput.h"

namespace gale::render::detail {

/// A 2-D texture for a table: one level, clamped at the edges, `filter` (GL_NEAREST / GL_LINEAR)
/// for both minification and magnification. Requires a current context.
Texture newTableTexture(GLint filter);

/// Tilt rows of the bend table; odd so that tilt 0 (no wind) is a row, exactly.
constexpr int TILT_LEVELS = 513;
/// Width of the group grid when the wind names none: groups beyond it wrap to the next row, so
/// per-vertex grouping of a large mesh stays within GL_MAX_TEXTURE_SIZE.
constexpr int DEFAULT_GROUP_COLUMNS = 1024;

class BendTables {
  public:
    /// Creates the textures. Requires a current context.
    BendTables();

    /// Rebuilds the bend table if N, the height (metres) or the stiffness changed. shells >= 0
    /// (0: only the ground row), height_m > 0, stiffness > 0 (checked by the renderer).
    void setBlade(int shells, float height_m, float stiffness);

    /// Computes every group's tip tilt from wind.groupIntensity (tipTilt_rad, render/Bend.h) and
    /// uploads them `columns` groups to a row (columns >= 1). An empty groupIntensity is one
    /// group at rest. Throws std::logic_error naming GrassWind.groupIntensity[g] if an
    /// intensity is not finite, or if the grid exceeds maxTextureSize texels on a side.
    void setGroups(const GrassWind& wind, int columns, int maxTextureSize);

    GLuint bendTexture() const { return mBend.get(); }
    GLuint groupTexture() const { return mGroups.get(); }
    /// Columns of the group grid last uploaded.
    int columns() const { return mColumns; }

  private:
    Texture mBend, mGroups;
    int mShells = -1;
    float mHeight_m = 0.0f, mStiffness = 0.0f;
    int mColumns = 0, mRows = 0;
    std::vector<float> mTilts;
};

/// The density map and the texture's density cut table (render/DensityMap.h), for shell.frag.
class DensityTables {
  public:
    /// Creates the textures (no map: density 1). Requires a current context.
    DensityTables();
    /// The cut table of a new grass texture (its level 0); keeps its alpha histogram for the
    /// pass table.
    void setCuts(const Image& level0);
    /// Rebuilds the pass table (shellPassFractions, render/DensityMap.h) if the texture or N
    /// changed: texel m of a (MAX_SHELLS + 1) x 1 table holds entry m, 0 beyond N.
    void setShells(int shells);
    /// Uploads `map`, or removes it when map.width == 0. Throws std::logic_error naming the
    /// field on wrong sizes, non-finite values or a side above maxTextureSize.
    void setMap(const DensityMap& map, int maxTextureSize);

    bool active() const { return mActive; }
    const glm::vec2& wsMin_m() const { return mMin_m; }
    const glm::vec2& wsSize_m() const { return mSize_m; }
    GLuint mapTexture() const { return mMap.get(); }
    GLuint cutTexture() const { return mCuts.get(); }
    GLuint passTexture() const { return mPasses.get(); }

  private:
    Texture mMap, mCuts, mPasses;
    std::array<size_t, 256> mAlphaCount{};
    int mPassShells = -1;  ///< N of the pass table, -1 when the texture changed since
    bool mActive = false;
    glm::vec2 mMin_m{0.0f}, mSize_m{1.0f};
};

}  // namespace gale::render::detail
