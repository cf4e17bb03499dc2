#include "sim/Heightfield.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/Interpolation.h"

namespace gale::sim {
namespace {

constexpr int MAX_SAMPLES_PER_SIDE = 16384;

struct KindName {
    TerrainKind kind;
    const char* name;
};
constexpr KindName KIND_NAMES[] = {
    {TerrainKind::Flat, "flat"},
    {TerrainKind::GaussianHill, "gaussian_hill"},
    {TerrainKind::Ridge, "ridge"},
    {TerrainKind::Valley, "valley"},
    {TerrainKind::Crater, "crater"},
    {TerrainKind::Fractal, "fractal"},
    {TerrainKind::Hemisphere, "hemisphere"},
    {TerrainKind::Heightmap, "heightmap"},
};

/// `key`: the scene's dotted key of the value.
void requirePositive(double value, const char* key) {
    if (!std::isfinite(value) || value <= 0.0)
        throw ParameterError(key, formatG(value), "must be a finite number > 0");
}

void requireFinite(double value, const char* key) {
    if (!std::isfinite(value)) throw ParameterError(key, formatG(value), "must be finite");
}

/// Samples along one side of `size_m` (named `sizeName`, e.g. "size_m[0]").
int samplesAlong(double size_m, double spacing_m, const char* sizeName) {
    const double n = std::floor(size_m / spacing_m + 0.5) + 1.0;
    if (n > MAX_SAMPLES_PER_SIDE)
        throw ParameterError("terrain.spacing_m", formatG(spacing_m),
                             "gives " + formatG(n, 12) + " samples along " + sizeName + " = " +
                                 formatG(size_m) + " m; at most " +
                                 std::to_string(MAX_SAMPLES_PER_SIDE) +
                                 " are allowed per side (raise spacing_m)");
    return std::max(2, static_cast<int>(n));
}

// splitmix64: a portable hash, so fractal terrains are identical on every compiler and machine.
uint64_t mix(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// Value noise in [-1, 1] at lattice point (ix, iy) of octave `o`.
double latticeValue(uint32_t seed, int o, int64_t ix, int64_t iy) {
    uint64_t h = mix(seed ^ mix(static_cast<uint64_t>(o) * 0x632be59bd9b4e019ull ^
                                mix(static_cast<uint64_t>(ix) ^ mix(static_cast<uint64_t>(iy)))));
    return (static_cast<double>(h >> 11) / 9007199254740992.0) * 2.0 - 1.0;
}

// Smooth (C1, quintic-faded) value noise at (x, y) in lattice units.
double valueNoise(uint32_t seed, int o, double x, double y) {
    const double fx = std::floor(x), fy = std::floor(y);
    const int64_t ix = static_cast<int64_t>(fx), iy = static_cast<int64_t>(fy);
    auto fade = [](double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); };
    const double tx = fade(x - fx), ty = fade(y - fy);
    const double v00 = latticeValue(seed, o, ix, iy), v10 = latticeValue(seed, o, ix + 1, iy);
    const double v01 = latticeValue(seed, o, ix, iy + 1),
                 v11 = latticeValue(seed, o, ix + 1, iy + 1);
    return bilinearWeighted(v00, v10, v01, v11, tx, ty);
}

// Height of the procedural terrain at world (x, y), metres.
double proceduralHeight(const TerrainSpec& s, double x, double y) {
    const double dx = x - s.centerX_m, dy = y - s.centerY_m;
    const double r2 = dx * dx + dy * dy;
    const double a = radiansFromDegrees(s.axis_deg);
    // Distance from the feature's axis line (ridge, valley).
    const double across = -dx * std::sin(a) + dy * std::cos(a);
    const double sigma2 = s.radius_m * s.radius_m;
    switch (s.kind) {
        case TerrainKind::Flat:
        case TerrainKind::Heightmap:
            return 0.0;
        case TerrainKind::GaussianHill:
            return s.height_m * std::exp(-r2 / (2.0 * sigma2));
        case TerrainKind::Ridge:
            return s.height_m * std::exp(-across * across / (2.0 * sigma2));
        case TerrainKind::Valley:
            // Floor at 0 along the axis, rising to height_m on both sides.
            return s.height_m * (1.0 - std::exp(-across * across / (2.0 * sigma2)));
        case TerrainKind::Crater: {
            // A rim of height_m at r = radius with a bowl inside that dips below the plain.
            const double r = std::sqrt(r2), w = 0.25 * s.radius_m;
            const double rim = std::exp(-(r - s.radius_m) * (r - s.radius_m) / (2.0 * w * w));
            const double bowl = std::exp(-r2 / (2.0 * 0.36 * sigma2));
            return s.height_m * (rim - 0.6 * bowl);
        }
        case TerrainKind::Fractal: {
            // Fractional Brownian motion of value noise: octave o has wavelength
            // featureSize / 2^o and amplitude roughness^o, normalised to peak height_m.
            double sum = 0.0, amp = 1.0, norm = 0.0, freq = 1.0 / s.featureSize_m;
            for (int o = 0; o < s.octaves; ++o) {
                sum += amp * valueNoise(s.seed, o, x * freq, y * freq);
                norm += amp;
                amp *= s.roughness;
                freq *= 2.0;
            }
            return s.height_m * 0.5 * (sum / norm + 1.0);
        }
        case TerrainKind::Hemisphere:
            return r2 < sigma2 ? std::sqrt(sigma2 - r2) : 0.0;
    }
    return 0.0;
}

}  // namespace

const char* terrainKindName(TerrainKind kind) {
    for (const KindName& k : KIND_NAMES)
        if (k.kind == kind) return k.name;
    return "unknown";
}

TerrainKind terrainKindFromName(const std::string& name) {
    for (const KindName& k : KIND_NAMES)
        if (name == k.name) return k.kind;
    std::string valid;
    for (const KindName& k : KIND_NAMES) valid += std::string(valid.empty() ? "" : ", ") + k.name;
    throw ParameterError("terrain.kind", "\"" + name + "\"", "expected one of: " + valid);
}

double Heightfield::sample(double wsX_m, double wsY_m) const {
    const double fx = std::clamp((wsX_m - originX_m) / spacing_m, 0.0, double(nx - 1));
    const double fy = std::clamp((wsY_m - originY_m) / spacing_m, 0.0, double(ny - 1));
    const int i = std::min(static_cast<int>(fx), nx - 2),
              j = std::min(static_cast<int>(fy), ny - 2);
    const double tx = fx - i, ty = fy - j;
    return bilinearWeighted<double>(at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1), tx, ty);
}

std::array<double, 3> Heightfield::normalAt(int i, int j) const {
    const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, nx - 1);
    const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, ny - 1);
    const double dhdx = (at(i1, j) - at(i0, j)) / ((i1 - i0) * spacing_m);
    const double dhdy = (at(i, j1) - at(i, j0)) / ((j1 - j0) * spacing_m);
    // Normal of z = h(x, y) is (-h_x, -h_y, 1) / |...|: never degenerate for finite slopes.
    const double len = std::sqrt(dhdx * dhdx + dhdy * dhdy + 1.0);
    return {-dhdx / len, -dhdy / len, 1.0 / len};
}

double Heightfield::minHeight_m() const {
    return height_m.empty() ? 0.0 : *std::min_element(height_m.begin(), height_m.end());
}

double Heightfield::maxHeight_m() const {
    return height_m.empty() ? 0.0 : *std::max_element(height_m.begin(), height_m.end());
}

Heightfield makeTerrain(const TerrainSpec& spec) {
    if (spec.kind == TerrainKind::Heightmap)
        throw std::logic_error(
            "makeTerrain: terrain.kind 'heightmap' is loaded from an image, "
            "not built");
    requirePositive(spec.sizeX_m, "terrain.size_m[0]");
    requirePositive(spec.sizeY_m, "terrain.size_m[1]");
    requirePositive(spec.spacing_m, "terrain.spacing_m");
    requireFinite(spec.height_m, "terrain.height_m");
    requireFinite(spec.centerX_m, "terrain.center_m[0]");
    requireFinite(spec.centerY_m, "terrain.center_m[1]");
    requireFinite(spec.axis_deg, "terrain.axis_deg");
    if (spec.kind != TerrainKind::Flat && spec.kind != TerrainKind::Fractal)
        requirePositive(spec.radius_m, "terrain.radius_m");
    if (spec.kind == TerrainKind::Fractal) {
        requirePositive(spec.featureSize_m, "terrain.feature_size_m");
        if (spec.octaves < 1 || spec.octaves > 16)
            throw ParameterError("terrain.octaves", std::to_string(spec.octaves),
                                 "must be in 1..16");
        if (!(spec.roughness > 0.0 && spec.roughness <= 1.0))
            throw ParameterError("terrain.roughness", formatG(spec.roughness), "must be in (0, 1]");
    }
    Heightfield f;
    f.nx = samplesAlong(spec.sizeX_m, spec.spacing_m, "size_m[0]");
    f.ny = samplesAlong(spec.sizeY_m, spec.spacing_m, "size_m[1]");
    f.spacing_m = spec.spacing_m;
    f.height_m.resize(static_cast<size_t>(f.nx) * f.ny);
    for (int j = 0; j < f.ny; ++j)
        for (int i = 0; i < f.nx; ++i)
            f.height_m[static_cast<size_t>(j) * f.nx + i] =
                static_cast<float>(proceduralHeight(spec, i * spec.spacing_m, j * spec.spacing_m));
    return f;
}

Heightfield makeHeightfield(int nx, int ny, double spacing_m, std::vector<float> height_m) {
    if (nx < 2 || ny < 2)
        throw std::invalid_argument("heightfield must be at least 2x2 samples, got " +
                                    std::to_string(nx) + "x" + std::to_string(ny));
    if (nx > MAX_SAMPLES_PER_SIDE || ny > MAX_SAMPLES_PER_SIDE)
        throw std::invalid_argument("heightfield of " + std::to_string(nx) + "x" +
                                    std::to_string(ny) + " samples exceeds " +
                                    std::to_string(MAX_SAMPLES_PER_SIDE) + " per side");
    requirePositive(spacing_m, "terrain.metres_per_pixel");
    if (height_m.size() != static_cast<size_t>(nx) * ny)
        throw std::logic_error("heightfield has " + std::to_string(height_m.size()) +
                               " heights for " + std::to_string(nx) + "x" + std::to_string(ny) +
                               " samples");
    for (size_t k = 0; k < height_m.size(); ++k) {
        if (!std::isfinite(height_m[k])) {
            std::ostringstream msg;
            msg << "height at sample (" << k % nx << ", " << k / nx << ") is " << height_m[k]
                << "; heights must be finite";
            throw std::invalid_argument(msg.str());
        }
    }
    Heightfield f;
    f.nx = nx;
    f.ny = ny;
    f.spacing_m = spacing_m;
    f.height_m = std::move(height_m);
    return f;
}

}  // namespace gale::sim
