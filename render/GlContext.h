#pragma once
/// \file GlContext.h
/// A current OpenGL 4.5 core context with a framebuffer of a fixed size, behind a small interface
/// (after Filament's platform classes) so headless OSMesa, a GLFW window and later EGL can serve
/// the same renderer.

#include <memory>
#include <string>

#include "render/GrassInput.h"

namespace gale::render {

class GlContext {
  public:
    virtual ~GlContext() = default;
    /// Makes this context current on the calling thread.
    virtual void makeCurrent() = 0;
    virtual int width() const = 0;
    virtual int height() const = 0;
    /// Finishes GL work and reads the default framebuffer into `out` (rows top-down).
    virtual void readPixels(Image& out) = 0;
    /// Presents the frame (a window swaps buffers; headless does nothing).
    virtual void present() {}
    /// GL_RENDERER and GL_VERSION, for reports.
    virtual std::string description() const = 0;
};

/// Headless OSMesa context, 4.5 core, RGBA8 with a 24-bit depth buffer, width x height pixels.
/// Throws std::runtime_error if OSMesa cannot make such a context.
std::unique_ptr<GlContext> createOsMesaContext(int width, int height);

}  // namespace gale::render
