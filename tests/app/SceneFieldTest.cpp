// One scene, one field (app/scene/SceneField.h): every verb that builds a scene's wind builds the
// same field, says what it ran, refuses what the solve refuses, and exits 3 when the solve did
// not converge; probes read what the grass reads; a .vdb carries where it came from.

#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "AppTestSupport.h"
#include "GeoTestSupport.h"
#include "ProbeTestSupport.h"
#include "app/scene/LoadScene.h"
#include "app/scene/SceneBuilder.h"
#include "app/scene/SceneField.h"
#include "coupling/FieldSampling.h"
#include "coupling/TerrainMeshBuilder.h"

namespace gale::app {
namespace {

using test::TempDir;

/// Probe output is printed with 4 decimals: half a unit of the last one.
constexpr double PRINTED_TOLERANCE = 5e-5;
/// A .vdb holds the face velocities as floats: probes of it agree with probes of the solved
/// doubles to float rounding (relative 6e-8 of speeds under 20 m/s) plus the printed rounding.
constexpr double FLOAT_FACES_TOLERANCE_MPS = 1e-4;

using test::readCsv;

/// The line of `text` that starts with `prefix`, or "".
std::string lineStarting(const std::string& text, const std::string& prefix) {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(prefix, 0) == 0) return line;
    return "";
}

/// The field digest a summary line ends with ("..., field 0123abcd...").
std::string digestIn(const std::string& line) {
    std::smatch m;
    const std::regex re("field ([0-9a-f]{16})");
    return std::regex_search(line, m, re) ? m[1].str() : "";
}

std::string example(const std::string& name) { return test::sourcePath("examples/" + name); }

/// Points on a line across the lee ridge (x along the wind), 2 and 10 m up.
const char* RIDGE_POINTS =
    "name,x,y,height_agl_m\nwindward,6,20,2\ncrest,16,20,2\nlee,24,20,2\nlee10,24,20,10\n";

TEST(SceneField, ProbeAndRenderRunTheMomentumModelOfGaleSolveToTheLastBit) {
    TempDir dir;
    test::writeFile(dir / "p.csv", RIDGE_POINTS);
    const std::string scene = example("lee_ridge_momentum.toml");
    // The example's wake sheds: its pseudo-time iteration ends on the cycle mean, not converged
    // (docs/validation.md), so solve exits 3; every verb must give that same verdict.
    const auto solve = test::runGale({"solve", scene, "-o", dir / "w.vdb"});
    ASSERT_TRUE(solve.exitCode == 0 || solve.exitCode == 3) << solve.describe();
    const auto direct = test::runGale({"probe", scene, dir / "p.csv", "-o", dir / "direct.csv"});
    EXPECT_EQ(direct.exitCode, solve.exitCode) << direct.describe();
    const auto fromVdb = test::runGale(
        {"probe", scene, dir / "p.csv", "-o", dir / "vdb.csv", "--vdb", dir / "w.vdb"});
    ASSERT_EQ(fromVdb.exitCode, 0) << fromVdb.describe();

    // The same composition: the report's field digest (the bits of every face velocity) is the
    // one probe's and render's summaries print, and each says the momentum model ran.
    const nlohmann::json report = nlohmann::json::parse(test::readFile(dir / "w.json"));
    const std::string solveDigest = digestIn(report["report"]["summary"].get<std::string>());
    ASSERT_EQ(solveDigest.size(), 16u) << report["report"]["summary"];
    const std::string probeLine = lineStarting(direct.err, "probe: momentum model");
    ASSERT_FALSE(probeLine.empty()) << direct.err;
    EXPECT_EQ(digestIn(probeLine), solveDigest) << probeLine;
    EXPECT_NE(report["model"].get<std::string>().find("momentum model"), std::string::npos);
    const auto render = test::runGale({"render", scene, "-o", dir / "frames", "--frames", "1",
                                       "--width", "64", "--height", "48"});
    ASSERT_EQ(render.exitCode, 0) << render.describe();
    const std::string renderLine = lineStarting(render.err, "gale: steady wind: momentum model");
    ASSERT_FALSE(renderLine.empty()) << render.err;
    EXPECT_EQ(digestIn(renderLine), solveDigest) << renderLine;

    // The mass-consistent twin of the scene gives another field: the digest tells them apart.
    const auto massConsistent =
        test::runGale({"probe", example("lee_ridge_mass_consistent.toml"), dir / "p.csv"});
    ASSERT_EQ(massConsistent.exitCode, 0) << massConsistent.describe();
    EXPECT_NE(digestIn(lineStarting(massConsistent.err, "probe: mass-consistent")), solveDigest);

    // Probing the solved field and its .vdb: the same values to float storage.
    const auto a = readCsv(test::readFile(dir / "direct.csv"));
    const auto b = readCsv(test::readFile(dir / "vdb.csv"));
    const auto m = readCsv(massConsistent.out);
    ASSERT_EQ(a.size(), 4u);
    ASSERT_EQ(b.size(), a.size());
    ASSERT_EQ(m.size(), a.size());
    for (size_t i = 0; i < a.size(); ++i)
        for (const char* c : {"u_mps", "v_mps", "w_mps", "speed_mps"})
            EXPECT_NEAR(std::stod(a[i].at(c)), std::stod(b[i].at(c)), FLOAT_FACES_TOLERANCE_MPS)
                << a[i].at("name") << " " << c;
    // The momentum model's shelter, which the mass-consistent field (what probe solved before,
    // whatever solver.model said) does not have: 8 m behind the crest, 2 m up, the wind is less
    // than half the crest's, and less than half the mass-consistent field's there.
    const double crest = std::stod(a[1].at("speed_mps")), lee = std::stod(a[2].at("speed_mps"));
    EXPECT_LT(lee, 0.5 * crest);
    EXPECT_LT(lee, 0.5 * std::stod(m[2].at("speed_mps")));
}

TEST(SceneField, CheckSaysWhatTheCompositionRuns) {
    const auto check = test::runGale({"check", example("lee_ridge_momentum.toml")});
    ASSERT_EQ(check.exitCode, 0) << check.describe();
    for (const char* said :
         {"solved steady field (momentum)", "mixing-length closure",
          "semi-Lagrangian pseudo-time step", "pseudo-time steps on each level", "cells: 40 x 40"})
        EXPECT_NE(check.out.find(said), std::string::npos) << said << "\n" << check.out;
    EXPECT_EQ(check.out.find("mass-consistent, docs/design.md"), std::string::npos) << check.out;
}

const char* HILL_SCENE = R"(
[terrain]
kind = "gaussian_hill"
size_m = [40.0, 40.0]
spacing_m = 0.5
height_m = 6.0
radius_m = 6.0
[wind]
kind = "solved"
speed_mps = 5.0
reference_height_m = 10.0
profile = "log"
roughness_m = 0.03
[solver]
voxel_size_m = 1.0
top_m = 40.0
)";

TEST(SceneField, ProbeExitsThreeWhenTheSolveDidNotConvergeAsSolveDoes) {
    TempDir dir;
    test::writeFile(dir / "p.csv", "name,x,y,height_agl_m\na,10,20,2\n");
    struct Case {
        const char* name;
        std::string scene;
    };
    std::string unsteady = HILL_SCENE;
    unsteady.replace(unsteady.find("kind = \"solved\""), 15, "kind = \"unsteady\"");
    unsteady +=
        "[unsteady]\nduration_s = 0.5\noutput_every_s = 0.5\nmax_iterations = 1\n"
        "tolerance = 1e-9\n";
    const Case cases[] = {
        {"mass-consistent, max_iterations = 1", std::string(HILL_SCENE) + "max_iterations = 1\n"},
        {"momentum, momentum_max_iterations = 1",
         std::string(HILL_SCENE) + "model = \"momentum\"\nmomentum_max_iterations = 1\n"},
        {"unsteady, one projection iteration a step", unsteady},
    };
    for (const Case& c : cases) {
        test::writeFile(dir / "s.toml", c.scene);
        const auto probe = test::runGale({"probe", dir / "s.toml", dir / "p.csv"});
        EXPECT_EQ(probe.exitCode, 3) << c.name << "\n" << probe.describe();
        const auto solve = test::runGale({"solve", dir / "s.toml", "-o", dir / "out/w.vdb"});
        EXPECT_EQ(solve.exitCode, 3) << c.name << "\n" << solve.describe();
        // probe says so in the words solve uses.
        const bool steady = c.scene.find("unsteady") == std::string::npos;
        EXPECT_NE(probe.err.find(steady ? "DID NOT CONVERGE" : "SOME SOLVES DID NOT CONVERGE"),
                  std::string::npos)
            << c.name << "\n"
            << probe.err;
    }
}

TEST(SceneField, CheckRefusesWhatSolveRefuses) {
    TempDir dir;
    // A displacement height above the wind's reference height: the log law has no wind there.
    test::writeFile(dir / "d.toml", std::string(HILL_SCENE) +
                                        "model = \"momentum\"\ndisplacement_height_m = 30.0\n");
    // The momentum model with a power-law profile: no roughness for its wall stress.
    std::string power = HILL_SCENE;
    power.replace(power.find("profile = \"log\""), 15, "profile = \"uniform\"");
    test::writeFile(dir / "p.toml", power + "model = \"momentum\"\n");
    // A roughness above the whole domain (z0 100 m under a 40 m top, reference 300 m): the log
    // profile is zero everywhere, a calm field that would "converge in 0 iterations".
    std::string rough = HILL_SCENE;
    rough.replace(rough.find("reference_height_m = 10.0"), 25, "reference_height_m = 300.0");
    rough.replace(rough.find("roughness_m = 0.03"), 18, "roughness_m = 100.0");
    test::writeFile(dir / "r.toml", rough);
    for (const char* scene : {"d.toml", "p.toml", "r.toml"}) {
        const auto solve = test::runGale({"solve", dir / scene, "-o", dir / "out/w.vdb"});
        EXPECT_EQ(solve.exitCode, 2) << solve.describe();
        const auto check = test::runGale({"check", dir / scene});
        EXPECT_EQ(check.exitCode, 2) << check.describe();
        EXPECT_EQ(test::countLines(check.err), 1) << check.err;
        EXPECT_EQ(test::errorOf(check.err), test::errorOf(solve.err)) << scene;
        EXPECT_EQ(test::countFiles(dir / "out"), 0);
    }
}

TEST(SceneField, ProbeRefusesAVdbOfAnotherTerrainAndWarnsOnAnotherWind) {
    TempDir dir;
    test::writeFile(dir / "p.csv", "name,x,y,height_agl_m\na,10,20,2\n");
    test::writeFile(dir / "hill.toml", HILL_SCENE);
    // The same grid over flat ground: the file would read, and be wrong.
    std::string flat = HILL_SCENE;
    flat.replace(flat.find("gaussian_hill"), 13, "flat");
    test::writeFile(dir / "flat.toml", flat);
    std::string windier = HILL_SCENE;
    windier.replace(windier.find("speed_mps = 5.0"), 15, "speed_mps = 9.0");
    test::writeFile(dir / "windier.toml", windier);
    ASSERT_EQ(test::runGale({"solve", dir / "flat.toml", "-o", dir / "flat.vdb"}).exitCode, 0);
    ASSERT_EQ(test::runGale({"solve", dir / "hill.toml", "-o", dir / "hill.vdb"}).exitCode, 0);

    const auto other = test::runGale({"probe", dir / "hill.toml", dir / "p.csv", "--vdb",
                                      dir / "flat.vdb", "-o", dir / "out/p.csv"});
    EXPECT_EQ(other.exitCode, 2) << other.describe();
    EXPECT_EQ(test::countLines(other.err), 1) << other.err;
    EXPECT_NE(other.err.find("solved over another terrain"), std::string::npos) << other.err;
    EXPECT_EQ(test::countFiles(dir / "out"), 0);

    const auto wind = test::runGale({"probe", dir / "windier.toml", dir / "p.csv", "--vdb",
                                     dir / "hill.vdb", "-o", dir / "w.csv"});
    EXPECT_EQ(wind.exitCode, 0) << wind.describe();
    EXPECT_NE(wind.err.find("warning: --vdb"), std::string::npos) << wind.err;
    EXPECT_NE(wind.err.find("another wind"), std::string::npos) << wind.err;
}

TEST(SceneField, ProbeRefusesAVdbOfAnotherCropOfTheSameDem) {
    TempDir dir;
    test::TestRaster r;
    r.cols = 40, r.rows = 40;
    const double x0 = 612000.0, y0 = 4830000.0, pixel = 2.0;
    const double gt[6] = {x0, pixel, 0.0, y0, 0.0, -pixel};
    std::copy(gt, gt + 6, r.gt);
    r.srs = "EPSG:32633";
    r.value = [&](int c, int row) { return 100.0 + 0.2 * c + 0.1 * row; };
    ASSERT_EQ(test::writeTestRaster(dir / "dem.tif", r), "");
    const std::string body = "[terrain]\nkind = \"dem\"\ndem = \"dem.tif\"\n";
    const std::string rest =
        "[wind]\nkind = \"solved\"\n[solver]\nvoxel_size_m = 4.0\n"
        "top_m = 160.0\n";
    // Two crops one pixel apart: grids of the same size, fields of other ground.
    test::writeFile(dir / "a.toml",
                    body + "crop_m = [612010.0, 4829930.0, 612050.0, 4829970.0]\n" + rest);
    test::writeFile(dir / "b.toml",
                    body + "crop_m = [612012.0, 4829930.0, 612052.0, 4829970.0]\n" + rest);
    test::writeFile(dir / "p.csv", "name,x,y,height_agl_m\nm,612030,4829950,5\n");
    ASSERT_EQ(test::runGale({"solve", dir / "a.toml", "-o", dir / "a.vdb"}).exitCode, 0);
    const auto r2 = test::runGale({"probe", dir / "b.toml", dir / "p.csv", "--vdb", dir / "a.vdb"});
    EXPECT_EQ(r2.exitCode, 2) << r2.describe();
    EXPECT_NE(r2.err.find("another crop"), std::string::npos) << r2.err;
}

TEST(SceneField, TheReportListsTheGridsTheFileHoldsAndTheLayers) {
    openvdb::initialize();
    TempDir dir;
    test::writeFile(dir / "cubes.toml", HILL_SCENE);
    test::writeFile(dir / "layers.toml",
                    std::string(HILL_SCENE) + "first_cell_m = 0.5\nstretch_ratio = 1.2\n");
    for (const char* scene : {"cubes", "layers"}) {
        const std::string vdb = dir / (std::string(scene) + ".vdb");
        const auto solve =
            test::runGale({"solve", dir / (std::string(scene) + ".toml"), "-o", vdb});
        ASSERT_EQ(solve.exitCode, 0) << solve.describe();
        const nlohmann::json j =
            nlohmann::json::parse(test::readFile(dir / (std::string(scene) + ".json")));
        std::set<std::string> listed, held;
        for (const auto& g : j["outputs"]["vdb"]["grids"]) {
            const std::string text = g.get<std::string>();
            listed.insert(text.substr(0, text.find(' ')));
        }
        openvdb::io::File file(vdb);
        file.open();
        for (auto it = file.beginName(); it != file.endName(); ++it) held.insert(*it);
        file.close();
        EXPECT_EQ(listed, held) << scene;
        const nlohmann::json& layers = j["domain"]["layers"];
        if (std::string(scene) == "layers") {
            EXPECT_EQ(layers["kind"], "stretched");
            EXPECT_NEAR(layers["first_cell_m"].get<double>(), 0.5, 1e-12);
            const auto levels = layers["z_levels_m"].get<std::vector<double>>();
            EXPECT_EQ(int(levels.size()), j["domain"]["cells"][2].get<int>() + 1);
            // The standard grids are the cubic resample: their voxels differ from the layers.
            EXPECT_NE(j["domain"]["vdb_voxels"][2], j["domain"]["cells"][2]);
            EXPECT_TRUE(held.count("velocity_layers")) << "stretched faces";
        } else {
            EXPECT_EQ(layers["kind"], "cubic");
            EXPECT_EQ(j["domain"]["vdb_voxels"], j["domain"]["cells"]);
        }
        EXPECT_EQ(j["provenance"]["model"], "mass_consistent");
        EXPECT_EQ(j["provenance"]["terrain_digest"].get<std::string>().size(), 16u);
    }
}

/// HILL_SCENE written to `dir` and loaded.
Scene loadHillScene(const TempDir& dir) {
    test::writeFile(dir / "hill.toml", HILL_SCENE);
    SceneRunOptions o;
    o.scenePath = dir / "hill.toml";
    return loadScene(o);
}

TEST(SceneField, TheLiveWindOnCoarserCellsIsTheScenesCompositionOnThoseCells) {
    TempDir dir;
    const Scene scene = loadHillScene(dir);
    const SceneTerrain terrain = buildTerrain(scene);
    const double h = scene.solver.domain.voxelSize_m;
    const LiveWindGrid grid = buildLiveWindGrid(scene, terrain.field, 2.0 * h);
    // The same as every verb's composition of the scene with solver.voxel_size_m doubled.
    Scene doubled = scene;
    doubled.solver.domain.voxelSize_m = 2.0 * h;
    const SceneField want = buildSceneField(doubled, terrain.field);
    ASSERT_TRUE(grid.domain);
    EXPECT_EQ(grid.domain->voxelSize_m(), 2.0 * h);
    EXPECT_EQ(grid.domain->nx(), want.domain->nx());
    EXPECT_EQ(grid.domain->nz(), want.domain->nz());
    EXPECT_EQ(grid.steady.u_mps(), want.field.u_mps());
    EXPECT_EQ(grid.steady.w_mps(), want.field.w_mps());
    // Stretched layers are refused, naming the key.
    Scene stretched = scene;
    stretched.solver.domain.firstCell_m = 0.5 * h;
    try {
        (void)buildLiveWindGrid(stretched, terrain.field, 2.0 * h);
        ADD_FAILURE() << "stretched layers were accepted";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("solver.first_cell_m"), std::string::npos) << e.what();
    }
}

TEST(SceneField, ProbeAtGrassHeightOverCutGroundReadsWhatTheGrassReads) {
    // The hill's slopes cut the first cells; at 0.25 m the grass reads the tangential law below
    // the solved faces (coupling/NearGround.h). A probe at a mesh vertex, 0.25 m up, must print
    // the grass sampler's velocity there.
    constexpr double GRASS_HEIGHT_M = 0.25;
    TempDir dir;
    const Scene scene = loadHillScene(dir);
    const SceneTerrain terrain = buildTerrain(scene);
    const SceneField f = buildSceneField(scene, terrain.field);
    ASSERT_TRUE(f.converged());
    const render::TerrainMesh mesh = coupling::buildTerrainMesh(terrain.field, 3.0f, 8);
    coupling::GrassSampler grass(mesh, GRASS_HEIGHT_M, nearGroundOf(scene));
    const std::vector<glm::vec3> v = grass.sample(f.field);
    std::string csv = "name,x,y,height_agl_m\n";
    std::vector<size_t> picked;
    for (size_t i = 0; i < mesh.wsPosition_m.size(); i += 7) {
        const glm::vec3& p = mesh.wsPosition_m[i];
        if (p.x <= 0.0f || p.y <= 0.0f || p.x >= 40.0f || p.y >= 40.0f) continue;
        char row[160];
        std::snprintf(row, sizeof row, "v%zu,%.9g,%.9g,%.9g\n", i, p.x, p.y, GRASS_HEIGHT_M);
        csv += row;
        picked.push_back(i);
    }
    test::writeFile(dir / "p.csv", csv);
    const auto probe = test::runGale({"probe", dir / "hill.toml", dir / "p.csv"});
    ASSERT_EQ(probe.exitCode, 0) << probe.describe();
    const auto rows = readCsv(probe.out);
    ASSERT_EQ(rows.size(), picked.size());
    int nearGround = 0, differsFromTrilinear = 0;
    for (size_t r = 0; r < rows.size(); ++r) {
        const glm::vec3& want = v[picked[r]];
        EXPECT_NEAR(std::stod(rows[r].at("u_mps")), want.x, PRINTED_TOLERANCE) << r;
        EXPECT_NEAR(std::stod(rows[r].at("v_mps")), want.y, PRINTED_TOLERANCE) << r;
        EXPECT_NEAR(std::stod(rows[r].at("w_mps")), want.z, PRINTED_TOLERANCE) << r;
        nearGround += rows[r].at("read") == "tangential";
        const glm::vec3& p = mesh.wsPosition_m[picked[r]];
        const auto tri = f.field.velocityAt_mps(p.x, p.y, p.z + GRASS_HEIGHT_M);
        differsFromTrilinear += std::abs(tri[0] - want.x) > 10 * PRINTED_TOLERANCE;
    }
    // The case tests what it claims: most points are read below the solved faces, where the
    // field's own trilinear value (what probe printed before) is another number.
    EXPECT_GT(nearGround, int(rows.size()) / 2) << probe.out;
    EXPECT_GT(differsFromTrilinear, int(rows.size()) / 2);
}

TEST(SceneField, APointOutsideTheTerrainKeepsItsRowWithAReason) {
    TempDir dir;
    test::writeFile(dir / "hill.toml", HILL_SCENE);
    test::writeFile(dir / "p.csv",
                    "name,x,y,height_agl_m\nin,10,20,2\nout,55,20,2\nhigh,10,20,500\n");
    const auto probe = test::runGale({"probe", dir / "hill.toml", dir / "p.csv"});
    ASSERT_EQ(probe.exitCode, 0) << probe.describe();
    const auto rows = readCsv(probe.out);
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[0].at("reason"), "");
    EXPECT_GT(std::stod(rows[0].at("speed_mps")), 0.0);
    EXPECT_EQ(rows[1].at("speed_mps"), "");
    EXPECT_NE(rows[1].at("reason").find("outside the terrain"), std::string::npos);
    EXPECT_NE(rows[2].at("reason").find("above the air domain's top"), std::string::npos);
    EXPECT_EQ(test::countLines(probe.err) >= 2, true);
    EXPECT_NE(probe.err.find("warning: " + std::string(dir / "p.csv") + ":3: out"),
              std::string::npos)
        << probe.err;
    // Every point outside: nothing to probe, refused.
    test::writeFile(dir / "q.csv", "name,x,y,height_agl_m\nout,55,20,2\n");
    const auto none = test::runGale({"probe", dir / "hill.toml", dir / "q.csv"});
    EXPECT_EQ(none.exitCode, 2) << none.describe();
}

TEST(SceneField, AMomentumSolvePrintsProgressAndAnInterruptedOneLeavesItsReport) {
    TempDir dir;
    // Enough pseudo-time steps that the solve is still running when the signal comes.
    test::writeFile(dir / "m.toml", std::string(HILL_SCENE) +
                                        "model = \"momentum\"\nmomentum_max_iterations = 100000\n"
                                        "momentum_coarse_levels = 0\n");
    gale::test::Child child({"solve", dir / "m.toml", "-o", dir / "out/w.vdb"}, {});
    const auto started = std::chrono::steady_clock::now();
    while (child.errSoFar().find("momentum: level") == std::string::npos &&
           std::chrono::steady_clock::now() - started < std::chrono::seconds(120))
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_NE(child.errSoFar().find("pseudo-time step"), std::string::npos) << child.errSoFar();
    child.signal(SIGTERM);
    const auto r = child.wait(120.0);
    EXPECT_EQ(r.exitCode, 143) << r.describe();
    EXPECT_FALSE(std::filesystem::exists(dir / "out/w.vdb"));
    const nlohmann::json j = nlohmann::json::parse(test::readFile(dir / "out/w.json"));
    EXPECT_TRUE(j["interrupted"].get<bool>());
    EXPECT_TRUE(j["momentum"]["stopped"].get<bool>());
    EXPECT_GE(j["momentum"]["history"].size(), 1u);
    EXPECT_FALSE(j["report"]["converged"].get<bool>());
}

}  // namespace
}  // namespace gale::app
