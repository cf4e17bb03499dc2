/// \file PoissonTerrains.cpp
/// The rough test terrains of PoissonTerrains.h (docs/solver.md, "Rough terrain").

#include "validation/PoissonTerrains.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace gale::validation {
using namespace gale::sim;  // Heightfield and its builders
namespace {

void requirePositive(double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v))
        throw std::invalid_argument(std::string("makeRoughTerrain: ") + name +
                                    " must be > 0 and finite, got " + std::to_string(v));
}

/// Largest |grad h| by one-sided differences between neighbouring samples (dimensionless).
double maxSlope(const Heightfield& f) {
    double s = 0.0;
    for (int j = 0; j < f.ny; ++j)
        for (int i = 0; i < f.nx; ++i) {
            if (i + 1 < f.nx)
                s = std::max(s, std::abs(double(f.at(i + 1, j)) - f.at(i, j)) / f.spacing_m);
            if (j + 1 < f.ny)
                s = std::max(s, std::abs(double(f.at(i, j + 1)) - f.at(i, j)) / f.spacing_m);
        }
    return s;
}

/// fBm with heights in [0, relief] before slope scaling.
Heightfield fractalBase(double size_m, double spacing_m, double relief_m, uint32_t seed,
                        int octaves) {
    TerrainSpec t;
    t.kind = TerrainKind::Fractal;
    t.sizeX_m = t.sizeY_m = size_m;
    t.spacing_m = spacing_m;
    t.height_m = relief_m;
    t.seed = seed;
    t.octaves = octaves;
    t.roughness = 0.55;
    t.featureSize_m = 0.5 * size_m;
    return makeTerrain(t);
}

}  // namespace

const char* roughTerrainName(RoughTerrainKind kind) {
    return kind == RoughTerrainKind::Fractal ? "fractal" : "sharp_features";
}

Heightfield makeRoughTerrain(RoughTerrainKind kind, double size_m, double spacing_m,
                             double relief_m, uint32_t seed) {
    requirePositive(size_m, "size_m");
    requirePositive(spacing_m, "spacing_m");
    requirePositive(relief_m, "relief_m");
    if (size_m / spacing_m < 15.0)
        throw std::invalid_argument("makeRoughTerrain: size_m / spacing_m must be >= 15, got " +
                                    std::to_string(size_m / spacing_m));
    if (kind == RoughTerrainKind::Fractal) {
        Heightfield f = fractalBase(size_m, spacing_m, relief_m, seed, /*octaves=*/6);
        // Scale about the lowest point so the steepest sample-to-sample slope is 1: the relief then
        // follows from the noise, which is what a DEM with 45-degree slopes looks like.
        const double lo = f.minHeight_m(), s = maxSlope(f);
        const double scale = s > 0.0 ? 1.0 / s : 1.0;
        for (float& z : f.height_m) z = float((z - lo) * scale);
        return f;
    }
    // Sharp features on a gentle base (a quarter of the relief, three octaves).
    Heightfield f = fractalBase(size_m, spacing_m, 0.25 * relief_m, seed, /*octaves=*/3);
    const double lo = f.minHeight_m();
    for (float& z : f.height_m) z = float(z - lo);
    const int n = f.nx;
    auto add = [&](int i, int j, double dz) {
        if (i >= 0 && j >= 0 && i < f.nx && j < f.ny) f.height_m[size_t(j) * n + i] += float(dz);
    };
    const double cliff = 0.35 * relief_m, gully = 0.3 * relief_m;
    for (int j = 0; j < f.ny; ++j)
        for (int i = 0; i < f.nx; ++i) {
            // A cliff: everything beyond x = 0.6 size (bending with y) stands `cliff` higher.
            const int edge = int(0.6 * n) + int(0.08 * n * std::sin(6.0 * j / n));
            if (i >= edge) add(i, j, cliff);
            // A square mesa with vertical sides.
            if (i > n / 8 && i < n / 4 && j > n / 8 && j < n / 4) add(i, j, 0.5 * relief_m);
        }
    // Two gullies two pixels wide: one along y, one diagonal.
    for (int j = 0; j < f.ny; ++j) {
        add(n / 3, j, -gully), add(n / 3 + 1, j, -gully);
        const int d = j * 3 / 4 + n / 6;
        if (d + 1 < f.nx && j > f.ny / 3) add(d, j, -gully), add(d + 1, j, -gully);
    }
    // A single-pixel spike as tall as the relief, on the high side of the cliff.
    add(int(0.8 * n), f.ny / 2, relief_m);
    const double low = f.minHeight_m();
    for (float& z : f.height_m) z = float(z - low);
    return f;
}

}  // namespace gale::validation
