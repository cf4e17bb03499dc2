#pragma once
/// \file PoissonTerrains.h
/// Rough, real-like terrains for the solver's iteration tests and `gale bench solve` (issue 12):
/// where the synthetic hills are smooth, these have what makes a real DEM hard for multigrid:
/// slopes up to 1, features one heightmap pixel wide and thin cut cells everywhere. Built in
/// code from a seed, so every run and machine sees the same heights.
///
/// Both cover [0, size_m] x [0, size_m] with samples every spacing_m metres (world metres, z up,
/// heights >= 0). The heights do not depend on the voxel size a solve later uses, so one terrain
/// can be solved at several resolutions.

#include <cstdint>

#include "sim/Heightfield.h"

namespace gale::validation {

enum class RoughTerrainKind {
    /// Fractional Brownian motion (six octaves of value noise, amplitude ratio 0.55), scaled so
    /// that its steepest slope between neighbouring samples is exactly 1 (45 degrees).
    Fractal,
    /// A gentle fractal base with sharp features: a vertical cliff across the box (one pixel
    /// wide), two narrow gullies (two pixels wide, deep), a square mesa with cliff sides and a
    /// single-pixel spike as tall as the relief.
    SharpFeatures,
};

/// "fractal" or "sharp_features".
const char* roughTerrainName(RoughTerrainKind kind);

/// Builds the terrain. Fractal: relief_m is ignored, the relief follows from the slope (about 17
/// spacings). SharpFeatures: relief_m is the spike's height above its surroundings; the base
/// spans 0.25, the cliff 0.35, the gullies 0.3 and the mesa 0.5 of it. Throws std::invalid_argument
/// naming the parameter when size_m, spacing_m or relief_m is not positive and finite, or size_m
/// holds fewer than 16 samples per side.
sim::Heightfield makeRoughTerrain(RoughTerrainKind kind, double size_m, double spacing_m,
                                  double relief_m, uint32_t seed = 12);

}  // namespace gale::validation
