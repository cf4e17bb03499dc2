#pragma once
/// \file VdbIO.h
/// OpenVDB access to the air domain and the wind field. The one sim header that includes OpenVDB:
/// include it only from .cpp files that need grids (compile time).
///
/// Transform of every grid gale writes: uniform scale h (the voxel size), translated so that
/// index-space voxel (i, j, k) is cell (i, j, k) and its centre sits at world
/// wsMin + ((i + 1/2) h, (j + 1/2) h, (k + 1/2) h). Values are cell-centred.
///
/// Stretched layers (GridLayout with level heights): a VDB transform is affine, so it cannot
/// place layers of varying thickness. The standard grids ("velocity", "speed", Houdini's "vel"
/// and "surface") are then a cubic resample at the horizontal spacing h with the transform above
/// (voxel centres sampled through WindField::velocityAt_mps), so every VDB tool reads them as
/// for cubic cells; the native face values go to "velocity_layers" (not "velocity_faces", so no
/// tool mistakes them for a cubic staggered grid), whose voxel k is layer k, with the level
/// heights in the metadata "z_levels_m" (world z of z-face k, metres, space-separated).

#include <openvdb/openvdb.h>

#include <array>
#include <map>
#include <string>
#include <vector>

#include "sim/AirDomain.h"
#include "sim/WindField.h"

namespace gale::sim {
namespace detail {
/// Linear transform of a cell-centred grid of cubic cells of edge voxelSize_m whose cell
/// (0, 0, 0) has its minimum corner at wsMin_m.
openvdb::math::Transform::Ptr cellCentredTransform(double voxelSize_m,
                                                   const std::array<double, 3>& wsMin_m);
}  // namespace detail

/// The air mask: active voxels are the air cells of the domain (value true), never rock.
openvdb::BoolGrid::ConstPtr airMaskGrid(const AirDomain& domain);

/// "velocity": cell-centred averages of the MAC face velocities, m/s, world axes, active on air
/// cells (stretched layers: the cubic resample, active where the voxel centre is above the
/// terrain); GRID_UNKNOWN, VEC_CONTRAVARIANT_RELATIVE, isInWorldSpace = true.
openvdb::Vec3SGrid::Ptr velocityGrid(const WindField& field);
/// "velocity_faces": the MAC face velocities themselves, m/s, as a staggered grid (GRID_STAGGERED):
/// voxel (i, j, k) holds (u, v, w) on cell (i, j, k)'s low x, y and z faces, so
/// openvdb::tools::StaggeredBoxSampler reads it as WindField::velocityAt_mps does inside the box.
/// Values in all (nx+1) x (ny+1) x (nz+1) voxels (the samplers read inactive ones too); active
/// where a face belongs to an air cell. Float, so 1e-7 relative off the doubles. On stretched
/// layers the grid is "velocity_layers" with metadata "z_levels_m" (file comment).
openvdb::Vec3SGrid::Ptr staggeredVelocityGrid(const WindField& field);
/// Reads the "velocity_faces" grid of a .vdb that gale wrote into `field`'s face velocities
/// (m/s). `field` gives the geometry (from the same scene's AirDomain); the file's voxel size and
/// origin must match it to 1e-6 of a voxel (stretched layers: "velocity_layers", whose
/// z_levels_m must equal the field's levels). Returns the file's "time_s" metadata (unsteady
/// sequences), or NaN when it has none. Throws std::runtime_error naming the file when it cannot
/// be read, has no velocity_faces grid, or was solved on another grid (both geometries named).
double readFaceVelocities(const std::string& path, WindField& field);

/// Writes the field for Houdini (and other y-up tools): a Vec3s grid "vel" (m/s, cell-centred,
/// GRID_UNKNOWN, VEC_CONTRAVARIANT_RELATIVE) and a level-set FloatGrid "surface" of the terrain
/// (negative inside the ground), both with a y-up transform: gale's world (x, y, z), z up, becomes
/// (x, z, -y), so the ground lies in Houdini's xz plane and north (+y) points along -z. The SDF is
/// the vertical distance z - h(x, y) on a narrow band of 3 voxels (exact for flat ground, an
/// overestimate of the true distance on slopes, still zero on the surface). Written atomically.
/// Throws std::runtime_error naming the path when it cannot be written.
void writeHoudiniVdb(const std::string& path, const WindField& field, const Heightfield& terrain);

/// "speed": |velocity| of the cell-centred average, m/s, active on air cells.
openvdb::FloatGrid::Ptr speedGrid(const WindField& field);

/// Name of the turbulent kinetic energy grid on cubic cells, and on stretched layers (voxel k is
/// layer k, metadata "z_levels_m", like "velocity_layers").
inline constexpr const char* TKE_GRID = "tke";
inline constexpr const char* TKE_LAYERS_GRID = "tke_layers";

/// "tke" (stretched layers: "tke_layers"): the momentum model's turbulent kinetic energy k,
/// m^2/s^2, one float per air cell, voxel (i, j, k) = cell (i, j, k) with the cell-centred
/// transform of the file comment (stretched: its z is the layer index, the layers' world z in
/// "z_levels_m"); active on air cells, background 0; GRID_UNKNOWN (the grid's "class"), metadata
/// "units" = "m^2/s^2", "quantity" and "cell_placement". tke_m2ps2 holds one value per cell
/// (GridIndex cell layout); throws std::invalid_argument otherwise.
openvdb::FloatGrid::Ptr tkeGrid(const WindField& field, const std::vector<double>& tke_m2ps2);

/// Reads the "tke" grid (stretched layers: "tke_layers") of a .vdb that gale solve wrote for
/// `field`'s geometry into one value per cell (m^2/s^2, GridIndex cell layout; solid cells 0).
/// Empty when the file holds no such grid (a mass-consistent field: no turbulence). Call it after
/// readFaceVelocities has accepted the file (same grid). Throws std::runtime_error naming the file
/// when it cannot be read, the grid is not a float grid, lies outside the field's cells, or sits
/// on another voxel size, origin or layers.
std::vector<double> readCellTke(const std::string& path, const WindField& field);

/// Voxels along z of the standard grids ("velocity", "speed", Houdini's "vel") of a field on
/// `layout`: its nz for cubic cells, the cubic resample's layers for stretched layers (file
/// comment).
int vdbCubicLayers(const GridLayout& layout);

/// The names of the grids a .vdb file holds, in the file's order; reads the file's grid
/// descriptors, not its trees. Throws std::runtime_error "PATH: reason".
std::vector<std::string> vdbGridNames(const std::string& path);

/// The string metadata of grid `gridName` of a .vdb (scene, converged, provenance, ...); reads
/// that grid's metadata, not its tree. Throws std::runtime_error "PATH: reason" when the file
/// cannot be read or has no such grid.
std::map<std::string, std::string> vdbGridStrings(const std::string& path,
                                                  const std::string& gridName);

}  // namespace gale::sim
