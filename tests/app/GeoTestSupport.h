#pragma once
// GeoTIFFs written by the tests themselves through GDAL (so the oracle is GDAL's own writer, not
// gale's reader), and the coordinate systems they use.

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <functional>
#include <string>
#include <vector>

#include "app/scene/Dem.h"

namespace gale::app::test {

/// The value written into nodata pixels.
inline constexpr double TEST_NODATA = -9999.0;

/// What a test GeoTIFF holds: size, geotransform, coordinate system and one height per pixel.
struct TestRaster {
    int cols = 0, rows = 0;
    double gt[6] = {0, 1, 0, 0, 0, -1};  ///< GDAL geotransform
    std::string srs;                     ///< "EPSG:32632", a WKT, or "" for none
    bool nodata = false;                 ///< set TEST_NODATA as the band's nodata value
    std::function<double(int col, int row)> value;
};

/// Writes `r` as a one-band float32 GeoTIFF (or, with driver "AAIGrid", an ESRI ASCII grid with
/// its .prj) at `path`; returns "" or GDAL's error.
inline std::string writeTestRaster(const std::string& path, const TestRaster& r,
                                   const char* driverName = "GTiff") {
    ensureGdalRegistered();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driverName);
    if (!driver) return std::string("no GDAL driver ") + driverName;
    std::vector<float> data(static_cast<size_t>(r.cols) * r.rows);
    for (int row = 0; row < r.rows; ++row)
        for (int col = 0; col < r.cols; ++col)
            data[static_cast<size_t>(row) * r.cols + col] = static_cast<float>(r.value(col, row));
    // AAIGrid has no Create: write through an in-memory dataset and CreateCopy.
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    GDALDataset* ds = mem->Create("", r.cols, r.rows, 1, GDT_Float32, nullptr);
    if (!ds) return CPLGetLastErrorMsg();
    double gt[6];
    for (int i = 0; i < 6; ++i) gt[i] = r.gt[i];
    ds->SetGeoTransform(gt);
    if (!r.srs.empty()) {
        OGRSpatialReference srs;
        srs.SetFromUserInput(r.srs.c_str());
        ds->SetSpatialRef(&srs);
    }
    GDALRasterBand* band = ds->GetRasterBand(1);
    if (r.nodata) band->SetNoDataValue(TEST_NODATA);
    CPLErr err = band->RasterIO(GF_Write, 0, 0, r.cols, r.rows, data.data(), r.cols, r.rows,
                                GDT_Float32, 0, 0, nullptr);
    std::string result;
    if (err != CE_None) result = CPLGetLastErrorMsg();
    GDALDataset* out = driver->CreateCopy(path.c_str(), ds, FALSE, nullptr, nullptr, nullptr);
    if (!out) result = CPLGetLastErrorMsg();
    GDALClose(out);
    GDALClose(ds);
    return result;
}

}  // namespace gale::app::test
