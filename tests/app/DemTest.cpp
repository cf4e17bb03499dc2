// DEM terrain through GDAL: GeoTIFFs and ASCII grids written by the test become heights at their
// own coordinates; geographic, unplaceable and empty DEMs are refused with the file and a fix.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "AppTestSupport.h"
#include "GeoTestSupport.h"
#include "app/io/Errors.h"
#include "app/scene/Dem.h"

namespace gale::app {
namespace {

using test::TempDir;
using test::TestRaster;

/// Heights of a few hundred metres stored as float32: 2^-15 m steps, so a few 1e-5 m of
/// rounding; 1e-3 m leaves room without hiding a pixel shift (which moves heights by >= 0.02 m).
constexpr double FLOAT_HEIGHT_TOLERANCE_M = 1e-3;
/// Coordinates are sums of a few exact binary fractions of metres: only double rounding.
constexpr double COORDINATE_TOLERANCE_M = 1e-6;

constexpr double X0 = 500000.0, Y0 = 5200000.0, PIXEL_M = 2.0;
constexpr int COLS = 20, ROWS = 16, BORDER = 2;

/// The terrain the test rasters sample: a tilted plane in the DEM's coordinates.
double plane_m(double x, double y) { return 300.0 + 0.01 * (x - X0) + 0.02 * (y - Y0); }

/// UTM zone 32N, origin (X0, Y0) at the top-left corner, north up, a 2-pixel nodata border.
TestRaster projectedWithBorder() {
    TestRaster r;
    r.cols = COLS, r.rows = ROWS;
    const double gt[6] = {X0, PIXEL_M, 0.0, Y0, 0.0, -PIXEL_M};
    std::copy(gt, gt + 6, r.gt);
    r.srs = "EPSG:32632";
    r.nodata = true;
    r.value = [](int col, int row) {
        if (col < BORDER || row < BORDER || col >= COLS - BORDER || row >= ROWS - BORDER)
            return test::TEST_NODATA;
        return plane_m(X0 + (col + 0.5) * PIXEL_M, Y0 - (row + 0.5) * PIXEL_M);
    };
    return r;
}

/// The whole raster at `path` (no crop window, stride 1).
DemSpec demAt(const std::filesystem::path& path) {
    DemSpec spec;
    spec.path = path.string();
    return spec;
}

std::string demError(const DemSpec& spec) {
    try {
        loadDem(spec);
    } catch (const ImageError& e) {
        return e.what();
    }
    return "";
}

void expectHeightsOnThePlane(const Dem& dem) {
    const sim::Heightfield& f = dem.field;
    for (int j = 0; j < f.ny; ++j)
        for (int i = 0; i < f.nx; ++i) {
            const double x = dem.georef.demX_m(f.originX_m + i * f.spacing_m);
            const double y = dem.georef.demY_m(f.originY_m + j * f.spacing_m);
            ASSERT_NEAR(f.at(i, j), plane_m(x, y), FLOAT_HEIGHT_TOLERANCE_M) << i << ", " << j;
        }
}

TEST(Dem, ProjectedGeoTiffWithNodataBorderGivesHeightsAtTheirCoordinates) {
    TempDir dir;
    ASSERT_EQ(test::writeTestRaster(dir / "dem.tif", projectedWithBorder()), "");
    const Dem dem = loadDem(demAt(dir / "dem.tif"));
    EXPECT_EQ(dem.field.nx, COLS - 2 * BORDER);
    EXPECT_EQ(dem.field.ny, ROWS - 2 * BORDER);
    EXPECT_EQ(dem.trimmedColumns, 2 * BORDER);
    EXPECT_EQ(dem.trimmedRows, 2 * BORDER);
    EXPECT_DOUBLE_EQ(dem.field.spacing_m, PIXEL_M);
    // Local (0, 0) is the centre of the lower-left kept pixel: column 2, row 13.
    EXPECT_NEAR(dem.georef.originX_m, X0 + 2.5 * PIXEL_M, COORDINATE_TOLERANCE_M);
    EXPECT_NEAR(dem.georef.originY_m, Y0 - (ROWS - BORDER - 0.5) * PIXEL_M, COORDINATE_TOLERANCE_M);
    EXPECT_NE(dem.georef.crsName.find("UTM zone 32N"), std::string::npos) << dem.georef.crsName;
    expectHeightsOnThePlane(dem);
}

TEST(Dem, CropWindowKeepsThePixelsWhoseCentresLieInside) {
    TempDir dir;
    ASSERT_EQ(test::writeTestRaster(dir / "dem.tif", projectedWithBorder()), "");
    // Centres at X0 + 11, 13, ..., 19 and Y0 - 11, ..., -19: five by five.
    const Dem dem = loadDem({dir / "dem.tif", CropWindow{X0 + 10, Y0 - 20, X0 + 20, Y0 - 10}});
    EXPECT_EQ(dem.field.nx, 5);
    EXPECT_EQ(dem.field.ny, 5);
    EXPECT_NEAR(dem.georef.originX_m, X0 + 11, COORDINATE_TOLERANCE_M);
    EXPECT_NEAR(dem.georef.originY_m, Y0 - 19, COORDINATE_TOLERANCE_M);
    expectHeightsOnThePlane(dem);
}

TEST(Dem, AsciiGridWithItsPrjIsReadLikeAGeoTiff) {
    TempDir dir;
    TestRaster r = projectedWithBorder();
    r.nodata = false;
    r.value = [](int col, int row) {
        return plane_m(X0 + (col + 0.5) * PIXEL_M, Y0 - (row + 0.5) * PIXEL_M);
    };
    ASSERT_EQ(test::writeTestRaster(dir / "dem.asc", r, "AAIGrid"), "");
    const Dem dem = loadDem(demAt(dir / "dem.asc"));
    EXPECT_EQ(dem.field.nx, COLS);
    EXPECT_EQ(dem.field.ny, ROWS);
    EXPECT_NEAR(dem.georef.originX_m, X0 + 0.5 * PIXEL_M, COORDINATE_TOLERANCE_M);
    expectHeightsOnThePlane(dem);
}

TEST(Dem, GeographicDemIsRefusedWithTheGdalwarpCommandForItsUtmZone) {
    TempDir dir;
    TestRaster r = projectedWithBorder();
    const double gt[6] = {10.0, 1e-4, 0.0, 47.0, 0.0, -1e-4};  // near 10.0 E, 47.0 N: UTM 32N
    std::copy(gt, gt + 6, r.gt);
    r.srs = "EPSG:4326";
    ASSERT_EQ(test::writeTestRaster(dir / "latlon.tif", r), "");
    const std::string e = demError(demAt(dir / "latlon.tif"));
    EXPECT_NE(e.find(dir / "latlon.tif"), std::string::npos) << e;
    EXPECT_NE(e.find("geographic"), std::string::npos) << e;
    EXPECT_NE(e.find("gdalwarp -t_srs EPSG:32632"), std::string::npos) << e;
}

TEST(Dem, UtmZoneOfALongitude) {
    EXPECT_EQ(utmZone(-180.0), 1);
    EXPECT_EQ(utmZone(9.99), 32);
    EXPECT_EQ(utmZone(179.99), 60);
    EXPECT_EQ(utmEpsg(10.0, 47.0), 32632);
    EXPECT_EQ(utmEpsg(-70.0, -33.0), 32719);
}

TEST(Dem, BadDemsAreRefusedNamingTheFileAndTheReason) {
    TempDir dir;
    struct Case {
        const char* name;
        std::string srs;
        std::function<double(int, int)> value;
        const char* reason;
    };
    const std::string localCs = "LOCAL_CS[\"site grid\",UNIT[\"metre\",1]]";
    const Case cases[] = {
        {"nocrs.tif", "", projectedWithBorder().value, "has no coordinate system"},
        {"local.tif", localCs, projectedWithBorder().value, "neither projected nor geographic"},
        {"empty.tif", "EPSG:32632", [](int, int) { return test::TEST_NODATA; }, "is nodata"},
        {"hole.tif", "EPSG:32632",
         [](int c, int r) { return c == 7 && r == 5 ? test::TEST_NODATA : 1.0; },
         "nodata inside the data at pixel column 7, row 5 (x 500015, y 5199989)"},
        {"huge.tif", "EPSG:32632", [](int, int) { return 1e9; }, "absurd height"},
    };
    for (const Case& c : cases) {
        TestRaster r = projectedWithBorder();
        r.srs = c.srs;
        r.value = c.value;
        ASSERT_EQ(test::writeTestRaster(dir / c.name, r), "") << c.name;
        const std::string e = demError(demAt(dir / c.name));
        EXPECT_EQ(e.rfind(dir / c.name + ": ", 0), 0u) << e;
        EXPECT_NE(e.find(c.reason), std::string::npos) << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
    EXPECT_NE(demError(demAt(dir / "missing.tif")).find("no such file"), std::string::npos);
    test::writeFile(dir / "text.tif", "not a raster\n");
    EXPECT_NE(demError(demAt(dir / "text.tif")).find("not a raster GDAL can read"),
              std::string::npos);
}

}  // namespace
}  // namespace gale::app
