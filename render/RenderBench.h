#pragma once
/// \file RenderBench.h
/// Fill-rate measurement of the shell renderer in the layout of the paper's Table 2 (thesis Table
/// 4.1): a flat, fully grass-covered view, full lighting, N shells, against a trivial textured
/// alpha-tested fill of the same geometry in the same run. The table and CLI live in app/.

#include <string>
#include <vector>

#include "render/GrassInput.h"

namespace gale::render {

struct ShellFillCase {
    int width = 640;  ///< framebuffer, pixels
    int height = 480;
    int layers = 17;        ///< layers drawn including the ground (the paper's "shells"), 1..257
    int frames = 20;        ///< timed frames per pass
    int warmupFrames = 2;   ///< untimed frames before each pass
    int lights = 3;         ///< point lights (the thesis used 3), 0..MAX_LIGHTS
    int gridVertices = 17;  ///< base mesh is gridVertices^2 vertices: 17 -> 512 triangles
    std::string framePath;  ///< if set, the last full frame is written here (atomic)
};

struct ShellFillResult {
    int layers = 0;
    int width = 0;
    int height = 0;
    long triangles = 0;           ///< per frame: base triangles x layers
    double fps = 0.0;             ///< full renderer: bend, Kajiya-Kay / Banks lighting, alpha test
    double baselineFps = 0.0;     ///< texture fetch + alpha test only, same geometry and layers
    double nearestFps = 0.0;      ///< the same fill with nearest-texel sampling: the fill's floor
    double fullNearestFps = 0.0;  ///< full renderer with DrawOptions::nearestTexels
    double cpu_ms = 0.0;    ///< mean per-frame CPU part of the full renderer (tables, uploads)
    double coverage = 0.0;  ///< fraction of pixels covered by terrain/grass in the last frame
    std::string renderer;   ///< GL_RENDERER, GL_VERSION
};

/// Flat square grid on z = 0 centred at the origin: verticesPerSide^2 vertices spanning size_m,
/// up normals, uv = xy / tile_m. Requires verticesPerSide >= 2, size_m > 0, tile_m > 0
/// (std::invalid_argument otherwise).
TerrainMesh makeFlatGridMesh(int verticesPerSide, float size_m, float tile_m);

/// Renders `c.frames` timed frames of each pass in a fresh headless context (timed with
/// std::chrono around glFinish, after c.warmupFrames untimed frames) and reports frames per
/// second. Throws std::invalid_argument on a bad case, std::runtime_error on GL failures.
ShellFillResult measureShellFill(const ShellFillCase& c);

/// The fill profile: where a shell fragment's time goes on this GL. The benchmark's flat field and
/// grass texture drawn as `layers` full-screen layers, once per variant, each changing one thing
/// from the trivial fill (filter, fetches, arithmetic, alpha test, depth test, order), plus the
/// full renderer.
struct FillProfileCase {
    int width = 640;   ///< framebuffer, pixels, 1..16384
    int height = 480;  ///< pixels, 1..16384
    int layers = 17;   ///< layers including the ground, 1..MAX_SHELLS + 1
    int frames = 8;    ///< timed rounds; every round draws every variant once, >= 1
};

struct FillProfileRow {
    std::string name;       ///< what the variant changes
    double cpu_ms = 0.0;    ///< median process CPU time per frame (all threads: llvmpipe's too), ms
    double wall_ms = 0.0;   ///< median wall time per frame (draw to glFinish), ms
    bool baseline = false;  ///< the trivial fill: trilinear fetch and alpha test
};

/// Runs the profile in a fresh headless context: one untimed round, then c.frames rounds that
/// draw every variant once each (so load from other processes hits all alike), each frame cleared
/// and finished. Rows come in a fixed order, exactly one with `baseline` set. Throws
/// std::invalid_argument on a bad case, std::runtime_error on GL failures.
std::vector<FillProfileRow> profileShellFill(const FillProfileCase& c);

}  // namespace gale::render
