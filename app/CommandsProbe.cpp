/// \file CommandsProbe.cpp
/// `gale probe SCENE POINTS.csv [-o OUT.csv] [--vdb FILE.vdb ...] [--reference NAME]`: the wind
/// at points (met masts, turbines) as a CSV table (docs/cli.md, "gale probe").
///
/// Points are in the scene's coordinates: the DEM's coordinate system for a DEM terrain (the
/// local offset of Dem.h is removed inside and added back in the output), the terrain's own
/// metres otherwise. Each point gives x, y and either a height above the ground or an absolute z.
/// The field comes from solving the scene (steady; unsteady scenes are stepped to every output
/// time) or from .vdb files that `gale solve` wrote for the same scene (one file per time).

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
#include "app/io/OutputFolder.h"
#include "app/scene/SceneBuilder.h"
#include "base/Numbers.h"
#include "sim/AirDomain.h"
#include "sim/SteadyWind.h"
#include "sim/UnsteadyWind.h"
#include "sim/VdbIO.h"

namespace gale::app {
namespace {

using gale::PI;
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
    double z = 0;    ///< world (local frame) z, metres
    double agl = 0;  ///< height above the ground, metres
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

/// Reads the probe CSV: a header naming x, y and height_agl_m or z_m (name optional), then one
/// point per line. Throws InputError "FILE:LINE: reason" for anything it cannot place.
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
        const double x0 = field.originX_m, y0 = field.originY_m;
        if (p.localX < x0 || p.localX > x0 + field.sizeX_m() || p.localY < y0 ||
            p.localY > y0 + field.sizeY_m()) {
            char box[256];
            std::snprintf(
                box, sizeof box,
                "point (%.3f, %.3f) is outside the terrain (x %.3f .. %.3f, y %.3f .. %.3f)", p.x,
                p.y, geo.demX_m(x0), geo.demX_m(x0 + field.sizeX_m()), geo.demY_m(y0),
                geo.demY_m(y0 + field.sizeY_m()));
            fail(box);
        }
        const double ground = field.sample(p.localX, p.localY);
        if (ch >= 0) {
            p.agl = number(ch, "height_agl_m");
            p.z = ground + p.agl;
        } else {
            p.z = number(cz, "z_m");
            p.agl = p.z - ground;
        }
        if (!(p.agl > 0.0))
            fail("point is not above the ground (ground at " + std::to_string(ground) +
                 " m, point at " + std::to_string(p.z) + " m)");
        if (!(p.z < top_m))
            fail("point is above the air domain's top (" + std::to_string(top_m) +
                 " m; raise solver.top_m)");
        points.push_back(p);
    }
    if (points.empty())
        throw InputError(path + ": no probe points (a header, then one point per line)");
    return points;
}

std::string fmt(double v, const char* f = "%.4f") {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

/// One CSV row per point for the field at time t_s (NaN: steady, no time column).
void appendRows(std::string& csv, const std::vector<ProbePoint>& points,
                const sim::WindField& field, const sim::AmbientWind& ambient,
                const std::string& referenceName, double t_s) {
    std::vector<std::array<double, 3>> vel;
    for (const ProbePoint& p : points) vel.push_back(field.velocityAt_mps(p.localX, p.localY, p.z));
    auto speedOf = [](const std::array<double, 3>& v) {
        return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    };
    double refSpeed = -1.0;
    for (size_t i = 0; i < points.size(); ++i)
        if (!referenceName.empty() && points[i].name == referenceName) refSpeed = speedOf(vel[i]);
    for (size_t i = 0; i < points.size(); ++i) {
        const ProbePoint& p = points[i];
        const auto& v = vel[i];
        const double speed = speedOf(v);
        const double horizontal = std::hypot(v[0], v[1]);
        const double ref = referenceName.empty() ? ambient.speedAt_mps(p.agl) : refSpeed;
        std::string from;
        if (horizontal > CALM_MPS) {
            sim::AmbientWind a;
            a.direction_deg = std::atan2(v[1], v[0]) * 180.0 / PI;
            from = fmt(a.from_deg(), "%.2f");
        }
        if (!std::isnan(t_s)) csv += fmt(t_s) + ",";
        csv += p.name + "," + fmt(p.x) + "," + fmt(p.y) + "," + fmt(p.z) + "," + fmt(p.agl) + "," +
               fmt(v[0]) + "," + fmt(v[1]) + "," + fmt(v[2]) + "," + fmt(speed) + "," + from + "," +
               (ref > 0.0 ? fmt((speed - ref) / ref) : std::string()) + "\n";
    }
}

int runProbe(const ProbeOptions& o) {
    SceneRunOptions sceneOptions;
    sceneOptions.scenePath = o.scenePath;
    const Scene scene = loadScene(sceneOptions);
    const SceneTerrain terrain = buildTerrain(scene);
    std::unique_ptr<sim::AirDomain> domain;
    try {
        domain = std::make_unique<sim::AirDomain>(terrain.field, scene.solver.domain);
    } catch (const std::invalid_argument& e) {
        rethrowAsSceneError(scene, "solver", e);  // at the key's line when it names one
    }
    const std::vector<ProbePoint> points =
        readPoints(o.pointsPath, terrain.field, terrain.georef, domain->wsTop_m());
    if (!o.reference.empty() &&
        std::none_of(points.begin(), points.end(),
                     [&](const ProbePoint& p) { return p.name == o.reference; }))
        throw InputError("--reference: no point named '" + o.reference + "' in " + o.pointsPath);
    const std::filesystem::path outFolder = std::filesystem::path(o.outPath).parent_path();
    const std::string outFolderText = outFolder.empty() ? "." : outFolder.string();
    if (!o.outPath.empty()) (void)checkOutputFolder(outFolderText, "-o", "probe", 0);
    const sim::AmbientWind& ambient = scene.wind.ambient;
    const bool series =
        o.vdbPaths.size() > 1 || (o.vdbPaths.empty() && scene.wind.kind == WindKind::Unsteady);
    std::string csv = std::string(series ? "t_s," : "") +
                      "name,x,y,z_m,height_agl_m,u_mps,v_mps,w_mps,speed_mps,from_deg,speedup\n";
    if (!o.vdbPaths.empty()) {
        for (const std::string& path : o.vdbPaths) {
            sim::WindField field(domain->layout(), domain->terrainShared(), domain->airFlags());
            double t_s;
            try {
                t_s = sim::readFaceVelocities(path, field);
            } catch (const std::runtime_error& e) {
                throw InputError(e.what());
            }
            appendRows(csv, points, field, ambient, o.reference,
                       series ? (std::isnan(t_s) ? 0.0 : t_s) : std::nan(""));
        }
    } else {
        std::fprintf(stderr, "probe: solving the steady wind (%d x %d x %d cells)...\n",
                     domain->nx(), domain->ny(), domain->nz());
        sim::SteadyWindResult steady;
        try {
            steady =
                sim::solveSteadyWind(*domain, ambient, scene.solver.weights, scene.solver.settings);
        } catch (const std::invalid_argument& e) {
            rethrowAsSceneError(scene, "wind", e);
        }
        if (!series) {
            appendRows(csv, points, steady.field, ambient, o.reference, std::nan(""));
        } else {
            sim::UnsteadyWindSolver solver(*domain, steady.field, scene.unsteady.settings,
                                           ambient.speed_mps);
            appendRows(csv, points, solver.field(), ambient, o.reference, solver.time_s());
            const double every = scene.unsteady.outputEvery_s, duration = scene.unsteady.duration_s;
            const int outputs = int(std::ceil(duration / every - 1e-9));
            for (int n = 1; n <= outputs; ++n) {
                (void)solver.advanceTo(std::min(duration, n * every));
                appendRows(csv, points, solver.field(), ambient, o.reference, solver.time_s());
            }
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
    return EXIT_OK;
}

}  // namespace

void addProbeVerb(CLI::App& app, VerbTable& verbs) {
    auto options = std::make_shared<ProbeOptions>();
    CLI::App* verb = app.add_subcommand(
        "probe",
        "The wind at points (masts) of a scene as CSV: u, v, w, speed, from-direction, "
        "speed-up; from solving the scene or from .vdb files gale solve wrote");
    verb->add_option("scene", options->scenePath, "Scene file")->required();
    verb->add_option("points", options->pointsPath,
                     "CSV of points: header with x, y and height_agl_m or z_m (name optional), "
                     "in the scene's (DEM's) coordinates")
        ->required();
    verb->add_option("-o,--output", options->outPath, "CSV file to write (default: stdout)")
        ->check(NOT_EMPTY);
    verb->add_option(
        "--vdb", options->vdbPaths,
        "Read the field from these .vdb files (gale solve of the same scene; several: a "
        "time series) instead of solving");
    verb->add_option("--reference", options->reference,
                     "Speed-up against this point (by name); default: the ambient profile at the "
                     "point's height above ground")
        ->check(NOT_EMPTY);
    verb->footer(
        std::string("\nColumns: [t_s,] name, x, y, z_m, height_agl_m, u_mps, v_mps, w_mps, "
                    "speed_mps, from_deg (meteorological: where the wind comes from, "
                    "clockwise from north = +y), speedup = speed / reference - 1. docs/cli.md "
                    "says more.") +
        EXIT_CODES_FOOTER);
    verbs.add(verb, [options] { return runProbe(*options); });
}

}  // namespace gale::app
