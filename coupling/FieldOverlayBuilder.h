#pragma once
/// \file FieldOverlayBuilder.h
/// Turns a wind field into the plain overlay structs of render/FieldOverlay.h (docs/design.md 6,
/// views of the field): arrows on a grid over the terrain, a terrain-following slice coloured by
/// speed, streamlines traced from the upstream edge, and vortex cores where the Q-criterion passes
/// a threshold. Works from any sim::WindField, whichever solver made it; for the point-source
/// heuristic, which has no velocity field, from the grass wind itself (direction x intensity).

#include <algorithm>
#include <array>
#include <functional>
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <vector>

#include "coupling/WindSource.h"
#include "render/FieldOverlay.h"
#include "render/GrassInput.h"
#include "sim/WindField.h"

namespace gale::coupling {

/// The scene's [overlay] section (docs/scene-format.md). Heights are above the local ground.
struct OverlaySpec {
    bool arrows = false;
    /// Grid spacing of the arrows, metres, > 0; unset: 1/16 of the terrain's larger side.
    std::optional<double> arrowSpacing_m;
    /// Arrow bases this high above the ground, metres, >= 0; unset: 1.25 x the grass height.
    std::optional<double> arrowHeight_m;
    bool slice = false;
    double sliceHeight_m = 2.0;  ///< terrain-following slice this high above the ground, > 0
    bool streamlines = false;
    int streamlineCount = 12;  ///< seeds along the upstream edge, 1..1000
    bool vortexCores = false;
    /// Q threshold, 1/s^2, > 0; unset: automatic (see buildFieldOverlay).
    std::optional<double> vortexQ_per_s2;
    bool legend = true;
    /// Top of the colour map, m/s, > 0; unset: the largest speed shown, rounded up.
    std::optional<double> speedMax_mps;
    /// With speedMax_mps unset: the automatic top never goes below this, m/s. A run passes the last
    /// frame's top here so its colour scale only ever grows (frames stay comparable, the legend
    /// does not flicker as gusts come and go); see OverlayScaleKeeper.
    double speedMaxFloor_mps = 0.0;

    bool any() const { return arrows || slice || streamlines || vortexCores; }
};

/// Holds an automatic colour scale steady over a run: frame(spec) gives the spec to build a frame
/// with (the scene's, plus the largest top so far as its floor); seen(data) records the top the
/// frame used. A fixed speed_max_mps passes through unchanged.
class OverlayScaleKeeper {
  public:
    OverlaySpec frame(OverlaySpec spec) const {
        spec.speedMaxFloor_mps = mTop;
        return spec;
    }
    void seen(const render::FieldOverlayData& data) {
        mTop = std::max(mTop, double(data.speedMax));
    }

  private:
    double mTop = 0.0;
};

/// Throws gale::ParameterError with the scene key (overlay.arrow_spacing_m ...) on a bad value.
void validate(const OverlaySpec& spec);

/// The terrain's height under a point, by bilinear interpolation of a render mesh (a regular grid
/// in x and y, i fastest); points outside are clamped to the edge.
class MeshHeight {
  public:
    /// std::logic_error unless the mesh is an nx x ny grid with nx, ny >= 2.
    explicit MeshHeight(const render::TerrainMesh& mesh);
    double at(double wsX_m, double wsY_m) const;
    double minX() const { return mX0; }
    double maxX() const { return mX1; }
    double minY() const { return mY0; }
    double maxY() const { return mY1; }

  private:
    const render::TerrainMesh& mMesh;
    double mX0, mX1, mY0, mY1;
};

/// Velocity, m/s, at a world position, metres.
using VelocityFn = std::function<glm::dvec3(const glm::dvec3& wsPos_m)>;

/// One step of the explicit midpoint rule (RK2): x + dt u(x + dt/2 u(x)). Exact for uniform flow
/// (moves by u dt) and second order in dt.
glm::dvec3 rk2Step(const VelocityFn& velocity, const glm::dvec3& wsPos_m, double dt_s);

/// A streamline from `seed`: RK2 steps of arc length about step_m (dt = step_m / |u|), until the
/// speed falls below minSpeed_mps (outside the field, under the terrain, a stagnation point) or
/// maxPoints points are reached. Returns the points, seed first.
std::vector<glm::dvec3> traceStreamline(const VelocityFn& velocity, const glm::dvec3& seed,
                                        double step_m, int maxPoints, double minSpeed_mps = 1e-4);

/// The Q-criterion of Hunt, Wray and Moin (1988): Q = (|Omega|^2 - |S|^2) / 2 with S and Omega
/// the symmetric and antisymmetric parts of the velocity gradient gradient[i][j] = d u_i / d x_j,
/// 1/s^2. Q > 0 where rotation dominates strain: a vortex core. Solid-body rotation at rate w
/// gives Q = w^2; pure strain gives Q < 0.
double qCriterion(const std::array<std::array<double, 3>, 3>& gradient);

/// Overlays of `field` over `mesh`. Arrows: a grid of spacing arrowSpacing_m inset half a spacing
/// from the terrain's edges, each at arrowHeight_m above the ground showing the field's velocity
/// there, 0.85 spacing long at speedMax. Slice: a grid at about the arrow spacing / 4 (at most
/// 128 x 128), sliceHeight_m above the ground. Streamlines: streamlineCount seeds evenly along the
/// terrain's upstream edge (the side the mean wind on the slice comes from) at sliceHeight_m,
/// traced with RK2 in steps of half a voxel. Vortex cores: air cells whose Q (central differences
/// of cell-centre velocities) exceeds the threshold and is a local maximum of its 3 x 3 x 3
/// neighbours, the strongest 24 at least 5 cells apart; the automatic threshold is
/// max(0.25 max Q, (0.1 U / h)^2), U the largest speed and h the voxel size, and cells within two
/// of the terrain are skipped (their differences read extrapolated faces), so an irrotational
/// field marks nothing. A core's marker sits where it touches the ground: on the grass tops
/// (grassHeight_m above the ground) under the core's cell. Thread-safe for a const field.
render::FieldOverlayData buildFieldOverlay(const sim::WindField& field,
                                           const render::TerrainMesh& mesh, const OverlaySpec& spec,
                                           double grassHeight_m);

/// Overlays of a wind without a velocity field (the point source): arrows only, along each
/// nearest vertex's wind direction, coloured and scaled by its group's |intensity| (unit
/// "intensity"; 1 tilts the tip 75.7 degrees, the top of the map unless speedMax_mps is given).
render::FieldOverlayData buildGrassWindOverlay(const render::GrassWind& wind,
                                               const render::TerrainMesh& mesh,
                                               const OverlaySpec& spec, double grassHeight_m);

/// Overlays of whatever `source` has: its currentField() through buildFieldOverlay, or, for a
/// source without a field, `wind` (its last update) through buildGrassWindOverlay. An empty
/// FieldOverlayData (nothing to draw) when spec.any() is false.
render::FieldOverlayData buildOverlay(const WindSource& source, const render::GrassWind& wind,
                                      const render::TerrainMesh& mesh, const OverlaySpec& spec,
                                      double grassHeight_m);

/// The top of the colour map for speeds up to `maxSpeed`: rounded up to a multiple of the legend's
/// tick step (so the top label is a round number); 1 for a zero or non-finite speed.
float niceSpeedMax(float maxSpeed);

}  // namespace gale::coupling
