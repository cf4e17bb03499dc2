/// \file ShellRenderer.cpp
/// Shell grass (Bakay 2003, chapter 3): the terrain mesh drawn N + 1 times, instanced, with one
/// tip tilt per group computed on the CPU once per frame and the bend read from a table of bends
/// over tilts (render/BendTables.h, after thesis Table 3.2); the displacement, the Kajiya-Kay /
/// Banks lighting and the alpha test are in shaders/shell.vert and shell.frag.

#include "render/ShellRenderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "render/Bend.h"
#include "render/BendTables.h"
#include "render/CameraMath.h"
#include "render/GlInfo.h"
#include "render/GlUtil.h"
#include "render/TerrainGrid.h"

namespace gale::render {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Vertex attribute locations shared with shaders/shell.vert and fill.vert.
constexpr GLuint kPositionLoc = 0;
constexpr GLuint kNormalLoc = 1;
constexpr GLuint kUvLoc = 2;
constexpr GLuint kWindDirLoc = 3;
constexpr GLuint kGroupLoc = 4;
constexpr GLuint kGroupCoordLoc = 5;

// Texture units.
constexpr GLint kGrassUnit = 0;
constexpr GLint kBendUnit = 1;
constexpr GLint kGroupUnit = 2;
constexpr GLint kDensityUnit = 3;
constexpr GLint kDensityCutUnit = 4;

/// Static per-vertex data, interleaved.
struct TerrainVertex {
    float position[3];
    float normal[3];
    float uv[2];
};

/// Per-vertex wind data, re-uploaded only when GrassWind::revision changes.
struct WindVertex {
    float direction[3];
    uint32_t group;
    float groupCoord[2];  ///< position in the group grid (VertexWind::groupCoord), or unused
};

GLint uniform(GLuint program, const char* name) { return glGetUniformLocation(program, name); }

}  // namespace

struct ShellRenderer::Impl {
    GlContext& context;

    detail::Program shellProgram;
    detail::Program fillProgram;
    detail::VertexArray vao;
    detail::Buffer terrainVbo;
    detail::Buffer windVbo;
    detail::Buffer indexBuffer;
    detail::Texture grassTexture;
    std::unique_ptr<detail::BendTables> tables;
    std::unique_ptr<detail::DensityTables> density;

    // Uniform locations of shell.vert / shell.frag.
    struct {
        GLint clipFromWorld, eyePos, shells, topShell, bend, grass, groups, groupColumns,
            blendGroups, maxTilt, aperiodic, hasDensity, density, densityCut, densityMin,
            densitySize;
        GLint lightCount, lightPos, lightColor, lightAtten;
        GLint ambient, specularPower, specularStrength, shadowMin;
    } shellLoc{};
    struct {
        GLint clipFromWorld, shells, shellSpacing, grass;
    } fillLoc{};

    int maxTextureSize = 0;

    // Terrain.
    bool haveTerrain = false;
    size_t vertexCount = 0;
    GLsizei indexCount = 0;

    // Grass.
    bool haveGrass = false;
    GrassParams grass;

    // Lighting (uploaded to the shell program on setLighting).
    Lighting lighting;

    // Wind state on the GPU.
    bool windUploaded = false;
    bool windWasNone = false;
    uint64_t windRevision = 0;
    uint32_t windMaxGroup = 0;
    int windColumns = 0;       ///< VertexWind::groupColumns of the uploaded wind
    bool windBlends = false;   ///< the uploaded wind carries groupCoord

    explicit Impl(GlContext& ctx) : context(ctx) {}

    void init();
    void uploadLighting();
    void uploadWind(const GrassWind& wind);
    void requireReady(const char* what) const;
    void beginFrame();
};

void ShellRenderer::Impl::init() {
    context.makeCurrent();
    const GlInfo info = queryGlInfo();
    if (info.majorVersion < 4 || (info.majorVersion == 4 && info.minorVersion < 5)) {
        throw std::runtime_error("ShellRenderer needs OpenGL 4.5, the context has " + info.version);
    }
    maxTextureSize = info.maxTextureSize;

    shellProgram = detail::Program(detail::linkProgramFiles("shell.vert", "shell.frag"));
    fillProgram = detail::Program(detail::linkProgramFiles("fill.vert", "fill.frag"));

    const GLuint sp = shellProgram.get();
    // Uniform locations of shell.vert / shell.frag (-1 for a name the compiler dropped).
    const std::pair<GLint*, const char*> shellNames[] = {
        {&shellLoc.clipFromWorld, "uClipFromWorld"}, {&shellLoc.eyePos, "uEyePos"},
        {&shellLoc.shells, "uShells"}, {&shellLoc.topShell, "uTopShell"},
        {&shellLoc.bend, "uBend"}, {&shellLoc.grass, "uGrass"}, {&shellLoc.groups, "uGroupTilt"},
        {&shellLoc.groupColumns, "uGroupColumns"}, {&shellLoc.blendGroups, "uBlendGroups"},
        {&shellLoc.maxTilt, "uMaxTilt"}, {&shellLoc.aperiodic, "uAperiodic"},
        {&shellLoc.hasDensity, "uHasDensity"}, {&shellLoc.density, "uDensity"},
        {&shellLoc.densityCut, "uDensityCut"}, {&shellLoc.densityMin, "uDensityMin"},
        {&shellLoc.densitySize, "uDensitySize"}, {&shellLoc.lightCount, "uLightCount"},
        {&shellLoc.lightPos, "uLightPos"}, {&shellLoc.lightColor, "uLightColor"},
        {&shellLoc.lightAtten, "uLightAtten"}, {&shellLoc.ambient, "uAmbient"},
        {&shellLoc.specularPower, "uSpecularPower"},
        {&shellLoc.specularStrength, "uSpecularStrength"}, {&shellLoc.shadowMin, "uShadowMin"}
    };
    for (const auto& [loc, name] : shellNames) *loc = uniform(sp, name);
    // The shader's light arrays must be exactly kMaxLights long.
    GLint arraySize = 0;
    const GLuint index = glGetProgramResourceIndex(sp, GL_UNIFORM, "uLightPos[0]");
    if (index != GL_INVALID_INDEX) {
        const GLenum prop = GL_ARRAY_SIZE;
        glGetProgramResourceiv(sp, GL_UNIFORM, index, 1, &prop, 1, nullptr, &arraySize);
    }
    if (arraySize != kMaxLights) {
        throw std::runtime_error("shaders/shell.vert: MAX_LIGHTS is " + std::to_string(arraySize) +
                                 ", expected kMaxLights = " + std::to_string(kMaxLights) +
                                 " (render/RenderLimits.h)");
    }

    const GLuint fp = fillProgram.get();
    fillLoc.clipFromWorld = uniform(fp, "uClipFromWorld");
    fillLoc.shells = uniform(fp, "uShells");
    fillLoc.shellSpacing = uniform(fp, "uShellSpacing");
    fillLoc.grass = uniform(fp, "uGrass");

    glUseProgram(sp);
    glUniform1i(shellLoc.grass, kGrassUnit);
    glUniform1i(shellLoc.bend, kBendUnit);
    glUniform1i(shellLoc.groups, kGroupUnit);
    glUniform1i(shellLoc.density, kDensityUnit);
    glUniform1i(shellLoc.densityCut, kDensityCutUnit);
    glUniform1f(shellLoc.maxTilt, static_cast<float>(kMaxTipTilt_rad));
    glUseProgram(fp);
    glUniform1i(fillLoc.grass, kGrassUnit);
    glUseProgram(0);

    GLuint name = 0;
    glGenVertexArrays(1, &name);
    vao = detail::VertexArray(name);
    glGenBuffers(1, &name);
    terrainVbo = detail::Buffer(name);
    glGenBuffers(1, &name);
    windVbo = detail::Buffer(name);
    glGenBuffers(1, &name);
    indexBuffer = detail::Buffer(name);
    glGenTextures(1, &name);
    grassTexture = detail::Texture(name);
    tables = std::make_unique<detail::BendTables>();
    density = std::make_unique<detail::DensityTables>();

    glBindVertexArray(vao.get());
    glBindBuffer(GL_ARRAY_BUFFER, terrainVbo.get());
    const auto stride = static_cast<GLsizei>(sizeof(TerrainVertex));
    glEnableVertexAttribArray(kPositionLoc);
    glVertexAttribPointer(kPositionLoc, 3, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(offsetof(TerrainVertex, position)));
    glEnableVertexAttribArray(kNormalLoc);
    glVertexAttribPointer(kNormalLoc, 3, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(offsetof(TerrainVertex, normal)));
    glEnableVertexAttribArray(kUvLoc);
    glVertexAttribPointer(kUvLoc, 2, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(offsetof(TerrainVertex, uv)));
    glBindBuffer(GL_ARRAY_BUFFER, windVbo.get());
    const auto windStride = static_cast<GLsizei>(sizeof(WindVertex));
    glEnableVertexAttribArray(kWindDirLoc);
    glVertexAttribPointer(kWindDirLoc, 3, GL_FLOAT, GL_FALSE, windStride,
                          reinterpret_cast<const void*>(offsetof(WindVertex, direction)));
    glEnableVertexAttribArray(kGroupLoc);
    glVertexAttribIPointer(kGroupLoc, 1, GL_UNSIGNED_INT, windStride,
                           reinterpret_cast<const void*>(offsetof(WindVertex, group)));
    glEnableVertexAttribArray(kGroupCoordLoc);
    glVertexAttribPointer(kGroupCoordLoc, 2, GL_FLOAT, GL_FALSE, windStride,
                          reinterpret_cast<const void*>(offsetof(WindVertex, groupCoord)));
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indexBuffer.get());
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    detail::checkFramebufferComplete("ShellRenderer (default framebuffer)");
    detail::checkGlError("ShellRenderer setup");

    uploadLighting();
}

void ShellRenderer::Impl::uploadLighting() {
    const int count = static_cast<int>(lighting.lights.size());
    std::vector<glm::vec3> pos(kMaxLights, glm::vec3(0.0f));
    std::vector<glm::vec3> color(kMaxLights, glm::vec3(0.0f));
    std::vector<glm::vec3> atten(kMaxLights, glm::vec3(1.0f, 0.0f, 0.0f));
    for (int l = 0; l < count; ++l) {
        pos[l] = lighting.lights[l].wsPosition_m;
        color[l] = lighting.lights[l].color;
        atten[l] = lighting.lights[l].attenuation;
    }
    glUseProgram(shellProgram.get());
    glUniform1i(shellLoc.lightCount, count);
    glUniform3fv(shellLoc.lightPos, kMaxLights, glm::value_ptr(pos[0]));
    glUniform3fv(shellLoc.lightColor, kMaxLights, glm::value_ptr(color[0]));
    glUniform3fv(shellLoc.lightAtten, kMaxLights, glm::value_ptr(atten[0]));
    glUniform3fv(shellLoc.ambient, 1, glm::value_ptr(lighting.ambient));
    glUniform1f(shellLoc.specularPower, lighting.specularPower);
    glUniform1f(shellLoc.specularStrength, lighting.specularStrength);
    glUniform1f(shellLoc.shadowMin, lighting.selfShadowMin);
    glUseProgram(0);
}

void ShellRenderer::Impl::requireReady(const char* what) const {
    if (!haveTerrain) {
        throw std::logic_error(std::string("ShellRenderer::") + what +
                               ": setTerrain must be called first");
    }
    if (!haveGrass) {
        throw std::logic_error(std::string("ShellRenderer::") + what +
                               ": setGrass must be called first");
    }
}

void ShellRenderer::Impl::uploadWind(const GrassWind& wind) {
    const bool none = wind.groupIntensity.empty();
    const size_t n = vertexCount;
    // Size checks every frame (cheap); content checks only when the data is re-uploaded.
    auto checkSize = [&](const char* field, size_t size) {
        if (size != n && !(none && size == 0)) {
            throw std::invalid_argument("GrassWind." + std::string(field) + " has " +
                                        std::to_string(size) + " entries, expected " +
                                        std::to_string(n) + " (one per terrain vertex)" +
                                        (none ? " or 0 (no wind)" : ""));
        }
    };
    const std::vector<glm::vec3>& direction = wind.wsDirection();
    const std::vector<uint32_t>& group = wind.group();
    checkSize("wsDirection", direction.size());
    checkSize("group", group.size());
    static const std::vector<glm::vec2> kNoCoord;
    const std::vector<glm::vec2>& coord = wind.vertex ? wind.vertex->groupCoord : kNoCoord;
    const bool blends = !none && !coord.empty();
    if (blends) checkSize("vertex->groupCoord", coord.size());

    const bool needUpload =
        !windUploaded || none != windWasNone || (!none && wind.revision != windRevision);
    if (needUpload) {
        std::vector<WindVertex> data(n, WindVertex{{0.0f, 0.0f, 0.0f}, 0u, {0.0f, 0.0f}});
        uint32_t maxGroup = 0;
        if (!none) {
            for (size_t v = 0; v < n; ++v) {
                const glm::vec3& d = direction[v];
                if (!finite3(d)) {
                    throw std::invalid_argument("GrassWind.wsDirection[" + std::to_string(v) +
                                                "] is not finite");
                }
                const glm::vec2 c = blends ? coord[v] : glm::vec2(0.0f);
                if (!std::isfinite(c.x) || !std::isfinite(c.y)) {
                    throw std::invalid_argument("GrassWind.vertex->groupCoord[" +
                                                std::to_string(v) + "] is not finite");
                }
                data[v] = WindVertex{{d.x, d.y, d.z}, group[v], {c.x, c.y}};
                maxGroup = std::max(maxGroup, group[v]);
            }
        }
        glBindBuffer(GL_ARRAY_BUFFER, windVbo.get());
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(WindVertex)),
                     data.data(), GL_STATIC_DRAW);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        windUploaded = true;
        windWasNone = none;
        windRevision = wind.revision;
        windMaxGroup = maxGroup;
        windColumns = wind.vertex ? wind.vertex->groupColumns : 0;
        windBlends = blends;
    }
    if (!none && windMaxGroup >= wind.groupIntensity.size()) {
        throw std::invalid_argument("GrassWind.group holds group " + std::to_string(windMaxGroup) +
                                    ", but groupIntensity has only " +
                                    std::to_string(wind.groupIntensity.size()) + " groups");
    }
}

void ShellRenderer::Impl::beginFrame() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, context.width(), context.height());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    // Shells are seen from below on slopes and at grazing angles: no culling.
    glDisable(GL_CULL_FACE);
    glClearColor(kSkyColor[0], kSkyColor[1], kSkyColor[2], 1.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glActiveTexture(GL_TEXTURE0 + kGrassUnit);
    glBindTexture(GL_TEXTURE_2D, grassTexture.get());
}

ShellRenderer::ShellRenderer(GlContext& context) : mImpl(std::make_unique<Impl>(context)) {
    mImpl->init();
}

ShellRenderer::~ShellRenderer() = default;

void ShellRenderer::setTerrain(const TerrainMesh& mesh) {
    if (mesh.nx < 2 || mesh.ny < 2) {
        throw std::invalid_argument("TerrainMesh needs nx, ny >= 2, got " +
                                    std::to_string(mesh.nx) + " x " + std::to_string(mesh.ny));
    }
    const size_t n = static_cast<size_t>(mesh.nx) * static_cast<size_t>(mesh.ny);
    if (n > 0xFFFFFFFFull) throw std::invalid_argument("TerrainMesh has too many vertices");
    auto checkSize = [&](const char* field, size_t size) {
        if (size != n) {
            throw std::invalid_argument("TerrainMesh." + std::string(field) + " has " +
                                        std::to_string(size) +
                                        " entries, expected nx * ny = " + std::to_string(n));
        }
    };
    checkSize("wsPosition_m", mesh.wsPosition_m.size());
    checkSize("wsNormal", mesh.wsNormal.size());
    checkSize("uv", mesh.uv.size());

    std::vector<TerrainVertex> vertices(n);
    for (size_t v = 0; v < n; ++v) {
        const glm::vec3& p = mesh.wsPosition_m[v];
        const glm::vec3& nn = mesh.wsNormal[v];
        const glm::vec2& uv = mesh.uv[v];
        if (!finite3(p) || !finite3(nn) || !std::isfinite(uv.x) || !std::isfinite(uv.y)) {
            throw std::invalid_argument("TerrainMesh vertex " + std::to_string(v) +
                                        " has a non-finite position, normal or uv");
        }
        vertices[v] = TerrainVertex{{p.x, p.y, p.z}, {nn.x, nn.y, nn.z}, {uv.x, uv.y}};
    }
    const std::vector<uint32_t> indices =
        detail::gridTriangleIndices(mesh.nx, 0, mesh.nx - 1, 0, mesh.ny - 1);
    Impl& m = *mImpl;
    m.context.makeCurrent();
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, m.terrainVbo.get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(TerrainVertex)),
                 vertices.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindVertexArray(m.vao.get());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(indices.size() * sizeof(uint32_t)), indices.data(),
                 GL_STATIC_DRAW);
    glBindVertexArray(0);
    detail::checkGlError("ShellRenderer::setTerrain");
    m.vertexCount = n;
    m.indexCount = static_cast<GLsizei>(indices.size());
    m.haveTerrain = true;
    m.windUploaded = false;  // the per-vertex wind arrays must match the new vertex count
}

void ShellRenderer::setGrass(const GrassParams& params, const GrassTexture& texture) {
    if (!(params.height_m > 0.0f) || !std::isfinite(params.height_m)) {
        throw std::invalid_argument("GrassParams.height_m must be > 0, got " +
                                    std::to_string(params.height_m));
    }
    if (params.shells < 0 || params.shells > kMaxShells) {
        throw std::invalid_argument("GrassParams.shells must be in 0.." +
                                    std::to_string(kMaxShells) + ", got " +
                                    std::to_string(params.shells));
    }
    if (!(params.stiffness > 0.0f) || !std::isfinite(params.stiffness)) {
        throw std::invalid_argument("GrassParams.stiffness must be > 0, got " +
                                    std::to_string(params.stiffness));
    }
    if (texture.levels.empty()) {
        throw std::invalid_argument("GrassTexture has no levels");
    }
    for (size_t l = 0; l < texture.levels.size(); ++l) {
        const Image& level = texture.levels[l];
        const int expected = texture.levels[0].width >> l;
        if (level.width != level.height || level.width < 1 || (l > 0 && level.width != expected) ||
            level.rgba.size() != static_cast<size_t>(level.width) * level.height * 4u) {
            throw std::invalid_argument(
                "GrassTexture level " + std::to_string(l) + " is " + std::to_string(level.width) +
                "x" + std::to_string(level.height) + " with " + std::to_string(level.rgba.size()) +
                " bytes; levels must be square RGBA8, each half the previous");
        }
    }
    Impl& m = *mImpl;
    m.context.makeCurrent();
    glActiveTexture(GL_TEXTURE0 + kGrassUnit);
    glBindTexture(GL_TEXTURE_2D, m.grassTexture.get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // Rows go up top-down, so texture v = 0 is the image's top row; the texture only tiles, so
    // the orientation does not matter.
    for (size_t l = 0; l < texture.levels.size(); ++l) {
        const Image& level = texture.levels[l];
        glTexImage2D(GL_TEXTURE_2D, static_cast<GLint>(l), GL_RGBA8, level.width, level.height, 0,
                     GL_RGBA, GL_UNSIGNED_BYTE, level.rgba.data());
    }
    // Thesis 3.4: only the blade-keeping levels exist; sampling never goes past the last one.
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL,
                    static_cast<GLint>(texture.levels.size()) - 1);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    m.density->setCuts(texture.levels[0]);
    detail::checkGlError("ShellRenderer::setGrass");
    m.grass = params;
    m.haveGrass = true;
}

void ShellRenderer::setDensityMap(const DensityMap& map) {
    Impl& m = *mImpl;
    m.context.makeCurrent();
    m.density->setMap(map, m.maxTextureSize);
}

void ShellRenderer::setLighting(const Lighting& lighting) {
    if (lighting.lights.size() > static_cast<size_t>(kMaxLights)) {
        throw std::invalid_argument("Lighting has " + std::to_string(lighting.lights.size()) +
                                    " lights; the shell renderer supports at most " +
                                    std::to_string(kMaxLights) + " (kMaxLights)");
    }
    for (size_t l = 0; l < lighting.lights.size(); ++l) {
        const PointLight& light = lighting.lights[l];
        const glm::vec3& k = light.attenuation;
        if (!finite3(light.wsPosition_m) || !finite3(light.color) || !finite3(k) || k.x < 0.0f ||
            k.y < 0.0f || k.z < 0.0f || !(k.x + k.y + k.z > 0.0f)) {
            throw std::invalid_argument(
                "Lighting.lights[" + std::to_string(l) +
                "]: position and colour must be finite, attenuation (k_c, k_l, k_q) >= 0 and not "
                "all zero");
        }
    }
    if (!finite3(lighting.ambient) || !(lighting.specularPower >= 0.0f) ||
        !std::isfinite(lighting.specularPower) || !std::isfinite(lighting.specularStrength)) {
        throw std::invalid_argument(
            "Lighting: ambient and specularStrength must be finite, specularPower >= 0");
    }
    if (!(lighting.selfShadowMin >= 0.0f && lighting.selfShadowMin <= 1.0f)) {
        throw std::invalid_argument("Lighting.selfShadowMin must be in [0, 1], got " +
                                    std::to_string(lighting.selfShadowMin));
    }
    mImpl->context.makeCurrent();
    mImpl->lighting = lighting;
    mImpl->uploadLighting();
}

FrameStats ShellRenderer::draw(const Camera& camera, const GrassWind& wind) {
    return draw(camera, wind, DrawOptions{});
}

void ShellRenderer::setShellCount(int shells) {
    Impl& m = *mImpl;
    if (!m.haveGrass) throw std::logic_error("ShellRenderer::setShellCount before setGrass");
    if (shells < 0 || shells > kMaxShells)
        throw std::invalid_argument("ShellRenderer::setShellCount: shells must be in 0.." +
                                    std::to_string(kMaxShells) + ", got " +
                                    std::to_string(shells));
    m.grass.shells = shells;
}

int ShellRenderer::shellCount() const { return mImpl->grass.shells; }

FrameStats ShellRenderer::draw(const Camera& camera, const GrassWind& wind,
                               const DrawOptions& options) {
    Impl& m = *mImpl;
    m.requireReady("draw");
    const auto cpuStart = Clock::now();
    const float aspect =
        static_cast<float>(m.context.width()) / static_cast<float>(m.context.height());
    const glm::mat4 clipFromWorldM = clipFromWorld(camera, aspect);
    m.context.makeCurrent();
    m.uploadWind(wind);
    const int groupCount = static_cast<int>(wind.groupIntensity.size());
    const int columns = m.windColumns > 0 ? m.windColumns
                        : m.windBlends    ? groupCount
                                          : detail::kDefaultGroupColumns;
    m.tables->setBlade(m.grass.shells, m.grass.height_m, m.grass.stiffness);
    m.tables->setGroups(wind, columns, m.maxTextureSize);
    FrameStats stats;
    stats.cpu_ms = msSince(cpuStart);

    const auto gpuStart = Clock::now();
    m.beginFrame();
    glUseProgram(m.shellProgram.get());
    glUniformMatrix4fv(m.shellLoc.clipFromWorld, 1, GL_FALSE, glm::value_ptr(clipFromWorldM));
    glUniform3fv(m.shellLoc.eyePos, 1, glm::value_ptr(camera.wsPosition_m));
    glUniform1i(m.shellLoc.shells, m.grass.shells);
    glUniform1i(m.shellLoc.groupColumns, m.tables->columns());
    glUniform1i(m.shellLoc.blendGroups, m.windBlends && groupCount > 0 ? 1 : 0);
    glActiveTexture(GL_TEXTURE0 + kBendUnit);
    glBindTexture(GL_TEXTURE_2D, m.tables->bendTexture());
    glActiveTexture(GL_TEXTURE0 + kGroupUnit);
    glBindTexture(GL_TEXTURE_2D, m.tables->groupTexture());
    glUniform1i(m.shellLoc.aperiodic, m.grass.aperiodic ? 1 : 0);
    glUniform1i(m.shellLoc.hasDensity, m.density->active() ? 1 : 0);
    glUniform2fv(m.shellLoc.densityMin, 1, glm::value_ptr(m.density->wsMin_m()));
    glUniform2fv(m.shellLoc.densitySize, 1, glm::value_ptr(m.density->wsSize_m()));
    glActiveTexture(GL_TEXTURE0 + kDensityUnit);
    glBindTexture(GL_TEXTURE_2D, m.density->mapTexture());
    glActiveTexture(GL_TEXTURE0 + kDensityCutUnit);
    glBindTexture(GL_TEXTURE_2D, m.density->cutTexture());
    // The viewer's toggles: without grass the top shell is the ground; without terrain the
    // ground (shell 0) is left out.
    const int top = options.grass ? m.grass.shells : 0;
    const int bottom = options.terrain ? 0 : 1;
    glUniform1i(m.shellLoc.topShell, top);
    glBindVertexArray(m.vao.get());
    // Instance k is shell top - k: top shell first, ground last. The thesis (3.1) draws bottom to
    // top because its shells were blended; ours are alpha-tested and opaque with the depth test on,
    // so the image does not depend on the order, and top first lets the early depth test discard
    // the lower shells' fragments hidden under blades (measured +5-18 % fill rate on llvmpipe).
    if (top >= bottom)
        glDrawElementsInstanced(GL_TRIANGLES, m.indexCount, GL_UNSIGNED_INT, nullptr,
                                top - bottom + 1);
    glBindVertexArray(0);
    glUseProgram(0);
    glFinish();
    stats.gpu_ms = msSince(gpuStart);
    detail::checkGlError("ShellRenderer::draw");
    return stats;
}

FrameStats ShellRenderer::drawFillBaseline(const Camera& camera) {
    Impl& m = *mImpl;
    m.requireReady("drawFillBaseline");
    const float aspect =
        static_cast<float>(m.context.width()) / static_cast<float>(m.context.height());
    const glm::mat4 clipFromWorldM = clipFromWorld(camera, aspect);
    m.context.makeCurrent();
    // fill.vert reads no wind, but the VAO's wind arrays must still be backed by a full buffer.
    if (!m.windUploaded) m.uploadWind(GrassWind{});
    FrameStats stats;
    const auto gpuStart = Clock::now();
    m.beginFrame();
    glUseProgram(m.fillProgram.get());
    glUniformMatrix4fv(m.fillLoc.clipFromWorld, 1, GL_FALSE, glm::value_ptr(clipFromWorldM));
    glUniform1i(m.fillLoc.shells, m.grass.shells);
    glUniform1f(m.fillLoc.shellSpacing,
                m.grass.shells > 0 ? m.grass.height_m / static_cast<float>(m.grass.shells) : 0.0f);
    glBindVertexArray(m.vao.get());
    glDrawElementsInstanced(GL_TRIANGLES, m.indexCount, GL_UNSIGNED_INT, nullptr,
                            m.grass.shells + 1);
    glBindVertexArray(0);
    glUseProgram(0);
    glFinish();
    stats.gpu_ms = msSince(gpuStart);
    detail::checkGlError("ShellRenderer::drawFillBaseline");
    return stats;
}

}  // namespace gale::render
