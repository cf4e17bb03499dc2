#pragma once
/// \file WindRaster.h
/// The wind at one height above the ground as GIS rasters: a GeoTIFF with two bands (speed, m/s;
/// meteorological from-direction, degrees clockwise from north) and an ESRI ASCII grid of the
/// speed, both in the DEM's coordinate system (docs/cli.md, "gale solve").

#include <string>
#include <vector>

#include "app/scene/Dem.h"
#include "sim/Heightfield.h"
#include "sim/WindField.h"

namespace gale::app {

/// Nodata value of the rasters (cells where the height lies outside the air domain).
inline constexpr double WIND_RASTER_NODATA = -9999.0;

/// Writes `<stem>.tif` and `<stem>.asc` (with `<stem>.prj` when georeferenced): one pixel per
/// terrain sample, pixel centres on the samples, the wind sampled at height_m above the ground
/// there. North-up; the geotransform is in the DEM's coordinates (the local offset added back).
/// With tke_m2ps2 (the momentum model's k on the field's cells, m^2/s^2) the GeoTIFF holds three
/// more bands at the same height: tke_m2ps2, turbulence_intensity and gust_mps
/// (coupling/Turbulence.h: sqrt(2k/3) / speed and speed + 3.5 sqrt(2k/3)); the ASCII grid stays
/// the speed. Each file is written to a temporary name and renamed. Returns the paths written.
/// Throws std::runtime_error naming the path when GDAL cannot write it.
std::vector<std::string> writeWindRasters(const sim::WindField& field,
                                          const sim::Heightfield& terrain,
                                          const Georeference& georef, double height_m,
                                          const std::string& stem,
                                          const std::vector<double>& tke_m2ps2 = {});

}  // namespace gale::app
