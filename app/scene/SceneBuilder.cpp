#include "app/scene/SceneBuilder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <memory>
#include <stdexcept>

#include "app/io/Errors.h"
#include "app/io/QuietStderr.h"
#include "app/io/Timing.h"
#include "app/scene/Dem.h"
#include "app/scene/Heightmap.h"
#include "app/scene/SceneField.h"
#include "base/Numbers.h"
#include "base/ParameterError.h"
#include "coupling/FieldSampling.h"
#include "coupling/FieldWind.h"
#include "coupling/Flutter.h"
#include "coupling/PointSourceWind.h"
#include "coupling/SteadyGustWind.h"
#include "coupling/TerrainMeshBuilder.h"
#include "coupling/UnsteadyFieldWind.h"
#include "render/ImageIO.h"
#include "sim/Advection.h"
#include "sim/AirDomain.h"
#include "sim/MemoryEstimate.h"
#include "sim/SteadyWind.h"

namespace gale::app {
namespace {

using gale::PI;
/// Largest grass texture image we read; matches GrassTextureSpec::size's range.
constexpr int MAX_TEXTURE_SIDE_PX = 4096;
/// Default view: elevation of the camera above the horizontal, seen from the target. Low, as the
/// default scene's (examples/knoll.toml) three-quarter view: the relief reads in its shading and
/// silhouettes, and the grass is seen at the grazing angles it is drawn for.
constexpr double DEFAULT_ELEVATION_DEG = 20.0;
/// The camera stands at this fraction of the distance at which the terrain's bounding sphere just
/// fits the frame: the sphere's top and bottom fall outside, the terrain (flatter than the sphere)
/// still spans the frame's width.
constexpr double FRAME_FILL = 0.8;
/// The default camera stays at least this high over the ground under it (a person's eyes).
constexpr double MIN_EYE_HEIGHT_M = 1.7;

[[noreturn]] void failAt(const Scene& scene, const std::string& key, const std::string& reason) {
    throw SceneError(scene.where(key) + ": " + reason);
}

}  // namespace

void rethrowAsSceneError(const Scene& scene, const std::string& fallbackKey,
                         const std::invalid_argument& error) {
    const auto* p = dynamic_cast<const ParameterError*>(&error);
    if (!p) failAt(scene, fallbackKey, error.what());
    const auto lineOf = [&](const std::string& key) {
        const auto it = scene.keyLines.find(key);
        return it == scene.keyLines.end() ? 0 : it->second;
    };
    // The line of the key, or of the nearest enclosing part the scene wrote: "terrain.size_m[0]"
    // is on terrain.size_m's line; a default the scene did not write, on its section's.
    std::string written = p->key();
    while (!written.empty() && lineOf(written) == 0) {
        const size_t cut = written.find_last_of(".[");
        written = cut == std::string::npos ? std::string() : written.substr(0, cut);
    }
    const std::string key = p->key().substr(0, p->key().find('[', p->key().rfind('.') + 1));
    const bool isDefault = written.size() < key.size();
    const int line = !written.empty() ? lineOf(written) : lineOf(fallbackKey);
    throw SceneError(scene.path + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " +
                     p->key() + ": " + p->expected() + " (got " + p->value() +
                     (isDefault ? ", the default)" : ")"));
}

namespace {

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

coupling::GustCurve gustCurve(const Scene& scene) {
    return scene.wind.curve ? *scene.wind.curve
                            : coupling::GustCurve::attackDecay(/*period_s=*/4.0, /*base=*/0.1,
                                                               /*peak=*/0.8, /*attack_s=*/0.4,
                                                               /*decay_s=*/1.6);
}

void buildPointSourceWind(const Scene& scene, BuiltScene& built) {
    const sim::Heightfield& field = built.heightfield;
    coupling::PointSourceSpec source = scene.wind.pointSource;
    if (scene.wind.autoSource) {
        // West edge, half way along it, on the ground: the gust crosses the terrain along +x.
        const double y = field.originY_m + 0.5 * field.sizeY_m();
        source.wsSource_m = glm::vec3(field.originX_m, y, field.sample(field.originX_m, y));
    }
    built.wsWindSource_m = source.wsSource_m;
    try {
        built.wind =
            std::make_unique<coupling::PointSourceWind>(built.mesh, source, gustCurve(scene));
    } catch (const std::invalid_argument& e) {
        rethrowAsSceneError(scene, "wind", e);
    }
}

std::string describeDomain(const sim::AirDomain& d) {
    char buf[256];
    std::snprintf(
        buf, sizeof buf,
        "%d x %d x %d cells of %.3g m, %zu air cells (%.0f%% of the box), top at %.1f m, "
        "about %.0f MiB",
        d.nx(), d.ny(), d.nz(), d.voxelSize_m(), d.activeCellCount(),
        100.0 * double(d.activeCellCount()) / double(std::max<size_t>(1, d.boxCellCount())),
        d.wsTop_m(), d.memoryEstimate_bytes() / (1024.0 * 1024.0));
    return buf;
}

/// The scene's air domain over the built terrain (app/scene/SceneField.h), summarised in
/// built.domainSummary and built.fieldPlan, with the checks the solve would make before solving.
std::unique_ptr<sim::AirDomain> buildDomain(const Scene& scene, BuiltScene& built) {
    checkSceneFieldInputs(scene);
    std::unique_ptr<sim::AirDomain> domain = buildSceneDomain(scene, built.heightfield);
    built.domainSummary = describeDomain(*domain);
    built.domainEstimate_bytes = double(domain->memoryEstimate_bytes());
    built.domainVdbFile_bytes = sim::vdbWindFile_bytes(domain->nx(), domain->ny(), domain->nz());
    built.fieldPlan = describeSceneField(scene, *domain);
    return domain;
}

/// The composition's options for a build: progress lines when the build shows progress (render
/// and view print "gale: ..."), nothing otherwise.
SceneFieldOptions fieldOptions(const BuildOptions& options) {
    return options.progress ? verbFieldOptions("gale") : SceneFieldOptions{};
}

/// Metres above the ground where the grass reads the field: wind.sample_height_m, or the grass
/// height when the scene leaves it out.
double sampleHeightOf(const Scene& scene) {
    return scene.wind.sampleHeight_m.value_or(double(scene.grass.params.height_m));
}

/// The turbulent flutter of a steady field's grass (coupling/Flutter.h), one amplitude per mesh
/// vertex: from the momentum model's k where it has one, sampled (trilinear) at the grass point
/// over each vertex; otherwise from the mixing-length k of the shear between the sample height
/// and twice it.
std::vector<float> steadyFlutter(const Scene& scene, const SceneField& result,
                                 const sim::WindField& field, const BuiltScene& built,
                                 const std::vector<glm::vec3>& velocity) {
    const double bend_mps = scene.wind.response.bendSpeed_mps;
    const double z_m = std::max(sampleHeightOf(scene), 0.05);
    const render::TerrainMesh& mesh = built.mesh;
    std::vector<double> k(mesh.wsPosition_m.size(), 0.0);
    if (!result.tke_m2ps2.empty() && result.domain) {
        const sim::MacGrid grid(result.domain->layout(), &result.domain->terrain());
        for (size_t v = 0; v < k.size(); ++v) {
            const glm::vec3& p = mesh.wsPosition_m[v];
            k[v] = std::max(0.0, sim::sampleAt(grid, sim::Placement::Cell, result.tke_m2ps2,
                                               sim::Vec3d{p.x, p.y, p.z + z_m}));
        }
    } else {
        const std::vector<glm::vec3> high =
            coupling::sampleAtGrass(field, mesh, 2.0 * z_m, nearGroundOf(scene));
        for (size_t v = 0; v < k.size(); ++v)
            k[v] = coupling::shearTke_m2ps2(glm::length(velocity[v]), glm::length(high[v]), z_m,
                                            2.0 * z_m);
    }
    return coupling::flutterFromTke(k, velocity, bend_mps);
}

/// wind.kind = "solved": the steady mass-consistent field (docs/design.md 4.1) sampled at grass
/// height, then either held (steady) or swept by travelling gusts (docs/design.md 4.2, kinematic
/// mode).
void buildSolvedWind(const Scene& scene, const BuildOptions& options, BuiltScene& built) {
    const auto start = Clock::now();
    std::unique_ptr<sim::AirDomain> domain = buildDomain(scene, built);
    if (!options.solveWind) return;
    if (options.progress) options.progress("solving the steady wind: " + built.domainSummary);
    SceneField result = solveSceneField(scene, std::move(domain), fieldOptions(options));
    built.solve = result.report;
    built.fieldSummary = result.summary();
    // Kept alive in the wind source for views of the field (coupling/FieldOverlayBuilder).
    auto field = std::make_shared<const sim::WindField>(std::move(result.field));
    const std::vector<glm::vec3> velocity =
        coupling::sampleAtGrass(*field, built.mesh, sampleHeightOf(scene), nearGroundOf(scene));
    std::vector<float> flutter = steadyFlutter(scene, result, *field, built, velocity);
    try {
        if (scene.wind.gusts) {
            coupling::SteadyGustSpec spec;
            spec.response = scene.wind.response;
            spec.arrivalBands = scene.wind.arrivalBands;
            spec.levels = scene.wind.levels;
            // The front travels with the ambient wind at its reference height (at least 0.5 m/s,
            // so a calm scene still has a finite arrival time).
            spec.convection_mps = std::max(0.5, scene.wind.ambient.speed_mps);
            const double a = radiansFromDegrees(scene.wind.ambient.direction_deg);
            spec.wsDirection = glm::vec3(std::cos(a), std::sin(a), 0.0f);
            auto wind = std::make_unique<coupling::SteadyGustWind>(built.mesh, velocity, spec,
                                                                   gustCurve(scene));
            wind->keepField(field);
            wind->setFlutter(std::move(flutter));
            built.wind = std::move(wind);
        } else {
            auto wind = std::make_unique<coupling::FieldWind>(built.mesh, scene.wind.response);
            wind->addFieldStep(0.0, velocity);
            wind->setFlutter(std::move(flutter));
            wind->keepField(field);
            built.wind = std::move(wind);
        }
    } catch (const std::invalid_argument& e) {
        rethrowAsSceneError(scene, "wind", e);
    }
    built.solve_ms = msSince(start);
}

/// wind.kind = "unsteady": the steady field as initial state and mean flow, stepped in time by
/// sim::UnsteadyWindSolver inside a coupling::UnsteadyFieldWind as the frames ask
/// (docs/design.md 4.2).
void buildUnsteadyWind(const Scene& scene, const BuildOptions& options, BuiltScene& built) {
    const auto start = Clock::now();
    std::unique_ptr<sim::AirDomain> domain = buildDomain(scene, built);
    if (!options.solveWind) return;
    if (options.progress)
        options.progress("solving the steady wind (initial state): " + built.domainSummary);
    SceneField result = solveSceneField(scene, std::move(domain), fieldOptions(options));
    built.solve = result.report;
    built.fieldSummary = result.summary();
    const UnsteadyStepping stepping = unsteadySteppingOf(scene);
    try {
        built.wind = std::make_unique<coupling::UnsteadyFieldWind>(
            built.mesh, std::move(result.domain), result.field, stepping.settings,
            stepping.referenceSpeed_mps, scene.wind.response, sampleHeightOf(scene));
    } catch (const std::invalid_argument& e) {
        rethrowAsSceneError(scene, "unsteady", e);
    }
    built.solve_ms = msSince(start);
}

}  // namespace

LiveWindGrid buildLiveWindGrid(const Scene& scene, const sim::Heightfield& terrain,
                               double voxelSize_m) {
    if (scene.solver.domain.firstCell_m)
        failAt(scene, "solver.first_cell_m",
               "the coarser live grid needs cubic cells; this scene has stretched layers");
    Scene other = scene;
    other.solver.domain.voxelSize_m = voxelSize_m;
    SceneField result = solveSceneField(other, buildSceneDomain(other, terrain));
    const UnsteadyStepping stepping = unsteadySteppingOf(other);
    LiveWindGrid grid;
    grid.summary = result.summary();
    grid.domain = std::move(result.domain);
    grid.steady = std::move(result.field);
    grid.settings = stepping.settings;
    grid.referenceSpeed_mps = stepping.referenceSpeed_mps;
    return grid;
}

SceneTerrain buildTerrain(const Scene& scene) {
    const TerrainSection& t = scene.terrain;
    if (t.dem) {
        try {
            Dem dem = loadDem({t.demPath, t.crop, t.meshStride});
            return {std::move(dem.field), std::move(dem.georef)};
        } catch (const ImageError& e) {
            failAt(scene, "terrain.dem", e.what());
        }
    }
    if (t.spec.kind == sim::TerrainKind::Heightmap) {
        try {
            return {loadHeightmap({t.imagePath, t.metresPerPixel, t.heightScale_m, t.heightOffset_m,
                                   t.meshStride}),
                    {}};
        } catch (const ImageError& e) {
            failAt(scene, "terrain.image", e.what());
        }
    }
    try {
        return {sim::makeTerrain(t.spec), {}};
    } catch (const std::invalid_argument& e) {
        rethrowAsSceneError(scene, "terrain", e);
    }
}

sim::Heightfield buildHeightfield(const Scene& scene) { return buildTerrain(scene).field; }

render::Camera defaultCamera(const sim::Heightfield& field, const render::Camera& base,
                             bool keepPosition, bool keepTarget) {
    render::Camera camera = base;
    const double minZ = field.minHeight_m(), maxZ = field.maxHeight_m();
    const double cx = field.originX_m + 0.5 * field.sizeX_m();
    const double cy = field.originY_m + 0.5 * field.sizeY_m();
    if (!keepTarget) camera.wsTarget_m = glm::vec3(cx, cy, field.sample(cx, cy) * 0.5 + minZ * 0.5);
    if (keepPosition) return camera;
    const double halfFov = radiansFromDegrees(0.5 * camera.fovY_deg);
    const double azimuth = radiansFromDegrees(235.0);  // from the south-west
    auto place = [&](double distance, double elevation) {
        const glm::dvec3 target(camera.wsTarget_m);
        camera.wsPosition_m =
            glm::vec3(target + distance * glm::dvec3(std::cos(elevation) * std::cos(azimuth),
                                                     std::cos(elevation) * std::sin(azimuth),
                                                     std::sin(elevation)));
    };
    // Frame a sphere around the terrain: distance = radius / sin(fov / 2).
    const double radius =
        0.5 * std::sqrt(field.sizeX_m() * field.sizeX_m() + field.sizeY_m() * field.sizeY_m() +
                        (maxZ - minZ) * (maxZ - minZ));
    const double distance = std::max(1.0, FRAME_FILL * radius / std::sin(halfFov));
    const double elevation = radiansFromDegrees(DEFAULT_ELEVATION_DEG);
    place(distance, elevation);
    // Never inside a hill between the camera and the target.
    const float ground = float(field.sample(camera.wsPosition_m.x, camera.wsPosition_m.y));
    camera.wsPosition_m.z = std::max(camera.wsPosition_m.z, ground + float(MIN_EYE_HEIGHT_M));
    return camera;
}

/// The default far plane follows the terrain: at least 1.5 x the distance from the camera to the
/// terrain's farthest bounding-box corner (a 2 km terrain's default camera sits beyond 1000 m).
/// An explicit far plane nearer than the terrain's nearest point is a warning: every frame would
/// be sky.
void fitFarPlane(const Scene& scene, const sim::Heightfield& field, BuiltScene& built) {
    constexpr double AUTO_FAR_MARGIN = 1.5;  // the mesh's skirt and grass tops lie beyond the box
    render::Camera& c = built.camera;
    const glm::dvec3 eye(c.wsPosition_m);
    const glm::dvec3 lo(field.originX_m, field.originY_m, field.minHeight_m());
    const glm::dvec3 hi(field.originX_m + field.sizeX_m(), field.originY_m + field.sizeY_m(),
                        field.maxHeight_m());
    double farthest = 0.0;
    for (int n = 0; n < 8; ++n) {
        const glm::dvec3 corner(n & 1 ? hi.x : lo.x, n & 2 ? hi.y : lo.y, n & 4 ? hi.z : lo.z);
        farthest = std::max(farthest, glm::length(corner - eye));
    }
    if (scene.autoCameraFar) {
        c.far_m = float(std::max(double(c.far_m), AUTO_FAR_MARGIN * farthest));
        return;
    }
    const double nearest = glm::length(glm::clamp(eye, lo, hi) - eye);
    if (nearest >= double(c.far_m))
        built.warnings.push_back(
            scene.where("camera.far_m") + ": far_m = " + formatG(c.far_m, 4) +
            " m but the nearest terrain is " + formatG(nearest, 4) +
            " m from the camera: every frame would show only sky (raise far_m, or leave it out "
            "and it follows the terrain)");
}

BuiltScene buildScene(const Scene& scene, const BuildOptions& options) {
    const auto start = Clock::now();
    BuiltScene built;
    SceneTerrain terrain = buildTerrain(scene);
    built.heightfield = std::move(terrain.field);
    built.georef = std::move(terrain.georef);
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
            rethrowAsSceneError(scene, "grass.generated", e);
        }
    } else {
        built.texture = loadTexture(scene);
    }
    if (!scene.grass.densityMapPath.empty()) {
        // The map covers the render mesh's plan, its top row the north edge.
        glm::vec2 lo(built.mesh.wsPosition_m.front()), hi = lo;
        for (const glm::vec3& p : built.mesh.wsPosition_m)
            lo = glm::min(lo, glm::vec2(p)), hi = glm::max(hi, glm::vec2(p));
        try {
            QuietStderr quiet;  // libpng would print the error a second time
            built.densityMap = render::loadDensityMap(scene.grass.densityMapPath, lo, hi - lo);
        } catch (const std::exception& e) {
            failAt(scene, "grass.density_map", e.what());
        }
    }

    built.camera =
        defaultCamera(field, scene.camera, !scene.autoCameraPosition, !scene.autoCameraTarget);
    const glm::vec3 d = built.camera.wsTarget_m - built.camera.wsPosition_m;
    if (!(d.x * d.x + d.y * d.y + d.z * d.z > 1e-12f))
        failAt(scene, scene.autoCameraTarget ? "camera.position_m" : "camera.target_m",
               "the camera sits on its target (give both position_m and target_m)");
    fitFarPlane(scene, field, built);

    if (scene.wind.kind == WindKind::Solved)
        buildSolvedWind(scene, options, built);
    else if (scene.wind.kind == WindKind::Unsteady)
        buildUnsteadyWind(scene, options, built);
    else
        buildPointSourceWind(scene, built);
    built.build_ms = msSince(start);
    return built;
}

}  // namespace gale::app
