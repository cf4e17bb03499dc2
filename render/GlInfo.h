#pragma once
/// \file GlInfo.h
/// What the current GL context is, for reports and for the context tests.

#include <string>

namespace gale::render {

struct GlInfo {
    int majorVersion = 0;
    int minorVersion = 0;
    bool coreProfile = false;  ///< GL_CONTEXT_CORE_PROFILE_BIT set in GL_CONTEXT_PROFILE_MASK
    int depthBits = 0;         ///< of the default framebuffer's depth attachment
    int maxTextureSize = 0;    ///< GL_MAX_TEXTURE_SIZE, texels per side
    std::string renderer;      ///< GL_RENDERER
    std::string version;       ///< GL_VERSION
};

/// Queries the context current on this thread. Requires a current context; throws
/// std::runtime_error if there is none.
GlInfo queryGlInfo();

}  // namespace gale::render
