#pragma once
/// \file RenderMemory.h
/// The peak resident memory of `gale render`, estimated from the built scene (docs/reliability.md
/// has the table against measured peaks, `gale bench memory`).

#include "app/scene/Scene.h"
#include "app/scene/SceneBuilder.h"

namespace gale::app {

/// Resident bytes an OSMesa (llvmpipe) context adds once it has compiled the shell shaders and
/// drawn a frame, beyond its per-pixel buffers: measured on Mesa 22.3 (Debian 12) as the peak of a
/// 64 x 48 render minus that of `gale check` on the same scene.
inline constexpr double GL_CONTEXT_BYTES = 64.0 * 1024 * 1024;

/// Estimated peak resident bytes of `gale render` on this scene: the process as loadScene found
/// it (DomainSpec::run.processBaseline_bytes), the heightfield and render mesh, the grass
/// texture's MIP chain (on the CPU and in GL), and the larger of a steady wind's solve (the
/// domain's estimate beyond that baseline) and the GL phase (the frame's buffers and the
/// context); an unsteady wind's arrays live beside the GL phase, so they add. Never throws.
double estimateRenderMemory_bytes(const Scene& scene, const BuiltScene& built);

}  // namespace gale::app
