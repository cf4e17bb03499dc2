#pragma once
/// \file ImageIO.h
/// Images in and out through OpenImageIO. Writes are atomic: a temporary file in the same folder,
/// then a rename, so a crash or Ctrl-C never leaves half an image.

#include <string>

#include "render/GrassInput.h"

namespace gale::render {

/// Writes `image` to `path` (format from the extension: .png, .exr, .jpg ...). An .exr gets half
/// floats of linear light (the sRGB codes decoded; alpha / 255), the OpenEXR convention. Throws
/// std::runtime_error naming the path and the reason.
void writeImageAtomic(const Image& image, const std::string& path);

/// Whether writeImageAtomic has a writer for `path`'s extension (OpenImageIO's plugins), checked
/// before a run so that a bad name is refused before any work.
bool canWriteImageFormat(const std::string& path);

/// Reads an 8-bit RGBA image (grey and RGB are expanded; 16-bit and float converted). Throws
/// std::runtime_error naming the path and the reason.
Image readImageRgba8(const std::string& path);

}  // namespace gale::render
