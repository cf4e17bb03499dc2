#include "coupling/SteadyGustWind.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "coupling/GroupGrid.h"
#include "coupling/PointSourceWind.h"

namespace gale::coupling {

SteadyGustWind::SteadyGustWind(const render::TerrainMesh& mesh,
                               const std::vector<glm::vec3>& wsVelocity_mps,
                               const SteadyGustSpec& spec, GustCurve curve)
    : mSpec(spec), mCurve(std::move(curve)) {
    FieldWindSpec response = spec.response;
    response.grouping = Grouping::Tiles;  // fixed groups: validate the rest as FieldWind does
    validate(response);
    if (spec.arrivalBands < 1 || spec.arrivalBands > 1024)
        throw ParameterError("wind.arrival_bands", std::to_string(spec.arrivalBands),
                             "must be in 1..1024");
    if (spec.levels < 1 || spec.levels > 256)
        throw ParameterError("wind.levels", std::to_string(spec.levels), "must be in 1..256");
    if (!std::isfinite(spec.convection_mps) || spec.convection_mps <= 0.0)
        throw std::logic_error("gust convection speed must be finite and > 0, got " +
                               std::to_string(spec.convection_mps));
    const size_t count = mesh.wsPosition_m.size();
    if (wsVelocity_mps.size() != count || mesh.wsNormal.size() != count || count == 0)
        throw std::logic_error("steady gust wind: " + std::to_string(wsVelocity_mps.size()) +
                               " velocities for " + std::to_string(count) + " vertices");
    glm::vec2 along(spec.wsDirection.x, spec.wsDirection.y);
    along = glm::length(along) > 0.0f ? glm::normalize(along) : glm::vec2(1.0f, 0.0f);
    mAlong = along;

    // Per vertex: direction, steady intensity, distance downwind -> arrival time.
    render::VertexWind vertex;
    vertex.wsDirection.resize(count);
    mArrival_s.resize(count);
    std::vector<float> base(count);
    float minAlong = 1e30f, maxAlong = -1e30f, minBase = 1e30f, maxBase = -1e30f;
    for (size_t v = 0; v < count; ++v) {
        const glm::vec3& w = wsVelocity_mps[v];
        const bool finite = std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z);
        const glm::vec3 wind = finite ? w : glm::vec3(0.0f);
        vertex.wsDirection[v] = tangentWindDirection(wind, mesh.wsNormal[v]);
        base[v] = static_cast<float>(
            std::clamp(glm::dot(wind, vertex.wsDirection[v]) / response.bendSpeed_mps,
                       -response.maxIntensity, response.maxIntensity));
        const float s = glm::dot(glm::vec2(mesh.wsPosition_m[v]), along);
        mArrival_s[v] = s;
        minAlong = std::min(minAlong, s), maxAlong = std::max(maxAlong, s);
        minBase = std::min(minBase, base[v]), maxBase = std::max(maxBase, base[v]);
    }
    mMinAlong_m = minAlong;
    const double spanAlong = std::max(double(maxAlong) - minAlong, 1e-9);
    const double spanBase = std::max(double(maxBase) - minBase, 1e-9);
    const int groups = spec.arrivalBands * spec.levels;
    vertex.group.resize(count);
    // Groups row by row: a row per arrival band, a column per level (render::VertexWind).
    vertex.groupColumns = spec.levels;
    const bool blend = spec.response.blendGroups;
    if (blend) vertex.groupCoord.resize(count);
    std::vector<double> sumBase(groups, 0.0), sumArrival(groups, 0.0);
    std::vector<uint32_t> members(groups, 0);
    for (size_t v = 0; v < count; ++v) {
        mArrival_s[v] = static_cast<float>((mArrival_s[v] - minAlong) / spec.convection_mps);
        const int band =
            std::min(spec.arrivalBands - 1, static_cast<int>((mArrival_s[v] * spec.convection_mps) /
                                                             spanAlong * spec.arrivalBands));
        const int level = std::min(spec.levels - 1,
                                   static_cast<int>((base[v] - minBase) / spanBase * spec.levels));
        const int g = band * spec.levels + level;
        vertex.group[v] = static_cast<uint32_t>(g);
        if (blend)
            vertex.groupCoord[v] = {
                binCoord(base[v], minBase, spanBase, spec.levels),
                binCoord(mArrival_s[v] * spec.convection_mps, 0.0, spanAlong, spec.arrivalBands)};
        sumBase[g] += base[v];
        sumArrival[g] += mArrival_s[v];
        ++members[g];
    }
    mGroupBase.assign(groups, 0.0);
    mGroupArrival_s.assign(groups, 0.0);
    for (int g = 0; g < groups; ++g) {
        if (members[g] == 0) {
            // No vertex here: the bin's centre, so a blend towards it continues its neighbours.
            mGroupBase[g] = minBase + (g % spec.levels + 0.5) * spanBase / spec.levels;
            mGroupArrival_s[g] =
                (g / spec.levels + 0.5) * spanAlong / spec.arrivalBands / spec.convection_mps;
            continue;
        }
        mGroupBase[g] = sumBase[g] / members[g];
        mGroupArrival_s[g] = sumArrival[g] / members[g];
    }
    mVertex = std::make_shared<const render::VertexWind>(std::move(vertex));
}

void SteadyGustWind::keepField(std::shared_ptr<const sim::WindField> field) {
    mField = std::move(field);
    mGustField.reset();
}

double SteadyGustWind::arrivalAt_s(double x, double y) const {
    return (double(mAlong.x) * x + double(mAlong.y) * y - mMinAlong_m) / mSpec.convection_mps;
}

const sim::WindField* SteadyGustWind::currentField() const {
    if (!mField) return nullptr;
    if (mGustField && mGustField_s == mLastUpdate_s) return &*mGustField;
    if (!mGustField) mGustField.emplace(*mField);
    sim::WindField& out = *mGustField;
    const sim::GridIndex G{out.nx(), out.ny(), out.nz()};
    const double h = out.voxelSize_m();
    const auto lo = out.wsMin_m();
    // One face kind p: its columns of faces, the first at plan offset (ox, oy) cells; the factor
    // depends on the column's plan position alone. Layer k of p is the columnCount(p) faces
    // from index(p, 0, 0, k) on, in column order.
    auto scale = [&](const std::vector<double>& steady, std::vector<double>& gust, sim::Placement p,
                     double ox, double oy) {
        const auto n = G.dims(p);
        std::vector<double> factor(G.columnCount(p));
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i)
                factor[G.column(p, i, j)] =
                    mCurve(mLastUpdate_s - arrivalAt_s(lo[0] + (i + ox) * h, lo[1] + (j + oy) * h));
        for (int k = 0; k < n[2]; ++k) {
            const size_t f0 = G.index(p, 0, 0, k);
            for (size_t c = 0; c < factor.size(); ++c) gust[f0 + c] = steady[f0 + c] * factor[c];
        }
    };
    scale(mField->u_mps(), out.u_mps(), sim::Placement::FaceX, 0.0, 0.5);
    scale(mField->v_mps(), out.v_mps(), sim::Placement::FaceY, 0.5, 0.0);
    scale(mField->w_mps(), out.w_mps(), sim::Placement::FaceZ, 0.5, 0.5);
    mGustField_s = mLastUpdate_s;
    return &out;
}

void SteadyGustWind::setFlutter(std::vector<float> flutter_rad) {
    if (!flutter_rad.empty() && flutter_rad.size() != mVertex->wsDirection.size())
        throw std::logic_error("SteadyGustWind::setFlutter: " + std::to_string(flutter_rad.size()) +
                               " amplitudes for " + std::to_string(mVertex->wsDirection.size()) +
                               " vertices");
    // A new buffer: the old one may be held by a renderer or a viewer's snapshot.
    auto vertex = std::make_shared<render::VertexWind>(*mVertex);
    vertex->flutter_rad = std::move(flutter_rad);
    mVertex = std::move(vertex);
}

void SteadyGustWind::update(double t_s, render::GrassWind& wind) {
    mLastUpdate_s = t_s;
    wind.time_s = t_s;
    if (wind.vertex != mVertex) {
        wind.vertex = mVertex;
        ++wind.revision;
    }
    const int groups = groupCount();
    // docs/design.md 4.2's kinematic gust: the steady intensity scaled by the curve, delayed by
    // arrival.
    auto drive = [this](int g, double t) { return mGroupBase[g] * mCurve(t - mGroupArrival_s[g]); };
    wind.groupIntensity.resize(groups);
    if (mSpec.response.response == BladeResponse::Oscillator) {
        if (!mOscillators)
            mOscillators.emplace(mSpec.response.frequency_hz, mSpec.response.dampingRatio);
        mOscillators->advance(t_s, groups, drive);
        for (int g = 0; g < groups; ++g)
            wind.groupIntensity[g] = static_cast<float>(mOscillators->bend()[g]);
    } else {
        for (int g = 0; g < groups; ++g) wind.groupIntensity[g] = static_cast<float>(drive(g, t_s));
    }
}

std::string SteadyGustWind::describe() const {
    std::ostringstream out;
    out << "solved steady field with travelling gusts: " << mSpec.arrivalBands
        << " arrival bands x " << mSpec.levels << " intensity levels = " << groupCount()
        << " groups, front at " << mSpec.convection_mps << " m/s, "
        << bladeResponseName(mSpec.response.response) << " blade response (bend speed "
        << mSpec.response.bendSpeed_mps << " m/s), gust period " << mCurve.period_s() << " s";
    return out.str();
}

}  // namespace gale::coupling
