/// \file OsMesaContext.cpp
/// The headless GlContext: an OSMesa 4.5 core context rendering into a client-memory RGBA8 buffer
/// (docs/design.md 7: pass OSMESA_DEPTH_BITS, rows come bottom-up, the buffer is filled on
/// glFinish).

#include <GL/osmesa.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/GlContext.h"

namespace gale::render {
namespace {

class OsMesaContext final : public GlContext {
  public:
    OsMesaContext(int width, int height) : mWidth(width), mHeight(height) {
        if (width < 1 || height < 1 || width > 16384 || height > 16384) {
            throw std::runtime_error("createOsMesaContext: size must be 1..16384 per side, got " +
                                     std::to_string(width) + "x" + std::to_string(height));
        }
        const int attribs[] = {OSMESA_FORMAT,
                               OSMESA_RGBA,
                               OSMESA_DEPTH_BITS,
                               24,
                               OSMESA_STENCIL_BITS,
                               0,
                               OSMESA_ACCUM_BITS,
                               0,
                               OSMESA_PROFILE,
                               OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION,
                               4,
                               OSMESA_CONTEXT_MINOR_VERSION,
                               5,
                               0};
        mContext = OSMesaCreateContextAttribs(attribs, nullptr);
        if (mContext == nullptr) {
            throw std::runtime_error(
                "createOsMesaContext: OSMesaCreateContextAttribs returned null for an RGBA8, "
                "24-bit depth, OpenGL 4.5 core profile context (Mesa too old, or built without "
                "llvmpipe?)");
        }
        mBuffer.assign(static_cast<size_t>(width) * static_cast<size_t>(height) * 4u, 0);
        makeCurrent();
    }

    ~OsMesaContext() override {
        if (mContext != nullptr) OSMesaDestroyContext(mContext);
    }

    void makeCurrent() override {
        if (!OSMesaMakeCurrent(mContext, mBuffer.data(), GL_UNSIGNED_BYTE, mWidth, mHeight)) {
            throw std::runtime_error("OsMesaContext: OSMesaMakeCurrent failed for a " +
                                     std::to_string(mWidth) + "x" + std::to_string(mHeight) +
                                     " buffer");
        }
    }

    int width() const override { return mWidth; }
    int height() const override { return mHeight; }

    void readPixels(Image& out) override {
        makeCurrent();
        glFinish();
        out.width = mWidth;
        out.height = mHeight;
        out.rgba.resize(mBuffer.size());
        // OSMesa keeps rows bottom-up (OSMESA_Y_UP = 1 by default); Image rows are top-down.
        const size_t rowBytes = static_cast<size_t>(mWidth) * 4u;
        for (int y = 0; y < mHeight; ++y) {
            std::memcpy(out.rgba.data() + static_cast<size_t>(y) * rowBytes,
                        mBuffer.data() + static_cast<size_t>(mHeight - 1 - y) * rowBytes, rowBytes);
        }
    }

    std::string description() const override {
        const GLubyte* renderer = glGetString(GL_RENDERER);
        const GLubyte* version = glGetString(GL_VERSION);
        return std::string(renderer ? reinterpret_cast<const char*>(renderer) : "?") + ", OpenGL " +
               (version ? reinterpret_cast<const char*>(version) : "?");
    }

  private:
    int mWidth;
    int mHeight;
    OSMesaContext mContext = nullptr;
    std::vector<uint8_t> mBuffer;  ///< RGBA8, rows bottom-up, filled on glFinish
};

}  // namespace

std::unique_ptr<GlContext> createOsMesaContext(int width, int height) {
    return std::make_unique<OsMesaContext>(width, height);
}

}  // namespace gale::render
