#pragma once
/// \file FieldOverlay.h
/// Views of the wind itself (docs/design.md 6, "views of the field"), drawn over a rendered frame:
/// speed-coloured arrows, a slice coloured by speed, streamlines coloured by speed, vortex-core
/// markers, and a legend bar with numeric labels. The renderer knows nothing of the field: it draws
/// the plain structs below, which coupling/FieldOverlayBuilder fills from a wind field (or from
/// the grass wind of a point source). Colours come from viridis (render/ColorMap.h).
///
/// @code
/// FieldOverlay overlay(context);        // after ShellRenderer, same context
/// renderer.draw(camera, wind);
/// overlay.draw(camera, data);           // depth-tested against the frame just drawn
/// context.readPixels(image);
/// @endcode

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <memory>
#include <string>
#include <vector>

#include "render/GlContext.h"
#include "render/GrassInput.h"

namespace gale::render {

/// One arrow: from wsBase_m to wsBase_m + wsVector_m (world metres; the builder chooses the
/// scale), coloured by `speed` (in FieldOverlayData::unit).
struct OverlayArrow {
    glm::vec3 wsBase_m{0.0f};
    glm::vec3 wsVector_m{0.0f};
    float speed = 0.0f;
};

/// A sheet of nx x ny points (i fastest), triangulated two per quad, coloured by speed. A quad
/// with a non-finite speed at any corner is left out (no data there).
struct OverlaySlice {
    int nx = 0;
    int ny = 0;
    std::vector<glm::vec3> wsPosition_m;
    std::vector<float> speed;
};

/// A polyline (a streamline), coloured by the speed at each point.
struct OverlayPolyline {
    std::vector<glm::vec3> wsPoint_m;
    std::vector<float> speed;
};

/// A marked point (a vortex core): a ring of radius size_m facing the camera.
struct OverlayMarker {
    glm::vec3 wsPosition_m{0.0f};
    float size_m = 0.5f;
};

struct FieldOverlayData {
    std::vector<OverlayArrow> arrows;
    OverlaySlice slice;  ///< nx == 0: no slice
    std::vector<OverlayPolyline> streamlines;
    std::vector<OverlayMarker> vortexCores;
    float speedMax = 1.0f;     ///< speed at the top of the colour map (> 0); 0 maps to the bottom
    std::string unit = "m/s";  ///< label of the legend's colour bar
    /// The legend's heading, one line each above the bar: the quantity coloured ("wind speed")
    /// and where it is measured ("2 m above ground"). Empty lines are left out.
    std::string quantity;
    std::string where;
    bool legend = true;  ///< draw the legend bar (only when something is coloured)
    /// Alpha of the slice, [0, 1]. 1: the slice shows its true colour, so the legend reads the
    /// speed `gale probe` gives at the slice (a translucent slice takes the grass tint beneath).
    float sliceOpacity = 1.0f;
};

/// The shortest arrow drawn, in pixels on screen: a slow wind's arrows stay visible.
inline constexpr float MIN_ARROW_LENGTH_PX = 12.0f;

/// Colour of the vortex-core markers: red, which viridis never uses.
inline constexpr float VORTEX_MARKER_COLOR[3] = {0.93f, 0.16f, 0.16f};

class FieldOverlay {
  public:
    /// Compiles shaders/overlay.vert and overlay.frag (throws std::runtime_error naming them).
    /// The context must be current and outlive the overlay.
    explicit FieldOverlay(GlContext& context);
    ~FieldOverlay();
    FieldOverlay(const FieldOverlay&) = delete;
    FieldOverlay& operator=(const FieldOverlay&) = delete;

    /// Draws `data` over the current framebuffer without clearing it: world geometry depth-tested
    /// against what is there (the terrain hides what lies behind it), then the legend on top.
    /// The slice goes first and writes no depth, so arrows, streamlines and markers draw over
    /// it; an arrow shorter on screen than MIN_ARROW_LENGTH_PX is drawn that long (same base and
    /// direction), and over a slice arrows are outlined in white so their colour never merges
    /// with the slice's.
    /// Throws gale::ParameterError (overlay.speed_max_mps) for speedMax <= 0, std::logic_error on
    /// a non-finite position or a slice or polyline whose arrays differ in size. Ends with
    /// glFinish.
    void draw(const Camera& camera, const FieldOverlayData& data);

    /// Draws one line of text with the built-in font at pixel (x_px, y_px) (top-left corner,
    /// origin top-left of the window), `scale` pixels per font pixel, in sRGB `color`, over a
    /// translucent dark backdrop when `backdrop` is set.
    void drawText(const std::string& text, int x_px, int y_px, int scale, const glm::vec3& color,
                  bool backdrop = true);

    /// The legend's tick values for a colour map over [0, speedMax]: multiples of 1, 2 or 5 x 10^k,
    /// 3 to 6 of them, starting at 0 and never above speedMax.
    static std::vector<float> legendTicks(float speedMax);
    /// A tick's label: as few decimals as the tick step needs ("0", "2.5", "0.25").
    static std::string tickLabel(float value, float step);

  private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

}  // namespace gale::render
