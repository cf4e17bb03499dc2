/// \file CommandsTerrain.cpp
/// `gale terrain`: the scene's heightfield as a 16-bit greyscale PNG that a heightmap scene can
/// read back.

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <system_error>
#include <vector>

#include "app/Cli.h"
#include "app/Commands.h"
#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/io/ImageCheck.h"
#include "app/io/Interrupt.h"
#include "app/io/OutputLock.h"
#include "app/scene/Heightmap.h"
#include "app/scene/SceneBuilder.h"
#include "app/scene/SceneParser.h"

namespace gale::app {
int runTerrainExport(const TerrainExportOptions& options) {
    namespace fs = std::filesystem;
    const fs::path out(options.imagePath);
    std::string ext = out.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".png")
        throw InputError(
            "-o: the heightmap is written as a 16-bit PNG; the name must end in .png "
            "(got \"" +
            options.imagePath + "\")");
    std::error_code ec;
    if (fs::is_directory(out, ec)) throw InputError("-o: '" + options.imagePath + "' is a folder");
    const fs::path parent = out.parent_path().empty() ? fs::path(".") : out.parent_path();
    if (!fs::is_directory(parent, ec))
        throw InputError("-o: folder '" + parent.string() + "' does not exist");

    InterruptScope interrupt("while exporting the terrain: nothing written");
    const Scene scene = parseSceneFile(options.scenePath);
    refuseAliases(sceneInputs(scene), {{options.imagePath, "-o"}});
    const sim::Heightfield field = buildHeightfield(scene);
    const OutputLock lock(parent.string(), "-o");
    removeStaleTemporaries(parent.string());
    // Written to a temporary, read back whole, fsync'ed, then renamed over the destination: a
    // full disk leaves the earlier file (if any) as it was.
    StagedFiles staged;
    const std::string tmp = staged.add(options.imagePath);
    HeightmapRange range;
    errno = 0;
    try {
        range = writeHeightmapPng16(field, tmp);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(options.imagePath + ": cannot write: " + e.what());
    }
    verifyImageFile(tmp, options.imagePath, field.nx, field.ny, errno);
    staged.seal(options.imagePath);
    staged.commit();
    std::printf("wrote %s: %d x %d pixels, 16-bit grey, heights %.6g .. %.6g m\n",
                options.imagePath.c_str(), field.nx, field.ny, range.minHeight_m,
                range.maxHeight_m);
    std::printf("read it back with:\n");
    std::printf("  [terrain]\n  kind = \"heightmap\"\n  image = \"%s\"\n",
                out.filename().string().c_str());
    std::printf("  metres_per_pixel = %.9g\n  height_offset_m = %.9g\n  height_scale_m = %.9g\n",
                field.spacing_m, range.minHeight_m, range.maxHeight_m - range.minHeight_m);
    return EXIT_OK;
}

void addTerrainVerb(CLI::App& app, VerbTable& verbs) {
    auto options = std::make_shared<TerrainExportOptions>();
    CLI::App* verb = app.add_subcommand(
        "terrain",
        "Export a scene's heightfield as a 16-bit grey PNG (a heightmap scene reads it)");
    verb->add_option("scene", options->scenePath, "Scene file")->required();
    verb->add_option("-o,--output", options->imagePath, "PNG file to write")->required();
    verb->footer(EXIT_CODES_FOOTER);
    verbs.add(verb, [options] { return runTerrainExport(*options); });
}

}  // namespace gale::app
