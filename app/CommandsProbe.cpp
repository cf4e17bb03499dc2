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
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "app/Cli.h"
#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/io/Interrupt.h"
#include "app/io/OutputFolder.h"
#include "app/scene/SceneBuilder.h"
#include "app/scene/SceneField.h"
#include "base/Numbers.h"
#include "coupling/FieldSampling.h"
#include "sim/AirDomain.h"
#include "sim/UnsteadyWind.h"
#include "sim/VdbIO.h"

namespace gale::app {
namespace {

/// Below this horizontal speed (m/s) the from-direction is undefined and left empty.
constexpr double CALM_MPS = 1e-9;
/// Longest probe file read, bytes: a probe table is a list of masts, not a point cloud.
constexpr std::streamoff MAX_PROBE_FILE_BYTES = 16 * 1024 * 1024;

struct ProbeOptions {
    std::string scenePath;
    std::string pointsPath;
    std::string outPath;                ///< empty: the table goes to stdout
    std::vector<std::string> vdbPaths;  ///< empty: solve the scene
    std::string reference;              ///< a point's name; empty: the ambient profile
};

struct ProbePoint {
    std::string name;
    int line = 0;
    double x = 0, y = 0;  ///< scene (DEM) coordinates, metres
    double localX = 0, localY = 0;
    double z = 0;                         ///< world (local frame) z, metres
    double agl = 0;                       ///< height above the ground, metres
    bool zKnown = true, aglKnown = true;  ///< false for a point outside the terrain (no ground)
    /// Why the point has no values (outside the terrain, not above the ground, above the top);
    /// empty: it is sampled.
    std::string reason;
};

std::vector<std::string> splitCsv(const std::string& line) {
    std::vector<std::string> cells;
    std::string cell;
    std::istringstream in(line);
    while (std::getline(in, cell, ',')) {
        const auto a = cell.find_first_not_of(" \t\r");
        const auto b = cell.find_last_not_of(" \t\r");
        cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
    }
    if (!line.empty() && line.back() == ',') cells.push_back("");
    return cells;
}

std::string fmt(double v, const char* f = "%.4f") {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

/// Reads the probe CSV: a header naming x, y and height_agl_m or z_m (name optional), then one
/// point per line. A point the field cannot answer (outside the terrain, not above the ground,
/// above the domain's top) is kept with its reason; throws InputError "FILE:LINE: reason" for a
/// line it cannot read, and "FILE: ..." when no point can be answered.
std::vector<ProbePoint> readPoints(const std::string& path, const sim::Heightfield& field,
                                   const Georeference& geo, double top_m) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw InputError(path + ": cannot read the probe points (no such file?)");
    if (in.tellg() > MAX_PROBE_FILE_BYTES)
        throw InputError(path + ": too large for a probe table (at most 16 MiB)");
    in.seekg(0);
    std::string line;
    int lineNo = 0;
    auto fail = [&](const std::string& reason) -> void {
        throw InputError(path + ":" + std::to_string(lineNo) + ": " + reason);
    };
    int cx = -1, cy = -1, ch = -1, cz = -1, cn = -1;
    size_t columns = 0;
    std::vector<ProbePoint> points;
    while (std::getline(in, line)) {
        ++lineNo;
        if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
        const std::vector<std::string> cells = splitCsv(line);
        if (columns == 0) {
            for (size_t i = 0; i < cells.size(); ++i) {
                const std::string& c = cells[i];
                int* slot = c == "x"              ? &cx
                            : c == "y"            ? &cy
                            : c == "height_agl_m" ? &ch
                            : c == "z_m"          ? &cz
                            : c == "name"         ? &cn
                                                  : nullptr;
                if (!slot)
                    fail("unknown column '" + c + "' (expected name, x, y, height_agl_m or z_m)");
                *slot = static_cast<int>(i);
            }
            if (cx < 0 || cy < 0) fail("the header must name columns x and y");
            if ((ch < 0) == (cz < 0))
                fail(
                    "the header must name exactly one of height_agl_m (above the ground) or z_m "
                    "(absolute)");
            columns = cells.size();
            continue;
        }
        if (cells.size() != columns)
            fail("expected " + std::to_string(columns) + " values, got " +
                 std::to_string(cells.size()));
        auto number = [&](int col, const char* what) {
            const std::string& t = cells[static_cast<size_t>(col)];
            char* end = nullptr;
            const double v = std::strtod(t.c_str(), &end);
            if (t.empty() || *end != '\0' || !std::isfinite(v))
                fail(std::string(what) + ": not a finite number (got '" + t + "')");
            return v;
        };
        ProbePoint p;
        p.line = lineNo;
        p.name = cn >= 0 ? cells[static_cast<size_t>(cn)] : "p" + std::to_string(points.size() + 1);
        p.x = number(cx, "x");
        p.y = number(cy, "y");
        p.localX = p.x - geo.originX_m;
        p.localY = p.y - geo.originY_m;
        const double height = number(ch >= 0 ? ch : cz, ch >= 0 ? "height_agl_m" : "z_m");
        const double x0 = field.originX_m, y0 = field.originY_m;
        if (p.localX < x0 || p.localX > x0 + field.sizeX_m() || p.localY < y0 ||
            p.localY > y0 + field.sizeY_m()) {
            char box[256];
            std::snprintf(
                box, sizeof box,
                "point (%.3f, %.3f) is outside the terrain (x %.3f .. %.3f, y %.3f .. %.3f)", p.x,
                p.y, geo.demX_m(x0), geo.demX_m(x0 + field.sizeX_m()), geo.demY_m(y0),
                geo.demY_m(y0 + field.sizeY_m()));
            p.reason = box;
            (ch >= 0 ? p.agl : p.z) = height;
            p.zKnown = cz >= 0, p.aglKnown = ch >= 0;
            points.push_back(p);
            continue;
        }
        const double ground = field.sample(p.localX, p.localY);
        if (ch >= 0) {
            p.agl = height;
            p.z = ground + p.agl;
        } else {
            p.z = height;
            p.agl = p.z - ground;
        }
        if (!(p.agl > 0.0))
            p.reason = "point is not above the ground (ground at " + fmt(ground, "%.3f") +
                       " m, point at " + fmt(p.z, "%.3f") + " m)";
        else if (!(p.z < top_m))
            p.reason = "point is above the air domain's top (" + fmt(top_m, "%.3f") +
                       " m; raise solver.top_m)";
        points.push_back(p);
    }
    if (points.empty())
        throw InputError(path + ": no probe points (a header, then one point per line)");
    const auto answered = std::count_if(points.begin(), points.end(),
                                        [](const ProbePoint& p) { return p.reason.empty(); });
    if (answered == 0)
        throw InputError(
            path + ":" + std::to_string(points.front().line) + ": " + points.front().reason +
            (points.size() > 1 ? " (and so is every other point: nothing to probe)" : ""));
    for (const ProbePoint& p : points)
        if (!p.reason.empty())
            std::fprintf(stderr, "probe: warning: %s:%d: %s: %s; its row has no values\n",
                         path.c_str(), p.line, p.name.c_str(), p.reason.c_str());
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

std::string csvHeader(bool series) {
    return std::string(series ? "t_s," : "") +
           "name,x,y,z_m,height_agl_m,u_mps,v_mps,w_mps,speed_mps,from_deg,speedup,read,reason\n";
}

/// One CSV row per point for the field at time t_s (NaN: steady, no time column).
void appendRows(std::string& csv, const std::vector<ProbePoint>& points, ProbeSampler& sampler,
                const sim::WindField& field, const sim::AmbientWind& ambient,
                const std::string& referenceName, double t_s) {
    std::vector<std::optional<glm::vec3>> vel;
    std::vector<std::string> read;
    sampler.sample(field, vel, read);
    auto speedOf = [](const glm::vec3& v) {
        return std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z);
    };
    double refSpeed = -1.0;
    for (size_t i = 0; i < points.size(); ++i)
        if (!referenceName.empty() && points[i].name == referenceName && vel[i])
            refSpeed = speedOf(*vel[i]);
    for (size_t i = 0; i < points.size(); ++i) {
        const ProbePoint& p = points[i];
        if (!std::isnan(t_s)) csv += fmt(t_s) + ",";
        csv += p.name + "," + fmt(p.x) + "," + fmt(p.y) + ",";
        if (!vel[i]) {
            // The point as given; no values, the reason instead (quoted: it holds commas).
            std::string reason = p.reason;
            std::replace(reason.begin(), reason.end(), '"', '\'');
            csv += (p.zKnown ? fmt(p.z) : std::string()) + "," +
                   (p.aglKnown ? fmt(p.agl) : std::string()) + ",,,,,,,,\"" + reason + "\"\n";
            continue;
        }
        const glm::vec3& v = *vel[i];
        const double speed = speedOf(v);
        const double horizontal = std::hypot(double(v.x), double(v.y));
        const double ref = referenceName.empty() ? ambient.speedAt_mps(p.agl) : refSpeed;
        std::string from;
        if (horizontal > CALM_MPS) {
            sim::AmbientWind a;
            a.direction_deg = degreesFromRadians(std::atan2(double(v.y), double(v.x)));
            from = fmt(a.from_deg(), "%.2f");
        }
        csv += fmt(p.z) + "," + fmt(p.agl) + "," + fmt(v.x) + "," + fmt(v.y) + "," + fmt(v.z) +
               "," + fmt(speed) + "," + from + "," +
               (ref > 0.0 ? fmt((speed - ref) / ref) : std::string()) + "," + read[i] + ",\n";
    }
}

/// Refuses a .vdb whose terrain or crop differ from the scene's (InputError naming what
/// differs), and warns on stderr when only the model, the solver keys or the wind differ.
void checkVdbProvenance(const std::string& path, const FieldProvenance& scene) {
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
}

int runProbe(const ProbeOptions& o) {
    SceneRunOptions sceneOptions;
    sceneOptions.scenePath = o.scenePath;
    const Scene scene = loadScene(sceneOptions);
    const SceneTerrain terrain = buildTerrain(scene);
    checkSceneFieldInputs(scene);
    std::unique_ptr<sim::AirDomain> domain = buildSceneDomain(scene, terrain.field);
    const std::vector<ProbePoint> points =
        readPoints(o.pointsPath, terrain.field, terrain.georef, domain->wsTop_m());
    if (!o.reference.empty()) {
        const auto ref = std::find_if(points.begin(), points.end(),
                                      [&](const ProbePoint& p) { return p.name == o.reference; });
        if (ref == points.end())
            throw InputError("--reference: no point named '" + o.reference + "' in " +
                             o.pointsPath);
        if (!ref->reason.empty())
            throw InputError("--reference: point '" + o.reference + "' (" + o.pointsPath + ":" +
                             std::to_string(ref->line) + ") has no wind: " + ref->reason);
    }
    const std::filesystem::path outFolder = std::filesystem::path(o.outPath).parent_path();
    const std::string outFolderText = outFolder.empty() ? "." : outFolder.string();
    if (!o.outPath.empty()) (void)checkOutputFolder(outFolderText, "-o", "probe", 0);
    const sim::AmbientWind& ambient = scene.wind.ambient;
    const bool series =
        o.vdbPaths.size() > 1 || (o.vdbPaths.empty() && scene.wind.kind == WindKind::Unsteady);
    std::string csv = csvHeader(series);
    ProbeSampler sampler(points, nearGroundOf(scene));
    bool ok = true;
    if (!o.vdbPaths.empty()) {
        const FieldProvenance provenance = fieldProvenance(scene, terrain.field);
        for (const std::string& path : o.vdbPaths) checkVdbProvenance(path, provenance);
        for (const std::string& path : o.vdbPaths) {
            sim::WindField field(domain->layout(), domain->terrainShared(), domain->airFlags());
            double t_s;
            try {
                t_s = sim::readFaceVelocities(path, field);
            } catch (const std::runtime_error& e) {
                throw InputError(e.what());
            }
            appendRows(csv, points, sampler, field, ambient, o.reference,
                       series ? (std::isnan(t_s) ? 0.0 : t_s) : std::nan(""));
        }
    } else {
        InterruptScope interrupt("while solving: nothing written");
        interrupt.defer();  // the momentum model stops between pseudo-time steps, see below
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
        // What solve prints, and the verdict it gives (exit 3 when it did not converge).
        std::fprintf(stderr, "probe: %s\n", sf.summary().c_str());
        ok = sf.converged();
        if (!ok) std::fprintf(stderr, "probe: %s\n", sf.report.message.c_str());
        if (!series) {
            appendRows(csv, points, sampler, sf.field, ambient, o.reference, std::nan(""));
        } else {
            const UnsteadyStepping stepping = unsteadySteppingOf(scene);
            sim::UnsteadyWindSolver solver(*sf.domain, sf.field, stepping.settings,
                                           stepping.referenceSpeed_mps);
            appendRows(csv, points, sampler, solver.field(), ambient, o.reference, solver.time_s());
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
                appendRows(csv, points, sampler, solver.field(), ambient, o.reference,
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
        std::fputs(csv.c_str(), stdout);
    } else {
        prepareOutputFolder(outFolderText, "-o");
        writeTextAtomic(o.outPath, csv);
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
                    "reference - 1, read (how the grass reads the field there: field, "
                    "tangential, log_law, zero), reason (why a point has no values: outside "
                    "the terrain, not above the ground, above the top). A solve that did not "
                    "converge still writes the table and exits 3. docs/cli.md says more.") +
        EXIT_CODES_FOOTER);
    verbs.add(verb, [options] { return runProbe(*options); });
}

}  // namespace gale::app
