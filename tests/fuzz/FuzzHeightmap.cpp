// libFuzzer target: the heightmap loader (app/scene/Heightmap) on arbitrary file contents, through
// every image format OpenImageIO reads. The contract under test: a file either loads into a
// finite heightfield or throws ImageError naming the file. Anything else (another exception, a
// crash, a sanitizer report, an allocation beyond -rss_limit_mb, a hang) is a bug.

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "app/io/Errors.h"
#include "app/scene/Heightmap.h"

namespace {

/// The fuzzed bytes go to this file (no extension: OpenImageIO tries every reader on it).
std::string gPath;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    const char* tmp = std::getenv("TMPDIR");
    gPath = std::string(tmp && *tmp ? tmp : "/tmp") + "/gale-fuzz-heightmap-" +
            std::to_string(::getpid());
    OIIO::attribute("threads", 1);  // no thread pool: one input at a time, reproducible
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::FILE* f = std::fopen(gPath.c_str(), "wb");
    if (!f) std::abort();
    if (size && std::fwrite(data, 1, size, f) != size) std::abort();
    std::fclose(f);

    gale::app::HeightmapSpec spec;
    spec.path = gPath;
    try {
        const gale::sim::Heightfield field = gale::app::loadHeightmap(spec);
        for (float h : field.height_m)
            if (!std::isfinite(h)) std::abort();  // the loader promises finite heights
    } catch (const gale::app::ImageError& e) {
        if (std::string(e.what()).rfind(gPath, 0) != 0) std::abort();  // must name the file
    }
    std::remove(gPath.c_str());
    return 0;
}
