// libFuzzer target: the scene parser (app/scene/SceneParser) on arbitrary bytes. The contract under
// test: any input either parses into a Scene or throws SceneError, whose message is one line
// starting with the file name. Anything else (another exception, a crash, a sanitizer report,
// a hang) is a bug.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "app/io/Errors.h"
#include "app/scene/SceneParser.h"

namespace {
/// Relative image paths in fuzzed scenes resolve here, a folder that does not exist, so the
/// parser's file checks answer "no such file" without touching real files.
const char* const SCENE_PATH = "/nonexistent-gale-fuzz/fuzz.toml";
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        (void)gale::app::parseSceneString(text, SCENE_PATH);
    } catch (const gale::app::SceneError& e) {
        const std::string message = e.what();
        if (message.rfind(SCENE_PATH, 0) != 0 || message.find('\n') != std::string::npos)
            std::abort();  // an error that does not name the file, or is not one line
    }
    return 0;
}
