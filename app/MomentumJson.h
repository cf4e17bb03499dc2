#pragma once
/// \file MomentumJson.h
/// The momentum model's part of `gale solve`'s JSON report (docs/scene-format.md, [solver]).

#include <nlohmann/json.hpp>

#include "sim/MomentumWind.h"

namespace gale::app {

/// The momentum model's settings, result, levels of the coarse start and convergence history (one
/// entry per pseudo-time step of every level, with its wall times) as JSON. Does not throw beyond
/// allocation.
nlohmann::json momentumJson(const sim::MomentumReport& report,
                            const sim::MomentumSettings& settings);

}  // namespace gale::app
