#pragma once
/// \file Heightmap.h
/// Terrain from a greyscale image, read through OpenImageIO, and back. Pixel (col, row) of a
/// W x H image, rows top-down, becomes sample (i, j) = (col, H - 1 - row): the top row is the
/// far edge y = (H - 1) * metres_per_pixel, the left column x = 0 (north up, as on a map).
/// height_m = heightOffset_m + heightScale_m * value, where value is the first channel, in [0, 1]
/// for 8- and 16-bit integer images and raw for float images.

#include <string>

#include "sim/Heightfield.h"

namespace gale::app {

struct HeightmapSpec {
    std::string path;             ///< image file (PNG, TIFF, EXR, ... anything OIIO reads)
    double metresPerPixel = 1.0;  ///< sample spacing, metres
    double heightScale_m = 10.0;  ///< height of value 1.0 (white), metres
    double heightOffset_m = 0.0;  ///< height of value 0.0 (black), metres
    int meshStride = 1;           ///< render mesh stride, for the memory estimate only
};

/// What an image's header says, read without decoding pixels.
struct ImageHeader {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::string format;     ///< e.g. "png"
    std::string pixelType;  ///< e.g. "uint16", "float"
};

/// Reads the header of any image (no checks beyond "it is a readable image"). Throws ImageError
/// ("PATH: reason") for a missing, empty or unreadable file.
ImageHeader readImageHeader(const std::string& path);

/// Reads the header of `path` as a heightmap. Throws ImageError ("PATH: reason") for a missing or
/// unreadable file, a file that is not an image, a volume or deep image, fewer than 2 x 2 pixels,
/// more than MAX_SAMPLES_PER_SIDE pixels per side, or a grid whose mesh would exceed
/// MAX_TERRAIN_BYTES.
ImageHeader readHeightmapHeader(const std::string& path, int meshStride = 1);

/// Loads the heightmap into a heightfield via sim::makeHeightfield. Checks the header before
/// reading pixels; throws ImageError for everything readHeightmapHeader rejects, for truncated or
/// corrupt pixel data, and for NaN or infinite pixels (naming the first one).
sim::Heightfield loadHeightmap(const HeightmapSpec& spec);

/// Height range written by writeHeightmapPng16.
struct HeightmapRange {
    double minHeight_m = 0.0;  ///< height of black (value 0)
    double maxHeight_m = 0.0;  ///< height of white (value 65535)
};

/// Writes `field` as a 16-bit greyscale PNG (black = its lowest sample, white = its highest; a flat
/// field is all black), in the orientation loadHeightmap reads, atomically (temporary file in the
/// same folder, then rename). Loading it back with metres_per_pixel = spacing_m, height_offset_m =
/// min and height_scale_m = max - min reproduces the heights to (max - min) / 131070.
/// Throws std::runtime_error naming the path if the file cannot be written.
HeightmapRange writeHeightmapPng16(const sim::Heightfield& field, const std::string& path);

}  // namespace gale::app
