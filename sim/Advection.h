#pragma once
/// \file Advection.h
/// Advection on the staggered (MAC) grid of the wind solvers (docs/unsteady.md, "Method").
///
/// Layout. A MacGrid is the AirDomain's GridLayout (GridLayout.h: cells, the four placements of
/// MAC values, index space, the one staggered sampler) plus the terrain traces stop at. Traces
/// run in world metres (a trace moves by u dt metres) and read values through the layout's
/// sampler at GridLayout::isFromWs of each point, so stretched layers (level heights that grow
/// upwards) are read like cubic ones: the sampler's vertical weights come from the world heights
/// of the samples. A layout of cubic cells takes a fast lattice instead (UniformLattice.h: the
/// same interpolation and clamping without the per-sample layout branches), equal to the general
/// path to round-off; the choice is made once per advect() or traceBack() call.
///
/// Schemes (AdvectionScheme):
///  - SemiLagrangian: Stam 1999 ("Stable fluids"), with a second-order (explicit midpoint, RK2)
///    backward trace through the frozen velocity and trilinear interpolation. Unconditionally
///    stable: each new value is a convex combination of old ones.
///
/// Traces (every scheme). A trace is split into substeps of at most MAX_TRACE_CELLS_PER_SUBSTEP
/// cells each along every axis (horizontal cells of h, vertical ones of the local layer's
/// thickness; the substep length follows the local speed, so a trace at CFL 50 follows the
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
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "sim/GridLayout.h"
#include "sim/Heightfield.h"

namespace gale::sim {

enum class AdvectionScheme { SemiLagrangian, MacCormack, Bfecc };

/// The arithmetic of the traces and samples on cubic cells (docs/unsteady.md, "Single precision
/// and rows"). Double: the general path in double. Single: each placement's x rows as SIMD
/// lanes in float (sim/AdvectionRows.h), the samples a one-substep trace does not cover (longer
/// traces, the box sides, the terrain) redone on the general path; the result is rounded to
/// float, the limiter in double. Stretched layers always take the general path.
enum class AdvectionPrecision { Double, Single };

/// "double", "single" and back; fromName throws gale::ParameterError (unsteady.precision).
const char* advectionPrecisionName(AdvectionPrecision precision);
AdvectionPrecision advectionPrecisionFromName(const std::string& name);

/// "semi_lagrangian", "maccormack", "bfecc" and back; fromName throws gale::ParameterError
/// (unsteady.advection) listing the valid names.
const char* advectionSchemeName(AdvectionScheme scheme);
AdvectionScheme advectionSchemeFromName(const std::string& name);

/// Longest substep of a trace, in cells of travel (issue: at most 1-2 cells per substep).
constexpr double MAX_TRACE_CELLS_PER_SUBSTEP = 2.0;

struct MacGrid : GridLayout {
    /// The terrain surface traces stop at (world metres, not owned; must outlive the grid's
    /// users). nullptr: no terrain, traces run their full time.
    const Heightfield* terrain = nullptr;

    MacGrid() = default;
    /// nx * ny * nz cubic cells of edge voxelSize (metres), cell (0, 0, 0) with its minimum
    /// corner at wsMin.
    MacGrid(int nxCells, int nyCells, int nzCells, double voxelSize, const Vec3d& wsMin,
            const Heightfield* ground = nullptr)
        : GridLayout(nxCells, nyCells, nzCells, voxelSize, wsMin), terrain(ground) {
        noteTerrainTop();
    }
    MacGrid(const GridLayout& layout, const Heightfield* ground)
        : GridLayout(layout), terrain(ground) {
        noteTerrainTop();
    }

    /// The terrain's highest point, world metres (-inf without terrain): traces above it skip
    /// the ground's sampling. Worked out when the grid is made; a grid whose terrain is set
    /// afterwards works it out on every call.
    double terrainTop_m() const {
        if (!terrain) return -HUGE_VAL;
        return terrain == mTopOf ? mTerrainTop_m : terrain->maxHeight_m();
    }

    /// True if a world point lies outside the box through an x or y side or the top (the bottom
    /// lies under the terrain and clamps instead).
    bool outside(const Vec3d& ws) const {
        const Vec3d is = isFromWs(ws);
        return !(is[0] >= 0.0 && is[0] <= nx && is[1] >= 0.0 && is[1] <= ny && is[2] <= nz);
    }

  private:
    void noteTerrainTop() {
        mTopOf = terrain;
        mTerrainTop_m = terrain ? terrain->maxHeight_m() : -HUGE_VAL;
    }
    const Heightfield* mTopOf = nullptr;  ///< the terrain mTerrainTop_m belongs to
    double mTerrainTop_m = -HUGE_VAL;
};

/// The MAC velocity arrays (m/s) a trace follows; not owned.
struct MacVelocity {
    const std::vector<double>* u = nullptr;
    const std::vector<double>* v = nullptr;
    const std::vector<double>* w = nullptr;
    /// Optional: u, v, w rounded to float, for AdvectionPrecision::Single, which otherwise rounds
    /// them on every call (a caller advecting three components through one velocity rounds it
    /// once). All three or none; the same values as u, v, w.
    const std::vector<float>* uSingle = nullptr;
    const std::vector<float>* vSingle = nullptr;
    const std::vector<float>* wSingle = nullptr;
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

/// Working arrays of advect(), kept by a caller that advects again and again (the unsteady
/// solver: three components of about one size every step, where fresh vectors would be zeroed and
/// faulted in each time). Every pass writes what it reads of them; one call at a time.
struct AdvectionScratch {
    std::vector<double> forward, backward, low, high, corrected;  ///< the schemes' passes
    std::vector<float> quantity, starts;  ///< the float rows' quantity and trace starts
    std::vector<uint8_t> general;         ///< the samples the rows leave to the double path
};

/// Advects q (placement p) through the frozen velocity over dt_s seconds with `scheme` and writes
/// the result to `out` (resized). Samples with mask[idx] == 0 (if mask is given) are copied
/// unchanged. `outside` gives q where a trace leaves the box (empty: clamp to the box). Each
/// sample's trace starts at its world position (GridLayout::wsPosition). Multithreaded (TBB).
/// `precision` chooses the arithmetic on cubic cells (AdvectionPrecision). `scratch`: working
/// arrays to reuse (none: the call makes its own).
/// Throws std::logic_error on wrong sizes (a caller's bug).
void advect(const MacGrid& g, Placement p, const std::vector<double>& q, const MacVelocity& vel,
            const FarField& far, const OutsideValue& outside, double dt_s, AdvectionScheme scheme,
            std::vector<double>& out, const std::vector<uint8_t>* mask = nullptr,
            AdvectionPrecision precision = AdvectionPrecision::Double,
            AdvectionScratch* scratch = nullptr);

}  // namespace gale::sim
