/// \file ImageIO.cpp
/// Atomic image writes and RGBA8 reads through OpenImageIO (STYLE: never write a half file).

#include "render/ImageIO.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace gale::render {
namespace {

namespace fs = std::filesystem;

/// "<dir>/.<stem>.tmp<pid>.<ext>": same folder (so rename is atomic), same extension (OIIO picks
/// the format from it), hidden, and distinct per process.
fs::path tempPathFor(const fs::path& target) {
    fs::path temp = target.parent_path();
    temp /= "." + target.stem().string() + ".tmp" + std::to_string(::getpid()) +
            target.extension().string();
    return temp;
}

[[noreturn]] void failWrite(const std::string& path, const std::string& reason,
                            const fs::path& temp) {
    std::error_code ignored;
    if (!temp.empty()) fs::remove(temp, ignored);
    throw std::runtime_error("cannot write image '" + path + "': " + reason);
}

}  // namespace

void writeImageAtomic(const Image& image, const std::string& path) {
    if (image.width < 1 || image.height < 1 ||
        image.rgba.size() != static_cast<size_t>(image.width) * image.height * 4u) {
        failWrite(path,
                  "image is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                      " with " + std::to_string(image.rgba.size()) +
                      " bytes; expected a non-empty RGBA8 image of width * height * 4 bytes",
                  {});
    }
    const fs::path target(path);
    if (target.filename().empty() || target.extension().empty()) {
        failWrite(path, "the file name needs an extension (.png, .exr, .jpg ...) to pick a format",
                  {});
    }
    const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) {
        failWrite(path,
                  "folder '" + folder.string() +
                      (fs::exists(folder, ec) ? "' is not a directory" : "' does not exist"),
                  {});
    }
    const fs::path temp = tempPathFor(target);

    auto out = OIIO::ImageOutput::create(temp.string());
    if (!out) {
        failWrite(path,
                  "no image writer for extension '" + target.extension().string() +
                      "': " + OIIO::geterror(),
                  {});
    }
    // Formats without alpha (JPEG ...) get RGB only.
    const int channels = out->supports("alpha") ? 4 : 3;
    // OpenEXR holds linear light in half floats: decode the frame's sRGB (IEC 61966-2-1) to linear
    // (alpha stays as it is), rather than let OIIO store the 8-bit codes as if they were linear.
    std::string ext = target.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const bool linearHalf = ext == ".exr";
    OIIO::ImageSpec spec(image.width, image.height, channels,
                         linearHalf ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::UINT8);
    if (channels == 4) spec.alpha_channel = 3;
    // Our alpha is data (blade height) beside straight colour: tell OIIO not to un-premultiply.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    if (!out->open(temp.string(), spec)) {
        const std::string reason = out->geterror();
        out.reset();
        failWrite(path, "cannot open it: " + reason, temp);
    }
    bool ok = true;
    if (linearHalf) {
        float decode[256];
        for (int v = 0; v < 256; ++v) {
            const float c = static_cast<float>(v) / 255.0f;
            decode[v] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
        }
        std::vector<float> pixels(static_cast<size_t>(image.width) * image.height * channels);
        for (size_t t = 0, n = pixels.size() / channels; t < n; ++t) {
            for (int c = 0; c < 3; ++c) pixels[t * channels + c] = decode[image.rgba[t * 4 + c]];
            if (channels == 4)
                pixels[t * 4 + 3] = static_cast<float>(image.rgba[t * 4 + 3]) / 255.0f;
        }
        ok = out->write_image(OIIO::TypeDesc::FLOAT, pixels.data());
    } else if (channels == 4) {
        ok = out->write_image(OIIO::TypeDesc::UINT8, image.rgba.data());
    } else {
        std::vector<uint8_t> rgb(static_cast<size_t>(image.width) * image.height * 3u);
        for (size_t t = 0, n = rgb.size() / 3; t < n; ++t) {
            for (int c = 0; c < 3; ++c) rgb[t * 3 + c] = image.rgba[t * 4 + c];
        }
        ok = out->write_image(OIIO::TypeDesc::UINT8, rgb.data());
    }
    std::string reason = ok ? std::string() : out->geterror();
    if (!out->close() && ok) {
        ok = false;
        reason = out->geterror();
    }
    out.reset();
    if (!ok) failWrite(path, "writing failed: " + reason, temp);

    fs::rename(temp, target, ec);
    if (ec) failWrite(path, "rename from '" + temp.string() + "' failed: " + ec.message(), temp);
}

bool canWriteImageFormat(const std::string& path) {
    const fs::path target(path);
    if (target.extension().empty()) return false;
    return OIIO::ImageOutput::create(target.string()) != nullptr;
}

Image readImageRgba8(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) {
        throw std::runtime_error("cannot read image '" + path + "': no such file");
    }
    // Keep colour and alpha as stored (no premultiplication): alpha is blade height, not coverage.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) {
        throw std::runtime_error("cannot read image '" + path + "': " + OIIO::geterror());
    }
    const OIIO::ImageSpec& spec = in->spec();
    const int channels = spec.nchannels;
    if (spec.width < 1 || spec.height < 1 || channels < 1) {
        throw std::runtime_error("cannot read image '" + path + "': empty image (" +
                                 std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                                 ", " + std::to_string(channels) + " channels)");
    }
    if (spec.depth > 1) {
        throw std::runtime_error("cannot read image '" + path +
                                 "': volume images are not supported");
    }
    const size_t texels = static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height);
    std::vector<uint8_t> raw(texels * static_cast<size_t>(channels));
    // OIIO converts 16-bit and float to UINT8 here (clamped to [0, 1] and scaled).
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, raw.data())) {
        std::string reason = in->geterror();
        if (reason.empty()) reason = "read failed (truncated or corrupt file?)";
        throw std::runtime_error("cannot read image '" + path + "': " + reason);
    }
    in->close();

    Image image;
    image.width = spec.width;
    image.height = spec.height;
    image.rgba.resize(texels * 4u);
    const int alphaChannel = spec.alpha_channel >= 0
                                 ? spec.alpha_channel
                                 : (channels == 2 ? 1 : (channels >= 4 ? 3 : -1));
    for (size_t t = 0; t < texels; ++t) {
        const uint8_t* src = &raw[t * channels];
        uint8_t* dst = &image.rgba[t * 4u];
        if (channels < 3) {  // grey, or grey + alpha
            dst[0] = dst[1] = dst[2] = src[0];
        } else {
            dst[0] = src[0];
            dst[1] = src[1];
            dst[2] = src[2];
        }
        dst[3] = alphaChannel >= 0 && alphaChannel < channels ? src[alphaChannel] : 255;
    }
    return image;
}

}  // namespace gale::render
