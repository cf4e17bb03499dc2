/// \file RenderMemory.cpp
/// The render's memory estimate (RenderMemory.h).

#include "app/scene/RenderMemory.h"

#include <algorithm>

#include "app/scene/SceneParser.h"

namespace gale::app {

double estimateRenderMemory_bytes(const Scene& scene, const BuiltScene& built) {
    const double baseline = scene.solver.domain.run.processBaseline_bytes;
    const double wind = std::max(0.0, built.domainEstimate_bytes - baseline);
    const double terrain = estimateTerrainBytes(built.heightfield.nx, built.heightfield.ny,
                                                std::max(1, scene.terrain.meshStride));
    double texture = 0.0;  // RGBA8 levels, once on the CPU and once in GL
    for (const render::Image& level : built.texture.levels)
        texture += 2 * 4.0 * double(level.width) * double(level.height);
    const double frame = FRAME_BYTES_PER_PIXEL * double(scene.output.width) * scene.output.height;
    // A steady solve is over (its solver, system and scratch freed) before the GL context exists;
    // an unsteady wind steps beside the renderer all along.
    const double gl = frame + GL_CONTEXT_BYTES;
    const double phases = scene.wind.kind == WindKind::Unsteady ? wind + gl : std::max(wind, gl);
    return baseline + terrain + texture + phases;
}

}  // namespace gale::app
