#pragma once
/// \file GrassTexture.h
/// The grass texture (paper Figure 3): RGB colour, alpha = blade height as a fraction of the grass
/// height (0 = bare ground), and its custom MIP chain that keeps blade cross-sections (thesis 3.4).

#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "render/GrassInput.h"

namespace gale::render {

struct GrassTextureSpec {
    int size = 256;  ///< texels per side (power of two, 16..4096)
    uint32_t seed = 1;
    float density = 0.35f;    ///< fraction of texels covered by blade cross-sections, (0, 1]
    float minHeight = 0.35f;  ///< shortest blade, fraction of the grass height, (0, 1]
    glm::vec3 groundColor{0.22f, 0.16f, 0.08f};
    glm::vec3 baseColor{0.20f, 0.45f, 0.10f};  ///< blade colour near the root
    glm::vec3 tipColor{0.55f, 0.75f, 0.25f};   ///< blade colour at full height
    float colorVariation = 0.15f;              ///< random per-blade colour jitter, fraction
};

/// Level 0 plus the custom MIP levels, each an RGBA8 image with rows top-down.
struct GrassTexture {
    std::vector<Image> levels;
};

/// Generates a seeded grass texture and its MIP chain. Throws gale::ParameterError naming the
/// grass.generated key on a bad spec.
GrassTexture generateGrassTexture(const GrassTextureSpec& spec);

/// Wraps a loaded RGBA image (alpha = blade height) and builds its MIP chain. The image must be
/// square with a power-of-two side (gale::ParameterError naming grass.texture otherwise) and hold
/// width * height * 4 bytes (std::logic_error otherwise).
GrassTexture grassTextureFromImage(Image image);

/// Next MIP level by the blade-keeping rule: a 2x2 block becomes a blade texel if two or more of
/// its texels are blades (alpha > 0): colour = mean of the blade texels, alpha = their max;
/// otherwise alpha 0 and colour = mean of all four (Bakay 2003, 3.4). The level must be square,
/// a power of two and at least 2 x 2 (std::logic_error otherwise; ParameterError for the shape).
Image downsampleKeepingBlades(const Image& level);

/// The MIP chain down to the last level that can still hold a blade: generation stops at the first
/// level where a blade of level 0 would vanish (no blade texels left), or at 1x1.
std::vector<Image> buildBladeMipChain(Image level0);

}  // namespace gale::render
