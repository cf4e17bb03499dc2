#include "coupling/FieldSampling.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "base/Numbers.h"
#include "base/ParameterError.h"

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

GrassSampler::GrassSampler(const render::TerrainMesh& mesh, double sampleHeight_m,
                           const NearGround& nearGround) {
    if (!std::isfinite(sampleHeight_m) || sampleHeight_m < 0.0)
        throw ParameterError("wind.sample_height_m", formatG(sampleHeight_m),
                             "must be finite and >= 0");
    validate(nearGround);
    mVertex = mesh.wsPosition_m;
    mHeight_m = sampleHeight_m;
    mNearGround = nearGround;
}

void GrassSampler::sample(const sim::WindField& field, std::vector<glm::vec3>& out) {
    const sim::WindField::Geometry geometry = field.geometry();
    // A new geometry: the read plans are made in the same pass as the samples.
    const bool plan = mRead.size() != mVertex.size() || mPlanGeometry != geometry;
    if (plan) mRead.resize(mVertex.size());
    out.resize(mVertex.size());
    forEachPoint(mVertex.size(), [&](size_t v) {
        if (plan) {
            const glm::vec3& p = mVertex[v];
            mRead[v] = planNearGroundRead(field, glm::dvec3(p.x, p.y, double(p.z) + mHeight_m),
                                          mNearGround);
        }
        const NearGroundRead& r = mRead[v];
        const auto u = field.velocityComponentsAt_mps({r.wsUV_m.x, r.wsUV_m.y, r.wsUV_m.z},
                                                      {r.wsW_m.x, r.wsW_m.y, r.wsW_m.z});
        out[v] = applyNearGroundMap(r.map, glm::vec3(u[0], u[1], u[2]));
    });
    mPlanGeometry = geometry;
}

std::vector<glm::vec3> sampleAtGrass(const sim::WindField& field, const render::TerrainMesh& mesh,
                                     double sampleHeight_m, const NearGround& nearGround) {
    return GrassSampler(mesh, sampleHeight_m, nearGround).sample(field);
}

}  // namespace gale::coupling
