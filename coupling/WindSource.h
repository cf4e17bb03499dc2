#pragma once
/// \file WindSource.h
/// The seam between wind and grass: anything that can fill a render::GrassWind for a time t.
/// The paper's point source and the solved field both implement it, so the renderer never changes
/// when one replaces the other.

#include <functional>
#include <string>

#include "render/GrassInput.h"

namespace gale::sim {
class WindField;  // sim/WindField.h (no OpenVDB there either)
}

namespace gale::coupling {

class WindSource {
  public:
    virtual ~WindSource() = default;
    /// Number of animation-step groups this source produces (>= 1).
    virtual int groupCount() const = 0;
    /// Brings `wind` to time t_s (seconds from the start of the run): per-group intensities always;
    /// per-vertex directions and groups only when they change, bumping wind.revision then.
    /// `wind` must be the object returned by a previous call or empty.
    virtual void update(double t_s, render::GrassWind& wind) = 0;
    /// update() that may stop early: a source that steps a solver asks `stop` before each step
    /// and, when it returns true, brings `wind` to the time its solver reached instead. Returns
    /// the time `wind` now shows, seconds (t_s unless stopped; never earlier than the previous
    /// update's). The default cannot stop: it calls update(t_s, wind). The wind worker passes
    /// "work was posted" so a dropped source need not wait for the whole update under way.
    virtual double updateUntil(double t_s, render::GrassWind& wind,
                               const std::function<bool()>& stop) {
        (void)stop;
        update(t_s, wind);
        return t_s;
    }
    /// One line for `gale check` and reports.
    virtual std::string describe() const = 0;
    /// The velocity field (world axes, m/s) behind the wind at the last update, for views of the
    /// field (coupling/FieldOverlayBuilder); nullptr when the source has none (the point source).
    /// Valid until the next update() or the source's destruction.
    virtual const sim::WindField* currentField() const { return nullptr; }
    /// One short line on the solver work of the last update (steps, iterations, residual, CFL),
    /// for the viewer's heads-up line; empty when the source solves nothing per update.
    virtual std::string stepReport() const { return {}; }
};

}  // namespace gale::coupling
