#include "coupling/SteadyGustWind.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>

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
        throw std::invalid_argument("wind.arrival_bands must be in 1..1024, got " +
                                    std::to_string(spec.arrivalBands));
    if (spec.levels < 1 || spec.levels > 256)
        throw std::invalid_argument("wind.levels must be in 1..256, got " + std::to_string(spec.levels));
    if (!std::isfinite(spec.convection_mps) || spec.convection_mps <= 0.0)
        throw std::invalid_argument("gust convection speed must be finite and > 0, got " +
                                    std::to_string(spec.convection_mps));
    const size_t count = mesh.wsPosition_m.size();
    if (wsVelocity_mps.size() != count || mesh.wsNormal.size() != count || count == 0)
        throw std::invalid_argument("steady gust wind: " + std::to_string(wsVelocity_mps.size()) +
                                    " velocities for " + std::to_string(count) + " vertices");
    glm::vec2 along(spec.wsDirection.x, spec.wsDirection.y);
    along = glm::length(along) > 0.0f ? glm::normalize(along) : glm::vec2(1.0f, 0.0f);

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
        base[v] = static_cast<float>(std::clamp(glm::dot(wind, vertex.wsDirection[v]) / response.bendSpeed_mps,
                                                -response.maxIntensity, response.maxIntensity));
        const float s = glm::dot(glm::vec2(mesh.wsPosition_m[v]), along);
        mArrival_s[v] = s;
        minAlong = std::min(minAlong, s), maxAlong = std::max(maxAlong, s);
        minBase = std::min(minBase, base[v]), maxBase = std::max(maxBase, base[v]);
    }
    const double spanAlong = std::max(double(maxAlong) - minAlong, 1e-9);
    const double spanBase = std::max(double(maxBase) - minBase, 1e-9);
    const int groups = spec.arrivalBands * spec.levels;
    vertex.group.resize(count);
    std::vector<double> sumBase(groups, 0.0), sumArrival(groups, 0.0);
    std::vector<uint32_t> members(groups, 0);
    for (size_t v = 0; v < count; ++v) {
        mArrival_s[v] = static_cast<float>((mArrival_s[v] - minAlong) / spec.convection_mps);
        const int band = std::min(spec.arrivalBands - 1,
                                  static_cast<int>((mArrival_s[v] * spec.convection_mps) / spanAlong * spec.arrivalBands));
        const int level = std::min(spec.levels - 1, static_cast<int>((base[v] - minBase) / spanBase * spec.levels));
        const int g = band * spec.levels + level;
        vertex.group[v] = static_cast<uint32_t>(g);
        sumBase[g] += base[v];
        sumArrival[g] += mArrival_s[v];
        ++members[g];
    }
    mGroupBase.assign(groups, 0.0);
    mGroupArrival_s.assign(groups, 0.0);
    for (int g = 0; g < groups; ++g) {
        if (members[g] == 0) continue;
        mGroupBase[g] = sumBase[g] / members[g];
        mGroupArrival_s[g] = sumArrival[g] / members[g];
    }
    mVertex = std::make_shared<const render::VertexWind>(std::move(vertex));
}

void SteadyGustWind::update(double t_s, render::GrassWind& wind) {
    if (wind.vertex != mVertex) {
        wind.vertex = mVertex;
        ++wind.revision;
    }
    const int groups = groupCount();
    // DESIGN 4.2's kinematic gust: the steady intensity scaled by the curve, delayed by arrival.
    auto drive = [this](int g, double t) { return mGroupBase[g] * mCurve(t - mGroupArrival_s[g]); };
    wind.groupIntensity.resize(groups);
    if (mSpec.response.response == BladeResponse::Oscillator) {
        if (!mOscillators) mOscillators.emplace(mSpec.response.frequency_hz, mSpec.response.dampingRatio);
        mOscillators->advance(t_s, groups, drive);
        for (int g = 0; g < groups; ++g) wind.groupIntensity[g] = static_cast<float>(mOscillators->bend()[g]);
    } else {
        for (int g = 0; g < groups; ++g) wind.groupIntensity[g] = static_cast<float>(drive(g, t_s));
    }
}

std::string SteadyGustWind::describe() const {
    std::ostringstream out;
    out << "solved steady field with travelling gusts: " << mSpec.arrivalBands << " arrival bands x "
        << mSpec.levels << " intensity levels = " << groupCount() << " groups, front at "
        << mSpec.convection_mps << " m/s, " << bladeResponseName(mSpec.response.response)
        << " blade response (bend speed " << mSpec.response.bendSpeed_mps << " m/s), gust period "
        << mCurve.period_s() << " s";
    return out.str();
}

}  // namespace gale::coupling
