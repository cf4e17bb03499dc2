/// \file AirDomain.cpp
/// Open fractions of cut cells over a heightfield, and the OpenVDB air mask.

#include "sim/AirDomain.h"

#include <openvdb/openvdb.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/Format.h"
#include "sim/MomentumWind.h"
#include "sim/VdbIO.h"

namespace gale::sim {

struct AirDomain::Vdb {
    openvdb::BoolGrid::Ptr mask;
};

namespace detail {
namespace {

using detail::num;

/// Mean over t in [0, 1] of clamp(f0 + (f1 - f0) t, 0, D): exact for a linear f.
double meanClampedLinear(double f0, double f1, double D) {
    if (f0 > f1) std::swap(f0, f1);  // the mean is symmetric under t -> 1 - t
    if (f1 <= 0.0) return 0.0;
    if (f0 >= D) return D;
    const double df = f1 - f0;
    if (df < 1e-300) return std::clamp(f0, 0.0, D);
    const double t0 = std::clamp(-f0 / df, 0.0, 1.0), t1 = std::clamp((D - f0) / df, 0.0, 1.0);
    const double a = f0 + df * t0, b = f0 + df * t1;
    return (t1 - t0) * 0.5 * (a + b) + (1.0 - t1) * D;
}

/// Fraction of t in [0, 1] where g0 + (g1 - g0) t < level.
double fractionBelow(double g0, double g1, double level) {
    const bool b0 = g0 < level, b1 = g1 < level;
    if (b0 && b1) return 1.0;
    if (!b0 && !b1) return 0.0;
    const double t = (level - g0) / (g1 - g0);
    return b0 ? t : 1.0 - t;
}

float cleanFraction(double f, bool cutCells) {
    if (!cutCells) return f >= 0.5 ? 1.f : 0.f;
    if (f < AirDomain::MIN_OPEN_FRACTION) return 0.f;
    if (f > 1.0 - 1e-6) return 1.f;
    return float(f);
}

}  // namespace
}  // namespace detail

double AirDomain::estimateSolveMemory_bytes(int nx, int ny, int nz, bool momentum) {
    return solveArrays_bytes(nx, ny, nz, /*terrainSamples=*/0, momentum, RunMemory{});
}

double AirDomain::estimateSolveMemory_bytes(const GridLayout& g, bool momentum) {
    double bytes = estimateSolveMemory_bytes(g.nx, g.ny, g.nz, momentum);
    if (!g.uniformZ())
        bytes += RESAMPLE_BYTES_PER_VOXEL * double(g.nx) * g.ny *
                 std::ceil((g.wsTop_m() - g.wsMin_m[2]) / g.voxelSize_m - 1e-9);
    return bytes;
}

std::vector<double> AirDomain::stretchedLevels_m(double z0, double top, double first, double ratio,
                                                 double maxCell) {
    std::vector<double> z{z0};
    double dz = first;
    // Each level adds at least `first` > 0, so this ends; the caller bounds the count.
    while (z.back() < top - 1e-9 * first) {
        z.push_back(z.back() + dz);
        dz = std::min(dz * ratio, maxCell);
    }
    if (z.size() < 2) z.push_back(z0 + first);
    return z;
}

AirDomain::AirDomain(const Heightfield& hf, const DomainSpec& spec)
    : mClosedSidesY(spec.closedSidesY) {
    using detail::num;
    // --- validate everything before allocating anything ------------------------------------
    if (hf.nx < 2 || hf.ny < 2)
        throw std::invalid_argument("terrain must have at least 2x2 samples, got " +
                                    std::to_string(hf.nx) + "x" + std::to_string(hf.ny));
    if (hf.height_m.size() != size_t(hf.nx) * hf.ny)
        throw std::logic_error("AirDomain: the heightfield must have nx*ny = " +
                               std::to_string(size_t(hf.nx) * hf.ny) + " heights, got " +
                               std::to_string(hf.height_m.size()));
    if (!(hf.spacing_m > 0.0) || !std::isfinite(hf.spacing_m))
        throw ParameterError("terrain.spacing_m", num(hf.spacing_m), "must be > 0 and finite");
    if (!std::isfinite(hf.originX_m) || !std::isfinite(hf.originY_m))
        throw std::invalid_argument("terrain origin must be finite");
    for (size_t n = 0; n < hf.height_m.size(); ++n)
        if (!std::isfinite(hf.height_m[n]))
            throw std::invalid_argument("terrain height is not finite (" + num(hf.height_m[n]) +
                                        ") at sample (" + std::to_string(n % hf.nx) + ", " +
                                        std::to_string(n / hf.nx) + ")");
    const double h = spec.voxelSize_m;
    if (!(h > 0.0) || !std::isfinite(h))
        throw ParameterError("solver.voxel_size_m", num(h), "must be > 0 and finite");
    if (!(spec.memoryLimit_bytes > 0.0))
        throw ParameterError("solver.memory_limit_mb", num(spec.memoryLimit_bytes / MIB),
                             "must be > 0");
    const double nxD = std::floor(hf.sizeX_m() / h + 1e-9),
                 nyD = std::floor(hf.sizeY_m() / h + 1e-9);
    if (nxD < 1 || nyD < 1)
        throw ParameterError("solver.voxel_size_m", num(h),
                             "must not exceed the terrain (" + num(hf.sizeX_m()) + " x " +
                                 num(hf.sizeY_m()) + " m)");
    const double minH = hf.minHeight_m(), maxH = hf.maxHeight_m();
    // Stretched layers: validated here, their levels made below once the top is known.
    const bool stretched = spec.firstCell_m.has_value();
    const double first = stretched ? *spec.firstCell_m : h;
    const double maxCell = spec.maxCell_m ? *spec.maxCell_m : MAX_LAYER_THICKENING * h;
    if (stretched) {
        if (!(first >= h / MAX_FIRST_CELL_THINNING * (1 - 1e-12) && first <= h * (1 + 1e-12)))
            throw ParameterError("solver.first_cell_m", num(first),
                                 "must be in [voxel_size_m / 5, voxel_size_m] = [" +
                                     num(h / MAX_FIRST_CELL_THINNING) + ", " + num(h) + "] m");
        if (!(spec.stretchRatio >= 1.0 && spec.stretchRatio <= MAX_STRETCH_RATIO))
            throw ParameterError("solver.stretch_ratio", num(spec.stretchRatio),
                                 "must be in [1, " + num(MAX_STRETCH_RATIO) + "]");
        if (!(maxCell >= first && maxCell <= MAX_LAYER_THICKENING * h * (1 + 1e-12)))
            throw ParameterError("solver.max_cell_m", num(maxCell),
                                 "must be in [solver.first_cell_m, 2 voxel_size_m] = [" +
                                     num(first) + ", " + num(MAX_LAYER_THICKENING * h) + "] m");
    } else if (spec.maxCell_m) {
        throw ParameterError("solver.max_cell_m", num(maxCell),
                             "applies to stretched layers only: give solver.first_cell_m too");
    }
    const double zMin = std::floor(minH / first) * first;
    double top = 0.0;
    if (spec.top_m) {
        top = *spec.top_m;
        if (!std::isfinite(top) || !(top > maxH))
            throw ParameterError("solver.top_m", num(top),
                                 "must be above the highest terrain point (" + num(maxH) +
                                     " m): the domain would have no air");
    } else {
        top = maxH + std::max(AUTO_TOP_RELIEF_FACTOR * (maxH - minH), AUTO_TOP_MIN_CELLS * h);
    }
    std::vector<double> levels;
    constexpr double MAX_LAYERS = 1e7;  // far above any box the memory limit lets through
    if (stretched && (top - zMin) / maxCell > MAX_LAYERS)
        throw ParameterError("solver.top_m", num(top),
                             "gives more than " + num(MAX_LAYERS) + " layers: lower it");
    if (stretched) levels = stretchedLevels_m(zMin, top, first, spec.stretchRatio, maxCell);
    const double nzD = stretched ? double(levels.size() - 1) : std::ceil((top - zMin) / h - 1e-9);
    const double resampleD = stretched ? std::ceil((levels.back() - zMin) / h - 1e-9) : 0.0;
    const double estimate =
        spec.run.processBaseline_bytes +
        solveArrays_bytes(nxD, nyD, nzD, double(hf.height_m.size()), spec.momentumModel, spec.run) +
        RESAMPLE_BYTES_PER_VOXEL * nxD * nyD * resampleD;
    if (nxD * nyD * nzD > 2.0e9 || estimate > spec.memoryLimit_bytes)
        throw ParameterError(
            "solver.memory_limit_mb", formatG(spec.memoryLimit_bytes / MIB, 4),
            "is below the estimated memory of " + formatG(estimate / MIB, 4) + " MiB for " +
                num(nxD) + " x " + num(nyD) + " x " + num(nzD) + " cells" +
                (spec.run.processBaseline_bytes > 0
                     ? " (the program itself " + formatG(spec.run.processBaseline_bytes / MIB, 3) +
                           " MiB)"
                     : std::string()) +
                ": raise solver.voxel_size_m, lower solver.top_m or raise "
                "the limit");

    mLayout = stretched ? GridLayout(int(nxD), int(nyD), h, {hf.originX_m, hf.originY_m, zMin},
                                     std::move(levels))
                        : GridLayout(int(nxD), int(nyD), std::max(1, int(nzD)), h,
                                     {hf.originX_m, hf.originY_m, zMin});
    mMemoryEstimate_bytes = size_t(estimate);
    mTerrain = std::make_shared<const Heightfield>(hf);

    // --- open fractions, column by column ------------------------------------------------
    const GridLayout& G = mLayout;
    const int nx = G.nx, ny = G.ny, nz = G.nz, S = FRACTION_SUBSAMPLES;
    const std::array<double, 3>& wsMin = G.wsMin_m;
    mOpenX.assign(G.count(Placement::FaceX), 0.f);
    mOpenY.assign(G.count(Placement::FaceY), 0.f);
    mOpenZ.assign(G.count(Placement::FaceZ), 0.f);
    mAir.assign(G.cellCount(), 0);
    const Heightfield& T = *mTerrain;
    // Vertical face along a line of S+1 heights: open fraction of its cell k (thickness dz).
    auto verticalFace = [&](const double* line, int k, double lineMin, double lineMax) -> float {
        const double dz = G.dz_m(k), z0 = G.zFace_m(k), z1 = z0 + dz;
        if (z0 >= lineMax) return 1.f;
        if (z1 <= lineMin) return 0.f;
        double s = 0.0;
        for (int b = 0; b < S; ++b)
            s += detail::meanClampedLinear(z1 - line[b], z1 - line[b + 1], dz);
        return detail::cleanFraction(s / (S * dz), spec.cutCells);
    };
    tbb::parallel_for(tbb::blocked_range<int>(0, ny), [&](const tbb::blocked_range<int>& rj) {
        std::vector<double> H(size_t(S + 1) * (S + 1)), line(S + 1), mid(S + 1);
        auto Hat = [&](int a, int b) -> double& { return H[size_t(b) * (S + 1) + a]; };
        for (int j = rj.begin(); j < rj.end(); ++j)
            for (int i = 0; i < nx; ++i) {
                double cMin = 1e300, cMax = -1e300;
                for (int b = 0; b <= S; ++b)
                    for (int a = 0; a <= S; ++a) {
                        const double v = T.sample(wsMin[0] + (i + double(a) / S) * h,
                                                  wsMin[1] + (j + double(b) / S) * h);
                        Hat(a, b) = v;
                        cMin = std::min(cMin, v), cMax = std::max(cMax, v);
                    }
                auto doLine = [&](bool alongY, int fixed, auto&& store) {
                    double lMin = 1e300, lMax = -1e300;
                    for (int t = 0; t <= S; ++t) {
                        line[t] = alongY ? Hat(fixed, t) : Hat(t, fixed);
                        lMin = std::min(lMin, line[t]), lMax = std::max(lMax, line[t]);
                    }
                    for (int k = 0; k < nz; ++k) store(k, verticalFace(line.data(), k, lMin, lMax));
                };
                doLine(true, 0, [&](int k, float f) { mOpenX[G.faceXIndex(i, j, k)] = f; });
                if (i == nx - 1)
                    doLine(true, S, [&](int k, float f) { mOpenX[G.faceXIndex(nx, j, k)] = f; });
                doLine(false, 0, [&](int k, float f) { mOpenY[G.faceYIndex(i, j, k)] = f; });
                if (j == ny - 1)
                    doLine(false, S, [&](int k, float f) { mOpenY[G.faceYIndex(i, ny, k)] = f; });
                // Horizontal faces: area where h < z_face, S rows at the sub-row midpoints.
                for (int k = 0; k <= nz; ++k) {
                    const double zf = G.zFace_m(k);
                    float f;
                    if (zf > cMax) {
                        f = 1.f;
                    } else if (zf <= cMin) {
                        f = 0.f;
                    } else {
                        double s = 0.0;
                        for (int b = 0; b < S; ++b) {
                            for (int a = 0; a <= S; ++a) mid[a] = 0.5 * (Hat(a, b) + Hat(a, b + 1));
                            for (int a = 0; a < S; ++a)
                                s += detail::fractionBelow(mid[a], mid[a + 1], zf);
                        }
                        f = detail::cleanFraction(s / (S * S), spec.cutCells);
                    }
                    mOpenZ[G.faceZIndex(i, j, k)] = f;
                }
            }
    });
    // --- air cells, and closing every face that touches rock ------------------------------
    size_t active = 0;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const bool air = openFractionZ(i, j, k + 1) > 0.f;
                mAir[cellIndex(i, j, k)] = air;
                active += air;
            }
    mActiveCount = active;
    if (active == 0)
        throw ParameterError(
            "solver.top_m", num(top),
            "leaves no air cells: raise it above the terrain (max " + num(maxH) + " m)");
    auto air = [&](int i, int j, int k) { return mAir[cellIndex(i, j, k)] != 0; };
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j) {
            for (int i = 0; i <= nx; ++i)
                if ((i > 0 && !air(i - 1, j, k)) || (i < nx && !air(i, j, k)))
                    mOpenX[G.faceXIndex(i, j, k)] = 0.f;
        }
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i < nx; ++i)
                if ((j > 0 && !air(i, j - 1, k)) || (j < ny && !air(i, j, k)))
                    mOpenY[G.faceYIndex(i, j, k)] = 0.f;
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                if (k == 0 || (k > 0 && !air(i, j, k - 1)) || (k < nz && !air(i, j, k)))
                    mOpenZ[G.faceZIndex(i, j, k)] = 0.f;

    // --- the OpenVDB air mask ------------------------------------------------------------
    openvdb::initialize();
    mVdb = std::make_shared<Vdb>();
    mVdb->mask = openvdb::BoolGrid::create(false);
    mVdb->mask->setTransform(detail::cellCentredTransform(h, wsMin));
    mVdb->mask->setName("air");
    {
        auto acc = mVdb->mask->getAccessor();
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                for (int k = 0; k < nz; ++k)
                    if (air(i, j, k)) acc.setValueOn(openvdb::Coord(i, j, k), true);
    }
}

AirDomain::~AirDomain() = default;
AirDomain::AirDomain(AirDomain&&) noexcept = default;
AirDomain& AirDomain::operator=(AirDomain&&) noexcept = default;

size_t AirDomain::vdbMemory_bytes() const {
    return mVdb && mVdb->mask ? size_t(mVdb->mask->memUsage()) : 0;
}

size_t AirDomain::memory_bytes() const {
    return (mOpenX.size() + mOpenY.size() + mOpenZ.size()) * sizeof(float) + mAir.size() +
           vdbMemory_bytes() + mTerrain->height_m.size() * sizeof(float);
}

openvdb::BoolGrid::ConstPtr airMaskGrid(const AirDomain& domain) { return domain.vdb().mask; }

void AirDomain::openOutfluxRow(const std::vector<double>& U, const std::vector<double>& V,
                               const std::vector<double>& W, int j, int k, double* out) const {
    const GridLayout& g = mLayout;
    const size_t x0 = g.faceXIndex(0, j, k), y0 = g.faceYIndex(0, j, k),
                 y1 = g.faceYIndex(0, j + 1, k), z0 = g.faceZIndex(0, j, k),
                 z1 = g.faceZIndex(0, j, k + 1);
    const double *u = U.data() + x0, *v0 = V.data() + y0, *v1 = V.data() + y1, *w0 = W.data() + z0,
                 *w1 = W.data() + z1;
    const float *ox = mOpenX.data() + x0, *oy0 = mOpenY.data() + y0, *oy1 = mOpenY.data() + y1,
                *oz0 = mOpenZ.data() + z0, *oz1 = mOpenZ.data() + z1;
    const bool uniform = g.uniformZ();
    const double side = uniform ? 1.0 : g.dz_m(k) / g.voxelSize_m;
    for (int i = 0; i < g.nx; ++i) {
        const double horizontal =
            ox[i + 1] * u[i + 1] - ox[i] * u[i] + oy1[i] * v1[i] - oy0[i] * v0[i];
        out[i] = (uniform ? horizontal : horizontal * side) + oz1[i] * w1[i] - oz0[i] * w0[i];
    }
}

}  // namespace gale::sim
