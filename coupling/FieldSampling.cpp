#include "coupling/FieldSampling.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace gale::coupling {
namespace {

// Points per TBB task: enough to hide the scheduling, few enough to balance two cores.
constexpr size_t GRAIN = 4096;

template <class F>
void forEachPoint(size_t count, F&& f) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, GRAIN),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t v = r.begin(); v != r.end(); ++v) f(v);
                      });
}

}  // namespace

GrassSampler::GrassSampler(const render::TerrainMesh& mesh, double sampleHeight_m) {
    if (!std::isfinite(sampleHeight_m) || sampleHeight_m < 0.0)
        throw std::invalid_argument("wind.sample_height_m must be finite and >= 0, got " +
                                    std::to_string(sampleHeight_m));
    mVertex = mesh.wsPosition_m;
    mHeight_m = sampleHeight_m;
}

void GrassSampler::sample(const sim::WindField& field, std::vector<glm::vec3>& out) {
    const sim::WindField::Geometry geometry = field.geometry();
    // A new geometry: the terrain test is made in the same pass as the samples.
    const bool testTerrain = mBelowTerrain.size() != mVertex.size() || mMaskGeometry != geometry;
    if (testTerrain) mBelowTerrain.resize(mVertex.size());
    out.resize(mVertex.size());
    forEachPoint(mVertex.size(), [&](size_t v) {
        const glm::vec3& p = mVertex[v];
        const double z = p.z + mHeight_m;
        if (testTerrain) mBelowTerrain[v] = field.belowTerrain(p.x, p.y, z) ? 1 : 0;
        if (mBelowTerrain[v]) {
            out[v] = glm::vec3(0.0f);
            return;
        }
        const auto u = field.velocityAboveTerrainAt_mps(p.x, p.y, z);
        out[v] = glm::vec3(u[0], u[1], u[2]);
    });
    mMaskGeometry = geometry;
}

std::vector<glm::vec3> sampleAtGrass(const sim::WindField& field, const render::TerrainMesh& mesh,
                                     double sampleHeight_m) {
    return GrassSampler(mesh, sampleHeight_m).sample(field);
}

}  // namespace gale::coupling
