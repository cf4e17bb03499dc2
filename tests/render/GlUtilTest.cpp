// Shader compilation errors name the shader file and carry the log (STYLE, errors).
#define GL_GLEXT_PROTOTYPES 1
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "render/GlContext.h"
#include "render/GlUtil.h"
#include "render/ShellRendererImpl.h"

namespace gale::render {
namespace {

std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "(no exception)";
}

TEST(ShaderCompile, MissingFileErrorNamesTheFile) {
    auto context = createOsMesaContext(8, 8);
    const std::string message =
        messageOf([] { detail::compileShaderFile(GL_VERTEX_SHADER, "no_such.vert"); });
    EXPECT_NE(message.find("shaders/no_such.vert"), std::string::npos) << message;
}

TEST(ShaderCompile, CompileErrorNamesTheFileAndCarriesTheLog) {
    auto context = createOsMesaContext(8, 8);
    const char* broken = "#version 450 core\nvoid main() { gl_Position = undeclaredThing; }\n";
    const std::string message =
        messageOf([&] { detail::compileShaderSource(GL_VERTEX_SHADER, "broken.vert", broken); });
    EXPECT_NE(message.find("shaders/broken.vert: compile failed"), std::string::npos) << message;
    EXPECT_NE(message.find("undeclaredThing"), std::string::npos) << message;
}

TEST(ShaderCompile, EmbeddedShadersCompileAndLink) {
    auto context = createOsMesaContext(8, 8);
    const detail::Program shell(detail::linkProgramFiles("shell.vert", "shell.frag"));
    const detail::Program fill(detail::linkProgramFiles("fill.vert", "fill.frag"));
    EXPECT_NE(shell.get(), 0u);
    EXPECT_NE(fill.get(), 0u);
}

TEST(ShaderCompile, EveryShellVariantCompilesAndLinks) {
    // The renderer compiles a variant when a frame first needs it: all of them must build.
    auto context = createOsMesaContext(8, 8);
    for (unsigned bits = 0; bits < shell_detail::SHELL_VARIANTS; ++bits) {
        const std::string defines = shell_detail::shellVariantDefines(bits);
        EXPECT_NO_THROW(
            detail::Program(detail::linkProgramFiles("shell.vert", "shell.frag", defines)))
            << defines;
    }
}

TEST(ShaderCompile, DefinesGoAfterTheVersionLine) {
    auto context = createOsMesaContext(8, 8);
    // A define the shader tests with #if: without it the shader would not compile.
    const char* defines = "#define BLEND_GROUPS 1\n#define UNUSED_BY_THE_SHADER 3\n";
    EXPECT_NO_THROW(detail::Program(detail::linkProgramFiles("shell.vert", "shell.frag", defines)));
    const std::string message = messageOf([] {
        detail::compileShaderFile(GL_VERTEX_SHADER, "shell.vert", "#error from the defines\n");
    });
    EXPECT_NE(message.find("from the defines"), std::string::npos) << message;
}

}  // namespace
}  // namespace gale::render
