#pragma once
/// \file ShellRenderer.h
/// Draws the terrain and N + 1 grass shells (Bakay 2003, chapter 3) with the length-preserving bend
/// and Kajiya-Kay / Banks lighting, into the current GlContext's framebuffer.

#include <memory>

#include "render/GlContext.h"
#include "render/GrassInput.h"
#include "render/GrassTexture.h"

namespace gale::render {

struct FrameStats {
    double cpu_ms = 0.0;  ///< table building and uploads on the CPU
    double gpu_ms = 0.0;  ///< draw calls through glFinish
};

class ShellRenderer {
public:
    /// Compiles the shaders (throws std::runtime_error naming the shader file and its log).
    /// The context must be current and stay alive while the renderer is used.
    explicit ShellRenderer(GlContext& context);
    ~ShellRenderer();
    ShellRenderer(const ShellRenderer&) = delete;
    ShellRenderer& operator=(const ShellRenderer&) = delete;

    void setTerrain(const TerrainMesh& mesh);
    /// Uploads the grass texture with its blade-keeping MIP chain (thesis 3.4).
    void setGrass(const GrassParams& params, const GrassTexture& texture);
    void setLighting(const Lighting& lighting);

    /// Draws one frame: per-group (n_i, w_i) tables are built on the CPU from wind.groupIntensity
    /// (once per group per shell, never per vertex), directions and groups are re-uploaded only
    /// when wind.revision changed.
    FrameStats draw(const Camera& camera, const GrassWind& wind);

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

}  // namespace gale::render
