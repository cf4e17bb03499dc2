/// \file ViewPipeline.cpp
/// The view's per-frame loop (see ViewPipeline.h).

#include "coupling/ViewPipeline.h"

#include <chrono>
#include <stdexcept>

namespace gale::coupling {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// `context`, once every input is known to be there (runs before any member is built).
render::GlContext& checked(render::GlContext& context, const ViewInputs& inputs) {
    if (!inputs.mesh || !inputs.grass || !inputs.texture || !inputs.densityMap ||
        !inputs.lighting || !inputs.wind)
        throw std::logic_error("ViewPipeline: every ViewInputs pointer must be set");
    return context;
}

}  // namespace

ViewPipeline::ViewPipeline(render::GlContext& context, const ViewInputs& inputs)
    : mContext(checked(context, inputs)),
      mRenderer(mContext),
      mOverlay(mContext),
      mWorker(*inputs.wind, *inputs.mesh, inputs.grass->height_m) {
    mRenderer.setTerrain(*inputs.mesh);
    mRenderer.setGrass(*inputs.grass, *inputs.texture);
    mRenderer.setDensityMap(*inputs.densityMap);
    mRenderer.setLighting(*inputs.lighting);
}

FrameTimes ViewPipeline::draw(const render::Camera& camera, double t_s, const OverlaySpec& overlay,
                              const render::DrawOptions& options, bool exact) {
    FrameTimes times;
    const auto windStart = Clock::now();
    mWorker.request(t_s, overlay);
    if (exact)
        mWorker.waitFor(t_s, mShown);
    else
        mWorker.take(mShown);
    mWorker.rethrowIfFailed();
    times.wind_ms = msSince(windStart);

    static const render::GrassWind still;  // before the wind's first step
    const render::FrameStats stats =
        mRenderer.draw(camera, mShown.serial > 0 ? mShown.wind : still, options);
    times.upload_ms = stats.cpu_ms;
    times.draw_ms = stats.gpu_ms;
    times.blades = stats.blades;
    if (overlay.any() && mShown.serial > 0) {
        const auto overlayStart = Clock::now();
        mOverlay.draw(camera, mShown.overlay);
        times.draw_ms += msSince(overlayStart);
    }
    return times;
}

double ViewPipeline::present() {
    const auto start = Clock::now();
    mContext.present();
    return msSince(start);
}

}  // namespace gale::coupling
