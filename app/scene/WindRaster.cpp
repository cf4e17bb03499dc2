/// \file WindRaster.cpp
/// GeoTIFF and ASCII-grid wind at a height above ground (WindRaster.h).

#include "app/scene/WindRaster.h"

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "app/io/AtomicFile.h"
#include "base/Numbers.h"
#include "coupling/Turbulence.h"
#include "sim/AmbientWind.h"

namespace gale::app {
namespace {

namespace fs = std::filesystem;

using gale::PI;

GDALDataset* memoryRaster(int nx, int ny, int bands, const double gt[6], const Georeference& g) {
    ensureGdalRegistered();
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    GDALDataset* ds = mem->Create("", nx, ny, bands, GDT_Float32, nullptr);
    if (!ds) throw std::runtime_error(std::string("cannot make a raster: ") + CPLGetLastErrorMsg());
    double t[6];
    for (int i = 0; i < 6; ++i) t[i] = gt[i];
    ds->SetGeoTransform(t);
    if (g.georeferenced()) {
        OGRSpatialReference srs;
        srs.importFromWkt(g.crsWkt.c_str());
        ds->SetSpatialRef(&srs);
    }
    return ds;
}

/// Copies `ds` to `path` with `driver` through a temporary name in the same folder, so a reader
/// never sees half a file; the side files GDAL writes (.prj) are renamed with it.
void copyTo(GDALDataset* ds, const char* driverName, const std::string& path,
            std::vector<std::string>& written) {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driverName);
    const fs::path target(path);
    const std::string tmp = temporaryPathFor(path);
    const fs::path tmpPath(tmp);
    // GDAL picks side-file names from the extension: keep it last.
    const fs::path tmpWithExt = tmpPath.string() + target.extension().string();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    GDALDataset* out = driver->CreateCopy(tmpWithExt.c_str(), ds, FALSE, nullptr, nullptr, nullptr);
    const std::string why = CPLGetLastErrorMsg();
    CPLPopErrorHandler();
    if (!out) throw std::runtime_error(path + ": cannot write (" + why + ")");
    GDALClose(out);
    const fs::path prjTmp = fs::path(tmpWithExt).replace_extension(".prj");
    std::error_code ec;
    fs::remove(fs::path(tmpWithExt).string() + ".aux.xml", ec);
    if (fs::exists(prjTmp)) {
        const fs::path prj = fs::path(target).replace_extension(".prj");
        fs::rename(prjTmp, prj);
        written.push_back(prj.string());
    }
    fs::rename(tmpWithExt, target);
    written.push_back(path);
}

}  // namespace

std::vector<std::string> writeWindRasters(const sim::WindField& field, const sim::Heightfield& t,
                                          const Georeference& g, double height_m,
                                          const std::string& stem,
                                          const std::vector<double>& tke_m2ps2) {
    const int nx = t.nx, ny = t.ny;
    const bool turbulent = !tke_m2ps2.empty();
    std::vector<float> speed(static_cast<size_t>(nx) * ny), from(speed.size());
    std::vector<float> tke(turbulent ? speed.size() : 0), intensity(tke.size()), gust(tke.size());
    const float nodata = static_cast<float>(WIND_RASTER_NODATA);
    for (int row = 0; row < ny; ++row) {
        const int j = ny - 1 - row;  // north-up: the first row is the far edge
        for (int i = 0; i < nx; ++i) {
            const double x = t.originX_m + i * t.spacing_m, y = t.originY_m + j * t.spacing_m;
            const double z = t.at(i, j) + height_m;
            const size_t n = static_cast<size_t>(row) * nx + i;
            const auto top = field.wsMin_m()[2] + field.nz() * field.voxelSize_m();
            if (!(z < top)) {
                speed[n] = from[n] = nodata;
                if (turbulent) tke[n] = intensity[n] = gust[n] = nodata;
                continue;
            }
            const auto v = field.velocityAt_mps(x, y, z);
            speed[n] = static_cast<float>(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
            sim::AmbientWind a;
            a.direction_deg = degreesFromRadians(std::atan2(v[1], v[0]));
            from[n] = std::hypot(v[0], v[1]) > 1e-9 ? static_cast<float>(a.from_deg())
                                                    : static_cast<float>(WIND_RASTER_NODATA);
            if (turbulent) {
                const double k = coupling::sampleTke_m2ps2(field, tke_m2ps2, x, y, z);
                const double ti = coupling::turbulenceIntensity(k, double(speed[n]));
                tke[n] = std::isfinite(k) ? static_cast<float>(k) : nodata;
                intensity[n] = std::isfinite(ti) ? static_cast<float>(ti) : nodata;
                gust[n] = std::isfinite(k)
                              ? static_cast<float>(coupling::gustSpeed_mps(double(speed[n]), k))
                              : nodata;
            }
        }
    }
    const double h = t.spacing_m;
    const double gt[6] = {g.demX_m(t.originX_m) - 0.5 * h,
                          h,
                          0.0,
                          g.demY_m(t.originY_m + (ny - 1) * h) + 0.5 * h,
                          0.0,
                          -h};
    std::vector<std::string> written;
    auto fill = [&](GDALDataset* ds, int band, std::vector<float>& data, const char* what) {
        GDALRasterBand* b = ds->GetRasterBand(band);
        b->SetNoDataValue(WIND_RASTER_NODATA);
        b->SetDescription(what);
        if (b->RasterIO(GF_Write, 0, 0, nx, ny, data.data(), nx, ny, GDT_Float32, 0, 0, nullptr) !=
            CE_None)
            throw std::runtime_error(stem + ": cannot fill the raster band " + what);
    };
    // The GeoTIFF holds both bands; an ASCII grid holds one, the speed.
    for (const bool tiff : {true, false}) {
        GDALDataset* ds = memoryRaster(nx, ny, tiff ? (turbulent ? 5 : 2) : 1, gt, g);
        try {
            fill(ds, 1, speed, "speed_mps");
            if (tiff) fill(ds, 2, from, "from_deg");
            if (tiff && turbulent) {
                fill(ds, 3, tke, "tke_m2ps2");
                fill(ds, 4, intensity, "turbulence_intensity");
                fill(ds, 5, gust, "gust_mps");
            }
            copyTo(ds, tiff ? "GTiff" : "AAIGrid", stem + (tiff ? ".tif" : ".asc"), written);
        } catch (...) {
            GDALClose(ds);
            throw;
        }
        GDALClose(ds);
    }
    return written;
}

}  // namespace gale::app
