#pragma once
/// \file AirDomain.h
/// The air above a heightfield terrain, discretised into cubic cells for the wind solvers.
///
/// Geometry. The domain is the box [wsMin.x, wsMin.x + nx h] x [wsMin.y, wsMin.y + ny h] x
/// [wsMin.z, wsTop] with h = voxelSize_m. x and y cover the heightfield's extent (rounded down to
/// whole cells); wsMin.z = floor(min height / h) * h, so no cell lies wholly below the lowest
/// point; the top is DomainSpec::top_m or, by default,
///   max height + max(AUTO_TOP_RELIEF_FACTOR * relief, AUTO_TOP_MIN_CELLS * h),
/// rounded up to whole cells.
///
/// Stretched layers (DomainSpec::firstCell_m set): the horizontal cells keep their edge h, the
/// layers (shared by every column, a tensor-product grid) start firstCell_m thick at
/// wsMin.z = floor(min height / firstCell_m) * firstCell_m and grow by stretchRatio per layer up to
/// maxCell_m; the top is rounded up to the next level (GridLayout holds the level heights).
///
/// Cut cells (Batty, Bertails, Bridson 2007; Ng, Min, Gibou 2009). Every cell face carries an open
/// fraction in [0, 1], the fraction of its area above the terrain h(x, y) (the Heightfield's
/// bilinear surface). Vertical faces: the exact integral of clamp(z_top - h, 0, dz) along the face
/// for h piecewise linear between FRACTION_SUBSAMPLES sub-samples. Horizontal faces: the area where
/// h < z_face, exact along FRACTION_SUBSAMPLES rows of sub-samples, midpoint rule across rows.
/// Fractions below MIN_OPEN_FRACTION are closed (tiny slivers make the system ill-conditioned and
/// carry no flux worth keeping). A cell is air iff its top face is open; every face touching a
/// non-air cell is closed, and the bottom of the box is closed (it lies under the terrain).
///
/// Storage. The topology lives in an OpenVDB BoolGrid (active voxel = air cell; voxel (i, j, k)
/// is cell (i, j, k), see VdbIO.h for the transform). The solver works on dense arrays over the
/// box (cells under the terrain are present but inactive): memory and time scale with the box,
/// not with the air count. The memory estimate counts that honestly and is checked against
/// DomainSpec::memoryLimit_bytes before anything is allocated.
///
/// No OpenVDB types in this header: sim/VdbIO.h gives access to the grid.

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "sim/GridLayout.h"
#include "sim/Heightfield.h"
#include "sim/MemoryEstimate.h"

namespace gale::sim {

struct DomainSpec {
    double voxelSize_m = 1.0;     ///< cell edge (cubic cells), metres, > 0
    std::optional<double> top_m;  ///< world z of the open top boundary; unset: automatic
    /// Refuse domains whose estimate exceeds this, bytes, > 0 (the scene's 4096 MiB).
    double memoryLimit_bytes = 4096.0 * 1024.0 * 1024.0;
    /// true: cut cells (open fractions in [0, 1]); false: stair-steps, every fraction rounded to
    /// 0 or 1 at 1/2 (for comparisons: first-order boundary, docs/solver.md).
    bool cutCells = true;
    /// true: the estimate also counts the momentum model's arrays (sim/MomentumWind.h).
    bool momentumModel = false;
    /// Stretched layers (docs/solver.md, "Stretched layers"): thickness of the lowest layer,
    /// metres, in [voxelSize_m / 5, voxelSize_m]. Unset: cubic cells.
    std::optional<double> firstCell_m{};
    /// Stretched layers: each layer is this many times thicker than the one below, [1, 1.2].
    double stretchRatio = 1.2;
    /// Stretched layers: the largest layer thickness, metres, in [firstCell_m, 2 voxelSize_m].
    /// Unset: AirDomain::MAX_LAYER_THICKENING voxelSize_m.
    std::optional<double> maxCell_m{};
    /// The rest of the run the estimate and limit count: an unsteady run's arrays and the
    /// process's resident bytes before the domain (sim/MemoryEstimate.h).
    RunMemory run = {};
    /// true: the two sides of constant y (the box's y = min and y = max planes) are free-slip
    /// walls (no flow through them, no potential prescribed on them) instead of open: the
    /// symmetry planes of a two-dimensional case a few cells across, such as a wind tunnel's
    /// ridge with the wind along x. Open sides there would let the flow go round the ridge
    /// sideways (docs/validation.md, section 3). No scene key sets it.
    bool closedSidesY = false;
};

class AirDomain : public LayoutAccessors<AirDomain> {
  public:
    /// Automatic top: this many terrain reliefs above the highest point...
    static constexpr double AUTO_TOP_RELIEF_FACTOR = 3.0;
    /// ...but at least this many cells (flat terrain has no relief).
    static constexpr int AUTO_TOP_MIN_CELLS = 8;
    /// Sub-samples per cell edge when integrating open fractions.
    static constexpr int FRACTION_SUBSAMPLES = 8;
    /// Open fractions below this are closed.
    static constexpr float MIN_OPEN_FRACTION = 1e-3f;
    /// Stretched layers: the thinnest first layer is voxelSize_m / MAX_FIRST_CELL_THINNING (the
    /// z-line smoother keeps the iterations flat there, docs/solver.md).
    static constexpr double MAX_FIRST_CELL_THINNING = 5.0;
    /// Stretched layers: the thickest layer is MAX_LAYER_THICKENING voxelSize_m. Thicker layers
    /// make the horizontal couplings dominate, which z-lines do not smooth: at 4 voxels the
    /// hemisphere's iterations grew 9, 16, 23 as the cells halved; at 2 they stay 9, 11, 11.
    static constexpr double MAX_LAYER_THICKENING = 2.0;
    /// Stretched layers: the largest growth ratio from one layer to the next.
    static constexpr double MAX_STRETCH_RATIO = 1.2;

    /// Builds the domain. Throws gale::ParameterError naming the scene key: terrain.spacing_m
    /// when not > 0 and finite; solver.voxel_size_m when not > 0 and finite or larger than the
    /// terrain; solver.top_m when not above the highest point (no air); solver.memory_limit_mb
    /// when not > 0 or below the memory estimate (checked before allocating);
    /// solver.first_cell_m, solver.stretch_ratio or solver.max_cell_m outside their ranges.
    /// Throws std::invalid_argument (bad terrain data) for a NaN/Inf height or
    /// origin or fewer than 2x2 samples, std::logic_error when height_m is not nx * ny long.
    AirDomain(const Heightfield& terrain, const DomainSpec& spec);
    ~AirDomain();
    AirDomain(AirDomain&&) noexcept;
    AirDomain& operator=(AirDomain&&) noexcept;

    /// The box's layout (cells, faces, world <-> index): the one shared with the Poisson system,
    /// the wind field and advection.
    /// nx(), ny(), nz(), voxelSize_m(), wsMin_m() and wsTop_m() come from LayoutAccessors.
    const GridLayout& layout() const { return mLayout; }

    size_t boxCellCount() const { return mLayout.cellCount(); }
    size_t activeCellCount() const { return mActiveCount; }
    /// Estimated peak resident bytes of the run on this domain (made before allocating): the
    /// process's baseline plus every array of the solve (DomainSpec::run, sim/MemoryEstimate.h).
    size_t memoryEstimate_bytes() const { return mMemoryEstimate_bytes; }
    /// Bytes this object holds (open fractions, flags, OpenVDB mask).
    size_t memory_bytes() const;
    /// Bytes of the OpenVDB air mask alone (Grid::memUsage).
    size_t vdbMemory_bytes() const;

    /// Estimated peak bytes of the arrays of a steady solve on a box of nx * ny * nz cells
    /// (momentum: of the momentum model, which adds MOMENTUM_EXTRA_BYTES_PER_CELL), without the
    /// terrain copy or the process baseline (sim/MemoryEstimate.h).
    static double estimateSolveMemory_bytes(int nx, int ny, int nz, bool momentum = false);
    /// Estimated peak bytes of a steady solve on `layout`: estimateSolveMemory_bytes over its
    /// cells, plus, for stretched layers, the cubic resample of the standard .vdb grids (nx * ny
    /// cells of voxelSize_m up to the top, RESAMPLE_BYTES_PER_VOXEL each; docs/solver.md).
    static double estimateSolveMemory_bytes(const GridLayout& layout, bool momentum = false);
    /// Bytes per voxel of the cubic resample written for stretched layers: the velocity (12 B)
    /// and speed (4 B) grids, as for cubic cells.
    static constexpr double RESAMPLE_BYTES_PER_VOXEL = 16.0;
    /// Level heights (world z, metres) of stretched layers from z0: the first layer firstCell_m
    /// thick, each next one ratio times the one below, capped at maxCell_m, up to the first level
    /// at or above top_m. Arguments as validated by the constructor.
    static std::vector<double> stretchedLevels_m(double z0_m, double top_m, double firstCell_m,
                                                 double ratio, double maxCell_m);

    /// Open fraction of the x-face between cells (i-1, j, k) and (i, j, k), i in [0, nx].
    float openFractionX(int i, int j, int k) const { return mOpenX[mLayout.faceXIndex(i, j, k)]; }
    /// Open fraction of the y-face between cells (i, j-1, k) and (i, j, k), j in [0, ny].
    float openFractionY(int i, int j, int k) const { return mOpenY[mLayout.faceYIndex(i, j, k)]; }
    /// Open fraction of the z-face between cells (i, j, k-1) and (i, j, k), k in [0, nz].
    float openFractionZ(int i, int j, int k) const { return mOpenZ[mLayout.faceZIndex(i, j, k)]; }
    /// Face arrays in PoissonSystem's layout (PoissonSystem::faceXIndex etc.).
    const std::vector<float>& openFractionsX() const { return mOpenX; }
    const std::vector<float>& openFractionsY() const { return mOpenY; }
    const std::vector<float>& openFractionsZ() const { return mOpenZ; }

    /// Net flux out of cell (i, j, k) through its open faces divided by h^2 (h = voxelSize_m),
    /// m/s: the sum of open fraction x face velocity x face area / h^2, outward positive, of face
    /// arrays U, V, W in this layout (WindField's); side faces have area h dz_k (h^2 for cubic
    /// cells), z-faces h^2. Times h^2 it is the cell's volume outflow; zero for a discretely
    /// divergence-free field. Inline: the solvers evaluate it per cell per step.
    double openOutflux(const std::vector<double>& U, const std::vector<double>& V,
                       const std::vector<double>& W, int i, int j, int k) const {
        const GridLayout& g = mLayout;
        const size_t xm = g.faceXIndex(i, j, k), xp = g.faceXIndex(i + 1, j, k);
        const size_t ym = g.faceYIndex(i, j, k), yp = g.faceYIndex(i, j + 1, k);
        const size_t zm = g.faceZIndex(i, j, k), zp = g.faceZIndex(i, j, k + 1);
        const double side =
            mOpenX[xp] * U[xp] - mOpenX[xm] * U[xm] + mOpenY[yp] * V[yp] - mOpenY[ym] * V[ym];
        return (g.uniformZ() ? side : side * (g.dz_m(k) / g.voxelSize_m)) + mOpenZ[zp] * W[zp] -
               mOpenZ[zm] * W[zm];
    }

    /// openOutflux of every cell of row (j, k) into out[0, nx), solid cells too (the caller masks
    /// them): the same expression term for term, in a loop the compiler vectorises.
    void openOutfluxRow(const std::vector<double>& U, const std::vector<double>& V,
                        const std::vector<double>& W, int j, int k, double* out) const;

    /// True if cell (i, j, k) holds air (an unknown of the solve).
    bool isAir(int i, int j, int k) const { return mAir[cellIndex(i, j, k)] != 0; }
    const std::vector<uint8_t>& airFlags() const { return mAir; }
    size_t cellIndex(int i, int j, int k) const { return mLayout.cellIndex(i, j, k); }

    const Heightfield& terrain() const { return *mTerrain; }
    /// DomainSpec::closedSidesY: the y sides are free-slip walls.
    bool closedSidesY() const { return mClosedSidesY; }
    std::shared_ptr<const Heightfield> terrainShared() const { return mTerrain; }

    struct Vdb;  ///< the OpenVDB mask (defined in AirDomain.cpp; see VdbIO.h)
    const Vdb& vdb() const { return *mVdb; }

  private:
    GridLayout mLayout;
    size_t mActiveCount = 0;
    size_t mMemoryEstimate_bytes = 0;
    std::vector<float> mOpenX, mOpenY, mOpenZ;
    std::vector<uint8_t> mAir;
    std::shared_ptr<const Heightfield> mTerrain;
    std::shared_ptr<Vdb> mVdb;
    bool mClosedSidesY = false;
};

}  // namespace gale::sim
