#pragma once
/// \file FaceExtrapolation.h
/// \internal Included only by sim/ and tests/sim (docs/architecture.md lists sim's public headers).
/// Values for MAC faces that carry none (closed by the terrain), so that interpolating the field
/// near the ground stays smooth. Shared by the steady and unsteady solvers.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sim/GridLayout.h"

namespace gale::sim::detail {

/// The fills of extrapolateFaces for one mask, worked out once: a solver's masks stay as they are
/// from step to step, only the values change, so each step just applies the list.
class FaceExtrapolation {
  public:
    FaceExtrapolation() = default;
    /// The fills for faces of placement p with valid == 0 (g.count(p) flags), `layers` deep.
    FaceExtrapolation(const std::vector<uint8_t>& valid, const GridIndex& g, Placement p,
                      int layers);
    /// Fills `a` (g.count(p) values): each layer's closed faces get the mean of their neighbours
    /// that are valid by then, in the order -x, +x, -y, +y, -z, +z; faces no layer reaches get 0.
    void apply(std::vector<double>& a) const;
    /// The number of faces the layers fill (for tests).
    size_t filledCount() const;

  private:
    struct Fill {
        size_t face = 0;
        int count = 0;  ///< valid neighbours, 1..6
        size_t from[6] = {};
    };
    std::vector<std::vector<Fill>> mLayers;
    std::vector<size_t> mZeroed;  ///< closed faces no layer reaches
};

/// Fills faces with valid == 0 in the face array `a` (g.count(p) values of placement p) by the
/// mean of their valid face neighbours, `layers` times outwards; faces still without a value get
/// 0. Velocities, m/s; `valid` is not changed. FaceExtrapolation(valid, g, p, layers).apply(a).
void extrapolateFaces(std::vector<double>& a, const std::vector<uint8_t>& valid, const GridIndex& g,
                      Placement p, int layers);

}  // namespace gale::sim::detail
