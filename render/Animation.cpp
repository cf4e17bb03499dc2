/// \file Animation.cpp
/// Contact sheets and animated GIFs (see Animation.h).

#include "render/Animation.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "render/ImageIO.h"

namespace gale::render {
namespace {

namespace fs = std::filesystem;

// Sheet background and gap between thumbnails, pixels.
constexpr uint8_t SHEET_BACKGROUND = 32;
constexpr int SHEET_GAP = 4;

fs::path hiddenTemp(const std::string& path) {
    const fs::path target(path);
    return target.parent_path() / ("." + target.stem().string() + ".tmp" +
                                   std::to_string(::getpid()) + target.extension().string());
}

}  // namespace

Image downscale(const Image& src, int width, int height) {
    if (width < 1 || height < 1 || width > src.width || height > src.height)
        throw std::logic_error("downscale: target " + std::to_string(width) + "x" +
                               std::to_string(height) + " must be within the source " +
                               std::to_string(src.width) + "x" + std::to_string(src.height));
    Image out;
    out.width = width;
    out.height = height;
    out.rgba.resize(static_cast<size_t>(width) * height * 4);
    const double sx = double(src.width) / width, sy = double(src.height) / height;
    for (int y = 0; y < height; ++y) {
        const int y0 = static_cast<int>(y * sy),
                  y1 = std::max(y0 + 1, static_cast<int>((y + 1) * sy));
        for (int x = 0; x < width; ++x) {
            const int x0 = static_cast<int>(x * sx),
                      x1 = std::max(x0 + 1, static_cast<int>((x + 1) * sx));
            unsigned sum[4] = {0, 0, 0, 0};
            for (int yy = y0; yy < y1; ++yy)
                for (int xx = x0; xx < x1; ++xx)
                    for (int c = 0; c < 4; ++c)
                        sum[c] += src.rgba[(static_cast<size_t>(yy) * src.width + xx) * 4 + c];
            const unsigned n = static_cast<unsigned>((y1 - y0) * (x1 - x0));
            for (int c = 0; c < 4; ++c)
                out.rgba[(static_cast<size_t>(y) * width + x) * 4 + c] =
                    static_cast<uint8_t>((sum[c] + n / 2) / n);
        }
    }
    return out;
}

struct AnimationWriter::Impl {
    AnimationOptions options;
    int totalFrames = 0;
    std::vector<int> sheetIndices;
    std::vector<Image> thumbs;
    std::unique_ptr<OIIO::ImageOutput> gif;
    fs::path gifTemp;
    int gifWidth = 0, gifHeight = 0;
    bool gifOpen = false;
    bool finished = false;

    void openGif(const Image& first) {
        gifWidth = std::min(first.width, options.gifMaxWidth);
        gifHeight = std::max(
            1, static_cast<int>(std::lround(double(first.height) * gifWidth / first.width)));
        gifTemp = hiddenTemp(options.gifPath);
        gif = OIIO::ImageOutput::create(gifTemp.string());
        if (!gif)
            throw std::runtime_error("cannot write '" + options.gifPath +
                                     "': no GIF writer in OpenImageIO");
        OIIO::ImageSpec spec(gifWidth, gifHeight, 4, OIIO::TypeDesc::UINT8);
        spec.alpha_channel = 3;
        const int fps100 = static_cast<int>(std::lround(options.fps * 100.0));
        const int rate[2] = {fps100, 100};
        spec.attribute("FramesPerSecond", OIIO::TypeRational, rate);
        spec.attribute("gif:LoopCount", 0);  // loop forever
        if (!gif->open(gifTemp.string(), spec))
            throw std::runtime_error("cannot write '" + options.gifPath + "': " + gif->geterror());
        gifOpen = true;
    }

    void appendGif(const Image& frame, bool first) {
        Image small = (frame.width == gifWidth && frame.height == gifHeight)
                          ? frame
                          : downscale(frame, gifWidth, gifHeight);
        // GIF has no partial transparency: every pixel of a frame is opaque.
        for (size_t p = 3; p < small.rgba.size(); p += 4) small.rgba[p] = 255;
        if (!first) {
            OIIO::ImageSpec spec(gifWidth, gifHeight, 4, OIIO::TypeDesc::UINT8);
            spec.alpha_channel = 3;
            if (!gif->open(gifTemp.string(), spec, OIIO::ImageOutput::AppendSubimage))
                throw std::runtime_error("cannot add a frame to '" + options.gifPath +
                                         "': " + gif->geterror());
        }
        if (!gif->write_image(OIIO::TypeDesc::UINT8, small.rgba.data()))
            throw std::runtime_error("cannot write a frame of '" + options.gifPath +
                                     "': " + gif->geterror());
    }
};

std::vector<int> AnimationWriter::sheetIndices(int totalFrames, int sheetFrames) {
    std::vector<int> out;
    const int n = std::min(totalFrames, std::max(1, sheetFrames));
    for (int j = 0; j < n; ++j)
        out.push_back(
            n == 1 ? 0 : static_cast<int>(std::lround(double(j) * (totalFrames - 1) / (n - 1))));
    return out;
}

AnimationWriter::AnimationWriter(const AnimationOptions& options, int totalFrames)
    : mImpl(std::make_unique<Impl>()) {
    if (totalFrames < 1)
        throw ParameterError("output.frames", std::to_string(totalFrames), "must be >= 1");
    if (!(options.fps > 0.0) || !std::isfinite(options.fps))
        throw ParameterError("output.fps", formatG(options.fps), "must be finite and > 0");
    mImpl->options = options;
    mImpl->totalFrames = totalFrames;
    if (!options.sheetPath.empty())
        mImpl->sheetIndices = sheetIndices(totalFrames, options.sheetFrames);
}

AnimationWriter::~AnimationWriter() {
    if (mImpl && !mImpl->finished && mImpl->gifOpen) {
        mImpl->gif->close();
        std::error_code ignored;
        fs::remove(mImpl->gifTemp, ignored);
    }
}

void AnimationWriter::addFrame(const Image& frame, int index) {
    Impl& m = *mImpl;
    if (!m.options.gifPath.empty()) {
        const bool first = !m.gifOpen;
        if (first) m.openGif(frame);
        m.appendGif(frame, first);
    }
    if (std::find(m.sheetIndices.begin(), m.sheetIndices.end(), index) != m.sheetIndices.end()) {
        const int w = std::min(frame.width, m.options.sheetThumbWidth);
        const int h =
            std::max(1, static_cast<int>(std::lround(double(frame.height) * w / frame.width)));
        m.thumbs.push_back(downscale(frame, w, h));
    }
}

void AnimationWriter::finish() {
    Impl& m = *mImpl;
    if (m.gifOpen) {
        if (!m.gif->close())
            throw std::runtime_error("cannot finish '" + m.options.gifPath +
                                     "': " + m.gif->geterror());
        std::error_code ec;
        fs::rename(m.gifTemp, m.options.gifPath, ec);
        if (ec) {
            fs::remove(m.gifTemp, ec);
            throw std::runtime_error("cannot move the GIF into place at '" + m.options.gifPath +
                                     "'");
        }
    }
    if (!m.options.sheetPath.empty() && !m.thumbs.empty()) {
        const int cols =
            std::max(1, std::min(m.options.sheetColumns, static_cast<int>(m.thumbs.size())));
        const int rows = (static_cast<int>(m.thumbs.size()) + cols - 1) / cols;
        const int tw = m.thumbs[0].width, th = m.thumbs[0].height;
        Image sheet;
        sheet.width = cols * tw + (cols + 1) * SHEET_GAP;
        sheet.height = rows * th + (rows + 1) * SHEET_GAP;
        sheet.rgba.assign(static_cast<size_t>(sheet.width) * sheet.height * 4, SHEET_BACKGROUND);
        for (size_t p = 3; p < sheet.rgba.size(); p += 4) sheet.rgba[p] = 255;
        for (size_t k = 0; k < m.thumbs.size(); ++k) {
            const Image& t = m.thumbs[k];
            const int ox = SHEET_GAP + static_cast<int>(k % cols) * (tw + SHEET_GAP);
            const int oy = SHEET_GAP + static_cast<int>(k / cols) * (th + SHEET_GAP);
            for (int y = 0; y < std::min(th, t.height); ++y)
                std::copy_n(
                    t.rgba.data() + static_cast<size_t>(y) * t.width * 4, std::min(tw, t.width) * 4,
                    sheet.rgba.data() + (static_cast<size_t>(oy + y) * sheet.width + ox) * 4);
        }
        writeImageAtomic(sheet, m.options.sheetPath);
    }
    m.finished = true;
}

}  // namespace gale::render
