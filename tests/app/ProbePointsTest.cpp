// Probe points through GDAL/OGR (app/scene/ProbePoints.h), run as a user runs gale probe: a CSV
// with a byte order mark, CR line ends, quoted names and extra columns; GeoJSON points in
// latitude and longitude over a UTM DEM, reprojected; results written as RFC 4180 CSV and as a
// GeoPackage that OGR reads back.

#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "AppTestSupport.h"
#include "GeoTestSupport.h"

namespace gale::app {
namespace {

using test::TempDir;

/// Probe output is printed with 4 decimals: half a unit of the last one.
constexpr double PRINTED_TOLERANCE = 5e-5;

const char* FLAT_SCENE = R"(
[terrain]
kind = "flat"
size_m = [20.0, 20.0]
spacing_m = 1.0
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

/// The cells of an RFC 4180 CSV (quotes doubled inside quoted cells).
std::vector<std::vector<std::string>> parseCsv(const std::string& text) {
    std::vector<std::vector<std::string>> rows(1, std::vector<std::string>(1));
    bool quoted = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"')
                rows.back().back() += '"', ++i;
            else if (c == '"')
                quoted = false;
            else
                rows.back().back() += c;
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            rows.back().emplace_back();
        } else if (c == '\n') {
            rows.emplace_back(1);
        } else {
            rows.back().back() += c;
        }
    }
    if (rows.back().size() == 1 && rows.back()[0].empty()) rows.pop_back();
    return rows;
}

TEST(ProbePoints, ACsvWithABomCrLinesQuotesAndExtraColumnsRoundTrips) {
    TempDir dir;
    test::writeFile(dir / "flat.toml", FLAT_SCENE);
    test::writeFile(dir / "p.csv",
                    "\xEF\xBB\xBFname,x,y,height_agl_m,owner\r"
                    "\"mast, north\",5,15,10,\"Ann \"\"the surveyor\"\"\"\r"
                    "# a comment row\r"
                    "south,5,5,10,Bob\r");
    const auto r = test::runGale({"probe", dir / "flat.toml", dir / "p.csv", "-o", dir / "o.csv"});
    ASSERT_EQ(r.exitCode, 0) << r.describe();
    const auto rows = parseCsv(test::readFile(dir / "o.csv"));
    ASSERT_EQ(rows.size(), 3u) << test::readFile(dir / "o.csv");
    const std::vector<std::string>& header = rows[0];
    ASSERT_EQ(header.back(), "owner");
    EXPECT_EQ(header[0], "name");  // the byte order mark is not part of the first name
    EXPECT_EQ(rows[1][0], "mast, north");
    EXPECT_EQ(rows[1].back(), "Ann \"the surveyor\"");
    EXPECT_EQ(rows[2][0], "south");
    EXPECT_EQ(rows[2].back(), "Bob");
    for (size_t i = 1; i < rows.size(); ++i) ASSERT_EQ(rows[i].size(), header.size());
}

TEST(ProbePoints, GeoJsonInLatitudeAndLongitudeIsReprojectedToTheDem) {
    TempDir dir;
    test::TestRaster dem;
    dem.cols = 30, dem.rows = 30;
    const double x0 = 500000.0, y0 = 5200000.0, pixel = 4.0;  // UTM 32N, near 9 E 46.9 N
    const double gt[6] = {x0, pixel, 0.0, y0, 0.0, -pixel};
    std::copy(gt, gt + 6, dem.gt);
    dem.srs = "EPSG:32632";
    dem.value = [](int, int) { return 300.0; };
    ASSERT_EQ(test::writeTestRaster(dir / "dem.tif", dem), "");
    test::writeFile(dir / "dem.toml",
                    "[terrain]\nkind = \"dem\"\ndem = \"dem.tif\"\n[wind]\nkind = \"solved\"\n"
                    "[solver]\nvoxel_size_m = 4.0\ntop_m = 360.0\n");
    // The point (500060, 5199940) in UTM 32N, given in WGS 84 through OGR's own transform.
    ensureGdalRegistered();
    OGRSpatialReference utm, wgs;
    utm.SetFromUserInput("EPSG:32632");
    wgs.SetFromUserInput("EPSG:4326");
    utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    wgs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&utm, &wgs));
    ASSERT_TRUE(t);
    double lon = 500060.0, lat = 5199940.0;
    ASSERT_TRUE(t->Transform(1, &lon, &lat));
    char json[512];
    std::snprintf(json, sizeof json,
                  R"({"type": "FeatureCollection", "features": [{"type": "Feature",
                      "properties": {"name": "m1", "height_agl_m": 10},
                      "geometry": {"type": "Point", "coordinates": [%.12f, %.12f]}}]})",
                  lon, lat);
    test::writeFile(dir / "p.geojson", json);
    const auto r = test::runGale({"probe", dir / "dem.toml", dir / "p.geojson"});
    ASSERT_EQ(r.exitCode, 0) << r.describe();
    const auto rows = parseCsv(r.out);
    ASSERT_EQ(rows.size(), 2u) << r.out;
    EXPECT_NEAR(std::stod(rows[1][1]), 500060.0, 1e-3);
    EXPECT_NEAR(std::stod(rows[1][2]), 5199940.0, 1e-3);
    EXPECT_NEAR(std::stod(rows[1][3]), 310.0, 1e-3);  // ground 300 m + 10 m
}

TEST(ProbePoints, AGeoPackageOutputHoldsOnePointFeaturePerPoint) {
    TempDir dir;
    test::writeFile(dir / "flat.toml", FLAT_SCENE);
    test::writeFile(dir / "p.csv", "name,x,y,height_agl_m\na,5,15,10\nb,15,5,2\n");
    const auto csv = test::runGale({"probe", dir / "flat.toml", dir / "p.csv"});
    ASSERT_EQ(csv.exitCode, 0) << csv.describe();
    const auto gpkg =
        test::runGale({"probe", dir / "flat.toml", dir / "p.csv", "-o", dir / "o.gpkg"});
    ASSERT_EQ(gpkg.exitCode, 0) << gpkg.describe();
    const auto rows = parseCsv(csv.out);
    ensureGdalRegistered();
    GDALDataset* ds = GDALDataset::FromHandle(
        GDALOpenEx((dir / "o.gpkg").c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
    ASSERT_NE(ds, nullptr);
    OGRLayer* layer = ds->GetLayer(0);
    ASSERT_EQ(layer->GetFeatureCount(), 2);
    int n = 1;
    for (auto& f : *layer) {
        const OGRPoint* p = f->GetGeometryRef()->toPoint();
        EXPECT_NEAR(p->getX(), std::stod(rows[size_t(n)][1]), PRINTED_TOLERANCE);
        EXPECT_NEAR(p->getY(), std::stod(rows[size_t(n)][2]), PRINTED_TOLERANCE);
        EXPECT_STREQ(f->GetFieldAsString("name"), rows[size_t(n)][0].c_str());
        EXPECT_NEAR(f->GetFieldAsDouble("speed_mps"), std::stod(rows[size_t(n)][8]),
                    PRINTED_TOLERANCE);
        ++n;
    }
    GDALClose(ds);
    // An extension no single-file OGR driver writes is refused before any work.
    const auto shp =
        test::runGale({"probe", dir / "flat.toml", dir / "p.csv", "-o", dir / "out/o.shp"});
    EXPECT_EQ(shp.exitCode, 2) << shp.describe();
    EXPECT_EQ(test::countFiles(dir / "out"), 0);
}

TEST(ProbePoints, AReferenceNameGivenTwiceIsRefused) {
    TempDir dir;
    test::writeFile(dir / "flat.toml", FLAT_SCENE);
    test::writeFile(dir / "p.csv", "name,x,y,height_agl_m\na,5,15,10\na,15,5,2\n");
    const auto r = test::runGale({"probe", dir / "flat.toml", dir / "p.csv", "--reference", "a"});
    EXPECT_EQ(r.exitCode, 2) << r.describe();
    EXPECT_NE(r.err.find("2 points are named 'a'"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace gale::app
