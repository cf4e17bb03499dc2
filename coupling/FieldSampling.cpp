#include "coupling/FieldSampling.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "sim/Interpolation.h"

namespace gale::coupling {
namespace {

// Points per TBB task: enough to hide the scheduling, few enough to balance two cores.
constexpr size_t GRAIN = 4096;
// Roughly how many faces a vertex's near-ground plan tests (two searches of up to ten candidate
// points, 8-24 faces each): the plan keeps every solved-face flag when that is fewer faces.
constexpr size_t FACE_TESTS_PER_PLANNED_VERTEX = 100;

template <class F>
void forEachPoint(size_t count, F&& f) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, GRAIN),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t v = r.begin(); v != r.end(); ++v) f(v);
                      });
}

// ComponentRead::flags: the stencil lies outside the box (the component reads zero).
constexpr uint32_t OUTSIDE = 8;

// The planned trilinear read: the same eight faces in the same order, and the same
// sim::trilinearBlend, as GridLayout's blendStencils, so the value is bit for bit the one it gives.
inline double blendPlanned(const double* a, const GrassSampler::ComponentRead& r, size_t strideY,
                           size_t strideZ) {
    if (r.flags & OUTSIDE) return 0.0;
    const size_t dx = r.flags & 1u, dy = (r.flags >> 1 & 1u) * strideY,
                 dz = (r.flags >> 2 & 1u) * strideZ;
    const double* p00 = a + r.base;
    const double* p10 = p00 + dy;
    const double* p01 = p00 + dz;
    const double* p11 = p10 + dz;
    const double c[8] = {p00[0], p00[dx], p10[0], p10[dx], p01[0], p01[dx], p11[0], p11[dx]};
    return sim::trilinearBlend(c, r.t[0], r.t[1], r.t[2]);
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

void GrassSampler::plan(const sim::WindField& field) {
    const sim::GridLayout& g = field.layout();
    // A field this large (32 GB per face array) is refused by the memory estimate long before.
    for (int c = 0; c < 3; ++c)
        if (g.count(sim::Placement(c)) > size_t(UINT32_MAX))
            throw std::length_error("GrassSampler: face array too large for a read plan");
    mRead.resize(mVertex.size());
    // The solved faces tested once for every vertex's search (the plan's main cost otherwise),
    // unless testing them all costs more than the vertices' own tests would; the reads are the
    // same either way.
    std::optional<SolvedFaces> solved;
    if (mNearGround.model != NearGroundModel::Interpolated &&
        SolvedFaces::keptFaceCount(field) < mVertex.size() * FACE_TESTS_PER_PLANNED_VERTEX)
        solved.emplace(field);
    forEachPoint(mVertex.size(), [&](size_t v) {
        const glm::vec3& p = mVertex[v];
        const glm::dvec3 grass(p.x, p.y, double(p.z) + mHeight_m);
        const NearGroundRead r = solved ? planNearGroundRead(*solved, grass, mNearGround)
                                        : planNearGroundRead(field, grass, mNearGround);
        VertexRead& out = mRead[v];
        out.map = r.map;
        for (int c = 0; c < 3; ++c) {
            // As WindField::velocityComponentsAt_mps reads: u and v at wsUV_m, w at wsW_m, by
            // GridLayout::sample's stencils, zero outside the box.
            const glm::vec3& q = c < 2 ? r.wsUV_m : r.wsW_m;
            const sim::Vec3d is = g.isFromWs({q.x, q.y, q.z});
            ComponentRead& cr = out.component[c];
            if (g.nx == 0 || !g.containsIs(is)) {
                cr = {{0.0, 0.0, 0.0}, 0, OUTSIDE};
                continue;
            }
            const sim::AxisStencil x = g.stencil(0, c == 0, is[0]);
            const sim::AxisStencil y = g.stencil(1, c == 1, is[1]);
            const sim::AxisStencil z = g.stencil(2, c == 2, is[2]);
            const auto d = g.dims(sim::Placement(c));
            const size_t base =
                size_t(x.i0) + size_t(d[0]) * (size_t(y.i0) + size_t(d[1]) * size_t(z.i0));
            cr = {{x.t, y.t, z.t},
                  uint32_t(base),
                  uint32_t(x.i1 - x.i0) | uint32_t(y.i1 - y.i0) << 1 | uint32_t(z.i1 - z.i0) << 2};
        }
    });
}

void GrassSampler::sample(const sim::WindField& field, std::vector<glm::vec3>& out) {
    const sim::WindField::Geometry geometry = field.geometry();
    if (mRead.size() != mVertex.size() || mPlanGeometry != geometry) {
        mRead.clear();  // a failed plan leaves none
        plan(field);
        mPlanGeometry = geometry;
    }
    const sim::GridLayout& g = field.layout();
    const double* faces[3] = {field.u_mps().data(), field.v_mps().data(), field.w_mps().data()};
    size_t strideY[3], strideZ[3];
    for (int c = 0; c < 3; ++c) {
        const auto d = g.dims(sim::Placement(c));
        strideY[c] = size_t(d[0]);
        strideZ[c] = size_t(d[0]) * size_t(d[1]);
    }
    out.resize(mVertex.size());
    forEachPoint(mVertex.size(), [&](size_t v) {
        const VertexRead& r = mRead[v];
        float u[3];
        for (int c = 0; c < 3; ++c)
            u[c] = float(blendPlanned(faces[c], r.component[c], strideY[c], strideZ[c]));
        out[v] = applyNearGroundMap(r.map, glm::vec3(u[0], u[1], u[2]));
    });
}

std::vector<glm::vec3> sampleAtGrass(const sim::WindField& field, const render::TerrainMesh& mesh,
                                     double sampleHeight_m, const NearGround& nearGround) {
    return GrassSampler(mesh, sampleHeight_m, nearGround).sample(field);
}

}  // namespace gale::coupling
