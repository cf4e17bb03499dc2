#pragma once
/// \file Heightfield.h
/// The terrain as a heightfield h(x, y) in world metres, z up (docs/design.md 3), and the
/// procedural and verification terrains a scene can name. Pure C++: no OpenVDB here, so every
/// module may use it.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace gale::sim {

/// Heights on a regular grid. Sample (i, j) sits at world position
/// (originX_m + i * spacing_m, originY_m + j * spacing_m, height_m[j * nx + i]).
struct Heightfield {
    int nx = 0;                   ///< samples along x (>= 2)
    int ny = 0;                   ///< samples along y (>= 2)
    double spacing_m = 1.0;       ///< distance between neighbouring samples, metres
    double originX_m = 0.0;       ///< world x of sample (0, 0), metres
    double originY_m = 0.0;       ///< world y of sample (0, 0), metres
    std::vector<float> height_m;  ///< nx * ny heights, metres, i fastest

    float at(int i, int j) const { return height_m[static_cast<size_t>(j) * nx + i]; }
    double sizeX_m() const { return (nx - 1) * spacing_m; }
    double sizeY_m() const { return (ny - 1) * spacing_m; }
    /// Bilinear height at world (x, y) in metres; clamps to the edge outside the grid.
    double sample(double wsX_m, double wsY_m) const;
    /// Unit upward normal at sample (i, j) from central differences (one-sided at the edges).
    std::array<double, 3> normalAt(int i, int j) const;
    double minHeight_m() const;
    double maxHeight_m() const;
};

enum class TerrainKind {
    Flat,
    GaussianHill,
    Ridge,
    Valley,
    Crater,
    Fractal,
    Hemisphere,
    Heightmap
};

/// Name as written in scene files ("gaussian_hill"), and back; fromName throws
/// gale::ParameterError (terrain.kind) listing the valid names.
const char* terrainKindName(TerrainKind kind);
TerrainKind terrainKindFromName(const std::string& name);

/// A procedural terrain. All lengths in metres; the grid covers [0, size] in x and y. The defaults
/// are the scene format's ([terrain], docs/scene-format.md): a 6 m knoll on a 40 m square.
struct TerrainSpec {
    TerrainKind kind = TerrainKind::GaussianHill;
    double sizeX_m = 40.0, sizeY_m = 40.0;  ///< extent of the terrain
    double spacing_m = 0.25;                ///< heightfield sample spacing
    double height_m = 6.0;  ///< hill/ridge height, valley/crater depth, fractal amplitude
    double radius_m = 8.0;  ///< hill sigma, ridge/valley half-width, crater/hemisphere radius
    double centerX_m = 20.0, centerY_m = 20.0;  ///< feature centre (the scene: size / 2)
    double axis_deg = 0.0;        ///< ridge/valley axis, degrees counter-clockwise from +x
    uint32_t seed = 1;            ///< fractal seed
    int octaves = 5;              ///< fractal octaves
    double roughness = 0.5;       ///< fractal amplitude ratio between octaves
    double featureSize_m = 20.0;  ///< fractal largest wavelength
};

/// Builds the heightfield of a procedural kind (not Heightmap, which the scene loads from an
/// image). Throws gale::ParameterError naming the scene key (terrain.size_m[0], terrain.spacing_m,
/// terrain.octaves, ...) when a size or spacing is not positive and finite, a fractal setting is
/// out of range, or the grid would exceed 16384 samples per side; std::logic_error for the
/// Heightmap kind.
Heightfield makeTerrain(const TerrainSpec& spec);

/// Heightfield from samples already in memory (e.g. a decoded heightmap image), validated:
/// throws std::invalid_argument (bad input data; the caller names its file) if a height is
/// NaN/Inf or the grid is smaller than 2x2 or larger than 16384 per side, gale::ParameterError
/// (terrain.metres_per_pixel) if the spacing is not positive and finite, and std::logic_error if
/// height_m does not hold nx * ny samples.
Heightfield makeHeightfield(int nx, int ny, double spacing_m, std::vector<float> height_m);

}  // namespace gale::sim
