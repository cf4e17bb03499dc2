/// \file GlUtil.cpp
/// Shader compilation with checked logs, GL error checks, GL object deleters.

#include "render/GlUtil.h"

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/GlInfo.h"
#include "render/ShaderSources.h"

namespace gale::render {
namespace detail {
namespace {

std::string shaderLog(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<size_t>(length > 0 ? length : 1), '\0');
    glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
    return std::string(log.data());
}

std::string programLog(GLuint program) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<size_t>(length > 0 ? length : 1), '\0');
    glGetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
    return std::string(log.data());
}

}  // namespace

GLuint compileShaderFile(GLenum stage, const char* fileName, const std::string& defines) {
    const char* source = shaderSource(fileName);
    if (source == nullptr) {
        throw std::runtime_error(std::string("shaders/") + fileName +
                                 ": no such shader embedded in the binary");
    }
    if (defines.empty()) return compileShaderSource(stage, fileName, source);
    // GLSL wants #version first: the defines go on the lines right after it.
    std::string text(source);
    const size_t lineEnd = text.find('\n');
    if (text.rfind("#version", 0) != 0 || lineEnd == std::string::npos) {
        throw std::runtime_error(std::string("shaders/") + fileName +
                                 ": defines need the file to start with a #version line");
    }
    text.insert(lineEnd + 1, defines);
    return compileShaderSource(stage, fileName, text.c_str());
}

GLuint compileShaderSource(GLenum stage, const char* fileName, const char* source) {
    const GLuint shader = glCreateShader(stage);
    if (shader == 0) {
        throw std::runtime_error(std::string("shaders/") + fileName +
                                 ": glCreateShader failed (is a GL context current?)");
    }
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string log = shaderLog(shader);
        glDeleteShader(shader);
        throw std::runtime_error(std::string("shaders/") + fileName + ": compile failed:\n" + log);
    }
    return shader;
}

GLuint linkProgramFiles(const char* vertexFile, const char* fragmentFile,
                        const std::string& defines, const std::vector<const char*>& feedback) {
    const GLuint vs = compileShaderFile(GL_VERTEX_SHADER, vertexFile, defines);
    GLuint fs = 0;
    try {
        fs = compileShaderFile(GL_FRAGMENT_SHADER, fragmentFile, defines);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    if (!feedback.empty())
        glTransformFeedbackVaryings(program, static_cast<GLsizei>(feedback.size()), feedback.data(),
                                    GL_INTERLEAVED_ATTRIBS);
    glLinkProgram(program);
    glDetachShader(program, vs);
    glDetachShader(program, fs);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string log = programLog(program);
        glDeleteProgram(program);
        throw std::runtime_error(std::string("shaders/") + vertexFile + " + shaders/" +
                                 fragmentFile + ": link failed:\n" + log);
    }
    return program;
}

void checkFramebufferComplete(const char* what) {
    const GLenum status = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        char hex[16];
        std::snprintf(hex, sizeof hex, "%04x", status);
        throw std::runtime_error(std::string(what) + ": framebuffer incomplete (status 0x" + hex +
                                 ")");
    }
}

void checkGlError(const char* what) {
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        char hex[16];
        std::snprintf(hex, sizeof hex, "%04x", error);
        throw std::runtime_error(std::string(what) + ": GL error 0x" + hex);
    }
}

void deleteProgram(GLuint name) { glDeleteProgram(name); }
void deleteBuffer(GLuint name) { glDeleteBuffers(1, &name); }
void deleteTexture(GLuint name) { glDeleteTextures(1, &name); }
void deleteVertexArray(GLuint name) { glDeleteVertexArrays(1, &name); }
void deleteSampler(GLuint name) { glDeleteSamplers(1, &name); }
void deleteFramebuffer(GLuint name) { glDeleteFramebuffers(1, &name); }

}  // namespace detail

GlInfo queryGlInfo() {
    const GLubyte* renderer = glGetString(GL_RENDERER);
    if (renderer == nullptr) {
        throw std::runtime_error("queryGlInfo: no current GL context (glGetString returned null)");
    }
    GlInfo info;
    info.renderer = reinterpret_cast<const char*>(renderer);
    const GLubyte* version = glGetString(GL_VERSION);
    info.version = version ? reinterpret_cast<const char*>(version) : "";
    glGetIntegerv(GL_MAJOR_VERSION, &info.majorVersion);
    glGetIntegerv(GL_MINOR_VERSION, &info.minorVersion);
    GLint mask = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
    info.coreProfile = (mask & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &info.maxTextureSize);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    GLint depthBits = 0;
    glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, GL_DEPTH,
                                          GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &depthBits);
    info.depthBits = depthBits;
    glGetError();  // a context without a depth attachment reports an error here; depthBits stays 0
    return info;
}

}  // namespace gale::render
