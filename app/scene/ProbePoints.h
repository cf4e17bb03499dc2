#pragma once
/// \file ProbePoints.h
/// The points `gale probe` reads and the table it writes, through GDAL/OGR (docs/cli.md, "gale
/// probe").
///
/// In: any vector file OGR opens. A CSV (OGR's CSV driver: RFC 4180 quoting, a UTF-8 byte order
/// mark, CRLF, LF or CR line ends) names its columns in a header: x, y, and exactly one of
/// height_agl_m (above the ground) or z_m (absolute), name optional; every other column is kept
/// and carried to the output. A row whose first cell starts with '#' is a comment. GeoJSON,
/// GeoPackage, shapefiles and other OGR formats give x and y by their point geometry, reprojected
/// by OGR from the layer's coordinate system to the DEM's (a layer without one is taken to be in
/// the scene's coordinates), and the height and name by attributes of the same names. Numbers
/// are strict: decimal notation only (no hex, no inf or nan), finite and not subnormal.
///
/// Out: RFC 4180 CSV (cells holding a comma, a quote or a line end are quoted, quotes doubled), or
/// any OGR vector format chosen by the output's extension (.gpkg, .geojson, .shp, ...: point
/// features in the DEM's coordinate system, one per point and time), written atomically.

#include <optional>
#include <string>
#include <vector>

#include "app/scene/Dem.h"

namespace gale::app {

/// One point as given.
struct ProbeInput {
    std::string name;  ///< the name column, or "p1", "p2", ... in the order given
    int line = 0;      ///< CSV: the line the row starts on; other formats: the feature's number
    double x_m = 0.0, y_m = 0.0;     ///< the scene's (DEM's) coordinates, metres
    double height_m = 0.0;           ///< height_agl_m or z_m as given (ProbeTable says which)
    std::vector<std::string> extra;  ///< the kept columns' values, as text, in extraColumns' order
};

struct ProbeTable {
    std::string path;
    bool csv = true;                        ///< lines are CSV lines; else feature numbers
    bool heightAboveGround = true;          ///< height_agl_m (true) or z_m
    std::vector<std::string> extraColumns;  ///< columns kept beyond name, x, y and the height
    std::vector<ProbeInput> points;
    /// "FILE:LINE" for a CSV, "FILE: feature N" otherwise.
    std::string where(const ProbeInput& p) const;
};

/// Reads the probe points of `path` in the coordinates of `geo` (a DEM's; empty: the terrain's
/// own metres, and a layer with a coordinate system is refused). Throws InputError "FILE:LINE:
/// reason" (or "FILE: reason") for a file OGR cannot open, a missing, duplicate or unknown
/// height column, a value that is not a strict finite number, a name with control characters,
/// or a point that cannot be reprojected; at most MAX_PROBE_POINTS points.
ProbeTable readProbeTable(const std::string& path, const Georeference& geo);

/// Most points a probe table may hold: a list of masts, not a point cloud.
inline constexpr size_t MAX_PROBE_POINTS = 1000000;
/// Largest probe file read, bytes.
inline constexpr double MAX_PROBE_FILE_BYTES = 64.0 * 1024 * 1024;

/// One cell of the output table: a number (written with `decimals` digits after the point) or
/// text; empty when neither.
struct ProbeCell {
    std::optional<double> number;
    std::string text;
    int decimals = 4;
};

/// The output: column names and rows of cells, the x and y columns' indices (the point's DEM
/// coordinates, the geometry of vector outputs).
struct ProbeOutput {
    std::vector<std::string> columns;
    std::vector<std::vector<ProbeCell>> rows;
    int xColumn = 0, yColumn = 0;
};

/// The table as RFC 4180 CSV text.
std::string probeCsv(const ProbeOutput& table);

/// True when `path`'s extension picks a vector format gale writes (.gpkg, .geojson, .json, .fgb);
/// any other name is written as CSV.
bool isVectorOutput(const std::string& path);

/// Throws InputError "-o: ..." for an extension of a vector format gale does not write (.shp,
/// .kml, ...), so that such a name never receives a CSV.
void checkProbeOutputPath(const std::string& path);

/// Writes the table to `path` atomically in the OGR format its extension picks, point features in
/// `geo`'s coordinate system (none for a scene without one). Throws InputError for an extension
/// no OGR driver writes, std::runtime_error "PATH: cannot write: REASON" otherwise.
void writeProbeVector(const std::string& path, const ProbeOutput& table, const Georeference& geo);

}  // namespace gale::app
