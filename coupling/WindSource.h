#pragma once
/// \file WindSource.h
/// The seam between wind and grass: anything that can fill a render::GrassWind for a time t.
/// The paper's point source and the solved field both implement it, so the renderer never changes
/// when one replaces the other.

#include <string>

#include "render/GrassInput.h"

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
    /// One line for `gale check` and reports.
    virtual std::string describe() const = 0;
};

}  // namespace gale::coupling
