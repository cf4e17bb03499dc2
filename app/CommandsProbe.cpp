/// \file CommandsProbe.cpp
/// `gale probe SCENE POINTS.csv [-o OUT.csv] [--vdb FILE.vdb ...] [--reference NAME]`: the wind
/// at points (met masts, turbines) as a CSV table (docs/cli.md, "gale probe").
///
/// Points are in the scene's coordinates: the DEM's coordinate system for a DEM terrain (the
/// local offset of Dem.h is removed inside and added back in the output), the terrain's own
/// metres otherwise. Each point gives x, y and either a height above the ground or an absolute z.
/// The field comes from the scene's one composition (app/scene/SceneField.h: the same model,
/// keys and solve as gale solve; unsteady scenes stepped to every output time), or from .vdb
/// files that gale solve wrote for the same scene (their provenance checked). Every point is read
/// as the grass reads the field (coupling::GrassSampler with the scene's near-ground treatment).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/Cli.h"
#include "app/Commands.h"
#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/io/Interrupt.h"
#include "app/io/OutputFolder.h"
#include "app/scene/ProbePoints.h"
#include "app/scene/SceneBuilder.h"
#include "app/scene/SceneField.h"
#include "base/Numbers.h"
#include "coupling/FieldSampling.h"
#include "coupling/Turbulence.h"
#include "sim/AirDomain.h"
#include "sim/UnsteadyWind.h"
#include "sim/VdbIO.h"

namespace gale::app {
namespace {

/// Below this horizontal speed (m/s) the from-direction is undefined and left empty.
constexpr double CALM_MPS = 1e-9;

struct ProbeOptions {
    std::string scenePath;
    std::string pointsPath;
    std::string outPath;                ///< empty: the table goes to stdout
    std::vector<std::string> vdbPaths;  ///< empty: solve the scene
    std::string reference;              ///< a point's name; empty: the ambient profile
};

struct ProbePoint {
    ProbeInput in;  ///< as given (name, line, DEM coordinates, height, kept columns)
    double localX = 0, localY = 0;
    double z = 0;                         ///< world (local frame) z, metres
    double agl = 0;                       ///< height above the ground, metres
    bool zKnown = true, aglKnown = true;  ///< false for a point outside the terrain (no ground)
    /// Why the point has no values (outside the terrain, not above the ground, above the top);
    /// empty: it is sampled.
    std::string reason;
};

std::string fmt(double v, const char* f = "%.4f") {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

/// Places the table's points over the terrain. A point the field cannot answer (outside the
/// terrain, not above the ground, above the domain's top) is kept with its reason and a warning
/// line; throws InputError naming the first when no point can be answered.
std::vector<ProbePoint> placePoints(const ProbeTable& table, const sim::Heightfield& field,
                                    const Georeference& geo, double top_m) {
    std::vector<ProbePoint> points;
    for (const ProbeInput& in : table.points) {
        ProbePoint p;
        p.in = in;
        p.localX = in.x_m - geo.originX_m;
        p.localY = in.y_m - geo.originY_m;
        const double x0 = field.originX_m, y0 = field.originY_m;
        if (p.localX < x0 || p.localX > x0 + field.sizeX_m() || p.localY < y0 ||
            p.localY > y0 + field.sizeY_m()) {
            char box[256];
            std::snprintf(
                box, sizeof box,
                "point (%.3f, %.3f) is outside the terrain (x %.3f .. %.3f, y %.3f .. %.3f)",
                in.x_m, in.y_m, geo.demX_m(x0), geo.demX_m(x0 + field.sizeX_m()), geo.demY_m(y0),
                geo.demY_m(y0 + field.sizeY_m()));
            p.reason = box;
            (table.heightAboveGround ? p.agl : p.z) = in.height_m;
            p.zKnown = !table.heightAboveGround, p.aglKnown = table.heightAboveGround;
            points.push_back(p);
            continue;
        }
        const double ground = field.sample(p.localX, p.localY);
        p.agl = table.heightAboveGround ? in.height_m : in.height_m - ground;
        p.z = table.heightAboveGround ? ground + in.height_m : in.height_m;
        if (!(p.agl > 0.0))
            p.reason = "point is not above the ground (ground at " + fmt(ground, "%.3f") +
                       " m, point at " + fmt(p.z, "%.3f") + " m)";
        else if (!(p.z < top_m))
            p.reason = "point is above the air domain's top (" + fmt(top_m, "%.3f") +
                       " m; raise solver.top_m)";
        points.push_back(p);
    }
    const auto answered = std::count_if(points.begin(), points.end(),
                                        [](const ProbePoint& p) { return p.reason.empty(); });
    if (answered == 0)
        throw InputError(
            table.where(points.front().in) + ": " + points.front().reason +
            (points.size() > 1 ? " (and so is every other point: nothing to probe)" : ""));
    for (const ProbePoint& p : points)
        if (!p.reason.empty())
            std::fprintf(stderr, "probe: warning: %s: %s: %s; its row has no values\n",
                         table.where(p.in).c_str(), p.in.name.c_str(), p.reason.c_str());
    return points;
}

/// Reads the probe points as the grass reads the field: one GrassSampler over the answered
/// points' world positions, planned once per field geometry.
class ProbeSampler {
  public:
    ProbeSampler(const std::vector<ProbePoint>& points, const coupling::NearGround& nearGround)
        : mSampler(positions(points), nearGround) {
        for (size_t i = 0; i < points.size(); ++i)
            if (points[i].reason.empty()) mIndex.push_back(i);
    }
    /// Velocity (m/s) and read kind per point, in the points' order (unanswered points: absent).
    void sample(const sim::WindField& field, std::vector<std::optional<glm::vec3>>& velocity,
                std::vector<std::string>& read) {
        mSampler.sample(field, mOut);
        velocity.assign(mCount, std::nullopt);
        read.assign(mCount, "");
        for (size_t s = 0; s < mIndex.size(); ++s) {
            velocity[mIndex[s]] = mOut[s];
            read[mIndex[s]] = coupling::nearGroundReadKindName(mSampler.readKind(s));
        }
    }

  private:
    std::vector<glm::dvec3> positions(const std::vector<ProbePoint>& points) {
        mCount = points.size();
        std::vector<glm::dvec3> out;
        for (const ProbePoint& p : points)
            if (p.reason.empty()) out.emplace_back(p.localX, p.localY, p.z);
        return out;
    }
    size_t mCount = 0;
    std::vector<size_t> mIndex;  // sampler index -> point index
    coupling::GrassSampler mSampler;
    std::vector<glm::vec3> mOut;
};

/// The output's columns: [t_s,] name, x, y, z_m, height_agl_m, u_mps, v_mps, w_mps, speed_mps,
/// from_deg, speedup, tke_m2ps2, turbulence_intensity, gust_mps, read, reason, then the input's
/// kept columns.
ProbeOutput outputTable(bool series, const ProbeTable& table) {
    ProbeOutput out;
    if (series) out.columns.push_back("t_s");
    for (const char* c :
         {"name", "x", "y", "z_m", "height_agl_m", "u_mps", "v_mps", "w_mps", "speed_mps",
          "from_deg", "speedup", "tke_m2ps2", "turbulence_intensity", "gust_mps", "read", "reason"})
        out.columns.push_back(c);
    out.xColumn = series ? 2 : 1, out.yColumn = out.xColumn + 1;
    for (const std::string& c : table.extraColumns) out.columns.push_back(c);
    return out;
}

/// Says once on stderr that a field carries no turbulence, so its turbulence columns are empty.
void noteNoTurbulence(const std::string& why) {
    static bool said = false;
    if (said) return;
    said = true;
    std::fprintf(stderr,
                 "probe: note: %s: the columns tke_m2ps2, turbulence_intensity and gust_mps are "
                 "empty\n",
                 why.c_str());
}

/// One row per point for the field at time t_s (NaN: steady, no time column). tke_m2ps2: the
/// field's turbulent kinetic energy on its cells (empty: none, the turbulence columns empty).
void appendRows(ProbeOutput& out, const std::vector<ProbePoint>& points, ProbeSampler& sampler,
                const sim::WindField& field, const std::vector<double>& tke_m2ps2,
                const sim::AmbientWind& ambient, const std::string& referenceName, double t_s) {
    std::vector<std::optional<glm::vec3>> vel;
    std::vector<std::string> read;
    sampler.sample(field, vel, read);
    auto speedOf = [](const glm::vec3& v) {
        return std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z);
    };
    double refSpeed = -1.0;
    for (size_t i = 0; i < points.size(); ++i)
        if (!referenceName.empty() && points[i].in.name == referenceName && vel[i])
            refSpeed = speedOf(*vel[i]);
    auto num = [](double v, int decimals = 4) { return ProbeCell{v, "", decimals}; };
    for (size_t i = 0; i < points.size(); ++i) {
        const ProbePoint& p = points[i];
        std::vector<ProbeCell> row;
        if (!std::isnan(t_s)) row.push_back(num(t_s));
        row.push_back({std::nullopt, p.in.name});
        row.push_back(num(p.in.x_m)), row.push_back(num(p.in.y_m));
        row.push_back(p.zKnown ? num(p.z) : ProbeCell{});
        row.push_back(p.aglKnown ? num(p.agl) : ProbeCell{});
        if (!vel[i]) {
            for (int k = 0; k < 10; ++k) row.push_back({});  // u .. read: no values
            row.push_back({std::nullopt, p.reason});
        } else {
            const glm::vec3& v = *vel[i];
            const double speed = speedOf(v);
            const double horizontal = std::hypot(double(v.x), double(v.y));
            const double ref = referenceName.empty() ? ambient.speedAt_mps(p.agl) : refSpeed;
            row.push_back(num(v.x)), row.push_back(num(v.y)), row.push_back(num(v.z));
            row.push_back(num(speed));
            if (horizontal > CALM_MPS) {
                sim::AmbientWind a;
                a.direction_deg = degreesFromRadians(std::atan2(double(v.y), double(v.x)));
                row.push_back(num(a.from_deg(), 2));
            } else {
                row.push_back({});
            }
            row.push_back(ref > 0.0 ? num((speed - ref) / ref) : ProbeCell{});
            // k at the point (coupling/Turbulence.h: constant below the first air cell's centre,
            // as in the log layer), and the intensity and gust from it and the speed beside it.
            if (tke_m2ps2.empty()) {
                for (int k = 0; k < 3; ++k) row.push_back({});
            } else {
                const double k =
                    coupling::sampleTke_m2ps2(field, tke_m2ps2, p.localX, p.localY, p.z);
                const double intensity = coupling::turbulenceIntensity(k, speed);
                row.push_back(std::isfinite(k) ? num(k, 6) : ProbeCell{});
                row.push_back(std::isfinite(intensity) ? num(intensity, 6) : ProbeCell{});
                row.push_back(std::isfinite(k) ? num(coupling::gustSpeed_mps(speed, k))
                                               : ProbeCell{});
            }
            row.push_back({std::nullopt, read[i]});
            row.push_back({});
        }
        for (const std::string& e : p.in.extra) row.push_back({std::nullopt, e});
        out.rows.push_back(std::move(row));
    }
}

/// Refuses a .vdb whose terrain or crop differ from the scene's (InputError naming what
/// differs), and warns on stderr when only the model, the solver keys or the wind differ.
/// Returns the file's metadata strings (read once, without the trees).
std::map<std::string, std::string> checkVdbProvenance(const std::string& path,
                                                      const FieldProvenance& scene) {
    std::map<std::string, std::string> meta;
    try {
        meta = sim::vdbGridStrings(path, "velocity");
    } catch (const std::runtime_error& e) {
        throw InputError(e.what());
    }
    const ProvenanceDiff diff = compareProvenance(meta, scene);
    if (!diff.refusals.empty()) {
        std::string what = diff.refusals.front();
        for (size_t i = 1; i < diff.refusals.size(); ++i) what += "; " + diff.refusals[i];
        throw InputError("--vdb: " + path + ": not this scene's field: " + what +
                         " (solve this scene with gale solve, or probe the scene it came from)");
    }
    for (const std::string& w : diff.warnings)
        std::fprintf(stderr, "probe: warning: --vdb: %s: %s\n", path.c_str(), w.c_str());
    return meta;
}

/// A time series must come from one run: every file's provenance (terrain, crop, model, solver
/// keys, wind) equals the first's, or InputError names the two files and what differs.
void refuseMixedSeries(const std::vector<std::string>& paths,
                       const std::vector<std::map<std::string, std::string>>& metadata) {
    if (paths.size() < 2) return;
    const std::map<std::string, std::string>& first = metadata.front();
    for (size_t i = 1; i < paths.size(); ++i) {
        const std::map<std::string, std::string>& meta = metadata[i];
        for (const char* key : {"gale_terrain_digest", "gale_crop", "gale_model",
                                "gale_solver_digest", "gale_wind_digest"}) {
            const auto a = first.find(key), b = meta.find(key);
            const bool same = (a == first.end()) == (b == meta.end()) &&
                              (a == first.end() || a->second == b->second);
            if (!same)
                throw InputError("--vdb: " + paths[i] + " and " + paths.front() +
                                 " come from different runs (their " + std::string(key + 5) +
                                 " differs): a time series must be one run's sequence");
        }
    }
}

int runProbe(const ProbeOptions& o) {
    SceneRunOptions sceneOptions;
    sceneOptions.scenePath = o.scenePath;
    // A signal stops the run at once with one line and nothing written, except while the
    // momentum model steps (deferred there: it stops between two pseudo-time steps).
    InterruptScope interrupt("while probing: nothing written");
    const Scene scene = loadScene(sceneOptions);
    // Nothing this run reads is replaced by what it writes (docs/reliability.md): the scene and
    // every file it names, the points, the .vdb files; a CSV to a device or FIFO is a stream.
    if (!o.outPath.empty()) {
        std::vector<RunPath> inputs = sceneInputs(scene);
        inputs.push_back({o.pointsPath, "the points file"});
        for (const std::string& v : o.vdbPaths) inputs.push_back({v, "--vdb"});
        refuseAliases(inputs, {{o.outPath, "-o (the probe output)",
                                /*streamable=*/!isVectorOutput(o.outPath)}});
        checkProbeOutputPath(o.outPath);
    }
    const bool toStream = !o.outPath.empty() && isStreamOutput(o.outPath);
    const SceneTerrain terrain = buildTerrain(scene);
    checkSceneFieldInputs(scene);
    std::unique_ptr<sim::AirDomain> domain = buildSceneDomain(scene, terrain.field);
    const ProbeTable table = readProbeTable(o.pointsPath, terrain.georef);
    const std::vector<ProbePoint> points =
        placePoints(table, terrain.field, terrain.georef, domain->wsTop_m());
    if (!o.reference.empty()) {
        const auto named = std::count_if(points.begin(), points.end(), [&](const ProbePoint& p) {
            return p.in.name == o.reference;
        });
        if (named == 0)
            throw InputError("--reference: no point named '" + o.reference + "' in " +
                             o.pointsPath);
        if (named > 1)
            throw InputError("--reference: " + std::to_string(named) + " points are named '" +
                             o.reference + "' in " + o.pointsPath +
                             ": the reference must be one point");
        const auto ref = std::find_if(points.begin(), points.end(), [&](const ProbePoint& p) {
            return p.in.name == o.reference;
        });
        if (!ref->reason.empty())
            throw InputError("--reference: point '" + o.reference + "' (" + table.where(ref->in) +
                             ") has no wind: " + ref->reason);
    }
    const std::filesystem::path outFolder = std::filesystem::path(o.outPath).parent_path();
    const std::string outFolderText = outFolder.empty() ? "." : outFolder.string();
    if (!o.outPath.empty() && !toStream) (void)checkOutputFolder(outFolderText, "-o", "probe", 0);
    const sim::AmbientWind& ambient = scene.wind.ambient;
    const bool series =
        o.vdbPaths.size() > 1 || (o.vdbPaths.empty() && scene.wind.kind == WindKind::Unsteady);
    ProbeOutput out = outputTable(series, table);
    ProbeSampler sampler(points, nearGroundOf(scene));
    bool ok = true;
    if (!o.vdbPaths.empty()) {
        const FieldProvenance provenance = fieldProvenance(scene, terrain.field);
        std::vector<std::map<std::string, std::string>> metadata;
        for (const std::string& path : o.vdbPaths)
            metadata.push_back(checkVdbProvenance(path, provenance));
        refuseMixedSeries(o.vdbPaths, metadata);
        for (const std::string& path : o.vdbPaths) {
            sim::WindField field(domain->layout(), domain->terrainShared(), domain->airFlags());
            double t_s;
            std::vector<double> tke;
            try {
                t_s = sim::readFaceVelocities(path, field);
                tke = sim::readCellTke(path, field);
            } catch (const std::runtime_error& e) {
                throw InputError(e.what());
            }
            if (tke.empty())
                noteNoTurbulence("--vdb: " + path +
                                 " holds no tke grid (a mass-consistent field has no turbulence)");
            appendRows(out, points, sampler, field, tke, ambient, o.reference,
                       series ? (std::isnan(t_s) ? 0.0 : t_s) : std::nan(""));
        }
    } else {
        // The momentum model stops between pseudo-time steps; anything else stops at once.
        if (scene.solver.model == sim::SteadyModel::Momentum) interrupt.defer();
        std::fprintf(stderr, "probe: solving the wind (%d x %d x %d cells)...\n", domain->nx(),
                     domain->ny(), domain->nz());
        for (const std::string& line : describeSceneField(scene, *domain))
            std::fprintf(stderr, "probe: %s\n", line.c_str());
        SceneField sf = solveSceneField(scene, std::move(domain), verbFieldOptions("probe"));
        if (sf.stopped() || interruptSignal()) {
            std::fprintf(stderr, "probe: interrupted (%s): %s; nothing written\n",
                         interruptSignalName(), sf.summary().c_str());
            return interruptExitCode();
        }
        interrupt.exitAtOnce("while probing: nothing written");
        // What solve prints, and the verdict it gives (exit 3 when it did not converge).
        std::fprintf(stderr, "probe: %s\n", sf.summary().c_str());
        ok = sf.converged();
        if (!ok) std::fprintf(stderr, "probe: %s\n", sf.report.message.c_str());
        if (sf.tke_m2ps2.empty())
            noteNoTurbulence(sf.momentum ? "the momentum model ran without its closure"
                                         : "the mass-consistent model has no turbulence");
        if (!series) {
            appendRows(out, points, sampler, sf.field, sf.tke_m2ps2, ambient, o.reference,
                       std::nan(""));
        } else {
            const UnsteadyStepping stepping = unsteadySteppingOf(scene);
            sim::UnsteadyWindSolver solver(*sf.domain, sf.field, stepping.settings,
                                           stepping.referenceSpeed_mps);
            appendRows(out, points, sampler, solver.field(), sf.tke_m2ps2, ambient, o.reference,
                       solver.time_s());
            const double every = scene.unsteady.outputEvery_s, duration = scene.unsteady.duration_s;
            const int outputs = int(std::ceil(duration / every - 1e-9));
            bool converged = true, finite = true;
            int steps = 0;
            for (int n = 1; n <= outputs && finite; ++n) {
                for (const sim::StepReport& r : solver.advanceTo(std::min(duration, n * every))) {
                    ++steps;
                    converged = converged && r.projection.converged;
                    finite = finite && r.finite;
                }
                if (interruptSignal()) {
                    std::fprintf(stderr, "probe: interrupted (%s) at t = %.3g s; nothing written\n",
                                 interruptSignalName(), solver.time_s());
                    return interruptExitCode();
                }
                if (!finite) break;
                // The unsteady solver's own k after its last surface-layer step (empty without
                // one: its rows' turbulence columns stay empty).
                appendRows(out, points, sampler, solver.field(),
                           solver.turbulentKineticEnergy_m2ps2(), ambient, o.reference,
                           solver.time_s());
            }
            std::fprintf(stderr, "probe: unsteady, %d steps to t = %.2f s, %s\n", steps,
                         solver.time_s(),
                         !finite     ? "NON-FINITE FIELD"
                         : converged ? "all solves converged"
                                     : "SOME SOLVES DID NOT CONVERGE");
            ok = ok && converged && finite;
        }
    }
    if (o.outPath.empty()) {
        const std::string csv = probeCsv(out);
        if (std::fwrite(csv.data(), 1, csv.size(), stdout) != csv.size() ||
            std::fflush(stdout) != 0)
            throw std::runtime_error("stdout: cannot write the probe table");
    } else {
        if (!toStream) prepareOutputFolder(outFolderText, "-o");
        if (isVectorOutput(o.outPath))
            writeProbeVector(o.outPath, out, terrain.georef);
        else
            writeTextAtomic(o.outPath, probeCsv(out));
        std::printf("probe: %zu points%s to %s\n", points.size(), series ? " (time series)" : "",
                    o.outPath.c_str());
    }
    return ok ? EXIT_OK : EXIT_UNMET;
}

}  // namespace

void addProbeVerb(CLI::App& app, VerbTable& verbs) {
    auto options = std::make_shared<ProbeOptions>();
    CLI::App* verb = app.add_subcommand(
        "probe",
        "The wind at points (masts) of a scene as CSV: u, v, w, speed, from-direction, "
        "speed-up; from the scene's field (solved as gale solve solves it) or from .vdb files "
        "gale solve wrote for it");
    verb->add_option("scene", options->scenePath, "Scene file")->required();
    verb->add_option("points", options->pointsPath,
                     "CSV of points: header with x, y and height_agl_m or z_m (name optional), "
                     "in the scene's (DEM's) coordinates")
        ->required();
    verb->add_option("-o,--output", options->outPath, "CSV file to write (default: stdout)")
        ->check(NOT_EMPTY);
    verb->add_option("--vdb", options->vdbPaths,
                     "Read the field from these .vdb files (gale solve of the same scene, its "
                     "terrain and crop checked; several: a time series) instead of solving");
    verb->add_option("--reference", options->reference,
                     "Speed-up against this point (by name); default: the ambient profile at the "
                     "point's height above ground")
        ->check(NOT_EMPTY);
    verb->footer(
        std::string("\nColumns: [t_s,] name, x, y, z_m, height_agl_m, u_mps, v_mps, w_mps, "
                    "speed_mps, from_deg (meteorological: where the wind comes from, "
                    "clockwise from the scene's +y: grid north for a DEM), speedup = speed / "
                    "reference - 1, tke_m2ps2 (the momentum model's turbulent kinetic energy k), "
                    "turbulence_intensity = sqrt(2k/3) / speed, gust_mps = speed + 3.5 "
                    "sqrt(2k/3) (the three empty for the mass-consistent model), read (how the "
                    "grass reads the field there: field, "
                    "tangential, log_law, zero), reason (why a point has no values: outside "
                    "the terrain, not above the ground, above the top). A solve that did not "
                    "converge still writes the table and exits 3. docs/cli.md says more.") +
        EXIT_CODES_FOOTER);
    verbs.add(verb, [options] { return runProbe(*options); });
}

}  // namespace gale::app
