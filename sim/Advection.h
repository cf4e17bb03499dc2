#pragma once
/// \file Advection.h
/// Advection on the staggered (MAC) grid of the wind solvers (docs/unsteady.md, "Method").
///
/// Layout. A MacGrid is the AirDomain's box: nx * ny * nz cubic cells of edge h, cell (0, 0, 0)
/// with its minimum corner at wsMin. Values live at four placements (Placement): u on x-faces at
/// wsMin + (i, j + 1/2, k + 1/2) h, v on y-faces, w on z-faces, scalars at cell centres; arrays in
/// PoissonSystem's layout (i fastest). Index space: cell (i, j, k) spans [i, i+1] x [j, j+1] x
/// [k, k+1]. The conversion world metres -> index cells happens in one place only,
/// MacGrid::isFromWs (so a trace moves by u dt metres = u dt / h cells, never by u dt cells).
///
/// Schemes (AdvectionScheme):
///  - SemiLagrangian: Stam 1999 ("Stable fluids"), with a second-order (explicit midpoint, RK2)
///    backward trace through the frozen velocity and trilinear interpolation. Unconditionally
///    stable: each new value is a convex combination of old ones.
///
/// Traces (every scheme). A trace is split into substeps of at most MAX_TRACE_CELLS_PER_SUBSTEP
/// cells each (the substep length follows the local speed, so a trace at CFL 50 follows the
/// streamline through ~25 midpoint steps instead of jumping 50 cells in one), and, when the grid
/// names its terrain (MacGrid::terrain), a trace that crosses from above the terrain surface to
/// below it stops on the surface (the crossing found by bisection along the substep): air next to
/// the ground is never read from inside the rock. A trace that leaves the box finishes its
/// remaining time in one midpoint step through the far field.
///  - MacCormack: Selle, Fedkiw, Kim, Liu, Osher 2008 ("An unconditionally stable MacCormack
///    method"): forward and backward semi-Lagrangian passes, phi = phi_f + (phi - phi_b) / 2,
///    clamped to the min/max of the 8 interpolation neighbours of the forward departure point
///    (their limiter, so the scheme stays bounded).
///  - Bfecc: Kim, Liu, Llamas, Rossignac 2005 (back and forth error compensation and correction):
///    phi' = phi + (phi - phi_b) / 2 advected forward once more, clamped the same way.
///
/// Outside the box (x, y sides and the top) the caller supplies the far field (FarField): a trace
/// that leaves the box reads the state of the air that enters through that side (the unsteady
/// solver's inflow: the mean flow plus the gusts). Below the top and inside the x, y extent the
/// interpolation clamps to the grid of each placement.

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "sim/Heightfield.h"

namespace gale::sim {

enum class AdvectionScheme { SemiLagrangian, MacCormack, Bfecc };

/// "semi_lagrangian", "maccormack", "bfecc" and back; fromName throws std::invalid_argument
/// listing the valid names.
const char* advectionSchemeName(AdvectionScheme scheme);
AdvectionScheme advectionSchemeFromName(const std::string& name);

/// Where on the cell a value lives.
enum class Placement { FaceX = 0, FaceY = 1, FaceZ = 2, Cell = 3 };

using Vec3d = std::array<double, 3>;

/// Longest substep of a trace, in cells of travel (issue: at most 1-2 cells per substep).
constexpr double MAX_TRACE_CELLS_PER_SUBSTEP = 2.0;

struct MacGrid {
    int nx = 0, ny = 0, nz = 0;
    double voxelSize_m = 1.0;  ///< h, metres
    Vec3d wsMin_m{};           ///< world position of the minimum corner of cell (0, 0, 0)
    /// The terrain surface traces stop at (world metres, not owned; must outlive the grid's
    /// users). nullptr: no terrain, traces run their full time.
    const Heightfield* terrain = nullptr;

    /// A length in metres as a length in cells: l / h. The only metres-to-cells conversion;
    /// isFromWs and the advection's traces go through it.
    double cellsFromMetres(double l_m) const { return l_m / voxelSize_m; }
    /// World metres -> index space (cells): (ws - wsMin) / h.
    Vec3d isFromWs(const Vec3d& ws) const {
        return {cellsFromMetres(ws[0] - wsMin_m[0]), cellsFromMetres(ws[1] - wsMin_m[1]),
                cellsFromMetres(ws[2] - wsMin_m[2])};
    }
    /// Index space -> world metres.
    Vec3d wsFromIs(const Vec3d& is) const {
        return {wsMin_m[0] + is[0] * voxelSize_m, wsMin_m[1] + is[1] * voxelSize_m,
                wsMin_m[2] + is[2] * voxelSize_m};
    }
    /// Samples along x, y, z of a placement (faces: one more along their axis).
    std::array<int, 3> dims(Placement p) const {
        return {nx + (p == Placement::FaceX), ny + (p == Placement::FaceY),
                nz + (p == Placement::FaceZ)};
    }
    size_t count(Placement p) const {
        const auto d = dims(p);
        return size_t(d[0]) * d[1] * d[2];
    }
    /// World position of sample (i, j, k) of placement p, metres.
    Vec3d wsPosition(Placement p, int i, int j, int k) const {
        return wsFromIs({i + (p == Placement::FaceX ? 0.0 : 0.5),
                         j + (p == Placement::FaceY ? 0.0 : 0.5),
                         k + (p == Placement::FaceZ ? 0.0 : 0.5)});
    }
    /// True if a world point lies outside the box through an x or y side or the top (the bottom
    /// lies under the terrain and clamps instead).
    bool outside(const Vec3d& ws) const {
        const Vec3d is = isFromWs(ws);
        return !(is[0] >= 0.0 && is[0] <= nx && is[1] >= 0.0 && is[1] <= ny && is[2] <= nz);
    }
};

/// The MAC velocity arrays (m/s) a trace follows; not owned.
struct MacVelocity {
    const std::vector<double>* u = nullptr;
    const std::vector<double>* v = nullptr;
    const std::vector<double>* w = nullptr;
};

/// The state outside the box at a world position: velocity in m/s (world axes).
using FarField = std::function<Vec3d(const Vec3d& wsPos_m)>;

/// Trilinear sample of q (placement p) at a world position, index coordinates clamped to the
/// placement's grid. If lo/hi are given they receive the min/max of the 8 values used.
double sampleAt(const MacGrid& g, Placement p, const std::vector<double>& q, const Vec3d& wsPos_m,
                double* lo = nullptr, double* hi = nullptr);

/// Velocity at a world position, m/s: the far field outside the box, else each component
/// trilinearly from its own faces.
Vec3d velocityAt(const MacGrid& g, const MacVelocity& vel, const FarField& far,
                 const Vec3d& wsPos_m);

/// Departure point of the particle that reaches wsPos_m after dt_s seconds (dt_s < 0: the forward
/// arrival point), by explicit midpoint substeps through the frozen velocity,
///   x_mid = x - s/2 u(x),  x_next = x - s u(x_mid),
/// each substep s at most MAX_TRACE_CELLS_PER_SUBSTEP cells long; stopped on the terrain surface
/// (g.terrain) when it crosses it from above. Metres in, metres out.
Vec3d traceBack(const MacGrid& g, const MacVelocity& vel, const FarField& far, const Vec3d& wsPos_m,
                double dt_s);

/// Value of the advected quantity outside the box at a world position (same units as q).
using OutsideValue = std::function<double(const Vec3d& wsPos_m)>;

/// Advects q (placement p) through the frozen velocity over dt_s seconds with `scheme` and writes
/// the result to `out` (resized). Samples with mask[idx] == 0 (if mask is given) are copied
/// unchanged. `outside` gives q where a trace leaves the box (empty: clamp to the box).
/// Multithreaded (TBB). Throws std::invalid_argument on wrong sizes.
void advect(const MacGrid& g, Placement p, const std::vector<double>& q, const MacVelocity& vel,
            const FarField& far, const OutsideValue& outside, double dt_s, AdvectionScheme scheme,
            std::vector<double>& out, const std::vector<uint8_t>* mask = nullptr);

}  // namespace gale::sim
