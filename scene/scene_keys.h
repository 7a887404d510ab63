// The scene key table: every key of a scene file declared once.
//
// Description
//     Each key names its field in the scene structs (scene.h, whose member
//     initialisers are the defaults), its SI unit, the range or choices it
//     must meet and one line of documentation. The reader (scene_read.cpp)
//     checks type and range from here, the writer (scene_write.cpp) writes
//     scene.resolved.toml from here, and docs/scenes.md's key reference is
//     generated from here (scene_keys_markdown, the `scene_keys` tool; a test
//     fails when the document and the table differ). Rules that tie one key
//     to another (chamfer < size/2, air_density < fluid_density) are checked
//     in the reader and stated in the key's doc line.
//
// Usage
//     for (const SceneSection &section : scene_sections())
//         for (const KeyInfo &key : section.keys())
//             std::cout << key.dotted << " [" << key.unit << "]\n";
//     std::string block = scene_keys_markdown("run");
#pragma once

#include "scene.h"

#include <cstdint>
#include <limits>
#include <string>
#include <variant>
#include <vector>

namespace armour {

// Allowed interval of a number (integers use lo only); unbounded by default.
struct Range {
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool lo_open = false, hi_open = false;

    static Range above(double lo) { return {lo, std::numeric_limits<double>::infinity(), true, false}; }
    static Range at_least(double lo) { return {lo, std::numeric_limits<double>::infinity(), false, false}; }
    static Range open(double lo, double hi) { return {lo, hi, true, true}; }
    static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
    static Range open_closed(double lo, double hi) { return {lo, hi, true, false}; } // (lo, hi]
    static Range closed_open(double lo, double hi) { return {lo, hi, false, true}; } // [lo, hi)

    bool bounded() const;
    bool contains(double v) const;
    std::string text() const; // "> 0", "in (0, 90]", "" when unbounded
};

enum class Need {
    Optional, // absent: the struct's default
    Required, // absent: "missing required key"
    Custom,   // read by the reader itself, scene_read*.cpp (defaults or presence depend on other keys)
};

template <class S>
using Field =
    std::variant<std::string S::*, double S::*, int S::*, bool S::*, std::uint64_t S::*, Eigen::Vector3d S::*,
                 Eigen::Vector4d S::*, std::array<bool, 3> S::*, std::array<int, 3> S::*,
                 std::optional<double> S::*, std::optional<Eigen::Vector3d> S::*, std::optional<bool> S::*,
                 std::vector<double> S::*>;

// One key of a section whose entries are read into an S.
template <class S> struct Key {
    const char *name;
    Field<S> field;
    const char *unit; // SI, "" for none
    const char *doc;  // one line: what it means, and rules tying it to other keys
    Range range{};
    std::vector<std::string> choices{};
    Need need = Need::Optional;
    const char *required_note = "";       // appended to "missing required key"
    const char *when = "";                // the shape or wall type it belongs to ("" = all)
    const char *default_doc = "";         // when the default is not the struct's value
    bool path = false;                    // a file, relative to the scene file's folder
    bool (*written)(const S &) = nullptr; // scene.resolved.toml: only when this holds

    Key in(Range r) const {
        return with([&](Key &k) { k.range = r; });
    }
    Key one_of(std::vector<std::string> c) const {
        return with([&](Key &k) { k.choices = std::move(c); });
    }
    Key required(const char *note = "") const {
        return with([&](Key &k) {
            k.need = Need::Required;
            k.required_note = note;
        });
    }
    Key custom(const char *default_text) const {
        return with([&](Key &k) {
            k.need = Need::Custom;
            k.default_doc = default_text;
        });
    }
    Key only_for(const char *variant) const {
        return with([&](Key &k) { k.when = variant; });
    }
    Key defaults(const char *text) const {
        return with([&](Key &k) { k.default_doc = text; });
    }
    Key file() const {
        return with([&](Key &k) { k.path = true; });
    }
    Key written_if(bool (*predicate)(const S &)) const {
        return with([&](Key &k) { k.written = predicate; });
    }

  private:
    template <class F> Key with(F change) const {
        Key k = *this;
        change(k);
        return k;
    }
};

template <class S, class T> Key<S> key(const char *name, T S::*field, const char *unit, const char *doc) {
    return Key<S>{name, Field<S>(field), unit, doc};
}

// The keys of each section, in the order the resolved scene writes them.
const std::vector<Key<Scene>> &root_keys();
const std::vector<Key<Scene>> &run_keys();
const std::vector<Key<Scene>> &contact_keys();
const std::vector<Key<Scene>> &analysis_keys();
const std::vector<Key<SceneFluid>> &fluid_keys();
const std::vector<Key<SceneMaterial>> &material_keys();
const std::vector<Key<SceneMaterialPair>> &material_pair_keys();
const std::vector<Key<SceneUnit>> &unit_keys();
const std::vector<Key<SceneWall>> &wall_keys();
const std::vector<Key<SceneBody>> &body_keys();
const std::vector<Key<SceneDrop>> &drop_keys();
const std::vector<Key<ScenePattern>> &pattern_keys();
const std::vector<Key<SceneWaves>> &wave_keys();
const std::vector<Key<ScenePorous>> &porous_keys();
const std::vector<Key<SceneSeriesStep>> &series_keys();
const std::vector<Key<SceneRefine>> &refine_keys();

// A key described in words, whatever struct it fills.
struct KeyInfo {
    std::string section; // "" at the top level
    std::string name;
    std::string dotted; // run.duration, unit.size (arrays of tables unindexed)
    std::string type;   // "number", "integer", "string", "[x, y, z]", ...
    std::string unit;
    std::string default_text;
    std::string allowed; // range or choices, "" when any value of the type is allowed
    std::string doc;
    std::string when;
};

enum class SectionKind { Root, Table, ArrayOfTables };

struct SceneSection {
    const char *name; // "" for the top level
    SectionKind kind;
    // Units and walls: the key that picks which other keys apply, and a line per choice.
    const char *selector;
    std::vector<std::pair<std::string, std::string>> variants;
    std::vector<KeyInfo> (*keys)();
};

// In file order: top level, [run], [contact], [analysis], [fluid], [[material]], ...
const std::vector<SceneSection> &scene_sections();
const SceneSection *find_section(const std::string &name);
std::vector<std::string> key_names(const SceneSection &section);

// The Markdown key reference of one section (the block between its markers in docs/scenes.md).
std::string scene_keys_markdown(const std::string &section);
// docs/scenes.md with every generated block replaced by the table's; throws
// InputError for a block marker naming no section.
std::string with_generated_key_reference(const std::string &document);

template <class... F> struct overloaded : F... { using F::operator()...; };
template <class... F> overloaded(F...) -> overloaded<F...>;

// Text helpers shared by the reader and the writer.
std::string number_text(double v); // shortest text reading back as exactly v
std::string figure_text(double v); // a computed figure in a message: 4 significant digits
std::string toml_float(double v);  // a TOML float literal: "1.0", never "1" (an integer)
std::string vector_text(const Eigen::Ref<const Eigen::VectorXd> &v); // "[1.0, -0.5, 2.0]"
std::string toml_string(const std::string &s);

} // namespace armour
