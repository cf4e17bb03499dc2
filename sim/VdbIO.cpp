/// \file VdbIO.cpp
#include "sim/VdbIO.h"

#include <openvdb/io/File.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <filesystem>
#include <stdexcept>

namespace gale::sim {

namespace detail {
openvdb::math::Transform::Ptr cellCentredTransform(double h, const std::array<double, 3>& wsMin) {
    auto xform = openvdb::math::Transform::createLinearTransform(h);
    xform->postTranslate(openvdb::Vec3d(wsMin[0] + 0.5 * h, wsMin[1] + 0.5 * h, wsMin[2] + 0.5 * h));
    return xform;
}
}  // namespace detail

namespace {
// An empty world-space velocity grid (m/s) on the field's cells.
openvdb::Vec3SGrid::Ptr emptyVelocityGrid(const WindField& f, const char* name, openvdb::GridClass gridClass) {
    openvdb::initialize();
    auto grid = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
    grid->setName(name);
    grid->setTransform(detail::cellCentredTransform(f.voxelSize_m(), f.wsMin_m()));
    grid->setGridClass(gridClass);
    grid->setVectorType(openvdb::VEC_CONTRAVARIANT_RELATIVE);
    grid->setIsInWorldSpace(true);
    return grid;
}
// Calls f(coord, cell-centred velocity) for every air cell, in the order the grids are filled.
template <class F>
void forEachAirCell(const WindField& field, F&& f) {
    for (int j = 0; j < field.ny(); ++j)
        for (int i = 0; i < field.nx(); ++i)
            for (int k = 0; k < field.nz(); ++k)
                if (field.isAir(i, j, k)) f(openvdb::Coord(i, j, k), field.cellVelocity_mps(i, j, k));
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
    auto grid = emptyVelocityGrid(f, "velocity_faces", openvdb::GRID_STAGGERED);
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

void WindField::writeVdb(const std::string& path, const VdbMetadata& metadata) const {
    openvdb::initialize();
    auto vel = velocityGrid(*this);
    auto speed = speedGrid(*this);
    auto faces = staggeredVelocityGrid(*this);
    for (openvdb::GridBase* g : {static_cast<openvdb::GridBase*>(vel.get()), static_cast<openvdb::GridBase*>(speed.get()),
                                 static_cast<openvdb::GridBase*>(faces.get())}) {
        g->insertMeta("units", openvdb::StringMetadata("m/s"));
        g->insertMeta("cell_placement",
                      openvdb::StringMetadata(
                          g == faces.get()
                              ? "MAC face velocities, staggered: voxel (i,j,k) holds u, v, w on the low x, y, z faces "
                                "of the cell whose centre is at world wsMin + (i+0.5, j+0.5, k+0.5) * voxel_size"
                              : "cell-centred average of MAC face velocities; voxel (i,j,k) centre at "
                                "world wsMin + (i+0.5, j+0.5, k+0.5) * voxel_size"));
        g->insertMeta("voxel_size_m", openvdb::DoubleMetadata(mH));
        for (const auto& [k, v] : metadata.strings) g->insertMeta(k, openvdb::StringMetadata(v));
        for (const auto& [k, v] : metadata.numbers) g->insertMeta(k, openvdb::DoubleMetadata(v));
    }
    namespace fs = std::filesystem;
    const fs::path target(path);
    const fs::path tmp = target.parent_path() / (target.filename().string() + ".tmp" + std::to_string(::getpid()));
    // openvdb::io::File::write never looks at its stream after writing, so a full disk gave a
    // truncated file and no error: write the same archive to a stream we check.
    struct CheckedArchive : openvdb::io::File {
        using openvdb::io::File::File;
        void writeTo(std::ostream& os, const openvdb::GridCPtrVec& grids) const {
            openvdb::io::Archive::write(os, grids, /*seekable=*/true, openvdb::MetaMap());
        }
    };
    try {
        std::ofstream os(tmp, std::ios_base::out | std::ios_base::binary | std::ios_base::trunc);
        if (!os) throw std::runtime_error(std::string("cannot create it: ") + std::strerror(errno));
        CheckedArchive(tmp.string()).writeTo(os, {vel, speed, faces});
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

}  // namespace gale::sim
