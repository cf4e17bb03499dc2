#include "app/SceneBuilder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "app/Errors.h"
#include "app/Heightmap.h"
#include "app/QuietStderr.h"
#include "coupling/PointSourceWind.h"
#include "coupling/TerrainMeshBuilder.h"
#include "render/ImageIO.h"

namespace gale::app {
namespace {

constexpr double PI = 3.14159265358979323846;
/// Largest grass texture image we read; matches GrassTextureSpec::size's range.
constexpr int MAX_TEXTURE_SIDE_PX = 4096;
/// Default view: elevation of the camera above the horizontal, seen from the target.
constexpr double DEFAULT_ELEVATION_DEG = 28.0;

[[noreturn]] void failAt(const Scene& scene, const std::string& key, const std::string& reason) {
    throw SceneError(scene.where(key) + ": " + reason);
}

render::GrassTexture loadTexture(const Scene& scene) {
    const std::string& path = scene.grass.texturePath;
    // Check the header before decoding: a huge image must not be allocated.
    ImageHeader header;
    try {
        header = readImageHeader(path);
    } catch (const ImageError& e) {
        failAt(scene, "grass.texture", e.what());
    }
    if (header.width != header.height || header.width < 1 ||
        (header.width & (header.width - 1)) != 0 || header.width > MAX_TEXTURE_SIDE_PX)
        failAt(scene, "grass.texture",
               path + ": a grass texture must be square with a power-of-two side of at most " +
                   std::to_string(MAX_TEXTURE_SIDE_PX) + " pixels (got " +
                   std::to_string(header.width) + " x " + std::to_string(header.height) + ")");
    try {
        render::Image image;
        {
            QuietStderr quiet;  // libpng would print the error a second time
            image = render::readImageRgba8(path);
        }
        return render::grassTextureFromImage(std::move(image));
    } catch (const std::exception& e) {
        failAt(scene, "grass.texture", e.what());
    }
}

}  // namespace

sim::Heightfield buildHeightfield(const Scene& scene) {
    const TerrainSection& t = scene.terrain;
    if (t.spec.kind == sim::TerrainKind::Heightmap) {
        try {
            return loadHeightmap(
                {t.imagePath, t.metresPerPixel, t.heightScale_m, t.heightOffset_m, t.meshStride});
        } catch (const ImageError& e) {
            failAt(scene, "terrain.image", e.what());
        }
    }
    try {
        return sim::makeTerrain(t.spec);
    } catch (const std::invalid_argument& e) {
        failAt(scene, "terrain", e.what());
    }
}

render::Camera defaultCamera(const sim::Heightfield& field, const render::Camera& base,
                             bool keepPosition, bool keepTarget) {
    render::Camera camera = base;
    const double minZ = field.minHeight_m(), maxZ = field.maxHeight_m();
    const double cx = field.originX_m + 0.5 * field.sizeX_m();
    const double cy = field.originY_m + 0.5 * field.sizeY_m();
    if (!keepTarget) camera.wsTarget_m = glm::vec3(cx, cy, field.sample(cx, cy) * 0.5 + minZ * 0.5);
    if (!keepPosition) {
        // Frame a sphere around the terrain: distance = radius / sin(fov / 2).
        const double radius =
            0.5 * std::sqrt(field.sizeX_m() * field.sizeX_m() + field.sizeY_m() * field.sizeY_m() +
                            (maxZ - minZ) * (maxZ - minZ));
        const double distance =
            std::max(1.0, 0.8 * radius / std::sin(0.5 * camera.fovY_deg * PI / 180.0));
        const double elevation = DEFAULT_ELEVATION_DEG * PI / 180.0;
        const double azimuth = 235.0 * PI / 180.0;  // from the south-west
        const glm::dvec3 target(camera.wsTarget_m);
        camera.wsPosition_m =
            glm::vec3(target + distance * glm::dvec3(std::cos(elevation) * std::cos(azimuth),
                                                     std::cos(elevation) * std::sin(azimuth),
                                                     std::sin(elevation)));
    }
    return camera;
}

BuiltScene buildScene(const Scene& scene) {
    const auto start = std::chrono::steady_clock::now();
    BuiltScene built;
    built.heightfield = buildHeightfield(scene);
    const sim::Heightfield& field = built.heightfield;
    if (scene.terrain.meshStride >= std::max(field.nx, field.ny))
        failAt(scene, "terrain.mesh_stride",
               "must be smaller than the grid (" + std::to_string(field.nx) + " x " +
                   std::to_string(field.ny) + " samples) (got " +
                   std::to_string(scene.terrain.meshStride) + ")");
    built.mesh =
        coupling::buildTerrainMesh(field, scene.grass.params.tile_m, scene.terrain.meshStride);

    if (scene.grass.texturePath.empty()) {
        try {
            built.texture = render::generateGrassTexture(scene.grass.generated);
        } catch (const std::invalid_argument& e) {
            failAt(scene, "grass.generated", e.what());
        }
    } else {
        built.texture = loadTexture(scene);
    }

    built.camera =
        defaultCamera(field, scene.camera, !scene.autoCameraPosition, !scene.autoCameraTarget);
    const glm::vec3 d = built.camera.wsTarget_m - built.camera.wsPosition_m;
    if (!(d.x * d.x + d.y * d.y + d.z * d.z > 1e-12f))
        failAt(scene, scene.autoCameraTarget ? "camera.position_m" : "camera.target_m",
               "the camera sits on its target (give both position_m and target_m)");

    coupling::PointSourceSpec source = scene.wind.pointSource;
    if (scene.wind.autoSource) {
        // West edge, half way along it, on the ground: the gust crosses the terrain along +x.
        const double y = field.originY_m + 0.5 * field.sizeY_m();
        source.wsSource_m = glm::vec3(field.originX_m, y, field.sample(field.originX_m, y));
    }
    built.wsWindSource_m = source.wsSource_m;
    try {
        const coupling::GustCurve curve =
            scene.wind.curve ? *scene.wind.curve
                             : coupling::GustCurve::attackDecay(/*period_s=*/4.0, /*base=*/0.1,
                                                                /*peak=*/0.8, /*attack_s=*/0.4,
                                                                /*decay_s=*/1.6);
        built.wind = std::make_unique<coupling::PointSourceWind>(built.mesh, source, curve);
    } catch (const std::invalid_argument& e) {
        failAt(scene, "wind", e.what());
    }
    built.build_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return built;
}

}  // namespace gale::app
