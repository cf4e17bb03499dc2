#pragma once
/// \file SceneSection.h
/// The table-reading layer under the scene parser (SceneParser.cpp): showing TOML values in
/// messages, allowed ranges, and `Section`, which reads one TOML table, records every key it asks
/// for, and throws SceneError with FILE:LINE and the key's dotted name. Only SceneParser.cpp
/// includes it.

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "app/io/Errors.h"
#include "app/scene/Scene.h"
#include "base/Numbers.h"
#include "base/ParameterError.h"

namespace gale::app::detail {

namespace fs = std::filesystem;

inline constexpr double INF = std::numeric_limits<double>::infinity();
/// Longest value echoed back in a message; longer values are cut with "...".
inline constexpr size_t MAX_SHOWN_CHARS = 60;

// ---------------------------------------------------------------------------------------------
// Showing values in messages

inline std::string typeName(toml::node_type t) {
    switch (t) {
        case toml::node_type::table:
            return "a table";
        case toml::node_type::array:
            return "an array";
        case toml::node_type::string:
            return "a string";
        case toml::node_type::integer:
            return "an integer";
        case toml::node_type::floating_point:
            return "a float";
        case toml::node_type::boolean:
            return "a boolean";
        case toml::node_type::date:
            return "a date";
        case toml::node_type::time:
            return "a time";
        case toml::node_type::date_time:
            return "a date-time";
        default:
            return "nothing";
    }
}

inline std::string showNumber(double v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.15g", v);
    std::string s = buf;
    if (s.find_first_of(".eE") == std::string::npos) s += ".0";
    return s;
}

inline std::string cut(std::string s) {
    if (s.size() > MAX_SHOWN_CHARS) s = s.substr(0, MAX_SHOWN_CHARS - 3) + "...";
    return s;
}

inline std::string show(const toml::node& n) {
    switch (n.type()) {
        case toml::node_type::string: {
            std::string out = "\"";
            for (char c : n.as_string()->get()) {
                if (c == '"' || c == '\\') {
                    out += '\\';
                    out += c;
                } else if (static_cast<unsigned char>(c) < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\x%02x", c);
                    out += buf;
                } else {
                    out += c;
                }
            }
            return cut(out + "\"");
        }
        case toml::node_type::integer:
            return std::to_string(n.as_integer()->get());
        case toml::node_type::floating_point:
            return showNumber(n.as_floating_point()->get());
        case toml::node_type::boolean:
            return n.as_boolean()->get() ? "true" : "false";
        case toml::node_type::array: {
            std::string out = "[";
            const toml::array& a = *n.as_array();
            for (size_t i = 0; i < a.size() && out.size() < MAX_SHOWN_CHARS; ++i)
                out += (i ? ", " : "") + show(a[i]);
            return cut(out + "]");
        }
        case toml::node_type::table:
            return "a table";
        default:
            return typeName(n.type());
    }
}

/// `s` with control characters written as \xNN: keys and strings from the scene (`kind =
/// "a\nb"`) must not break the one-line message or send escape codes to the terminal.
inline std::string printable(const std::string& s) {
    std::string out;
    for (char c : s) {
        const auto u = static_cast<unsigned char>(c);
        if (u < 0x20 || u == 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02x", u);
            out += buf;
        } else {
            out += c;
        }
    }
    return out;
}

inline size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1] ? 1 : 0)});
            diag = up;
        }
    }
    return row[b.size()];
}

// ---------------------------------------------------------------------------------------------
// Ranges

/// An interval of allowed values; NaN and infinities never pass.
struct Limit {
    double lo = -INF, hi = INF;
    bool loOpen = false, hiOpen = false;

    bool holds(double v) const {
        if (!std::isfinite(v)) return false;
        if (loOpen ? !(v > lo) : !(v >= lo)) return false;
        if (hiOpen ? !(v < hi) : !(v <= hi)) return false;
        return true;
    }
    std::string text() const {
        if (lo == -INF && hi == INF) return "must be a finite number";
        if (hi == INF) return std::string("must be ") + (loOpen ? "> " : ">= ") + num(lo);
        if (lo == -INF) return std::string("must be ") + (hiOpen ? "< " : "<= ") + num(hi);
        return std::string("must be in ") + (loOpen ? "(" : "[") + num(lo) + ", " + num(hi) +
               (hiOpen ? ")" : "]");
    }
    static std::string num(double v) { return formatG(v); }
};

inline Limit anyFinite() { return {}; }
inline Limit above(double lo, double hi = INF) { return {lo, hi, true, false}; }
inline Limit atLeast(double lo, double hi = INF) { return {lo, hi, false, false}; }
inline Limit closed(double lo, double hi) { return {lo, hi, false, false}; }
/// Positions the renderer holds as floats (camera, lights, the point source): a float keeps a
/// metre's resolution up to 1.6e7 m, and squared distances stay far below FLT_MAX.
inline constexpr double MAX_FLOAT_POSITION_M = 1e7;
inline Limit floatPosition() { return closed(-MAX_FLOAT_POSITION_M, MAX_FLOAT_POSITION_M); }

// ---------------------------------------------------------------------------------------------
// Reading one table

struct Context {
    std::string file;  ///< the scene path as the user gave it
    fs::path folder;   ///< folder relative paths resolve against
    Scene* scene;
    /// When set, every getter records its key's default here as TOML text ("terrain.size_m" ->
    /// "[40.0, 40.0]"), for sceneKeyDefaults (SceneParser.h).
    std::map<std::string, std::string>* defaults = nullptr;
};

/// One TOML table being read: every getter records the key as known (so `finish` can tell typos
/// from valid keys) and throws SceneError with the key's full dotted name and line.
class Section {
  public:
    Section(Context& ctx, const toml::table* table, std::string name, int line)
        : mCtx(ctx), mTable(table), mName(std::move(name)), mLine(line) {}

    bool present() const { return mTable != nullptr; }
    const std::string& name() const { return mName; }
    int line() const { return mLine; }
    std::string full(const std::string& key) const {
        return mName.empty() ? key : mName + "." + key;
    }

    /// The node at `key`, or nullptr; marks the key as known and records its line.
    const toml::node* take(const std::string& key) {
        if (std::find(mKnown.begin(), mKnown.end(), key) == mKnown.end()) mKnown.push_back(key);
        if (mCtx.defaults) mCtx.defaults->emplace(full(key), "");  // no default unless a getter's
        if (!mTable) return nullptr;
        auto it = mTable->find(key);
        if (it == mTable->end()) return nullptr;
        mGiven.insert(key);
        mCtx.scene->keyLines[full(key)] = lineOf(it->first, it->second);
        return &it->second;
    }
    bool given(const std::string& key) const { return mGiven.count(key) != 0; }
    int lineOfKey(const std::string& key) const {
        auto it = mCtx.scene->keyLines.find(full(key));
        return it == mCtx.scene->keyLines.end() ? mLine : it->second;
    }

    [[noreturn]] void fail(int line, const std::string& key, const std::string& reason) const {
        std::string where = mCtx.file;
        if (line > 0) where += ":" + std::to_string(line);
        throw SceneError(where + ": " +
                         printable((key.empty() ? mName : full(key)) + ": " + reason));
    }
    [[noreturn]] void failValue(const toml::node& n, const std::string& key,
                                const std::string& reason) const {
        fail(lineOf(n), key, reason + " (got " + show(n) + ")");
    }
    [[noreturn]] void failKey(const std::string& key, const std::string& reason) const {
        fail(lineOfKey(key), key, reason);
    }
    /// A library's ParameterError about a key of this section, at the line of the key it names
    /// ("wind.profile"; for an element of an array of tables, "wind.gusts.peak_mps" is this
    /// element's peak_mps), or at this section's line when the key was not written (its default
    /// is then what is wrong, and the message says so).
    [[noreturn]] void failParameter(const ParameterError& e) const {
        // "wind.gusts[2]" answers for "wind.gusts.KEY" too.
        const bool element = !mName.empty() && mName.back() == ']';
        const std::string prefix = (element ? mName.substr(0, mName.rfind('[')) : mName) + ".";
        const bool inside = !mName.empty() && e.key().compare(0, prefix.size(), prefix) == 0;
        const std::string key = inside ? e.key().substr(prefix.size()) : e.key();
        const bool isDefault = inside && !given(key);  // a default another key made invalid
        const std::string got = " (got " + e.value() + (isDefault ? ", the default)" : ")");
        if (inside) fail(lineOfKey(key), key, e.expected() + got);
        fail(mLine, "", e.key() + ": " + e.expected() + got);
    }

    /// The getters below return the value written under `key`, checked, or `def` when the key is
    /// absent. `def` is the default of the struct field the value goes to, never a second copy.
    double number(const std::string& key, double def, Limit limit) {
        noteDefault(key, showNumber(def));
        const toml::node* n = take(key);
        return n ? toNumber(*n, key, limit) : def;
    }

    /// An optional key (no default: its absence has a meaning of its own, documented with it).
    std::optional<double> optionalNumber(const std::string& key, Limit limit) {
        const toml::node* n = take(key);
        return n ? std::optional<double>(toNumber(*n, key, limit)) : std::nullopt;
    }

    int64_t integer(const std::string& key, int64_t def, int64_t lo, int64_t hi) {
        noteDefault(key, std::to_string(def));
        const toml::node* n = take(key);
        return n ? toInteger(*n, key, lo, hi) : def;
    }

    std::string string(const std::string& key, const std::string& def) {
        noteDefault(key, show(toml::value<std::string>(def)));
        const toml::node* n = take(key);
        if (!n) return def;
        if (!n->is_string()) failValue(*n, key, "expected a string, not " + typeName(n->type()));
        return n->as_string()->get();
    }

    bool boolean(const std::string& key, bool def) {
        noteDefault(key, def ? "true" : "false");
        const toml::node* n = take(key);
        if (!n) return def;
        if (!n->is_boolean())
            failValue(*n, key, "expected true or false, not " + typeName(n->type()));
        return n->as_boolean()->get();
    }

    template <size_t N>
    std::array<double, N> vec(const std::string& key, std::array<double, N> def, Limit limit) {
        std::string text = "[";
        for (size_t i = 0; i < N; ++i) text += (i ? ", " : "") + showNumber(def[i]);
        noteDefault(key, text + "]");
        const toml::node* n = take(key);
        if (!n) return def;
        const toml::array* a = n->as_array();
        if (!a || a->size() != N)
            failValue(*n, key, "expected an array of " + std::to_string(N) + " numbers");
        std::array<double, N> out{};
        for (size_t i = 0; i < N; ++i)
            out[i] = toNumber((*a)[i], key + "[" + std::to_string(i) + "]", limit);
        return out;
    }

    /// Sub-table `key` (absent: a Section that is not present, reading defaults).
    Section table(const std::string& key) {
        const toml::node* n = take(key);
        if (n && !n->is_table()) failValue(*n, key, "expected a table ([" + full(key) + "])");
        return Section(mCtx, n ? n->as_table() : nullptr, full(key), n ? lineOf(*n) : mLine);
    }

    /// Array of tables `key` ([[key]] in TOML); empty if absent.
    std::vector<Section> tables(const std::string& key) {
        const toml::node* n = take(key);
        std::vector<Section> out;
        if (!n) return out;
        const toml::array* a = n->as_array();
        if (!a || !a->is_array_of_tables())
            failValue(*n, key, "expected an array of tables ([[" + full(key) + "]])");
        for (size_t i = 0; i < a->size(); ++i)
            out.emplace_back(mCtx, (*a)[i].as_table(), full(key) + "[" + std::to_string(i) + "]",
                             lineOf((*a)[i]));
        return out;
    }

    /// Throws for the first key of the table that no getter asked for.
    void finish() const {
        if (!mTable) return;
        for (auto&& [k, v] : *mTable) {
            const std::string key(k.str());
            if (std::find(mKnown.begin(), mKnown.end(), key) != mKnown.end()) continue;
            std::string best;
            size_t bestDistance = 3;  // suggest only near misses (two edits or fewer)
            for (const std::string& known : mKnown) {
                const size_t d = editDistance(key, known);
                if (d < bestDistance) bestDistance = d, best = known;
            }
            // A key written without its unit suffix ("speed" for "speed_mps").
            for (const std::string& known : mKnown)
                if (best.empty() && known.rfind(key + "_", 0) == 0) best = known;
            std::string valid;
            for (const std::string& known : mKnown) valid += (valid.empty() ? "" : ", ") + known;
            std::string reason = v.is_table() ? "unknown section" : "unknown key";
            if (!best.empty()) reason += " (did you mean '" + best + "'?)";
            reason += mName.empty() ? "; valid top-level keys: " : "; valid keys here: ";
            reason += valid;
            fail(lineOf(k, v), key, reason);
        }
    }

    double toNumber(const toml::node& n, const std::string& key, Limit limit) const {
        double v;
        if (n.is_integer())
            v = static_cast<double>(n.as_integer()->get());
        else if (n.is_floating_point())
            v = n.as_floating_point()->get();
        else
            failValue(n, key, "expected a number, not " + typeName(n.type()));
        if (!limit.holds(v)) failValue(n, key, limit.text());
        return v;
    }

    int64_t toInteger(const toml::node& n, const std::string& key, int64_t lo, int64_t hi) const {
        if (!n.is_integer()) failValue(n, key, "expected an integer, not " + typeName(n.type()));
        const int64_t v = n.as_integer()->get();
        if (v < lo || v > hi)
            failValue(n, key, "must be in " + std::to_string(lo) + ".." + std::to_string(hi));
        return v;
    }

    static int lineOf(const toml::node& n) { return static_cast<int>(n.source().begin.line); }
    static int lineOf(const toml::key& k, const toml::node& n) {
        const int line = static_cast<int>(k.source().begin.line);
        return line > 0 ? line : lineOf(n);
    }

  private:
    void noteDefault(const std::string& key, const std::string& text) {
        if (mCtx.defaults) (*mCtx.defaults)[full(key)] = text;
    }

    Context& mCtx;
    const toml::table* mTable;
    std::string mName;
    int mLine;
    std::vector<std::string> mKnown;
    std::set<std::string> mGiven;
};

}  // namespace gale::app::detail
