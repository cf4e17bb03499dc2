/// \file RenderBench.cpp
/// The paper's Table 2 set-up (Bakay 2003, 4.1): full-screen grass, 3 point lights, a ~512-triangle
/// base mesh, N layers, timed against a trivial alpha-tested fill of the same geometry.

#include "render/RenderBench.h"

#include <chrono>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>
#include <string>

#include "render/GlContext.h"
#include "render/GrassTexture.h"
#include "render/ImageIO.h"
#include "render/RenderLimits.h"
#include "render/ShellRenderer.h"

namespace gale::render {
namespace {

using Clock = std::chrono::steady_clock;

// The benchmark scene: a 32 m field (larger than the view), 0.3 m grass, the texture repeating
// every 2 m, the camera 9 m up looking slightly forward (as in the thesis' Figure 4.1, the field
// fills the screen).
constexpr float kFieldSize_m = 32.0f;
constexpr float kGrassHeight_m = 0.3f;
constexpr float kTile_m = 2.0f;
constexpr int kTextureSize = 256;
constexpr int kWindGroups = 8;

GrassWind makeBenchWind(const TerrainMesh& mesh) {
    // The paper's point source: wind blowing away from a source beside the field, groups by
    // distance so gusts travel (paper section 3). Directions are already tangent on flat ground.
    const glm::vec3 source_m(-20.0f, -10.0f, 0.0f);
    float maxDistance = 0.0f;
    for (const glm::vec3& p : mesh.wsPosition_m)
        maxDistance = std::max(maxDistance, glm::length(p - source_m));
    auto vertex = std::make_shared<VertexWind>();
    for (const glm::vec3& p : mesh.wsPosition_m) {
        const glm::vec3 away = p - source_m;
        const float d = glm::length(away);
        vertex->wsDirection.push_back(d > 0.0f ? away / d : glm::vec3(0.0f));
        const int g = std::min(kWindGroups - 1, static_cast<int>(d / maxDistance * kWindGroups));
        vertex->group.push_back(static_cast<uint32_t>(g));
    }
    GrassWind wind;
    wind.vertex = std::move(vertex);
    wind.revision = 1;
    wind.groupIntensity.assign(kWindGroups, 0.0f);
    return wind;
}

void setFrameIntensities(GrassWind& wind, int frame) {
    for (int g = 0; g < kWindGroups; ++g) {
        const float phase = 0.3f * static_cast<float>(frame) - 0.7f * static_cast<float>(g);
        wind.groupIntensity[static_cast<size_t>(g)] = 0.35f + 0.3f * std::sin(phase);
    }
}

Lighting makeBenchLighting(int lights) {
    Lighting lighting;
    lighting.ambient = glm::vec3(0.12f);
    const glm::vec3 positions[3] = {{-8.0f, -6.0f, 7.0f}, {9.0f, 2.0f, 5.0f}, {0.0f, 12.0f, 9.0f}};
    const glm::vec3 colors[3] = {{1.0f, 0.9f, 0.75f}, {0.4f, 0.45f, 0.7f}, {0.6f, 0.6f, 0.5f}};
    for (int l = 0; l < lights; ++l) {
        PointLight light;
        light.wsPosition_m =
            positions[l % 3] + glm::vec3(0.0f, 0.0f, 1.5f * static_cast<float>(l / 3));
        light.color = colors[l % 3];
        light.attenuation = glm::vec3(1.0f, 0.02f, 0.002f);
        lighting.lights.push_back(light);
    }
    return lighting;
}

}  // namespace

TerrainMesh makeFlatGridMesh(int verticesPerSide, float size_m, float tile_m) {
    if (verticesPerSide < 2 || !(size_m > 0.0f) || !(tile_m > 0.0f)) {
        throw std::invalid_argument(
            "makeFlatGridMesh: need verticesPerSide >= 2, size_m > 0, "
            "tile_m > 0, got " +
            std::to_string(verticesPerSide) + ", " + std::to_string(size_m) + ", " +
            std::to_string(tile_m));
    }
    TerrainMesh mesh;
    mesh.nx = mesh.ny = verticesPerSide;
    const float step_m = size_m / static_cast<float>(verticesPerSide - 1);
    for (int j = 0; j < verticesPerSide; ++j) {
        for (int i = 0; i < verticesPerSide; ++i) {
            const glm::vec3 p(-0.5f * size_m + step_m * i, -0.5f * size_m + step_m * j, 0.0f);
            mesh.wsPosition_m.push_back(p);
            mesh.wsNormal.emplace_back(0.0f, 0.0f, 1.0f);
            mesh.uv.emplace_back(p.x / tile_m, p.y / tile_m);
        }
    }
    return mesh;
}

ShellFillResult measureShellFill(const ShellFillCase& c) {
    if (c.layers < 1 || c.layers > kMaxShells + 1) {
        throw std::invalid_argument("ShellFillCase.layers must be in 1.." +
                                    std::to_string(kMaxShells + 1) + ", got " +
                                    std::to_string(c.layers));
    }
    if (c.frames < 1 || c.warmupFrames < 0 || c.lights < 0 || c.lights > kMaxLights) {
        throw std::invalid_argument(
            "ShellFillCase: need frames >= 1, warmupFrames >= 0, lights in "
            "0.." +
            std::to_string(kMaxLights));
    }
    auto context = createOsMesaContext(c.width, c.height);
    ShellRenderer renderer(*context);
    const TerrainMesh mesh = makeFlatGridMesh(c.gridVertices, kFieldSize_m, kTile_m);
    renderer.setTerrain(mesh);
    GrassParams grass;
    grass.height_m = kGrassHeight_m;
    grass.shells = c.layers - 1;
    grass.tile_m = kTile_m;
    grass.lodPixels = 0.0f;  // the table measures N full layers: no level of detail
    GrassTextureSpec spec;
    spec.size = kTextureSize;
    spec.seed = 2002;
    renderer.setGrass(grass, generateGrassTexture(spec));
    renderer.setLighting(makeBenchLighting(c.lights));
    Camera camera;
    camera.wsPosition_m = glm::vec3(0.0f, -2.0f, 9.0f);
    camera.wsTarget_m = glm::vec3(0.0f, 0.0f, 0.0f);
    camera.fovY_deg = 45.0f;
    camera.near_m = 0.5f;
    camera.far_m = 200.0f;
    GrassWind wind = makeBenchWind(mesh);

    ShellFillResult result;
    result.layers = c.layers;
    result.width = c.width;
    result.height = c.height;
    result.triangles = 2L * (c.gridVertices - 1) * (c.gridVertices - 1) * c.layers;
    result.renderer = context->description();

    // Warm up every pass, then alternate timed frames of them so that load from other
    // processes on the machine hits all alike. Every draw ends with glFinish.
    DrawOptions nearestTexels;
    nearestTexels.nearestTexels = true;
    int frame = 0;
    for (int w = 0; w < c.warmupFrames; ++w) {
        setFrameIntensities(wind, frame++);
        renderer.draw(camera, wind);
        renderer.drawFillBaseline(camera);
        renderer.drawFillBaseline(camera, /*nearestSampling=*/true);
        renderer.draw(camera, wind, nearestTexels);
    }
    double full_s = 0.0;
    double fullNearest_s = 0.0;
    double baseline_s = 0.0;
    double nearest_s = 0.0;
    double cpuSum_ms = 0.0;
    for (int f = 0; f < c.frames; ++f) {
        setFrameIntensities(wind, frame++);
        auto start = Clock::now();
        cpuSum_ms += renderer.draw(camera, wind).cpu_ms;
        full_s += std::chrono::duration<double>(Clock::now() - start).count();
        start = Clock::now();
        renderer.drawFillBaseline(camera);
        baseline_s += std::chrono::duration<double>(Clock::now() - start).count();
        start = Clock::now();
        renderer.drawFillBaseline(camera, /*nearestSampling=*/true);
        nearest_s += std::chrono::duration<double>(Clock::now() - start).count();
        start = Clock::now();
        renderer.draw(camera, wind, nearestTexels);
        fullNearest_s += std::chrono::duration<double>(Clock::now() - start).count();
    }
    result.fps = c.frames / full_s;
    result.baselineFps = c.frames / baseline_s;
    result.nearestFps = c.frames / nearest_s;
    result.fullNearestFps = c.frames / fullNearest_s;
    result.cpu_ms = cpuSum_ms / c.frames;

    // One more full frame (untimed) for the coverage check and the optional image.
    renderer.draw(camera, wind);
    Image image;
    context->readPixels(image);
    if (!c.framePath.empty()) writeImageAtomic(image, c.framePath);
    const auto sky = [](float v) { return static_cast<int>(std::lround(v * 255.0f)); };
    long covered = 0;
    for (size_t p = 0; p < image.rgba.size(); p += 4) {
        const bool isSky = std::abs(image.rgba[p] - sky(ShellRenderer::kSkyColor[0])) <= 1 &&
                           std::abs(image.rgba[p + 1] - sky(ShellRenderer::kSkyColor[1])) <= 1 &&
                           std::abs(image.rgba[p + 2] - sky(ShellRenderer::kSkyColor[2])) <= 1;
        if (!isSky) ++covered;
    }
    result.coverage = static_cast<double>(covered) / (static_cast<double>(c.width) * c.height);
    return result;
}

}  // namespace gale::render
