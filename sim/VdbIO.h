#pragma once
/// \file VdbIO.h
/// OpenVDB access to the air domain and the wind field. The one sim header that includes OpenVDB:
/// include it only from .cpp files that need grids (compile time).
///
/// Transform of every grid gale writes: uniform scale h (the voxel size), translated so that
/// index-space voxel (i, j, k) is cell (i, j, k) and its centre sits at world
/// wsMin + ((i + 1/2) h, (j + 1/2) h, (k + 1/2) h). Values are cell-centred.

#include <openvdb/openvdb.h>

#include <array>

#include "sim/AirDomain.h"
#include "sim/WindField.h"

namespace gale::sim {
namespace detail {
/// Linear transform of a cell-centred grid of cubic cells of edge voxelSize_m whose cell
/// (0, 0, 0) has its minimum corner at wsMin_m.
openvdb::math::Transform::Ptr cellCentredTransform(double voxelSize_m, const std::array<double, 3>& wsMin_m);
}  // namespace detail

/// The air mask: active voxels are the air cells of the domain (value true), never rock.
openvdb::BoolGrid::ConstPtr airMaskGrid(const AirDomain& domain);

/// "velocity": cell-centred averages of the MAC face velocities, m/s, world axes, active on air
/// cells; GRID_UNKNOWN, VEC_CONTRAVARIANT_RELATIVE, isInWorldSpace = true.
openvdb::Vec3SGrid::Ptr velocityGrid(const WindField& field);
/// "velocity_faces": the MAC face velocities themselves, m/s, as a staggered grid (GRID_STAGGERED):
/// voxel (i, j, k) holds (u, v, w) on cell (i, j, k)'s low x, y and z faces, so
/// openvdb::tools::StaggeredBoxSampler reads it as WindField::velocityAt_mps does inside the box.
/// Values in all (nx+1) x (ny+1) x (nz+1) voxels (the samplers read inactive ones too); active
/// where a face belongs to an air cell. Float, so 1e-7 relative off the doubles.
openvdb::Vec3SGrid::Ptr staggeredVelocityGrid(const WindField& field);
/// "speed": |velocity| of the cell-centred average, m/s, active on air cells.
openvdb::FloatGrid::Ptr speedGrid(const WindField& field);

}  // namespace gale::sim
