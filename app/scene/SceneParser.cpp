#include "app/scene/SceneParser.h"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <system_error>

#include "app/io/Errors.h"
#include "app/scene/SceneKeys.h"
#include "app/scene/SceneSection.h"
#include "base/Numbers.h"
#include "render/GrassInput.h"
#include "render/RenderLimits.h"

namespace gale::app {

static_assert(MAX_SHELLS <= render::MAX_SHELLS,
              "the parser must not allow more shells than the renderer draws");

int maxLights() { return render::MAX_LIGHTS; }

namespace {

namespace fs = std::filesystem;

using namespace detail;  // the table-reading layer: Section, Limit, Context (SceneSection.h)
/// Bytes per output pixel as PNG, for the absurd-output estimate: grass is noisy and compresses
/// to roughly 1.5-2.5 bytes per RGB(A) pixel.
constexpr double PNG_BYTES_PER_PIXEL = 2.0;

std::string resolveAgainst(const fs::path& folder, const std::string& p) {
    fs::path path(p);
    if (path.is_absolute() || folder.empty()) return path.lexically_normal().string();
    return (folder / path).lexically_normal().string();
}

/// Requires an input file to exist and be a regular file; names it as resolved and as written.
void requireInputFile(Section& s, const std::string& key, const std::string& resolved,
                      const std::string& written) {
    std::error_code ec;
    const fs::file_status st = fs::status(resolved, ec);
    const std::string got = " (got \"" + written + "\")";
    if (ec || !fs::exists(st)) s.failKey(key, "no such file '" + resolved + "'" + got);
    if (fs::is_directory(st)) s.failKey(key, "'" + resolved + "' is a folder, not an image" + got);
    if (!fs::is_regular_file(st)) s.failKey(key, "'" + resolved + "' is not a regular file" + got);
}

// ---------------------------------------------------------------------------------------------
// Sections

/// For a terrain key the kind does not read, the key (or kind) that does what the scene
/// probably meant: "; did you mean height_scale_m ...?" (empty when there is none).
std::string terrainKeyHint(const std::string& key, const std::string& kindName, bool heightmap,
                           bool dem) {
    if (heightmap) {
        if (key == "height_m")
            return "; did you mean height_scale_m (the height of a full-scale pixel, metres)?";
        if (key == "size_m" || key == "spacing_m")
            return "; a heightmap's size is its pixels times metres_per_pixel: did you mean "
                   "metres_per_pixel?";
        if (key == "dem" || key == "crop_m")
            return "; for a georeferenced raster use kind = \"dem\" with dem = \"FILE\"";
        return "";
    }
    if (dem) {
        if (key == "image") return "; a DEM is named by dem = \"FILE\", not image";
        if (key == "height_m" || key == "height_scale_m" || key == "height_offset_m")
            return "; a DEM's heights are metres as stored (no scale or offset)";
        if (key == "size_m" || key == "metres_per_pixel" || key == "spacing_m")
            return "; a DEM's size and spacing come from its geotransform: did you mean crop_m?";
        return "";
    }
    if (key == "image" || key == "metres_per_pixel" || key == "height_scale_m" ||
        key == "height_offset_m")
        return "; an image terrain needs kind = \"heightmap\" (kind is \"" + kindName + "\")";
    if (key == "dem" || key == "crop_m")
        return "; a georeferenced raster needs kind = \"dem\" (kind is \"" + kindName + "\")";
    return "";
}

void readTerrain(Context& ctx, Section s) {
    TerrainSection& t = ctx.scene->terrain;
    sim::TerrainSpec& spec = t.spec;

    const std::string kindName = s.string("kind", sim::terrainKindName(spec.kind));
    const bool isDem = kindName == "dem";  // loaded like a heightmap, through GDAL (Dem.h)
    try {
        spec.kind = isDem ? sim::TerrainKind::Heightmap : sim::terrainKindFromName(kindName);
    } catch (const ParameterError&) {  // the list below adds dem, which is not built in sim/
        s.failKey("kind",
                  "expected one of flat, gaussian_hill, ridge, valley, crater, fractal, "
                  "hemisphere, heightmap, dem (got \"" +
                      kindName + "\")");
    }
    const bool heightmap = spec.kind == sim::TerrainKind::Heightmap && !isDem;

    const auto size = s.vec<2>("size_m", {spec.sizeX_m, spec.sizeY_m}, above(0.0));
    spec.sizeX_m = size[0];
    spec.sizeY_m = size[1];
    spec.spacing_m = s.number("spacing_m", spec.spacing_m, above(0.0));
    spec.height_m = s.number("height_m", spec.height_m, closed(0.0, 1e5));
    spec.radius_m = s.number("radius_m", spec.radius_m, closed(1e-3, 1e7));  // 1/(2 r^2) finite
    const auto center = s.vec<2>("center_m", {spec.sizeX_m / 2, spec.sizeY_m / 2}, anyFinite());
    spec.centerX_m = center[0];
    spec.centerY_m = center[1];
    spec.axis_deg = s.number("axis_deg", spec.axis_deg, anyFinite());
    spec.seed = static_cast<uint32_t>(s.integer("seed", spec.seed, 0, 4294967295LL));
    spec.octaves = static_cast<int>(s.integer("octaves", spec.octaves, 1, 16));
    spec.roughness = s.number("roughness", spec.roughness, above(0.0, 1.0));
    spec.featureSize_m = s.number("feature_size_m", spec.featureSize_m, above(0.0));

    const std::string image = s.string("image", "");
    t.metresPerPixel = s.number("metres_per_pixel", t.metresPerPixel, above(0.0));
    t.heightScale_m = s.number("height_scale_m", t.heightScale_m, closed(-1e5, 1e5));
    t.heightOffset_m = s.number("height_offset_m", t.heightOffset_m, closed(-1e5, 1e5));
    t.meshStride = static_cast<int>(s.integer("mesh_stride", t.meshStride, 1, 1024));
    const std::string demFile = readDemKeys(s, t, isDem);
    s.finish();

    // Which keys each kind reads (sim/Heightfield.cpp); the others are noted as ignored.
    using K = sim::TerrainKind;
    auto uses = [&](const std::string& key) -> bool {
        const K k = spec.kind;
        if (key == "size_m" || key == "spacing_m") return !heightmap && !isDem;
        if (key == "dem" || key == "crop_m") return isDem;
        if (key == "height_m")
            return k == K::GaussianHill || k == K::Ridge || k == K::Valley || k == K::Crater ||
                   k == K::Fractal;
        if (key == "radius_m" || key == "center_m")
            return k == K::GaussianHill || k == K::Ridge || k == K::Valley || k == K::Crater ||
                   k == K::Hemisphere;
        if (key == "axis_deg") return k == K::Ridge || k == K::Valley;
        if (key == "seed" || key == "octaves" || key == "roughness" || key == "feature_size_m")
            return k == K::Fractal;
        if (key == "image" || key == "metres_per_pixel" || key == "height_scale_m" ||
            key == "height_offset_m")
            return heightmap;
        return true;
    };
    for (const char* key :
         {"size_m", "spacing_m", "height_m", "radius_m", "center_m", "axis_deg", "seed", "octaves",
          "roughness", "feature_size_m", "image", "metres_per_pixel", "height_scale_m",
          "height_offset_m", "dem", "crop_m"}) {
        if (s.given(key) && !uses(key))
            ctx.scene->notes.push_back(ctx.scene->where(s.full(key)) + ": not used by kind \"" +
                                       kindName + "\" (ignored)" +
                                       terrainKeyHint(key, kindName, heightmap, isDem));
    }

    if (isDem) {
        t.dem = true;
        t.demPath = resolveAgainst(ctx.folder, demFile);
        requireInputFile(s, "dem", t.demPath, demFile);
        return;  // grid size is known once the raster is opened (Dem.cpp checks it)
    }
    if (heightmap) {
        if (image.empty()) {
            if (s.given("image")) s.failKey("image", "must name an image file (got \"\")");
            s.fail(s.line(), "image", "kind \"heightmap\" needs an image file (image = \"...\")");
        }
        t.imagePath = resolveAgainst(ctx.folder, image);
        requireInputFile(s, "image", t.imagePath, image);
        return;  // grid size is known once the image header is read (Heightmap.cpp checks it)
    }

    // Refuse absurd grids before anything allocates them.
    const int64_t nx = samplesAlong(spec.sizeX_m, spec.spacing_m);
    const int64_t ny = samplesAlong(spec.sizeY_m, spec.spacing_m);
    if (nx > MAX_SAMPLES_PER_SIDE || ny > MAX_SAMPLES_PER_SIDE) {
        std::ostringstream msg;
        msg << "a " << Limit::num(spec.sizeX_m) << " x " << Limit::num(spec.sizeY_m)
            << " m terrain at this spacing needs " << nx << " x " << ny << " samples; at most "
            << MAX_SAMPLES_PER_SIDE << " per side (raise spacing_m) (got "
            << Limit::num(spec.spacing_m) << ")";
        s.failKey("spacing_m", msg.str());
    }
    const double bytes = estimateTerrainBytes(nx, ny, t.meshStride);
    if (bytes > MAX_TERRAIN_BYTES) {
        std::ostringstream msg;
        msg << "a " << nx << " x " << ny << " sample terrain and its render mesh need about "
            << formatBytes(bytes) << "; at most " << formatBytes(MAX_TERRAIN_BYTES)
            << " (raise spacing_m or mesh_stride) (got " << Limit::num(spec.spacing_m) << ")";
        s.failKey("spacing_m", msg.str());
    }
    if (t.meshStride >= std::max(nx, ny))
        s.failKey("mesh_stride", "must be smaller than the grid (" + std::to_string(nx) + " x " +
                                     std::to_string(ny) + " samples) (got " +
                                     std::to_string(t.meshStride) + ")");
}

void readGrass(Context& ctx, Section s) {
    GrassSection& g = ctx.scene->grass;
    g.params.height_m =
        static_cast<float>(s.number("height_m", g.params.height_m, closed(1e-4, 100.0)));
    g.params.shells = static_cast<int>(s.integer("shells", g.params.shells, 1, MAX_SHELLS));
    g.params.stiffness =
        static_cast<float>(s.number("stiffness", g.params.stiffness, above(0.0, 100.0)));
    g.params.tile_m = static_cast<float>(s.number("tile_m", g.params.tile_m, closed(1e-3, 1e5)));
    const std::string texture = s.string("texture", "generated");
    g.params.aperiodic = s.boolean("aperiodic", g.params.aperiodic);
    g.params.lodPixels =
        static_cast<float>(s.number("lod_pixels", g.params.lodPixels, closed(0.0, 1000.0)));
    g.params.nearBlades =
        static_cast<int>(s.integer("near_blades", g.params.nearBlades, 0, render::MAX_NEAR_BLADES));
    const std::string densityMap = s.string("density_map", "");
    if (s.given("density_map")) {
        if (densityMap.empty()) s.failKey("density_map", "expected an image path (got \"\")");
        g.densityMapPath = resolveAgainst(ctx.folder, densityMap);
        requireInputFile(s, "density_map", g.densityMapPath, densityMap);
    }

    Section gen = s.table("generated");
    render::GrassTextureSpec& spec = g.generated;
    const int64_t size = gen.integer("size", spec.size, 16, 4096);
    if ((size & (size - 1)) != 0)
        gen.failKey("size",
                    "must be a power of two in 16..4096 (got " + std::to_string(size) + ")");
    spec.size = static_cast<int>(size);
    spec.seed = static_cast<uint32_t>(gen.integer("seed", spec.seed, 0, 4294967295LL));
    spec.density = static_cast<float>(gen.number("density", spec.density, above(0.0, 1.0)));
    spec.minHeight = static_cast<float>(gen.number("min_height", spec.minHeight, above(0.0, 1.0)));
    spec.groundColor = toVec3(gen.vec<3>("ground_color", fromVec3(spec.groundColor), closed(0, 1)));
    spec.baseColor = toVec3(gen.vec<3>("base_color", fromVec3(spec.baseColor), closed(0, 1)));
    spec.tipColor = toVec3(gen.vec<3>("tip_color", fromVec3(spec.tipColor), closed(0, 1)));
    spec.colorVariation =
        static_cast<float>(gen.number("color_variation", spec.colorVariation, closed(0.0, 1.0)));
    gen.finish();
    s.finish();

    if (texture.empty()) s.failKey("texture", "expected \"generated\" or an image path (got \"\")");
    if (texture != "generated") {
        g.texturePath = resolveAgainst(ctx.folder, texture);
        requireInputFile(s, "texture", g.texturePath, texture);
        if (gen.present())
            ctx.scene->notes.push_back(ctx.scene->where("grass.generated") +
                                       ": not used: grass.texture names an image (ignored)");
    }
}

void readSolver(Context& ctx, Section s) {
    SolverSection& v = ctx.scene->solver;
    v.domain.voxelSize_m = s.number("voxel_size_m", v.domain.voxelSize_m, closed(1e-3, 1e5));
    v.domain.top_m = s.optionalNumber("top_m", anyFinite());
    // Stretched layers (docs/solver.md): AirDomain checks the ranges against voxel_size_m.
    v.domain.firstCell_m = s.optionalNumber("first_cell_m", above(0.0, 1e5));
    v.domain.stretchRatio = s.number("stretch_ratio", v.domain.stretchRatio, closed(1.0, 1.2));
    v.domain.maxCell_m = s.optionalNumber("max_cell_m", above(0.0, 1e5));
    for (const char* key : {"stretch_ratio", "max_cell_m"})
        if (s.given(key) && !v.domain.firstCell_m)
            s.failKey(key, "applies to stretched layers only: give solver.first_cell_m too");
    v.domain.memoryLimit_bytes =
        s.number("memory_limit_mb", v.domain.memoryLimit_bytes / MIB, above(0.0, 1e9)) * MIB;
    v.weights.alphaH = s.number("alpha_h", v.weights.alphaH, above(0.0, 1e6));
    v.weights.alphaV = s.number("alpha_v", v.weights.alphaV, above(0.0, 1e6));
    const double ratio =
        (v.weights.alphaH / v.weights.alphaV) * (v.weights.alphaH / v.weights.alphaV);
    if (ratio < sim::SteadyWindSolver::MIN_VERTICAL_RATIO ||
        ratio > sim::SteadyWindSolver::MAX_VERTICAL_RATIO)
        s.failKey(s.given("alpha_v") ? "alpha_v" : "alpha_h",
                  "(alpha_h / alpha_v)^2 must be in [" +
                      Limit::num(sim::SteadyWindSolver::MIN_VERTICAL_RATIO) + ", " +
                      Limit::num(sim::SteadyWindSolver::MAX_VERTICAL_RATIO) +
                      "]: stronger anisotropy defeats the multigrid smoother (got " +
                      Limit::num(ratio) + ")");
    v.settings.relativeTolerance =
        s.number("tolerance", v.settings.relativeTolerance, above(0.0, 0.5));
    v.settings.maxIterations =
        static_cast<int>(s.integer("max_iterations", v.settings.maxIterations, 1, 100000));
    // The steady model (docs/validation.md compares them); the momentum keys apply to it only.
    const std::string model = s.string("model", sim::steadyModelName(v.model));
    try {
        v.model = sim::steadyModelFromName(model);
    } catch (const ParameterError& e) {
        s.failParameter(e);
    }
    v.domain.momentumModel = v.model == sim::SteadyModel::Momentum;
    v.momentum.displacementHeight_m =
        s.number("displacement_height_m", v.momentum.displacementHeight_m, closed(0.0, 1e4));
    v.momentum.maxIterations =
        static_cast<int>(s.integer("momentum_max_iterations", v.momentum.maxIterations, 1, 100000));
    v.momentum.coarseLevels =
        static_cast<int>(s.integer("momentum_coarse_levels", v.momentum.coarseLevels, 0, 8));
    const std::string advection =
        s.string("momentum_advection", sim::pseudoTimeAdvectionName(v.momentum.advection));
    try {
        v.momentum.advection = sim::pseudoTimeAdvectionFromName(advection);
    } catch (const ParameterError& e) {
        s.failParameter(e);
    }
    const std::string turbulence =
        s.string("turbulence", sim::turbulenceClosureName(v.momentum.turbulence));
    try {
        v.momentum.turbulence = sim::turbulenceClosureFromName(turbulence);
    } catch (const ParameterError& e) {
        s.failParameter(e);
    }
    s.finish();
}

/// [unsteady]: time stepping of wind.kind = "unsteady" (docs/unsteady.md).
void readUnsteady(Context& ctx, Section s) {
    UnsteadySection& u = ctx.scene->unsteady;
    sim::UnsteadySettings& v = u.settings;
    u.duration_s = s.number("duration_s", u.duration_s, above(0.0, 1e7));
    if (const auto dt_s = s.optionalNumber("dt_s", above(0.0, 1e6))) v.dt_s = *dt_s;
    v.cfl = s.number("cfl", v.cfl, above(0.0, 1000.0));
    if (s.given("dt_s") && s.given("cfl"))
        s.failKey("cfl", "give either dt_s (fixed step) or cfl (adaptive), not both");
    v.maxDt_s = s.number("max_dt_s", v.maxDt_s, above(0.0, 1e6));
    const std::string adv = s.string("advection", sim::advectionSchemeName(v.advection));
    try {
        v.advection = sim::advectionSchemeFromName(adv);
    } catch (const ParameterError& e) {
        s.failParameter(e);
    } catch (const std::invalid_argument& e) {
        s.failKey("advection", e.what());
    }
    const std::string precision = s.string("precision", sim::advectionPrecisionName(v.precision));
    try {
        v.precision = sim::advectionPrecisionFromName(precision);
    } catch (const ParameterError& e) {
        s.failParameter(e);
    }
    v.viscosity_m2ps = s.number("viscosity_m2ps", v.viscosity_m2ps, closed(0.0, 1e6));
    v.vorticityConfinement =
        s.number("vorticity_confinement", v.vorticityConfinement, closed(0.0, 100.0));
    v.openTop = s.boolean("open_top", v.openTop);
    // The momentum model's surface layer in each step (sim/MomentumTurbulence.h): the wind's
    // roughness at the wall, the mixing-length eddy viscosity, a log wind held in balance.
    v.surfaceLayer.enabled = s.boolean("surface_layer", v.surfaceLayer.enabled);
    const sim::AmbientWind& ambient = ctx.scene->wind.ambient;
    v.surfaceLayer.roughness_m = ambient.roughness_m;
    v.surfaceLayer.displacementHeight_m = ctx.scene->solver.momentum.displacementHeight_m;
    if (ambient.profile == sim::WindProfile::LogLaw) v.surfaceLayer.balanced = ambient;
    // The closure of [solver] turbulence; the two-equation closure reads its inflow and top from
    // the ambient log profile, so it needs one (the mixing length then runs without balance).
    if (v.surfaceLayer.balanced) v.surfaceLayer.closure = ctx.scene->solver.momentum.turbulence;
    v.projection.relativeTolerance =
        s.number("tolerance", v.projection.relativeTolerance, above(0.0, 0.5));
    v.projection.maxIterations =
        static_cast<int>(s.integer("max_iterations", v.projection.maxIterations, 1, 100000));
    u.liveTolerance = s.number("live_tolerance", u.liveTolerance, above(0.0, 0.5));
    u.liveIterations = static_cast<int>(s.integer("live_iterations", u.liveIterations, 1, 1000));
    u.outputEvery_s = s.number("output_every_s", u.outputEvery_s, above(0.0, 1e7));
    u.maxFiles = s.integer("max_files", u.maxFiles, 1, 100000000);
    u.maxSteps = s.integer("max_steps", u.maxSteps, 1, 1000000000000);
    u.maxOutputBytes =
        s.number("max_output_gib", u.maxOutputBytes / (MIB * 1024.0), closed(1e-3, 1e9)) * MIB *
        1024.0;
    s.finish();
    if (ctx.scene->wind.kind == WindKind::Unsteady) {
        // Bounds on work (docs/reliability.md): the files and steps this run plans, refused
        // beyond the limits unless the scene raises them.
        const double files = plannedSequenceFiles(u);
        if (files > static_cast<double>(u.maxFiles))
            s.failKey("output_every_s", "duration_s / output_every_s plans " + Limit::num(files) +
                                            " .vdb files; at most " + std::to_string(u.maxFiles) +
                                            " unless unsteady.max_files raises it");
        const double steps = plannedUnsteadySteps(*ctx.scene);
        if (steps > static_cast<double>(u.maxSteps))
            s.failKey(s.given("dt_s") ? "dt_s" : "cfl",
                      "plans at least " + Limit::num(steps) + " time steps over duration_s = " +
                          Limit::num(u.duration_s) + " s; at most " + std::to_string(u.maxSteps) +
                          " unless unsteady.max_steps raises it");
    }
    if (s.present() && ctx.scene->wind.kind != WindKind::Unsteady)
        ctx.scene->notes.push_back(ctx.scene->where("unsteady") +
                                   ": used by wind.kind = \"unsteady\" only (ignored)");
}

}  // namespace

std::optional<BudgetProblem> outputBudgetProblem(const OutputSection& o) {
    const double pixels = static_cast<double>(o.width) * o.height;
    if (pixels * FRAME_BYTES_PER_PIXEL > MAX_FRAME_BYTES)
        return BudgetProblem{"width", "a " + std::to_string(o.width) + " x " +
                                          std::to_string(o.height) + " frame needs about " +
                                          formatBytes(pixels * FRAME_BYTES_PER_PIXEL) +
                                          " of buffers; at most " + formatBytes(MAX_FRAME_BYTES)};
    const double outBytes = pixels * o.frames * PNG_BYTES_PER_PIXEL;
    if (outBytes > MAX_OUTPUT_BYTES)
        return BudgetProblem{
            "frames", std::to_string(o.frames) + " frames of " + std::to_string(o.width) + " x " +
                          std::to_string(o.height) + " would write about " + formatBytes(outBytes) +
                          " of PNG; at most " + formatBytes(MAX_OUTPUT_BYTES)};
    return std::nullopt;
}

double plannedSequenceFiles(const UnsteadySection& u) {
    return std::ceil(u.duration_s / u.outputEvery_s - 1e-9) + 1.0;
}

double plannedUnsteadySteps(const Scene& scene) {
    const UnsteadySection& u = scene.unsteady;
    const sim::UnsteadySettings& v = u.settings;
    double dt_s = v.dt_s;
    if (!(dt_s > 0.0)) {
        // Adaptive: dt = cfl h / |u|max, at most max_dt_s. The field's peak is at least the
        // ambient speed, so this dt is an upper bound and the count a lower one.
        const double speed_mps = std::max(scene.wind.ambient.speed_mps, 1e-300);
        dt_s = std::min(v.maxDt_s, v.cfl * scene.solver.domain.voxelSize_m / speed_mps);
    }
    return std::ceil(u.duration_s / dt_s);
}

double plannedSequenceBytes(const UnsteadySection& u, double fileBytes) {
    return plannedSequenceFiles(u) * fileBytes;
}

std::optional<std::string> sequenceBytesProblem(const UnsteadySection& u, double fileBytes) {
    const double bytes = plannedSequenceBytes(u, fileBytes);
    if (bytes <= u.maxOutputBytes) return std::nullopt;
    return "plans " + Limit::num(plannedSequenceFiles(u)) + " .vdb files of up to " +
           formatBytes(fileBytes) + " each, about " + formatBytes(bytes) + " in all; at most " +
           formatBytes(u.maxOutputBytes) +
           " unless unsteady.max_output_gib raises it (or raise output_every_s)";
}

double estimatePngBytes(const OutputSection& o) {
    return static_cast<double>(o.width) * o.height * o.frames * PNG_BYTES_PER_PIXEL;
}

int64_t samplesAlong(double size_m, double spacing_m) {
    const double n = std::floor(size_m / spacing_m + 0.5) + 1.0;
    if (!(n < 1e15)) return std::numeric_limits<int64_t>::max() / 4;
    return std::max<int64_t>(2, static_cast<int64_t>(n));
}

double estimateTerrainBytes(int64_t nx, int64_t ny, int stride) {
    // Heightfield: one float per sample. Mesh vertex: position, normal (2 x 12 B), uv (8 B); wind
    // direction and group (16 B) in the source and in GrassWind; GL copies of all of it; and two
    // triangles (24 B of indices) per quad.
    constexpr double HEIGHT_BYTES = 4.0, VERTEX_BYTES = 2 * (32.0 + 2 * 16.0) + 24.0;
    const double mx = std::ceil(static_cast<double>(nx - 1) / stride) + 1;
    const double my = std::ceil(static_cast<double>(ny - 1) / stride) + 1;
    return HEIGHT_BYTES * static_cast<double>(nx) * static_cast<double>(ny) +
           VERTEX_BYTES * mx * my;
}

std::string formatBytes(double bytes) {
    const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    int u = 0;
    while (bytes >= 1024.0 && u < 6) bytes /= 1024.0, ++u;
    char buf[64];
    std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.1f %s", bytes, units[u]);
    return buf;
}

namespace {

/// Parses `text`; with `defaults` set, also records every key's default there (Context).
Scene parseScene(const std::string& text, const std::string& pathForMessages,
                 std::map<std::string, std::string>* defaults) {
    Scene scene;
    scene.path = pathForMessages;
    scene.name = fs::path(pathForMessages).stem().string();
    if (scene.name.empty()) scene.name = "scene";

    toml::table root;
    try {
        root = toml::parse(text, pathForMessages);
    } catch (const toml::parse_error& e) {
        const auto& begin = e.source().begin;
        std::string reason(e.description());
        std::replace(reason.begin(), reason.end(), '\n', ' ');
        throw SceneError(pathForMessages + ":" + std::to_string(begin.line) + ":" +
                         std::to_string(begin.column) + ": " + reason);
    }

    Context ctx{pathForMessages, fs::path(pathForMessages).parent_path(), &scene, defaults};
    Section top(ctx, &root, "", 1);
    scene.description = top.string("description", scene.description);
    // Terrain first: later sections' defaults and checks may depend on it.
    readTerrain(ctx, top.table("terrain"));
    readGrass(ctx, top.table("grass"));
    readWind(ctx, top.table("wind"));
    readSolver(ctx, top.table("solver"));
    readUnsteady(ctx, top.table("unsteady"));
    readLighting(ctx, top.table("lighting"));
    readCamera(ctx, top.table("camera"));
    readOutput(ctx, top.table("output"));
    readOverlay(ctx, top.table("overlay"));
    top.finish();
    return scene;
}

}  // namespace

Scene parseSceneString(const std::string& text, const std::string& pathForMessages) {
    return parseScene(text, pathForMessages, nullptr);
}

std::map<std::string, std::string> sceneKeyDefaults() {
    // The smallest scene that reaches every reader: entries of the arrays of tables are read one
    // by one, so it names one gust, one whirlwind and one light, with only their required keys.
    const std::string scene = R"(
[[wind.gusts]]
[[wind.whirlwinds]]
position_m = [10, 10]
peak_speed_mps = 3
[[lighting.light]]
position_m = [0, 0, 10]
)";
    std::map<std::string, std::string> indexed, out;
    (void)parseScene(scene, "defaults.toml", &indexed);
    for (const auto& [key, text] : indexed) {
        std::string plain;  // "wind.gusts[0].start_s" -> "wind.gusts.start_s"
        for (size_t i = 0; i < key.size(); ++i) {
            if (key[i] != '[') {
                plain += key[i];
                continue;
            }
            while (i < key.size() && key[i] != ']') ++i;
        }
        out[plain] = text;
    }
    return out;
}

Scene parseSceneFile(const std::string& path) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) throw SceneError(path + ": cannot read the scene: no such file");
    if (fs::is_directory(st)) throw SceneError(path + ": is a folder, not a scene file");
    const uintmax_t size = fs::file_size(path, ec);
    if (!ec && size > MAX_SCENE_FILE_BYTES)
        throw SceneError(path + ": " + formatBytes(static_cast<double>(size)) +
                         " is too large for a scene file (at most " +
                         formatBytes(MAX_SCENE_FILE_BYTES) + ")");
    // Read through a bounded buffer whatever the file is: a device (/dev/zero) or a pipe has no
    // size to check first, and must not grow without bound.
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SceneError(path + ": cannot read the scene: " + std::strerror(errno));
    std::string text;
    char chunk[65536];
    while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
        text.append(chunk, static_cast<size_t>(in.gcount()));
        if (text.size() > MAX_SCENE_FILE_BYTES)
            throw SceneError(path + ": more than " + formatBytes(MAX_SCENE_FILE_BYTES) +
                             " of input: too large for a scene file (stopped reading there)");
    }
    if (in.bad()) throw SceneError(path + ": cannot read the scene: read error");
    return parseSceneString(text, path);
}

}  // namespace gale::app
