#pragma once
/// \file FieldSampling.h
/// Reads a solved sim::WindField where the grass lives (DESIGN 5, step 1).

#include <vector>

#include <glm/vec3.hpp>

#include "render/GrassInput.h"
#include "sim/WindField.h"

namespace gale::coupling {

/// World velocity, m/s, at sampleHeight_m straight above every mesh vertex (vertical, not along
/// the normal: the field's log profile is measured from the ground vertically), by the field's
/// staggered trilinear interpolation. Vertices outside the field's box, or whose sample point is
/// below its terrain, get zero (WindField::velocityAt_mps's fallback), so the grass there stands
/// still rather than reading garbage. Multithreaded; O(vertices).
std::vector<glm::vec3> sampleAtGrass(const sim::WindField& field, const render::TerrainMesh& mesh,
                                     double sampleHeight_m);

}  // namespace gale::coupling
