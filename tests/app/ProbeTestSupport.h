#pragma once
// What the probe tests share: an RFC 4180 reader for gale probe's tables (quoted cells may hold
// commas and doubled quotes) and the flat meadow they probe.

#include <map>
#include <string>
#include <vector>

namespace gale::app::test {

/// The cells of an RFC 4180 CSV: cells split at commas outside quotes, quotes doubled inside
/// quoted cells, records ended by LF (a CR before it dropped).
inline std::vector<std::vector<std::string>> parseCsv(const std::string& text) {
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
        } else if (c != '\r') {
            rows.back().back() += c;
        }
    }
    if (rows.back().size() == 1 && rows.back()[0].empty()) rows.pop_back();
    return rows;
}

/// The table's rows as maps from column name (the first row) to text.
inline std::vector<std::map<std::string, std::string>> readCsv(const std::string& text) {
    const std::vector<std::vector<std::string>> cells = parseCsv(text);
    std::vector<std::map<std::string, std::string>> rows;
    for (size_t r = 1; r < cells.size(); ++r) {
        std::map<std::string, std::string> row;
        for (size_t i = 0; i < cells[0].size() && i < cells[r].size(); ++i)
            row[cells[0][i]] = cells[r][i];
        rows.push_back(row);
    }
    return rows;
}

/// A flat 20 m meadow in a log-law wind of 5 m/s at 10 m from the west (z0 0.03 m), on cubes of
/// 0.5 m up to 70 m.
inline const char* FLAT_PROBE_SCENE = R"(
[terrain]
kind = "flat"
size_m = [20.0, 20.0]
spacing_m = 1.0
[wind]
kind = "solved"
speed_mps = 5.0
reference_height_m = 10.0
from_deg = 270.0
profile = "log"
roughness_m = 0.03
[solver]
voxel_size_m = 0.5
top_m = 70.0
)";

}  // namespace gale::app::test
