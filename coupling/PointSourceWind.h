#pragma once
/// \file PointSourceWind.h
/// The paper's wind (Bakay, Lalonde, Heidrich 2002, section 3): each vertex's wind vector is the
/// direction from the vertex to a source point, projected onto the vertex's tangent plane
/// (V = W - (W.N)N); each vertex's animation step is its distance from the source, quantised into
/// `steps` rings; ring k feels the gust curve delayed by k * stepDelay_s, so waves travel outwards.
/// This is the baseline the solved field replaces.

#include <glm/vec3.hpp>
#include <memory>

#include "coupling/GustCurve.h"
#include "coupling/TangentWind.h"
#include "coupling/WindSource.h"
#include "render/GrassInput.h"

namespace gale::coupling {

struct PointSourceSpec {
    glm::vec3 wsSource_m{0.0f};  ///< the source point, world metres
    int steps = 16;              ///< animation steps (groups), 1..1024
    double stepDelay_s = 0.15;   ///< delay of the gust between neighbouring rings, seconds
    bool blowAway = true;        ///< true: grass bends away from the source (a gust from there)
    /// Give every vertex its place between rings so the renderer blends neighbouring rings (no
    /// stripes at ring edges); false: each vertex shows its ring alone (the paper's).
    bool blendGroups = true;
};

class PointSourceWind : public WindSource {
  public:
    /// Throws gale::ParameterError naming the scene key (wind.steps, wind.step_delay_s,
    /// wind.source_m) on a bad spec, std::logic_error when the mesh has not one normal per
    /// position.
    PointSourceWind(const render::TerrainMesh& mesh, const PointSourceSpec& spec, GustCurve curve);
    int groupCount() const override { return mSpec.steps; }
    void update(double t_s, render::GrassWind& wind) override;
    std::string describe() const override;

    /// The group (ring) of vertex v; for tests.
    uint32_t groupOf(size_t v) const { return mVertex->group[v]; }
    /// Time delay of group g relative to group 0, seconds.
    double groupDelay_s(int g) const { return g * mSpec.stepDelay_s; }

  private:
    PointSourceSpec mSpec;
    GustCurve mCurve;
    std::shared_ptr<const render::VertexWind> mVertex;  // directions and rings, fixed
};

}  // namespace gale::coupling
