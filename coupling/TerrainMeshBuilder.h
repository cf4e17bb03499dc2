#pragma once
/// \file TerrainMeshBuilder.h
/// The render mesh of a sim::Heightfield: one vertex per sample (or every `stride`-th), normals
/// from the heightfield, texture coordinates repeating every tile_m metres.

#include "render/GrassInput.h"
#include "sim/Heightfield.h"

namespace gale::coupling {

/// stride >= 1 takes every stride-th sample (the last row/column is always kept); tile_m, metres
/// per texture tile, > 0. Throws gale::ParameterError naming terrain.mesh_stride or grass.tile_m,
/// std::logic_error for a heightfield smaller than 2 x 2.
render::TerrainMesh buildTerrainMesh(const sim::Heightfield& field, float tile_m, int stride = 1);

}  // namespace gale::coupling
