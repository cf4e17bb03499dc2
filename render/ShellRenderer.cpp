/// \file ShellRenderer.cpp
/// Shell grass (Bakay 2003, chapter 3): the terrain mesh drawn N + 1 times, instanced, with one
/// tip tilt per group computed on the CPU once per frame and the bend read from a table of bends
/// over tilts (render/BendTables.h, after thesis Table 3.2); the displacement, the Kajiya-Kay /
/// Banks lighting and the alpha test are in shaders/shell.vert and shell.frag.

#include "render/ShellRenderer.h"

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "render/ShellRendererImpl.h"

namespace gale::render {
using namespace shell_detail;

void ShellRenderer::Impl::init() {
    context.makeCurrent();
    const GlInfo info = queryGlInfo();
    if (info.majorVersion < 4 || (info.majorVersion == 4 && info.minorVersion < 5)) {
        throw std::runtime_error("ShellRenderer needs OpenGL 4.5, the context has " + info.version);
    }
    maxTextureSize = info.maxTextureSize;

    fillProgram = detail::Program(detail::linkProgramFiles("fill.vert", "fill.frag"));
    // The plain variant now, so a shader that does not compile fails here, not at the first draw.
    shellProgram(0u);

    const GLuint fp = fillProgram.get();
    fillLoc.clipFromWorld = uniform(fp, "uClipFromWorld");
    fillLoc.shells = uniform(fp, "uShells");
    fillLoc.shellSpacing = uniform(fp, "uShellSpacing");
    fillLoc.grass = uniform(fp, "uGrass");

    glUseProgram(fp);
    glUniform1i(fillLoc.grass, GRASS_UNIT);
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
    glGenSamplers(1, &name);
    nearestSampler = detail::Sampler(name);
    glSamplerParameteri(name, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glSamplerParameteri(name, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(name, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glSamplerParameteri(name, GL_TEXTURE_WRAP_T, GL_REPEAT);
    tables = std::make_unique<detail::BendTables>();
    density = std::make_unique<detail::DensityTables>();

    glBindVertexArray(vao.get());
    glBindBuffer(GL_ARRAY_BUFFER, terrainVbo.get());
    const auto stride = static_cast<GLsizei>(sizeof(TerrainVertex));
    glEnableVertexAttribArray(POSITION_LOC);
    glVertexAttribPointer(POSITION_LOC, 3, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(offsetof(TerrainVertex, position)));
    glEnableVertexAttribArray(NORMAL_LOC);
    glVertexAttribPointer(NORMAL_LOC, 3, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(offsetof(TerrainVertex, normal)));
    glEnableVertexAttribArray(UV_LOC);
    glVertexAttribPointer(UV_LOC, 2, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(offsetof(TerrainVertex, uv)));
    static_assert(detail::MESH_LEVELS == 6, "the key light's levels take a vec4 and a vec2");
    glEnableVertexAttribArray(KEY_LIGHT_LOC);
    glVertexAttribPointer(KEY_LIGHT_LOC, 4, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(offsetof(TerrainVertex, keyLight)));
    glEnableVertexAttribArray(KEY_LIGHT_LOC + 1);
    glVertexAttribPointer(
        KEY_LIGHT_LOC + 1, 2, GL_FLOAT, GL_FALSE, stride,
        reinterpret_cast<const void*>(offsetof(TerrainVertex, keyLight) + 4 * sizeof(float)));
    glBindBuffer(GL_ARRAY_BUFFER, windVbo.get());
    const auto windStride = static_cast<GLsizei>(sizeof(WindVertex));
    glEnableVertexAttribArray(WIND_DIR_LOC);
    glVertexAttribPointer(WIND_DIR_LOC, 3, GL_FLOAT, GL_FALSE, windStride,
                          reinterpret_cast<const void*>(offsetof(WindVertex, direction)));
    glEnableVertexAttribArray(GROUP_LOC);
    glVertexAttribIPointer(GROUP_LOC, 1, GL_UNSIGNED_INT, windStride,
                           reinterpret_cast<const void*>(offsetof(WindVertex, group)));
    glEnableVertexAttribArray(GROUP_COORD_LOC);
    glVertexAttribPointer(GROUP_COORD_LOC, 2, GL_FLOAT, GL_FALSE, windStride,
                          reinterpret_cast<const void*>(offsetof(WindVertex, groupCoord)));
    glEnableVertexAttribArray(FLUTTER_LOC);
    glVertexAttribPointer(FLUTTER_LOC, 1, GL_FLOAT, GL_FALSE, windStride,
                          reinterpret_cast<const void*>(offsetof(WindVertex, flutter_rad)));
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indexBuffer.get());
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);

    // The near blades: every attribute per instance (shell.vert, BLADES).
    glGenVertexArrays(1, &name);
    bladeVao = detail::VertexArray(name);
    glGenBuffers(1, &name);
    bladeVbo = detail::Buffer(name);
    glBindVertexArray(bladeVao.get());
    glBindBuffer(GL_ARRAY_BUFFER, bladeVbo.get());
    using detail::BladeInstance;
    constexpr auto bladeStride = static_cast<GLsizei>(sizeof(BladeInstance));
    const auto perBlade = [](GLuint loc, GLint size, size_t offset) {
        glEnableVertexAttribArray(loc);
        glVertexAttribPointer(loc, size, GL_FLOAT, GL_FALSE, bladeStride,
                              reinterpret_cast<const void*>(offset));
        glVertexAttribDivisor(loc, 1);
    };
    perBlade(POSITION_LOC, 3, offsetof(BladeInstance, root));
    perBlade(NORMAL_LOC, 3, offsetof(BladeInstance, normal));
    perBlade(UV_LOC, 4, offsetof(BladeInstance, blade));
    perBlade(WIND_DIR_LOC, 3, offsetof(BladeInstance, windDir));
    glEnableVertexAttribArray(GROUP_LOC);
    glVertexAttribIPointer(GROUP_LOC, 1, GL_UNSIGNED_INT, bladeStride,
                           reinterpret_cast<const void*>(offsetof(BladeInstance, group)));
    glVertexAttribDivisor(GROUP_LOC, 1);
    perBlade(GROUP_COORD_LOC, 2, offsetof(BladeInstance, groupCoord));
    perBlade(FLUTTER_LOC, 1, offsetof(BladeInstance, flutter_rad));
    perBlade(KEY_LIGHT_LOC, 4, offsetof(BladeInstance, color));
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    detail::checkFramebufferComplete("ShellRenderer (default framebuffer)");
    detail::checkGlError("ShellRenderer setup");
}

namespace shell_detail {
std::string shellVariantDefines(unsigned bits) {
    const auto line = [bits](const char* name, unsigned bit) {
        return std::string("#define ") + name + ((bits & bit) != 0u ? " 1\n" : " 0\n");
    };
    return line("APERIODIC", VARIANT_APERIODIC) + line("FADE", VARIANT_FADE) +
           line("DENSITY", VARIANT_DENSITY) + line("BLEND_GROUPS", VARIANT_BLEND) +
           line("BLADES", VARIANT_BLADES) + "#define BLADES_SEGMENTS " +
           std::to_string(detail::BLADE_SEGMENTS) + "\n";
}
}  // namespace shell_detail

ShellProgram& ShellRenderer::Impl::shellProgram(unsigned bits) {
    std::unique_ptr<ShellProgram>& slot = shellPrograms.at(bits);
    if (!slot) slot = makeShellProgram(bits, {});
    return *slot;
}

std::unique_ptr<ShellProgram> ShellRenderer::Impl::makeShellProgram(
    unsigned bits, const std::vector<const char*>& feedback) const {
    auto p = std::make_unique<ShellProgram>();
    p->program = detail::Program(
        detail::linkProgramFiles("shell.vert", "shell.frag", shellVariantDefines(bits), feedback));
    const GLuint sp = p->program.get();
    ShellLocations& loc = p->loc;
    const std::pair<GLint*, const char*> names[] = {{&loc.clipFromWorld, "uClipFromWorld"},
                                                    {&loc.eyePos, "uEyePos"},
                                                    {&loc.shells, "uShells"},
                                                    {&loc.topShell, "uTopShell"},
                                                    {&loc.shellStride, "uShellStride"},
                                                    {&loc.lodD1, "uLodD1"},
                                                    {&loc.lastShell, "uLastShell"},
                                                    {&loc.time, "uTime_s"},
                                                    {&loc.bladeColor, "uBladeColor"},
                                                    {&loc.bend, "uBend"},
                                                    {&loc.grass, "uGrass"},
                                                    {&loc.groups, "uGroupTilt"},
                                                    {&loc.groupColumns, "uGroupColumns"},
                                                    {&loc.maxTilt, "uMaxTilt"},
                                                    {&loc.density, "uDensity"},
                                                    {&loc.densityCut, "uDensityCut"},
                                                    {&loc.shellPass, "uShellPass"},
                                                    {&loc.shellFocal, "uShellFocal"},
                                                    {&loc.meshLevel, "uMeshLevel"},
                                                    {&loc.densityMin, "uDensityMin"},
                                                    {&loc.densitySize, "uDensitySize"},
                                                    {&loc.nearIn, "uNearIn"},
                                                    {&loc.nearR, "uNearR"},
                                                    {&loc.lightCount, "uLightCount"},
                                                    {&loc.lightPos, "uLightPos"},
                                                    {&loc.lightColor, "uLightColor"},
                                                    {&loc.lightAtten, "uLightAtten"},
                                                    {&loc.ambient, "uAmbient"},
                                                    {&loc.specularPower, "uSpecularPower"},
                                                    {&loc.specularStrength, "uSpecularStrength"},
                                                    {&loc.shadowMin, "uShadowMin"}};
    for (const auto& [where, name] : names) *where = uniform(sp, name);
    // The shader's light arrays must be exactly MAX_LIGHTS long.
    GLint arraySize = 0;
    const GLuint index = glGetProgramResourceIndex(sp, GL_UNIFORM, "uLightPos[0]");
    if (index != GL_INVALID_INDEX) {
        const GLenum prop = GL_ARRAY_SIZE;
        glGetProgramResourceiv(sp, GL_UNIFORM, index, 1, &prop, 1, nullptr, &arraySize);
    }
    if (arraySize != MAX_LIGHTS) {
        throw std::runtime_error("shaders/shell.vert: MAX_LIGHTS is " + std::to_string(arraySize) +
                                 ", expected MAX_LIGHTS = " + std::to_string(MAX_LIGHTS) +
                                 " (render/RenderLimits.h)");
    }
    glUseProgram(sp);
    glUniform1i(loc.grass, GRASS_UNIT);
    glUniform1i(loc.bend, BEND_UNIT);
    glUniform1i(loc.groups, GROUP_UNIT);
    glUniform1i(loc.density, DENSITY_UNIT);
    glUniform1i(loc.densityCut, DENSITY_CUT_UNIT);
    glUniform1i(loc.shellPass, SHELL_PASS_UNIT);
    glUniform1f(loc.maxTilt, static_cast<float>(MAX_TIP_TILT_RAD));
    glUseProgram(0);
    uploadLighting(*p);
    return p;
}

void ShellRenderer::Impl::uploadLighting(const ShellProgram& program) const {
    const ShellLocations& shellLoc = program.loc;
    const int count = static_cast<int>(lighting.lights.size());
    std::vector<glm::vec3> pos(MAX_LIGHTS, glm::vec3(0.0f));
    std::vector<glm::vec3> color(MAX_LIGHTS, glm::vec3(0.0f));
    std::vector<glm::vec3> atten(MAX_LIGHTS, glm::vec3(1.0f, 0.0f, 0.0f));
    for (int l = 0; l < count; ++l) {
        pos[l] = lighting.lights[l].wsPosition_m;
        color[l] = lighting.lights[l].color;
        atten[l] = lighting.lights[l].attenuation;
    }
    glUseProgram(program.program.get());
    glUniform1i(shellLoc.lightCount, count);
    glUniform3fv(shellLoc.lightPos, MAX_LIGHTS, glm::value_ptr(pos[0]));
    glUniform3fv(shellLoc.lightColor, MAX_LIGHTS, glm::value_ptr(color[0]));
    glUniform3fv(shellLoc.lightAtten, MAX_LIGHTS, glm::value_ptr(atten[0]));
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
            throw std::logic_error("GrassWind." + std::string(field) + " has " +
                                   std::to_string(size) + " entries, expected " +
                                   std::to_string(n) + " (one per terrain vertex)" +
                                   (none ? " or 0 (no wind)" : ""));
        }
    };
    const std::vector<glm::vec3>& direction = wind.wsDirection();
    const std::vector<uint32_t>& group = wind.group();
    checkSize("wsDirection", direction.size());
    checkSize("group", group.size());
    static const std::vector<glm::vec2> NO_COORD;
    const std::vector<glm::vec2>& coord = wind.vertex ? wind.vertex->groupCoord : NO_COORD;
    const bool blends = !none && !coord.empty();
    if (blends) checkSize("vertex->groupCoord", coord.size());
    static const std::vector<float> NO_FLUTTER;
    const std::vector<float>& flutter = wind.vertex ? wind.vertex->flutter_rad : NO_FLUTTER;
    const bool flutters = !none && !flutter.empty();
    if (flutters) checkSize("vertex->flutter_rad", flutter.size());

    const bool needUpload =
        !windUploaded || none != windWasNone || (!none && wind.revision != windRevision);
    if (needUpload) {
        std::vector<WindVertex> data(n, WindVertex{{0.0f, 0.0f, 0.0f}, 0u, {0.0f, 0.0f}, 0.0f});
        uint32_t maxGroup = 0;
        if (!none) {
            for (size_t v = 0; v < n; ++v) {
                const glm::vec3& d = direction[v];
                if (!finite3(d)) {
                    throw std::logic_error("GrassWind.wsDirection[" + std::to_string(v) +
                                           "] is not finite");
                }
                const glm::vec2 c = blends ? coord[v] : glm::vec2(0.0f);
                if (!std::isfinite(c.x) || !std::isfinite(c.y)) {
                    throw std::logic_error("GrassWind.vertex->groupCoord[" + std::to_string(v) +
                                           "] is not finite");
                }
                const float f = flutters ? flutter[v] : 0.0f;
                if (!(f >= 0.0f) || !std::isfinite(f)) {
                    throw std::logic_error("GrassWind.vertex->flutter_rad[" + std::to_string(v) +
                                           "] is not finite and >= 0");
                }
                data[v] = WindVertex{{d.x, d.y, d.z}, group[v], {c.x, c.y}, f};
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
        // The near blades read the wind the shells were given: the uploaded revision's.
        windVertex = none ? nullptr : wind.vertex;
    }
    if (!none && windMaxGroup >= wind.groupIntensity.size()) {
        throw std::logic_error("GrassWind.group holds group " + std::to_string(windMaxGroup) +
                               ", but groupIntensity has only " +
                               std::to_string(wind.groupIntensity.size()) + " groups");
    }
}

glm::vec3 shell_detail::meanBladeColor(const Image& level) {
    glm::dvec3 sum(0.0);
    size_t blades = 0;
    for (size_t p = 0; p + 3 < level.rgba.size(); p += 4) {
        if (level.rgba[p + 3] == 0) continue;
        sum += glm::dvec3(level.rgba[p], level.rgba[p + 1], level.rgba[p + 2]);
        ++blades;
    }
    // A texture without blades: the ground's mean colour stands in for itself.
    if (blades == 0) {
        for (size_t p = 0; p + 3 < level.rgba.size(); p += 4)
            sum += glm::dvec3(level.rgba[p], level.rgba[p + 1], level.rgba[p + 2]);
        blades = std::max<size_t>(level.rgba.size() / 4, 1);
    }
    return glm::vec3(sum / (255.0 * static_cast<double>(blades)));
}

ShellRenderer::ShellRenderer(GlContext& context) : mImpl(std::make_unique<Impl>(context)) {
    mImpl->init();
}

ShellRenderer::~ShellRenderer() = default;

void ShellRenderer::setTerrain(const TerrainMesh& mesh) {
    if (mesh.nx < 2 || mesh.ny < 2) {
        throw std::logic_error("TerrainMesh needs nx, ny >= 2, got " + std::to_string(mesh.nx) +
                               " x " + std::to_string(mesh.ny));
    }
    const size_t n = static_cast<size_t>(mesh.nx) * static_cast<size_t>(mesh.ny);
    if (n > 0xFFFFFFFFull) throw std::logic_error("TerrainMesh has too many vertices");
    auto checkSize = [&](const char* field, size_t size) {
        if (size != n) {
            throw std::logic_error("TerrainMesh." + std::string(field) + " has " +
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
            throw std::logic_error("TerrainMesh vertex " + std::to_string(v) +
                                   " has a non-finite position, normal or uv");
        }
        vertices[v] = TerrainVertex{{p.x, p.y, p.z},
                                    {nn.x, nn.y, nn.z},
                                    {uv.x, uv.y},
                                    {1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f}};
    }
    std::vector<uint32_t> indices;
    std::vector<detail::TerrainChunk> chunks =
        detail::buildChunks(mesh.nx, mesh.ny, mesh.wsPosition_m, indices);
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
    // The full mesh: every chunk's level 0, at the start of the index buffer (buildChunks).
    m.indexCount = static_cast<GLsizei>(static_cast<size_t>(mesh.nx - 1) * (mesh.ny - 1) * 6u);
    m.chunks = std::move(chunks);
    m.terrainIndices.assign(indices.begin(), indices.begin() + m.indexCount);
    m.terrainVertices = std::move(vertices);
    m.terrainNx = mesh.nx;
    m.terrainNy = mesh.ny;
    m.terrainPlanRegular = detail::planRegular(mesh.nx, mesh.ny, mesh.wsPosition_m,
                                               m.terrainOrigin_m, m.terrainSpacing_m);
    m.terrainMin_m = m.terrainMax_m = mesh.wsPosition_m[0];
    for (const glm::vec3& p : mesh.wsPosition_m) {
        m.terrainMin_m = glm::min(m.terrainMin_m, p);
        m.terrainMax_m = glm::max(m.terrainMax_m, p);
    }
    m.shadowDirty = true;
    m.haveTerrain = true;
    m.windUploaded = false;  // the per-vertex wind arrays must match the new vertex count
}

void ShellRenderer::setGrass(const GrassParams& params, const GrassTexture& texture) {
    if (!(params.height_m > 0.0f) || !std::isfinite(params.height_m)) {
        throw ParameterError("grass.height_m", formatG(params.height_m), "must be > 0 and finite");
    }
    if (params.shells < 0 || params.shells > MAX_SHELLS) {
        throw ParameterError("grass.shells", std::to_string(params.shells),
                             "must be in 0.." + std::to_string(MAX_SHELLS));
    }
    if (!(params.lodPixels >= 0.0f) || !std::isfinite(params.lodPixels)) {
        throw ParameterError("grass.lod_pixels", formatG(params.lodPixels),
                             "must be >= 0 and finite");
    }
    if (!(params.stiffness > 0.0f) || !std::isfinite(params.stiffness)) {
        throw ParameterError("grass.stiffness", formatG(params.stiffness),
                             "must be > 0 and finite");
    }
    if (!(params.tile_m > 0.0f) || !std::isfinite(params.tile_m)) {
        throw ParameterError("grass.tile_m", formatG(params.tile_m), "must be > 0 and finite");
    }
    if (params.nearBlades < 0 || params.nearBlades > MAX_NEAR_BLADES) {
        throw ParameterError("grass.near_blades", std::to_string(params.nearBlades),
                             "must be in 0.." + std::to_string(MAX_NEAR_BLADES));
    }
    if (texture.levels.empty()) {
        throw std::logic_error("GrassTexture has no levels");
    }
    for (size_t l = 0; l < texture.levels.size(); ++l) {
        const Image& level = texture.levels[l];
        const int expected = texture.levels[0].width >> l;
        if (level.width != level.height || level.width < 1 || (l > 0 && level.width != expected) ||
            level.rgba.size() != static_cast<size_t>(level.width) * level.height * 4u) {
            throw std::logic_error(
                "GrassTexture level " + std::to_string(l) + " is " + std::to_string(level.width) +
                "x" + std::to_string(level.height) + " with " + std::to_string(level.rgba.size()) +
                " bytes; levels must be square RGBA8, each half the previous");
        }
    }
    Impl& m = *mImpl;
    m.context.makeCurrent();
    glActiveTexture(GL_TEXTURE0 + GRASS_UNIT);
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
    m.bladeColor = meanBladeColor(texture.levels[0]);
    m.bladeStats = detail::bladeStatistics(texture.levels[0], params.tile_m);
    m.bladeCuts = densityCuts(texture.levels[0]);
    detail::checkGlError("ShellRenderer::setGrass");
    // The map's box holds the grass: a new height redraws it, nothing else of the grass does.
    if (!m.haveGrass || params.height_m != m.grass.height_m) m.shadowDirty = true;
    m.grass = params;
    m.haveGrass = true;
}

void ShellRenderer::setDensityMap(const DensityMap& map) {
    Impl& m = *mImpl;
    m.context.makeCurrent();
    m.density->setMap(map, m.maxTextureSize);
    m.densityMap = map;
}

void ShellRenderer::setLighting(const Lighting& lighting) {
    if (lighting.lights.size() > static_cast<size_t>(MAX_LIGHTS)) {
        throw ParameterError(
            "lighting.light", std::to_string(lighting.lights.size()) + " lights",
            "must hold at most " + std::to_string(MAX_LIGHTS) + " lights (MAX_LIGHTS)");
    }
    for (size_t l = 0; l < lighting.lights.size(); ++l) {
        const PointLight& light = lighting.lights[l];
        const glm::vec3& k = light.attenuation;
        if (!finite3(light.wsPosition_m) || !finite3(light.color) || !finite3(k) || k.x < 0.0f ||
            k.y < 0.0f || k.z < 0.0f || !(k.x + k.y + k.z > 0.0f)) {
            throw ParameterError(
                "lighting.light[" + std::to_string(l) + "]." +
                    (!finite3(light.wsPosition_m) ? "position_m"
                     : !finite3(light.color)      ? "color"
                                                  : "attenuation"),
                "a non-finite or negative value",
                "position and colour must be finite, attenuation (k_c, k_l, k_q) >= 0 and not "
                "all zero");
        }
    }
    if (!finite3(lighting.ambient) || !(lighting.specularPower >= 0.0f) ||
        !std::isfinite(lighting.specularPower) || !std::isfinite(lighting.specularStrength)) {
        throw ParameterError(!finite3(lighting.ambient) ? "lighting.ambient"
                             : !std::isfinite(lighting.specularStrength)
                                 ? "lighting.specular_strength"
                                 : "lighting.specular_power",
                             "a non-finite or negative value",
                             "ambient and specular_strength must be finite, specular_power >= 0");
    }
    if (!(lighting.selfShadowMin >= 0.0f && lighting.selfShadowMin <= 1.0f)) {
        throw ParameterError("lighting.self_shadow_min", formatG(lighting.selfShadowMin),
                             "must be in [0, 1]");
    }
    mImpl->context.makeCurrent();
    mImpl->lighting = lighting;
    mImpl->shadowDirty = true;
    for (const auto& program : mImpl->shellPrograms)
        if (program) mImpl->uploadLighting(*program);
}

void ShellRenderer::setShellCount(int shells) {
    Impl& m = *mImpl;
    if (!m.haveGrass) throw std::logic_error("ShellRenderer::setShellCount before setGrass");
    if (shells < 0 || shells > MAX_SHELLS)
        throw ParameterError("grass.shells", std::to_string(shells),
                             "must be in 0.." + std::to_string(MAX_SHELLS));
    m.grass.shells = shells;
}

int ShellRenderer::shellCount() const { return mImpl->grass.shells; }

}  // namespace gale::render
