/// \file ProbePoints.cpp
/// Probe points in and the probe table out through GDAL/OGR (ProbePoints.h).

#include "app/scene/ProbePoints.h"

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>

#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/scene/GdalSupport.h"
#include "base/Numbers.h"

namespace gale::app {
namespace {

namespace fs = std::filesystem;

/// Decimal notation only: digits with an optional point and exponent (no hex, inf, nan).
const std::regex& decimalNumber() {
    static const std::regex re(R"(^[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?$)");
    return re;
}

std::string trimmed(const std::string& s) {
    const auto a = s.find_first_not_of(" \t\r\n");
    const auto b = s.find_last_not_of(" \t\r\n");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

/// A CSV record as OGR's CSV driver sees it: the line it starts on (1-based) and its cells.
struct CsvRecord {
    int line = 0;
    int cells = 0;
};

/// The file's records: split at LF, CRLF or CR outside quotes, empty records skipped, cells
/// counted at commas outside quotes. Element 0 is the header.
std::vector<CsvRecord> csvRecords(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<CsvRecord> records;
    int line = 1;
    CsvRecord r{1, 1};
    bool quoted = false, empty = true;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        const bool crlf = c == '\r' && i + 1 < text.size() && text[i + 1] == '\n';
        if (c == '"') quoted = !quoted;
        if ((c == '\n' || c == '\r') && !crlf) {
            if (!quoted) {
                if (!empty) records.push_back(r);
                empty = true;
                r = {line + 1, 1};
            }
            ++line;
            continue;
        }
        if (c == '\r') continue;
        if (empty) empty = false, r.line = line;
        if (c == ',' && !quoted) ++r.cells;
    }
    if (!empty) records.push_back(r);
    return records;
}

/// The first control character of `s` (below 0x20, or DEL), or -1.
int controlCharacter(const std::string& s) {
    for (unsigned char c : s)
        if (c < 0x20 || c == 0x7f) return c;
    return -1;
}

std::string quoteCsv(const std::string& s) {
    if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string cellText(const ProbeCell& c) {
    if (!c.number) return c.text;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", c.decimals, *c.number);
    return buf;
}

/// The OGR driver an output extension picks; empty for none gale writes. Formats that are one
/// file only: a shapefile's several files cannot be written atomically.
std::string vectorDriverFor(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".gpkg") return "GPKG";
    if (ext == ".geojson" || ext == ".json") return "GeoJSON";
    if (ext == ".fgb") return "FlatGeobuf";
    return "";
}

}  // namespace

std::string ProbeTable::where(const ProbeInput& p) const {
    return csv ? path + ":" + std::to_string(p.line) : path + ": feature " + std::to_string(p.line);
}

ProbeTable readProbeTable(const std::string& path, const Georeference& geo) {
    std::error_code ec;
    if (!fs::exists(path, ec))
        throw InputError(path + ": cannot read the probe points (no such file)");
    if (fs::is_directory(path, ec)) throw InputError(path + ": is a folder, not a probe table");
    if (fs::is_regular_file(path, ec) && double(fs::file_size(path, ec)) > MAX_PROBE_FILE_BYTES)
        throw InputError(path + ": too large for a probe table (at most " +
                         formatG(MAX_PROBE_FILE_BYTES / MIB, 3) + " MiB)");
    ensureGdalRegistered();
    QuietGdal quiet;
    const char* options[] = {"AUTODETECT_TYPE=NO", nullptr};  // CSV cells stay text: parsed here
    DatasetPtr ds(GDALDataset::FromHandle(
        GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, options, nullptr)));
    if (!ds)
        throw InputError(path + ": not a table of points GDAL can read (" + gdalMessage() + ")");
    if (ds->GetLayerCount() < 1) throw InputError(path + ": holds no layer of points");
    OGRLayer* layer = ds->GetLayer(0);
    ProbeTable t;
    t.path = path;
    t.csv = std::string(ds->GetDriver()->GetDescription()) == "CSV";
    const std::vector<CsvRecord> records = t.csv ? csvRecords(path) : std::vector<CsvRecord>{};
    const int headerLine = records.empty() ? 1 : records.front().line;
    auto failHeader = [&](const std::string& reason) -> void {
        throw InputError(t.csv ? path + ":" + std::to_string(headerLine) + ": " + reason
                               : path + ": " + reason);
    };

    OGRFeatureDefn* defn = layer->GetLayerDefn();
    int cx = -1, cy = -1, ch = -1, cz = -1, cn = -1;
    std::vector<int> kept;
    for (int i = 0; i < defn->GetFieldCount(); ++i) {
        const std::string c = defn->GetFieldDefn(i)->GetNameRef();
        for (int j = 0; j < i; ++j)
            if (c == defn->GetFieldDefn(j)->GetNameRef())
                failHeader("column '" + c + "' is given twice (columns " + std::to_string(j + 1) +
                           " and " + std::to_string(i + 1) + ")");
        int* slot = c == "x"              ? &cx
                    : c == "y"            ? &cy
                    : c == "height_agl_m" ? &ch
                    : c == "z_m"          ? &cz
                    : c == "name"         ? &cn
                                          : nullptr;
        if (slot)
            *slot = i;
        else
            kept.push_back(i), t.extraColumns.push_back(c);
    }
    const bool fromFields = cx >= 0 || cy >= 0;
    if (fromFields && (cx < 0 || cy < 0)) failHeader("the header must name both columns x and y");
    if (!fromFields && (t.csv || wkbFlatten(layer->GetGeomType()) == wkbNone))
        failHeader("the header must name columns x and y (or the layer must have point geometry)");
    if ((ch < 0) == (cz < 0))
        failHeader(
            "the header must name exactly one of height_agl_m (above the ground) or z_m "
            "(absolute)");
    t.heightAboveGround = ch >= 0;

    // Geometries are reprojected to the DEM's coordinate system.
    std::unique_ptr<OGRCoordinateTransformation> toDem;
    const OGRSpatialReference* layerSrs = fromFields ? nullptr : layer->GetSpatialRef();
    if (layerSrs && !layerSrs->IsEmpty()) {
        if (!geo.georeferenced())
            failHeader("the points are in a coordinate system (" +
                       std::string(layerSrs->GetName() ? layerSrs->GetName() : "unnamed") +
                       ") but the terrain has none: give them in the terrain's metres");
        OGRSpatialReference dem, src(*layerSrs);
        dem.importFromWkt(geo.crsWkt.c_str());
        dem.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        src.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        if (!src.IsSame(&dem)) {
            toDem.reset(OGRCreateCoordinateTransformation(&src, &dem));
            if (!toDem)
                failHeader("cannot reproject the points from " +
                           std::string(src.GetName() ? src.GetName() : "their coordinate system") +
                           " to the DEM's " + geo.crsName + " (" + gdalMessage() + ")");
        }
    }

    int index = 0;
    for (auto& feature : *layer) {
        ++index;
        ProbeInput p;
        const bool known = t.csv && index < int(records.size());
        p.line = known ? records[size_t(index)].line : t.csv ? headerLine + index : index;
        auto fail = [&](const std::string& reason) -> void {
            throw InputError(t.where(p) + ": " + reason);
        };
        auto text = [&](int col) {
            return col >= 0 && feature->IsFieldSetAndNotNull(col)
                       ? std::string(feature->GetFieldAsString(col))
                       : std::string();
        };
        // A comment: the first cell starts with '#'.
        if (t.csv && trimmed(text(0)).rfind('#', 0) == 0) continue;
        if (known && records[size_t(index)].cells != records.front().cells)
            fail("expected " + std::to_string(records.front().cells) + " values, got " +
                 std::to_string(records[size_t(index)].cells));
        if (t.points.size() >= MAX_PROBE_POINTS)
            fail("more than " + std::to_string(MAX_PROBE_POINTS) +
                 " points: a probe table is a list of masts");
        auto number = [&](int col, const char* what) {
            const std::string s = trimmed(text(col));
            if (!std::regex_match(s, decimalNumber()))
                fail(std::string(what) + ": not a decimal number (got '" + s + "')");
            const double v = std::strtod(s.c_str(), nullptr);
            if (!std::isfinite(v) || std::fpclassify(v) == FP_SUBNORMAL)
                fail(std::string(what) + ": not a finite normal number (got '" + s + "')");
            return v;
        };
        p.name = trimmed(text(cn));
        if (p.name.empty()) p.name = "p" + std::to_string(t.points.size() + 1);
        if (const int c = controlCharacter(p.name); c >= 0) {
            char code[16];
            std::snprintf(code, sizeof code, "0x%02x", c);
            fail(std::string("name: holds a control character (byte ") + code + ")");
        }
        if (fromFields) {
            p.x_m = number(cx, "x");
            p.y_m = number(cy, "y");
        } else {
            const OGRGeometry* g = feature->GetGeometryRef();
            if (!g || wkbFlatten(g->getGeometryType()) != wkbPoint || g->IsEmpty())
                fail("not a point (its geometry is " +
                     std::string(g ? g->getGeometryName() : "missing") + ")");
            double x = g->toPoint()->getX(), y = g->toPoint()->getY();
            if (toDem && !toDem->Transform(1, &x, &y))
                fail("cannot reproject the point to the DEM's " + geo.crsName);
            if (!std::isfinite(x) || !std::isfinite(y)) fail("its coordinates are not finite");
            p.x_m = x, p.y_m = y;
        }
        p.height_m = number(ch >= 0 ? ch : cz, ch >= 0 ? "height_agl_m" : "z_m");
        for (size_t k = 0; k < kept.size(); ++k) {
            std::string v = text(kept[k]);
            if (const int c = controlCharacter(v); c >= 0) {
                char code[16];
                std::snprintf(code, sizeof code, "0x%02x", c);
                fail(t.extraColumns[k] + ": holds a control character (byte " + code + ")");
            }
            p.extra.push_back(std::move(v));
        }
        t.points.push_back(std::move(p));
    }
    if (t.points.empty())
        throw InputError(path + ": no probe points (a header, then one point per line)");
    return t;
}

std::string probeCsv(const ProbeOutput& table) {
    std::string out;
    for (size_t i = 0; i < table.columns.size(); ++i)
        out += (i ? "," : "") + quoteCsv(table.columns[i]);
    out += "\n";
    for (const std::vector<ProbeCell>& row : table.rows) {
        for (size_t i = 0; i < row.size(); ++i) out += (i ? "," : "") + quoteCsv(cellText(row[i]));
        out += "\n";
    }
    return out;
}

bool isVectorOutput(const std::string& path) { return !vectorDriverFor(path).empty(); }

void checkProbeOutputPath(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    // Vector formats OGR has but gale does not write: several files (a shapefile), or a fixed
    // coordinate system (KML); a user asking for them must not get a CSV under their name.
    for (const char* other : {".shp", ".kml", ".kmz", ".gml", ".sqlite", ".tab", ".mif", ".dxf"})
        if (ext == other)
            throw InputError("-o: '" + path +
                             "': gale writes the table as .csv, or as a single-file vector "
                             "format by extension: .gpkg (GeoPackage), .geojson, .fgb "
                             "(FlatGeobuf)");
}

void writeProbeVector(const std::string& path, const ProbeOutput& table, const Georeference& geo) {
    checkProbeOutputPath(path);
    const std::string driverName = vectorDriverFor(path);
    if (driverName.empty())
        throw InputError("-o: '" + path + "' is not a vector format gale writes");
    ensureGdalRegistered();
    QuietGdal quiet;
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driverName.c_str());
    if (!driver) throw InputError("-o: this GDAL has no " + driverName + " driver for " + path);
    const std::string tmp = temporaryPathFor(path);
    auto cannot = [&](const std::string& reason) -> void {
        discardTemporary(tmp);
        throw std::runtime_error(path + ": cannot write: " + reason);
    };
    {
        DatasetPtr ds(driver->Create(tmp.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        if (!ds) cannot(gdalMessage());
        std::unique_ptr<OGRSpatialReference> srs;
        if (geo.georeferenced()) {
            srs = std::make_unique<OGRSpatialReference>();
            srs->importFromWkt(geo.crsWkt.c_str());
            srs->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        }
        OGRLayer* layer = ds->CreateLayer("probe", srs.get(), wkbPoint, nullptr);
        if (!layer) cannot(gdalMessage());
        // A column is a number field when every cell that holds something holds a number.
        std::vector<bool> numeric(table.columns.size(), true);
        for (const auto& row : table.rows)
            for (size_t i = 0; i < row.size(); ++i)
                if (!row[i].number && !row[i].text.empty()) numeric[i] = false;
        for (size_t i = 0; i < table.columns.size(); ++i) {
            OGRFieldDefn field(table.columns[i].c_str(), numeric[i] ? OFTReal : OFTString);
            if (layer->CreateField(&field) != OGRERR_NONE) cannot(gdalMessage());
        }
        for (const auto& row : table.rows) {
            OGRFeature feature(layer->GetLayerDefn());
            for (size_t i = 0; i < row.size(); ++i) {
                if (row[i].number)
                    feature.SetField(int(i), *row[i].number);
                else if (!row[i].text.empty())
                    feature.SetField(int(i), row[i].text.c_str());
            }
            const ProbeCell& x = row[size_t(table.xColumn)];
            const ProbeCell& y = row[size_t(table.yColumn)];
            OGRPoint point(x.number.value_or(0.0), y.number.value_or(0.0));
            feature.SetGeometry(&point);
            if (layer->CreateFeature(&feature) != OGRERR_NONE) cannot(gdalMessage());
        }
        ds->FlushCache();
        if (CPLGetLastErrorType() == CE_Failure || CPLGetLastErrorType() == CE_Fatal)
            cannot(gdalMessage());
    }
    commitTemporary(tmp, path);
}

}  // namespace gale::app
