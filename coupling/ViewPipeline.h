#pragma once
/// \file ViewPipeline.h
/// The per-frame loop of `gale view`, shared with `gale bench view` so the benchmark times the
/// window's own code path: the wind on its worker thread (WindWorker.h), the shell renderer, the
/// field overlays, and the present, each frame split into wind, upload, draw and present times.
///
/// @code
/// ViewPipeline view(context, inputs);     // the context is current
/// for (;;) {
///     FrameTimes times = view.draw(camera, t_s, overlaySpec, drawOptions, /*exact=*/false);
///     // heads-up text, screenshots: here, before the present
///     times.present_ms = view.present();
/// }
/// @endcode

#include <string>

#include "coupling/FieldOverlayBuilder.h"
#include "coupling/WindSource.h"
#include "coupling/WindWorker.h"
#include "render/DensityMap.h"
#include "render/FieldOverlay.h"
#include "render/GlContext.h"
#include "render/GrassInput.h"
#include "render/GrassTexture.h"
#include "render/ShellRenderer.h"

namespace gale::coupling {

/// What the view draws, all of it borrowed: everything must outlive the pipeline, and the wind
/// source belongs to the pipeline's worker thread while the pipeline lives.
struct ViewInputs {
    const render::TerrainMesh* mesh = nullptr;
    const render::GrassParams* grass = nullptr;
    const render::GrassTexture* texture = nullptr;
    const render::DensityMap* densityMap = nullptr;
    const render::Lighting* lighting = nullptr;
    WindSource* wind = nullptr;
};

/// One frame's wall times on the calling (render) thread, milliseconds.
struct FrameTimes {
    double wind_ms = 0.0;     ///< asking the worker for the frame's time and taking its snapshot
    double upload_ms = 0.0;   ///< the renderer's CPU side: group tables and changed uploads
    double draw_ms = 0.0;     ///< draw calls through glFinish: grass, terrain and overlays
    double present_ms = 0.0;  ///< the context's present (a window's copy to the screen)
    int blades = 0;           ///< near blades the frame drew (render::FrameStats::blades)
    double total_ms() const { return wind_ms + upload_ms + draw_ms + present_ms; }
};

class ViewPipeline {
  public:
    /// Compiles the renderer and overlay shaders in `context` (current, outliving the pipeline),
    /// uploads the inputs and starts the wind worker. Every pointer in `inputs` must be set
    /// (std::logic_error otherwise); the renderer's setters throw as documented in
    /// ShellRenderer.h.
    ViewPipeline(render::GlContext& context, const ViewInputs& inputs);

    /// Draws the frame for sim time t_s (seconds): asks the worker for t_s, takes its newest
    /// snapshot (exact: waits for the one of t_s, as scripted frames do), draws the grass with it
    /// and the overlays of `overlay` when any. Before the first snapshot the grass stands still.
    /// Rethrows a failure of the worker thread. present_ms is left 0: call present().
    FrameTimes draw(const render::Camera& camera, double t_s, const OverlaySpec& overlay,
                    const render::DrawOptions& options, bool exact);
    /// Presents the frame; returns its wall time in milliseconds.
    double present();

    /// The snapshot the last frame drew (serial 0: none yet).
    const WindSnapshot& shown() const { return mShown; }
    render::ShellRenderer& renderer() { return mRenderer; }
    render::FieldOverlay& overlay() { return mOverlay; }
    WindWorker& worker() { return mWorker; }

  private:
    render::GlContext& mContext;
    render::ShellRenderer mRenderer;
    render::FieldOverlay mOverlay;
    WindWorker mWorker;
    WindSnapshot mShown;
};

}  // namespace gale::coupling
