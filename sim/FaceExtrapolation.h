#pragma once
/// \file FaceExtrapolation.h
/// \internal Included only by sim/ and tests/sim (docs/architecture.md lists sim's public headers).
/// Values for MAC faces that carry none (closed by the terrain), so that interpolating the field
/// near the ground stays smooth. Shared by the steady and unsteady solvers.

#include <cstdint>
#include <vector>

#include "sim/GridLayout.h"

namespace gale::sim::detail {

/// Fills faces with valid == 0 in the face array `a` (g.count(p) values of placement p) by the
/// mean of their valid face neighbours, `layers` times outwards; faces still without a value get
/// 0. Velocities, m/s; `valid` is not changed.
void extrapolateFaces(std::vector<double>& a, const std::vector<uint8_t>& valid, const GridIndex& g,
                      Placement p, int layers);

}  // namespace gale::sim::detail
