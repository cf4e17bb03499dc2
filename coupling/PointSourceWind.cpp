#include "coupling/PointSourceWind.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <sstream>
#include <stdexcept>

#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "coupling/GroupGrid.h"

namespace gale::coupling {
namespace {

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

PointSourceWind::PointSourceWind(const render::TerrainMesh& mesh, const PointSourceSpec& spec,
                                 GustCurve curve)
    : mSpec(spec), mCurve(std::move(curve)) {
    if (spec.steps < 1 || spec.steps > 1024)
        throw ParameterError("wind.steps", std::to_string(spec.steps), "must be in 1..1024");
    if (!std::isfinite(spec.stepDelay_s) || spec.stepDelay_s < 0.0)
        throw ParameterError("wind.step_delay_s", formatG(spec.stepDelay_s),
                             "must be finite and >= 0");
    if (!finite(spec.wsSource_m))
        throw ParameterError("wind.source_m",
                             "[" + formatG(spec.wsSource_m.x) + ", " + formatG(spec.wsSource_m.y) +
                                 ", " + formatG(spec.wsSource_m.z) + "]",
                             "must be finite");
    const size_t count = mesh.wsPosition_m.size();
    if (mesh.wsNormal.size() != count)
        throw std::logic_error("terrain mesh has " + std::to_string(count) + " positions but " +
                               std::to_string(mesh.wsNormal.size()) + " normals");
    render::VertexWind vertex;
    vertex.wsDirection.resize(count);
    vertex.group.resize(count);
    std::vector<float> distance_m(count);
    float maxDistance_m = 0.0f;
    for (size_t v = 0; v < count; ++v) {
        // W points from the vertex to the source (paper); a gust blowing from the source pushes
        // the grass the other way.
        const glm::vec3 toSource = spec.wsSource_m - mesh.wsPosition_m[v];
        vertex.wsDirection[v] =
            tangentWindDirection(spec.blowAway ? -toSource : toSource, mesh.wsNormal[v]);
        distance_m[v] = glm::length(toSource);
        maxDistance_m = std::max(maxDistance_m, distance_m[v]);
    }
    // Animation step = distance from the source in `steps` equal rings (paper section 3).
    const float ringWidth_m = maxDistance_m > 0.0f ? maxDistance_m / spec.steps : 1.0f;
    vertex.groupColumns = spec.steps;
    if (spec.blendGroups) vertex.groupCoord.resize(count);
    for (size_t v = 0; v < count; ++v) {
        vertex.group[v] = static_cast<uint32_t>(
            std::min(spec.steps - 1, static_cast<int>(distance_m[v] / ringWidth_m)));
        if (spec.blendGroups)
            vertex.groupCoord[v] = {
                binCoord(distance_m[v], 0.0, ringWidth_m * spec.steps, spec.steps), 0.0f};
    }
    mVertex = std::make_shared<const render::VertexWind>(std::move(vertex));
}

void PointSourceWind::update(double t_s, render::GrassWind& wind) {
    wind.time_s = t_s;
    if (wind.vertex != mVertex) {
        wind.vertex = mVertex;
        ++wind.revision;
    }
    wind.groupIntensity.resize(static_cast<size_t>(mSpec.steps));
    for (int g = 0; g < mSpec.steps; ++g)
        wind.groupIntensity[g] = static_cast<float>(mCurve(t_s - groupDelay_s(g)));
}

std::string PointSourceWind::describe() const {
    std::ostringstream out;
    out << "point-source wind (Bakay et al. 2002) from (" << mSpec.wsSource_m.x << ", "
        << mSpec.wsSource_m.y << ", " << mSpec.wsSource_m.z << ") m, " << mSpec.steps
        << " animation steps, " << mSpec.stepDelay_s << " s apart, gust period "
        << mCurve.period_s() << " s";
    return out.str();
}

}  // namespace gale::coupling
