#pragma once
/// \file FieldSampling.h
/// Reads a solved sim::WindField where the grass lives (docs/design.md 5, step 1).

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "coupling/NearGround.h"
#include "render/GrassInput.h"
#include "sim/WindField.h"

namespace gale::coupling {

/// Samples fields at sampleHeight_m straight above every vertex of a fixed mesh (vertical, not
/// along the normal: the field's log profile is measured from the ground vertically), by the
/// field's staggered trilinear interpolation, extended below the lowest solved faces by the
/// near-wall behaviour of the model that made the field (NearGround; coupling/NearGround.h).
/// Vertices outside the field's box, or whose sample point is below its terrain, get zero, so the
/// grass there stands still rather than reading garbage.
///
/// Made for a run that samples one field geometry step after step: how a point is read depends
/// only on the geometry (cells, air, terrain), so that plan is made once per geometry and kept
/// (60 bytes per vertex); a field step is then one interpolation and one 3 x 3 product per vertex.
/// Multithreaded; O(vertices). One sampler serves one caller at a time.
class GrassSampler {
  public:
    /// Copies the vertex positions. Throws std::invalid_argument unless sampleHeight_m is finite
    /// and
    /// >= 0 (wind.sample_height_m), or when nearGround's parameters are out of range (validate).
    GrassSampler(const render::TerrainMesh& mesh, double sampleHeight_m,
                 const NearGround& nearGround = {});

    /// World velocity, m/s, at every sample point into `out` (resized to the vertex count; its
    /// storage is reused).
    void sample(const sim::WindField& field, std::vector<glm::vec3>& out);
    std::vector<glm::vec3> sample(const sim::WindField& field) {
        std::vector<glm::vec3> out;
        sample(field, out);
        return out;
    }

    size_t vertexCount() const { return mVertex.size(); }
    const NearGround& nearGround() const { return mNearGround; }

  private:
    std::vector<glm::vec3> mVertex;  // world metres
    double mHeight_m;
    NearGround mNearGround;
    sim::WindField::Geometry mPlanGeometry;
    std::vector<NearGroundRead> mRead;  // per vertex, for mPlanGeometry; empty: not made yet
};

/// One-off sampling: GrassSampler(mesh, sampleHeight_m, nearGround).sample(field).
std::vector<glm::vec3> sampleAtGrass(const sim::WindField& field, const render::TerrainMesh& mesh,
                                     double sampleHeight_m, const NearGround& nearGround = {});

}  // namespace gale::coupling
