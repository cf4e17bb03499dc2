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

#include "sim/Heightfield.h"
#include "sim/MemoryEstimate.h"

namespace gale::sim {

struct DomainSpec {
    double voxelSize_m = 2.0;          ///< cell edge (cubic cells), metres, > 0
    std::optional<double> top_m;       ///< world z of the open top boundary; unset: automatic
    double memoryLimit_bytes = 4.0e9;  ///< refuse domains whose estimate exceeds this, > 0
    /// true: cut cells (open fractions in [0, 1]); false: stair-steps, every fraction rounded to
    /// 0 or 1 at 1/2 (for comparisons: first-order boundary, docs/solver.md).
    bool cutCells = true;
    /// true: the estimate also counts the momentum model's arrays (sim/MomentumWind.h).
    bool momentumModel = false;
    /// The rest of the run the estimate and limit count: an unsteady run's arrays and the
    /// process's resident bytes before the domain (sim/MemoryEstimate.h).
    RunMemory run = {};
};

class AirDomain {
  public:
    /// Automatic top: this many terrain reliefs above the highest point...
    static constexpr double AUTO_TOP_RELIEF_FACTOR = 3.0;
    /// ...but at least this many cells (flat terrain has no relief).
    static constexpr int AUTO_TOP_MIN_CELLS = 8;
    /// Sub-samples per cell edge when integrating open fractions.
    static constexpr int FRACTION_SUBSAMPLES = 8;
    /// Open fractions below this are closed.
    static constexpr float MIN_OPEN_FRACTION = 1e-3f;

    /// Builds the domain. Throws std::invalid_argument naming the parameter when the terrain has a
    /// NaN/Inf height or a bad size/spacing, voxelSize_m is not > 0 and finite or is larger than
    /// the terrain, top_m is not above the highest point (no air), memoryLimit_bytes is not > 0,
    /// or the memory estimate exceeds memoryLimit_bytes (checked before allocating).
    AirDomain(const Heightfield& terrain, const DomainSpec& spec);
    ~AirDomain();
    AirDomain(AirDomain&&) noexcept;
    AirDomain& operator=(AirDomain&&) noexcept;

    int nx() const { return mNx; }
    int ny() const { return mNy; }
    int nz() const { return mNz; }
    double voxelSize_m() const { return mVoxelSize_m; }
    /// World position of the minimum corner of cell (0, 0, 0), metres.
    std::array<double, 3> wsMin_m() const { return mWsMin_m; }
    /// World z of the top boundary (after rounding to whole cells), metres.
    double wsTop_m() const { return mWsMin_m[2] + mNz * mVoxelSize_m; }

    size_t boxCellCount() const { return size_t(mNx) * mNy * mNz; }
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

    /// Open fraction of the x-face between cells (i-1, j, k) and (i, j, k), i in [0, nx].
    float openFractionX(int i, int j, int k) const {
        return mOpenX[size_t(i) + size_t(mNx + 1) * (j + size_t(mNy) * k)];
    }
    /// Open fraction of the y-face between cells (i, j-1, k) and (i, j, k), j in [0, ny].
    float openFractionY(int i, int j, int k) const {
        return mOpenY[size_t(i) + size_t(mNx) * (j + size_t(mNy + 1) * k)];
    }
    /// Open fraction of the z-face between cells (i, j, k-1) and (i, j, k), k in [0, nz].
    float openFractionZ(int i, int j, int k) const {
        return mOpenZ[size_t(i) + size_t(mNx) * (j + size_t(mNy) * k)];
    }
    /// Face arrays in PoissonSystem's layout (PoissonSystem::faceXIndex etc.).
    const std::vector<float>& openFractionsX() const { return mOpenX; }
    const std::vector<float>& openFractionsY() const { return mOpenY; }
    const std::vector<float>& openFractionsZ() const { return mOpenZ; }

    /// Net flux out of cell (i, j, k) through its open faces, per unit face area, m/s: the sum of
    /// open fraction x face velocity, outward positive, of face arrays U, V, W in this layout
    /// (WindField's). Times h^2 it is the cell's volume outflow; zero for a discretely
    /// divergence-free field. Inline: the solvers evaluate it per cell per step.
    double openOutflux(const std::vector<double>& U, const std::vector<double>& V,
                       const std::vector<double>& W, int i, int j, int k) const {
        const size_t xm = size_t(i) + size_t(mNx + 1) * (j + size_t(mNy) * k), xp = xm + 1;
        const size_t ym = size_t(i) + size_t(mNx) * (j + size_t(mNy + 1) * k),
                     yp = ym + size_t(mNx);
        const size_t zm = size_t(i) + size_t(mNx) * (j + size_t(mNy) * k),
                     zp = zm + size_t(mNx) * mNy;
        return mOpenX[xp] * U[xp] - mOpenX[xm] * U[xm] + mOpenY[yp] * V[yp] - mOpenY[ym] * V[ym] +
               mOpenZ[zp] * W[zp] - mOpenZ[zm] * W[zm];
    }

    /// True if cell (i, j, k) holds air (an unknown of the solve).
    bool isAir(int i, int j, int k) const { return mAir[cellIndex(i, j, k)] != 0; }
    const std::vector<uint8_t>& airFlags() const { return mAir; }
    size_t cellIndex(int i, int j, int k) const {
        return size_t(i) + size_t(mNx) * (j + size_t(mNy) * k);
    }

    const Heightfield& terrain() const { return *mTerrain; }
    std::shared_ptr<const Heightfield> terrainShared() const { return mTerrain; }

    struct Vdb;  ///< the OpenVDB mask (defined in AirDomain.cpp; see VdbIO.h)
    const Vdb& vdb() const { return *mVdb; }

  private:
    int mNx = 0, mNy = 0, mNz = 0;
    double mVoxelSize_m = 0;
    std::array<double, 3> mWsMin_m{};
    size_t mActiveCount = 0;
    size_t mMemoryEstimate_bytes = 0;
    std::vector<float> mOpenX, mOpenY, mOpenZ;
    std::vector<uint8_t> mAir;
    std::shared_ptr<const Heightfield> mTerrain;
    std::shared_ptr<Vdb> mVdb;
};

}  // namespace gale::sim
