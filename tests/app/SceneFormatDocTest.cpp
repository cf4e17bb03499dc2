// docs/scene-format.md against the parser: every key the page lists is read by the parser, every
// key the parser reads is on the page, and every default the page shows as a literal is the
// default the parser uses (which it takes from the struct field the value goes to). The oracle
// is the page itself, read as a user reads it.
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "app/scene/SceneParser.h"

namespace gale::app {
namespace {

/// Defaults of float fields (grass, lighting, camera) reach the parser through a float: they keep
/// about 7 significant digits of the decimal the page shows.
constexpr double FLOAT_FIELD_RELATIVE_TOLERANCE = 1e-6;

struct DocRow {
    std::string key;          ///< dotted, without array indices: "wind.gusts.start_s"
    std::string defaultCell;  ///< the table's default column, as written
    int line = 0;
};

std::vector<std::string> cellsOf(std::string row) {
    // An escaped bar (\|I\|) is part of a cell, not a separator.
    const std::string BAR = "\x01";
    for (size_t at = row.find("\\|"); at != std::string::npos; at = row.find("\\|", at))
        row.replace(at, 2, BAR);
    std::vector<std::string> cells;
    std::stringstream in(row);
    std::string cell;
    std::getline(in, cell, '|');  // before the first bar
    while (std::getline(in, cell, '|')) {
        const size_t b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
        cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
    }
    if (!cells.empty() && cells.back().empty()) cells.pop_back();  // after the last bar
    return cells;
}

/// The key tables of the page: a heading naming `[section]` or `[[section]]` opens the section
/// its rows belong to; a second-level heading without one returns to the top level.
std::vector<DocRow> documentedKeys(const std::string& path) {
    std::ifstream in(path);
    EXPECT_TRUE(in.good()) << "cannot read " << path;
    std::vector<DocRow> rows;
    std::string line, section;
    int lineNumber = 0, defaultColumn = -1;
    while (std::getline(in, line)) {
        ++lineNumber;
        if (line.rfind("#", 0) == 0) {
            const size_t open = line.find("`[");
            if (open != std::string::npos) {
                const size_t b = line.find_first_not_of('[', open + 1);
                section = line.substr(b, line.find(']', b) - b);
            } else if (line.rfind("## ", 0) == 0) {
                section.clear();
            }
            defaultColumn = -1;
            continue;
        }
        if (line.rfind("|", 0) != 0) continue;
        const std::vector<std::string> cells = cellsOf(line);
        if (cells.empty() || cells[0].rfind("---", 0) == 0) continue;
        if (cells[0] == "key") {
            defaultColumn = -1;
            for (size_t c = 0; c < cells.size(); ++c)
                if (cells[c] == "default") defaultColumn = int(c);
            continue;
        }
        if (defaultColumn < 0 || int(cells.size()) <= defaultColumn) continue;
        const std::string& keyCell = cells[0];
        if (keyCell.size() < 3 || keyCell.front() != '`' || keyCell.back() != '`') continue;
        const std::string key = keyCell.substr(1, keyCell.size() - 2);
        rows.push_back(
            {section.empty() ? key : section + "." + key, cells[defaultColumn], lineNumber});
    }
    return rows;
}

/// The value of a default cell that is exactly one backticked TOML literal (`40`, `[1, 0, 0]`,
/// `"log"`); std::nullopt for prose ("the grass height") or an expression (`0.1 * period_s`).
std::optional<toml::table> literalOf(const std::string& cell) {
    if (cell.size() < 3 || cell.front() != '`' || cell.back() != '`') return std::nullopt;
    const std::string text = cell.substr(1, cell.size() - 2);
    if (text.find('`') != std::string::npos) return std::nullopt;
    try {
        return toml::parse("v = " + text);
    } catch (const toml::parse_error&) {
        return std::nullopt;
    }
}

bool sameValue(const toml::node& a, const toml::node& b) {
    if (a.is_number() && b.is_number()) {
        const double x = a.value<double>().value(), y = b.value<double>().value();
        return std::abs(x - y) <= FLOAT_FIELD_RELATIVE_TOLERANCE * std::max(std::abs(x), 1e-12);
    }
    if (a.is_array() && b.is_array()) {
        const toml::array &p = *a.as_array(), &q = *b.as_array();
        if (p.size() != q.size()) return false;
        for (size_t i = 0; i < p.size(); ++i)
            if (!sameValue(p[i], q[i])) return false;
        return true;
    }
    if (a.is_string() && b.is_string()) return a.as_string()->get() == b.as_string()->get();
    if (a.is_boolean() && b.is_boolean()) return a.as_boolean()->get() == b.as_boolean()->get();
    return false;
}

const std::string DOC = std::string(GALE_SOURCE_DIR) + "/docs/scene-format.md";

TEST(SceneFormatDoc, EveryLiteralDefaultOnThePageIsTheParsers) {
    const std::map<std::string, std::string> code = sceneKeyDefaults();
    const std::vector<DocRow> rows = documentedKeys(DOC);
    ASSERT_GT(rows.size(), 100u) << "the page's key tables were not found";
    int compared = 0;
    for (const DocRow& row : rows) {
        const auto it = code.find(row.key);
        if (it == code.end()) continue;  // EveryDocumentedKeyIsRead reports it
        const std::optional<toml::table> doc = literalOf(row.defaultCell);
        if (!doc) continue;
        const std::string where = "docs/scene-format.md:" + std::to_string(row.line) + ": " +
                                  row.key + " default " + row.defaultCell;
        if (it->second.empty()) {
            ADD_FAILURE() << where << ", but the key is optional: its absence has a meaning of "
                          << "its own, which the page must say in words";
            continue;
        }
        const toml::table parsed = toml::parse("v = " + it->second);
        EXPECT_TRUE(sameValue(*doc->get("v"), *parsed.get("v")))
            << where << ", but the parser's is " << it->second;
        ++compared;
    }
    // Most keys have a literal default; a page whose defaults all became prose would pass above.
    EXPECT_GT(compared, 100);
}

TEST(SceneFormatDoc, EveryDocumentedKeyIsRead) {
    const std::map<std::string, std::string> code = sceneKeyDefaults();
    for (const DocRow& row : documentedKeys(DOC))
        EXPECT_EQ(code.count(row.key), 1u) << "docs/scene-format.md:" << row.line << ": " << row.key
                                           << " is documented but the parser does not read it";
}

TEST(SceneFormatDoc, EveryKeyTheParserReadsIsDocumented) {
    const std::map<std::string, std::string> code = sceneKeyDefaults();
    std::map<std::string, int> documented;
    for (const DocRow& row : documentedKeys(DOC)) documented[row.key] = row.line;
    for (const auto& [key, text] : code) {
        // A table ("wind.gust") is a heading on the page, not a row.
        const auto next = code.upper_bound(key);
        if (next != code.end() && next->first.rfind(key + ".", 0) == 0) continue;
        EXPECT_EQ(documented.count(key), 1u)
            << key << " is read by the parser (default " << (text.empty() ? "none" : text)
            << ") but docs/scene-format.md does not list it";
    }
}

}  // namespace
}  // namespace gale::app
