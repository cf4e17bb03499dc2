#include "render/FieldOverlay.h"

#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>
#include <stdexcept>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "render/BitmapFont.h"
#include "render/CameraMath.h"
#include "render/ColorMap.h"
#include "render/GlUtil.h"

namespace gale::render {
namespace {

using gale::PI;

// Arrow shape, as fractions of the arrow's length (a quiver-plot arrow: a shaft and a head).
constexpr float ARROW_HEAD_LENGTH = 0.38f;
constexpr float ARROW_HEAD_HALF_WIDTH = 0.22f;
constexpr float ARROW_SHAFT_HALF_WIDTH = 0.07f;
/// Arrow outlines: near black, one pixel; white over a slice (whose dark blues and purples a
/// black outline would vanish into).
constexpr float ARROW_OUTLINE_GREY = 0.05f;
constexpr float ARROW_OUTLINE_OVER_SLICE_GREY = 1.0f;
// Streamline ribbons and marker rings are this many pixels wide, whatever their distance.
constexpr float LINE_WIDTH_PX = 2.0f;
constexpr int MARKER_SEGMENTS = 16;
// Legend layout, in pixels at text scale 1.
constexpr int LEGEND_MARGIN_PX = 6;
constexpr int LEGEND_BAR_WIDTH_PX = 10;
constexpr int LEGEND_BAR_STEPS = 64;  // quads in the colour bar
constexpr float BACKDROP_ALPHA = 0.6f;

struct Vertex {
    float position[3];
    float color[4];
};

bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::vec4 speedColor(float speed, float speedMax, float alpha = 1.0f) {
    return glm::vec4(viridis(speed / speedMax), alpha);
}

void pushVertex(std::vector<Vertex>& out, const glm::vec3& p, const glm::vec4& c) {
    out.push_back(Vertex{{p.x, p.y, p.z}, {c.r, c.g, c.b, c.a}});
}

void pushTriangle(std::vector<Vertex>& out, const glm::vec3& a, const glm::vec3& b,
                  const glm::vec3& c, const glm::vec4& color) {
    pushVertex(out, a, color);
    pushVertex(out, b, color);
    pushVertex(out, c, color);
}

void pushQuad(std::vector<Vertex>& out, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
              const glm::vec3& d, const glm::vec4& color) {
    pushTriangle(out, a, b, c, color);
    pushTriangle(out, a, c, d, color);
}

/// A flat arrow in the plane of its direction and the horizontal perpendicular to it, so seen
/// from above or at an angle it shows its full shape.
void pushArrow(std::vector<Vertex>& out, const OverlayArrow& a, const glm::vec4& color) {
    const float length = glm::length(a.wsVector_m);
    if (!(length > 0.0f)) return;
    const glm::vec3 d = a.wsVector_m / length;
    glm::vec3 side = glm::cross(d, glm::vec3(0.0f, 0.0f, 1.0f));
    if (glm::length(side) < 1e-3f) side = glm::vec3(1.0f, 0.0f, 0.0f);  // vertical arrow
    side = glm::normalize(side);
    const glm::vec3 tip = a.wsBase_m + a.wsVector_m;
    const glm::vec3 neck = tip - d * (ARROW_HEAD_LENGTH * length);
    const glm::vec3 s = side * (ARROW_SHAFT_HALF_WIDTH * length);
    const glm::vec3 h = side * (ARROW_HEAD_HALF_WIDTH * length);
    pushQuad(out, a.wsBase_m - s, a.wsBase_m + s, neck + s, neck - s, color);
    pushTriangle(out, neck - h, neck + h, tip, color);
}

/// The arrow's outline as line segments, so an arrow shows against a slice or grass of its own
/// colour.
void pushArrowOutline(std::vector<Vertex>& out, const OverlayArrow& a, float grey) {
    const float length = glm::length(a.wsVector_m);
    if (!(length > 0.0f)) return;
    const glm::vec3 d = a.wsVector_m / length;
    glm::vec3 side = glm::cross(d, glm::vec3(0.0f, 0.0f, 1.0f));
    if (glm::length(side) < 1e-3f) side = glm::vec3(1.0f, 0.0f, 0.0f);
    side = glm::normalize(side);
    const glm::vec3 tip = a.wsBase_m + a.wsVector_m;
    const glm::vec3 neck = tip - d * (ARROW_HEAD_LENGTH * length);
    const glm::vec3 s = side * (ARROW_SHAFT_HALF_WIDTH * length);
    const glm::vec3 h = side * (ARROW_HEAD_HALF_WIDTH * length);
    const glm::vec3 loop[7] = {a.wsBase_m - s, a.wsBase_m + s, neck + s, neck + h, tip,
                               neck - h,       neck - s};
    const glm::vec4 color(grey, grey, grey, 1.0f);
    for (int k = 0; k < 7; ++k) {
        pushVertex(out, loop[k], color);
        pushVertex(out, loop[(k + 1) % 7], color);
    }
}

struct ScreenScale {
    glm::vec3 wsEye;
    float metresPerPixelPerMetre;  // world size of one pixel at distance 1 m
    float at(const glm::vec3& p) const {
        return std::max(1e-6f, glm::length(p - wsEye)) * metresPerPixelPerMetre;
    }
};

/// `a` lengthened to MIN_ARROW_LENGTH_PX on screen (at its base's distance) if it is shorter; a
/// zero arrow stays zero (no direction to draw).
OverlayArrow atLeastMinimumSize(OverlayArrow a, const ScreenScale& screen) {
    const float length = glm::length(a.wsVector_m);
    const float min_m = MIN_ARROW_LENGTH_PX * screen.at(a.wsBase_m);
    if (length > 0.0f && length < min_m) a.wsVector_m *= min_m / length;
    return a;
}

/// A camera-facing ribbon along the polyline, LINE_WIDTH_PX wide on screen.
void pushRibbon(std::vector<Vertex>& out, const OverlayPolyline& line, float speedMax,
                const ScreenScale& screen) {
    const auto& p = line.wsPoint_m;
    for (size_t k = 0; k + 1 < p.size(); ++k) {
        const glm::vec3 along = p[k + 1] - p[k];
        if (!(glm::length(along) > 0.0f)) continue;
        auto offset = [&](const glm::vec3& q) {
            glm::vec3 side = glm::cross(along, q - screen.wsEye);
            const float len = glm::length(side);
            if (!(len > 0.0f)) return glm::vec3(0.0f);
            return side / len * (0.5f * LINE_WIDTH_PX * screen.at(q));
        };
        const glm::vec3 o0 = offset(p[k]), o1 = offset(p[k + 1]);
        const glm::vec4 c0 = speedColor(line.speed[k], speedMax);
        const glm::vec4 c1 = speedColor(line.speed[k + 1], speedMax);
        pushVertex(out, p[k] - o0, c0);
        pushVertex(out, p[k] + o0, c0);
        pushVertex(out, p[k + 1] + o1, c1);
        pushVertex(out, p[k] - o0, c0);
        pushVertex(out, p[k + 1] + o1, c1);
        pushVertex(out, p[k + 1] - o1, c1);
    }
}

/// A camera-facing ring of radius size_m, LINE_WIDTH_PX + 1 wide, plus a dot in its centre.
void pushMarker(std::vector<Vertex>& out, const OverlayMarker& m, const Camera& camera,
                const ScreenScale& screen) {
    const glm::vec3 view = glm::normalize(camera.wsTarget_m - camera.wsPosition_m);
    glm::vec3 right = glm::cross(view, glm::vec3(0.0f, 0.0f, 1.0f));
    if (glm::length(right) < 1e-3f) right = glm::vec3(1.0f, 0.0f, 0.0f);
    right = glm::normalize(right);
    const glm::vec3 up = glm::normalize(glm::cross(right, view));
    const glm::vec4 color(VORTEX_MARKER_COLOR[0], VORTEX_MARKER_COLOR[1], VORTEX_MARKER_COLOR[2],
                          1.0f);
    const float halfWidth = 0.5f * (LINE_WIDTH_PX + 1.0f) * screen.at(m.wsPosition_m);
    const float r0 = std::max(0.0f, m.size_m - halfWidth), r1 = m.size_m + halfWidth;
    for (int s = 0; s < MARKER_SEGMENTS; ++s) {
        const float a0 = float(2.0 * PI * s / MARKER_SEGMENTS);
        const float a1 = float(2.0 * PI * (s + 1) / MARKER_SEGMENTS);
        const glm::vec3 d0 = std::cos(a0) * right + std::sin(a0) * up;
        const glm::vec3 d1 = std::cos(a1) * right + std::sin(a1) * up;
        const glm::vec3& c = m.wsPosition_m;
        pushQuad(out, c + d0 * r0, c + d0 * r1, c + d1 * r1, c + d1 * r0, color);
        pushTriangle(out, c, c + d0 * (2.0f * halfWidth), c + d1 * (2.0f * halfWidth), color);
    }
}

}  // namespace

struct FieldOverlay::Impl {
    GlContext& context;
    detail::Program program;
    detail::VertexArray vao;
    detail::Buffer vbo;
    GLint clipFromWorldLoc = -1;
    std::vector<Vertex> world, screen;

    explicit Impl(GlContext& c) : context(c) {}

    /// Pixel rectangle (top-left origin) to clip space.
    glm::vec3 clipOf(float x_px, float y_px) const {
        return glm::vec3(2.0f * x_px / float(context.width()) - 1.0f,
                         1.0f - 2.0f * y_px / float(context.height()), 0.0f);
    }
    void pushRect(float x0, float y0, float x1, float y1, const glm::vec4& color) {
        pushQuad(screen, clipOf(x0, y0), clipOf(x1, y0), clipOf(x1, y1), clipOf(x0, y1), color);
    }
    void pushText(const std::string& text, int x, int y, int scale, const glm::vec4& color) {
        for (const glm::ivec2& p : textPixels(text, scale))
            pushRect(float(x + p.x), float(y + p.y), float(x + p.x + scale), float(y + p.y + scale),
                     color);
    }
    void pushLegend(const FieldOverlayData& data);

    void drawBatch(const std::vector<Vertex>& vertices, const glm::mat4& clipFromWorld,
                   GLenum mode = GL_TRIANGLES) {
        if (vertices.empty()) return;
        glBindBuffer(GL_ARRAY_BUFFER, vbo.get());
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(Vertex)), vertices.data(),
                     GL_STREAM_DRAW);
        glUniformMatrix4fv(clipFromWorldLoc, 1, GL_FALSE, glm::value_ptr(clipFromWorld));
        glDrawArrays(mode, 0, GLsizei(vertices.size()));
    }
    void begin() {
        context.makeCurrent();
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, context.width(), context.height());
        glUseProgram(program.get());
        glBindVertexArray(vao.get());
        glDisable(GL_CULL_FACE);
        glEnable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    }
    void end() {
        glBindVertexArray(0);
        glUseProgram(0);
        glDisable(GL_BLEND);
        glDepthMask(GL_TRUE);
        glFinish();
        detail::checkGlError("FieldOverlay");
    }
};

void FieldOverlay::Impl::pushLegend(const FieldOverlayData& data) {
    const int scale = context.height() >= 400 ? 2 : 1;
    const std::vector<float> ticks = legendTicks(data.speedMax);
    const float step = ticks.size() > 1 ? ticks[1] - ticks[0] : data.speedMax;
    int labelWidth = textWidth_px(data.unit, scale);
    for (float t : ticks)
        labelWidth = std::max(labelWidth, textWidth_px(tickLabel(t, step), scale));
    const int margin = LEGEND_MARGIN_PX * scale, barWidth = LEGEND_BAR_WIDTH_PX * scale;
    const int textHeight = GLYPH_HEIGHT_PX * scale;
    // The heading: the quantity and where it is measured, above the unit; "a, b" parts of a line
    // on lines of their own, and at text scale 1 when scale 2 would take over a quarter of the
    // frame's width.
    std::vector<std::string> heading;
    for (const std::string* text : {&data.quantity, &data.where}) {
        size_t from = 0;
        while (from < text->size()) {
            const size_t comma = text->find(", ", from);
            const size_t to = comma == std::string::npos ? text->size() : comma + 1;
            heading.push_back(text->substr(from, to - from));
            from = comma == std::string::npos ? to : comma + 2;
        }
    }
    int headingScale = scale, headingWidth = 0;
    for (int pass = 0; pass < 2; ++pass) {
        headingWidth = 0;
        for (const std::string& line : heading)
            headingWidth = std::max(headingWidth, textWidth_px(line, headingScale));
        if (headingWidth <= context.width() / 4 || headingScale == 1) break;
        headingScale = 1;
    }
    const int lineHeight = (GLYPH_HEIGHT_PX + 2) * headingScale;
    const int boxWidth = std::max(margin + barWidth + margin / 2 + 2 * scale + labelWidth + margin,
                                  headingWidth + 2 * margin);
    const int headingHeight = int(heading.size()) * lineHeight;
    const int boxHeight =
        std::max(4 * textHeight, int(0.5f * float(context.height()))) + headingHeight;
    const int x0 = context.width() - boxWidth - margin, y0 = margin;
    pushRect(float(x0), float(y0), float(x0 + boxWidth), float(y0 + boxHeight),
             glm::vec4(0.0f, 0.0f, 0.0f, BACKDROP_ALPHA));
    const glm::vec4 white(1.0f);
    for (size_t k = 0; k < heading.size(); ++k)
        pushText(heading[k], x0 + margin, y0 + margin + int(k) * lineHeight, headingScale, white);
    pushText(data.unit, x0 + boxWidth - margin - textWidth_px(data.unit, scale),
             y0 + margin + headingHeight, scale, white);
    // The bar: bottom = 0, top = speedMax.
    const float barTop = float(y0 + headingHeight + 2 * margin + textHeight);
    const float barBottom = float(y0 + boxHeight - margin - textHeight / 2);
    const float bx0 = float(x0 + margin), bx1 = bx0 + float(barWidth);
    for (int s = 0; s < LEGEND_BAR_STEPS; ++s) {
        const float f0 = float(s) / LEGEND_BAR_STEPS, f1 = float(s + 1) / LEGEND_BAR_STEPS;
        const glm::vec4 c(viridis(0.5f * (f0 + f1)), 1.0f);
        pushRect(bx0, barBottom - f1 * (barBottom - barTop), bx1,
                 barBottom - f0 * (barBottom - barTop), c);
    }
    for (float t : ticks) {
        const float y = barBottom - t / data.speedMax * (barBottom - barTop);
        pushRect(bx1, y - 0.5f * scale, bx1 + float(margin / 2), y + 0.5f * scale, white);
        const std::string label = tickLabel(t, step);
        pushText(label, int(bx1) + margin / 2 + 2 * scale, int(std::lround(y)) - 3 * scale, scale,
                 white);
    }
}

FieldOverlay::FieldOverlay(GlContext& context) : mImpl(std::make_unique<Impl>(context)) {
    Impl& m = *mImpl;
    context.makeCurrent();
    m.program = detail::Program(detail::linkProgramFiles("overlay.vert", "overlay.frag"));
    m.clipFromWorldLoc = glGetUniformLocation(m.program.get(), "uClipFromWorld");
    GLuint name = 0;
    glGenVertexArrays(1, &name);
    m.vao = detail::VertexArray(name);
    glGenBuffers(1, &name);
    m.vbo = detail::Buffer(name);
    glBindVertexArray(m.vao.get());
    glBindBuffer(GL_ARRAY_BUFFER, m.vbo.get());
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<void*>(offsetof(Vertex, position)));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<void*>(offsetof(Vertex, color)));
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    detail::checkGlError("FieldOverlay setup");
}

FieldOverlay::~FieldOverlay() = default;

void FieldOverlay::draw(const Camera& camera, const FieldOverlayData& data) {
    if (!(data.speedMax > 0.0f) || !std::isfinite(data.speedMax))
        throw ParameterError("overlay.speed_max_mps", formatG(data.speedMax),
                             "must be > 0 and finite");
    const OverlaySlice& slice = data.slice;
    const size_t sliceN = size_t(std::max(0, slice.nx)) * size_t(std::max(0, slice.ny));
    if (slice.nx != 0 && (slice.nx < 2 || slice.ny < 2 || slice.wsPosition_m.size() != sliceN ||
                          slice.speed.size() != sliceN))
        throw std::logic_error(
            "OverlaySlice needs nx, ny >= 2 and nx * ny positions and "
            "speeds, got " +
            std::to_string(slice.nx) + " x " + std::to_string(slice.ny) + " with " +
            std::to_string(slice.wsPosition_m.size()) + " positions, " +
            std::to_string(slice.speed.size()) + " speeds");
    for (const OverlayPolyline& line : data.streamlines)
        if (line.speed.size() != line.wsPoint_m.size())
            throw std::logic_error("OverlayPolyline has " + std::to_string(line.wsPoint_m.size()) +
                                   " points but " + std::to_string(line.speed.size()) + " speeds");
    for (const OverlayArrow& a : data.arrows)
        if (!finite3(a.wsBase_m) || !finite3(a.wsVector_m) || !std::isfinite(a.speed))
            throw std::logic_error("OverlayArrow with a non-finite base, vector or speed");

    Impl& m = *mImpl;
    const float aspect = float(m.context.width()) / float(m.context.height());
    const glm::mat4 clipFromWorldM = clipFromWorld(camera, aspect);
    ScreenScale screen{camera.wsPosition_m,
                       2.0f * std::tan(0.5f * float(radiansFromDegrees(camera.fovY_deg))) /
                           float(m.context.height())};

    m.begin();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    // The slice first, translucent, without writing depth so arrows under it still show.
    m.world.clear();
    if (slice.nx != 0) {
        for (int j = 0; j + 1 < slice.ny; ++j)
            for (int i = 0; i + 1 < slice.nx; ++i) {
                const size_t a = size_t(j) * slice.nx + i, b = a + 1, c = a + slice.nx, d = c + 1;
                bool ok = true;
                for (size_t v : {a, b, c, d})
                    ok = ok && std::isfinite(slice.speed[v]) && finite3(slice.wsPosition_m[v]);
                if (!ok) continue;
                for (size_t v : {a, b, d, a, d, c})
                    pushVertex(m.world, slice.wsPosition_m[v],
                               speedColor(slice.speed[v], data.speedMax, data.sliceOpacity));
            }
    }
    glDepthMask(GL_FALSE);
    m.drawBatch(m.world, clipFromWorldM);
    glDepthMask(GL_TRUE);

    m.world.clear();
    std::vector<OverlayArrow> arrows;
    arrows.reserve(data.arrows.size());
    for (const OverlayArrow& a : data.arrows) arrows.push_back(atLeastMinimumSize(a, screen));
    for (const OverlayArrow& a : arrows) pushArrow(m.world, a, speedColor(a.speed, data.speedMax));
    for (const OverlayPolyline& line : data.streamlines)
        pushRibbon(m.world, line, data.speedMax, screen);
    for (const OverlayMarker& marker : data.vortexCores)
        if (finite3(marker.wsPosition_m)) pushMarker(m.world, marker, camera, screen);
    m.drawBatch(m.world, clipFromWorldM);
    m.world.clear();
    const float outline = slice.nx != 0 ? ARROW_OUTLINE_OVER_SLICE_GREY : ARROW_OUTLINE_GREY;
    for (const OverlayArrow& a : arrows) pushArrowOutline(m.world, a, outline);
    m.drawBatch(m.world, clipFromWorldM, GL_LINES);

    glDisable(GL_DEPTH_TEST);
    m.screen.clear();
    const bool coloured = !data.arrows.empty() || slice.nx != 0 || !data.streamlines.empty();
    if (data.legend && coloured) m.pushLegend(data);
    m.drawBatch(m.screen, glm::mat4(1.0f));
    m.end();
}

void FieldOverlay::drawText(const std::string& text, int x_px, int y_px, int scale,
                            const glm::vec3& color, bool backdrop) {
    Impl& m = *mImpl;
    scale = std::max(1, scale);
    m.begin();
    glDisable(GL_DEPTH_TEST);
    m.screen.clear();
    if (backdrop)
        m.pushRect(float(x_px - 2 * scale), float(y_px - 2 * scale),
                   float(x_px + textWidth_px(text, scale) + 2 * scale),
                   float(y_px + GLYPH_HEIGHT_PX * scale + scale),
                   glm::vec4(0, 0, 0, BACKDROP_ALPHA));
    m.pushText(text, x_px, y_px, scale, glm::vec4(color, 1.0f));
    m.drawBatch(m.screen, glm::mat4(1.0f));
    m.end();
}

std::vector<float> FieldOverlay::legendTicks(float speedMax) {
    if (!(speedMax > 0.0f) || !std::isfinite(speedMax)) return {0.0f};
    // The smallest 1-2-5 step giving at most 5 intervals (so 3 to 6 ticks with 0).
    const double decade = std::pow(10.0, std::floor(std::log10(double(speedMax) / 5.0)));
    double step = decade;
    for (double f : {1.0, 2.0, 5.0, 10.0}) {
        step = f * decade;
        if (double(speedMax) / step <= 5.0 + 1e-9) break;
    }
    std::vector<float> ticks;
    for (int k = 0; k * step <= double(speedMax) * (1.0 + 1e-6); ++k)
        ticks.push_back(float(k * step));
    return ticks;
}

std::string FieldOverlay::tickLabel(float value, float step) {
    int decimals = 0;
    while (decimals < 6 && std::fabs(step * std::pow(10.0f, float(decimals)) -
                                     std::round(step * std::pow(10.0f, float(decimals)))) > 1e-3f)
        ++decimals;
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, double(value));
    return buf;
}

}  // namespace gale::render
