// One TOML table of a scene file, read with every lookup type-checked and
// every failure naming file, line and full dotted key (internal to the scene
// library: it includes toml++).
#pragma once

#include "input_error.h"
#include "scene_keys.h"

#include <toml++/toml.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace armour::scene_detail {

// The source name toml++ records for nodes that came from --set, so errors
// in overridden values point at the option rather than a file line.
inline constexpr std::string_view kSetSource = "--set";

inline std::string join(const std::vector<std::string> &items, const std::string &sep) {
    std::string out;
    for (std::size_t i = 0; i < items.size(); ++i)
        out += (i ? sep : "") + items[i];
    return out;
}

inline std::size_t edit_distance(const std::string &a, const std::string &b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0u : 1u)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

// The known name closest to a misspelt one, or "" when none is close.
inline std::string nearest(const std::string &key, const std::vector<std::string> &known) {
    std::string best;
    std::size_t best_distance = std::max<std::size_t>(1, std::min<std::size_t>(3, key.size() / 3)) + 1;
    for (const auto &k : known) {
        const std::size_t d = edit_distance(key, k);
        if (d < best_distance) {
            best_distance = d;
            best = k;
        }
    }
    return best;
}

// " (did you mean 'size'?)" for a near miss, else the list of known keys.
inline std::string hint(const std::string &key, const std::vector<std::string> &known) {
    const std::string best = nearest(key, known);
    if (!best.empty())
        return " (did you mean '" + best + "'?)";
    return " (known: " + join(known, ", ") + ")";
}

inline std::string type_name(const toml::node &n) {
    switch (n.type()) {
    case toml::node_type::string:
        return "string " + toml_string(n.as_string()->get());
    case toml::node_type::integer:
        return "integer " + std::to_string(n.as_integer()->get());
    case toml::node_type::floating_point:
        return "float " + number_text(n.as_floating_point()->get());
    case toml::node_type::boolean:
        return n.as_boolean()->get() ? "true" : "false";
    case toml::node_type::array:
        return "an array";
    case toml::node_type::table:
        return "a table";
    default:
        return "a date/time";
    }
}

inline std::string choices(const std::vector<std::string> &options) {
    std::vector<std::string> q;
    for (const auto &o : options)
        q.push_back(toml_string(o));
    return join(q, ", ");
}
// ---------------------------------------------------------------- reading

// Where a node came from: "--set" for overrides, else FILE:LINE.
inline std::string location(const std::string &file, const toml::node &n) {
    const toml::source_region &src = n.source();
    if (src.path && *src.path == kSetSource)
        return std::string(kSetSource);
    if (src.begin.line == 0)
        return file;
    return file + ":" + std::to_string(src.begin.line);
}

// One TOML table being read: every lookup is type-checked, every failure
// names the file, line and full dotted key.
class Table {
  public:
    Table(const std::string &file, const toml::table &table, std::string path)
        : file_(file), table_(table), path_(std::move(path)) {}

    const toml::table &raw() const { return table_; }
    const std::string &file() const { return file_; }
    const std::string &path() const { return path_; }
    bool has(const std::string &key) const { return table_.contains(key); }
    const toml::node *node(const std::string &key) const { return table_.get(key); }

    std::string key_path(const std::string &key) const { return path_.empty() ? key : path_ + "." + key; }

    // At the key's own line when present, else at its enclosing table.
    [[noreturn]] void fail(const std::string &key, const std::string &reason) const {
        const toml::node *n = node(key);
        throw InputError(location(file_, n ? *n : static_cast<const toml::node &>(table_)) + ": key '" +
                         key_path(key) + "': " + reason);
    }

    void check(bool ok, const std::string &key, const std::string &rule, double got) const {
        if (!ok)
            fail(key, rule + " (got " + number_text(got) + ")");
    }

    // Reports the first unknown key in file order.
    void only(const std::vector<std::string> &known) const {
        const toml::node *first = nullptr;
        std::string first_key;
        for (const auto &[k, v] : table_) {
            const std::string key(k.str());
            if (std::find(known.begin(), known.end(), key) != known.end())
                continue;
            if (!first || v.source().begin.line < first->source().begin.line) {
                first = &v;
                first_key = key;
            }
        }
        if (first)
            fail(first_key, "unknown key" + hint(first_key, known));
    }

    void require(const std::string &key, const std::string &why = "") const {
        if (!has(key))
            fail(key, "missing required key" + why);
    }

    // Keys that belong to another shape or wall type are mistakes, not noise.
    void forbid_others(const std::vector<std::string> &allowed, const std::string &what) const {
        for (const auto &[k, v] : table_) {
            const std::string key(k.str());
            if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
                fail(key, "not used by " + what);
        }
    }

    double number_at(const toml::node &n, const std::string &key, const std::string &unit) const {
        if (!n.is_number())
            fail(key,
                 "must be a number" + (unit.empty() ? "" : " in " + unit) + " (got " + type_name(n) + ")");
        const double v = *n.value<double>();
        if (!std::isfinite(v))
            fail(key, "must be a finite number (got " + number_text(v) + ")");
        return v;
    }

    double num(const std::string &key, double fallback, const std::string &unit = "") const {
        const toml::node *n = node(key);
        return n ? number_at(*n, key, unit) : fallback;
    }

    std::optional<double> optional_num(const std::string &key, const std::string &unit = "") const {
        const toml::node *n = node(key);
        if (!n)
            return std::nullopt;
        return number_at(*n, key, unit);
    }

    long long integer(const std::string &key, long long fallback) const {
        const toml::node *n = node(key);
        if (!n)
            return fallback;
        if (!n->is_integer())
            fail(key, "must be an integer (got " + type_name(*n) + ")");
        return n->as_integer()->get();
    }

    // An int-sized count with a lower bound.
    int count(const std::string &key, int fallback, int min) const {
        const long long v = integer(key, fallback);
        if (v < min || v > INT_MAX)
            fail(key, "must be an integer in [" + std::to_string(min) + ", " + std::to_string(INT_MAX) +
                          "] (got " + std::to_string(v) + ")");
        return static_cast<int>(v);
    }

    std::string str(const std::string &key, const std::string &fallback) const {
        const toml::node *n = node(key);
        if (!n)
            return fallback;
        if (!n->is_string())
            fail(key, "must be a string (got " + type_name(*n) + ")");
        return n->as_string()->get();
    }

    std::string name(const std::string &key) const {
        require(key);
        const std::string s = str(key, "");
        if (s.empty())
            fail(key, "must not be empty");
        return s;
    }

    std::string choice(const std::string &key, const std::string &fallback,
                       const std::vector<std::string> &options) const {
        const std::string s = str(key, fallback);
        if (std::find(options.begin(), options.end(), s) == options.end()) {
            const std::string best = nearest(s, options);
            fail(key, "must be one of " + choices(options) + " (got " + toml_string(s) +
                          (best.empty() ? "" : "; did you mean " + toml_string(best) + "?") + ")");
        }
        return s;
    }

    bool boolean(const std::string &key, bool fallback) const {
        const toml::node *n = node(key);
        if (!n)
            return fallback;
        if (!n->is_boolean())
            fail(key, "must be true or false (got " + type_name(*n) + ")");
        return n->as_boolean()->get();
    }

    template <int N>
    Eigen::Matrix<double, N, 1> vec(const std::string &key, const Eigen::Matrix<double, N, 1> &fallback,
                                    const std::string &unit, const std::string &shape) const {
        const toml::node *n = node(key);
        if (!n)
            return fallback;
        const std::string rule = "must be an array of " + std::to_string(N) + " numbers " + shape +
                                 (unit.empty() ? "" : " in " + unit);
        const toml::array *a = n->as_array();
        if (!a)
            fail(key, rule + " (got " + type_name(*n) + ")");
        if (a->size() != static_cast<std::size_t>(N))
            fail(key, rule + " (got " + std::to_string(a->size()) + " entries)");
        Eigen::Matrix<double, N, 1> v;
        for (int i = 0; i < N; ++i)
            v[i] = entry_number(key, rule, *a, static_cast<std::size_t>(i));
        return v;
    }

    Eigen::Vector3d vec3(const std::string &key, const Eigen::Vector3d &fallback,
                         const std::string &unit) const {
        return vec<3>(key, fallback, unit, "[x, y, z]");
    }

    // A list of any length (an empty one too), each entry a finite number.
    std::vector<double> numbers(const std::string &key, const std::string &unit) const {
        const toml::node &n = *node(key);
        const std::string rule = "must be an array of numbers" + (unit.empty() ? "" : " in " + unit);
        const toml::array *a = n.as_array();
        if (!a)
            fail(key, rule + " (got " + type_name(n) + ")");
        std::vector<double> out;
        for (std::size_t i = 0; i < a->size(); ++i)
            out.push_back(entry_number(key, rule, *a, i));
        return out;
    }

    // Entry i of an array of numbers, refused under `rule` when it is not a finite number.
    double entry_number(const std::string &key, const std::string &rule, const toml::array &a,
                        std::size_t i) const {
        const toml::node &e = *a.get(i);
        if (!e.is_number())
            fail(key, rule + " (entry " + std::to_string(i) + " is " + type_name(e) + ")");
        const double v = *e.value<double>();
        if (!std::isfinite(v))
            fail(key, rule + " (entry " + std::to_string(i) + " is " + number_text(v) + ")");
        return v;
    }

    std::array<bool, 3> flags(const std::string &key, const std::array<bool, 3> &fallback) const {
        const toml::node *n = node(key);
        if (!n)
            return fallback;
        const toml::array *a = n->as_array();
        const std::string rule = "must be an array of 3 booleans [x, y, z]";
        if (!a || a->size() != 3)
            fail(key, rule + " (got " + (a ? std::to_string(a->size()) + " entries" : type_name(*n)) + ")");
        std::array<bool, 3> out{};
        for (std::size_t i = 0; i < 3; ++i) {
            if (!a->get(i)->is_boolean())
                fail(key, rule + " (entry " + std::to_string(i) + " is " + type_name(*a->get(i)) + ")");
            out[i] = a->get(i)->as_boolean()->get();
        }
        return out;
    }

    std::array<int, 3> cells(const std::string &key) const {
        const toml::node &n = *node(key);
        const toml::array *a = n.as_array();
        const std::string rule = "must be an array of 3 integers [nx, ny, nz], each >= 1";
        if (!a || a->size() != 3)
            fail(key, rule + " (got " + (a ? std::to_string(a->size()) + " entries" : type_name(n)) + ")");
        std::array<int, 3> out{};
        for (std::size_t i = 0; i < 3; ++i) {
            const toml::node &e = *a->get(i);
            if (!e.is_integer() || e.as_integer()->get() < 1 || e.as_integer()->get() > 100000)
                fail(key, rule + " (entry " + std::to_string(i) + " is " + type_name(e) + ")");
            out[i] = static_cast<int>(e.as_integer()->get());
        }
        return out;
    }

    // An optional single table ([run]); absent reads as empty.
    Table section(const std::string &key) const {
        static const toml::table empty;
        const toml::node *n = node(key);
        if (!n)
            return Table(file_, empty, key_path(key));
        if (!n->is_table())
            fail(key, "must be a table [" + key + "] (got " + type_name(*n) + ")");
        return Table(file_, *n->as_table(), key_path(key));
    }

    // An optional array of tables ([[unit]]).
    std::vector<Table> entries(const std::string &key) const {
        std::vector<Table> out;
        const toml::node *n = node(key);
        if (!n)
            return out;
        const std::string rule = "must be an array of tables, written [[" + key + "]]";
        const toml::array *a = n->as_array();
        if (!a)
            fail(key, rule + " (got " + type_name(*n) + ")");
        for (std::size_t i = 0; i < a->size(); ++i) {
            const toml::node &e = *a->get(i);
            const std::string path = key_path(key) + "." + std::to_string(i);
            if (!e.is_table())
                throw InputError(location(file_, e) + ": key '" + path + "': " + rule + " (entry is " +
                                 type_name(e) + ")");
            out.emplace_back(file_, *e.as_table(), path);
        }
        return out;
    }

  private:
    const std::string &file_;
    const toml::table &table_;
    std::string path_;
};

// Paths in a scene are relative to the scene file's folder, so a scene and
// its meshes move together.
inline std::string scene_relative_file(const Table &t, const std::string &key) {
    t.require(key);
    const std::string given = t.str(key, "");
    if (given.empty())
        t.fail(key, "must not be empty");
    std::filesystem::path p(given);
    if (p.is_relative())
        p = std::filesystem::absolute(std::filesystem::path(t.file()).parent_path() / p);
    p = p.lexically_normal();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec))
        t.fail(key, "no such file: " + p.string());
    return p.string();
}

// Reads a present key into its field, checking its type, range and choices
// as the table declares them.
template <class S> void read_value(const Table &t, const Key<S> &k, S &obj) {
    const std::string name = k.name;
    if (!t.has(name))
        return;
    const std::string unit = k.unit;
    const auto in_range = [&](double v) {
        if (k.range.bounded())
            t.check(k.range.contains(v), name, "must be " + k.range.text() + (unit.empty() ? "" : " " + unit),
                    v);
        return v;
    };
    const int lowest = std::isfinite(k.range.lo) ? static_cast<int>(k.range.lo) : INT_MIN;
    std::visit(overloaded{
                   [&](std::string S::*f) {
                       if (k.path)
                           obj.*f = scene_relative_file(t, name);
                       else if (!k.choices.empty())
                           obj.*f = t.choice(name, "", k.choices);
                       else
                           obj.*f = t.name(name);
                   },
                   [&](double S::*f) { obj.*f = in_range(t.num(name, 0.0, unit)); },
                   [&](std::optional<double> S::*f) { obj.*f = in_range(t.num(name, 0.0, unit)); },
                   [&](int S::*f) { obj.*f = t.count(name, 0, lowest); },
                   [&](std::uint64_t S::*f) {
                       const long long v = t.integer(name, 0);
                       if (v < lowest)
                           t.fail(name, "must be >= " + std::to_string(lowest) + " (got " +
                                            std::to_string(v) + ")");
                       obj.*f = static_cast<std::uint64_t>(v);
                   },
                   [&](bool S::*f) { obj.*f = t.boolean(name, false); },
                   [&](std::optional<bool> S::*f) { obj.*f = t.boolean(name, false); },
                   [&](Eigen::Vector3d S::*f) { obj.*f = t.vec3(name, obj.*f, unit); },
                   [&](std::optional<Eigen::Vector3d> S::*f) {
                       obj.*f = t.vec3(name, Eigen::Vector3d::Zero(), unit);
                   },
                   [&](Eigen::Vector4d S::*f) { obj.*f = t.vec<4>(name, obj.*f, unit, "[w, x, y, z]"); },
                   [&](std::array<bool, 3> S::*f) { obj.*f = t.flags(name, obj.*f); },
                   [&](std::array<int, 3> S::*f) { obj.*f = t.cells(name); },
                   [&](std::vector<double> S::*f) {
                       obj.*f = t.numbers(name, unit);
                       for (const double v : obj.*f)
                           in_range(v);
                   },
               },
               k.field);
}

// Every key of the entry that applies to `variant` (a shape or wall type),
// except those the reader handles itself (Need::Custom).
template <class S>
void read_keys(const Table &t, const std::vector<Key<S>> &keys, S &obj, const std::string &variant = "") {
    for (const auto &k : keys) {
        if (k.need == Need::Custom || (*k.when && variant != k.when))
            continue;
        if (k.need == Need::Required)
            t.require(k.name, k.required_note);
        read_value(t, k, obj);
    }
}

template <class S> const Key<S> &key_named(const std::vector<Key<S>> &keys, const std::string &name) {
    for (const auto &k : keys)
        if (name == k.name)
            return k;
    throw std::logic_error("scene key table: no key " + name);
}

template <class S>
std::vector<std::string> names_of(const std::vector<Key<S>> &keys, const char *when = nullptr) {
    std::vector<std::string> names;
    for (const auto &k : keys)
        if (!when || !*k.when || std::string(when) == k.when)
            names.push_back(k.name);
    return names;
}

} // namespace armour::scene_detail
