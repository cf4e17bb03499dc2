/// \file CommandsCheck.cpp
/// `gale check`: validate a scene and say what a run would build and what it leaves out.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>

#include "app/Cli.h"
#include "app/Commands.h"
#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/io/OutputFolder.h"
#include "app/io/OutputLock.h"
#include "app/scene/SceneBuilder.h"
#include "app/scene/SceneParser.h"
#include "base/Numbers.h"
#include "coupling/PointSourceWind.h"
#include "render/CameraMath.h"
#include "render/GrassTexture.h"
#include "render/NearBlades.h"

namespace gale::app {
namespace {

std::string vec3(const glm::vec3& v) {
    return "(" + formatG(v.x, 3) + ", " + formatG(v.y, 3) + ", " + formatG(v.z, 3) + ")";
}

/// "from 210 deg = towards 30 deg, counter-clockwise from +x 60 deg": the meteorological and the
/// mathematical direction of one wind, side by side.
std::string directionText(double direction_deg) {
    sim::AmbientWind a;
    a.direction_deg = direction_deg;
    return "from " + formatG(a.from_deg(), 3) + " deg = towards " +
           formatG(a.towardsBearing_deg(), 3) + " deg, counter-clockwise from +x " +
           formatG(direction_deg, 3) + " deg";
}

void line(const char* label, const std::string& text) {
    std::printf("%-9s %s\n", label, text.c_str());
}

/// Grid convergence beyond which check says how far the DEM's grid north is from true north.
constexpr double CONVERGENCE_NOTE_DEG = 0.5;

/// For a DEM scene: which north from_deg is measured from (the CRS's grid north, +y) and, when it
/// is more than CONVERGENCE_NOTE_DEG off true north at the terrain's centre, by how much.
void northNote(const BuiltScene& built) {
    const Georeference& geo = built.georef;
    if (!geo.georeferenced()) return;
    const sim::Heightfield& f = built.heightfield;
    const double cx = geo.demX_m(f.originX_m + 0.5 * f.sizeX_m());
    const double cy = geo.demY_m(f.originY_m + 0.5 * f.sizeY_m());
    const std::optional<double> g = gridNorthBearing_deg(geo, cx, cy);
    std::string text = "from_deg is measured clockwise from the grid north (+y) of " + geo.crsName;
    if (!g)
        text += " (its angle to true north could not be computed)";
    else if (std::abs(*g) > CONVERGENCE_NOTE_DEG)
        text += "; at the terrain's centre grid north is " + formatFixed(std::abs(*g), 2) +
                " deg " + (*g > 0 ? "east" : "west") +
                " of true north: a wind from the true bearing T is from_deg = T " +
                (*g > 0 ? "- " : "+ ") + formatFixed(std::abs(*g), 2) + " here";
    else
        text += " (within " + formatG(CONVERGENCE_NOTE_DEG, 2) +
                " deg of true north at the terrain's centre)";
    line("", text);
}

}  // namespace

int runCheck(const SceneRunOptions& options) {
    const Scene scene = loadScene(options);
    const OutputFolderStatus folder =
        checkOutputFolder(scene.output.folder, outputFolderSource(scene, options),
                          scene.output.prefix, scene.output.frames);
    BuildOptions buildOptions;
    buildOptions.solveWind = false;  // check validates and estimates; it does not solve
    const BuiltScene built = buildScene(scene, buildOptions);
    // Bounds on work the domain decides (the parser has refused too many files and steps).
    if (scene.wind.kind == WindKind::Unsteady)
        if (auto problem = sequenceBytesProblem(scene.unsteady, built.domainVdbFile_bytes))
            throw SceneError(scene.where("unsteady.output_every_s") + ": " + *problem);
    const sim::Heightfield& field = built.heightfield;
    const render::TerrainMesh& mesh = built.mesh;
    const GrassSection& grass = scene.grass;
    const OutputSection& out = scene.output;

    line("scene", scene.path + (scene.description.empty() ? "" : ": " + scene.description));

    std::ostringstream t;
    const Georeference& geo = built.georef;
    if (scene.terrain.dem)
        t << "dem from " << scene.terrain.demPath;
    else
        t << sim::terrainKindName(scene.terrain.spec.kind);
    if (scene.terrain.spec.kind == sim::TerrainKind::Heightmap && !scene.terrain.dem)
        t << " from " << scene.terrain.imagePath;
    t << ", " << field.nx << " x " << field.ny << " samples at " << formatG(field.spacing_m, 3)
      << " m (" << formatG(field.sizeX_m(), 3) << " x " << formatG(field.sizeY_m(), 3)
      << " m), heights " << formatFixed(field.minHeight_m()) << " .. "
      << formatFixed(field.maxHeight_m()) << " m";
    line("terrain", t.str());
    if (geo.georeferenced()) {
        line("", "coordinate system " + geo.crsName + "; covers x " + formatFixed(geo.demX_m(0.0)) +
                     " .. " + formatFixed(geo.demX_m(field.sizeX_m())) + ", y " +
                     formatFixed(geo.demY_m(0.0)) + " .. " +
                     formatFixed(geo.demY_m(field.sizeY_m())) +
                     " (pixel centres); inside gale local (0, 0) = (" + formatFixed(geo.originX_m) +
                     ", " + formatFixed(geo.originY_m) + ")");
    }

    const long long quads = static_cast<long long>(mesh.nx - 1) * (mesh.ny - 1);
    line("mesh", std::to_string(mesh.nx) + " x " + std::to_string(mesh.ny) + " = " +
                     std::to_string(mesh.wsPosition_m.size()) + " vertices, " +
                     std::to_string(2 * quads) + " triangles (every " +
                     std::to_string(scene.terrain.meshStride) +
                     (scene.terrain.meshStride == 1 ? "st" : "th") + " sample)");

    line("grass", formatG(grass.params.height_m, 3) + " m tall, " +
                      std::to_string(grass.params.shells) + " shells (" +
                      std::to_string(grass.params.shells + 1) +
                      " layers with the ground), stiffness " + formatG(grass.params.stiffness, 3) +
                      ", texture repeats every " + formatG(grass.params.tile_m, 3) + " m");

    const render::Image& level0 = built.texture.levels.front();
    std::string tex = grass.texturePath.empty()
                          ? "generated (seed " + std::to_string(grass.generated.seed) +
                                ", density " + formatG(grass.generated.density, 3) + ")"
                          : grass.texturePath;
    line("texture",
         tex + ", " + std::to_string(level0.width) + " x " + std::to_string(level0.height) + ", " +
             std::to_string(built.texture.levels.size()) + " MIP levels (blade-keeping, down to " +
             std::to_string(built.texture.levels.back().width) + " x " +
             std::to_string(built.texture.levels.back().height) + ")");

    const bool solved = scene.wind.kind == WindKind::Solved;
    const bool unsteady = scene.wind.kind == WindKind::Unsteady;
    const sim::UnsteadySettings& us = scene.unsteady.settings;
    if (unsteady) {
        const sim::AmbientWind& a = scene.wind.ambient;
        line("wind", "unsteady field (docs/design.md 4.2): " + formatG(a.speed_mps, 3) +
                         " m/s at " + formatG(a.referenceHeight_m, 3) + " m " +
                         directionText(a.direction_deg) + ", " + sim::windProfileName(a.profile) +
                         " profile");
        northNote(built);
        for (const std::string& l : built.fieldPlan) line("", l);
        line("", "gale solve plans " + formatG(plannedSequenceFiles(scene.unsteady), 12) +
                     " .vdb files (limit " + std::to_string(scene.unsteady.maxFiles) +
                     ", unsteady.max_files) and at least " +
                     formatG(plannedUnsteadySteps(scene), 12) + " time steps (limit " +
                     std::to_string(scene.unsteady.maxSteps) + ", unsteady.max_steps), about " +
                     formatBytes(plannedSequenceBytes(scene.unsteady, built.domainVdbFile_bytes)) +
                     " of .vdb at most (limit " + formatBytes(scene.unsteady.maxOutputBytes) +
                     ", unsteady.max_output_gib)");
        line("",
             "forces: " +
                 std::string(us.viscosity_m2ps > 0
                                 ? "implicit viscosity " + formatG(us.viscosity_m2ps, 3) + " m^2/s"
                                 : "no viscosity") +
                 (us.vorticityConfinement > 0
                      ? ", vorticity confinement " + formatG(us.vorticityConfinement, 3)
                      : ", no vorticity confinement"));
        for (size_t i = 0; i < us.gusts.size(); ++i) {
            const sim::GustEvent& g = us.gusts[i];
            line("", "gust " + std::to_string(i) + ": " + sim::gustEnvelopeName(g.envelope) +
                         " envelope, " + formatG(g.peak_mps, 3) + " m/s towards " +
                         formatG(g.direction_deg, 3) + " deg, from t = " + formatG(g.start_s, 3) +
                         " s for " + formatG(g.duration_s, 3) + " s, " +
                         (g.entry == sim::GustEntry::Inflow
                              ? std::string("entering through the inflow boundary")
                              : "as a moving forcing region of " + formatG(g.regionRadius_m, 3) +
                                    " m radius"));
        }
        for (size_t i = 0; i < us.whirlwinds.size(); ++i) {
            const sim::Whirlwind& v = us.whirlwinds[i];
            line("",
                 "whirlwind " + std::to_string(i) + ": " + sim::vortexProfileName(v.profile) +
                     " at (" + formatG(v.wsPosition_m[0], 3) + ", " +
                     formatG(v.wsPosition_m[1], 3) + ") m, core " + formatG(v.coreRadius_m, 3) +
                     " m, circulation " + formatG(v.circulation(), 3) + " m^2/s" +
                     (v.updraft_mps > 0 ? ", updraft " + formatG(v.updraft_mps, 3) + " m/s" : "") +
                     (v.forced
                          ? ", forced" + (v.lifetime_s ? " for " + formatG(*v.lifetime_s, 3) + " s"
                                                       : std::string())
                          : ", free"));
        }
        line("", std::string("blade response ") +
                     coupling::bladeResponseName(scene.wind.response.response) + ", " +
                     coupling::groupingName(scene.wind.response.grouping) + " groups (" +
                     std::to_string(scene.wind.response.groups) +
                     "), the field sampled after every step");
    } else if (solved) {
        const sim::AmbientWind& a = scene.wind.ambient;
        const coupling::FieldWindSpec& r = scene.wind.response;
        line(
            "wind",
            std::string("solved steady field (") + sim::steadyModelName(scene.solver.model) +
                "): " + formatG(a.speed_mps, 3) + " m/s at " + formatG(a.referenceHeight_m, 3) +
                " m " + directionText(a.direction_deg) + ", " + sim::windProfileName(a.profile) +
                " profile" +
                (a.profile == sim::WindProfile::LogLaw ? " (z0 " + formatG(a.roughness_m, 3) + " m)"
                                                       : ""));
        northNote(built);
        for (const std::string& l : built.fieldPlan) line("", l);
        line("", std::string("blade response ") + coupling::bladeResponseName(r.response) +
                     ", bend speed " + formatG(r.bendSpeed_mps, 3) + " m/s" +
                     (scene.wind.gusts
                          ? "; travelling gusts, " + std::to_string(scene.wind.arrivalBands) +
                                " arrival bands x " + std::to_string(scene.wind.levels) + " levels"
                          : "; " + std::string(coupling::groupingName(r.grouping)) + " groups (" +
                                std::to_string(r.groups) + ")"));
        if (scene.wind.gusts) line("", "gust: " + scene.wind.curveDescription);
    } else {
        const coupling::PointSourceSpec& ps = scene.wind.pointSource;
        line("wind", "point source at " + vec3(built.wsWindSource_m) + " m" +
                         (scene.wind.autoSource ? " (default: west edge)" : "") +
                         (ps.blowAway ? ", blowing away from it" : ", blowing towards it") + "; " +
                         std::to_string(built.wind->groupCount()) + " groups (rings), " +
                         formatG(ps.stepDelay_s, 3) + " s apart");
        line("", "gust: " + scene.wind.curveDescription);
    }

    const render::Lighting& l = scene.lighting;
    std::string lights = std::to_string(l.lights.size()) + " point light" +
                         (l.lights.size() == 1 ? "" : "s") + " + ambient " + vec3(l.ambient);
    line("lights", lights);
    for (size_t i = 0; i < l.lights.size(); ++i)
        line("", "light " + std::to_string(i) + " at " + vec3(l.lights[i].wsPosition_m) +
                     " m, colour " + vec3(l.lights[i].color) + ", attenuation " +
                     vec3(l.lights[i].attenuation));

    const render::Camera& c = built.camera;
    line("camera", vec3(c.wsPosition_m) + " m -> " + vec3(c.wsTarget_m) + " m" +
                       (scene.autoCameraPosition ? " (default 3/4 view)" : "") + ", fov " +
                       formatG(c.fovY_deg, 3) + " deg, near " + formatG(c.near_m, 3) + " m, far " +
                       formatG(c.far_m, 3) + " m");

    // The near level (docs/render.md, "Near blades"): what the texture says a blade is and how
    // far from the eye it is drawn as geometry at the output's size.
    if (grass.params.nearBlades == 0) {
        line("blades", "off (grass.near_blades = 0: the shells alone)");
    } else {
        const render::detail::BladeStatistics blades =
            render::detail::bladeStatistics(level0, grass.params.tile_m);
        const float focal_px = render::focalLength_px(c, scene.output.height);
        line("blades",
             blades.bladesPerM2 > 0.0f
                 ? "up to " + std::to_string(grass.params.nearBlades) + " a frame, " +
                       formatG(blades.bladesPerM2, 4) + " per m^2 of " +
                       formatG(100.0 * blades.width_m, 3) + " cm (the texture's), within " +
                       formatG(blades.width_m * focal_px / render::detail::MIN_BLADE_PX, 3) +
                       " m of the eye at most (where a blade is " +
                       formatG(render::detail::MIN_BLADE_PX, 2) + " px wide at " +
                       std::to_string(scene.output.height) + " px)"
                 : "none: the texture has no blades");
    }

    const coupling::OverlaySpec& ov = scene.overlay;
    if (ov.any()) {
        std::string views;
        auto add = [&](bool on, const std::string& what) {
            if (on) views += (views.empty() ? "" : ", ") + what;
        };
        add(ov.arrows, "arrows every " +
                           (ov.arrowSpacing_m ? formatG(*ov.arrowSpacing_m, 3) + " m"
                                              : std::string("1/16 of the terrain")) +
                           " at " +
                           (ov.arrowHeight_m ? formatG(*ov.arrowHeight_m, 3) + " m"
                                             : std::string("1.25 x grass height")));
        add(ov.slice, "terrain-following slice " + formatG(ov.sliceHeight_m, 3) + " m up");
        add(ov.streamlines,
            std::to_string(ov.streamlineCount) + " streamlines from the upstream edge");
        add(ov.vortexCores, "vortex cores (Q > " +
                                (ov.vortexQ_per_s2 ? formatG(*ov.vortexQ_per_s2, 3) + " 1/s^2"
                                                   : std::string("auto")) +
                                ")");
        line("overlay", views + "; colour map viridis up to " +
                            (ov.speedMax_mps ? formatG(*ov.speedMax_mps, 3) + " m/s"
                                             : std::string("the largest speed")) +
                            (ov.legend ? ", with legend" : ", no legend"));
        if (!solved && (ov.slice || ov.streamlines || ov.vortexCores))
            line("",
                 "note: the point source has no velocity field: only arrows (direction x "
                 "intensity) are drawn");
    } else {
        line("overlay",
             "none (an [overlay] section draws arrows, a slice, streamlines, vortex cores)");
    }

    const double endTime_s = out.startTime_s + (out.frames - 1) / out.fps;
    line("output", std::to_string(out.frames) + " frames of " + std::to_string(out.width) + " x " +
                       std::to_string(out.height) + " at " + formatG(out.fps, 3) + " fps (t = " +
                       formatG(out.startTime_s, 3) + " .. " + formatG(endTime_s, 4) + " s)");
    auto named = [&](int k) {  // output.format picks the extension
        return std::filesystem::path(framePath(out.folder, out.prefix, k))
            .replace_extension("." + out.format)
            .string();
    };
    std::string where = named(0) + " .. " + named(out.frames - 1).substr(out.folder.size() + 1);
    where += folder.exists ? " (folder exists, " + std::to_string(folder.existingFiles) + " files)"
                           : " (folder will be created)";
    line("", where);
    std::string size = "about " + formatBytes(estimatePngBytes(out)) + " of PNG";
    if (folder.freeBytes >= 0) size += ", " + formatBytes(folder.freeBytes) + " free";
    line("", size);
    if (!folder.staleFrames.empty())
        line("", "note: " + std::to_string(folder.staleFrames.size()) +
                     " older frames beyond this run's last (e.g. " + folder.staleFrames.front() +
                     ") stay in the folder");
    const std::vector<std::string> stale = staleTemporaries(out.folder);
    if (!stale.empty())
        line("", "note: " + std::to_string(stale.size()) +
                     " temporary files left by a gale run that was stopped (e.g. " +
                     std::filesystem::path(stale.front()).filename().string() +
                     "); the next render or solve into this folder removes them");
    const std::string lockPath = OutputLock::pathFor(out.folder);
    if (std::filesystem::exists(lockPath))
        line("", "note: " + lockPath +
                     " exists: another gale run writes here now (or was "
                     "killed; the next run takes a dead run's lock over)");

    if (unsteady) {
        std::string leftOut = us.whirlwinds.empty() && us.vorticityConfinement == 0.0
                                  ? "no vortex code (no whirlwinds, no confinement)"
                                  : "";
        auto add = [&](bool leave, const std::string& what) {
            if (leave) leftOut += (leftOut.empty() ? "" : "; ") + what;
        };
        add(us.gusts.empty(), "no gusts");
        add(us.viscosity_m2ps == 0.0, "no viscosity step");
        add(us.advection == sim::AdvectionScheme::SemiLagrangian, "no MacCormack/BFECC correction");
        line("left out",
             leftOut.empty() ? "nothing: every part of the unsteady solver runs" : leftOut);
    } else if (solved) {
        line("left out", "no unsteady solver: a steady field" +
                             std::string(scene.wind.gusts ? " with kinematic travelling gusts"
                                                          : ", held still") +
                             "; no vortex code");
    } else {
        line("left out",
             "no wind solver: point-source wind (Bakay et al. 2002), no velocity field");
    }
    line("", "no window: headless (OSMesa)");
    if (scene.defaultSun)
        line("", "no [[lighting.light]]: a default sun (from the south-west, 40 deg up)" +
                     std::string(l.ambient == glm::vec3(DEFAULT_SKY_AMBIENT_RGB[0],
                                                        DEFAULT_SKY_AMBIENT_RGB[1],
                                                        DEFAULT_SKY_AMBIENT_RGB[2])
                                     ? " and a sky ambient"
                                     : ""));
    for (const std::string& note : scene.notes) line("note", note);
    for (const std::string& warning : built.warnings) line("warning", warning);
    std::printf("ok: %s is valid (CPU side built in %.0f ms)\n", scene.path.c_str(),
                built.build_ms);
    return EXIT_OK;
}

void addCheckVerb(CLI::App& app, VerbTable& verbs) {
    auto options = std::make_shared<SceneRunOptions>();
    CLI::App* verb = app.add_subcommand(
        "check", "Validate a scene and print what a render would build and what it leaves out");
    addSceneOptions(verb, *options);
    verb->footer(EXIT_CODES_FOOTER);
    verbs.add(verb, [options] { return runCheck(*options); });
}

}  // namespace gale::app
