#pragma once
/// \file LiveWind.h
/// Wind the viewer drops into the unsteady flow while it runs (`gale view`: click, drag, keys):
/// a whirlwind, a gust front along a drag, a blast (a short radial outflow near the ground) and a
/// downwash (a falling column). Each adds a velocity to the solver's current field and projects
/// it, so what stays is divergence-free and the solver carries it on with the flow, over and
/// around the terrain. Call only from the thread that steps the solver (the view posts the call
/// to its wind worker, coupling/WindWorker.h).
///
/// Shapes (world metres, z up; s = smoothstep; h_g the height above the local ground):
///  - whirlwind: sim::addWhirlwind's Lamb-Oseen vortex (sim/Vortices.h), core radius_m, peak
///    speed_mps, counter-clockwise, the full column;
///  - gust front: speed_mps along the drag, over the drag's length (at least 2 radius_m) and
///    radius_m to each side, full up to 2 radius_m above the ground and tapering over radius_m;
///  - blast: radial outflow speed_mps (r / R) exp((1 - r^2 / R^2) / 2), R = radius_m, which peaks
///    at speed_mps on r = R, up to radius_m above the ground (tapering over radius_m / 2);
///  - downwash: w = -speed_mps exp(-r^2 / R^2) from radius_m / 2 above the ground up to the top.
/// The projection turns the blast and the downwash into what incompressible air makes of them:
/// air drawn in from above the blast, the downwash spreading out along the ground.

#include <array>
#include <optional>
#include <string>

#include "render/GrassInput.h"
#include "sim/PoissonSolver.h"
#include "sim/UnsteadyWind.h"

namespace gale::coupling {

enum class LiveSourceKind { Whirlwind, GustFront, Blast, Downwash };

/// "whirlwind", "gust front", "blast", "downwash".
const char* liveSourceName(LiveSourceKind kind);

struct LiveSource {
    LiveSourceKind kind = LiveSourceKind::Whirlwind;
    std::array<double, 2> wsAt_m{0.0, 0.0};  ///< where it is dropped (x, y), world metres
    std::array<double, 2> wsTo_m{0.0, 0.0};  ///< gust front: the drag's end (x, y), world metres
    double speed_mps = 6.0;                  ///< peak added speed, m/s, > 0
    double radius_m = 3.0;                   ///< core radius / half-width / radius, metres, > 0

    /// Throws gale::ParameterError naming the field (speed_mps, radius_m, positions not finite).
    void validate() const;
};

/// Adds `source` to the solver's current field and projects the field; returns the projection's
/// report (not converged is reported, not thrown). Throws gale::ParameterError on a bad source.
sim::SolveReport addLiveSource(sim::UnsteadyWindSolver& solver, const LiveSource& source);

/// Where a world ray (origin wsOrigin_m, unit direction wsDirection) first meets the terrain mesh
/// (heights interpolated bilinearly between its vertices), or nothing when it misses the mesh's
/// plan or passes above it. The mesh must be a grid of nx x ny vertices, i fastest, spaced evenly
/// along x and y (coupling::buildTerrainMesh). Throws nothing.
std::optional<glm::vec3> pickTerrain(const render::TerrainMesh& mesh, const glm::vec3& wsOrigin_m,
                                     const glm::vec3& wsDirection);

}  // namespace gale::coupling
