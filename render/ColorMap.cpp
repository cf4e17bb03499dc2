#include "render/ColorMap.h"

#include <algorithm>
#include <cmath>

namespace gale::render {
namespace {

/// matplotlib's viridis at t = k / 9, k = 0..9 (van der Walt and Smith 2015), as the hex codes
/// matplotlib documents: #440154 #482878 #3e4989 #31688e #26828e #1f9e89 #35b779 #6ece58
/// #b5de2b #fde725.
constexpr unsigned VIRIDIS_STOPS[10] = {0x440154, 0x482878, 0x3e4989, 0x31688e, 0x26828e,
                                        0x1f9e89, 0x35b779, 0x6ece58, 0xb5de2b, 0xfde725};

glm::vec3 stopColor(int k) {
    const unsigned c = VIRIDIS_STOPS[k];
    return glm::vec3(float((c >> 16) & 0xff), float((c >> 8) & 0xff), float(c & 0xff)) / 255.0f;
}

float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

glm::vec3 viridis(float t) {
    if (!(t > 0.0f)) t = 0.0f;  // also NaN
    t = std::min(t, 1.0f);
    const float x = t * 9.0f;
    const int k = std::min(8, static_cast<int>(x));
    const float f = x - static_cast<float>(k);
    return stopColor(k) * (1.0f - f) + stopColor(k + 1) * f;
}

float cieLightness(const glm::vec3& srgb) {
    const float y = 0.2126f * srgbToLinear(srgb.r) + 0.7152f * srgbToLinear(srgb.g) +
                    0.0722f * srgbToLinear(srgb.b);
    // CIE 1976: L* = 116 f(Y / Yn) - 16 with the linear toe below (6/29)^3.
    const float d = 6.0f / 29.0f;
    const float f = y > d * d * d ? std::cbrt(y) : y / (3.0f * d * d) + 4.0f / 29.0f;
    return 116.0f * f - 16.0f;
}

}  // namespace gale::render
