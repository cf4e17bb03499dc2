#pragma once
/// \file GlUtil.h
/// Small helpers shared by the GL code of render/: shader compilation from the embedded shaders/
/// files with checked logs, and move-only owners of GL object names. Internal to render/.

#include <GL/gl.h>

#include <string>
#include <utility>
#include <vector>

namespace gale::render::detail {

/// Compiles shaders/<fileName> (embedded, see ShaderSources.h) as a shader of `stage`
/// (GL_VERTEX_SHADER, GL_FRAGMENT_SHADER). `defines` (whole lines, e.g. "#define FOO 1\n") go
/// right after the file's #version line: the way one file yields several specialised shaders.
/// Requires a current context. Throws std::runtime_error naming the file and carrying the compiler
/// log if the file is missing or does not compile.
GLuint compileShaderFile(GLenum stage, const char* fileName, const std::string& defines = {});

/// Compiles `source` as a shader of `stage`; `fileName` only names it in errors. Throws
/// std::runtime_error naming the file and carrying the compiler log if it does not compile.
GLuint compileShaderSource(GLenum stage, const char* fileName, const char* source);

/// Links a program from shaders/<vertexFile> and shaders/<fragmentFile>, both compiled with
/// `defines` (as compileShaderFile). Throws std::runtime_error naming both files and carrying the
/// compile or link log. `feedback`: the vertex stage's outputs a transform feedback records
/// (interleaved, in this order; none by default).
GLuint linkProgramFiles(const char* vertexFile, const char* fragmentFile,
                        const std::string& defines = {},
                        const std::vector<const char*>& feedback = {});

/// Throws std::runtime_error naming `what` if the bound draw framebuffer is not complete.
void checkFramebufferComplete(const char* what);

/// Throws std::runtime_error naming `what` and the GL error code if glGetError reports one.
void checkGlError(const char* what);

/// Move-only owner of one GL object name; `Deleter` releases it (e.g. glDeleteProgram).
template <void (*Deleter)(GLuint)>
class GlName {
  public:
    GlName() = default;
    explicit GlName(GLuint name) : mName(name) {}
    ~GlName() { reset(); }
    GlName(GlName&& other) noexcept : mName(std::exchange(other.mName, 0)) {}
    GlName& operator=(GlName&& other) noexcept {
        if (this != &other) {
            reset();
            mName = std::exchange(other.mName, 0);
        }
        return *this;
    }
    GlName(const GlName&) = delete;
    GlName& operator=(const GlName&) = delete;
    GLuint get() const { return mName; }
    void reset() {
        if (mName != 0) Deleter(mName);
        mName = 0;
    }

  private:
    GLuint mName = 0;
};

void deleteProgram(GLuint name);
void deleteBuffer(GLuint name);
void deleteTexture(GLuint name);
void deleteVertexArray(GLuint name);
void deleteSampler(GLuint name);
void deleteFramebuffer(GLuint name);

using Program = GlName<deleteProgram>;
using Buffer = GlName<deleteBuffer>;
using Texture = GlName<deleteTexture>;
using VertexArray = GlName<deleteVertexArray>;
using Sampler = GlName<deleteSampler>;
using Framebuffer = GlName<deleteFramebuffer>;

}  // namespace gale::render::detail
