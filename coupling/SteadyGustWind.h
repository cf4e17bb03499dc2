#pragma once
/// \file SteadyGustWind.h
/// Gusts over a steady solved field, the cheap kinematic mode of DESIGN 4.2: the mass-consistent
/// solution is linear in the ambient wind, so an ambient speed scaled by g(t) gives the field
/// scaled by g(t) at every instant. We let that scaling travel downwind as a front at the
/// convection speed c, so a vertex at distance s downwind of the terrain's upwind edge feels
/// g(t - s / c): the paper's animation steps, with arrival times from the flow instead of the
/// distance from a point. The instantaneous field is then not exactly divergence-free where the
/// front is; the unsteady solver (gusts that are part of the flow) does without that shortcut.
///
/// Groups are K = arrivalBands x levels bins of (arrival time, steady intensity); a group's
/// intensity is its mean steady intensity times g(t - its mean arrival time), or that drive
/// through a damped oscillator per group. Per frame: O(K). Once: O(vertices).

#include <memory>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "coupling/FieldWind.h"
#include "coupling/GroupOscillators.h"
#include "coupling/GustCurve.h"
#include "coupling/WindSource.h"

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
    /// ambient wind the curve scales (g = 1 is that field). Throws std::invalid_argument naming
    /// the field on a bad spec or a size mismatch.
    SteadyGustWind(const render::TerrainMesh& mesh, const std::vector<glm::vec3>& wsVelocity_mps,
                   const SteadyGustSpec& spec, GustCurve curve);
    int groupCount() const override { return static_cast<int>(mGroupBase.size()); }
    void update(double t_s, render::GrassWind& wind) override;
    std::string describe() const override;
    /// Keeps the solved field the step velocities were sampled from, so views of the field can
    /// show it (currentField()); the source itself never reads it.
    void keepField(std::shared_ptr<const sim::WindField> field) { mField = std::move(field); }
    const sim::WindField* currentField() const override { return mField.get(); }

    /// Arrival delay of vertex v, seconds; for tests.
    double arrival_s(size_t v) const { return mArrival_s[v]; }

private:
    std::shared_ptr<const sim::WindField> mField;
    SteadyGustSpec mSpec;
    GustCurve mCurve;
    std::shared_ptr<const render::VertexWind> mVertex;  // directions and groups, fixed
    std::vector<float> mArrival_s;
    std::vector<double> mGroupBase, mGroupArrival_s;
    std::optional<GroupOscillators> mOscillators;
};

}  // namespace gale::coupling
