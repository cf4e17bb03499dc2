#pragma once
/// \file WindField.h
/// A wind field on a staggered (MAC) grid over an AirDomain's box: u on x-faces, v on y-faces,
/// w on z-faces, world axes, m/s. Layout, indices and sampling are the GridLayout's (GridLayout.h);
/// the x-face i of row (j, k) sits at world (wsMin.x + i h, wsMin.y + (j + 1/2) h, z_k + dz_k / 2)
/// (z_k = wsMin.z + k h for cubic cells).
///
/// Faces closed by the terrain hold extrapolated values (SteadyWind documents how), so sampling
/// near the ground interpolates smoothly; they carry no flux. No OpenVDB here: writeVdb is
/// implemented in VdbIO.cpp.

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "sim/GridLayout.h"
#include "sim/Heightfield.h"

namespace gale::sim {

/// Extra metadata for writeVdb: strings and numbers attached to both grids.
struct VdbMetadata {
    std::vector<std::pair<std::string, std::string>> strings;
    std::vector<std::pair<std::string, double>> numbers;
};

class WindField : public LayoutAccessors<WindField> {
  public:
    WindField() = default;
    /// An all-zero field over the cells of `layout`. `air` (cellCount() flags, i fastest) marks
    /// the cells with air.
    WindField(const GridLayout& layout, std::shared_ptr<const Heightfield> terrain,
              std::vector<uint8_t> air);
    /// The same over nx * ny * nz cubic cells of edge voxelSize_m whose cell (0, 0, 0) has its
    /// minimum corner at wsMin_m.
    WindField(int nx, int ny, int nz, double voxelSize_m, std::array<double, 3> wsMin_m,
              std::shared_ptr<const Heightfield> terrain, std::vector<uint8_t> air);

    /// The field's layout; nx(), ny(), nz(), voxelSize_m(), wsMin_m() and wsTop_m() come from
    /// LayoutAccessors.
    const GridLayout& layout() const { return mLayout; }

    /// Face velocities, m/s (sizes (nx+1)*ny*nz, nx*(ny+1)*nz, nx*ny*(nz+1)).
    std::vector<double>& u_mps() { return mU; }
    std::vector<double>& v_mps() { return mV; }
    std::vector<double>& w_mps() { return mW; }
    const std::vector<double>& u_mps() const { return mU; }
    const std::vector<double>& v_mps() const { return mV; }
    const std::vector<double>& w_mps() const { return mW; }
    double u(int i, int j, int k) const { return mU[mLayout.faceXIndex(i, j, k)]; }
    double v(int i, int j, int k) const { return mV[mLayout.faceYIndex(i, j, k)]; }
    double w(int i, int j, int k) const { return mW[mLayout.faceZIndex(i, j, k)]; }
    bool isAir(int i, int j, int k) const { return mAir[mLayout.cellIndex(i, j, k)] != 0; }

    /// Velocity at a world position (metres), m/s: each component trilinearly interpolated from
    /// its own staggered faces by GridLayout::sampleFaces (index coordinates clamped to the face
    /// grid, so within half a cell of the box sides the nearest face layer is used). Returns {0, 0,
    /// 0} outside the box and below the terrain surface (the Heightfield's bilinear h(x, y)). Const
    /// and lock-free: safe for any number of concurrent readers.
    std::array<double, 3> velocityAt_mps(double wsX_m, double wsY_m, double wsZ_m) const;
    /// velocityAt_mps without the terrain test, for a caller that has made it once for points it
    /// samples in many fields of the same geometry (coupling's grass sampler). Zero outside the
    /// box.
    std::array<double, 3> velocityAboveTerrainAt_mps(double wsX_m, double wsY_m,
                                                     double wsZ_m) const;
    /// True when the point lies below the terrain surface (never for a field without terrain).
    bool belowTerrain(double wsX_m, double wsY_m, double wsZ_m) const;
    /// Component selectors for readsOnlySolvedFaces.
    static constexpr unsigned COMPONENT_U = 1, COMPONENT_V = 2, COMPONENT_W = 4;
    static constexpr unsigned ALL_COMPONENTS = COMPONENT_U | COMPONENT_V | COMPONENT_W;
    /// True when every face that velocityAboveTerrainAt_mps reads at this world point (metres) for
    /// the selected components is solved (isSolvedFace). False outside the box, and for u or v
    /// below the lowest (above the highest) cell centre, where their interpolation holds a layer's
    /// value rather than interpolating.
    bool readsOnlySolvedFaces(double wsX_m, double wsY_m, double wsZ_m,
                              unsigned components = ALL_COMPONENTS) const;
    /// u and v interpolated at wsUV_m and w at wsW_m (world metres), m/s, each as
    /// velocityAboveTerrainAt_mps reads it: for a reader that places each component where its own
    /// faces are solved (coupling's near-ground sampler). A point outside the box gives zero for
    /// its components.
    std::array<double, 3> velocityComponentsAt_mps(const std::array<double, 3>& wsUV_m,
                                                   const std::array<double, 3>& wsW_m) const;
    /// True when face `i, j, k` of the `axis` face grid (0: u, 1: v, 2: w; layouts as u_mps etc.)
    /// carries flux: both its cells are air (a box-side face: its one cell; never the box bottom).
    bool isFlowFace(int axis, int i, int j, int k) const;
    /// True when the face carries flux and its centre lies above the terrain: its value is the
    /// flow at its centre. A cut face whose centre is under the ground carries the flux through
    /// its open sliver, a value the cut-cell solve resolves poorly as a point value (several
    /// percent off next to small cut cells; docs/coupling.md).
    bool isSolvedFace(int axis, int i, int j, int k) const;
    /// The terrain the field was solved over, or nullptr.
    const Heightfield* terrain() const { return mTerrain.get(); }

    /// What a point's place in the field depends on: cells, box and terrain. Two fields with equal
    /// geometries answer belowTerrain alike and share every interpolation stencil.
    struct Geometry {
        GridLayout layout;
        const Heightfield* terrain = nullptr;
        bool operator==(const Geometry& o) const {
            return layout == o.layout && terrain == o.terrain;
        }
        bool operator!=(const Geometry& o) const { return !(*this == o); }
    };
    Geometry geometry() const { return {mLayout, mTerrain.get()}; }

    /// Cell-centred velocity: the average of the two faces of each component, m/s.
    std::array<double, 3> cellVelocity_mps(int i, int j, int k) const {
        return {0.5 * (u(i, j, k) + u(i + 1, j, k)), 0.5 * (v(i, j, k) + v(i, j + 1, k)),
                0.5 * (w(i, j, k) + w(i, j, k + 1))};
    }

    /// Writes the field as an OpenVDB file: a Vec3s grid "velocity" (cell-centred averages of the
    /// face velocities, world axes, m/s; GRID_UNKNOWN, VEC_CONTRAVARIANT_RELATIVE, not staggered;
    /// voxel (i, j, k) is cell (i, j, k), its centre at world wsMin + (i+1/2, j+1/2, k+1/2) h),
    /// a float grid "speed" (|velocity|, m/s), both active on air cells only, and a staggered
    /// Vec3s grid "velocity_faces" (the face velocities themselves, GRID_STAGGERED; OpenVDB's
    /// StaggeredBoxSampler reads it as velocityAt_mps does; see VdbIO.h). Stretched layers: a
    /// cubic resample for the first two and "velocity_layers" with "z_levels_m" metadata instead
    /// of "velocity_faces" (VdbIO.h). With tke_m2ps2 (one value per cell, the momentum model's
    /// k, m^2/s^2) also a float grid "tke" (stretched layers: "tke_layers"; sim::tkeGrid). Atomic:
    /// written to a temporary name in the same folder, then renamed. Throws std::runtime_error on
    /// I/O failure, std::invalid_argument when tke_m2ps2 is neither empty nor one per cell.
    void writeVdb(const std::string& path, const VdbMetadata& metadata = {},
                  const std::vector<double>& tke_m2ps2 = {}) const;

  private:
    GridLayout mLayout;
    std::shared_ptr<const Heightfield> mTerrain;
    std::vector<uint8_t> mAir;
    std::vector<double> mU, mV, mW;
};

}  // namespace gale::sim
