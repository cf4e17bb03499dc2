#include "render/DensityMap.h"

#include <array>
#include <cmath>
#include <stdexcept>

#include "render/ImageIO.h"

namespace gale::render {

DensityMap loadDensityMap(const std::string& path, glm::vec2 wsMin_m, glm::vec2 wsSize_m) {
    if (!(std::isfinite(wsSize_m.x) && std::isfinite(wsSize_m.y) && wsSize_m.x > 0.0f &&
          wsSize_m.y > 0.0f && std::isfinite(wsMin_m.x) && std::isfinite(wsMin_m.y))) {
        throw std::logic_error("density map '" + path +
                               "': the plan rectangle it covers must be finite with a "
                               "positive size");
    }
    const Image image = readImageRgba8(path);
    DensityMap map;
    map.width = image.width;
    map.height = image.height;
    map.wsMin_m = wsMin_m;
    map.wsSize_m = wsSize_m;
    map.density.resize(static_cast<size_t>(image.width) * image.height);
    // Grey images arrive expanded to equal RGB: the red channel is the value either way.
    for (size_t t = 0; t < map.density.size(); ++t) map.density[t] = image.rgba[t * 4] / 255.0f;
    return map;
}

std::vector<float> densityCuts(const Image& level0) {
    std::array<size_t, 256> count{};
    for (size_t t = 0; t + 3 < level0.rgba.size(); t += 4) ++count[level0.rgba[t + 3]];
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
