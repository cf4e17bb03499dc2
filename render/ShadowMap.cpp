/// \file ShadowMap.cpp
/// The key light's depth map of the terrain (render/ShadowMap.h).

#include "render/ShadowMap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "render/GlUtil.h"

namespace gale::render::detail {
namespace {

bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

std::optional<ShadowView> keyLightView(const glm::vec3& light_m, const glm::vec3& lo,
                                       const glm::vec3& hi, int sizePx) {
    if (!finite3(light_m) || !finite3(lo) || !finite3(hi) || sizePx < 1) return std::nullopt;
    const glm::vec3 centre = 0.5f * (lo + hi);
    const float radius = 0.5f * glm::length(hi - lo);
    const glm::vec3 toLight = light_m - centre;
    const float distance = glm::length(toLight);
    if (!(radius > 0.0f) || !(distance > 1.05f * radius)) return std::nullopt;
    const glm::vec3 dir = toLight / distance;  // from the box towards the light
    const glm::vec3 up = std::abs(dir.z) < 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    ShadowView view;
    glm::mat4 clipFromLight(1.0f), lightFromWorld(1.0f);
    if (distance > DIRECTIONAL_DISTANCE_RATIO * radius) {
        // A direction: look along -dir from outside the box; fit the box's corners.
        lightFromWorld = glm::lookAt(centre + 2.0f * radius * dir, centre, up);
        glm::vec3 vmin(std::numeric_limits<float>::max()), vmax(-std::numeric_limits<float>::max());
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y,
                                   (c & 4) ? hi.z : lo.z);
            const glm::vec3 v = glm::vec3(lightFromWorld * glm::vec4(corner, 1.0f));
            vmin = glm::min(vmin, v);
            vmax = glm::max(vmax, v);
        }
        // The view looks down -z: depths run from -vmax.z (nearest) to -vmin.z.
        const float margin = 0.01f * radius;
        clipFromLight =
            glm::ortho(vmin.x, vmax.x, vmin.y, vmax.y, -vmax.z - margin, -vmin.z + margin);
        view.texel_m = std::max(vmax.x - vmin.x, vmax.y - vmin.y) / static_cast<float>(sizePx);
    } else {
        // A point: a cone from the light around the box's bounding sphere.
        lightFromWorld = glm::lookAt(light_m, centre, up);
        const float halfAngle = std::asin(std::min(radius / distance, 1.0f));
        clipFromLight =
            glm::perspective(2.0f * halfAngle, 1.0f, distance - radius, distance + radius);
        view.texel_m = 2.0f * distance * std::tan(halfAngle) / static_cast<float>(sizePx);
    }
    view.clipFromWorld = clipFromLight * lightFromWorld;
    const glm::mat4 textureFromClip = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) *
                                      glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
    view.textureFromWorld = textureFromClip * view.clipFromWorld;
    return view;
}

float mapVisibility(const std::vector<float>& depth, int sizePx, const glm::vec3& t) {
    const float x = t.x * static_cast<float>(sizePx) - 0.5f;
    const float y = t.y * static_cast<float>(sizePx) - 0.5f;
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(t.z)) return 1.0f;
    const float x0 = std::floor(x), y0 = std::floor(y);
    const float fx = x - x0, fy = y - y0;
    const auto lit = [&](float tx, float ty) {
        if (tx < 0.0f || ty < 0.0f || tx >= static_cast<float>(sizePx) ||
            ty >= static_cast<float>(sizePx))
            return 1.0f;
        const size_t k =
            static_cast<size_t>(ty) * static_cast<size_t>(sizePx) + static_cast<size_t>(tx);
        return t.z <= depth[k] ? 1.0f : 0.0f;
    };
    return (1.0f - fy) * ((1.0f - fx) * lit(x0, y0) + fx * lit(x0 + 1.0f, y0)) +
           fy * ((1.0f - fx) * lit(x0, y0 + 1.0f) + fx * lit(x0 + 1.0f, y0 + 1.0f));
}

std::vector<float> levelVisibility(const std::vector<float>& visible, int nx, int ny, int levels,
                                   int chunkQuads) {
    const size_t n = static_cast<size_t>(nx) * static_cast<size_t>(ny);
    std::vector<float> out(n * static_cast<size_t>(levels), 1.0f);
    if (visible.size() != n || levels < 1) return out;
    // Summed-area table, (nx + 1) x (ny + 1), in double.
    std::vector<double> sat(static_cast<size_t>(nx + 1) * static_cast<size_t>(ny + 1), 0.0);
    const auto at = [&](int i, int j) -> double& {
        return sat[static_cast<size_t>(j) * static_cast<size_t>(nx + 1) + static_cast<size_t>(i)];
    };
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            at(i + 1, j + 1) =
                visible[static_cast<size_t>(j) * nx + i] + at(i, j + 1) + at(i + 1, j) - at(i, j);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const size_t v = static_cast<size_t>(j) * nx + i;
            const bool border =
                i % chunkQuads == 0 || j % chunkQuads == 0 || i == nx - 1 || j == ny - 1;
            for (int l = 0; l < levels; ++l) {
                float value = visible[v];
                if (l > 0 && !border) {
                    const int h = 1 << (l - 1);
                    const int i0 = std::max(i - h, 0), i1 = std::min(i + h, nx - 1);
                    const int j0 = std::max(j - h, 0), j1 = std::min(j + h, ny - 1);
                    const double sum =
                        at(i1 + 1, j1 + 1) - at(i0, j1 + 1) - at(i1 + 1, j0) + at(i0, j0);
                    value = static_cast<float>(sum / double((i1 - i0 + 1) * (j1 - j0 + 1)));
                }
                out[v * static_cast<size_t>(levels) + static_cast<size_t>(l)] = value;
            }
        }
    return out;
}

std::vector<float> vertexVisibility(const ShadowView& view,
                                    const std::vector<glm::vec3>& positions_m,
                                    const std::vector<glm::vec3>& normals,
                                    const std::vector<uint32_t>& indices, size_t indexCount) {
    std::vector<float> depth(static_cast<size_t>(SHADOW_MAP_PX) * SHADOW_MAP_PX);
    {
        // The pass's objects, deleted at the end of this block.
        Program program(linkProgramFiles("shadow.vert", "shadow.frag"));
        GLuint name = 0;
        glGenVertexArrays(1, &name);
        VertexArray vao(name);
        glGenBuffers(1, &name);
        Buffer vertices(name);
        glGenBuffers(1, &name);
        Buffer elements(name);
        glGenTextures(1, &name);
        Texture depthTexture(name);
        glGenFramebuffers(1, &name);
        Framebuffer fbo(name);

        glBindVertexArray(vao.get());
        glBindBuffer(GL_ARRAY_BUFFER, vertices.get());
        glBufferData(GL_ARRAY_BUFFER,
                     static_cast<GLsizeiptr>(positions_m.size() * sizeof(glm::vec3)),
                     positions_m.data(), GL_STATIC_DRAW);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, elements.get());
        glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                     static_cast<GLsizeiptr>(indexCount * sizeof(uint32_t)), indices.data(),
                     GL_STATIC_DRAW);

        glBindTexture(GL_TEXTURE_2D, depthTexture.get());
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, SHADOW_MAP_PX, SHADOW_MAP_PX);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D,
                               depthTexture.get(), 0);
        glDrawBuffer(GL_NONE);
        glReadBuffer(GL_NONE);
        checkFramebufferComplete("shadow map");

        glViewport(0, 0, SHADOW_MAP_PX, SHADOW_MAP_PX);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glClearDepth(1.0);
        glClear(GL_DEPTH_BUFFER_BIT);
        // Slope-scaled offset: a slope the light grazes does not shadow itself.
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(2.0f, 4.0f);
        glUseProgram(program.get());
        glUniformMatrix4fv(glGetUniformLocation(program.get(), "uClipFromWorld"), 1, GL_FALSE,
                           &view.clipFromWorld[0][0]);
        glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(indexCount), GL_UNSIGNED_INT, nullptr);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glGetTexImage(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
        checkGlError("shadow map");
        glDisable(GL_POLYGON_OFFSET_FILL);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glBindVertexArray(0);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        glBindTexture(GL_TEXTURE_2D, 0);
        glUseProgram(0);
    }
    const float offset_m = SHADOW_NORMAL_OFFSET_TEXELS * view.texel_m;
    std::vector<float> visible(positions_m.size(), 1.0f);
    for (size_t v = 0; v < positions_m.size(); ++v) {
        const glm::vec4 t =
            view.textureFromWorld * glm::vec4(positions_m[v] + offset_m * normals[v], 1.0f);
        visible[v] = mapVisibility(depth, SHADOW_MAP_PX, glm::vec3(t) / t.w);
    }
    return visible;
}

}  // namespace gale::render::detail
