/// \file VdbRead.cpp
/// Reading gale's .vdb files back (sim/VdbIO.h), with bounded memory for a corrupt file
/// (docs/reliability.md); sim/VdbIO.cpp writes them.
#include <openvdb/io/File.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>

#include "sim/VdbFormat.h"
#include "sim/VdbIO.h"

namespace gale::sim {

namespace {

/// The size metadata OpenVDB writes beside a grid (voxel count, index bounding box, bytes in
/// memory), each null when the file lacks it: what the readers check before loading a grid.
struct SizeMetadata {
    openvdb::Int64Metadata::ConstPtr count, bytes;
    openvdb::Vec3IMetadata::ConstPtr lo, hi;
};

SizeMetadata sizeMetadata(const openvdb::GridBase& meta) {
    using openvdb::GridBase;
    return {meta.getMetadata<openvdb::Int64Metadata>(GridBase::META_FILE_VOXEL_COUNT),
            meta.getMetadata<openvdb::Int64Metadata>(GridBase::META_FILE_MEM_BYTES),
            meta.getMetadata<openvdb::Vec3IMetadata>(GridBase::META_FILE_BBOX_MIN),
            meta.getMetadata<openvdb::Vec3IMetadata>(GridBase::META_FILE_BBOX_MAX)};
}

using detail::CUBIC_FACES_GRID, detail::STRETCHED_FACES_GRID, detail::levelsText;

/// A .vdb refused by readFaceVelocities's own checks, told apart from other std::runtime_errors
/// (std::ios_base::failure is one) that OpenVDB's reading may throw.
struct VdbRefused : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// A corrupt or foreign .vdb: gale's own words, never OpenVDB's exception text.
[[noreturn]] void refuseVdb(const std::string& path, const std::string& reason) {
    throw VdbRefused(path + ": " + reason);
}

/// Checks what a .vdb says about itself before its trees are read, so that a corrupt file costs
/// bounded memory (docs/reliability.md): the file's size, and the face grid's own metadata (its
/// voxel count, bounding box and in-memory bytes, which OpenVDB writes beside each grid) against
/// what a field on `field`'s grid can hold. Returns the bytes the face grid may take in memory.
/// Throws std::runtime_error naming the file.
double checkVdbAgainstField(const std::string& path, openvdb::io::File& file, const char* facesName,
                            const WindField& field) {
    const double nx = field.nx(), ny = field.ny(),
                 nz = std::max(field.nz(), vdbCubicLayers(field.layout()));
    // A stretched file holds its native layers and a cubic resample: two fields; a margin of 2
    // over sim::vdbWindFile_bytes, itself an upper bound of the measured files (0.46-0.74).
    constexpr double FILE_BOUND_FACTOR = 4.0;
    constexpr double FILE_BOUND_SLACK_BYTES = 1 << 20;
    std::error_code ec;
    const double fileBytes = double(std::filesystem::file_size(path, ec));
    const double fileBound =
        FILE_BOUND_FACTOR * vdbWindFile_bytes(nx, ny, nz) + FILE_BOUND_SLACK_BYTES;
    if (!ec && fileBytes > fileBound)
        refuseVdb(path, "holds " + std::to_string(static_cast<long long>(fileBytes)) +
                            " bytes, more than a field of this scene's " +
                            std::to_string(field.nx()) + " x " + std::to_string(field.ny()) +
                            " x " + std::to_string(field.nz()) + " cells can take (" +
                            std::to_string(static_cast<long long>(fileBound)) +
                            "): not a field of this scene");
    const SizeMetadata m = sizeMetadata(*file.readGridMetadata(facesName));
    const auto& count = m.count;
    const auto &lo = m.lo, &hi = m.hi;
    const auto& bytes = m.bytes;
    if (!count || !lo || !hi || !bytes)
        refuseVdb(path, std::string("grid '") + facesName +
                            "' has no size metadata (file_voxel_count, file_bbox_min/max, "
                            "file_mem_bytes); write it with gale solve");
    const double faces = (nx + 1) * (ny + 1) * (nz + 1);
    // The 8^3 leaves and the 16^3 and 32^3 internal nodes that cover the face grid, at the
    // bytes OpenVDB allocates for a Vec3s tree (leaf: 512 values of 12 B and its masks; internal
    // nodes: one 8-byte slot per child and two masks), doubled for the allocator.
    const auto nodes = [&](double side) {
        return std::ceil((nx + 1) / side) * std::ceil((ny + 1) / side) * std::ceil((nz + 1) / side);
    };
    constexpr double LEAF_BYTES = 512 * 12 + 160, NODE16_BYTES = 4096 * 8 + 1024,
                     NODE32_BYTES = 32768 * 8 + 8192, MEMORY_MARGIN = 2.0;
    const double memoryBound = MEMORY_MARGIN * (nodes(8) * LEAF_BYTES + nodes(128) * NODE16_BYTES +
                                                nodes(4096) * NODE32_BYTES) +
                               FILE_BOUND_SLACK_BYTES;
    const openvdb::Vec3i a = lo->value(), b = hi->value();
    const bool boxInside = a.x() >= -1 && a.y() >= -1 && a.z() >= -1 && b.x() <= nx + 1 &&
                           b.y() <= ny + 1 && b.z() <= nz + 1;
    if (count->value() < 0 || double(count->value()) > faces || !boxInside || bytes->value() < 0 ||
        double(bytes->value()) > memoryBound)
        refuseVdb(path, std::string("grid '") + facesName + "' claims " +
                            std::to_string(count->value()) + " voxels in [" +
                            std::to_string(a.x()) + ", " + std::to_string(a.y()) + ", " +
                            std::to_string(a.z()) + "] .. [" + std::to_string(b.x()) + ", " +
                            std::to_string(b.y()) + ", " + std::to_string(b.z()) + "] and " +
                            std::to_string(bytes->value()) + " bytes, beyond the scene's " +
                            std::to_string(static_cast<long long>(faces)) +
                            " faces: a corrupt file, or not a field of this scene");
    return memoryBound;
}

/// Caps this process's address space (RLIMIT_AS) at what it maps at construction plus a budget,
/// for its lifetime, so that a corrupt size field in a .vdb (a metadata string's length, a
/// compressed chunk's length, a node count), which OpenVDB allocates as it reads, fails with
/// std::bad_alloc instead of taking gigabytes. Nothing is capped under the sanitizers, which map
/// their own shadow memory, or when the current size cannot be read. Only for a reading thread
/// while no other thread allocates.
class AddressSpaceCap {
  public:
    explicit AddressSpaceCap(double budget_bytes) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
        mUsable = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer) || \
    __has_feature(thread_sanitizer)
        mUsable = false;
#endif
#endif
        if (mUsable) start();
        widen(budget_bytes);
    }
    ~AddressSpaceCap() {
        if (mCapped) ::setrlimit(RLIMIT_AS, &mOld);
    }
    AddressSpaceCap(const AddressSpaceCap&) = delete;
    AddressSpaceCap& operator=(const AddressSpaceCap&) = delete;

    /// Sets the cap to the mapping at construction plus `budget_bytes` (never above the limit
    /// the process had).
    void widen(double budget_bytes) {
        if (!mUsable) return;
        const double want = mBaseline_bytes + budget_bytes;
        rlimit capped = mOld;
        if (mOld.rlim_cur == RLIM_INFINITY || double(mOld.rlim_cur) > want)
            capped.rlim_cur = static_cast<rlim_t>(want);
        mCapped = ::setrlimit(RLIMIT_AS, &capped) == 0 || mCapped;
    }

  private:
    void start() {
        mUsable = false;
        std::FILE* statm = std::fopen("/proc/self/statm", "r");
        if (!statm) return;
        unsigned long long pages = 0;
        const bool read = std::fscanf(statm, "%llu", &pages) == 1;
        std::fclose(statm);
        if (!read || ::getrlimit(RLIMIT_AS, &mOld) != 0) return;
        mBaseline_bytes = double(pages) * double(::sysconf(_SC_PAGESIZE));
        mUsable = true;
    }
    bool mUsable = true;
    double mBaseline_bytes = 0.0;
    rlimit mOld{};
    bool mCapped = false;
};

/// What a .vdb's header, metadata and grid descriptors may take in memory while they are read.
constexpr double VDB_HEADER_READ_BYTES = 256.0 * (1 << 20);

/// Refuses a path that is not a regular file (OpenVDB's "IoError: could not get size of file").
void refuseUnlessRegularVdb(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        refuseVdb(path,
                  std::filesystem::exists(path, ec) ? "is not a regular file" : "no such file");
}

/// Rethrows what reading `path` threw as gale's message: ours as it is, OpenVDB's and the
/// allocator's without their text.
[[noreturn]] void refuseUnreadableVdb(const std::string& path, const std::exception& e) {
    if (dynamic_cast<const VdbRefused*>(&e)) throw VdbRefused(e.what());
    if (dynamic_cast<const std::bad_alloc*>(&e))
        refuseVdb(path,
                  "not a readable .vdb file (corrupt: it claims more memory than a field "
                  "of this scene holds)");
    refuseVdb(path, "not a readable .vdb file (corrupt, truncated, or not written by OpenVDB)");
}

/// The grid's transform is the field's cells: the same voxel size and first cell centre, to
/// 1e-6 of a cell.
bool onFieldGrid(const openvdb::GridBase& grid, const WindField& field) {
    const double h = field.voxelSize_m(), tol = 1e-6 * h;
    const auto o = field.wsMin_m();
    const openvdb::Vec3d centre = grid.transform().indexToWorld(openvdb::Vec3d(0.0));
    return std::abs(grid.transform().voxelSize()[0] - h) <= tol &&
           std::abs(centre[0] - (o[0] + 0.5 * h)) <= tol &&
           std::abs(centre[1] - (o[1] + 0.5 * h)) <= tol &&
           std::abs(centre[2] - (o[2] + 0.5 * h)) <= tol;
}

}  // namespace

double readFaceVelocities(const std::string& path, WindField& field) {
    openvdb::initialize();
    const bool stretched = !field.layout().uniformZ();
    const char* facesName = stretched ? STRETCHED_FACES_GRID : CUBIC_FACES_GRID;
    openvdb::GridBase::Ptr base;
    refuseUnlessRegularVdb(path);
    // The file's header, metadata and grid descriptors first, within a small budget; then the
    // face grid's trees within what its checked metadata allows.
    try {
        AddressSpaceCap cap(VDB_HEADER_READ_BYTES);
        openvdb::io::File file(path);
        file.open(/*delayLoad=*/false);
        if (!file.hasGrid(facesName)) {
            file.close();
            refuseVdb(path, std::string("has no grid '") + facesName +
                                "' (write it with gale solve" +
                                (stretched ? ", stretched layers" : "") + ")");
        }
        const double gridBytes = checkVdbAgainstField(path, file, facesName, field);
        // The grid, OpenVDB's read buffers and a margin for the allocator's own mappings.
        cap.widen(2.0 * gridBytes + VDB_HEADER_READ_BYTES);
        base = file.readGrid(facesName);
        file.close();
    } catch (const openvdb::Exception&) {
        // OpenVDB's own text ("LookupError: Cannot read grid. Grid type  is not registered.")
        // says nothing a user can act on.
        refuseVdb(path, "not a readable .vdb file (corrupt, truncated, or not written by OpenVDB)");
    } catch (const std::bad_alloc&) {
        refuseVdb(path,
                  "not a readable .vdb file (corrupt: its trees claim more memory than a "
                  "field of this scene holds)");
    } catch (const VdbRefused&) {
        throw;  // ours, naming the file
    } catch (const std::exception&) {
        refuseVdb(path, "not a readable .vdb file (corrupt, truncated, or not written by OpenVDB)");
    }
    auto grid = openvdb::gridPtrCast<openvdb::Vec3SGrid>(base);
    if (!grid) throw std::runtime_error(path + ": grid '" + facesName + "' is not a Vec3s grid");
    if (stretched) {
        const auto levels = grid->getMetadata<openvdb::StringMetadata>("z_levels_m");
        if (!levels || levels->value() != levelsText(field.layout()))
            throw std::runtime_error(path +
                                     ": solved on other layers (z_levels_m) than the "
                                     "scene's stretched layers");
    }
    const double h = field.voxelSize_m();
    const auto o = field.wsMin_m();
    const openvdb::Vec3d centre = grid->transform().indexToWorld(openvdb::Vec3d(0.0));
    const double fileH = grid->transform().voxelSize()[0];
    if (!onFieldGrid(*grid, field))
        throw std::runtime_error(path + ": solved on another grid (voxel " + std::to_string(fileH) +
                                 " m, first cell centre at " + std::to_string(centre[0]) + ", " +
                                 std::to_string(centre[1]) + ", " + std::to_string(centre[2]) +
                                 ") than the scene's (voxel " + std::to_string(h) + " m, " +
                                 std::to_string(o[0] + 0.5 * h) + ", " +
                                 std::to_string(o[1] + 0.5 * h) + ", " +
                                 std::to_string(o[2] + 0.5 * h) + ")");
    auto acc = grid->getConstAccessor();
    const int nx = field.nx(), ny = field.ny(), nz = field.nz();
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) {
                const openvdb::Vec3s v = acc.getValue(openvdb::Coord(i, j, k));
                const GridLayout& g = field.layout();
                if (j < ny && k < nz) field.u_mps()[g.faceXIndex(i, j, k)] = v.x();
                if (i < nx && k < nz) field.v_mps()[g.faceYIndex(i, j, k)] = v.y();
                if (i < nx && j < ny) field.w_mps()[g.faceZIndex(i, j, k)] = v.z();
            }
    const auto time = grid->getMetadata<openvdb::DoubleMetadata>("time_s");
    return time ? time->value() : std::nan("");
}

std::vector<double> readCellTke(const std::string& path, const WindField& field) {
    openvdb::initialize();
    const GridLayout& g = field.layout();
    const char* name = g.uniformZ() ? TKE_GRID : TKE_LAYERS_GRID;
    refuseUnlessRegularVdb(path);
    openvdb::GridBase::Ptr base;
    try {
        // Checked as readFaceVelocities checks its grid: the descriptors within a small budget,
        // the tree only when its metadata says it fits the field's cells.
        AddressSpaceCap cap(VDB_HEADER_READ_BYTES);
        openvdb::io::File file(path);
        file.open(/*delayLoad=*/false);
        if (!file.hasGrid(name)) {
            file.close();
            return {};
        }
        const SizeMetadata m = sizeMetadata(*file.readGridMetadata(name));
        const auto& count = m.count;
        const auto &lo = m.lo, &hi = m.hi;
        const bool emptyGrid = count && count->value() == 0;
        if (!count || (!emptyGrid && (!lo || !hi)) || count->value() < 0 ||
            double(count->value()) > double(g.cellCount()) ||
            (!emptyGrid &&
             (lo->value().x() < 0 || lo->value().y() < 0 || lo->value().z() < 0 ||
              hi->value().x() >= g.nx || hi->value().y() >= g.ny || hi->value().z() >= g.nz)))
            refuseVdb(path, std::string("grid '") + name +
                                "' has no size metadata or lies outside the scene's cells: a "
                                "corrupt file, or not a field of this scene");
        // A float per cell in 8^3 leaves, doubled for the allocator, and the slack of the read.
        cap.widen(2.0 * (4.0 + 1.0) * double(g.cellCount()) + 2.0 * VDB_HEADER_READ_BYTES);
        base = file.readGrid(name);
        file.close();
    } catch (const std::exception& e) {
        refuseUnreadableVdb(path, e);
    }
    auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
    if (!grid) throw std::runtime_error(path + ": grid '" + name + "' is not a float grid");
    if (!onFieldGrid(*grid, field))
        throw std::runtime_error(path + ": grid '" + name +
                                 "' sits on another grid than the "
                                 "scene's (voxel size or origin)");
    if (!g.uniformZ()) {
        const auto levels = grid->getMetadata<openvdb::StringMetadata>("z_levels_m");
        if (!levels || levels->value() != levelsText(g))
            throw std::runtime_error(path + ": grid '" + name +
                                     "' sits on other layers (z_levels_m) than the scene's");
    }
    std::vector<double> tke(g.cellCount(), 0.0);
    auto acc = grid->getConstAccessor();
    for (int k = 0; k < g.nz; ++k)
        for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i)
                if (field.isAir(i, j, k))
                    tke[g.cellIndex(i, j, k)] = acc.getValue(openvdb::Coord(i, j, k));
    return tke;
}

std::vector<std::string> vdbGridNames(const std::string& path) {
    openvdb::initialize();
    std::vector<std::string> names;
    refuseUnlessRegularVdb(path);
    try {
        // The header and descriptors within a small budget (a corrupt length took 3.1 GB).
        const AddressSpaceCap cap(VDB_HEADER_READ_BYTES);
        openvdb::io::File file(path);
        file.open(/*delayLoad=*/false);
        for (auto it = file.beginName(); it != file.endName(); ++it) names.push_back(*it);
        file.close();
    } catch (const std::exception& e) {
        refuseUnreadableVdb(path, e);
    }
    return names;
}

std::map<std::string, std::string> vdbGridStrings(const std::string& path,
                                                  const std::string& gridName) {
    openvdb::initialize();
    std::map<std::string, std::string> strings;
    openvdb::GridBase::Ptr grid;
    refuseUnlessRegularVdb(path);
    try {
        const AddressSpaceCap cap(VDB_HEADER_READ_BYTES);
        openvdb::io::File file(path);
        file.open(/*delayLoad=*/false);
        if (!file.hasGrid(gridName)) {
            file.close();
            refuseVdb(path, "has no grid '" + gridName + "'");
        }
        grid = file.readGridMetadata(gridName);
        file.close();
    } catch (const std::exception& e) {
        refuseUnreadableVdb(path, e);
    }
    for (auto it = grid->beginMeta(); it != grid->endMeta(); ++it)
        if (const auto text = grid->getMetadata<openvdb::StringMetadata>(it->first))
            strings[it->first] = text->value();
    return strings;
}

}  // namespace gale::sim
