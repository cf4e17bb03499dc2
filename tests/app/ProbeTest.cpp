// gale probe and the meteorological wind direction, run as a user runs them: probe speeds over
// flat ground against the log law computed here, DEM coordinates round-tripping through a probe,
// bad probe tables and bad DEMs refused with one line and nothing written.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "AppTestSupport.h"
#include "GeoTestSupport.h"
#include "app/scene/SceneBuilder.h"
#include "sim/AirDomain.h"
#include "sim/SteadyWind.h"

namespace gale::app {
namespace {

using test::TempDir;

/// The issue's bound for probes against the analytic log law.
constexpr double LOG_LAW_RELATIVE_TOLERANCE = 0.01;
/// Probe output is printed with 4 decimals: half a unit of the last one.
constexpr double PRINTED_TOLERANCE = 5e-5;

/// The CSV's rows as maps from column name to text.
std::vector<std::map<std::string, std::string>> readCsv(const std::string& text) {
    std::istringstream in(text);
    std::string line;
    std::vector<std::string> header;
    std::vector<std::map<std::string, std::string>> rows;
    while (std::getline(in, line)) {
        std::vector<std::string> cells;
        std::string cell;
        std::istringstream ls(line);
        while (std::getline(ls, cell, ',')) cells.push_back(cell);
        if (!line.empty() && line.back() == ',') cells.push_back("");
        if (header.empty()) {
            header = cells;
            continue;
        }
        std::map<std::string, std::string> row;
        for (size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
        rows.push_back(row);
    }
    return rows;
}

const char* FLAT_SCENE = R"(
[terrain]
kind = "flat"
size_m = [20.0, 20.0]
spacing_m = 1.0
[wind]
kind = "solved"
speed_mps = 5.0
reference_height_m = 10.0
from_deg = 270.0
profile = "log"
roughness_m = 0.03
[solver]
voxel_size_m = 0.5
top_m = 70.0
)";

TEST(Probe, FlatGroundWithALogProfileGivesTheLogLawAt2And10And50Metres) {
    TempDir dir;
    test::writeFile(dir / "flat.toml", FLAT_SCENE);
    test::writeFile(dir / "masts.csv",
                    "name,x,y,height_agl_m\nm2,10,10,2\nm10,10,10,10\nm50,10,10,50\n");
    const auto r =
        test::runGale({"probe", dir / "flat.toml", dir / "masts.csv", "-o", dir / "out.csv"});
    ASSERT_EQ(r.exitCode, 0) << r.describe();
    const auto rows = readCsv(test::readFile(dir / "out.csv"));
    ASSERT_EQ(rows.size(), 3u);
    for (const auto& row : rows) {
        const double z = std::stod(row.at("height_agl_m"));
        // Neutral log law through 5 m/s at 10 m over z0 = 0.03 m, computed here.
        const double expected = 5.0 * std::log(z / 0.03) / std::log(10.0 / 0.03);
        const double speed = std::stod(row.at("speed_mps"));
        EXPECT_NEAR(speed, expected, LOG_LAW_RELATIVE_TOLERANCE * expected) << row.at("name");
        // from 270 (a west wind) blows along +x.
        EXPECT_NEAR(std::stod(row.at("from_deg")), 270.0, 0.01) << row.at("name");
        EXPECT_NEAR(std::stod(row.at("speedup")), speed / expected - 1.0, 2 * PRINTED_TOLERANCE);
    }
}

TEST(Probe, DemCoordinatesAndHeightsRoundTripThroughAProbe) {
    TempDir dir;
    test::TestRaster r;
    r.cols = 24, r.rows = 20;
    const double x0 = 612000.0, y0 = 4830000.0, pixel = 2.0;
    const double gt[6] = {x0, pixel, 0.0, y0, 0.0, -pixel};
    std::copy(gt, gt + 6, r.gt);
    r.srs = "EPSG:32633";
    r.nodata = true;
    auto plane = [&](double x, double y) { return 150.0 + 0.05 * (x - x0) - 0.03 * (y - y0); };
    r.value = [&](int c, int row) {
        if (c == 0 || row == 0) return test::TEST_NODATA;
        return plane(x0 + (c + 0.5) * pixel, y0 - (row + 0.5) * pixel);
    };
    ASSERT_EQ(test::writeTestRaster(dir / "dem.tif", r), "");
    test::writeFile(dir / "dem.toml",
                    "[terrain]\nkind = \"dem\"\ndem = \"dem.tif\"\n[wind]\nkind = \"solved\"\n"
                    "[solver]\nvoxel_size_m = 2.0\ntop_m = 200.0\n");
    const double px = x0 + 21.0, py = y0 - 17.0;  // inside the data, between pixel centres
    test::writeFile(dir / "p.csv", "name,x,y,height_agl_m\nmast," + std::to_string(px) + "," +
                                       std::to_string(py) + ",10\n");
    const auto run = test::runGale({"probe", dir / "dem.toml", dir / "p.csv"});
    ASSERT_EQ(run.exitCode, 0) << run.describe();
    const auto rows = readCsv(run.out);
    ASSERT_EQ(rows.size(), 1u) << run.out;
    EXPECT_NEAR(std::stod(rows[0].at("x")), px, PRINTED_TOLERANCE);
    EXPECT_NEAR(std::stod(rows[0].at("y")), py, PRINTED_TOLERANCE);
    // The ground under the mast is the plane there (bilinear interpolation of a plane is exact);
    // float heights of ~150 m round at 1e-5 m.
    EXPECT_NEAR(std::stod(rows[0].at("z_m")) - 10.0, plane(px, py), 1e-3);
    EXPECT_GT(std::stod(rows[0].at("speed_mps")), 0.0);

    const auto check = test::runGale({"check", dir / "dem.toml"});
    ASSERT_EQ(check.exitCode, 0) << check.describe();
    EXPECT_NE(check.out.find("UTM zone 33N"), std::string::npos) << check.out;
    EXPECT_NE(check.out.find("covers x 612003.00 .. 612047.00"), std::string::npos) << check.out;
}

TEST(Probe, BadProbeRowsExitTwoNamingFileAndLineAndWriteNothing) {
    TempDir dir;
    test::writeFile(dir / "flat.toml", FLAT_SCENE);
    struct Case {
        const char* csv;
        const char* message;
    };
    const Case cases[] = {
        {"x,y,height_agl_m\n1,1,2\n1,zz,2\n", "masts.csv:3: y: not a decimal number (got 'zz')"},
        {"x,y,height_agl_m\n1,0x10,2\n", "masts.csv:2: y: not a decimal number (got '0x10')"},
        {"x,y,height_agl_m\n1,1,1e-320\n",
         "masts.csv:2: height_agl_m: not a finite normal number (got '1e-320')"},
        {"x,y,x,height_agl_m\n1,1,1,2\n", "masts.csv:1: column 'x' is given twice"},
        {"name,x,y,height_agl_m\n\"a\x1b\",1,1,2\n",
         "masts.csv:2: name: holds a control character (byte 0x1b)"},
        {"x,y,height_agl_m\n1,1\n", "masts.csv:2: expected 3 values, got 2"},
        {"x,y,height_agl_m\n\n25,1,2\n",
         "masts.csv:3: point (25.000, 1.000) is outside the terrain"},
        {"x,y,z_m\n5,5,-1\n", "masts.csv:2: point is not above the ground"},
        {"x,y\n5,5\n", "masts.csv:1: the header must name exactly one of height_agl_m"},
        {"x,y,speed\n1,1,2\n", "masts.csv:1: the header must name exactly one of height_agl_m"},
    };
    for (const Case& c : cases) {
        test::writeFile(dir / "masts.csv", c.csv);
        const auto r =
            test::runGale({"probe", dir / "flat.toml", dir / "masts.csv", "-o", dir / "out/p.csv"});
        EXPECT_EQ(r.exitCode, 2) << r.describe();
        EXPECT_EQ(test::countLines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
        EXPECT_EQ(test::countFiles(dir / "out"), 0);
    }
}

TEST(Probe, BadDemsExitTwoWithOneLineNamingTheFileAndWriteNothing) {
    TempDir dir;
    test::TestRaster r;
    r.cols = 8, r.rows = 8;
    const double gt[6] = {1000.0, 1.0, 0.0, 2000.0, 0.0, -1.0};
    std::copy(gt, gt + 6, r.gt);
    r.nodata = true;
    struct Case {
        std::string srs;
        double value;
        const char* reason;
    };
    const Case cases[] = {
        {"", 1.0, "has no coordinate system"},
        {"LOCAL_CS[\"mine\",UNIT[\"metre\",1]]", 1.0, "neither projected nor geographic"},
        {"EPSG:32632", test::TEST_NODATA, "every height in the raster is nodata"}};
    for (const Case& c : cases) {
        r.srs = c.srs;
        const double v = c.value;
        r.value = [v](int, int) { return v; };
        ASSERT_EQ(test::writeTestRaster(dir / "bad.tif", r), "");
        test::writeFile(dir / "s.toml", "[terrain]\nkind = \"dem\"\ndem = \"bad.tif\"\n");
        const auto run = test::runGale({"solve", dir / "s.toml", "-o", dir / "out/w.vdb"});
        EXPECT_EQ(run.exitCode, 2) << run.describe();
        EXPECT_EQ(test::countLines(run.err), 1) << run.err;
        EXPECT_NE(run.err.find("bad.tif: "), std::string::npos) << run.err;
        EXPECT_NE(run.err.find(c.reason), std::string::npos) << run.err;
        EXPECT_EQ(test::countFiles(dir / "out"), 0);
    }
}

TEST(FromDeg, MeteorologicalAndMathematicalDirectionsGiveTheSameField) {
    const std::string base =
        "[terrain]\nkind = \"gaussian_hill\"\nsize_m = [16.0, 16.0]\nspacing_m = 0.5\n"
        "[wind]\nkind = \"solved\"\n";
    const Scene met = parseSceneString(base + "from_deg = 210.0\n", "met.toml");
    const Scene math = parseSceneString(base + "direction_deg = 60.0\n", "math.toml");
    // 210 from = towards bearing 30 = 60 counter-clockwise from +x (to double rounding).
    EXPECT_NEAR(met.wind.ambient.direction_deg, 60.0, 1e-12);
    const sim::Heightfield field = buildHeightfield(met);
    sim::DomainSpec spec;
    spec.voxelSize_m = 1.0;
    const sim::AirDomain domain(field, spec);
    const auto a =
        sim::solveSteadyWind(domain, met.wind.ambient, met.solver.weights, met.solver.settings);
    const auto b =
        sim::solveSteadyWind(domain, math.wind.ambient, math.solver.weights, math.solver.settings);
    double worst = 0.0;
    for (size_t i = 0; i < a.field.u_mps().size(); ++i)
        worst = std::max(worst, std::abs(a.field.u_mps()[i] - b.field.u_mps()[i]));
    for (size_t i = 0; i < a.field.v_mps().size(); ++i)
        worst = std::max(worst, std::abs(a.field.v_mps()[i] - b.field.v_mps()[i]));
    // Same direction to 1e-12 deg: the fields agree to the solver's rounding.
    EXPECT_LT(worst, 1e-9);
    EXPECT_NE(test::errorOf(base + "from_deg = 10.0\ndirection_deg = 5.0\n").find("not both"),
              std::string::npos);
}

TEST(FromDeg, CheckPrintsBothConventions) {
    TempDir dir;
    test::writeFile(dir / "s.toml",
                    "[terrain]\nkind = \"flat\"\nsize_m = [10.0, 10.0]\n[wind]\nkind = "
                    "\"solved\"\nfrom_deg = 210.0\n");
    const auto r = test::runGale({"check", dir / "s.toml"});
    ASSERT_EQ(r.exitCode, 0) << r.describe();
    EXPECT_NE(r.out.find("from 210 deg = towards 30 deg, counter-clockwise from +x 60 deg"),
              std::string::npos)
        << r.out;
}

/// `gale probe` of FLAT_SCENE at `masts` (CSV text) into dir/out.csv against `reference`.
test::RunResult probeFlatAgainst(const TempDir& dir, const std::string& masts,
                                 const std::string& reference) {
    test::writeFile(dir / "flat.toml", FLAT_SCENE);
    test::writeFile(dir / "masts.csv", masts);
    return test::runGale({"probe", dir / "flat.toml", dir / "masts.csv", "-o", dir / "out.csv",
                          "--reference", reference});
}

TEST(Probe, ReferencePointGivesSpeedupsAgainstItsOwnSpeed) {
    TempDir dir;
    const auto r =
        probeFlatAgainst(dir, "name,x,y,height_agl_m\nref,10,10,10\nhigh,10,10,40\n", "ref");
    ASSERT_EQ(r.exitCode, 0) << r.describe();
    const auto rows = readCsv(test::readFile(dir / "out.csv"));
    ASSERT_EQ(rows.size(), 2u);
    const double ref = std::stod(rows[0].at("speed_mps")),
                 high = std::stod(rows[1].at("speed_mps"));
    EXPECT_NEAR(std::stod(rows[0].at("speedup")), 0.0, PRINTED_TOLERANCE);
    // The speed-up against the reference, from the printed speeds (each rounded to 4 decimals).
    EXPECT_NEAR(std::stod(rows[1].at("speedup")), high / ref - 1.0, 4 * PRINTED_TOLERANCE);
    // And the log law's ratio between 40 m and 10 m over z0 = 0.03 m, computed here.
    const double lawRatio = std::log(40.0 / 0.03) / std::log(10.0 / 0.03);
    EXPECT_NEAR(high / ref, lawRatio, LOG_LAW_RELATIVE_TOLERANCE * lawRatio);
}

TEST(Probe, AnUnknownReferenceIsExitTwoNamingTheOptionAndWritesNothing) {
    TempDir dir;
    const auto r = probeFlatAgainst(dir, "name,x,y,height_agl_m\nref,10,10,10\n", "nope");
    EXPECT_EQ(r.exitCode, 2) << r.describe();
    EXPECT_NE(r.err.find("--reference: no point named 'nope'"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.csv"));
}

/// A small unsteady scene: 20 m of flat ground in 1 m cells, 1 s in outputs every 0.5 s.
const char* UNSTEADY_SCENE = R"(
[terrain]
kind = "flat"
size_m = [20.0, 20.0]
spacing_m = 1.0
[wind]
kind = "unsteady"
speed_mps = 5.0
profile = "log"
roughness_m = 0.03
[solver]
voxel_size_m = 1.0
top_m = 12.0
[unsteady]
duration_s = 1.0
output_every_s = 0.5
)";

TEST(Probe, AnUnsteadySceneGivesOneRowPerPointAndOutputTimeAsTheSequenceFromSolve) {
    // docs/cli.md: stepped and sampled at t = 0, every output_every_s and the end, the same
    // times as the .vdb sequence gale solve writes, and --vdb over that sequence gives the same
    // series (the files hold the face velocities as floats).
    constexpr double FLOAT_FACES_TOLERANCE_MPS = 1e-3;  // 4 printed decimals + float storage
    TempDir dir;
    test::writeFile(dir / "u.toml", UNSTEADY_SCENE);
    test::writeFile(dir / "p.csv", "name,x,y,height_agl_m\na,5,10,2\nb,15,10,6\n");
    const auto stepped =
        test::runGale({"probe", dir / "u.toml", dir / "p.csv", "-o", dir / "s.csv"});
    ASSERT_EQ(stepped.exitCode, 0) << stepped.describe();
    const auto solve = test::runGale({"solve", dir / "u.toml", "-o", dir / "seq/w.vdb"});
    ASSERT_EQ(solve.exitCode, 0) << solve.describe();
    const auto read =
        test::runGale({"probe", dir / "u.toml", dir / "p.csv", "-o", dir / "v.csv", "--vdb",
                       dir / "seq/w_0000.vdb", dir / "seq/w_0001.vdb", dir / "seq/w_0002.vdb"});
    ASSERT_EQ(read.exitCode, 0) << read.describe();
    const auto a = readCsv(test::readFile(dir / "s.csv")),
               b = readCsv(test::readFile(dir / "v.csv"));
    ASSERT_EQ(a.size(), 6u) << "2 points x 3 times (0, 0.5, 1 s)";
    ASSERT_EQ(b.size(), a.size());
    const double times[] = {0.0, 0.0, 0.5, 0.5, 1.0, 1.0};
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_NEAR(std::stod(a[i].at("t_s")), times[i], PRINTED_TOLERANCE) << i;
        EXPECT_NEAR(std::stod(b[i].at("t_s")), times[i], PRINTED_TOLERANCE) << i;
        EXPECT_EQ(a[i].at("name"), b[i].at("name"));
        const double speed = std::stod(a[i].at("speed_mps"));
        EXPECT_TRUE(std::isfinite(speed) && speed > 0.0) << i;
        EXPECT_NEAR(std::stod(b[i].at("speed_mps")), speed, FLOAT_FACES_TOLERANCE_MPS) << i;
    }
}

TEST(WindRaster, AnUnsteadySceneIsRefusedWithExitTwoBeforeAnyWork) {
    // docs/cli.md: rasters are for steady scenes; an unsteady one would need a raster per time.
    TempDir dir;
    test::writeFile(dir / "u.toml", UNSTEADY_SCENE);
    const auto r =
        test::runGale({"solve", dir / "u.toml", "-o", dir / "out/w.vdb", "--grid-height-m", "2"});
    EXPECT_EQ(r.exitCode, 2) << r.describe();
    EXPECT_EQ(test::countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("--grid-height-m: rasters are written for steady scenes only"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

}  // namespace
}  // namespace gale::app
