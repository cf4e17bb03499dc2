#pragma once
/// \file Dem.h
/// Terrain from a georeferenced raster (GeoTIFF, ESRI ASCII grid, or anything else GDAL reads),
/// with its coordinate system and geotransform (docs/scene-format.md, "DEM terrain").
///
/// Coordinates. A DEM's coordinates are large (UTM eastings are ~500 000 m), too large for the
/// float positions of the render mesh and the OpenVDB transforms. Inside gale the terrain is
/// therefore moved to a local frame: local (0, 0) is the centre of the DEM's lower-left kept
/// pixel (after crop and nodata trimming), local x = DEM x - originX_m, local y = DEM y -
/// originY_m, heights unchanged. Every coordinate gale reports, reads (probes) or writes
/// (GeoTIFF / ASCII grid) adds the offset back, so users only ever see the DEM's coordinates.
///
/// Policies (decided here, documented in docs/scene-format.md):
/// - the coordinate system must be projected with metre units; geographic (latitude/longitude)
///   DEMs are refused with the gdalwarp command that moves them to their UTM zone;
/// - pixels must be square and the grid north-up (no rotation);
/// - nodata: rows and columns at the edges that hold only nodata are trimmed away; nodata left
///   inside the kept rectangle is refused (gale does not invent heights), naming the first cell.

#include <array>
#include <optional>
#include <string>

#include "sim/Heightfield.h"

namespace gale::app {

/// Where a terrain sits in the coordinate system of the file it came from. Procedural terrains
/// and PNG heightmaps have none (crsWkt empty, zero offset).
struct Georeference {
    std::string crsWkt;      ///< the DEM's coordinate system as WKT; empty: not georeferenced
    std::string crsName;     ///< e.g. "WGS 84 / UTM zone 32N"
    double originX_m = 0.0;  ///< DEM x of local x = 0 (the local frame's offset), metres
    double originY_m = 0.0;  ///< DEM y of local y = 0, metres
    bool georeferenced() const { return !crsWkt.empty(); }
    /// DEM coordinates of a local point, metres.
    double demX_m(double localX_m) const { return localX_m + originX_m; }
    double demY_m(double localY_m) const { return localY_m + originY_m; }
};

/// A crop window in the DEM's coordinates, metres: pixels whose centres lie inside are kept.
struct CropWindow {
    double minX_m = 0.0, minY_m = 0.0, maxX_m = 0.0, maxY_m = 0.0;
};

struct DemSpec {
    std::string path;                ///< any raster GDAL reads; band 1 holds heights in metres
    std::optional<CropWindow> crop;  ///< DEM coordinates; absent: the whole raster
    int meshStride = 1;              ///< render mesh stride, for the memory estimate only
};

struct Dem {
    sim::Heightfield field;  ///< local frame: sample (0, 0) at (0, 0)
    Georeference georef;
    int trimmedColumns = 0;  ///< all-nodata columns trimmed at the edges (west + east)
    int trimmedRows = 0;     ///< all-nodata rows trimmed at the edges (south + north)
};

/// Reads the DEM. Throws ImageError ("PATH: reason", one line, saying how to fix it where there
/// is a fix) for a file GDAL cannot open, no coordinate system, a geographic or non-metre or
/// unknown (local/engineering) one, a rotated grid or non-square pixels, a crop window outside
/// the raster or smaller than 2 x 2 pixels, a grid over MAX_SAMPLES_PER_SIDE or
/// MAX_TERRAIN_BYTES, all-nodata data, nodata inside the kept rectangle, and absurd heights.
Dem loadDem(const DemSpec& spec);

/// The UTM zone (1..60) of a longitude in degrees, and the EPSG code of that zone in WGS 84
/// (326ZZ north of the equator, 327ZZ south): what the geographic-DEM message proposes.
int utmZone(double longitude_deg);
int utmEpsg(double longitude_deg, double latitude_deg);

/// Installs GDAL's drivers once (thread-safe); every GDAL user in gale calls it first.
void ensureGdalRegistered();

/// The bearing of the coordinate system's grid north (+y) from true north at DEM point (x, y),
/// degrees, east of north positive (the grid convergence): the angle a wind's from_deg, measured
/// from +y, is off the meteorological one. nullopt when the DEM is not georeferenced or its CRS
/// cannot be transformed to latitude and longitude. Does not throw.
std::optional<double> gridNorthBearing_deg(const Georeference& geo, double demX_m, double demY_m);

}  // namespace gale::app
