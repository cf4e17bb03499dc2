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

GrassSampler::GrassSampler(std::vector<glm::dvec3> wsPoints_m, const NearGround& nearGround) {
    for (const glm::dvec3& p : wsPoints_m)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw std::invalid_argument("GrassSampler: a sample point is not finite");
    validate(nearGround);
    mPoint = std::move(wsPoints_m);
    mHeight_m = 0.0;
    mNearGround = nearGround;
}

size_t GrassSampler::vertexCount() const { return mPoint.empty() ? mVertex.size() : mPoint.size(); }

glm::dvec3 GrassSampler::samplePoint_m(size_t v) const {
    if (!mPoint.empty()) return mPoint[v];
    const glm::vec3& p = mVertex[v];
    return {p.x, p.y, double(p.z) + mHeight_m};
}

NearGroundReadKind GrassSampler::readKind(size_t v) const {
    const VertexRead& r = mRead.at(v);
    bool identity = true, zero = true;
    for (int i = 0; i < 9; ++i) {
        identity = identity && r.map[size_t(i)] == (i % 4 == 0 ? 1.0f : 0.0f);
        zero = zero && r.map[size_t(i)] == 0.0f;
    }
    bool outside = true;
    for (const ComponentRead& c : r.component) outside = outside && (c.flags & OUTSIDE) != 0;
    if (outside) return NearGroundReadKind::OutsideBox;
    if (zero) return NearGroundReadKind::Zero;
    if (identity) return NearGroundReadKind::Field;
    return mNearGround.model == NearGroundModel::LogLaw ? NearGroundReadKind::LogLaw
                                                        : NearGroundReadKind::Tangential;
}

const char* nearGroundReadKindName(NearGroundReadKind kind) {
    switch (kind) {
        case NearGroundReadKind::Field:
            return "field";
        case NearGroundReadKind::Tangential:
            return "tangential";
        case NearGroundReadKind::LogLaw:
            return "log_law";
        case NearGroundReadKind::Zero:
            return "zero";
        default:
            return "outside";
    }
}

void GrassSampler::plan(const sim::WindField& field) {
    const sim::GridLayout& g = field.layout();
    // A field this large (32 GB per face array) is refused by the memory estimate long before.
    for (int c = 0; c < 3; ++c)
        if (g.count(sim::Placement(c)) > size_t(UINT32_MAX))
            throw std::length_error("GrassSampler: face array too large for a read plan");
    const size_t n = vertexCount();
    mRead.resize(n);
    // The solved faces tested once for every vertex's search (the plan's main cost otherwise),
    // unless testing them all costs more than the vertices' own tests would; the reads are the
    // same either way.
    std::optional<SolvedFaces> solved;
    if (mNearGround.model != NearGroundModel::Interpolated &&
        SolvedFaces::keptFaceCount(field) < n * FACE_TESTS_PER_PLANNED_VERTEX)
        solved.emplace(field);
    forEachPoint(n, [&](size_t v) {
        const glm::dvec3 grass = samplePoint_m(v);
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
    const size_t n = vertexCount();
    if (mRead.size() != n || mPlanGeometry != geometry) {
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
    out.resize(n);
    forEachPoint(n, [&](size_t v) {
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
