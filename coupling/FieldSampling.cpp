#include "coupling/FieldSampling.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace gale::coupling {

std::vector<glm::vec3> sampleAtGrass(const sim::WindField& field, const render::TerrainMesh& mesh,
                                     double sampleHeight_m) {
    if (!std::isfinite(sampleHeight_m) || sampleHeight_m < 0.0)
        throw std::invalid_argument("wind.sample_height_m must be finite and >= 0, got " +
                                    std::to_string(sampleHeight_m));
    std::vector<glm::vec3> out(mesh.wsPosition_m.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, out.size(), 4096),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t v = r.begin(); v != r.end(); ++v) {
                              const glm::vec3& p = mesh.wsPosition_m[v];
                              const auto u = field.velocityAt_mps(p.x, p.y, p.z + sampleHeight_m);
                              out[v] = glm::vec3(u[0], u[1], u[2]);
                          }
                      });
    return out;
}

}  // namespace gale::coupling
