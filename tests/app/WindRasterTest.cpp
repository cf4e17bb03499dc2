// gale solve --grid-height-m: the wind at a height above a DEM as a GeoTIFF and an ASCII grid,
// read back through GDAL: the DEM's coordinate system, a geotransform with pixel centres on the
// DEM's samples, and values that match the log law (flat ground) and gale probe at the same cell.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "AppTestSupport.h"
#include "GeoTestSupport.h"

namespace gale::app {
namespace {

using test::TempDir;

/// The bound against the analytic log law (here the profile's own reference height).
constexpr double LOG_LAW_RELATIVE_TOLERANCE = 0.01;
/// Raster values are float32, probe values printed to 4 decimals.
constexpr double FLOAT_VS_PRINTED_TOLERANCE = 1e-4;

constexpr double X0 = 431000.0, Y0 = 6102000.0, PIXEL_M = 2.0, GROUND_M = 100.0;
constexpr int COLS = 24, ROWS = 20;

struct Closer {
    void operator()(GDALDataset* d) const { GDALClose(d); }
};

TEST(WindRaster, GeoTiffAndAsciiGridCarryTheDemsCrsGeotransformAndTheWind) {
    TempDir dir;
    test::TestRaster r;
    r.cols = COLS, r.rows = ROWS;
    const double gt[6] = {X0, PIXEL_M, 0.0, Y0, 0.0, -PIXEL_M};
    std::copy(gt, gt + 6, r.gt);
    r.srs = "EPSG:32631";
    r.nodata = true;
    r.value = [](int c, int) {
        return c == 0 ? test::TEST_NODATA : GROUND_M;
    };  // west column trimmed
    ASSERT_EQ(test::writeTestRaster(dir / "dem.tif", r), "");
    test::writeFile(dir / "s.toml",
                    "[terrain]\nkind = \"dem\"\ndem = \"dem.tif\"\n[wind]\nkind = \"solved\"\n"
                    "speed_mps = 5.0\nreference_height_m = 10.0\nfrom_deg = 270.0\n"
                    "[solver]\nvoxel_size_m = 1.0\ntop_m = 140.0\n");
    const auto run =
        test::runGale({"solve", dir / "s.toml", "-o", dir / "out/w.vdb", "--grid-height-m", "10"});
    ASSERT_EQ(run.exitCode, 0) << run.describe();
    const std::string report = test::readFile(dir / "out/w.json");
    for (const char* listed : {"w_10m.tif", "w_10m.asc", "velocity_faces"})
        EXPECT_NE(report.find(listed), std::string::npos) << listed;

    ensureGdalRegistered();
    for (const char* name : {"out/w_10m.tif", "out/w_10m.asc"}) {
        std::unique_ptr<GDALDataset, Closer> ds(
            GDALDataset::Open((dir / name).c_str(), GDAL_OF_RASTER));
        ASSERT_TRUE(ds) << name;
        EXPECT_EQ(ds->GetRasterXSize(), COLS - 1) << name;
        EXPECT_EQ(ds->GetRasterYSize(), ROWS) << name;
        OGRSpatialReference utm31;
        utm31.importFromEPSG(32631);
        ASSERT_NE(ds->GetSpatialRef(), nullptr) << name;
        EXPECT_TRUE(ds->GetSpatialRef()->IsSame(&utm31)) << name;
        double out[6];
        ASSERT_EQ(ds->GetGeoTransform(out), CE_None);
        // The DEM's own pixels, less the trimmed west column (ASCII grids store 1e-? rounding).
        EXPECT_NEAR(out[0], X0 + PIXEL_M, 1e-6) << name;
        EXPECT_NEAR(out[3], Y0, 1e-6) << name;
        EXPECT_NEAR(out[1], PIXEL_M, 1e-9) << name;
        EXPECT_NEAR(out[5], -PIXEL_M, 1e-9) << name;
        // Flat ground: 10 m above it the log profile's reference speed, 5 m/s, from the west.
        float speed = 0.f;
        ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Read, 11, 9, 1, 1, &speed, 1, 1, GDT_Float32, 0,
                                                 0, nullptr),
                  CE_None);
        EXPECT_NEAR(speed, 5.0, LOG_LAW_RELATIVE_TOLERANCE * 5.0) << name;
        if (ds->GetRasterCount() == 2) {
            float from = 0.f;
            ASSERT_EQ(ds->GetRasterBand(2)->RasterIO(GF_Read, 11, 9, 1, 1, &from, 1, 1, GDT_Float32,
                                                     0, 0, nullptr),
                      CE_None);
            EXPECT_NEAR(from, 270.0, 0.5);
            // The same cell through gale probe, by its DEM coordinates (pixel centre).
            const double px = out[0] + 11.5 * out[1], py = out[3] + 9.5 * out[5];
            std::ostringstream csv;
            csv.precision(12);
            csv << "x,y,height_agl_m\n" << px << "," << py << ",10\n";
            test::writeFile(dir / "p.csv", csv.str());
            const auto probe =
                test::runGale({"probe", dir / "s.toml", dir / "p.csv", "--vdb", dir / "out/w.vdb"});
            ASSERT_EQ(probe.exitCode, 0) << probe.describe();
            const std::string row = probe.out.substr(probe.out.find('\n') + 1);
            std::istringstream cells(row);
            std::string cell;
            for (int i = 0; i < 9; ++i) std::getline(cells, cell, ',');  // ... speed_mps
            EXPECT_NEAR(std::stod(cell), speed, FLOAT_VS_PRINTED_TOLERANCE) << probe.out;
        }
    }
}

}  // namespace
}  // namespace gale::app
