#include "scene.h"

#include "engine_registry.h"
#include "mesh.h"
#include "shapes.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string_view>

namespace armour {

namespace {

namespace fs = std::filesystem;

// The source name toml++ records for nodes that came from --set, so errors
// in overridden values point at the option rather than a file line.
constexpr std::string_view kSetSource = "--set";

// ---------------------------------------------------------------- schema

const std::vector<std::string> kRootKeys = {"name",     "run",           "contact", "analysis",
                                            "material", "material_pair", "unit",    "wall",
                                            "body",     "drop",          "pattern", "fluid"};
// Sections that are one table ([run]) rather than an array of tables ([[unit]]).
const std::set<std::string> kSingleSections = {"run", "contact", "analysis", "fluid"};
// Analyses that measure the fluid's load or its effect: they need a [fluid].
const std::set<std::string> kFluidAnalyses = {"buoyancy", "float",    "still",
                                              "dambreak", "platform", "slope_waves"};

const std::vector<std::string> kUnitCommonKeys = {"name",       "shape",       "density", "spheres",
                                                  "tol_volume", "tol_surface", "method",  "material"};
const std::map<std::string, std::vector<std::string>> kUnitShapeKeys = {
    {"cube", {"size", "chamfer"}}, {"dolos", {"height", "waist"}}, {"stl", {"stl"}}};
const std::vector<std::string> kWallCommonKeys = {"name", "type", "material"};
const std::map<std::string, std::vector<std::string>> kWallTypeKeys = {
    {"plane", {"point", "normal", "size"}},
    {"slope", {"toe_x", "floor_z", "cot", "height", "width", "toe_height"}},
    {"box", {"min", "max"}},
    {"stl", {"file"}}};

std::vector<std::string> joined(std::vector<std::string> a,
                                const std::map<std::string, std::vector<std::string>> &m) {
    for (const auto &[kind, keys] : m)
        for (const auto &k : keys)
            if (std::find(a.begin(), a.end(), k) == a.end())
                a.push_back(k);
    return a;
}

const std::map<std::string, std::vector<std::string>> &section_keys() {
    static const std::map<std::string, std::vector<std::string>> keys = {
        {"run",
         {"engine", "duration", "output_interval", "time_step", "force_time_step", "gravity", "domain_min",
          "domain_max"}},
        {"contact", {"model", "characteristic_velocity"}},
        {"analysis", {"kind", "tilt_rate", "tilt_max"}},
        {"material",
         {"name", "youngs_modulus", "poisson_ratio", "restitution", "friction", "rolling_friction"}},
        {"material_pair", {"a", "b", "restitution", "friction", "rolling_friction"}},
        {"unit", joined(kUnitCommonKeys, kUnitShapeKeys)},
        {"wall", joined(kWallCommonKeys, kWallTypeKeys)},
        {"body",
         {"unit", "position", "orientation", "velocity", "angular_velocity", "fixed_translation",
          "fixed_rotation", "pivot"}},
        {"drop", {"unit", "count", "min", "max", "seed"}},
        {"pattern", {"unit", "wall", "rows", "columns", "spacing", "gap"}},
        {"fluid", {"case",           "water_level",     "cells",         "cell_size",   "penalty",
                   "mask",           "smoothing_cells", "added_mass",    "np",          "fluid_density",
                   "air_density",    "viscosity",       "air_viscosity", "max_courant", "max_time_step",
                   "write_interval", "water_box_min",   "water_box_max", "wave_height", "frozen",
                   "settle_time"}},
    };
    return keys;
}

// ---------------------------------------------------------------- text helpers

// Shortest text that reads back as exactly the same double, so the resolved
// scene reloads bit for bit.
std::string number(double v) {
    char buf[64];
    const auto result = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, result.ptr);
}

// A TOML float literal: "1" would read back as an integer and "-0" would lose its sign.
std::string toml_float(double v) {
    std::string s = number(v);
    if (s.find_first_of(".eEn") == std::string::npos)
        s += ".0";
    return s;
}

std::string quote(const std::string &s) {
    std::string out = "\"";
    for (const char c : s) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (u < 0x20 || u == 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(u));
            out += buf;
        } else {
            out += c;
        }
    }
    return out + "\"";
}

std::string join(const std::vector<std::string> &items, const std::string &sep) {
    std::string out;
    for (std::size_t i = 0; i < items.size(); ++i)
        out += (i ? sep : "") + items[i];
    return out;
}

std::size_t edit_distance(const std::string &a, const std::string &b) {
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
std::string nearest(const std::string &key, const std::vector<std::string> &known) {
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
std::string hint(const std::string &key, const std::vector<std::string> &known) {
    const std::string best = nearest(key, known);
    if (!best.empty())
        return " (did you mean '" + best + "'?)";
    return " (known: " + join(known, ", ") + ")";
}

std::string type_name(const toml::node &n) {
    switch (n.type()) {
    case toml::node_type::string:
        return "string " + quote(n.as_string()->get());
    case toml::node_type::integer:
        return "integer " + std::to_string(n.as_integer()->get());
    case toml::node_type::floating_point:
        return "float " + number(n.as_floating_point()->get());
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

std::string choices(const std::vector<std::string> &options) {
    std::vector<std::string> q;
    for (const auto &o : options)
        q.push_back(quote(o));
    return join(q, ", ");
}

// ---------------------------------------------------------------- reading

// Where a node came from: "--set" for overrides, else FILE:LINE.
std::string location(const std::string &file, const toml::node &n) {
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
            fail(key, rule + " (got " + number(got) + ")");
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
            fail(key, "must be a finite number (got " + number(v) + ")");
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
            fail(key, "must be one of " + choices(options) + " (got " + quote(s) +
                          (best.empty() ? "" : "; did you mean " + quote(best) + "?") + ")");
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
        for (int i = 0; i < N; ++i) {
            const toml::node &e = *a->get(static_cast<std::size_t>(i));
            if (!e.is_number())
                fail(key, rule + " (entry " + std::to_string(i) + " is " + type_name(e) + ")");
            v[i] = *e.value<double>();
            if (!std::isfinite(v[i]))
                fail(key, rule + " (entry " + std::to_string(i) + " is " + number(v[i]) + ")");
        }
        return v;
    }

    Eigen::Vector3d vec3(const std::string &key, const Eigen::Vector3d &fallback,
                         const std::string &unit) const {
        return vec<3>(key, fallback, unit, "[x, y, z]");
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
std::string scene_relative_file(const Table &t, const std::string &key, const std::string &scene_file) {
    t.require(key);
    const std::string given = t.str(key, "");
    if (given.empty())
        t.fail(key, "must not be empty");
    fs::path p(given);
    if (p.is_relative())
        p = fs::absolute(fs::path(scene_file).parent_path() / p);
    p = p.lexically_normal();
    std::error_code ec;
    if (!fs::is_regular_file(p, ec))
        t.fail(key, "no such file: " + p.string());
    return p.string();
}

// Unit vectors are stored normalised; a vector already normalised is kept
// bit for bit so that the resolved scene reloads unchanged.
template <typename V> V normalised(const V &v) {
    const double n2 = v.squaredNorm();
    return std::abs(n2 - 1.0) <= 1e-14 ? v : V(v / std::sqrt(n2));
}

std::string material_of(const Table &t, const std::vector<SceneMaterial> &materials) {
    std::vector<std::string> names;
    for (const auto &m : materials)
        names.push_back(m.name);
    if (!t.has("material")) {
        if (materials.size() == 1)
            return materials[0].name;
        t.fail("material", "missing required key: there are " + std::to_string(materials.size()) +
                               " materials, name one of " + choices(names));
    }
    const std::string m = t.str("material", "");
    if (std::find(names.begin(), names.end(), m) == names.end())
        t.fail("material", "no [[material]] named " + quote(m) + " (known: " + choices(names) + ")");
    return m;
}

bool inside(const Eigen::Vector3d &p, const Eigen::Vector3d &lo, const Eigen::Vector3d &hi) {
    return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
}

std::string vec_text(const Eigen::Ref<const Eigen::VectorXd> &v) {
    std::vector<std::string> parts;
    for (Eigen::Index i = 0; i < v.size(); ++i)
        parts.push_back(toml_float(v[i]));
    return "[" + join(parts, ", ") + "]";
}

void read_run(const Table &root, Scene &s) {
    const Table run = root.section("run");
    run.only(section_keys().at("run"));
    std::vector<std::string> engines;
    for (const EngineStyle &style : engine_styles())
        engines.push_back(style.name);
    s.engine = run.choice("engine", s.engine, engines);
    s.duration = run.num("duration", s.duration, "s");
    run.check(s.duration > 0, "duration", "must be > 0 s", s.duration);
    s.output_interval = run.num("output_interval", s.output_interval, "s");
    run.check(s.output_interval > 0, "output_interval", "must be > 0 s", s.output_interval);
    run.check(s.output_interval <= s.duration, "output_interval",
              "must be <= run.duration = " + number(s.duration) + " s", s.output_interval);
    s.time_step = run.num("time_step", s.time_step, "s");
    run.check(s.time_step >= 0, "time_step", "must be >= 0 s (0 = automatic)", s.time_step);
    run.check(s.time_step <= s.output_interval, "time_step",
              "must be <= run.output_interval = " + number(s.output_interval) + " s", s.time_step);
    s.force_time_step = run.boolean("force_time_step", s.force_time_step);
    s.gravity = run.vec3("gravity", s.gravity, "m/s^2");
    s.domain_min = run.vec3("domain_min", s.domain_min, "m");
    s.domain_max = run.vec3("domain_max", s.domain_max, "m");
    if (!(s.domain_max.array() > s.domain_min.array()).all())
        run.fail("domain_max", "must exceed run.domain_min " + vec_text(s.domain_min) +
                                   " m in every component (got " + vec_text(s.domain_max) + ")");
}

void read_contact_and_analysis(const Table &root, Scene &s) {
    const Table contact = root.section("contact");
    contact.only(section_keys().at("contact"));
    s.contact_model = contact.choice("model", s.contact_model, {"hertz", "hooke"});
    s.characteristic_velocity = contact.num("characteristic_velocity", s.characteristic_velocity, "m/s");
    contact.check(s.characteristic_velocity > 0, "characteristic_velocity", "must be > 0 m/s",
                  s.characteristic_velocity);

    const Table analysis = root.section("analysis");
    analysis.only(section_keys().at("analysis"));
    s.analysis = analysis.choice("kind", s.analysis,
                                 {"none", "tilt", "slope", "bounce", "buoyancy", "float", "still", "dambreak",
                                  "platform", "slope_waves"});
    if (kFluidAnalyses.count(s.analysis) && !root.has("fluid"))
        analysis.fail("kind",
                      "kind " + quote(s.analysis) + " measures the fluid: the scene needs a [fluid] table");
    if (s.analysis == "tilt")
        analysis.require("tilt_rate", " for kind \"tilt\"");
    s.tilt_rate = analysis.num("tilt_rate", s.tilt_rate, "deg/s");
    analysis.check(s.tilt_rate >= 0, "tilt_rate", "must be >= 0 deg/s", s.tilt_rate);
    analysis.check(s.analysis != "tilt" || s.tilt_rate > 0, "tilt_rate",
                   "must be > 0 deg/s for kind \"tilt\"", s.tilt_rate);
    s.tilt_max = analysis.num("tilt_max", s.tilt_max, "deg");
    analysis.check(s.tilt_max > 0 && s.tilt_max <= 90, "tilt_max", "must be in (0, 90] deg", s.tilt_max);
}

// Coefficient ranges shared by [[material]] and [[material_pair]].
void check_restitution(const Table &t, double v) {
    t.check(v > 0 && v <= 1, "restitution", "must be in (0, 1]", v);
}
void check_friction(const Table &t, const std::string &key, double v) {
    t.check(v >= 0, key, "must be >= 0", v);
}

void read_materials(const Table &root, Scene &s) {
    for (const Table &t : root.entries("material")) {
        t.only(section_keys().at("material"));
        SceneMaterial m;
        m.name = t.name("name");
        for (const auto &other : s.materials)
            if (other.name == m.name)
                t.fail("name", "duplicate material name " + quote(m.name));
        m.youngs_modulus = t.num("youngs_modulus", m.youngs_modulus, "Pa");
        t.check(m.youngs_modulus > 0, "youngs_modulus", "must be > 0 Pa", m.youngs_modulus);
        m.poisson_ratio = t.num("poisson_ratio", m.poisson_ratio);
        t.check(m.poisson_ratio > -1 && m.poisson_ratio < 0.5, "poisson_ratio", "must be in (-1, 0.5)",
                m.poisson_ratio);
        m.restitution = t.num("restitution", m.restitution);
        check_restitution(t, m.restitution);
        m.friction = t.num("friction", m.friction);
        check_friction(t, "friction", m.friction);
        m.rolling_friction = t.num("rolling_friction", m.rolling_friction);
        check_friction(t, "rolling_friction", m.rolling_friction);
        s.materials.push_back(m);
    }
    if (s.materials.empty())
        root.fail("material", "at least one [[material]] is required");

    std::vector<std::string> names;
    for (const auto &m : s.materials)
        names.push_back(m.name);
    for (const Table &t : root.entries("material_pair")) {
        t.only(section_keys().at("material_pair"));
        SceneMaterialPair p;
        for (const char *key : {"a", "b"}) {
            const std::string m = t.name(key);
            if (std::find(names.begin(), names.end(), m) == names.end())
                t.fail(key, "no [[material]] named " + quote(m) + " (known: " + choices(names) + ")");
            (key[0] == 'a' ? p.a : p.b) = m;
        }
        for (const auto &other : s.material_pairs)
            if ((other.a == p.a && other.b == p.b) || (other.a == p.b && other.b == p.a))
                t.fail("b", "duplicate pair " + quote(p.a) + " / " + quote(p.b));
        p.restitution = t.optional_num("restitution");
        if (p.restitution)
            check_restitution(t, *p.restitution);
        p.friction = t.optional_num("friction");
        if (p.friction)
            check_friction(t, "friction", *p.friction);
        p.rolling_friction = t.optional_num("rolling_friction");
        if (p.rolling_friction)
            check_friction(t, "rolling_friction", *p.rolling_friction);
        s.material_pairs.push_back(p);
    }
}

void read_units(const Table &root, Scene &s) {
    for (const Table &t : root.entries("unit")) {
        t.only(section_keys().at("unit"));
        SceneUnit u;
        u.name = t.name("name");
        for (const auto &other : s.units)
            if (other.name == u.name)
                t.fail("name", "duplicate unit name " + quote(u.name));
        t.require("shape");
        u.shape = t.choice("shape", "", {"cube", "dolos", "stl"});
        std::vector<std::string> allowed = kUnitCommonKeys;
        const auto &own = kUnitShapeKeys.at(u.shape);
        allowed.insert(allowed.end(), own.begin(), own.end());
        t.forbid_others(allowed, "shape " + quote(u.shape) + " (its keys: " + join(own, ", ") + ")");
        if (u.shape == "cube") {
            t.require("size", " for shape \"cube\" (edge length, m)");
            u.size = t.num("size", 0, "m");
            t.check(u.size > 0, "size", "must be > 0 m", u.size);
            u.chamfer = t.num("chamfer", u.chamfer, "m");
            t.check(u.chamfer >= 0 && u.chamfer < 0.5 * u.size, "chamfer",
                    "must be in [0, size/2) = [0, " + number(0.5 * u.size) + ") m", u.chamfer);
        } else if (u.shape == "dolos") {
            t.require("height", " for shape \"dolos\" (overall height, m)");
            u.height = t.num("height", 0, "m");
            t.check(u.height > 0, "height", "must be > 0 m", u.height);
            u.waist = t.num("waist", u.waist);
            t.check(u.waist >= kDolosWaistMin && u.waist <= kDolosWaistMax, "waist",
                    "must be in [" + number(kDolosWaistMin) + ", " + number(kDolosWaistMax) + "]", u.waist);
        } else {
            u.stl = scene_relative_file(t, "stl", s.file);
        }
        u.density = t.num("density", u.density, "kg/m^3");
        t.check(u.density > 0, "density", "must be > 0 kg/m^3", u.density);
        if (t.has("spheres"))
            u.spheres = t.count("spheres", 0, 1);
        u.tol_volume = t.num("tol_volume", u.tol_volume);
        t.check(u.tol_volume > 0 && u.tol_volume < 1, "tol_volume", "must be a fraction in (0, 1)",
                u.tol_volume);
        u.tol_surface = t.num("tol_surface", u.tol_surface);
        t.check(u.tol_surface > 0 && u.tol_surface < 1, "tol_surface", "must be a fraction of Dn in (0, 1)",
                u.tol_surface);
        u.method = t.choice("method", u.method, {"greedy", "optimised"});
        u.material = material_of(t, s.materials);
        s.units.push_back(u);
    }
}

void read_walls(const Table &root, Scene &s) {
    const auto entries = root.entries("wall");
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const Table &t = entries[i];
        t.only(section_keys().at("wall"));
        SceneWall w;
        t.require("type");
        w.type = t.choice("type", "", {"plane", "slope", "box", "stl"});
        // Walls need a name only when a [[pattern]] refers to them.
        w.name = t.has("name") ? t.name("name") : w.type + "_" + std::to_string(i);
        for (const auto &other : s.walls)
            if (other.name == w.name)
                t.fail("name", "duplicate wall name " + quote(w.name));
        std::vector<std::string> allowed = kWallCommonKeys;
        const auto &own = kWallTypeKeys.at(w.type);
        allowed.insert(allowed.end(), own.begin(), own.end());
        t.forbid_others(allowed, "wall type " + quote(w.type) + " (its keys: " + join(own, ", ") + ")");
        if (w.type == "plane") {
            t.require("point", " for type \"plane\"");
            t.require("normal", " for type \"plane\"");
            w.point = t.vec3("point", w.point, "m");
            const Eigen::Vector3d n = t.vec3("normal", w.normal, "");
            if (n.norm() < 1e-12)
                t.fail("normal", "must be a non-zero vector (got " + vec_text(n) + ")");
            w.normal = normalised(n);
            w.size = t.num("size", w.size, "m");
            t.check(w.size > 0, "size", "must be > 0 m", w.size);
        } else if (w.type == "slope") {
            for (const char *key : {"cot", "height", "width"})
                t.require(key, " for type \"slope\"");
            w.toe_x = t.num("toe_x", w.toe_x, "m");
            w.floor_z = t.num("floor_z", w.floor_z, "m");
            w.cot = t.num("cot", w.cot);
            t.check(w.cot > 0, "cot", "must be > 0 (horizontal per vertical)", w.cot);
            w.height = t.num("height", w.height, "m");
            t.check(w.height > 0, "height", "must be > 0 m", w.height);
            w.width = t.num("width", w.width, "m");
            t.check(w.width > 0, "width", "must be > 0 m", w.width);
            w.toe_height = t.num("toe_height", w.toe_height, "m");
            t.check(w.toe_height >= 0 && w.toe_height < w.height, "toe_height",
                    "must be in [0, height) = [0, " + number(w.height) + ") m", w.toe_height);
        } else if (w.type == "box") {
            t.require("min", " for type \"box\"");
            t.require("max", " for type \"box\"");
            w.min = t.vec3("min", w.min, "m");
            w.max = t.vec3("max", w.max, "m");
            if (!(w.max.array() > w.min.array()).all())
                t.fail("max", "must exceed min " + vec_text(w.min) + " m in every component (got " +
                                  vec_text(w.max) + ")");
        } else {
            w.file = scene_relative_file(t, "file", s.file);
        }
        w.material = material_of(t, s.materials);
        s.walls.push_back(w);
    }
}

void read_fluid(const Table &root, Scene &s) {
    if (!root.has("fluid"))
        return;
    const Table t = root.section("fluid");
    t.only(section_keys().at("fluid"));
    SceneFluid f;
    f.case_name = t.str("case", f.case_name);
    if (f.case_name.empty() || f.case_name.find('/') != std::string::npos || f.case_name[0] == '.')
        t.fail("case",
               "must name a template folder in foam_cases/, e.g. \"tank\" (got " + quote(f.case_name) + ")");
    // A water column (water_box_min/max) may replace the level: the level
    // then defaults to the mesh's bottom (no water outside the column).
    if (t.has("water_box_min") != t.has("water_box_max"))
        t.fail(t.has("water_box_min") ? "water_box_max" : "water_box_min",
               "missing: give both water_box_min and water_box_max (m)");
    f.has_water_box = t.has("water_box_min");
    if (f.has_water_box) {
        f.water_box_min = t.vec3("water_box_min", f.water_box_min, "m");
        f.water_box_max = t.vec3("water_box_max", f.water_box_max, "m");
        if (!(f.water_box_max.array() > f.water_box_min.array()).all())
            t.fail("water_box_max", "must exceed fluid.water_box_min " + vec_text(f.water_box_min) +
                                        " m in every component (got " + vec_text(f.water_box_max) + ")");
    } else {
        t.require("water_level", " (z of the still-water surface, m)");
    }
    f.water_level = t.num("water_level", s.domain_min.z(), "m");
    t.check((f.water_level > s.domain_min.z() || (f.has_water_box && f.water_level == s.domain_min.z())) &&
                f.water_level < s.domain_max.z(),
            "water_level",
            "must lie inside run.domain_min.z .. run.domain_max.z = (" + number(s.domain_min.z()) + ", " +
                number(s.domain_max.z()) + ") m",
            f.water_level);
    f.wave_height = t.num("wave_height", f.wave_height, "m");
    t.check(f.wave_height >= 0 && (f.wave_height == 0 || f.wave_height < f.water_level - s.domain_min.z()),
            "wave_height", "must be in [0, the still-water depth water_level - run.domain_min.z) m",
            f.wave_height);
    if (t.has("cells") == t.has("cell_size"))
        t.fail(t.has("cells") ? "cell_size" : "cells",
               t.has("cells") ? "give either cells or cell_size, not both"
                              : "missing required key: give cells = [nx, ny, nz] or cell_size (m)");
    const Eigen::Vector3d extent = s.domain_max - s.domain_min;
    if (t.has("cells")) {
        const toml::node &n = *t.node("cells");
        const toml::array *a = n.as_array();
        const std::string rule = "must be an array of 3 integers [nx, ny, nz], each >= 1";
        if (!a || a->size() != 3)
            t.fail("cells",
                   rule + " (got " + (a ? std::to_string(a->size()) + " entries" : type_name(n)) + ")");
        for (std::size_t i = 0; i < 3; ++i) {
            const toml::node &e = *a->get(i);
            if (!e.is_integer() || e.as_integer()->get() < 1 || e.as_integer()->get() > 100000)
                t.fail("cells", rule + " (entry " + std::to_string(i) + " is " + type_name(e) + ")");
            f.cells[i] = static_cast<int>(e.as_integer()->get());
        }
    } else {
        f.cell_size = t.num("cell_size", 0.0, "m");
        t.check(f.cell_size > 0 && f.cell_size <= extent.minCoeff(), "cell_size",
                "must be in (0, " + number(extent.minCoeff()) + "] m (the run domain's smallest extent)",
                f.cell_size);
        for (int i = 0; i < 3; ++i)
            f.cells[i] = std::max(1, static_cast<int>(std::lround(extent[i] / f.cell_size)));
    }
    f.penalty = t.num("penalty", f.penalty, "1/s");
    t.check(f.penalty > 0, "penalty", "must be > 0 1/s", f.penalty);
    f.mask = t.choice("mask", f.mask, {"exact", "spheres"});
    f.smoothing_cells = t.num("smoothing_cells", f.smoothing_cells);
    t.check(f.smoothing_cells > 0 && f.smoothing_cells <= 4, "smoothing_cells", "must be in (0, 4] cells",
            f.smoothing_cells);
    f.added_mass = t.num("added_mass", f.added_mass);
    t.check(f.added_mass >= 0, "added_mass", "must be >= 0", f.added_mass);
    f.np = t.count("np", f.np, 1);
    f.fluid_density = t.num("fluid_density", f.fluid_density, "kg/m^3");
    t.check(f.fluid_density > 0, "fluid_density", "must be > 0 kg/m^3", f.fluid_density);
    f.air_density = t.num("air_density", f.air_density, "kg/m^3");
    t.check(f.air_density > 0 && f.air_density < f.fluid_density, "air_density",
            "must be in (0, fluid_density = " + number(f.fluid_density) + ") kg/m^3", f.air_density);
    f.viscosity = t.num("viscosity", f.viscosity, "m^2/s");
    t.check(f.viscosity > 0, "viscosity", "must be > 0 m^2/s (kinematic)", f.viscosity);
    f.air_viscosity = t.num("air_viscosity", f.air_viscosity, "m^2/s");
    t.check(f.air_viscosity > 0, "air_viscosity", "must be > 0 m^2/s (kinematic)", f.air_viscosity);
    // interFoam's interface capturing (MULES) is explicit: it needs Co <= 1.
    f.max_courant = t.num("max_courant", f.max_courant);
    t.check(f.max_courant > 0 && f.max_courant <= 1, "max_courant", "must be in (0, 1]", f.max_courant);
    f.max_time_step = t.num("max_time_step", std::min(f.max_time_step, s.output_interval), "s");
    t.check(f.max_time_step > 0 && f.max_time_step <= s.output_interval, "max_time_step",
            "must be in (0, run.output_interval = " + number(s.output_interval) + "] s", f.max_time_step);
    f.write_interval = t.num("write_interval", s.duration, "s");
    t.check(f.write_interval > 0 && f.write_interval <= s.duration, "write_interval",
            "must be in (0, run.duration = " + number(s.duration) + "] s", f.write_interval);
    f.frozen = t.boolean("frozen", f.frozen);
    f.settle_time = t.num("settle_time", f.settle_time, "s");
    t.check(f.settle_time >= 0 && std::isfinite(f.settle_time), "settle_time", "must be >= 0 s",
            f.settle_time);
    s.fluid = f;
}

std::string unit_of(const Table &t, const Scene &s) {
    const std::string u = t.name("unit");
    std::vector<std::string> names;
    for (const auto &unit : s.units)
        names.push_back(unit.name);
    if (std::find(names.begin(), names.end(), u) == names.end())
        t.fail("unit",
               "no [[unit]] named " + quote(u) +
                   (names.empty() ? " (the scene has no [[unit]])" : " (known: " + choices(names) + ")"));
    return u;
}

void read_placements(const Table &root, Scene &s) {
    const std::string domain =
        "run.domain_min " + vec_text(s.domain_min) + " .. run.domain_max " + vec_text(s.domain_max) + " m";
    for (const Table &t : root.entries("body")) {
        t.only(section_keys().at("body"));
        SceneBody b;
        b.unit = unit_of(t, s);
        t.require("position");
        b.position = t.vec3("position", b.position, "m");
        if (!inside(b.position, s.domain_min, s.domain_max))
            t.fail("position", "must lie inside " + domain + " (got " + vec_text(b.position) + ")");
        const Eigen::Vector4d q = t.vec<4>("orientation", b.orientation, "", "[w, x, y, z]");
        if (q.norm() < 1e-12)
            t.fail("orientation", "must be a non-zero quaternion [w, x, y, z] (got " + vec_text(q) + ")");
        b.orientation = normalised(q);
        b.velocity = t.vec3("velocity", b.velocity, "m/s");
        b.angular_velocity = t.vec3("angular_velocity", b.angular_velocity, "rad/s");
        b.fixed_translation = t.flags("fixed_translation", b.fixed_translation);
        b.fixed_rotation = t.flags("fixed_rotation", b.fixed_rotation);
        if (t.has("pivot")) {
            b.pivot = t.vec3("pivot", Eigen::Vector3d::Zero(), "m");
            if (!engine_style(s.engine).capabilities.pivot) {
                const EngineStyle *hinged =
                    find_engine_style([](const EngineCapabilities &c) { return c.pivot; });
                t.fail("pivot", "needs run.engine = " + quote(hinged ? hinged->name : "an engine with pivots") +
                                    " (got " + quote(s.engine) +
                                    "): the contact engines hold locked axes at the centre of mass");
            }
            if (std::none_of(b.fixed_translation.begin(), b.fixed_translation.end(),
                             [](bool f) { return f; }))
                t.fail("pivot", "holds nothing without fixed_translation (the axes along which the pivot "
                                "point stays put)");
        }
        s.bodies.push_back(b);
    }
    for (const Table &t : root.entries("drop")) {
        t.only(section_keys().at("drop"));
        SceneDrop d;
        d.unit = unit_of(t, s);
        t.require("count");
        d.count = t.count("count", 0, 1);
        t.require("min");
        t.require("max");
        d.min = t.vec3("min", d.min, "m");
        d.max = t.vec3("max", d.max, "m");
        if (!(d.max.array() > d.min.array()).all())
            t.fail("max", "must exceed min " + vec_text(d.min) + " m in every component (got " +
                              vec_text(d.max) + ")");
        if (!inside(d.min, s.domain_min, s.domain_max))
            t.fail("min", "must lie inside " + domain + " (got " + vec_text(d.min) + ")");
        if (!inside(d.max, s.domain_min, s.domain_max))
            t.fail("max", "must lie inside " + domain + " (got " + vec_text(d.max) + ")");
        const long long seed = t.integer("seed", static_cast<long long>(d.seed));
        if (seed < 0)
            t.fail("seed", "must be >= 0 (got " + std::to_string(seed) + ")");
        d.seed = static_cast<std::uint64_t>(seed);
        s.drops.push_back(d);
    }
    for (const Table &t : root.entries("pattern")) {
        t.only(section_keys().at("pattern"));
        ScenePattern p;
        p.unit = unit_of(t, s);
        p.wall = t.name("wall");
        const auto wall = std::find_if(s.walls.begin(), s.walls.end(),
                                       [&](const SceneWall &w) { return w.name == p.wall; });
        if (wall == s.walls.end())
            t.fail("wall", "no [[wall]] named " + quote(p.wall));
        if (wall->type != "slope")
            t.fail("wall", "wall " + quote(p.wall) + " is of type " + quote(wall->type) +
                               "; a pattern needs a \"slope\" wall");
        p.rows = t.count("rows", p.rows, 1);
        p.columns = t.count("columns", p.columns, 1);
        p.spacing = t.num("spacing", p.spacing, "m");
        t.check(p.spacing >= 0, "spacing", "must be >= 0 m (0 = automatic)", p.spacing);
        p.gap = t.num("gap", p.gap, "m");
        t.check(p.gap >= 0, "gap", "must be >= 0 m", p.gap);
        s.patterns.push_back(p);
    }
    if (s.bodies.empty() && s.drops.empty() && s.patterns.empty())
        root.fail("body", "the scene places no units: add a [[body]], [[drop]] or [[pattern]]");
}

// ---------------------------------------------------------------- overrides

bool is_index(const std::string &s) {
    return !s.empty() && s.size() < 10 &&
           std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

std::string trimmed(const std::string &s) {
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos)
        return "";
    return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// The keys a table at `parents` (the path segments leading to it) may hold.
const std::vector<std::string> *known_keys(const std::vector<std::string> &parents) {
    if (parents.empty())
        return &kRootKeys;
    const auto it = section_keys().find(parents[0]);
    if (it == section_keys().end())
        return nullptr;
    const bool single = kSingleSections.count(parents[0]) > 0;
    if ((single && parents.size() == 1) || (!single && parents.size() == 2 && is_index(parents[1])))
        return &it->second;
    return nullptr;
}

void apply_override(toml::table &root, const std::string &text) {
    const auto bad = [&](const std::string &reason) { return InputError("--set '" + text + "': " + reason); };
    const auto eq = text.find('=');
    if (eq == std::string::npos)
        throw bad("expected KEY=VALUE, e.g. run.duration=0.5");
    const std::string key = trimmed(text.substr(0, eq));
    const std::string value = trimmed(text.substr(eq + 1));
    if (key.empty())
        throw bad("empty key");
    if (value.empty())
        throw bad("empty value (strings need quotes: name=\"x\")");
    std::vector<std::string> segments;
    for (std::size_t start = 0;;) {
        const auto dot = key.find('.', start);
        segments.push_back(
            trimmed(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start)));
        if (segments.back().empty())
            throw bad("empty segment in key '" + key + "'");
        if (dot == std::string::npos)
            break;
        start = dot + 1;
    }

    toml::table parsed;
    try {
        parsed = toml::parse("v = " + value + "\n", kSetSource);
    } catch (const toml::parse_error &e) {
        std::string description(e.description());
        std::replace(description.begin(), description.end(), '\n', ' ');
        throw bad("bad TOML value " + value + ": " + description + " (strings need quotes, arrays brackets)");
    }
    if (parsed.size() != 1)
        throw bad("the value must be a single TOML value");

    toml::node *cur = &root;
    std::string at;
    for (std::size_t i = 0; i + 1 < segments.size(); ++i) {
        const std::string &seg = segments[i];
        const std::string here = at.empty() ? seg : at + "." + seg;
        if (toml::table *t = cur->as_table()) {
            toml::node *child = t->get(seg);
            if (!child && cur == &root && kSingleSections.count(seg)) {
                // Sections with all-default values may be absent from the file.
                toml::table created = toml::parse("t = {}", kSetSource);
                t->insert_or_assign(seg, std::move(*created.get("t")));
                child = t->get(seg);
            }
            if (!child)
                throw bad("'" + here + "' does not exist in the scene");
            cur = child;
        } else if (toml::array *a = cur->as_array()) {
            if (!is_index(seg))
                throw bad("'" + at + "' is an array: index it, e.g. " + at + ".0");
            const std::size_t index = std::stoul(seg);
            if (index >= a->size())
                throw bad("index " + seg + " out of range: '" + at + "' has " + std::to_string(a->size()) +
                          " entries");
            cur = a->get(index);
        } else {
            throw bad("'" + at + "' is a single value, not a table");
        }
        at = here;
    }

    const std::string &last = segments.back();
    toml::node &v = *parsed.get("v");
    if (toml::table *t = cur->as_table()) {
        if (!t->contains(last)) {
            const std::vector<std::string> parents(segments.begin(), segments.end() - 1);
            const std::vector<std::string> *known = known_keys(parents);
            if (!known || std::find(known->begin(), known->end(), last) == known->end())
                throw bad("unknown key '" + key + "'" + (known ? hint(last, *known) : std::string()));
        }
        t->insert_or_assign(last, std::move(v));
    } else if (toml::array *a = cur->as_array()) {
        if (!is_index(last))
            throw bad("'" + at + "' is an array: index it, e.g. " + at + ".0");
        const std::size_t index = std::stoul(last);
        if (index >= a->size())
            throw bad("index " + last + " out of range: '" + at + "' has " + std::to_string(a->size()) +
                      " entries");
        a->replace(a->cbegin() + static_cast<std::ptrdiff_t>(index), std::move(v));
    } else {
        throw bad("'" + at + "' is a single value, not a table");
    }
}

std::string read_text(const std::string &path) {
    std::error_code ec;
    if (fs::is_directory(path, ec))
        throw InputError(path + ": cannot read: is a directory");
    errno = 0;
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw InputError(path + ": cannot read: " + (errno ? std::strerror(errno) : "open failed"));
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad())
        throw InputError(path + ": cannot read: read error");
    return text.str();
}

} // namespace

Scene load_scene(const std::string &path, const std::vector<std::string> &overrides) {
    const std::string text = read_text(path);
    toml::table doc;
    try {
        doc = toml::parse(text, std::string_view(path));
    } catch (const toml::parse_error &e) {
        // toml++ descriptions are single-line; keep the message one line regardless.
        std::string description(e.description());
        std::replace(description.begin(), description.end(), '\n', ' ');
        throw InputError(path + ":" + std::to_string(e.source().begin.line) +
                         ": invalid TOML: " + description);
    }
    for (const auto &o : overrides)
        apply_override(doc, o);

    Scene s;
    s.file = path;
    const Table root(path, doc, "");
    root.only(kRootKeys);
    s.name = root.name("name");
    read_run(root, s);
    read_contact_and_analysis(root, s);
    read_fluid(root, s);
    // A coupled run without run.engine takes exact hulls where the build has
    // them: there interFoam takes 97-99 % of the time whichever engine runs,
    // and sphere clumps change the answer (the platform case: 3 of 3 cubes
    // washed off against 2 of 3 with exact cubes; bench/run_coupled_engines.sh,
    // docs/comparison.md).
    if (s.fluid && !root.section("run").has("engine")) {
        if (const EngineStyle *exact = find_engine_style([](const EngineCapabilities &c) {
                return c.contacts != ContactKind::none && c.shape == ShapeModel::convex_hulls;
            }))
            s.engine = exact->name;
    }
    read_materials(root, s);
    read_units(root, s);
    read_walls(root, s);
    read_placements(root, s);
    return s;
}

std::string resolved_scene_toml(const Scene &s) {
    std::ostringstream o;
    const auto f = [](double v) { return toml_float(v); };
    const auto b = [](bool v) { return std::string(v ? "true" : "false"); };
    const auto flags = [&](const std::array<bool, 3> &v) {
        return "[" + b(v[0]) + ", " + b(v[1]) + ", " + b(v[2]) + "]";
    };

    o << "# Resolved scene: " << s.file << " after --set overrides, every default filled in (SI units).\n"
      << "name = " << quote(s.name) << "\n\n"
      << "[run]\n"
      << "engine = " << quote(s.engine) << "\n"
      << "duration = " << f(s.duration) << " # s\n"
      << "output_interval = " << f(s.output_interval) << " # s\n"
      << "time_step = " << f(s.time_step) << " # s, 0 = automatic\n"
      << "force_time_step = " << b(s.force_time_step) << "\n"
      << "gravity = " << vec_text(s.gravity) << " # m/s^2\n"
      << "domain_min = " << vec_text(s.domain_min) << " # m\n"
      << "domain_max = " << vec_text(s.domain_max) << " # m\n\n"
      << "[contact]\n"
      << "model = " << quote(s.contact_model) << "\n"
      << "characteristic_velocity = " << f(s.characteristic_velocity) << " # m/s\n\n"
      << "[analysis]\n"
      << "kind = " << quote(s.analysis) << "\n"
      << "tilt_rate = " << f(s.tilt_rate) << " # deg/s\n"
      << "tilt_max = " << f(s.tilt_max) << " # deg\n";
    if (s.fluid) {
        const SceneFluid &fl = *s.fluid;
        o << "\n[fluid]\n"
          << "case = " << quote(fl.case_name) << "\n"
          << "water_level = " << f(fl.water_level) << " # m\n";
        if (fl.cell_size > 0)
            o << "cell_size = " << f(fl.cell_size) << " # m, giving cells " << fl.cells[0] << " x "
              << fl.cells[1] << " x " << fl.cells[2] << "\n";
        else
            o << "cells = [" << fl.cells[0] << ", " << fl.cells[1] << ", " << fl.cells[2] << "]\n";
        o << "penalty = " << f(fl.penalty) << " # 1/s\n"
          << "mask = " << quote(fl.mask) << "\n"
          << "smoothing_cells = " << f(fl.smoothing_cells) << "\n"
          << "added_mass = " << f(fl.added_mass) << "\n"
          << "np = " << fl.np << "\n"
          << "fluid_density = " << f(fl.fluid_density) << " # kg/m^3\n"
          << "air_density = " << f(fl.air_density) << " # kg/m^3\n"
          << "viscosity = " << f(fl.viscosity) << " # m^2/s\n"
          << "air_viscosity = " << f(fl.air_viscosity) << " # m^2/s\n"
          << "max_courant = " << f(fl.max_courant) << "\n"
          << "max_time_step = " << f(fl.max_time_step) << " # s\n"
          << "write_interval = " << f(fl.write_interval) << " # s\n"
          << "wave_height = " << f(fl.wave_height) << " # m\n"
          << "frozen = " << (fl.frozen ? "true" : "false") << "\n"
          << "settle_time = " << f(fl.settle_time) << " # s\n";
        if (fl.has_water_box)
            o << "water_box_min = " << vec_text(fl.water_box_min) << " # m\n"
              << "water_box_max = " << vec_text(fl.water_box_max) << " # m\n";
    }
    for (const auto &m : s.materials)
        o << "\n[[material]]\n"
          << "name = " << quote(m.name) << "\n"
          << "youngs_modulus = " << f(m.youngs_modulus) << " # Pa\n"
          << "poisson_ratio = " << f(m.poisson_ratio) << "\n"
          << "restitution = " << f(m.restitution) << "\n"
          << "friction = " << f(m.friction) << "\n"
          << "rolling_friction = " << f(m.rolling_friction) << "\n";
    for (const auto &p : s.material_pairs) {
        o << "\n[[material_pair]]\n"
          << "a = " << quote(p.a) << "\n"
          << "b = " << quote(p.b) << "\n";
        if (p.restitution)
            o << "restitution = " << f(*p.restitution) << "\n";
        if (p.friction)
            o << "friction = " << f(*p.friction) << "\n";
        if (p.rolling_friction)
            o << "rolling_friction = " << f(*p.rolling_friction) << "\n";
    }
    for (const auto &u : s.units) {
        o << "\n[[unit]]\n"
          << "name = " << quote(u.name) << "\n"
          << "shape = " << quote(u.shape) << "\n";
        if (u.shape == "cube")
            o << "size = " << f(u.size) << " # m\n"
              << "chamfer = " << f(u.chamfer) << " # m\n";
        else if (u.shape == "dolos")
            o << "height = " << f(u.height) << " # m\n"
              << "waist = " << f(u.waist) << "\n";
        else
            o << "stl = " << quote(u.stl) << "\n";
        o << "density = " << f(u.density) << " # kg/m^3\n";
        if (u.spheres > 0)
            o << "spheres = " << u.spheres << "\n";
        else
            o << "# spheres absent: the fewest spheres meeting the tolerances\n";
        o << "tol_volume = " << f(u.tol_volume) << "\n"
          << "tol_surface = " << f(u.tol_surface) << "\n"
          << "method = " << quote(u.method) << "\n"
          << "material = " << quote(u.material) << "\n";
    }
    for (const auto &w : s.walls) {
        o << "\n[[wall]]\n"
          << "name = " << quote(w.name) << "\n"
          << "type = " << quote(w.type) << "\n";
        if (w.type == "plane")
            o << "point = " << vec_text(w.point) << " # m\n"
              << "normal = " << vec_text(w.normal) << "\n"
              << "size = " << f(w.size) << " # m\n";
        else if (w.type == "slope")
            o << "toe_x = " << f(w.toe_x) << " # m\n"
              << "floor_z = " << f(w.floor_z) << " # m\n"
              << "cot = " << f(w.cot) << "\n"
              << "height = " << f(w.height) << " # m\n"
              << "width = " << f(w.width) << " # m\n"
              << "toe_height = " << f(w.toe_height) << " # m\n";
        else if (w.type == "box")
            o << "min = " << vec_text(w.min) << " # m\n"
              << "max = " << vec_text(w.max) << " # m\n";
        else
            o << "file = " << quote(w.file) << "\n";
        o << "material = " << quote(w.material) << "\n";
    }
    for (const auto &bd : s.bodies)
        o << "\n[[body]]\n"
          << "unit = " << quote(bd.unit) << "\n"
          << "position = " << vec_text(bd.position) << " # m\n"
          << "orientation = " << vec_text(bd.orientation) << " # w, x, y, z\n"
          << "velocity = " << vec_text(bd.velocity) << " # m/s\n"
          << "angular_velocity = " << vec_text(bd.angular_velocity) << " # rad/s\n"
          << "fixed_translation = " << flags(bd.fixed_translation) << "\n"
          << "fixed_rotation = " << flags(bd.fixed_rotation) << "\n"
          << (bd.pivot ? "pivot = " + vec_text(*bd.pivot) + " # m\n" : std::string());
    for (const auto &d : s.drops)
        o << "\n[[drop]]\n"
          << "unit = " << quote(d.unit) << "\n"
          << "count = " << d.count << "\n"
          << "min = " << vec_text(d.min) << " # m\n"
          << "max = " << vec_text(d.max) << " # m\n"
          << "seed = " << d.seed << "\n";
    for (const auto &p : s.patterns)
        o << "\n[[pattern]]\n"
          << "unit = " << quote(p.unit) << "\n"
          << "wall = " << quote(p.wall) << "\n"
          << "rows = " << p.rows << "\n"
          << "columns = " << p.columns << "\n"
          << "spacing = " << f(p.spacing) << " # m\n"
          << "gap = " << f(p.gap) << " # m\n";
    return o.str();
}

} // namespace armour
