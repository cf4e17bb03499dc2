#pragma once
/// \file RenderTestUtil.h
/// Scenes and image comparison shared by the render tests.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <glm/geometric.hpp>
#include <string>
#include <vector>

#include "render/GrassInput.h"
#include "render/GrassTexture.h"
#include "render/ImageIO.h"

namespace gale::render::test {

/// A fresh, empty folder under the build tree for one test's files.
inline std::filesystem::path freshTestDir(const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::path(GALE_BINARY_DIR) / "render_test_tmp" / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

/// Regular grid of nx x ny vertices over [-halfSize_m, halfSize_m]^2 with height h(x, y) and
/// normals from central differences of h; uv = xy / tile_m.
template <class HeightFn>
TerrainMesh makeGridMesh(int nx, int ny, float halfSize_m, float tile_m, HeightFn h) {
    TerrainMesh mesh;
    mesh.nx = nx;
    mesh.ny = ny;
    const float eps_m = 1e-3f;
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const float x = -halfSize_m + 2.0f * halfSize_m * static_cast<float>(i) / (nx - 1);
            const float y = -halfSize_m + 2.0f * halfSize_m * static_cast<float>(j) / (ny - 1);
            mesh.wsPosition_m.emplace_back(x, y, h(x, y));
            const float dhdx = (h(x + eps_m, y) - h(x - eps_m, y)) / (2.0f * eps_m);
            const float dhdy = (h(x, y + eps_m) - h(x, y - eps_m)) / (2.0f * eps_m);
            mesh.wsNormal.push_back(glm::normalize(glm::vec3(-dhdx, -dhdy, 1.0f)));
            mesh.uv.emplace_back(x / tile_m, y / tile_m);
        }
    }
    return mesh;
}

inline TerrainMesh makeFlatMesh(int n, float halfSize_m, float tile_m) {
    return makeGridMesh(n, n, halfSize_m, tile_m, [](float, float) { return 0.0f; });
}

/// The small Gaussian hill of the reference image: 1.2 m high, 1.6 m wide (sigma), on 6 x 6 m.
inline TerrainMesh makeHillMesh() {
    return makeGridMesh(17, 17, 3.0f, 1.5f, [](float x, float y) {
        return 1.2f * std::exp(-(x * x + y * y) / (2.0f * 1.6f * 1.6f));
    });
}

/// A uniform global wind direction projected into each vertex's tangent plane (paper section 3),
/// two groups split at x = 0.
inline GrassWind makeUniformWind(const TerrainMesh& mesh, glm::vec3 wsGlobal, float intensityWest,
                                 float intensityEast) {
    auto vertex = std::make_shared<VertexWind>();
    for (size_t v = 0; v < mesh.wsPosition_m.size(); ++v) {
        const glm::vec3 n = mesh.wsNormal[v];
        const glm::vec3 t = wsGlobal - glm::dot(wsGlobal, n) * n;
        const float len = glm::length(t);
        vertex->wsDirection.push_back(len > 1e-6f ? t / len : glm::vec3(0.0f));
        vertex->group.push_back(mesh.wsPosition_m[v].x < 0.0f ? 0u : 1u);
    }
    GrassWind wind;
    wind.vertex = std::move(vertex);
    wind.revision = 1;
    wind.groupIntensity = {intensityWest, intensityEast};
    return wind;
}

/// A uniform texture: every texel the same colour and alpha.
inline Image makeUniformImage(int size, uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
    Image image;
    image.width = image.height = size;
    for (int t = 0; t < size * size; ++t) image.rgba.insert(image.rgba.end(), {r, g, b, a});
    return image;
}

struct ImageDiff {
    double differingFraction = 0.0;  ///< pixels with any channel beyond the tolerance
    int maxChannelDiff = 0;
    Image diff;  ///< per pixel: |a - b| scaled x4, red where beyond the tolerance
};

/// idiff-style comparison (STYLE, golden images). Requires equal sizes.
inline ImageDiff compareImages(const Image& a, const Image& b, int channelTolerance) {
    ImageDiff result;
    result.diff.width = a.width;
    result.diff.height = a.height;
    result.diff.rgba.assign(a.rgba.size(), 0);
    size_t differing = 0;
    const size_t pixels = static_cast<size_t>(a.width) * a.height;
    for (size_t p = 0; p < pixels; ++p) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
            const int d = std::abs(int(a.rgba[p * 4 + c]) - int(b.rgba[p * 4 + c]));
            worst = std::max(worst, d);
            result.diff.rgba[p * 4 + c] = static_cast<uint8_t>(std::min(255, d * 4));
        }
        result.diff.rgba[p * 4 + 3] = 255;
        if (worst > channelTolerance) {
            ++differing;
            result.diff.rgba[p * 4 + 0] = 255;
        }
        result.maxChannelDiff = std::max(result.maxChannelDiff, worst);
    }
    result.differingFraction = pixels ? static_cast<double>(differing) / pixels : 0.0;
    return result;
}

// llvmpipe is deterministic for one Mesa build (docs/design.md 7); a few levels of slack per
// channel absorb differences between CPU instruction sets (AVX2 / AVX-512 code paths) and Mesa
// updates.
constexpr int REFERENCE_CHANNEL_TOLERANCE = 8;
// A handful of pixels on blade edges may flip between blade and ground under such differences.
constexpr double REFERENCE_MAX_DIFFERING_FRACTION = 0.005;

/// Compares `actual` with tests/data/render/<name>.png within the tolerances above. With
/// GALE_UPDATE_REFERENCES=1 it rewrites the reference instead and skips. On failure it writes
/// <name>.actual.png and <name>.diff.png under the build folder and names them.
inline void expectMatchesReference(const Image& actual, const std::string& name) {
    namespace fs = std::filesystem;
    const fs::path reference = fs::path(GALE_SOURCE_DIR) / "tests/data/render" / (name + ".png");
    const char* update = std::getenv("GALE_UPDATE_REFERENCES");
    if (update != nullptr && std::string(update) == "1") {
        writeImageAtomic(actual, reference.string());
        GTEST_SKIP() << "reference rewritten: " << reference;
    }
    const Image expected = readImageRgba8(reference.string());
    ASSERT_EQ(expected.width, actual.width);
    ASSERT_EQ(expected.height, actual.height);
    const ImageDiff diff = compareImages(actual, expected, REFERENCE_CHANNEL_TOLERANCE);
    if (diff.differingFraction > REFERENCE_MAX_DIFFERING_FRACTION) {
        const fs::path out = fs::path(GALE_BINARY_DIR) / "render_test_output";
        fs::create_directories(out);
        const fs::path actualPath = out / (name + ".actual.png"),
                       diffPath = out / (name + ".diff.png");
        writeImageAtomic(actual, actualPath.string());
        writeImageAtomic(diff.diff, diffPath.string());
        ADD_FAILURE() << diff.differingFraction * 100.0 << "% of pixels differ by more than "
                      << REFERENCE_CHANNEL_TOLERANCE << "/255 (max " << diff.maxChannelDiff
                      << "); actual: " << actualPath << ", diff: " << diffPath
                      << ", expected: " << reference;
    }
}

}  // namespace gale::render::test
