/// \file RenderBench.cpp
/// The paper's Table 2 set-up (Bakay 2003, 4.1): full-screen grass, 3 point lights, a ~512-triangle
/// base mesh, N layers, timed against a trivial alpha-tested fill of the same geometry.

#include "render/RenderBench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>
#include <string>

#include "render/CameraMath.h"
#include "render/GlContext.h"
#include "render/GlUtil.h"
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
constexpr float FIELD_SIZE_M = 32.0f;
constexpr float GRASS_HEIGHT_M = 0.3f;
constexpr float TILE_M = 2.0f;
constexpr int TEXTURE_SIZE = 256;
constexpr int WIND_GROUPS = 8;

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
        const int g = std::min(WIND_GROUPS - 1, static_cast<int>(d / maxDistance * WIND_GROUPS));
        vertex->group.push_back(static_cast<uint32_t>(g));
    }
    GrassWind wind;
    wind.vertex = std::move(vertex);
    wind.revision = 1;
    wind.groupIntensity.assign(WIND_GROUPS, 0.0f);
    return wind;
}

void setFrameIntensities(GrassWind& wind, int frame) {
    for (int g = 0; g < WIND_GROUPS; ++g) {
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

Camera benchCamera() {
    Camera camera;
    camera.wsPosition_m = glm::vec3(0.0f, -2.0f, 9.0f);
    camera.wsTarget_m = glm::vec3(0.0f, 0.0f, 0.0f);
    camera.fovY_deg = 45.0f;
    camera.near_m = 0.5f;
    camera.far_m = 200.0f;
    return camera;
}

GrassTexture benchTexture() {
    GrassTextureSpec spec;
    spec.size = TEXTURE_SIZE;
    spec.seed = 2002;
    return generateGrassTexture(spec);
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
    if (c.layers < 1 || c.layers > MAX_SHELLS + 1) {
        throw std::invalid_argument("ShellFillCase.layers must be in 1.." +
                                    std::to_string(MAX_SHELLS + 1) + ", got " +
                                    std::to_string(c.layers));
    }
    if (c.frames < 1 || c.warmupFrames < 0 || c.lights < 0 || c.lights > MAX_LIGHTS) {
        throw std::invalid_argument(
            "ShellFillCase: need frames >= 1, warmupFrames >= 0, lights in "
            "0.." +
            std::to_string(MAX_LIGHTS));
    }
    auto context = createOsMesaContext(c.width, c.height);
    ShellRenderer renderer(*context);
    const TerrainMesh mesh = makeFlatGridMesh(c.gridVertices, FIELD_SIZE_M, TILE_M);
    renderer.setTerrain(mesh);
    GrassParams grass;
    grass.height_m = GRASS_HEIGHT_M;
    grass.shells = c.layers - 1;
    grass.tile_m = TILE_M;
    grass.lodPixels = 0.0f;  // the table measures N full layers: no level of detail
    grass.nearBlades = 0;    // and the shells alone
    renderer.setGrass(grass, benchTexture());
    renderer.setLighting(makeBenchLighting(c.lights));
    const Camera camera = benchCamera();
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
        const bool isSky = std::abs(image.rgba[p] - sky(ShellRenderer::SKY_COLOR[0])) <= 1 &&
                           std::abs(image.rgba[p + 1] - sky(ShellRenderer::SKY_COLOR[1])) <= 1 &&
                           std::abs(image.rgba[p + 2] - sky(ShellRenderer::SKY_COLOR[2])) <= 1;
        if (!isSky) ++covered;
    }
    result.coverage = static_cast<double>(covered) / (static_cast<double>(c.width) * c.height);
    return result;
}

namespace {

double processCpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// One row of the profile: a fragment variant of shaders/profile.frag and the fixed-function state
/// it is drawn with; fragment < 0 is the full shell renderer.
struct ProfileVariant {
    const char* name;
    int fragment;
    GLenum minFilter;
    GLenum magFilter;
    bool depthTest;
    bool bottomFirst;
};

constexpr GLenum TRILINEAR = GL_LINEAR_MIPMAP_LINEAR;
constexpr ProfileVariant PROFILE_VARIANTS[] = {
    {"flat colour, no texture, no alpha test", 0, TRILINEAR, GL_LINEAR, true, false},
    {"flat colour, alpha test on a pixel hash", 1, TRILINEAR, GL_LINEAR, true, false},
    {"nearest texel of level 0 (no MIP level)", 2, GL_NEAREST, GL_NEAREST, true, false},
    {"nearest texel, nearest MIP level", 2, GL_NEAREST_MIPMAP_NEAREST, GL_NEAREST, true, false},
    {"bilinear, level 0 (no MIP level)", 2, GL_LINEAR, GL_LINEAR, true, false},
    {"bilinear, nearest MIP level", 2, GL_LINEAR_MIPMAP_NEAREST, GL_LINEAR, true, false},
    {"nearest texel, two MIP levels blended", 2, GL_NEAREST_MIPMAP_LINEAR, GL_NEAREST, true, false},
    {"trilinear: the trivial fill", 2, TRILINEAR, GL_LINEAR, true, false},
    {"trilinear, MIP level from the shader (textureLod)", 3, TRILINEAR, GL_LINEAR, true, false},
    {"trilinear, times the vertex light", 4, TRILINEAR, GL_LINEAR, true, false},
    {"trilinear, plus 30 multiply-adds", 5, TRILINEAR, GL_LINEAR, true, false},
    {"trilinear, two fetches", 6, TRILINEAR, GL_LINEAR, true, false},
    {"trilinear, depth test off", 2, TRILINEAR, GL_LINEAR, false, false},
    {"trilinear, bottom layer first", 2, TRILINEAR, GL_LINEAR, true, true},
    {"full renderer (bend, 3 lights)", -1, TRILINEAR, GL_LINEAR, true, false},
};
constexpr size_t BASELINE_VARIANT = 7;
static_assert(PROFILE_VARIANTS[BASELINE_VARIANT].fragment == 2 &&
                  PROFILE_VARIANTS[BASELINE_VARIANT].minFilter == TRILINEAR,
              "the baseline row is the trilinear fill");

}  // namespace

std::vector<FillProfileRow> profileShellFill(const FillProfileCase& c) {
    if (c.width < 1 || c.width > 16384 || c.height < 1 || c.height > 16384 || c.layers < 1 ||
        c.layers > MAX_SHELLS + 1 || c.frames < 1) {
        throw std::invalid_argument(
            "FillProfileCase: need width and height in 1..16384, layers in 1.." +
            std::to_string(MAX_SHELLS + 1) + " and frames >= 1, got " + std::to_string(c.width) +
            " x " + std::to_string(c.height) + ", " + std::to_string(c.layers) + ", " +
            std::to_string(c.frames));
    }
    auto context = createOsMesaContext(c.width, c.height);
    // The full renderer, on the benchmark's own scene (measureShellFill's set-up).
    ShellRenderer renderer(*context);
    const TerrainMesh mesh = makeFlatGridMesh(17, FIELD_SIZE_M, TILE_M);
    renderer.setTerrain(mesh);
    GrassParams grass;
    grass.height_m = GRASS_HEIGHT_M;
    grass.shells = c.layers - 1;
    grass.tile_m = TILE_M;
    grass.lodPixels = 0.0f;
    grass.nearBlades = 0;
    const GrassTexture texture = benchTexture();
    renderer.setGrass(grass, texture);
    renderer.setLighting(makeBenchLighting(3));
    const Camera camera = benchCamera();
    GrassWind wind = makeBenchWind(mesh);
    setFrameIntensities(wind, 0);

    // The profile's own layers: the same mesh, texture and camera.
    context->makeCurrent();
    std::vector<float> vertices;  // position, normal, uv
    for (size_t v = 0; v < mesh.wsPosition_m.size(); ++v) {
        const glm::vec3& p = mesh.wsPosition_m[v];
        const glm::vec3& n = mesh.wsNormal[v];
        vertices.insert(vertices.end(), {p.x, p.y, p.z, n.x, n.y, n.z, mesh.uv[v].x, mesh.uv[v].y});
    }
    std::vector<uint32_t> indices;
    for (int j = 0; j + 1 < mesh.ny; ++j) {
        for (int i = 0; i + 1 < mesh.nx; ++i) {
            const auto a = static_cast<uint32_t>(j * mesh.nx + i);
            const auto nx = static_cast<uint32_t>(mesh.nx);
            indices.insert(indices.end(), {a, a + 1, a + nx + 1, a, a + nx + 1, a + nx});
        }
    }
    GLuint name = 0;
    glGenVertexArrays(1, &name);
    const detail::VertexArray vao(name);
    glGenBuffers(1, &name);
    const detail::Buffer vbo(name);
    glGenBuffers(1, &name);
    const detail::Buffer ibo(name);
    glBindVertexArray(vao.get());
    glBindBuffer(GL_ARRAY_BUFFER, vbo.get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
                 vertices.data(), GL_STATIC_DRAW);
    const GLsizei stride = 8 * sizeof(float);
    for (GLuint attribute = 0; attribute < 3; ++attribute) {
        glEnableVertexAttribArray(attribute);
        glVertexAttribPointer(attribute, attribute == 2 ? 2 : 3, GL_FLOAT, GL_FALSE, stride,
                              reinterpret_cast<const void*>(size_t(3 * attribute) * sizeof(float)));
    }
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo.get());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(indices.size() * sizeof(uint32_t)), indices.data(),
                 GL_STATIC_DRAW);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glGenTextures(1, &name);
    const detail::Texture grassTexture(name);
    glBindTexture(GL_TEXTURE_2D, grassTexture.get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (size_t l = 0; l < texture.levels.size(); ++l) {
        const Image& level = texture.levels[l];
        glTexImage2D(GL_TEXTURE_2D, static_cast<GLint>(l), GL_RGBA8, level.width, level.height, 0,
                     GL_RGBA, GL_UNSIGNED_BYTE, level.rgba.data());
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL,
                    static_cast<GLint>(texture.levels.size()) - 1);
    glBindTexture(GL_TEXTURE_2D, 0);

    constexpr size_t VARIANTS = std::size(PROFILE_VARIANTS);
    std::vector<detail::Program> programs(VARIANTS);
    std::vector<detail::Sampler> samplers(VARIANTS);
    const glm::mat4 clip =
        clipFromWorld(camera, static_cast<float>(c.width) / static_cast<float>(c.height));
    for (size_t k = 0; k < VARIANTS; ++k) {
        const ProfileVariant& v = PROFILE_VARIANTS[k];
        if (v.fragment < 0) continue;
        programs[k] = detail::Program(
            detail::linkProgramFiles("profile.vert", "profile.frag",
                                     "#define FRAGMENT " + std::to_string(v.fragment) + "\n"));
        const GLuint p = programs[k].get();
        glUseProgram(p);
        glUniformMatrix4fv(glGetUniformLocation(p, "uClipFromWorld"), 1, GL_FALSE,
                           glm::value_ptr(clip));
        glUniform1i(glGetUniformLocation(p, "uShells"), c.layers - 1);
        glUniform1f(glGetUniformLocation(p, "uShellSpacing"),
                    c.layers > 1 ? GRASS_HEIGHT_M / static_cast<float>(c.layers - 1) : 0.0f);
        glUniform1i(glGetUniformLocation(p, "uBottomFirst"), v.bottomFirst ? 1 : 0);
        glUniform1i(glGetUniformLocation(p, "uGrass"), 0);
        glGenSamplers(1, &name);
        samplers[k] = detail::Sampler(name);
        glSamplerParameteri(name, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(v.minFilter));
        glSamplerParameteri(name, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(v.magFilter));
        glSamplerParameteri(name, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glSamplerParameteri(name, GL_TEXTURE_WRAP_T, GL_REPEAT);
    }
    glUseProgram(0);
    detail::checkGlError("profileShellFill setup");

    const auto drawVariant = [&](size_t k) {
        const ProfileVariant& v = PROFILE_VARIANTS[k];
        if (v.fragment < 0) {
            renderer.draw(camera, wind);
            return;
        }
        context->makeCurrent();
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, c.width, c.height);
        if (v.depthTest)
            glEnable(GL_DEPTH_TEST);
        else
            glDisable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glClearColor(ShellRenderer::SKY_COLOR[0], ShellRenderer::SKY_COLOR[1],
                     ShellRenderer::SKY_COLOR[2], 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glUseProgram(programs[k].get());
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, grassTexture.get());
        glBindSampler(0, samplers[k].get());
        glBindVertexArray(vao.get());
        glDrawElementsInstanced(GL_TRIANGLES, static_cast<GLsizei>(indices.size()), GL_UNSIGNED_INT,
                                nullptr, c.layers);
        glBindVertexArray(0);
        glBindSampler(0, 0);
        glUseProgram(0);
        glFinish();
    };
    for (size_t k = 0; k < VARIANTS; ++k) drawVariant(k);  // warm-up: compiles llvmpipe's code
    std::vector<std::vector<double>> cpu_ms(VARIANTS);
    std::vector<std::vector<double>> wall_ms(VARIANTS);
    for (int f = 0; f < c.frames; ++f) {
        for (size_t k = 0; k < VARIANTS; ++k) {
            const double cpuStart_ms = processCpu_ms();
            const auto wallStart = Clock::now();
            drawVariant(k);
            wall_ms[k].push_back(
                std::chrono::duration<double, std::milli>(Clock::now() - wallStart).count());
            cpu_ms[k].push_back(processCpu_ms() - cpuStart_ms);
        }
    }
    detail::checkGlError("profileShellFill");
    std::vector<FillProfileRow> rows;
    for (size_t k = 0; k < VARIANTS; ++k) {
        rows.push_back({PROFILE_VARIANTS[k].name, median(cpu_ms[k]), median(wall_ms[k]),
                        k == BASELINE_VARIANT});
    }
    return rows;
}

}  // namespace gale::render
