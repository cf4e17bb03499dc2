#pragma once
/// \file DensityMap.h
/// Grass density over the terrain's plan (after the density maps of Boulanger, Pattanaik and
/// Bouatouch 2006): paths, bare patches and thinning meadows from an image. The renderer keeps a
/// blade where its height (the grass texture's alpha) is above a cut chosen so that the kept blades
/// cover the map's fraction of the texture's blade area: blades vanish whole, tallest last, and
/// the blades that stay keep their full height and bend. docs/render.md.

#include <array>
#include <glm/vec2.hpp>
#include <string>
#include <vector>

#include "render/GrassInput.h"

namespace gale::render {

/// Density in [0, 1] per texel (1: the grass texture's own density; 0: bare ground), over the
/// plan rectangle [wsMin_m, wsMin_m + wsSize_m] (world metres, x east, y north). Row 0 is the
/// north edge (an image's top row), column 0 the west edge.
struct DensityMap {
    int width = 0;  ///< 0: no map (density 1 everywhere)
    int height = 0;
    std::vector<float> density;  ///< width * height, row-major from the north edge
    glm::vec2 wsMin_m{0.0f};
    glm::vec2 wsSize_m{1.0f};
};

/// Largest side of a density map, pixels: its float copy is at most 256 MiB.
constexpr int MAX_DENSITY_MAP_SIDE_PX = 8192;

/// Reads a density map from any image OpenImageIO reads (8/16-bit or float; the first channel,
/// a grey image's grey: 0 = bare, full scale = full density) to cover the plan rectangle given.
/// The header is checked before anything is allocated (at most MAX_DENSITY_MAP_SIDE_PX a side; a
/// PNG smaller than its claimed pixels could compress to is corrupt), and every value must be
/// finite and in [0, 1] (float images). Throws std::runtime_error "PATH: reason" if the image
/// cannot be read or is refused; std::logic_error if wsSize_m is not positive and finite (the
/// caller's plan rectangle).
DensityMap loadDensityMap(const std::string& path, glm::vec2 wsMin_m, glm::vec2 wsSize_m);

/// Entries of the density cut table: entry k is the cut for density k / (DENSITY_CUTS - 1).
constexpr int DENSITY_CUTS = 256;

/// The cut table of a grass texture's level 0 (alpha = blade height, 0 = ground): entry k is the
/// alpha (in [0, 1], or 2 for none) such that the blade texels with alpha >= cut are a fraction
/// k / 255 of all blade texels, rounded up to whole 8-bit heights; entry 0 (density 0) keeps none;
/// entry 255 keeps every blade (cut 0). A texture without blades gives cuts of 0.
std::vector<float> densityCuts(const Image& level0);

/// How many texels of a grass texture's level 0 have each 8-bit alpha (blade height).
std::array<size_t, 256> alphaHistogram(const Image& level0);

/// The pass table of a grass texture for N = `shells` shells (level of detail, shell.vert): entry m
/// (m = 0..N) is the share of rays that cross shells 1..m, each at a texel of its own, without
/// stopping on a blade: the product over k = 1..m of (1 - c_k), c_k the share of texels shell k
/// keeps (alpha >= 255 k / N less half a step, shell.vert's test). Entry 0 is 1; an empty
/// histogram passes every ray.
std::vector<float> shellPassFractions(const std::array<size_t, 256>& alphaCount, int shells);

}  // namespace gale::render
