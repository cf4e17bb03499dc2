#pragma once
/// \file ColorMap.h
/// The colour map of the field views: viridis (van der Walt and Smith 2015, "mpl colormaps",
/// designed for matplotlib 2.0), perceptually uniform and with lightness rising monotonically, so
/// a person reads "faster" as "brighter" and a grey-scale print keeps the order.

#include <glm/vec3.hpp>

namespace gale::render {

/// viridis(t) as sRGB in [0, 1] for t in [0, 1] (clamped; NaN gives t = 0). A table fit: the ten
/// colours of matplotlib's viridis at t = k / 9 (its _viridis_data rows 0, 28, 57, ... 255),
/// linearly interpolated in sRGB. The largest departure from the 256-entry original is about
/// 1/100 per channel, well below what the eye separates in a legend.
glm::vec3 viridis(float t);

/// CIE 1976 lightness L* (0 black .. 100 white) of an sRGB colour in [0, 1] (sRGB decoding after
/// IEC 61966-2-1, D65 luminance weights); the tests use it to check the map.
float cieLightness(const glm::vec3& srgb);

}  // namespace gale::render
