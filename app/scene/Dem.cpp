/// \file Dem.cpp
/// GDAL terrain reader (Dem.h).

#include "app/scene/Dem.h"

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <system_error>
#include <vector>

#include "app/io/Errors.h"
#include "app/scene/GdalSupport.h"
#include "app/scene/SceneParser.h"
#include "base/Numbers.h"

namespace gale::app {
namespace {

namespace fs = std::filesystem;

/// Relative difference allowed between a pixel's width and height before it counts as not
/// square: GeoTIFFs written from metre grids carry ~1e-12 of rounding.
constexpr double SQUARE_PIXEL_TOLERANCE = 1e-6;
/// Largest |height| accepted, metres (ten times Everest's height above the sea bed).
constexpr double MAX_ABS_HEIGHT_M = 1e5;

[[noreturn]] void fail(const std::string& path, const std::string& reason) {
    throw ImageError(path + ": " + reason);
}

std::string num(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

DatasetPtr openRaster(const std::string& path) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) fail(path, "no such file");
    if (fs::is_directory(st)) fail(path, "is a folder, not a DEM");
    if (fs::is_regular_file(st) && fs::file_size(path, ec) == 0)
        fail(path, "empty file, not a DEM");
    ensureGdalRegistered();
    QuietGdal quiet;
    DatasetPtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!ds) fail(path, "not a raster GDAL can read (" + gdalMessage() + ")");
    if (ds->GetRasterCount() < 1) fail(path, "the raster has no bands");
    return ds;
}

/// An image format that holds pictures rather than rasters with a coordinate system (the
/// newcomer's heightmap given as a DEM).
bool plainImage(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".gif" ||
           ext == ".exr" || ext == ".tga";
}

/// Largest departure of a projection's scale factor from 1 that gale takes as metres: UTM's is at
/// most 0.1 % inside its zone; Web Mercator's 1 / cos(latitude) is 1.0001 at 0.8 degrees and
/// 1.47 at 47 degrees, where a hill would be taken 1.47 times too large.
constexpr double MAX_SCALE_FACTOR_ERROR = 0.01;

/// Refuses a Mercator-family projection (Web Mercator, Mercator 1SP / 2SP) whose scale factor at
/// the DEM's centre is more than MAX_SCALE_FACTOR_ERROR from 1: its "metres" are not metres on
/// the ground there. The fix named is a runnable gdalwarp to the centre's UTM zone.
void checkScaleFactor(const std::string& path, const OGRSpatialReference& srs,
                      const std::string& crsName, const double gt[6], int cols, int rows) {
    const char* projection = srs.GetAttrValue("PROJECTION");
    const std::string name = projection ? projection : "";
    if (name.find("Mercator") == std::string::npos ||
        name.find("Transverse") != std::string::npos || name.find("Oblique") != std::string::npos ||
        name.find("Hotine") != std::string::npos)
        return;
    double x = gt[0] + 0.5 * cols * gt[1] + 0.5 * rows * gt[2];
    double y = gt[3] + 0.5 * cols * gt[4] + 0.5 * rows * gt[5];
    OGRSpatialReference geographic;
    if (geographic.CopyGeogCSFrom(&srs) != OGRERR_NONE) return;
    geographic.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    OGRSpatialReference source(srs);
    source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    const std::unique_ptr<OGRCoordinateTransformation> toGeographic(
        OGRCreateCoordinateTransformation(&source, &geographic));
    if (!toGeographic || !toGeographic->Transform(1, &x, &y)) return;
    const double lon = x, lat = y;
    if (!(std::isfinite(lat) && std::abs(lat) < 89.0)) return;
    // Mercator's scale factor grows as 1 / cos(latitude) away from its true-scale parallel:
    // k = k0 / cos(lat) (1SP, Web Mercator) or cos(lat_ts) / cos(lat) (2SP).
    constexpr double DEG = 3.14159265358979323846 / 180.0;
    const double k0 = name.find("2SP") != std::string::npos
                          ? std::cos(srs.GetProjParm(SRS_PP_STANDARD_PARALLEL_1, 0.0) * DEG)
                          : srs.GetProjParm(SRS_PP_SCALE_FACTOR, 1.0);
    const double k = k0 / std::cos(lat * DEG);
    if (std::abs(k - 1.0) <= MAX_SCALE_FACTOR_ERROR) return;
    fail(path, "coordinate system '" + crsName +
                   "' is a Mercator projection whose scale factor at "
                   "the DEM's centre (latitude " +
                   num(lat) + ") is " + num(k) +
                   ": its metres are not metres on the ground there, so every distance would be " +
                   num(k) + " times too large; reproject it first: gdalwarp -t_srs EPSG:" +
                   std::to_string(utmEpsg(lon, lat)) + " -r bilinear " + path +
                   " dem_utm.tif (UTM zone " + std::to_string(utmZone(lon)) +
                   (lat >= 0 ? "N" : "S") + ")");
}

/// Refuses coordinate systems gale cannot use as metres on a plane, saying how to fix it.
Georeference checkCrs(const std::string& path, GDALDataset& ds, const double gt[6]) {
    const OGRSpatialReference* srs = ds.GetSpatialRef();
    if (!srs || srs->IsEmpty())
        fail(path, "has no coordinate system; give it one, e.g. gdal_edit.py -a_srs EPSG:32632 " +
                       path + " (a GeoTIFF), or put a .prj file beside an ASCII grid" +
                       (plainImage(path)
                            ? "; a plain heightmap image is kind = \"heightmap\" with image = "
                              "\"" +
                                  fs::path(path).filename().string() +
                                  "\" and metres_per_pixel, height_scale_m"
                            : std::string()));
    const char* name = srs->GetName();
    const std::string crsName = name ? name : "unnamed";
    const int cols = ds.GetRasterXSize(), rows = ds.GetRasterYSize();
    if (srs->IsGeographic()) {
        const double lon = gt[0] + 0.5 * cols * gt[1] + 0.5 * rows * gt[2];
        const double lat = gt[3] + 0.5 * cols * gt[4] + 0.5 * rows * gt[5];
        std::string fix = "gdalwarp -t_srs EPSG:<UTM zone> -r bilinear " + path + " dem_utm.tif";
        if (std::isfinite(lon) && std::isfinite(lat) && std::abs(lat) <= 84.0)
            fix = "gdalwarp -t_srs EPSG:" + std::to_string(utmEpsg(lon, lat)) + " -r bilinear " +
                  path + " dem_utm.tif (UTM zone " + std::to_string(utmZone(lon)) +
                  (lat >= 0 ? "N" : "S") + ")";
        fail(path, "coordinate system '" + crsName +
                       "' is geographic (latitude/longitude); gale needs metres on a plane: "
                       "reproject it first, e.g. " +
                       fix);
    }
    if (!srs->IsProjected())
        fail(path,
             "coordinate system '" + crsName +
                 "' is neither projected nor geographic (a local or engineering system "
                 "gale cannot place); assign the real one with gdal_edit.py -a_srs EPSG:NNNN");
    const char* unitName = nullptr;
    const double unit_m = srs->GetLinearUnits(&unitName);
    if (!(std::abs(unit_m - 1.0) < 1e-9))
        fail(path, "coordinate system '" + crsName + "' measures in " +
                       std::string(unitName ? unitName : "unknown units") + " (" + num(unit_m) +
                       " m); gale needs metres: gdalwarp -t_srs with a metre-based system");
    checkScaleFactor(path, *srs, crsName, gt, cols, rows);
    Georeference g;
    char* wkt = nullptr;
    const char* options[] = {"FORMAT=WKT2", nullptr};
    if (srs->exportToWkt(&wkt, options) != OGRERR_NONE || !wkt) {
        CPLFree(wkt);
        fail(path, "coordinate system '" + crsName + "' cannot be written as WKT");
    }
    g.crsWkt = wkt;
    CPLFree(wkt);
    g.crsName = crsName;
    return g;
}

/// The pixel columns or rows [first, last] whose centres lie in [lo, hi] along one axis with
/// pixel centres at start + (index + 0.5) * step.
std::pair<int, int> windowAlong(double start, double step, int count, double lo, double hi) {
    int first = count, last = -1;
    for (int n = 0; n < count; ++n) {
        const double c = start + (n + 0.5) * step;
        if (c >= lo && c <= hi) first = std::min(first, n), last = std::max(last, n);
    }
    return {first, last};
}

}  // namespace

void ensureGdalRegistered() {
    static std::once_flag once;
    std::call_once(once, [] { GDALAllRegister(); });
}

int utmZone(double longitude_deg) {
    const double lon = std::fmod(std::fmod(longitude_deg + 180.0, 360.0) + 360.0, 360.0);
    return std::clamp(static_cast<int>(std::floor(lon / 6.0)) + 1, 1, 60);
}

int utmEpsg(double longitude_deg, double latitude_deg) {
    return (latitude_deg >= 0.0 ? 32600 : 32700) + utmZone(longitude_deg);
}

Dem loadDem(const DemSpec& spec) {
    const std::string& path = spec.path;
    DatasetPtr ds = openRaster(path);
    double gt[6];
    if (ds->GetGeoTransform(gt) != CE_None)
        fail(path, "has no geotransform (pixel size and position); a DEM needs one");
    Dem dem;
    dem.georef = checkCrs(path, *ds, gt);
    if (gt[2] != 0.0 || gt[4] != 0.0)
        fail(path, "the grid is rotated; resample it north-up first: gdalwarp " + path +
                       " dem_north_up.tif");
    const double pixelW = gt[1], pixelH = std::abs(gt[5]);
    if (!(pixelW > 0.0) || !(pixelH > 0.0) || !std::isfinite(pixelW) || !std::isfinite(pixelH))
        fail(path, "the geotransform gives pixels of " + num(pixelW) + " x " + num(gt[5]) +
                       " m, not a positive size: its georeferencing is broken; export it again "
                       "from its source");
    if (std::abs(pixelW - pixelH) > SQUARE_PIXEL_TOLERANCE * pixelW) {
        // The finer of the two sides, so the resample loses nothing.
        const double side = std::min(pixelW, pixelH);
        fail(path, "pixels are " + num(pixelW) + " x " + num(pixelH) +
                       " m; gale needs square pixels: gdalwarp -tr " + num(side) + " " + num(side) +
                       " -r bilinear " + path + " dem_square.tif");
    }
    const int cols = ds->GetRasterXSize(), rows = ds->GetRasterYSize();

    // The window: every pixel, or those whose centres lie in the crop rectangle.
    int c0 = 0, c1 = cols - 1, r0 = 0, r1 = rows - 1;
    if (spec.crop) {
        const CropWindow& w = *spec.crop;
        const auto [ca, cb] = windowAlong(gt[0], gt[1], cols, w.minX_m, w.maxX_m);
        const auto [ra, rb] = windowAlong(gt[3], gt[5], rows, w.minY_m, w.maxY_m);
        const std::string extent = "[" + num(gt[0]) + ", " + num(gt[3] + rows * gt[5]) + ", " +
                                   num(gt[0] + cols * gt[1]) + ", " + num(gt[3]) + "]";
        if (cb - ca < 1 || rb - ra < 1)
            fail(path, "the crop window holds fewer than 2 x 2 pixel centres; the raster covers " +
                           extent + " (min x, min y, max x, max y)");
        c0 = ca, c1 = cb, r0 = ra, r1 = rb;
    }
    const int wc = c1 - c0 + 1, wr = r1 - r0 + 1;
    const std::string dims = std::to_string(wc) + " x " + std::to_string(wr);
    if (wc < 2 || wr < 2)
        fail(path, "too small for a DEM (" + dims + " pixels; need at least 2 x 2)");
    if (wc > MAX_SAMPLES_PER_SIDE || wr > MAX_SAMPLES_PER_SIDE)
        fail(path,
             "too large (" + dims + " pixels; at most " + std::to_string(MAX_SAMPLES_PER_SIDE) +
                 " per side): crop it (terrain.crop_m) or resample it: gdalwarp -tr " +
                 num(pixelW * std::ceil(double(std::max(wc, wr)) / MAX_SAMPLES_PER_SIDE)) + " " +
                 num(pixelW * std::ceil(double(std::max(wc, wr)) / MAX_SAMPLES_PER_SIDE)) +
                 " -r bilinear " + path + " dem_coarse.tif");
    const double bytes = estimateTerrainBytes(wc, wr, std::max(1, spec.meshStride));
    if (bytes > MAX_TERRAIN_BYTES)
        fail(path, "a " + dims + " DEM and its render mesh need about " + formatBytes(bytes) +
                       "; at most " + formatBytes(MAX_TERRAIN_BYTES) +
                       " (raise terrain.mesh_stride, crop or resample)");

    std::vector<double> value(static_cast<size_t>(wc) * wr);
    GDALRasterBand* band = ds->GetRasterBand(1);
    int hasNodata = 0;
    const double nodata = band->GetNoDataValue(&hasNodata);
    {
        QuietGdal quiet;
        if (band->RasterIO(GF_Read, c0, r0, wc, wr, value.data(), wc, wr, GDT_Float64, 0, 0,
                           nullptr) != CE_None)
            fail(path, "cannot read the heights (" + gdalMessage() + ")");
    }
    auto missing = [&](int c, int r) {
        const double v = value[static_cast<size_t>(r) * wc + c];
        return std::isnan(v) || (hasNodata && v == nodata);
    };

    // Trim edge rows and columns that hold only nodata; refuse nodata left inside.
    int ca = wc, cb = -1, ra = wr, rb = -1;
    for (int r = 0; r < wr; ++r)
        for (int c = 0; c < wc; ++c)
            if (!missing(c, r)) {
                ca = std::min(ca, c), cb = std::max(cb, c);
                ra = std::min(ra, r), rb = std::max(rb, r);
            }
    if (cb < 0)
        fail(path, std::string("every height in the ") + (spec.crop ? "crop window" : "raster") +
                       " is nodata");
    if (cb - ca < 1 || rb - ra < 1)
        fail(path, "fewer than 2 x 2 pixels hold data (the rest is nodata)");
    for (int r = ra; r <= rb; ++r)
        for (int c = ca; c <= cb; ++c)
            if (missing(c, r))
                fail(path, "nodata inside the data at pixel column " + std::to_string(c0 + c) +
                               ", row " + std::to_string(r0 + r) + " (x " +
                               num(gt[0] + (c0 + c + 0.5) * gt[1]) + ", y " +
                               num(gt[3] + (r0 + r + 0.5) * gt[5]) +
                               "); gale does not invent heights: crop inside the data "
                               "(terrain.crop_m) or fill the holes first (gdal_fillnodata.py)");
    dem.trimmedColumns = wc - (cb - ca + 1);
    dem.trimmedRows = wr - (rb - ra + 1);

    const int nx = cb - ca + 1, ny = rb - ra + 1;
    std::vector<float> height_m(static_cast<size_t>(nx) * ny);
    for (int r = ra; r <= rb; ++r) {
        // North-up rasters (negative pixel height) list the far edge first.
        const int j = gt[5] < 0.0 ? rb - r : r - ra;
        for (int c = ca; c <= cb; ++c) {
            const double z = value[static_cast<size_t>(r) * wc + c];
            if (!(std::abs(z) <= MAX_ABS_HEIGHT_M))
                fail(path, "pixel column " + std::to_string(c0 + c) + ", row " +
                               std::to_string(r0 + r) + " holds an absurd height of " + num(z) +
                               " m (at most " + num(MAX_ABS_HEIGHT_M) + " m in magnitude)");
            height_m[static_cast<size_t>(j) * nx + (c - ca)] = static_cast<float>(z);
        }
    }
    // Local (0, 0): the centre of the lower-left kept pixel.
    const int lowRow = gt[5] < 0.0 ? r0 + rb : r0 + ra;
    dem.georef.originX_m = gt[0] + (c0 + ca + 0.5) * gt[1];
    dem.georef.originY_m = gt[3] + (lowRow + 0.5) * gt[5];
    try {
        dem.field = sim::makeHeightfield(nx, ny, pixelW, std::move(height_m));
    } catch (const std::invalid_argument& e) {
        fail(path, e.what());
    }
    return dem;
}

std::optional<double> gridNorthBearing_deg(const Georeference& geo, double demX_m, double demY_m) {
    if (!geo.georeferenced()) return std::nullopt;
    ensureGdalRegistered();
    QuietGdal quiet;
    OGRSpatialReference projected;
    if (projected.importFromWkt(geo.crsWkt.c_str()) != OGRERR_NONE) return std::nullopt;
    projected.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRSpatialReference> geographic(projected.CloneGeogCS());
    if (!geographic) return std::nullopt;
    geographic->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // longitude, latitude
    std::unique_ptr<OGRCoordinateTransformation> toGeographic(
        OGRCreateCoordinateTransformation(&projected, geographic.get()));
    if (!toGeographic) return std::nullopt;
    // Two points a short step apart along the grid's +y: the bearing of that step on the sphere
    // (east of north positive) is the grid convergence there.
    constexpr double STEP_M = 100.0;
    double x[2] = {demX_m, demX_m}, y[2] = {demY_m, demY_m + STEP_M};
    if (!toGeographic->Transform(2, x, y)) return std::nullopt;
    const double lat = radiansFromDegrees(0.5 * (y[0] + y[1]));
    const double east = radiansFromDegrees(x[1] - x[0]) * std::cos(lat);
    const double north = radiansFromDegrees(y[1] - y[0]);
    if (!std::isfinite(east) || !std::isfinite(north) || (east == 0.0 && north == 0.0))
        return std::nullopt;
    return degreesFromRadians(std::atan2(east, north));
}

}  // namespace gale::app
