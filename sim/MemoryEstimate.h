#pragma once
/// \file MemoryEstimate.h
/// Peak memory of a solve, estimated from the box's shape before anything is allocated.
///
/// Every array a run allocates is counted with its real dimensions, so thin and flat boxes get
/// what they really cost: the multigrid levels carry one ghost layer on every side ((nx + 2)(ny
/// + 2)(nz + 2) per level), and an OpenVDB tree pays for whole 8^3 leaves and 128^3 / 4096^3
/// internal nodes however few voxels they hold (a column 2 cells wide costs 16x its voxels in
/// leaves, and one 33-66 KiB internal node per 128 cells of height). Dimensions are doubles so
/// absurd boxes can be priced (and refused) without overflow. Checked against the peak resident
/// memory of real runs by `gale bench memory` (docs/reliability.md).

namespace gale::sim {

/// Bytes of an OpenVDB tree whose active voxels fill a box of nx * ny * nz voxels starting at
/// index (0, 0, 0), with values of valueBytes bytes (1 for a BoolGrid: stored as bits): leaves,
/// both internal levels and the root's entries (the 5-4-3 tree every gale grid uses).
double vdbBoxTree_bytes(double nx, double ny, double nz, double valueBytes);

/// Faces of a MAC grid of nx * ny * nz cells, the three components together.
double macFaceCount(double nx, double ny, double nz);

/// Bytes of one .vdb file WindField::writeVdb writes for a box of nx * ny * nz cubic cells, at
/// most: the grids velocity (3 floats) and speed (1) over the box's cells and velocity_faces (3
/// floats) over (nx + 1)(ny + 1)(nz + 1) voxels, their values counted uncompressed (a field
/// with no smooth parts does not compress), plus what OpenVDB writes per 8^3 leaf
/// (VDB_FILE_LEAF_BYTES: two value masks, the compression header) however few voxels it holds, per
/// internal node and per file. Measured on written files of steady and unsteady runs, from 2 x 2 x
/// 3000 columns to 256 x 256 x 10 slabs: 0.46-0.74 of this (docs/reliability.md). Stretched layers
/// (a steady solve only) write other grids and are not covered.
double vdbWindFile_bytes(double nx, double ny, double nz);

/// What OpenVDB writes per leaf besides its values: the value mask twice (topology and buffers,
/// 64 B each), the compression's metadata byte, selection mask and Blosc headers; 241 B by count,
/// rounded up.
inline constexpr double VDB_FILE_LEAF_BYTES = 256.0;

struct UnsteadySettings;

/// What a run holds besides the air domain and the steady solve, and what the process held
/// before it (DomainSpec::run: AirDomain counts it in its estimate and limit).
struct RunMemory {
    /// An unsteady run: a second solver for the projection, the mean and current fields, the
    /// advection's arrays the solver keeps (scratchFaceArrays doubles per face) and the widest
    /// other scratch (viscosityFaceArrays doubles per face or scratchCellBytes per cell;
    /// unsteadyRunMemory fills these in).
    bool unsteady = false;
    double scratchFaceArrays = 0;
    double viscosityFaceArrays = 0;  ///< the implicit viscosity's CG vectors, doubles per face
    double scratchCellBytes = 0;
    /// A two-equation closure's arrays, bytes per cell (TurbulentStress::closureBytesPerCell:
    /// its transported variables and face arrays), for the momentum model or an unsteady surface
    /// layer that uses one; 0 for the mixing length.
    double closureCellBytes = 0;
    /// Resident bytes of the process before the domain is built (the program, its libraries, the
    /// scene and terrain), counted in the estimate; 0 for the arrays alone.
    double processBaseline_bytes = 0;
};

/// The unsteady run's RunMemory for these settings (its scratch depends on the advection scheme,
/// the viscosity step and vorticity confinement).
RunMemory unsteadyRunMemory(const UnsteadySettings& settings);

/// Estimated peak bytes a solve on a box of nx * ny * nz cells allocates: the air domain (with
/// its copy of terrainSamples heights), the steady solver and its field, the output grids
/// written at the end or per output time, the momentum model's arrays (momentum) and an unsteady
/// run's (run.unsteady); not run.processBaseline_bytes.
double solveArrays_bytes(double nx, double ny, double nz, double terrainSamples, bool momentum,
                         const RunMemory& run);

}  // namespace gale::sim
