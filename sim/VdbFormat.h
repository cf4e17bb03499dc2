#pragma once
/// \internal
/// \file VdbFormat.h
/// What gale's .vdb writer (sim/VdbIO.cpp) and reader (sim/VdbRead.cpp) agree on: the face
/// grids' names and the stretched layers' level heights as metadata text.

#include <string>

#include "sim/GridLayout.h"

namespace gale::sim::detail {

inline constexpr const char* CUBIC_FACES_GRID = "velocity_faces";
inline constexpr const char* STRETCHED_FACES_GRID = "velocity_layers";

/// The level heights as metadata text (z_levels_m): world z of z-face k, metres, space-separated,
/// each to 17 significant digits, so that a reader compares them exactly.
std::string levelsText(const GridLayout& layout);

}  // namespace gale::sim::detail
