#pragma once
/// \file GridLayout.h
/// The one grid layout of gale's solvers: the box of cells the air domain, the Poisson system,
/// the wind field and advection share, its cell and face indices, world <-> index conversion and
/// the one staggered (MAC) sampler.
///
/// Cells. nx * ny * nz cells; cell (i, j, k) spans [wsMin.x + i h, wsMin.x + (i+1) h] x
/// [wsMin.y + j h, ...] horizontally (h = voxelSize_m, the same along x and y) and
/// [z_k, z_{k+1}] vertically, where z_0 = wsMin.z < z_1 < ... < z_nz are the level heights
/// (world z of the horizontal faces, metres). A uniform layout has z_k = wsMin.z + k h (cubic
/// cells); a stretched one carries its own levels (thin at the ground, growing upwards).
///
/// Arrays (i fastest). Cells: i + nx (j + ny k). The four placements (Placement) of MAC values:
/// u on x-faces (nx+1) * ny * nz, face (i, j, k) between cells (i-1, j, k) and (i, j, k);
/// v on y-faces nx * (ny+1) * nz; w on z-faces nx * ny * (nz+1), face k at height z_k; scalars
/// at cell centres. GridIndex::index is the only place these formulas are written (and
/// GridIndex::column the one for 2-D arrays of one value per column).
///
/// Index space. Continuous coordinates in which cell (i, j, k) spans [i, i+1] x [j, j+1] x
/// [k, k+1]. Horizontally is = (ws - wsMin) / h; vertically is = k + (z - z_k) / (z_{k+1} - z_k)
/// inside layer k (linear within each layer; extended linearly below z_0 and above z_nz with the
/// end layers' thickness). GridLayout::isFromWs and wsFromIs are the only conversions.
///
/// Sampling (GridLayout::sample). Each placement is interpolated trilinearly in world space
/// between its own samples: along its own axis between faces, across it between cell centres.
/// With stretched levels the vertical weights come from the world heights of the samples, so a
/// field linear in world z is reproduced exactly on the faces and between them. Index coordinates
/// are clamped to each placement's lattice: within half a cell of a box side the nearest sample
/// layer is held.

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "sim/Interpolation.h"

namespace gale::sim {

using Vec3d = std::array<double, 3>;

/// Where on the cell a value lives.
enum class Placement { FaceX = 0, FaceY = 1, FaceZ = 2, Cell = 3 };

/// Cell and face indices of a box of nx * ny * nz cells (no geometry).
struct GridIndex {
    int nx = 0, ny = 0, nz = 0;  ///< cells along x, y, z

    /// Samples along x, y, z of a placement (faces: one more along their own axis).
    std::array<int, 3> dims(Placement p) const {
        return {nx + (p == Placement::FaceX), ny + (p == Placement::FaceY),
                nz + (p == Placement::FaceZ)};
    }
    size_t count(Placement p) const {
        const auto d = dims(p);
        return size_t(d[0]) * d[1] * d[2];
    }
    /// Index of sample (i, j, k) of placement p in its array: i fastest. The one face-index
    /// formula of the project.
    size_t index(Placement p, int i, int j, int k) const {
        const auto d = dims(p);
        return size_t(i) + size_t(d[0]) * (size_t(j) + size_t(d[1]) * size_t(k));
    }
    /// Values in a 2-D array of one value per column (i, j) of placement p: dims(p)[0] *
    /// dims(p)[1] (Cell and FaceZ share nx * ny columns).
    size_t columnCount(Placement p) const {
        const auto d = dims(p);
        return size_t(d[0]) * size_t(d[1]);
    }
    /// Index of column (i, j) of placement p in such a 2-D array: i fastest. The face-index
    /// formula without its level.
    size_t column(Placement p, int i, int j) const {
        return size_t(i) + size_t(dims(p)[0]) * size_t(j);
    }
    size_t cellCount() const { return count(Placement::Cell); }
    /// Cell (i, j, k), i in [0, nx).
    size_t cellIndex(int i, int j, int k) const { return index(Placement::Cell, i, j, k); }
    /// x-face i between cells i-1 and i, i in [0, nx].
    size_t faceXIndex(int i, int j, int k) const { return index(Placement::FaceX, i, j, k); }
    /// y-face j between cells j-1 and j, j in [0, ny].
    size_t faceYIndex(int i, int j, int k) const { return index(Placement::FaceY, i, j, k); }
    /// z-face k between cells k-1 and k, k in [0, nz].
    size_t faceZIndex(int i, int j, int k) const { return index(Placement::FaceZ, i, j, k); }
    /// Face of `axis` (0: x, 1: y, 2: z).
    size_t faceIndex(int axis, int i, int j, int k) const {
        return index(Placement(axis), i, j, k);
    }
};

/// One axis of a linear stencil on a lattice of n samples: lower sample i0, upper sample i1 and
/// the weight t of the upper.
struct AxisStencil {
    int i0 = 0, i1 = 0;
    double t = 0.0;
};

/// The stencil for a continuous lattice coordinate f (0 at the first sample, 1 at the second),
/// clamped to the lattice [0, n - 1].
inline AxisStencil latticeStencil(double f, int n) {
    f = f < 0.0 ? 0.0 : (f > n - 1 ? double(n - 1) : f);
    int i = int(f);
    if (i > n - 2) i = n > 1 ? n - 2 : 0;
    return {i, n > 1 ? i + 1 : i, n > 1 ? f - i : 0.0};
}

/// Trilinear blend of a sample array (n0 * n1 * n2, index 0 fastest) on three axis stencils:
/// along x, then y, then z (trilinearBlend, sim/Interpolation.h). If lo/hi are given they receive
/// the min/max of the 8 values (the MacCormack and BFECC limiter's bounds).
inline double blendStencils(const double* a, int n0, int n1, const AxisStencil& x,
                            const AxisStencil& y, const AxisStencil& z, double* lo = nullptr,
                            double* hi = nullptr) {
    const size_t sy = size_t(n0), sz = size_t(n0) * size_t(n1);
    const double* p00 = a + sy * size_t(y.i0) + sz * size_t(z.i0);
    const double* p10 = a + sy * size_t(y.i1) + sz * size_t(z.i0);
    const double* p01 = a + sy * size_t(y.i0) + sz * size_t(z.i1);
    const double* p11 = a + sy * size_t(y.i1) + sz * size_t(z.i1);
    const double c[8] = {p00[x.i0], p00[x.i1], p10[x.i0], p10[x.i1],
                         p01[x.i0], p01[x.i1], p11[x.i0], p11[x.i1]};
    if (lo) *lo = std::min({c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]});
    if (hi) *hi = std::max({c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]});
    return trilinearBlend(c, x.t, y.t, z.t);
}

/// The box's geometry: indices (GridIndex), horizontal spacing, origin and the vertical levels.
class GridLayout : public GridIndex {
  public:
    double voxelSize_m = 1.0;  ///< horizontal cell edge h (and the layer thickness if uniform), m
    Vec3d wsMin_m{};           ///< world position of the minimum corner of cell (0, 0, 0), m

    GridLayout() = default;
    /// Uniform cubic cells of edge voxelSize (metres).
    GridLayout(int nxCells, int nyCells, int nzCells, double voxelSize, const Vec3d& wsMin);
    /// Stretched layers: zLevels_m holds the nz + 1 world heights of the horizontal faces,
    /// strictly increasing, zLevels_m[0] = wsMin.z. Throws gale::ParameterError
    /// ("solver.first_cell_m") when there are fewer than 2 levels or they do not increase.
    GridLayout(int nxCells, int nyCells, double voxelSize, const Vec3d& wsMin,
               std::vector<double> zLevels_m);

    /// True for cubic cells (no level table).
    bool uniformZ() const { return mZLevels_m.empty(); }
    /// World z of z-face k, k in [0, nz], metres.
    double zFace_m(int k) const {
        return uniformZ() ? wsMin_m[2] + k * voxelSize_m : mZLevels_m[size_t(k)];
    }
    /// Thickness of layer k, k in [0, nz), metres.
    double dz_m(int k) const {
        return uniformZ() ? voxelSize_m : mZLevels_m[size_t(k) + 1] - mZLevels_m[size_t(k)];
    }
    /// World z of the centres of layer k, metres.
    double zCentre_m(int k) const {
        return uniformZ() ? wsMin_m[2] + (k + 0.5) * voxelSize_m
                          : 0.5 * (mZLevels_m[size_t(k)] + mZLevels_m[size_t(k) + 1]);
    }
    /// Distance between the centres z-face k separates, k in [0, nz], metres: h for cubic
    /// cells; on stretched layers the mean of the two layers, and at the bottom and the top
    /// face the end layer's thickness (a value on the face sits half of it from the centre).
    double centreGap_m(int k) const {
        if (uniformZ()) return voxelSize_m;
        if (k <= 0) return dz_m(0);
        if (k >= nz) return dz_m(nz - 1);
        return 0.5 * (dz_m(k - 1) + dz_m(k));
    }
    /// World z of the top of the box, metres.
    double wsTop_m() const { return zFace_m(nz); }
    /// The nz + 1 level heights (world z of the z-faces, metres), uniform layouts included.
    std::vector<double> zLevels_m() const;

    /// A horizontal length in metres as a length in cells, l / h (also the vertical one when
    /// uniformZ()).
    double cellsFromMetres(double l_m) const { return l_m / voxelSize_m; }
    /// World metres -> index space (see the file comment).
    Vec3d isFromWs(const Vec3d& ws) const {
        return {cellsFromMetres(ws[0] - wsMin_m[0]), cellsFromMetres(ws[1] - wsMin_m[1]),
                isZFromWs(ws[2])};
    }
    /// Index space -> world metres.
    Vec3d wsFromIs(const Vec3d& is) const {
        return {wsMin_m[0] + is[0] * voxelSize_m, wsMin_m[1] + is[1] * voxelSize_m,
                wsZFromIs(is[2])};
    }
    /// Vertical index coordinate of world height z (metres).
    double isZFromWs(double z_m) const {
        return uniformZ() ? cellsFromMetres(z_m - wsMin_m[2]) : stretchedIsZ(z_m);
    }
    /// World height (metres) of vertical index coordinate Z.
    double wsZFromIs(double Z) const {
        return uniformZ() ? wsMin_m[2] + Z * voxelSize_m : stretchedWsZ(Z);
    }
    /// World position of sample (i, j, k) of placement p, metres.
    Vec3d wsPosition(Placement p, int i, int j, int k) const {
        return {wsMin_m[0] + (i + (p == Placement::FaceX ? 0.0 : 0.5)) * voxelSize_m,
                wsMin_m[1] + (j + (p == Placement::FaceY ? 0.0 : 0.5)) * voxelSize_m,
                p == Placement::FaceZ ? zFace_m(k) : zCentre_m(k)};
    }
    /// True when an index-space point lies in the box (sides included).
    bool containsIs(const Vec3d& is) const {
        return is[0] >= 0.0 && is[0] <= nx && is[1] >= 0.0 && is[1] <= ny && is[2] >= 0.0 &&
               is[2] <= nz;
    }

    /// The stencil along `axis` at index coordinate c of the face lattice of that axis
    /// (onFaces) or of the cell-centre lattice, clamped to the lattice.
    AxisStencil stencil(int axis, bool onFaces, double c) const {
        const int n = axis == 0 ? nx : axis == 1 ? ny : nz;
        if (onFaces) return latticeStencil(c, n + 1);
        if (axis < 2 || uniformZ()) return latticeStencil(c - 0.5, n);
        return latticeStencil(centreLatticeZ(c), n);
    }
    /// Trilinear sample of q (placement p, count(p) values) at index-space point `is`; lo/hi as
    /// blendStencils. The one staggered sampler: WindField and the advection read through it.
    double sample(Placement p, const double* q, const Vec3d& is, double* lo = nullptr,
                  double* hi = nullptr) const {
        const auto d = dims(p);
        return blendStencils(q, d[0], d[1], stencil(0, p == Placement::FaceX, is[0]),
                             stencil(1, p == Placement::FaceY, is[1]),
                             stencil(2, p == Placement::FaceZ, is[2]), lo, hi);
    }
    /// The three MAC components at index-space point `is`, each from its own faces (u, v, w
    /// arrays of count(FaceX), count(FaceY), count(FaceZ) values), sharing their axis stencils.
    Vec3d sampleFaces(const double* u, const double* v, const double* w, const Vec3d& is) const {
        const AxisStencil fx = stencil(0, true, is[0]), cx = stencil(0, false, is[0]);
        const AxisStencil fy = stencil(1, true, is[1]), cy = stencil(1, false, is[1]);
        const AxisStencil fz = stencil(2, true, is[2]), cz = stencil(2, false, is[2]);
        return {blendStencils(u, nx + 1, ny, fx, cy, cz), blendStencils(v, nx, ny + 1, cx, fy, cz),
                blendStencils(w, nx, ny, cx, cy, fz)};
    }

    bool operator==(const GridLayout& o) const {
        return nx == o.nx && ny == o.ny && nz == o.nz && voxelSize_m == o.voxelSize_m &&
               wsMin_m == o.wsMin_m && mZLevels_m == o.mZLevels_m;
    }
    bool operator!=(const GridLayout& o) const { return !(*this == o); }

  private:
    /// World heights of the z-faces (nz + 1, increasing); empty: uniform cubic cells.
    std::vector<double> mZLevels_m;
    double stretchedIsZ(double z_m) const;
    double stretchedWsZ(double Z) const;
    /// Cell-centre lattice coordinate (0 at the centre of layer 0) of face-lattice coordinate Z,
    /// linear in world z between neighbouring centres.
    double centreLatticeZ(double Z) const;
};

/// The layout's sizes as members of a class that holds a GridLayout and returns it from
/// `layout()` (AirDomain, WindField), so callers write `domain.nx()`: one set of forwards for
/// every holder (CRTP: `class AirDomain : public LayoutAccessors<AirDomain>`).
template <class Holder>
class LayoutAccessors {
  public:
    /// Cells along x, y and z.
    int nx() const { return grid().nx; }
    int ny() const { return grid().ny; }
    int nz() const { return grid().nz; }
    /// Horizontal cell edge (and the layer thickness of a uniform layout), metres.
    double voxelSize_m() const { return grid().voxelSize_m; }
    /// World position of the minimum corner of cell (0, 0, 0), metres.
    Vec3d wsMin_m() const { return grid().wsMin_m; }
    /// World z of the top boundary (after rounding to whole cells), metres.
    double wsTop_m() const { return grid().wsTop_m(); }

  private:
    const GridLayout& grid() const { return static_cast<const Holder&>(*this).layout(); }
};

}  // namespace gale::sim
