/// \file GrassTexture.cpp
/// The seeded grass texture generator and the blade-keeping MIP filter (Bakay 2003, 3.1 and 3.4).

#include "render/GrassTexture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

#include "base/Numbers.h"
#include "base/ParameterError.h"

namespace gale::render {
namespace {

/// splitmix64 (Steele, Lea, Flood 2014): a fixed, portable generator, so a seed gives the same
/// texture bytes with every compiler and standard library.
class SplitMix64 {
  public:
    explicit SplitMix64(uint64_t seed) : mState(seed) {}
    uint64_t next() {
        uint64_t z = (mState += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// Uniform in [0, 1) with 24 bits, exact in float.
    float uniform() { return static_cast<float>(next() >> 40) * (1.0f / 16777216.0f); }
    /// Uniform integer in [0, n), n >= 1 (multiply-shift; bias below 2^-32 for n < 2^32).
    uint32_t below(uint32_t n) {
        return static_cast<uint32_t>(((next() >> 32) * static_cast<uint64_t>(n)) >> 32);
    }

  private:
    uint64_t mState;
};

bool isPowerOfTwo(int n) { return n > 0 && (n & (n - 1)) == 0; }

uint8_t toByte(float v) {
    const float c = std::clamp(v, 0.0f, 1.0f);
    return static_cast<uint8_t>(std::lround(c * 255.0f));
}

bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void requireSquarePowerOfTwo(const Image& image, const char* what) {
    if (image.width != image.height || !isPowerOfTwo(image.width)) {
        throw ParameterError("grass.texture",
                             std::to_string(image.width) + "x" + std::to_string(image.height),
                             std::string("must be square with a power-of-two side (") + what + ")");
    }
    const size_t expected =
        static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 4u;
    if (image.rgba.size() != expected) {
        throw std::logic_error(std::string(what) + ": image.rgba holds " +
                               std::to_string(image.rgba.size()) + " bytes, expected " +
                               std::to_string(expected) + " (width * height * 4)");
    }
}

void validateSpec(const GrassTextureSpec& spec) {
    // The scene's keys ([grass.generated], docs/scene-format.md).
    auto fail = [](const std::string& key, const std::string& expected, double got) {
        throw ParameterError("grass.generated." + key, formatG(got), "must be " + expected);
    };
    if (!isPowerOfTwo(spec.size) || spec.size < 16 || spec.size > 4096) {
        fail("size", "a power of two in 16..4096", spec.size);
    }
    if (!(spec.density > 0.0f && spec.density <= 1.0f)) fail("density", "in (0, 1]", spec.density);
    if (!(spec.minHeight > 0.0f && spec.minHeight <= 1.0f)) {
        fail("min_height", "in (0, 1]", spec.minHeight);
    }
    if (!(spec.colorVariation >= 0.0f && spec.colorVariation <= 1.0f)) {
        fail("color_variation", "in [0, 1]", spec.colorVariation);
    }
    if (!finite3(spec.groundColor) || !finite3(spec.baseColor) || !finite3(spec.tipColor)) {
        throw ParameterError("grass.generated.base_color", "a non-finite colour",
                             "ground_color, base_color and tip_color must be finite");
    }
}

// Blade cross-section footprints of 1 to 3 texels, as offsets from the blade's anchor texel
// (thesis 3.1: the "dots" of Figure 3.2).
struct Footprint {
    int count;
    int dx[3];
    int dy[3];
};
constexpr Footprint FOOTPRINTS[] = {
    {1, {0, 0, 0}, {0, 0, 0}},  // single texel
    {2, {0, 1, 0}, {0, 0, 0}},  // horizontal pair
    {2, {0, 0, 0}, {0, 1, 0}},  // vertical pair
    {2, {0, 1, 0}, {0, 1, 0}},  // diagonal pair
    {3, {0, 1, 0}, {0, 0, 1}},  // L
    {3, {0, 1, 1}, {0, 0, 1}},  // L, turned
    {3, {0, 1, 2}, {0, 0, 0}},  // short horizontal line
    {3, {0, 0, 0}, {0, 1, 2}},  // short vertical line
};
constexpr uint32_t FOOTPRINT_COUNT = sizeof(FOOTPRINTS) / sizeof(FOOTPRINTS[0]);

}  // namespace

GrassTexture generateGrassTexture(const GrassTextureSpec& spec) {
    validateSpec(spec);
    const int n = spec.size;
    const size_t texels = static_cast<size_t>(n) * static_cast<size_t>(n);
    Image image;
    image.width = n;
    image.height = n;
    image.rgba.assign(texels * 4u, 0);

    // Seed mixing keeps nearby seeds unrelated.
    SplitMix64 rng(0xD1B54A32D192ED03ull ^
                   (static_cast<uint64_t>(spec.seed) * 0x9E3779B97F4A7C15ull));

    // Bare ground: alpha 0, groundColor with a little per-texel brightness noise so the soil under
    // the blades is not flat.
    for (size_t t = 0; t < texels; ++t) {
        const float shade = 0.9f + 0.2f * rng.uniform();
        uint8_t* px = &image.rgba[t * 4u];
        px[0] = toByte(spec.groundColor.x * shade);
        px[1] = toByte(spec.groundColor.y * shade);
        px[2] = toByte(spec.groundColor.z * shade);
        px[3] = 0;
    }

    // Blades: random footprints, wrapped at the edges so the texture tiles, until the requested
    // fraction of texels is covered. Later blades overwrite earlier ones where they overlap.
    const size_t target =
        static_cast<size_t>(std::ceil(static_cast<double>(spec.density) * texels));
    size_t covered = 0;
    const size_t maxAttempts = 8u * target + 64u;
    auto paintBlade = [&](int x0, int y0, const Footprint& fp) {
        const float height = spec.minHeight + (1.0f - spec.minHeight) * rng.uniform();
        const float brightness = 1.0f + spec.colorVariation * (2.0f * rng.uniform() - 1.0f);
        const glm::vec3 hueJitter{
            1.0f + 0.5f * spec.colorVariation * (2.0f * rng.uniform() - 1.0f), 1.0f,
            1.0f + 0.5f * spec.colorVariation * (2.0f * rng.uniform() - 1.0f)};
        const glm::vec3 color =
            (spec.baseColor + (spec.tipColor - spec.baseColor) * height) * brightness * hueJitter;
        // Alpha = blade height fraction, 1..255: a blade is never 0 (that is bare ground).
        const uint8_t alpha =
            static_cast<uint8_t>(std::clamp<long>(std::lround(height * 255.0f), 1, 255));
        for (int k = 0; k < fp.count; ++k) {
            const int x = (x0 + fp.dx[k]) & (n - 1);
            const int y = (y0 + fp.dy[k]) & (n - 1);
            uint8_t* px = &image.rgba[(static_cast<size_t>(y) * n + x) * 4u];
            if (px[3] == 0) ++covered;
            px[0] = toByte(color.x);
            px[1] = toByte(color.y);
            px[2] = toByte(color.z);
            px[3] = alpha;
        }
    };
    for (size_t attempt = 0; attempt < maxAttempts && covered < target; ++attempt) {
        const int x0 = static_cast<int>(rng.below(static_cast<uint32_t>(n)));
        const int y0 = static_cast<int>(rng.below(static_cast<uint32_t>(n)));
        const Footprint& fp = FOOTPRINTS[rng.below(FOOTPRINT_COUNT)];
        // Stop short of overshooting the density by a whole footprint.
        if (covered + static_cast<size_t>(fp.count) > target + 2u) continue;
        paintBlade(x0, y0, fp);
    }
    // Near density 1 random placement stalls (coupon collector); fill the remaining ground texels
    // with single-texel blades in a scan from a random start.
    if (covered < target) {
        const size_t start = rng.below(static_cast<uint32_t>(texels));
        for (size_t k = 0; k < texels && covered < target; ++k) {
            const size_t t = (start + k) % texels;
            if (image.rgba[t * 4u + 3] != 0) continue;
            paintBlade(static_cast<int>(t % n), static_cast<int>(t / n), FOOTPRINTS[0]);
        }
    }

    GrassTexture texture;
    texture.levels = buildBladeMipChain(std::move(image));
    return texture;
}

GrassTexture grassTextureFromImage(Image image) {
    requireSquarePowerOfTwo(image, "grassTextureFromImage");
    GrassTexture texture;
    texture.levels = buildBladeMipChain(std::move(image));
    return texture;
}

Image downsampleKeepingBlades(const Image& level) {
    requireSquarePowerOfTwo(level, "downsampleKeepingBlades");
    if (level.width < 2) {
        throw std::logic_error("downsampleKeepingBlades: a 1x1 level has no next level");
    }
    const int n = level.width / 2;
    Image out;
    out.width = n;
    out.height = n;
    out.rgba.assign(static_cast<size_t>(n) * n * 4u, 0);
    const size_t srcRow = static_cast<size_t>(level.width) * 4u;
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            const uint8_t* q[4] = {
                &level.rgba[(2 * y) * srcRow + (2 * x) * 4u],
                &level.rgba[(2 * y) * srcRow + (2 * x + 1) * 4u],
                &level.rgba[(2 * y + 1) * srcRow + (2 * x) * 4u],
                &level.rgba[(2 * y + 1) * srcRow + (2 * x + 1) * 4u],
            };
            // Thesis 3.4: two or more blade texels (alpha > 0) make a blade texel with the mean
            // colour of the blade texels and their maximum alpha; otherwise ground (alpha 0) with
            // the mean colour of all four.
            int blades = 0;
            unsigned bladeSum[3] = {0, 0, 0};
            unsigned allSum[3] = {0, 0, 0};
            uint8_t maxAlpha = 0;
            for (const uint8_t* p : q) {
                for (int c = 0; c < 3; ++c) allSum[c] += p[c];
                if (p[3] > 0) {
                    ++blades;
                    for (int c = 0; c < 3; ++c) bladeSum[c] += p[c];
                    maxAlpha = std::max(maxAlpha, p[3]);
                }
            }
            uint8_t* o = &out.rgba[(static_cast<size_t>(y) * n + x) * 4u];
            if (blades >= 2) {
                for (int c = 0; c < 3; ++c) {
                    o[c] = static_cast<uint8_t>((bladeSum[c] + blades / 2) / blades);
                }
                o[3] = maxAlpha;
            } else {
                for (int c = 0; c < 3; ++c) o[c] = static_cast<uint8_t>((allSum[c] + 2u) / 4u);
                o[3] = 0;
            }
        }
    }
    return out;
}

std::vector<Image> buildBladeMipChain(Image level0) {
    requireSquarePowerOfTwo(level0, "buildBladeMipChain");
    std::vector<Image> levels;
    levels.push_back(std::move(level0));
    // Thesis 3.4: repeat until a cross-section can no longer be represented. We stop at the first
    // level left without any blade texel (that level is not kept) or at 1x1.
    while (levels.back().width > 1) {
        Image next = downsampleKeepingBlades(levels.back());
        bool anyBlade = false;
        for (size_t t = 3; t < next.rgba.size(); t += 4) {
            if (next.rgba[t] != 0) {
                anyBlade = true;
                break;
            }
        }
        if (!anyBlade) break;
        levels.push_back(std::move(next));
    }
    return levels;
}

}  // namespace gale::render
