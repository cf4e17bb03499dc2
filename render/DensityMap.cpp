#include "render/DensityMap.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "render/ImageIO.h"

namespace gale::render {

namespace fs = std::filesystem;

DensityMap loadDensityMap(const std::string& path, glm::vec2 wsMin_m, glm::vec2 wsSize_m) {
    if (!(std::isfinite(wsSize_m.x) && std::isfinite(wsSize_m.y) && wsSize_m.x > 0.0f &&
          wsSize_m.y > 0.0f && std::isfinite(wsMin_m.x) && std::isfinite(wsMin_m.y))) {
        throw std::logic_error("density map '" + path +
                               "': the plan rectangle it covers must be finite with a "
                               "positive size");
    }
    const auto fail = [&](const std::string& reason) {
        throw std::runtime_error(path + ": " + reason);
    };
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) fail("no such file");
    if (fs::is_directory(st)) fail("is a folder, not an image");
    auto in = OIIO::ImageInput::open(path);
    if (!in) fail("not an image OpenImageIO can read (" + OIIO::geterror() + ")");
    // The header decides what is allocated: check it before reading a pixel.
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1 || spec.depth > 1)
        fail("empty or volume image (" + std::to_string(spec.width) + " x " +
             std::to_string(spec.height) + ")");
    if (spec.width > MAX_DENSITY_MAP_SIDE_PX || spec.height > MAX_DENSITY_MAP_SIDE_PX)
        fail("the header claims " + std::to_string(spec.width) + " x " +
             std::to_string(spec.height) + " pixels; a density map has at most " +
             std::to_string(MAX_DENSITY_MAP_SIDE_PX) + " per side");
    const double texels = double(spec.width) * double(spec.height);
    if (fs::is_regular_file(st)) {
        // Deflate cannot compress beyond 1032:1, so a PNG this small cannot hold this many
        // pixels: the header is corrupt (a 69-byte file claiming 8192 x 8192).
        constexpr double DEFLATE_MAX_RATIO = 1032.0;
        const double fileBytes = double(fs::file_size(path, ec));
        const double rawBytes =
            double(spec.height) * (1.0 + double(spec.width) * spec.nchannels * spec.format.size());
        if (!ec && std::string(in->format_name()) == "png" &&
            fileBytes * DEFLATE_MAX_RATIO < rawBytes)
            fail("the header claims " + std::to_string(spec.width) + " x " +
                 std::to_string(spec.height) + " pixels but the file has only " +
                 std::to_string(static_cast<long long>(fileBytes)) +
                 " bytes, fewer than any PNG of that size: the file is corrupt");
    }
    DensityMap map;
    map.width = spec.width;
    map.height = spec.height;
    map.wsMin_m = wsMin_m;
    map.wsSize_m = wsSize_m;
    map.density.resize(static_cast<size_t>(texels));
    // The first channel (a grey image's grey), as float: 8- and 16-bit images arrive scaled to
    // [0, 1]; float images as stored, so out-of-range values can be refused below.
    if (!in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, map.density.data())) {
        std::string reason = in->geterror();
        if (reason.empty()) reason = "read failed (truncated or corrupt file?)";
        fail("cannot read the pixels: " + reason);
    }
    in->close();
    for (size_t t = 0; t < map.density.size(); ++t) {
        const float d = map.density[t];
        if (!(d >= 0.0f && d <= 1.0f)) {
            char value[32];
            std::snprintf(value, sizeof value, "%g", double(d));
            fail("pixel (" + std::to_string(t % size_t(spec.width)) + ", " +
                 std::to_string(t / size_t(spec.width)) + ") holds " + value +
                 "; a density map holds values in [0, 1] (0 bare, 1 full density)");
        }
    }
    return map;
}

std::array<size_t, 256> alphaHistogram(const Image& level0) {
    std::array<size_t, 256> count{};
    for (size_t t = 0; t + 3 < level0.rgba.size(); t += 4) ++count[level0.rgba[t + 3]];
    return count;
}

std::vector<float> shellPassFractions(const std::array<size_t, 256>& alphaCount, int shells) {
    const int n = std::max(shells, 0);
    std::vector<float> pass(static_cast<size_t>(n) + 1, 1.0f);
    // atLeast[a]: texels with alpha >= a.
    std::array<size_t, 257> atLeast{};
    for (int a = 255; a >= 0; --a) atLeast[a] = atLeast[a + 1] + alphaCount[a];
    if (atLeast[0] == 0 || n == 0) return pass;
    double through = 1.0;
    for (int k = 1; k <= n; ++k) {
        // shell.vert keeps alpha / 255 >= k / N - 0.5 / 255: alpha >= ceil(255 k / N - 0.5).
        const int a = std::clamp(static_cast<int>(std::ceil(255.0 * k / n - 0.5)), 0, 256);
        through *= 1.0 - double(atLeast[a]) / double(atLeast[0]);
        pass[static_cast<size_t>(k)] = static_cast<float>(through);
    }
    return pass;
}

std::vector<float> densityCuts(const Image& level0) {
    const std::array<size_t, 256> count = alphaHistogram(level0);
    // atLeast[a]: blade texels (alpha > 0) with alpha >= a, for a = 1..255.
    std::array<size_t, 257> atLeast{};
    for (int a = 255; a >= 1; --a) atLeast[a] = atLeast[a + 1] + count[a];
    const size_t blades = atLeast[1];
    std::vector<float> cuts(DENSITY_CUTS, 0.0f);
    if (blades == 0) return cuts;
    constexpr float NONE = 2.0f;  // above any alpha: nothing passes
    constexpr float HALF_STEP = 0.5f / 255.0f;
    cuts[0] = NONE;
    for (int k = 1; k < DENSITY_CUTS; ++k) {
        const double want = double(k) / (DENSITY_CUTS - 1) * double(blades);
        // The tallest cut that still keeps at least the wanted area.
        int a = 255;
        while (a > 1 && double(atLeast[a]) < want) --a;
        cuts[k] = atLeast[a] == blades ? 0.0f : a / 255.0f - HALF_STEP;  // all kept: no cut
    }
    return cuts;
}

}  // namespace gale::render
