// Turbulence out (issue 24, item 5), run as a user runs gale: the momentum model's k,
// turbulence intensity and gust in gale probe's table (from the solve and from the .vdb gale
// solve wrote, which must agree to float precision), in the .vdb and the GeoTIFF bands; the
// mass-consistent model, which has no turbulence, leaves the columns empty and says so.

#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "AppTestSupport.h"
#include "ProbeTestSupport.h"
#include "app/scene/Dem.h"

namespace gale::app {
namespace {

using test::readCsv;
using test::TempDir;

/// Probe prints k and the intensity with 6 decimals, speeds and gusts with 4: half a unit of the
/// last decimal of each column a formula combines, and of the result.
constexpr double PRINTED_6 = 5e-7, PRINTED_4 = 5e-5;
/// The peak factor the docs state for the gust column (docs/cli.md; EN 1991-1-4 expression 4.8).
constexpr double PEAK_FACTOR = 3.5;

/// 24 m x 8 m of flat meadow in 1 m cubes up to 16 m, the momentum model with its mixing length.
const char* MOMENTUM_SCENE = R"(
[terrain]
kind = "flat"
size_m = [24.0, 8.0]
spacing_m = 1.0
[wind]
kind = "solved"
speed_mps = 5.0
reference_height_m = 10.0
from_deg = 270.0
profile = "log"
roughness_m = 0.03
[solver]
voxel_size_m = 1.0
top_m = 16.0
model = "momentum"
)";

const char* POINTS = "name,x,y,height_agl_m\ngrass,12,4,0.5\nmast,12,4,2\nhigh,18,4,6\n";

double num(const std::map<std::string, std::string>& row, const char* column) {
    return std::stod(row.at(column));
}

TEST(TurbulenceOut, ProbeGivesKIntensityAndGustAndReadsTheSameKBackFromTheVdb) {
    TempDir dir;
    test::writeFile(dir / "m.toml", MOMENTUM_SCENE);
    test::writeFile(dir / "p.csv", POINTS);
    const auto direct =
        test::runGale({"probe", dir / "m.toml", dir / "p.csv", "-o", dir / "a.csv"});
    ASSERT_EQ(direct.exitCode, 0) << direct.describe();
    const auto solve =
        test::runGale({"solve", dir / "m.toml", "-o", dir / "out/w.vdb", "--grid-height-m", "2"});
    ASSERT_EQ(solve.exitCode, 0) << solve.describe();
    const auto fromVdb = test::runGale(
        {"probe", dir / "m.toml", dir / "p.csv", "-o", dir / "b.csv", "--vdb", dir / "out/w.vdb"});
    ASSERT_EQ(fromVdb.exitCode, 0) << fromVdb.describe();
    EXPECT_EQ(fromVdb.err.find("no turbulence"), std::string::npos) << fromVdb.err;
    const auto a = readCsv(test::readFile(dir / "a.csv")),
               b = readCsv(test::readFile(dir / "b.csv"));
    ASSERT_EQ(a.size(), 3u);
    ASSERT_EQ(b.size(), a.size());
    for (size_t i = 0; i < a.size(); ++i) {
        const double k = num(a[i], "tke_m2ps2"), speed = num(a[i], "speed_mps");
        EXPECT_GT(k, 0.0) << a[i].at("name");
        // The derived columns from their definitions and the columns beside them.
        const double sigma = std::sqrt(2.0 * k / 3.0);
        const double dSigma = PRINTED_6 / (3.0 * sigma);  // d sqrt(2k/3) / dk times the rounding
        EXPECT_NEAR(num(a[i], "turbulence_intensity"), sigma / speed,
                    PRINTED_6 + (dSigma + sigma * PRINTED_4 / speed) / speed);
        EXPECT_NEAR(num(a[i], "gust_mps"), speed + PEAK_FACTOR * sigma,
                    2 * PRINTED_4 + PEAK_FACTOR * dSigma);
        // The .vdb holds k as floats (relative 6e-8, far below the printed 1e-6): the same table.
        EXPECT_NEAR(num(b[i], "tke_m2ps2"), k, 2 * PRINTED_6) << a[i].at("name");
    }
    // The solve's report lists the grid and the bands.
    const nlohmann::json report = nlohmann::json::parse(test::readFile(dir / "out/w.json"));
    bool listed = false;
    for (const auto& g : report["outputs"]["vdb"]["grids"])
        listed = listed || g.get<std::string>().rfind("tke (float, m^2/s^2", 0) == 0;
    EXPECT_TRUE(listed) << report["outputs"]["vdb"]["grids"].dump();
    ASSERT_EQ(report["outputs"]["rasters"].size(), 1u);
    EXPECT_EQ(report["outputs"]["rasters"][0]["bands"].size(), 5u);

    // The GeoTIFF: bands 3-5 are k, the intensity and the gust of band 1's speed, pixel by pixel.
    constexpr double FLOAT_REL = 1e-6;  // float32 bands
    ensureGdalRegistered();
    std::unique_ptr<GDALDataset, void (*)(GDALDataset*)> ds(
        GDALDataset::Open((dir / "out/w_2m.tif").c_str(), GDAL_OF_RASTER),
        [](GDALDataset* d) { GDALClose(d); });
    ASSERT_TRUE(ds);
    ASSERT_EQ(ds->GetRasterCount(), 5);
    const int nx = ds->GetRasterXSize(), ny = ds->GetRasterYSize();
    std::vector<std::vector<float>> band(5, std::vector<float>(size_t(nx) * ny));
    for (int bnd = 0; bnd < 5; ++bnd)
        ASSERT_EQ(ds->GetRasterBand(bnd + 1)->RasterIO(GF_Read, 0, 0, nx, ny, band[bnd].data(), nx,
                                                       ny, GDT_Float32, 0, 0, nullptr),
                  CE_None);
    EXPECT_STREQ(ds->GetRasterBand(3)->GetDescription(), "tke_m2ps2");
    EXPECT_STREQ(ds->GetRasterBand(5)->GetDescription(), "gust_mps");
    for (size_t p = 0; p < band[0].size(); ++p) {
        const double speed = band[0][p], k = band[2][p], sigma = std::sqrt(2.0 * k / 3.0);
        ASSERT_GT(k, 0.0) << p;
        EXPECT_NEAR(band[3][p], sigma / speed, FLOAT_REL * 4 * sigma / speed) << p;
        EXPECT_NEAR(band[4][p], speed + PEAK_FACTOR * sigma, FLOAT_REL * 4 * band[4][p]) << p;
    }
}

TEST(TurbulenceOut, AMassConsistentSceneLeavesTheColumnsEmptyAndSaysSo) {
    TempDir dir;
    test::writeFile(dir / "flat.toml", test::FLAT_PROBE_SCENE);
    test::writeFile(dir / "p.csv", POINTS);
    const auto r = test::runGale({"probe", dir / "flat.toml", dir / "p.csv", "-o", dir / "a.csv"});
    ASSERT_EQ(r.exitCode, 0) << r.describe();
    EXPECT_NE(r.err.find("the mass-consistent model has no turbulence"), std::string::npos)
        << r.err;
    const auto rows = readCsv(test::readFile(dir / "a.csv"));
    ASSERT_EQ(rows.size(), 3u);
    for (const auto& row : rows) {
        EXPECT_GT(num(row, "speed_mps"), 0.0);
        for (const char* c : {"tke_m2ps2", "turbulence_intensity", "gust_mps"})
            EXPECT_EQ(row.at(c), "") << c;  // no k is invented
    }
    // Its .vdb has no tke grid, and probe --vdb says so too.
    const auto solve = test::runGale({"solve", dir / "flat.toml", "-o", dir / "out/w.vdb"});
    ASSERT_EQ(solve.exitCode, 0) << solve.describe();
    const nlohmann::json report = nlohmann::json::parse(test::readFile(dir / "out/w.json"));
    for (const auto& g : report["outputs"]["vdb"]["grids"])
        EXPECT_EQ(g.get<std::string>().find("tke"), std::string::npos);
    const auto v = test::runGale({"probe", dir / "flat.toml", dir / "p.csv", "-o", dir / "b.csv",
                                  "--vdb", dir / "out/w.vdb"});
    ASSERT_EQ(v.exitCode, 0) << v.describe();
    EXPECT_NE(v.err.find("holds no tke grid"), std::string::npos) << v.err;
}

}  // namespace
}  // namespace gale::app
