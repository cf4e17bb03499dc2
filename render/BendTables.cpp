#include "render/BendTables.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "render/Bend.h"
#include "render/RenderLimits.h"

namespace gale::render::detail {
Texture newTableTexture(GLint filter) {
    GLuint name = 0;
    glGenTextures(1, &name);
    Texture texture(name);
    glBindTexture(GL_TEXTURE_2D, name);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    return texture;
}

BendTables::BendTables()
    // The bend table is read with texelFetch and interpolated in the shader (full float weights);
    // the group table is sampled with bilinear filtering where vertices blend groups.
    : mBend(newTableTexture(GL_NEAREST)), mGroups(newTableTexture(GL_LINEAR)) {}

void BendTables::setBlade(int shells, float height_m, float stiffness) {
    if (shells == mShells && height_m == mHeight_m && stiffness == mStiffness) return;
    const int width = shells + 1;
    std::vector<float> table(static_cast<size_t>(width) * TILT_LEVELS * 4u, 0.0f);
    std::vector<ShellOffset> row(static_cast<size_t>(width));
    for (int l = 0; l < TILT_LEVELS; ++l) {
        if (shells > 0) {
            const double tilt = MAX_TIP_TILT_RAD * (2.0 * l / (TILT_LEVELS - 1) - 1.0);
            bendBladeByTiltInto(shells, height_m, tilt, stiffness, row.data());
        } else {
            row[0] = ShellOffset{0.0, 0.0};
        }
        float* out = &table[static_cast<size_t>(l) * width * 4u];
        for (int i = 0; i < width; ++i) {
            out[4 * i] = static_cast<float>(row[i].n_m);
            out[4 * i + 1] = static_cast<float>(row[i].w_m);
            // Segment i (shell i - 1 to shell i), the strand tangent's direction before
            // normalising; the ground's strand is the normal.
            out[4 * i + 2] = i == 0 ? 1.0f : static_cast<float>(row[i].n_m - row[i - 1].n_m);
            out[4 * i + 3] = i == 0 ? 0.0f : static_cast<float>(row[i].w_m - row[i - 1].w_m);
        }
    }
    glBindTexture(GL_TEXTURE_2D, mBend.get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, TILT_LEVELS, 0, GL_RGBA, GL_FLOAT,
                 table.data());
    glBindTexture(GL_TEXTURE_2D, 0);
    mShells = shells, mHeight_m = height_m, mStiffness = stiffness;
}

void BendTables::setGroups(const GrassWind& wind, int columns, int maxTextureSize) {
    const int groups = std::max<int>(1, static_cast<int>(wind.groupIntensity.size()));
    columns = std::clamp(columns, 1, groups);
    const int rows = (groups + columns - 1) / columns;
    if (columns > maxTextureSize || rows > maxTextureSize) {
        throw std::logic_error("GrassWind.groupIntensity has " + std::to_string(groups) +
                               " groups in a grid " + std::to_string(columns) +
                               " wide; the group table holds at most " +
                               std::to_string(maxTextureSize) + " on a side");
    }
    mTilts.resize(static_cast<size_t>(columns) * rows);
    for (int g = 0; g < groups; ++g) {
        const float intensity =
            wind.groupIntensity.empty() ? 0.0f : wind.groupIntensity[static_cast<size_t>(g)];
        if (!std::isfinite(intensity)) {
            throw std::logic_error("GrassWind.groupIntensity[" + std::to_string(g) +
                                   "] is not finite");
        }
        mTilts[static_cast<size_t>(g)] = static_cast<float>(tipTilt_rad(intensity));
    }
    // The last row's unused texels repeat the last group, so a blend at the grid's edge reads it.
    std::fill(mTilts.begin() + groups, mTilts.end(), mTilts[static_cast<size_t>(groups) - 1]);
    glBindTexture(GL_TEXTURE_2D, mGroups.get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    if (columns != mColumns || rows != mRows) {
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, columns, rows, 0, GL_RED, GL_FLOAT, mTilts.data());
        mColumns = columns, mRows = rows;
    } else {
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, columns, rows, GL_RED, GL_FLOAT, mTilts.data());
    }
    glBindTexture(GL_TEXTURE_2D, 0);
}

DensityTables::DensityTables()
    : mMap(newTableTexture(GL_LINEAR)),
      mCuts(newTableTexture(GL_LINEAR)),
      mPasses(newTableTexture(GL_NEAREST)) {}

void DensityTables::setShells(int shells) {
    if (shells == mPassShells) return;
    std::vector<float> table = shellPassFractions(mAlphaCount, shells);
    table.resize(MAX_SHELLS + 1, 0.0f);
    glBindTexture(GL_TEXTURE_2D, mPasses.get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, MAX_SHELLS + 1, 1, 0, GL_RED, GL_FLOAT, table.data());
    glBindTexture(GL_TEXTURE_2D, 0);
    mPassShells = shells;
}

void DensityTables::setCuts(const Image& level0) {
    mAlphaCount = alphaHistogram(level0);
    mPassShells = -1;
    const std::vector<float> cuts = densityCuts(level0);
    glBindTexture(GL_TEXTURE_2D, mCuts.get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, DENSITY_CUTS, 1, 0, GL_RED, GL_FLOAT, cuts.data());
    glBindTexture(GL_TEXTURE_2D, 0);
}

void DensityTables::setMap(const DensityMap& map, int maxTextureSize) {
    if (map.width == 0) {
        mActive = false;
        return;
    }
    const size_t texels = static_cast<size_t>(std::max(map.width, 0)) * std::max(map.height, 0);
    if (map.width < 1 || map.height < 1 || map.width > maxTextureSize ||
        map.height > maxTextureSize || map.density.size() != texels) {
        throw std::logic_error("DensityMap is " + std::to_string(map.width) + " x " +
                               std::to_string(map.height) + " with " +
                               std::to_string(map.density.size()) +
                               " values; expected width * height values, each side 1.." +
                               std::to_string(maxTextureSize));
    }
    for (size_t t = 0; t < texels; ++t)
        if (!std::isfinite(map.density[t]))
            throw std::logic_error("DensityMap.density[" + std::to_string(t) + "] is not finite");
    const bool finite = std::isfinite(map.wsSize_m.x) && std::isfinite(map.wsSize_m.y) &&
                        std::isfinite(map.wsMin_m.x) && std::isfinite(map.wsMin_m.y);
    if (!finite || !(map.wsSize_m.x > 0.0f && map.wsSize_m.y > 0.0f))
        throw std::logic_error("DensityMap.wsSize_m must be finite and > 0, wsMin_m finite");
    glBindTexture(GL_TEXTURE_2D, mMap.get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, map.width, map.height, 0, GL_RED, GL_FLOAT,
                 map.density.data());
    glBindTexture(GL_TEXTURE_2D, 0);
    checkGlError("ShellRenderer::setDensityMap");
    mActive = true;
    mMin_m = map.wsMin_m;
    mSize_m = map.wsSize_m;
}

}  // namespace gale::render::detail
