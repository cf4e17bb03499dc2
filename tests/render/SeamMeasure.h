#pragma once
/// \file SeamMeasure.h
/// The seam oracle (docs/render.md, "Level of detail"): a frame drawn with the level of detail
/// against the same frame with every shell everywhere, per 32 x 32 pixel tile and per tile-long
/// strip. Shared by tests/render/SeamTest.cpp (synthetic hills from 7 cameras) and
/// tests/app/ExampleSeamsTest.cpp (every example from its own camera).

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/GrassInput.h"

namespace gale::render::test {

inline constexpr int TILE_PX = 32;
// A tile's mean luminance (8-bit, Rec. 709 weights) may differ by this much: below what the eye
// sees as a band across a textured field. Measured on SeamTest's hill and meadow: the per-shell
// rule drawn plainly 20-59 from 10 m up, the whole-stack rule 0.7-2.7, the per-shell rule with
// its seen-shell shading 0.7-4.8 (docs/render.md).
inline constexpr double TILE_MEAN_TOLERANCE = 6.0;
// A step edge: the mean of the signed difference (level of detail minus all shells) over an
// 8-pixel strip one tile long changes across a strip border by more than this. The largest
// allowed step is the terrain's far edge, where the ground standing in for the grass lacks the
// grass's 0.5 m above it: a one-pixel line of sky at the silhouette (measured 11.3; the per-shell
// rule's bands drawn plainly gave 13-39).
inline constexpr int STRIP_PX = 8;
inline constexpr double STEP_TOLERANCE = 16.0;

inline std::vector<double> tileLuminance(const Image& image) {
    std::vector<double> l(size_t(image.width) * image.height);
    for (size_t p = 0; p < l.size(); ++p)
        l[p] = 0.2126 * image.rgba[p * 4] + 0.7152 * image.rgba[p * 4 + 1] +
               0.0722 * image.rgba[p * 4 + 2];
    return l;
}

struct SeamReport {
    double worstTileMean = 0.0;  // largest |mean difference| of a tile
    int worstTileX = 0, worstTileY = 0;
    double worstStep = 0.0;  // largest strip-mean step along a tile-long segment
};

inline SeamReport measureSeams(const Image& lod, const Image& full) {
    const std::vector<double> a = tileLuminance(lod), b = tileLuminance(full);
    const int w = lod.width, h = lod.height;
    std::vector<double> d(a.size());
    for (size_t p = 0; p < d.size(); ++p) d[p] = a[p] - b[p];
    SeamReport r;
    for (int ty = 0; ty < h / TILE_PX; ++ty)
        for (int tx = 0; tx < w / TILE_PX; ++tx) {
            double sum = 0.0;
            for (int y = ty * TILE_PX; y < (ty + 1) * TILE_PX; ++y)
                for (int x = tx * TILE_PX; x < (tx + 1) * TILE_PX; ++x) sum += d[size_t(y) * w + x];
            const double mean = std::abs(sum / (TILE_PX * TILE_PX));
            if (mean > r.worstTileMean) {
                r.worstTileMean = mean;
                r.worstTileX = tx;
                r.worstTileY = ty;
            }
        }
    // Strip means of d over STRIP_PX x TILE_PX (vertical edges) and TILE_PX x STRIP_PX
    // (horizontal edges), compared with the neighbouring strip, at every STRIP_PX / 2 offset.
    const auto stripMean = [&](int x0, int y0, int sw, int sh) {
        double s = 0.0;
        for (int y = y0; y < y0 + sh; ++y)
            for (int x = x0; x < x0 + sw; ++x) s += d[size_t(y) * w + x];
        return s / (sw * sh);
    };
    const int step = STRIP_PX / 2;
    for (int y0 = 0; y0 + TILE_PX <= h; y0 += TILE_PX / 2)
        for (int x0 = 0; x0 + 2 * STRIP_PX <= w; x0 += step)
            r.worstStep =
                std::max(r.worstStep, std::abs(stripMean(x0, y0, STRIP_PX, TILE_PX) -
                                               stripMean(x0 + STRIP_PX, y0, STRIP_PX, TILE_PX)));
    for (int x0 = 0; x0 + TILE_PX <= w; x0 += TILE_PX / 2)
        for (int y0 = 0; y0 + 2 * STRIP_PX <= h; y0 += step)
            r.worstStep =
                std::max(r.worstStep, std::abs(stripMean(x0, y0, TILE_PX, STRIP_PX) -
                                               stripMean(x0, y0 + STRIP_PX, TILE_PX, STRIP_PX)));
    return r;
}

}  // namespace gale::render::test
