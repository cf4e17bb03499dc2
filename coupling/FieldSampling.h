#pragma once
/// \file FieldSampling.h
/// Reads a solved sim::WindField where the grass lives (docs/design.md 5, step 1).

#include <array>
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
/// only on the geometry (cells, air, terrain), so that plan is made once per geometry and kept:
/// per vertex and component the first face the trilinear stencil reads, its steps to the other
/// seven and the three weights, and the near-ground 3 x 3 map (136 bytes per vertex). A field
/// step is then 24 face reads, the blends and one 3 x 3 product per vertex, with no coordinate
/// conversion; it gives bit for bit what WindField::velocityComponentsAt_mps gives at the
/// plan's points. Multithreaded; O(vertices). One sampler serves one caller at a time.
/// How a sample point was read (GrassSampler::readKind; gale probe's `read` column).
enum class NearGroundReadKind {
    Field,       ///< the field's own interpolation: every face its stencils read is solved
    Tangential,  ///< below the solved faces: the free-slip tangential law (mass-consistent)
    LogLaw,      ///< below the solved faces: the log law of the wall stress (momentum model)
    Zero,        ///< below the terrain, or at or below z0 + d of the log law: zero wind
    OutsideBox,  ///< outside the field's box: zero wind
};
/// "field", "tangential", "log_law", "zero", "outside".
const char* nearGroundReadKindName(NearGroundReadKind kind);

class GrassSampler {
  public:
    /// Copies the vertex positions. Throws gale::ParameterError unless sampleHeight_m is finite
    /// and >= 0 (wind.sample_height_m), or when nearGround's parameters are out of range
    /// (validate).
    GrassSampler(const render::TerrainMesh& mesh, double sampleHeight_m,
                 const NearGround& nearGround = {});

    /// Samples at arbitrary world points (metres; gale probe): each point is planned and read as
    /// a mesh vertex's grass point is, so a probe at a vertex's grass point reads exactly what the
    /// grass there reads. Throws std::invalid_argument for a non-finite point, gale::ParameterError
    /// as the mesh constructor for bad nearGround parameters.
    GrassSampler(std::vector<glm::dvec3> wsPoints_m, const NearGround& nearGround);

    /// World velocity, m/s, at every sample point into `out` (resized to the vertex count; its
    /// storage is reused). The first call for a field geometry makes the read plan (the cost of
    /// planNearGroundRead per vertex). Throws std::length_error for a field whose face arrays
    /// exceed 2^32 values (far beyond any memory limit).
    void sample(const sim::WindField& field, std::vector<glm::vec3>& out);
    std::vector<glm::vec3> sample(const sim::WindField& field) {
        std::vector<glm::vec3> out;
        sample(field, out);
        return out;
    }

    size_t vertexCount() const;  ///< the mesh's vertices, or the points given
    /// The world point (metres) that sample v reads: the vertex raised by the sample height, or
    /// the point given.
    glm::dvec3 samplePoint_m(size_t v) const;
    /// How sample v was read in the last sample() call's plan (std::out_of_range before one).
    NearGroundReadKind readKind(size_t v) const;
    const NearGround& nearGround() const { return mNearGround; }

    /// One component's trilinear read: the face array index of its stencil's first face (lowest
    /// x, y, z), whether the stencil steps to a second face along x, y, z (bits 0-2; not at a
    /// clamped lattice of one sample) or lies outside the box (bit 3: reads zero), and the
    /// weights of the upper faces along x, y, z (as GridLayout's AxisStencil::t).
    struct ComponentRead {
        double t[3];
        uint32_t base;
        uint32_t flags;
    };
    /// A vertex's read: u, v, w, then u(P) = map (u, v, w) (NearGroundRead's map).
    struct VertexRead {
        ComponentRead component[3];
        std::array<float, 9> map;
    };

  private:
    std::vector<glm::vec3> mVertex;  // world metres (the mesh constructor)
    std::vector<glm::dvec3> mPoint;  // world metres (the point constructor)
    double mHeight_m;
    NearGround mNearGround;
    void plan(const sim::WindField& field);  // fills mRead for field's geometry

    sim::WindField::Geometry mPlanGeometry;
    std::vector<VertexRead> mRead;  // per vertex, for mPlanGeometry; empty: not made yet
};

/// One-off sampling: GrassSampler(mesh, sampleHeight_m, nearGround).sample(field).
std::vector<glm::vec3> sampleAtGrass(const sim::WindField& field, const render::TerrainMesh& mesh,
                                     double sampleHeight_m, const NearGround& nearGround = {});

}  // namespace gale::coupling
