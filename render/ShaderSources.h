#pragma once
/// \file ShaderSources.h
/// The GLSL files of shaders/, embedded at build time (cmake/EmbedShaders.cmake).

namespace gale::render {
/// Source text of shaders/<name> (e.g. "shell.vert"), or nullptr if there is no such file.
const char* shaderSource(const char* name);
}  // namespace gale::render
