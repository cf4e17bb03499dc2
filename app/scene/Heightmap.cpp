#include "app/scene/Heightmap.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/io/QuietStderr.h"
#include "app/scene/SceneParser.h"

namespace gale::app {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& path, const std::string& reason) {
    throw ImageError(path + ": " + reason);
}

/// The first line of an OpenImageIO error (later lines repeat it in libpng's words).
std::string oneLine(std::string s) {
    s = s.substr(0, s.find('\n'));
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s.empty() ? "unknown error" : s;
}

std::unique_ptr<OIIO::ImageInput> openImage(const std::string& path) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) fail(path, "no such file");
    if (fs::is_directory(st)) fail(path, "is a folder, not an image");
    if (fs::is_regular_file(st) && fs::file_size(path, ec) == 0)
        fail(path, "empty file, not an image");
    std::unique_ptr<OIIO::ImageInput> in;
    {
        QuietStderr quiet;
        in = OIIO::ImageInput::open(path);
    }
    if (!in) fail(path, "not a readable image (" + oneLine(OIIO::geterror()) + ")");
    return in;
}

ImageHeader checkHeader(const std::string& path, const OIIO::ImageSpec& spec, const char* format,
                        int meshStride) {
    ImageHeader h;
    h.width = spec.width;
    h.height = spec.height;
    h.channels = spec.nchannels;
    h.format = format;
    h.pixelType = spec.format.c_str();
    const std::string dims = std::to_string(h.width) + " x " + std::to_string(h.height);
    if (spec.depth > 1)
        fail(path, "a volume image (depth " + std::to_string(spec.depth) + ") is not a heightmap");
    if (spec.deep) fail(path, "a deep image is not a heightmap");
    if (h.channels < 1) fail(path, "the image has no channels");
    if (h.width < 2 || h.height < 2)
        fail(path, "too small for a heightmap (" + dims + " pixels; need at least 2 x 2)");
    if (h.width > MAX_SAMPLES_PER_SIDE || h.height > MAX_SAMPLES_PER_SIDE)
        fail(path, "too large for a heightmap (" + dims + " pixels; at most " +
                       std::to_string(MAX_SAMPLES_PER_SIDE) + " per side)");
    const double bytes = estimateTerrainBytes(h.width, h.height, std::max(1, meshStride));
    if (bytes > MAX_TERRAIN_BYTES)
        fail(path, "a " + dims + " heightmap and its render mesh need about " + formatBytes(bytes) +
                       "; at most " + formatBytes(MAX_TERRAIN_BYTES) +
                       " (raise terrain.mesh_stride or shrink the image)");
    return h;
}

}  // namespace

ImageHeader readImageHeader(const std::string& path) {
    auto in = openImage(path);
    const OIIO::ImageSpec& spec = in->spec();
    ImageHeader h;
    h.width = spec.width;
    h.height = spec.height;
    h.channels = spec.nchannels;
    h.format = in->format_name();
    h.pixelType = spec.format.c_str();
    in->close();
    return h;
}

ImageHeader readHeightmapHeader(const std::string& path, int meshStride) {
    auto in = openImage(path);
    ImageHeader h = checkHeader(path, in->spec(), in->format_name(), meshStride);
    in->close();
    return h;
}

sim::Heightfield loadHeightmap(const HeightmapSpec& spec) {
    auto in = openImage(spec.path);
    const ImageHeader h = checkHeader(spec.path, in->spec(), in->format_name(), spec.meshStride);
    const size_t count = static_cast<size_t>(h.width) * h.height;
    std::vector<float> value(count);
    // The first channel only, converted to float: integer types become [0, 1], floats stay raw.
    bool read;
    {
        QuietStderr quiet;
        read = in->read_image(/*subimage=*/0, /*miplevel=*/0, /*chbegin=*/0, /*chend=*/1,
                              OIIO::TypeDesc::FLOAT, value.data());
    }
    if (!read) {
        fail(spec.path, "truncated or corrupt image data (" + oneLine(in->geterror()) + ")");
    }
    in->close();

    std::vector<float> height_m(count);
    for (int row = 0; row < h.height; ++row) {
        const int j = h.height - 1 - row;  // top row is the far (max y) edge
        for (int col = 0; col < h.width; ++col) {
            const float v = value[static_cast<size_t>(row) * h.width + col];
            if (!std::isfinite(v))
                fail(spec.path, std::string(std::isnan(v) ? "NaN" : "infinite") +
                                    " pixel at column " + std::to_string(col) + ", row " +
                                    std::to_string(row) + " (heights must be finite)");
            const double z = spec.heightOffset_m + spec.heightScale_m * static_cast<double>(v);
            if (!std::isfinite(z) || std::abs(z) > 1e7) {
                char shown[32];
                std::snprintf(shown, sizeof shown, "%.6g", z);
                fail(spec.path, "pixel at column " + std::to_string(col) + ", row " +
                                    std::to_string(row) + " gives an absurd height of " + shown +
                                    " m (at most 1e7 m)");
            }
            height_m[static_cast<size_t>(j) * h.width + col] = static_cast<float>(z);
        }
    }
    try {
        return sim::makeHeightfield(h.width, h.height, spec.metresPerPixel, std::move(height_m));
    } catch (const std::invalid_argument& e) {
        fail(spec.path, e.what());
    }
}

HeightmapRange writeHeightmapPng16(const sim::Heightfield& field, const std::string& path) {
    if (field.nx < 1 || field.ny < 1 ||
        field.height_m.size() != static_cast<size_t>(field.nx) * field.ny)
        throw std::runtime_error(path + ": cannot write an empty heightfield");
    HeightmapRange range{field.minHeight_m(), field.maxHeight_m()};
    const double span_m = range.maxHeight_m - range.minHeight_m;
    std::vector<uint16_t> pixels(field.height_m.size());
    for (int row = 0; row < field.ny; ++row) {
        const int j = field.ny - 1 - row;
        for (int i = 0; i < field.nx; ++i) {
            const double v = span_m > 0.0 ? (field.at(i, j) - range.minHeight_m) / span_m : 0.0;
            pixels[static_cast<size_t>(row) * field.nx + i] =
                static_cast<uint16_t>(std::lround(std::clamp(v, 0.0, 1.0) * 65535.0));
        }
    }
    const std::string tmp = temporaryPathFor(path);
    auto out = OIIO::ImageOutput::create(tmp);
    if (!out) throw std::runtime_error(path + ": cannot write (" + oneLine(OIIO::geterror()) + ")");
    OIIO::ImageSpec spec(field.nx, field.ny, 1, OIIO::TypeDesc::UINT16);
    spec.channelnames = {"Y"};
    const bool ok = out->open(tmp, spec) &&
                    out->write_image(OIIO::TypeDesc::UINT16, pixels.data()) && out->close();
    if (!ok) {
        const std::string why = oneLine(out->geterror());
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw std::runtime_error(path + ": cannot write (" + why + ")");
    }
    commitTemporary(tmp, path);
    return range;
}

}  // namespace gale::app
