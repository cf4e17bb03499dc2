// The grass texture generator and the blade-keeping MIP filter (Bakay 2003, 3.4).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <functional>
#include <set>
#include <vector>

#include "RenderTestUtil.h"
#include "render/GrassTexture.h"

namespace gale::render {
namespace {

Image makeImage(int size, const std::vector<std::array<uint8_t, 4>>& texels) {
    Image image;
    image.width = image.height = size;
    for (const auto& t : texels) image.rgba.insert(image.rgba.end(), t.begin(), t.end());
    return image;
}

const uint8_t* texel(const Image& image, int x, int y) {
    return &image.rgba[(static_cast<size_t>(y) * image.width + x) * 4];
}

/// 4-connected components of blade texels (alpha > 0), each with its maximum alpha, sorted.
std::multiset<int> bladeDots(const Image& image) {
    std::vector<char> seen(static_cast<size_t>(image.width) * image.height, 0);
    std::multiset<int> dots;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            if (seen[y * image.width + x] || texel(image, x, y)[3] == 0) continue;
            int maxAlpha = 0;
            std::vector<std::pair<int, int>> stack{{x, y}};
            seen[y * image.width + x] = 1;
            while (!stack.empty()) {
                auto [cx, cy] = stack.back();
                stack.pop_back();
                maxAlpha = std::max<int>(maxAlpha, texel(image, cx, cy)[3]);
                const int nbr[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
                for (const auto& d : nbr) {
                    const int nx = cx + d[0], ny = cy + d[1];
                    if (nx < 0 || ny < 0 || nx >= image.width || ny >= image.height) continue;
                    if (seen[ny * image.width + nx] || texel(image, nx, ny)[3] == 0) continue;
                    seen[ny * image.width + nx] = 1;
                    stack.emplace_back(nx, ny);
                }
            }
            dots.insert(maxAlpha);
        }
    }
    return dots;
}

TEST(BladeMip, OneBladeTexelOfFourIsGroundWithMeanOfAll) {
    const Image block =
        makeImage(2, {{200, 100, 0, 180}, {0, 0, 40, 0}, {0, 0, 40, 0}, {0, 0, 40, 0}});
    const Image next = downsampleKeepingBlades(block);
    ASSERT_EQ(next.width, 1);
    const uint8_t* t = texel(next, 0, 0);
    EXPECT_EQ(t[3], 0);
    EXPECT_EQ(t[0], 50);  // (200 + 0 + 0 + 0) / 4
    EXPECT_EQ(t[1], 25);  // 100 / 4
    EXPECT_EQ(t[2], 30);  // (0 + 40 * 3) / 4
}

TEST(BladeMip, TwoBladeTexelsOfFourMakeABladeWithTheirMeanColourAndMaxAlpha) {
    const Image block =
        makeImage(2, {{200, 100, 0, 180}, {0, 0, 40, 0}, {100, 50, 20, 90}, {0, 0, 40, 0}});
    const Image next = downsampleKeepingBlades(block);
    const uint8_t* t = texel(next, 0, 0);
    EXPECT_EQ(t[3], 180);  // max of 180 and 90
    EXPECT_EQ(t[0], 150);  // mean of the blade texels only
    EXPECT_EQ(t[1], 75);
    EXPECT_EQ(t[2], 10);
}

TEST(BladeMip, FourBladeTexelsKeepTheMaximumHeight) {
    const Image block =
        makeImage(2, {{10, 10, 10, 5}, {20, 20, 20, 250}, {30, 30, 30, 7}, {40, 40, 40, 1}});
    const Image next = downsampleKeepingBlades(block);
    const uint8_t* t = texel(next, 0, 0);
    EXPECT_EQ(t[3], 250);
    EXPECT_EQ(t[0], 25);
}

TEST(BladeMip, IsolatedDotsKeepCountAndHeightsUntilUnrepresentable) {
    // 64 x 64 with 4 x 4 dots on a 16-texel lattice, each with its own varied heights: the dots
    // survive as 2 x 2 at level 1 and 1 x 1 at level 2; at level 3 a dot covers one texel of a
    // 2 x 2 block, which the 2-of-4 rule drops, so the chain ends at level 2.
    Image image = test::makeUniformImage(64, 90, 60, 30, 0);
    std::multiset<int> expected;
    int dot = 0;
    for (int y0 = 4; y0 < 64; y0 += 16) {
        for (int x0 = 8; x0 < 64; x0 += 16, ++dot) {
            int maxAlpha = 0;
            for (int dy = 0; dy < 4; ++dy) {
                for (int dx = 0; dx < 4; ++dx) {
                    const int alpha = 1 + (dot * 13 + dx * 7 + dy * 29) % 255;
                    maxAlpha = std::max(maxAlpha, alpha);
                    uint8_t* t = &image.rgba[((y0 + dy) * 64 + x0 + dx) * 4];
                    t[0] = 40;
                    t[1] = static_cast<uint8_t>(100 + dot);
                    t[2] = 20;
                    t[3] = static_cast<uint8_t>(alpha);
                }
            }
            expected.insert(maxAlpha);
        }
    }
    ASSERT_EQ(bladeDots(image), expected);
    const std::vector<Image> chain = buildBladeMipChain(image);
    ASSERT_EQ(chain.size(), 3u);
    for (size_t level = 0; level < chain.size(); ++level) {
        EXPECT_EQ(chain[level].width, 64 >> level);
        EXPECT_EQ(bladeDots(chain[level]), expected) << "level " << level;
    }
    // The level after the last kept one has no blade left.
    EXPECT_TRUE(bladeDots(downsampleKeepingBlades(chain.back())).empty());
}

TEST(BladeMip, GeneratedChainEndsAtTheLastLevelWithBlades) {
    GrassTextureSpec spec;
    spec.size = 64;
    const GrassTexture texture = generateGrassTexture(spec);
    ASSERT_FALSE(texture.levels.empty());
    const Image& last = texture.levels.back();
    EXPECT_FALSE(bladeDots(last).empty());
    if (last.width > 1) {
        EXPECT_TRUE(bladeDots(downsampleKeepingBlades(last)).empty());
    }
}

TEST(BladeMip, RejectsNonSquareOrNonPowerOfTwo) {
    Image image = test::makeUniformImage(6, 0, 0, 0, 0);
    EXPECT_THROW(grassTextureFromImage(image), std::invalid_argument);
    Image wide;
    wide.width = 8;
    wide.height = 4;
    wide.rgba.assign(8 * 4 * 4, 0);
    try {
        grassTextureFromImage(wide);
        FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("8x4"), std::string::npos) << e.what();
    }
}

bool sameLevels(const GrassTexture& a, const GrassTexture& b) {
    if (a.levels.size() != b.levels.size()) return false;
    for (size_t l = 0; l < a.levels.size(); ++l) {
        if (a.levels[l].rgba != b.levels[l].rgba) return false;
    }
    return true;
}

TEST(GrassTextureGenerator, SameSeedGivesSameBytes) {
    GrassTextureSpec spec;
    spec.size = 128;
    spec.seed = 42;
    EXPECT_TRUE(sameLevels(generateGrassTexture(spec), generateGrassTexture(spec)));
}

TEST(GrassTextureGenerator, OtherSeedGivesOtherBytes) {
    GrassTextureSpec spec;
    spec.size = 128;
    spec.seed = 42;
    const GrassTexture a = generateGrassTexture(spec);
    spec.seed = 43;
    EXPECT_FALSE(sameLevels(a, generateGrassTexture(spec)));
}

TEST(GrassTextureGenerator, CoverageMatchesRequestedDensity) {
    // Blades are placed until the density is reached, overshooting by less than one footprint.
    constexpr double DENSITY_TOLERANCE = 0.005;
    for (float density : {0.05f, 0.35f, 0.8f, 1.0f}) {
        GrassTextureSpec spec;
        spec.size = 256;
        spec.density = density;
        const GrassTexture texture = generateGrassTexture(spec);
        const Image& level0 = texture.levels[0];
        size_t blades = 0;
        int minAlpha = 255;
        for (size_t t = 3; t < level0.rgba.size(); t += 4) {
            if (level0.rgba[t] > 0) {
                ++blades;
                minAlpha = std::min<int>(minAlpha, level0.rgba[t]);
            }
        }
        const double covered = static_cast<double>(blades) / (256.0 * 256.0);
        EXPECT_NEAR(covered, density, DENSITY_TOLERANCE) << "density " << density;
        // Alpha is the blade height fraction, never below minHeight (less half an 8-bit step).
        EXPECT_GE(minAlpha, static_cast<int>(spec.minHeight * 255.0f - 0.5f));
    }
}

TEST(GrassTextureGenerator, RejectsBadSpec) {
    GrassTextureSpec spec;
    spec.size = 100;
    EXPECT_THROW(generateGrassTexture(spec), std::invalid_argument);
    spec.size = 64;
    spec.density = 0.0f;
    EXPECT_THROW(generateGrassTexture(spec), std::invalid_argument);
    spec.density = 0.3f;
    spec.minHeight = 1.5f;
    EXPECT_THROW(generateGrassTexture(spec), std::invalid_argument);
}

}  // namespace
}  // namespace gale::render
