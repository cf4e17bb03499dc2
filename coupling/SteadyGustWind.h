#pragma once
/// \file SteadyGustWind.h
/// Gusts over a steady solved field, the cheap kinematic mode of docs/design.md 4.2: the
/// mass-consistent solution is linear in the ambient wind, so an ambient speed scaled by g(t) gives
/// the field scaled by g(t) at every instant. We let that scaling travel downwind as a front at the
/// convection speed c, so a vertex at distance s downwind of the terrain's upwind edge feels
/// g(t - s / c): the paper's animation steps, with arrival times from the flow instead of the
/// distance from a point. The instantaneous field is then not exactly divergence-free where the
/// front is; the unsteady solver (gusts that are part of the flow) does without that shortcut.
///
/// Groups are K = arrivalBands x levels bins of (arrival time, steady intensity); a group's
/// intensity is its mean steady intensity times g(t - its mean arrival time), or that drive
/// through a damped oscillator per group. Per frame: O(K). Once: O(vertices).

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <vector>

#include "coupling/FieldWind.h"
#include "coupling/GroupOscillators.h"
#include "coupling/GustCurve.h"
#include "coupling/WindSource.h"
#include "sim/WindField.h"

namespace gale::coupling {

struct SteadyGustSpec {
    FieldWindSpec response;       ///< bend speed, clamp, oscillator; grouping and groups ignored
    int arrivalBands = 16;        ///< bins of arrival time, 1..1024
    int levels = 4;               ///< bins of steady intensity, 1..256
    double convection_mps = 5.0;  ///< front speed c, > 0 (the ambient speed is a good choice)
    glm::vec3 wsDirection{1.0f, 0.0f, 0.0f};  ///< horizontal direction the gust travels
};

class SteadyGustWind : public WindSource {
  public:
    /// wsVelocity_mps: the steady field at grass height above each vertex (FieldSampling), for the
    /// ambient wind the curve scales (g = 1 is that field). Throws gale::ParameterError naming the
    /// scene key on a bad spec (wind.arrival_bands, wind.levels, ...), std::logic_error on a size
    /// mismatch or a convection speed that is not > 0 and finite.
    SteadyGustWind(const render::TerrainMesh& mesh, const std::vector<glm::vec3>& wsVelocity_mps,
                   const SteadyGustSpec& spec, GustCurve curve);
    int groupCount() const override { return static_cast<int>(mGroupBase.size()); }
    void update(double t_s, render::GrassWind& wind) override;
    std::string describe() const override;
    /// Keeps the steady field the velocities were sampled from, so views of the field can show
    /// it; the grass never reads it.
    void keepField(std::shared_ptr<const sim::WindField> field);
    /// The kept steady field as the grass feels it at the last update's time: every face velocity
    /// scaled by g(t - arrival) at the face's plan position, the same travelling front the groups
    /// follow. Built on the first call after an update (O(faces); the scaling is computed once per
    /// face column), so runs without views of the field never pay for it. Null without a kept
    /// field.
    const sim::WindField* currentField() const override;

    /// Arrival delay of vertex v, seconds; for tests.
    double arrival_s(size_t v) const { return mArrival_s[v]; }
    /// Arrival delay of the front at plan position (x, y), seconds (negative upwind of the mesh).
    double arrivalAt_s(double wsX_m, double wsY_m) const;

    /// The turbulent flutter amplitude per vertex, radians (coupling/Flutter.h; empty: none).
    /// Throws std::logic_error on a size other than 0 or the vertex count.
    void setFlutter(std::vector<float> flutter_rad);

  private:
    std::shared_ptr<const sim::WindField> mField;
    glm::vec2 mAlong{1.0f, 0.0f};  // unit plan direction the front travels
    double mMinAlong_m = 0.0;      // the mesh's most upwind position along it
    double mLastUpdate_s = 0.0;
    mutable std::optional<sim::WindField> mGustField;  // mField at mGustField_s
    mutable double mGustField_s = 0.0;
    SteadyGustSpec mSpec;
    GustCurve mCurve;
    std::shared_ptr<const render::VertexWind> mVertex;  // directions and groups, fixed
    std::vector<float> mArrival_s;
    std::vector<double> mGroupBase, mGroupArrival_s;
    std::optional<GroupOscillators> mOscillators;
};

}  // namespace gale::coupling
