/// \file ShellRendererDraw.cpp
/// The shell renderer's frames: culling and the level of detail per terrain chunk
/// (render/TerrainChunks.h), the instanced shell draws, and the benchmark's fill baseline.

#include "base/Numbers.h"
#include "render/ShellRendererImpl.h"

namespace gale::render {
using namespace shell_detail;

void ShellRenderer::Impl::beginFrame() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, context.width(), context.height());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    // Shells are seen from below on slopes and at grazing angles: no culling.
    glDisable(GL_CULL_FACE);
    glClearColor(SKY_COLOR[0], SKY_COLOR[1], SKY_COLOR[2], 1.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glActiveTexture(GL_TEXTURE0 + GRASS_UNIT);
    glBindTexture(GL_TEXTURE_2D, grassTexture.get());
}

void ShellRenderer::Impl::updateShadow() {
    if (!shadowDirty) return;
    shadowDirty = false;
    shadowView.reset();
    if (lighting.shadows && !lighting.lights.empty() && indexCount > 0) {
        // The box a bent blade can reach: the terrain raised by the grass height.
        const glm::vec3 reach(0.0f, 0.0f, haveGrass ? grass.height_m : 0.0f);
        shadowView = detail::keyLightView(lighting.lights[0].wsPosition_m, terrainMin_m - reach,
                                          terrainMax_m + reach, detail::SHADOW_MAP_PX);
    }
    std::vector<float> visible;
    if (shadowView) {
        std::vector<glm::vec3> positions_m(terrainVertices.size()), normals(positions_m.size());
        for (size_t v = 0; v < terrainVertices.size(); ++v) {
            const TerrainVertex& t = terrainVertices[v];
            positions_m[v] = glm::vec3(t.position[0], t.position[1], t.position[2]);
            normals[v] = glm::vec3(t.normal[0], t.normal[1], t.normal[2]);
        }
        visible = detail::vertexVisibility(*shadowView, positions_m, normals, terrainIndices,
                                           terrainIndices.size());
    }
    const std::vector<float> levels =
        shadowView ? detail::levelVisibility(visible, terrainNx, terrainNy, detail::MESH_LEVELS,
                                             detail::CHUNK_QUADS)
                   : std::vector<float>();
    for (size_t v = 0; v < terrainVertices.size(); ++v)
        for (int l = 0; l < detail::MESH_LEVELS; ++l)
            terrainVertices[v].keyLight[l] =
                shadowView ? levels[v * detail::MESH_LEVELS + static_cast<size_t>(l)] : 1.0f;
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, terrainVbo.get());
    glBufferSubData(GL_ARRAY_BUFFER, 0,
                    static_cast<GLsizeiptr>(terrainVertices.size() * sizeof(TerrainVertex)),
                    terrainVertices.data());
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void ShellRenderer::Impl::setFrameUniforms(const ShellLocations& loc,
                                           const FrameUniforms& f) const {
    glUniformMatrix4fv(loc.clipFromWorld, 1, GL_FALSE, glm::value_ptr(f.clipFromWorld));
    glUniform3fv(loc.eyePos, 1, glm::value_ptr(f.wsEye_m));
    glUniform1i(loc.shells, grass.shells);
    glUniform1i(loc.groupColumns, tables->columns());
    glUniform1f(loc.lodD1, f.lodD1_m);
    glUniform1f(loc.shellFocal, f.shellFocal);
    glUniform1i(loc.lastShell, f.lastShell);
    glUniform1f(loc.nearIn, f.nearIn_m);
    glUniform1f(loc.nearR, f.nearR_m);
    // Wrapped to a day so the float keeps millisecond steps (the flutter's periods are under 2 s
    // and its phases are per vertex: the wrap is one jump a day).
    glUniform1f(loc.time, float(std::fmod(f.time_s, 86400.0)));
    glUniform3fv(loc.bladeColor, 1, glm::value_ptr(bladeColor));
    glUniform2fv(loc.densityMin, 1, glm::value_ptr(density->wsMin_m()));
    glUniform2fv(loc.densitySize, 1, glm::value_ptr(density->wsSize_m()));
}

detail::NearBladeSet ShellRenderer::Impl::placeBlades(const Camera& camera,
                                                      const glm::mat4& clipFromWorld,
                                                      float focal_px) const {
    detail::BladeGround ground;
    ground.nx = terrainNx;
    ground.ny = terrainNy;
    ground.planRegular = terrainPlanRegular;
    ground.origin_m = terrainOrigin_m;
    ground.spacing_m = terrainSpacing_m;
    ground.vertices = terrainVertices.empty() ? nullptr : terrainVertices[0].position;
    ground.stride = sizeof(TerrainVertex) / sizeof(float);
    ground.positionAt = static_cast<int>(offsetof(TerrainVertex, position) / sizeof(float));
    ground.normalAt = static_cast<int>(offsetof(TerrainVertex, normal) / sizeof(float));
    // Level 0's share: the blades stand where the full mesh is drawn.
    ground.keyLightAt = static_cast<int>(offsetof(TerrainVertex, keyLight) / sizeof(float));
    ground.wind = windVertex.get();
    ground.density = density->active() ? &densityMap : nullptr;
    ground.densityCuts = &bladeCuts;
    detail::BladeView view;
    view.clipFromWorld = clipFromWorld;
    view.wsEye_m = camera.wsPosition_m;
    view.focal_px = focal_px;
    view.grassHeight_m = grass.height_m;
    view.budget = grass.nearBlades;
    return detail::placeNearBlades(ground, bladeStats, view);
}

void ShellRenderer::Impl::uploadBlades(const std::vector<detail::BladeInstance>& blades) {
    glBindBuffer(GL_ARRAY_BUFFER, bladeVbo.get());
    // A new store each frame (the driver may keep the last one for a draw still in flight).
    glBufferData(GL_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(blades.size() * sizeof(detail::BladeInstance)),
                 blades.data(), GL_STREAM_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

glm::mat4 ShellRenderer::Impl::prepareFrame(const Camera& camera, const GrassWind& wind) {
    const float aspect = static_cast<float>(context.width()) / static_cast<float>(context.height());
    const glm::mat4 clip = clipFromWorld(camera, aspect);
    context.makeCurrent();
    uploadWind(wind);
    const int groupCount = static_cast<int>(wind.groupIntensity.size());
    const int columns = windColumns > 0 ? windColumns
                        : windBlends    ? groupCount
                                        : detail::DEFAULT_GROUP_COLUMNS;
    tables->setBlade(grass.shells, grass.height_m, grass.stiffness);
    tables->setGroups(wind, columns, maxTextureSize);
    // Before the units are bound: a rebuilt pass table binds (and then unbinds) the active unit.
    density->setShells(grass.shells);
    return clip;
}

FrameStats ShellRenderer::draw(const Camera& camera, const GrassWind& wind) {
    return draw(camera, wind, DrawOptions{});
}

FrameStats ShellRenderer::draw(const Camera& camera, const GrassWind& wind,
                               const DrawOptions& options) {
    Impl& m = *mImpl;
    m.requireReady("draw");
    const auto cpuStart = Clock::now();
    const glm::mat4 clipFromWorldM = m.prepareFrame(camera, wind);
    const int groupCount = static_cast<int>(wind.groupIntensity.size());
    FrameStats stats;
    stats.cpu_ms = msSince(cpuStart);

    const auto gpuStart = Clock::now();
    m.updateShadow();
    m.beginFrame();
    glActiveTexture(GL_TEXTURE0 + BEND_UNIT);
    glBindTexture(GL_TEXTURE_2D, m.tables->bendTexture());
    glActiveTexture(GL_TEXTURE0 + GROUP_UNIT);
    glBindTexture(GL_TEXTURE_2D, m.tables->groupTexture());
    glActiveTexture(GL_TEXTURE0 + DENSITY_UNIT);
    glBindTexture(GL_TEXTURE_2D, m.density->mapTexture());
    glActiveTexture(GL_TEXTURE0 + DENSITY_CUT_UNIT);
    glBindTexture(GL_TEXTURE_2D, m.density->cutTexture());
    glActiveTexture(GL_TEXTURE0 + SHELL_PASS_UNIT);
    glBindTexture(GL_TEXTURE_2D, m.density->passTexture());
    // The viewer's toggles: without grass the top shell is the ground; without terrain the
    // ground (shell 0) is left out.
    const int shells = options.grass ? m.grass.shells : 0;
    const int bottom = options.terrain ? 0 : 1;
    // Level of detail (render/TerrainChunks.h): D1 = 2 S f / P, f the focal length in pixels.
    const float focal_px = focalLength_px(camera, m.context.height());
    const float d1_m =
        m.grass.lodPixels > 0.0f && shells > 0
            ? 2.0f * (m.grass.height_m / static_cast<float>(shells)) * focal_px / m.grass.lodPixels
            : 0.0f;
    // The program of each chunk (ShellVariantBits): the scene's choices, plus the fade where a
    // chunk reaches the distance at which one of its shells starts to thin out. Each program gets
    // this frame's uniforms the first time a chunk uses it.
    const unsigned sceneBits = (m.grass.aperiodic ? VARIANT_APERIODIC : 0u) |
                               (m.density->active() ? VARIANT_DENSITY : 0u) |
                               (m.windBlends && groupCount > 0 ? VARIANT_BLEND : 0u);
    int lastShell = 0;  // the largest power of two <= shells (the one dropped last), 0 without
    while (shells > 0 && lastShell * 2 <= shells) lastShell = lastShell == 0 ? 1 : lastShell * 2;
    Impl::FrameUniforms frame;
    frame.clipFromWorld = clipFromWorldM;
    frame.wsEye_m = camera.wsPosition_m;
    frame.lodD1_m = d1_m;
    frame.shellFocal = shells > 0 ? m.grass.height_m / static_cast<float>(shells) * focal_px : 0.0f;
    frame.lastShell = lastShell;
    frame.time_s = wind.time_s;
    unsigned preparedPrograms = 0;  // bit k: variant k has this frame's uniforms
    GLuint boundProgram = 0;
    const auto useProgram = [&](unsigned bits) -> const ShellLocations& {
        const ShellProgram& p = m.shellProgram(bits);
        const ShellLocations& loc = p.loc;
        if (p.program.get() == boundProgram) return loc;
        boundProgram = p.program.get();
        glUseProgram(boundProgram);
        if ((preparedPrograms & (1u << bits)) != 0u) return loc;
        preparedPrograms |= 1u << bits;
        m.setFrameUniforms(loc, frame);
        return loc;
    };
    // Visible chunks, their boxes grown by the grass height: a bent blade reaches that far from
    // its root. Each takes its mesh level from its nearest point (render/TerrainChunks.h: the
    // same level over the whole chunk, so no crack opens) and is drawn band by band, each band
    // with the shells its own nearest point needs; all bands nearest first (the early depth test
    // then discards more of the far ones).
    const glm::vec3 reach(m.grass.height_m);
    struct Visible {
        float near_m, far_m;  // nearest and farthest point of the band's ground from the eye
        detail::IndexRange mesh;
        int level;  // the chunk's mesh level
    };
    std::vector<Visible> visible;
    for (const detail::TerrainChunk& chunk : m.chunks) {
        if (!detail::boxMayBeVisible(clipFromWorldM, chunk.wsMin_m - reach,
                                     chunk.wsMax_m + reach)) {
            ++stats.chunksCulled;
            continue;
        }
        ++stats.chunks;
        const float chunkNear_m =
            detail::distanceToBox(camera.wsPosition_m, chunk.wsMin_m, chunk.wsMax_m);
        const int level = detail::meshLevel(chunk, focal_px, m.grass.lodPixels, chunkNear_m);
        for (int b = 0; b < chunk.bandCount[level]; ++b) {
            const detail::ChunkBand& band = chunk.bands[level][b];
            if (!detail::boxMayBeVisible(clipFromWorldM, band.wsMin_m - reach,
                                         band.wsMax_m + reach))
                continue;
            visible.push_back(
                {detail::distanceToBox(camera.wsPosition_m, band.wsMin_m, band.wsMax_m),
                 detail::farthestInBox(camera.wsPosition_m, band.wsMin_m, band.wsMax_m), band.range,
                 level});
        }
    }
    std::sort(visible.begin(), visible.end(),
              [](const Visible& a, const Visible& b) { return a.near_m < b.near_m; });
    // The near blades first: they stand in front of most of the shells they rise from, so the
    // early depth test discards the shell fragments behind them.
    if (shells > 0 && m.grass.nearBlades > 0) {
        const auto placeStart = Clock::now();
        const detail::NearBladeSet set = m.placeBlades(camera, clipFromWorldM, focal_px);
        stats.cpu_ms += msSince(placeStart);
        if (!set.blades.empty()) {
            frame.nearIn_m = set.innerRadius_m;
            frame.nearR_m = set.radius_m;
            m.uploadBlades(set.blades);
            useProgram((sceneBits & VARIANT_BLEND) | VARIANT_BLADES);
            glBindVertexArray(m.bladeVao.get());
            glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, detail::BLADE_STRIP_VERTICES,
                                  static_cast<GLsizei>(set.blades.size()));
            stats.blades = static_cast<int>(set.blades.size());
            stats.bladeRadius_m = set.radius_m;
            stats.triangles +=
                static_cast<long long>(set.blades.size()) * (detail::BLADE_STRIP_VERTICES - 2);
        }
    }
    if (options.nearestTexels) glBindSampler(GRASS_UNIT, m.nearestSampler.get());
    glEnable(GL_CLIP_DISTANCE0);
    glBindVertexArray(m.vao.get());
    for (const auto& [near_m, far_m, mesh, level] : visible) {
        const detail::ShellRange range = detail::shellRange(shells, d1_m, near_m);
        // Instance k is shell top - k stride: top shell first, ground last. The thesis (3.1)
        // draws bottom to top because its shells were blended; ours are alpha-tested and opaque
        // with the depth test on, so the image does not depend on the order, and top first lets
        // the early depth test discard the lower shells' fragments hidden under blades (measured
        // +5-18 % fill rate on llvmpipe).
        if (range.top < bottom) continue;
        const int count = (range.top - bottom) / range.stride + 1;
        // A band within the near blades' R hands its shells over to them (shell.vert uNearR).
        const bool fades =
            detail::chunkMayFade(range, shells, d1_m, far_m) || near_m < frame.nearR_m;
        const ShellLocations& loc = useProgram(sceneBits | (fades ? VARIANT_FADE : 0u));
        glUniform1i(loc.topShell, range.top);
        glUniform1i(loc.shellStride, range.stride);
        glUniform1i(loc.meshLevel, level);
        glDrawElementsInstanced(
            GL_TRIANGLES, static_cast<GLsizei>(mesh.count), GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(size_t(mesh.first) * sizeof(uint32_t)), count);
        stats.layers += count;
        stats.triangles += static_cast<long long>(mesh.count / 3) * count;
    }
    glBindVertexArray(0);
    glDisable(GL_CLIP_DISTANCE0);
    glBindSampler(GRASS_UNIT, 0);
    glUseProgram(0);
    glFinish();
    stats.gpu_ms = msSince(gpuStart);
    detail::checkGlError("ShellRenderer::draw");
    return stats;
}

NearBladeCapture ShellRenderer::captureNearBlades(const Camera& camera, const GrassWind& wind) {
    Impl& m = *mImpl;
    m.requireReady("captureNearBlades");
    const glm::mat4 clipFromWorldM = m.prepareFrame(camera, wind);
    const int groupCount = static_cast<int>(wind.groupIntensity.size());
    m.updateShadow();
    const float focal_px = focalLength_px(camera, m.context.height());
    NearBladeCapture capture;
    if (m.grass.shells <= 0 || m.grass.nearBlades <= 0) return capture;
    detail::NearBladeSet set = m.placeBlades(camera, clipFromWorldM, focal_px);
    capture.radius_m = set.radius_m;
    capture.innerRadius_m = set.innerRadius_m;
    capture.blades = std::move(set.blades);
    if (capture.blades.empty()) return capture;
    const bool blend = m.windBlends && groupCount > 0;
    std::unique_ptr<ShellProgram>& program = m.bladeCapturePrograms[blend ? 1 : 0];
    if (!program)
        program =
            m.makeShellProgram((blend ? VARIANT_BLEND : 0u) | VARIANT_BLADES, {"vBladeWorld"});
    m.uploadBlades(capture.blades);
    glActiveTexture(GL_TEXTURE0 + BEND_UNIT);
    glBindTexture(GL_TEXTURE_2D, m.tables->bendTexture());
    glActiveTexture(GL_TEXTURE0 + GROUP_UNIT);
    glBindTexture(GL_TEXTURE_2D, m.tables->groupTexture());
    glUseProgram(program->program.get());
    Impl::FrameUniforms frame;
    frame.clipFromWorld = clipFromWorldM;
    frame.wsEye_m = camera.wsPosition_m;
    frame.time_s = wind.time_s;
    m.setFrameUniforms(program->loc, frame);
    const size_t count = capture.blades.size() * detail::BLADE_STRIP_VERTICES;
    GLuint name = 0;
    glGenBuffers(1, &name);
    const detail::Buffer recorded(name);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, recorded.get());
    glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, static_cast<GLsizeiptr>(count * sizeof(glm::vec3)),
                 nullptr, GL_STATIC_READ);
    glEnable(GL_RASTERIZER_DISCARD);
    glBindVertexArray(m.bladeVao.get());
    glBeginTransformFeedback(GL_POINTS);
    glDrawArraysInstanced(GL_POINTS, 0, detail::BLADE_STRIP_VERTICES,
                          static_cast<GLsizei>(capture.blades.size()));
    glEndTransformFeedback();
    glBindVertexArray(0);
    glDisable(GL_RASTERIZER_DISCARD);
    capture.vertices.resize(count);
    glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0,
                       static_cast<GLsizeiptr>(count * sizeof(glm::vec3)), capture.vertices.data());
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    glUseProgram(0);
    detail::checkGlError("ShellRenderer::captureNearBlades");
    return capture;
}

FrameStats ShellRenderer::drawFillBaseline(const Camera& camera, bool nearestSampling) {
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
    // A sampler object overrides the texture's own filtering while it is bound to the unit.
    if (nearestSampling) glBindSampler(GRASS_UNIT, m.nearestSampler.get());
    glBindVertexArray(m.vao.get());
    glDrawElementsInstanced(GL_TRIANGLES, m.indexCount, GL_UNSIGNED_INT, nullptr,
                            m.grass.shells + 1);
    glBindVertexArray(0);
    glBindSampler(GRASS_UNIT, 0);
    glUseProgram(0);
    glFinish();
    stats.gpu_ms = msSince(gpuStart);
    detail::checkGlError("ShellRenderer::drawFillBaseline");
    return stats;
}

}  // namespace gale::render
