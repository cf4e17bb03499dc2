/// \file MemoryEstimate.cpp
/// Bytes of every array a solve allocates, from the box's shape (see MemoryEstimate.h).

#include "sim/MemoryEstimate.h"

#include <algorithm>
#include <cmath>

#include "sim/MomentumWind.h"
#include "sim/PoissonSolver.h"
#include "sim/UnsteadyWind.h"

namespace gale::sim {

double vdbBoxTree_bytes(double nx, double ny, double nz, double valueBytes) {
    auto nodes = [&](double span) {
        return std::ceil(nx / span) * std::ceil(ny / span) * std::ceil(nz / span);
    };
    // OpenVDB's 5-4-3 tree: a leaf holds 8^3 values (bools as a bit mask) and a value mask of
    // 64 B plus its header; an internal node holds a child-or-value slot per child (a pointer, or
    // the value when wider: 16 B for a Vec3s) and two bit masks. Allocator headers included.
    const bool isBool = valueBytes <= 1.0;
    const double leafBytes = (isBool ? 64.0 : 512.0 * valueBytes) + 64.0 + 96.0;
    const double slot = std::max(8.0, std::ceil(valueBytes / 8.0) * 8.0);
    const double node1Bytes = 4096.0 * slot + 2 * 512.0 + 64.0;
    const double node2Bytes = 32768.0 * slot + 2 * 4096.0 + 64.0;
    const double rootEntryBytes = 96.0;
    return nodes(8) * leafBytes + nodes(128) * node1Bytes +
           nodes(4096) * (node2Bytes + rootEntryBytes);
}

double vdbWindFile_bytes(double nx, double ny, double nz) {
    auto nodes = [](double x, double y, double z, double span) {
        return std::ceil(x / span) * std::ceil(y / span) * std::ceil(z / span);
    };
    // Internal nodes write their child and value masks (2 x 512 B for 16^3 children, 2 x 4 KiB
    // for 32^3) and their tile values, compressed (background only); a file its header, the grid
    // descriptors, transforms and metadata.
    constexpr double NODE1_FILE_BYTES = 1536.0, NODE2_FILE_BYTES = 9216.0, FILE_BYTES = 8192.0;
    auto grid = [&](double x, double y, double z, double valueBytes) {
        return x * y * z * valueBytes + nodes(x, y, z, 8) * VDB_FILE_LEAF_BYTES +
               nodes(x, y, z, 128) * NODE1_FILE_BYTES + nodes(x, y, z, 4096) * NODE2_FILE_BYTES;
    };
    return grid(nx, ny, nz, 12.0) + grid(nx, ny, nz, 4.0) + grid(nx + 1, ny + 1, nz + 1, 12.0) +
           FILE_BYTES;
}

double macFaceCount(double nx, double ny, double nz) {
    return (nx + 1) * ny * nz + nx * (ny + 1) * nz + nx * ny * (nz + 1);
}

RunMemory unsteadyRunMemory(const UnsteadySettings& settings) {
    RunMemory run;
    run.unsteady = true;
    // Advection keeps a copy of the field (one array of faces); MacCormack adds its backward pass
    // and the two limiter bounds, BFECC also its corrected copy, each for one component at a
    // time (at most about half the faces: the widest component of a flat box).
    double arrays = 1.0;
    if (settings.advection == AdvectionScheme::MacCormack) arrays += 4 * 0.5;
    if (settings.advection == AdvectionScheme::Bfecc) arrays += 5 * 0.5;
    run.scratchFaceArrays = arrays;
    // The implicit viscosity's conjugate gradients: six vectors of one component.
    if (settings.viscosity_m2ps > 0.0 || settings.surfaceLayer.enabled)
        run.viscosityFaceArrays = 6 * 0.5;
    // Vorticity confinement: centred velocity, vorticity and force (3 doubles each) and the
    // vorticity's magnitude, per cell.
    if (settings.vorticityConfinement > 0.0 || !settings.whirlwinds.empty())
        run.scratchCellBytes = (3 * 3 + 1) * 8.0;
    if (settings.surfaceLayer.enabled)
        run.closureCellBytes = TurbulentStress::closureBytesPerCell(settings.surfaceLayer.closure);
    return run;
}

double solveArrays_bytes(double nx, double ny, double nz, double terrainSamples, bool momentum,
                         const RunMemory& run) {
    const double cells = nx * ny * nz, faces = macFaceCount(nx, ny, nz);
    // The air domain: open fractions (a float per face), air flags, the OpenVDB air mask, its own
    // copy of the heightfield (a float per sample).
    const double domain =
        faces * 4.0 + cells * 1.0 + vdbBoxTree_bytes(nx, ny, nz, 1.0) + terrainSamples * 4.0;
    // The steady solve: the PoissonSystem's weight copy (a float per face), the solver, the MAC
    // field (a double per face) and its air flags, right-hand side and potential, the velocity
    // update's face flags.
    const double steady = faces * (4.0 + 8.0 + 1.0) + cells * (1.0 + 2 * 8.0) +
                          PoissonSolver::estimatedBytes(nx, ny, nz);
    // The grids written (VdbIO.h): cell-centred velocity (Vec3s) and speed (float) over the air,
    // counted over the box; the staggered face velocities (Vec3s) over the box and its far faces.
    const double output = vdbBoxTree_bytes(nx, ny, nz, 12.0) + vdbBoxTree_bytes(nx, ny, nz, 4.0) +
                          vdbBoxTree_bytes(nx + 1, ny + 1, nz + 1, 12.0);
    double extra = 0.0;
    if (momentum) extra += cells * MOMENTUM_EXTRA_BYTES_PER_CELL;
    extra += cells * run.closureCellBytes;
    if (run.unsteady) {
        // UnsteadyWindSolver beside the steady solve: its own PoissonSystem weights and solver,
        // the mean field and the current field (a double per face each), face masks, the
        // warm-start potential and the projection's right-hand side; the advection's arrays,
        // which the solver keeps from step to step (the field before the step, MacCormack's or
        // BFECC's passes, and for the float rows the velocity in float, one component's
        // quantity, trace starts and flags: 4 + 0.5 (4 + 12 + 1) bytes a face); then the widest
        // of the other scratch (the viscosity's CG vectors or vorticity confinement's cells).
        const double advection = faces * (8.0 * run.scratchFaceArrays + 4.0 + 0.5 * 17.0);
        const double viscosityFaces = run.viscosityFaceArrays * 8.0 * faces;
        extra += faces * (4.0 + 2 * 8.0 + 1.0) + cells * (1.0 + 3 * 8.0) +
                 PoissonSolver::estimatedBytes(nx, ny, nz) + advection +
                 std::max(viscosityFaces, cells * run.scratchCellBytes);
    }
    return domain + steady + output + extra;
}

}  // namespace gale::sim
