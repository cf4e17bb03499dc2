/// \file VdbIO.cpp
/// Writing the field as OpenVDB grids (sim/VdbIO.h); sim/VdbRead.cpp reads them back.
#include "sim/VdbIO.h"

#include <openvdb/io/File.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>

#include "sim/VdbFormat.h"

namespace gale::sim {

namespace detail {
openvdb::math::Transform::Ptr cellCentredTransform(double h, const std::array<double, 3>& wsMin) {
    auto xform = openvdb::math::Transform::createLinearTransform(h);
    xform->postTranslate(
        openvdb::Vec3d(wsMin[0] + 0.5 * h, wsMin[1] + 0.5 * h, wsMin[2] + 0.5 * h));
    return xform;
}
}  // namespace detail

std::string detail::levelsText(const GridLayout& g) {
    std::string out;
    char buf[32];
    for (double z : g.zLevels_m()) {
        std::snprintf(buf, sizeof buf, "%.17g", z);
        out += (out.empty() ? "" : " ") + std::string(buf);
    }
    return out;
}

namespace {
using detail::CUBIC_FACES_GRID, detail::STRETCHED_FACES_GRID, detail::levelsText;

// An empty world-space velocity grid (m/s) on the field's cells.
openvdb::Vec3SGrid::Ptr emptyVelocityGrid(const WindField& f, const char* name,
                                          openvdb::GridClass gridClass) {
    openvdb::initialize();
    auto grid = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
    grid->setName(name);
    grid->setTransform(detail::cellCentredTransform(f.voxelSize_m(), f.wsMin_m()));
    grid->setGridClass(gridClass);
    grid->setVectorType(openvdb::VEC_CONTRAVARIANT_RELATIVE);
    grid->setIsInWorldSpace(true);
    return grid;
}

// Calls f(coord, velocity) for every air voxel of the standard grids, in the order the grids are
// filled: cubic cells give each air cell's cell-centred velocity; stretched layers give the
// velocity sampled (velocityAt_mps) at the centre of each voxel of the cubic resample whose
// centre lies above the terrain.
template <class F>
void forEachAirCell(const WindField& field, F&& f) {
    const GridLayout& g = field.layout();
    const int nzOut = vdbCubicLayers(field.layout());
    const double h = g.voxelSize_m;
    for (int j = 0; j < field.ny(); ++j)
        for (int i = 0; i < field.nx(); ++i)
            for (int k = 0; k < nzOut; ++k) {
                if (g.uniformZ()) {
                    if (field.isAir(i, j, k))
                        f(openvdb::Coord(i, j, k), field.cellVelocity_mps(i, j, k));
                    continue;
                }
                const double x = g.wsMin_m[0] + (i + 0.5) * h, y = g.wsMin_m[1] + (j + 0.5) * h,
                             z = g.wsMin_m[2] + (k + 0.5) * h;
                if (z <= g.wsTop_m() && !field.belowTerrain(x, y, z))
                    f(openvdb::Coord(i, j, k), field.velocityAboveTerrainAt_mps(x, y, z));
            }
}

/// Writes `grids` to `path` through a temporary file in the same folder, renamed when complete.
void writeGridsAtomic(const std::string& path, const openvdb::GridCPtrVec& grids) {
    namespace fs = std::filesystem;
    const fs::path target(path);
    const fs::path tmp =
        target.parent_path() / (target.filename().string() + ".tmp" + std::to_string(::getpid()));
    // Only a regular file (or nothing) is replaced: the rename below would put a regular file in
    // place of a device node such as /dev/null.
    std::error_code statError;
    const fs::file_status st = fs::status(target, statError);
    if (fs::exists(st) && !fs::is_regular_file(st))
        throw std::runtime_error("cannot write VDB file '" + path +
                                 "': it exists and is not a regular file (a device, FIFO or "
                                 "folder); gale replaces only regular files");
    // openvdb::io::File::write never looks at its stream after writing, so a full disk gave a
    // truncated file and no error: write the same archive to a stream we check.
    struct CheckedArchive : openvdb::io::File {
        using openvdb::io::File::File;
        void writeTo(std::ostream& os, const openvdb::GridCPtrVec& g) const {
            openvdb::io::Archive::write(os, g, /*seekable=*/true, openvdb::MetaMap());
        }
    };
    try {
        std::ofstream os(tmp, std::ios_base::out | std::ios_base::binary | std::ios_base::trunc);
        if (!os) throw std::runtime_error(std::string("cannot create it: ") + std::strerror(errno));
        CheckedArchive(tmp.string()).writeTo(os, grids);
        os.flush();
        const int err = errno;
        if (!os) throw std::runtime_error(std::strerror(err));
        os.close();
        if (os.fail()) throw std::runtime_error(std::strerror(errno));
        fs::rename(tmp, target);
    } catch (const std::exception& e) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw std::runtime_error("cannot write VDB file '" + path + "': " + e.what());
    }
}
}  // namespace

openvdb::Vec3SGrid::Ptr velocityGrid(const WindField& f) {
    auto grid = emptyVelocityGrid(f, "velocity", openvdb::GRID_UNKNOWN);
    auto acc = grid->getAccessor();
    forEachAirCell(f, [&](const openvdb::Coord& c, const std::array<double, 3>& v) {
        acc.setValueOn(c, openvdb::Vec3s(float(v[0]), float(v[1]), float(v[2])));
    });
    return grid;
}

openvdb::Vec3SGrid::Ptr staggeredVelocityGrid(const WindField& f) {
    const bool stretched = !f.layout().uniformZ();
    auto grid = emptyVelocityGrid(f, stretched ? STRETCHED_FACES_GRID : CUBIC_FACES_GRID,
                                  openvdb::GRID_STAGGERED);
    if (stretched) grid->insertMeta("z_levels_m", openvdb::StringMetadata(levelsText(f.layout())));
    auto acc = grid->getAccessor();
    // Voxel (i, j, k) holds the three faces on cell (i, j, k)'s low sides, as OpenVDB's staggered
    // samplers expect; the layer i = nx (j = ny, k = nz) holds the high-side faces of the box.
    // Every voxel gets its values (the samplers read inactive voxels too, and closed faces hold
    // the extrapolated values gale samples near the ground); active are the voxels with a face
    // of an air cell, so the grid's topology is the air's.
    const int nx = f.nx(), ny = f.ny(), nz = f.nz();
    auto air = [&](int i, int j, int k) {
        return i >= 0 && j >= 0 && k >= 0 && i < nx && j < ny && k < nz && f.isAir(i, j, k);
    };
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) {
                openvdb::Vec3s faces(0.f);
                if (j < ny && k < nz) faces.x() = float(f.u(i, j, k));
                if (i < nx && k < nz) faces.y() = float(f.v(i, j, k));
                if (i < nx && j < ny) faces.z() = float(f.w(i, j, k));
                const openvdb::Coord c(i, j, k);
                if (air(i, j, k) || air(i - 1, j, k) || air(i, j - 1, k) || air(i, j, k - 1))
                    acc.setValueOn(c, faces);
                else
                    acc.setValueOff(c, faces);
            }
    return grid;
}

openvdb::FloatGrid::Ptr speedGrid(const WindField& f) {
    openvdb::initialize();
    auto grid = openvdb::FloatGrid::create(0.f);
    grid->setName("speed");
    grid->setTransform(detail::cellCentredTransform(f.voxelSize_m(), f.wsMin_m()));
    grid->setGridClass(openvdb::GRID_UNKNOWN);
    auto acc = grid->getAccessor();
    forEachAirCell(f, [&](const openvdb::Coord& c, const std::array<double, 3>& v) {
        acc.setValueOn(c, float(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])));
    });
    return grid;
}

void writeHoudiniVdb(const std::string& path, const WindField& f, const Heightfield& terrain) {
    openvdb::initialize();
    const double h = f.voxelSize_m();
    const auto o = f.wsMin_m();
    // y-up: gale cell (i, j, k) -> index (i, k, -j - 1), whose centre is (x, z, -y).
    auto xform = openvdb::math::Transform::createLinearTransform(h);
    xform->postTranslate(openvdb::Vec3d(o[0] + 0.5 * h, o[2] + 0.5 * h, -o[1] + 0.5 * h));
    auto vel = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
    vel->setName("vel");
    vel->setTransform(xform);
    vel->setGridClass(openvdb::GRID_UNKNOWN);
    vel->setVectorType(openvdb::VEC_CONTRAVARIANT_RELATIVE);
    vel->setIsInWorldSpace(true);
    auto vacc = vel->getAccessor();
    forEachAirCell(f, [&](const openvdb::Coord& c, const std::array<double, 3>& v) {
        vacc.setValueOn(openvdb::Coord(c.x(), c.z(), -c.y() - 1),
                        openvdb::Vec3s(float(v[0]), float(v[2]), float(-v[1])));
    });
    const float band = float(3.0 * h);
    auto sdf = openvdb::FloatGrid::create(band);
    sdf->setName("surface");
    sdf->setTransform(xform->copy());
    sdf->setGridClass(openvdb::GRID_LEVEL_SET);
    auto sacc = sdf->getAccessor();
    const int nzOut = vdbCubicLayers(f.layout());
    for (int j = 0; j < f.ny(); ++j)
        for (int i = 0; i < f.nx(); ++i) {
            const double x = o[0] + (i + 0.5) * h, y = o[1] + (j + 0.5) * h;
            const double ground = terrain.sample(x, y);
            for (int k = 0; k < nzOut; ++k) {
                const double d = o[2] + (k + 0.5) * h - ground;
                if (std::abs(d) < band) sacc.setValueOn(openvdb::Coord(i, k, -j - 1), float(d));
            }
        }
    // Below the band the ground is inside: negative background there, as a level set needs.
    openvdb::tools::signedFloodFill(sdf->tree());
    for (openvdb::GridBase* g :
         {static_cast<openvdb::GridBase*>(vel.get()), static_cast<openvdb::GridBase*>(sdf.get())})
        g->insertMeta("axes",
                      openvdb::StringMetadata("y-up: (x, y, z) here = gale (x, z, -y); metres"));
    writeGridsAtomic(path, {vel, sdf});
}

openvdb::FloatGrid::Ptr tkeGrid(const WindField& f, const std::vector<double>& tke) {
    const GridLayout& g = f.layout();
    if (tke.size() != g.cellCount())
        throw std::invalid_argument("tkeGrid: " + std::to_string(tke.size()) + " values for " +
                                    std::to_string(g.cellCount()) + " cells");
    openvdb::initialize();
    const bool stretched = !g.uniformZ();
    auto grid = openvdb::FloatGrid::create(0.f);
    grid->setName(stretched ? TKE_LAYERS_GRID : TKE_GRID);
    grid->setTransform(detail::cellCentredTransform(f.voxelSize_m(), f.wsMin_m()));
    grid->setGridClass(openvdb::GRID_UNKNOWN);
    auto acc = grid->getAccessor();
    for (int k = 0; k < f.nz(); ++k)
        for (int j = 0; j < f.ny(); ++j)
            for (int i = 0; i < f.nx(); ++i)
                if (f.isAir(i, j, k))
                    acc.setValueOn(openvdb::Coord(i, j, k), float(tke[g.cellIndex(i, j, k)]));
    grid->insertMeta("units", openvdb::StringMetadata("m^2/s^2"));
    grid->insertMeta("quantity", openvdb::StringMetadata("turbulent kinetic energy k"));
    grid->insertMeta(
        "cell_placement",
        openvdb::StringMetadata(
            stretched ? "cell-centred on stretched layers: voxel (i,j,k) is cell (i,j,k); its x, y "
                        "as the transform says, layer k between world z = z_levels_m[k] and "
                        "z_levels_m[k+1] (the transform's z is the layer index, not world z)"
                      : "cell-centred: voxel (i,j,k) is the cell whose centre is at world wsMin "
                        "+ (i+0.5, j+0.5, k+0.5) * voxel_size"));
    if (stretched) grid->insertMeta("z_levels_m", openvdb::StringMetadata(levelsText(g)));
    grid->insertMeta("voxel_size_m", openvdb::DoubleMetadata(g.voxelSize_m));
    return grid;
}

void WindField::writeVdb(const std::string& path, const VdbMetadata& metadata,
                         const std::vector<double>& tke_m2ps2) const {
    openvdb::initialize();
    if (!tke_m2ps2.empty() && tke_m2ps2.size() != mLayout.cellCount())
        throw std::invalid_argument("writeVdb: " + std::to_string(tke_m2ps2.size()) +
                                    " tke values for " + std::to_string(mLayout.cellCount()) +
                                    " cells");
    auto vel = velocityGrid(*this);
    auto speed = speedGrid(*this);
    auto faces = staggeredVelocityGrid(*this);
    openvdb::FloatGrid::Ptr tke = tke_m2ps2.empty() ? nullptr : tkeGrid(*this, tke_m2ps2);
    if (tke) {
        for (const auto& [k, v] : metadata.strings) tke->insertMeta(k, openvdb::StringMetadata(v));
        for (const auto& [k, v] : metadata.numbers) tke->insertMeta(k, openvdb::DoubleMetadata(v));
    }
    for (openvdb::GridBase* g :
         {static_cast<openvdb::GridBase*>(vel.get()), static_cast<openvdb::GridBase*>(speed.get()),
          static_cast<openvdb::GridBase*>(faces.get())}) {
        g->insertMeta("units", openvdb::StringMetadata("m/s"));
        const bool stretched = !mLayout.uniformZ();
        g->insertMeta(
            "cell_placement",
            openvdb::StringMetadata(
                g == faces.get()
                    ? (stretched
                           ? "MAC face velocities on stretched layers, staggered: voxel (i,j,k) "
                             "holds u, v, w on the low x, y, z faces of cell (i,j,k); its x, y "
                             "as the transform says, its z-faces at world z = z_levels_m[k] (the "
                             "transform's z is the layer index, not world z)"
                           : "MAC face velocities, staggered: voxel (i,j,k) holds u, v, w on the "
                             "low x, y, z faces of the cell whose centre is at world wsMin + "
                             "(i+0.5, j+0.5, k+0.5) * voxel_size")
                    : (stretched ? "velocity sampled at the voxel centre from the MAC faces of "
                                   "stretched layers (cubic resample); voxel (i,j,k) centre at "
                                   "world wsMin + (i+0.5, j+0.5, k+0.5) * voxel_size"
                                 : "cell-centred average of MAC face velocities; voxel (i,j,k) "
                                   "centre at world wsMin + (i+0.5, j+0.5, k+0.5) * voxel_size")));
        if (stretched) g->insertMeta("z_levels_m", openvdb::StringMetadata(levelsText(mLayout)));
        g->insertMeta("voxel_size_m", openvdb::DoubleMetadata(mLayout.voxelSize_m));
        for (const auto& [k, v] : metadata.strings) g->insertMeta(k, openvdb::StringMetadata(v));
        for (const auto& [k, v] : metadata.numbers) g->insertMeta(k, openvdb::DoubleMetadata(v));
    }
    if (tke)
        writeGridsAtomic(path, {vel, speed, faces, tke});
    else
        writeGridsAtomic(path, {vel, speed, faces});
}

int vdbCubicLayers(const GridLayout& layout) {
    if (layout.uniformZ()) return layout.nz;
    return std::max(
        1, int(std::ceil((layout.wsTop_m() - layout.wsMin_m[2]) / layout.voxelSize_m - 1e-9)));
}

}  // namespace gale::sim
