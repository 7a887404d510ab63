// Reading a scene file: the key table (scene_keys.h) checks each key's type
// and range; this file adds what ties keys together (references by name,
// one bound given by another key, defaults taken from other sections). The
// --set overrides are applied first (scene_overrides.h). The wave flume's
// sections are read in scene_read_flume.cpp.
#include "scene.h"

#include "engine_registry.h"
#include "input_error.h"
#include "scene_keys.h"
#include "scene_overrides.h"
#include "scene_read_parts.h"
#include "toml_table.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

namespace armour {

using namespace scene_detail;
using namespace scene_read;

namespace {

namespace fs = std::filesystem;

bool inside(const Eigen::Vector3d &p, const Eigen::Vector3d &lo, const Eigen::Vector3d &hi) {
    return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
}

// Analyses that measure the fluid's load or its effect: they need a [fluid].
bool measures_fluid(const std::string &kind) {
    for (const char *k : {"buoyancy", "float", "still", "dambreak", "platform", "slope_waves"})
        if (kind == k)
            return true;
    return false;
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
        t.fail("material", "no [[material]] named " + toml_string(m) + " (known: " + choices(names) + ")");
    return m;
}

// A single table ([run]) read into the scene itself.
void read_table(const Table &root, const char *name, const std::vector<Key<Scene>> &keys, Scene &s) {
    const Table t = root.section(name);
    t.only(names_of(keys));
    read_keys(t, keys, s);
}

void read_run(const Table &root, Scene &s) {
    read_table(root, "run", run_keys(), s);
    const Table run = root.section("run");
    run.check(s.output_interval <= s.duration, "output_interval",
              "must be <= run.duration = " + number_text(s.duration) + " s", s.output_interval);
    run.check(s.time_step <= s.output_interval, "time_step",
              "must be <= run.output_interval = " + number_text(s.output_interval) + " s", s.time_step);
    if (!(s.domain_max.array() > s.domain_min.array()).all())
        run.fail("domain_max", "must exceed run.domain_min " + vector_text(s.domain_min) +
                                   " m in every component (got " + vector_text(s.domain_max) + ")");
}

void read_contact_and_analysis(const Table &root, Scene &s) {
    read_table(root, "contact", contact_keys(), s);
    read_table(root, "analysis", analysis_keys(), s);
    const Table analysis = root.section("analysis");
    if (measures_fluid(s.analysis) && !root.has("fluid"))
        analysis.fail("kind", "kind " + toml_string(s.analysis) +
                                  " measures the fluid: the scene needs a [fluid] table");
    if (s.analysis == "tilt") {
        analysis.require("tilt_rate", " for kind \"tilt\"");
        analysis.check(s.tilt_rate > 0, "tilt_rate", "must be > 0 deg/s for kind \"tilt\"", s.tilt_rate);
    }
    if (s.analysis == "pull") {
        analysis.require("pull_rate", " for kind \"pull\"");
        analysis.check(s.pull_rate > 0, "pull_rate", "must be > 0 weights/s for kind \"pull\"", s.pull_rate);
        // A unit that never left is said to have held pull_max: the pull must get there.
        analysis.check(s.pull_max / s.pull_rate <= s.duration, "pull_max",
                       "must be reached within run.duration = " + number_text(s.duration) +
                           " s (pull_max / pull_rate = " + number_text(s.pull_max / s.pull_rate) + " s)",
                       s.pull_max);
        if (root.has("fluid"))
            analysis.fail("kind", "kind \"pull\" is a dry test and the fluid would set the units' loads: "
                                  "remove [fluid], [waves], [[porous]], [[series]] and [[refine]] "
                                  "(bench/run_pull_test.sh does)");
    }
}

void read_materials(const Table &root, Scene &s) {
    for (const Table &t : root.entries("material")) {
        t.only(names_of(material_keys()));
        SceneMaterial m;
        read_keys(t, material_keys(), m);
        for (const auto &other : s.materials)
            if (other.name == m.name)
                t.fail("name", "duplicate material name " + toml_string(m.name));
        s.materials.push_back(m);
    }
    if (s.materials.empty())
        root.fail("material", "at least one [[material]] is required");

    std::vector<std::string> names;
    for (const auto &m : s.materials)
        names.push_back(m.name);
    for (const Table &t : root.entries("material_pair")) {
        t.only(names_of(material_pair_keys()));
        SceneMaterialPair p;
        read_keys(t, material_pair_keys(), p);
        for (const auto &[key, m] : {std::pair<const char *, std::string>{"a", p.a}, {"b", p.b}})
            if (std::find(names.begin(), names.end(), m) == names.end())
                t.fail(key, "no [[material]] named " + toml_string(m) + " (known: " + choices(names) + ")");
        for (const auto &other : s.material_pairs)
            if (other.joins(p.a, p.b))
                t.fail("b", "duplicate pair " + toml_string(p.a) + " / " + toml_string(p.b));
        s.material_pairs.push_back(p);
    }
}

void read_units(const Table &root, Scene &s) {
    const auto &keys = unit_keys();
    for (const Table &t : root.entries("unit")) {
        t.only(names_of(keys));
        SceneUnit u;
        read_value(t, key_named(keys, "name"), u);
        t.require("name");
        for (const auto &other : s.units)
            if (other.name == u.name)
                t.fail("name", "duplicate unit name " + toml_string(u.name));
        t.require("shape");
        read_value(t, key_named(keys, "shape"), u);
        forbid_other_variants(t, keys, u.shape, "shape");
        read_keys(t, keys, u, u.shape);
        t.check(u.shape != "cube" || u.chamfer < 0.5 * u.size, "chamfer",
                "must be in [0, size/2) = [0, " + number_text(0.5 * u.size) + ") m", u.chamfer);
        // Edge spheres are a layout for a given count: the tolerance search
        // would pick the count without them.
        t.check(u.edge_spheres == 0 || u.spheres > 0, "edge_spheres", "needs a fixed `spheres` count",
                u.edge_spheres);
        t.check(u.edge_spheres == 0 || u.method != "greedy", "edge_spheres",
                "the greedy clump has no support spheres (method \"optimised\" or \"inscribed\")",
                u.edge_spheres);
        u.material = material_of(t, s.materials);
        s.units.push_back(u);
    }
}

void read_walls(const Table &root, Scene &s) {
    const auto &keys = wall_keys();
    const auto entries = root.entries("wall");
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const Table &t = entries[i];
        t.only(names_of(keys));
        SceneWall w;
        t.require("type");
        read_value(t, key_named(keys, "type"), w);
        forbid_other_variants(t, keys, w.type, "wall type");
        read_keys(t, keys, w, w.type);
        // Walls need a name only when a [[pattern]] refers to them.
        if (w.name.empty())
            w.name = w.type + "_" + std::to_string(i);
        for (const auto &other : s.walls)
            if (other.name == w.name)
                t.fail("name", "duplicate wall name " + toml_string(w.name));
        if (w.type == "plane") {
            if (w.normal.norm() < 1e-12)
                t.fail("normal", "must be a non-zero vector (got " + vector_text(w.normal) + ")");
            w.normal = normalised(w.normal);
        } else if (w.type == "slope") {
            t.check(w.toe_height < w.height, "toe_height",
                    "must be in [0, height) = [0, " + number_text(w.height) + ") m", w.toe_height);
        } else if (w.type == "box") {
            if (!(w.max.array() > w.min.array()).all())
                t.fail("max", "must exceed min " + vector_text(w.min) + " m in every component (got " +
                                  vector_text(w.max) + ")");
        }
        w.material = material_of(t, s.materials);
        s.walls.push_back(w);
    }
}

std::string unit_of(const Table &t, const Scene &s, const std::string &u) {
    std::vector<std::string> names;
    for (const auto &unit : s.units)
        names.push_back(unit.name);
    if (std::find(names.begin(), names.end(), u) == names.end())
        t.fail("unit",
               "no [[unit]] named " + toml_string(u) +
                   (names.empty() ? " (the scene has no [[unit]])" : " (known: " + choices(names) + ")"));
    return u;
}

void read_placements(const Table &root, Scene &s) {
    const std::string domain = "run.domain_min " + vector_text(s.domain_min) + " .. run.domain_max " +
                               vector_text(s.domain_max) + " m";
    for (const Table &t : root.entries("body")) {
        t.only(names_of(body_keys()));
        SceneBody b;
        read_keys(t, body_keys(), b);
        unit_of(t, s, b.unit);
        if (!inside(b.position, s.domain_min, s.domain_max))
            t.fail("position", "must lie inside " + domain + " (got " + vector_text(b.position) + ")");
        if (b.orientation.norm() < 1e-12)
            t.fail("orientation",
                   "must be a non-zero quaternion [w, x, y, z] (got " + vector_text(b.orientation) + ")");
        b.orientation = normalised(b.orientation);
        if (b.pivot) {
            if (!engine_style(s.engine).capabilities.pivot) {
                const EngineStyle *hinged =
                    find_engine_style([](const EngineCapabilities &c) { return c.pivot; });
                t.fail("pivot",
                       "needs run.engine = " + toml_string(hinged ? hinged->name : "an engine with pivots") +
                           " (got " + toml_string(s.engine) +
                           "): the contact engines hold locked axes at the centre of mass");
            }
            if (std::none_of(b.fixed_translation.begin(), b.fixed_translation.end(),
                             [](bool held) { return held; }))
                t.fail("pivot", "holds nothing without fixed_translation (the axes along which the pivot "
                                "point stays put)");
        }
        s.bodies.push_back(b);
    }
    for (const Table &t : root.entries("drop")) {
        t.only(names_of(drop_keys()));
        SceneDrop d;
        read_keys(t, drop_keys(), d);
        unit_of(t, s, d.unit);
        check_box(t, d.min, d.max, s);
        s.drops.push_back(d);
    }
    for (const Table &t : root.entries("pattern")) {
        t.only(names_of(pattern_keys()));
        ScenePattern p;
        read_keys(t, pattern_keys(), p);
        unit_of(t, s, p.unit);
        const auto wall = std::find_if(s.walls.begin(), s.walls.end(),
                                       [&](const SceneWall &w) { return w.name == p.wall; });
        if (wall == s.walls.end())
            t.fail("wall", "no [[wall]] named " + toml_string(p.wall));
        if (wall->type != "slope")
            t.fail("wall", "wall " + toml_string(p.wall) + " is of type " + toml_string(wall->type) +
                               "; a pattern needs a \"slope\" wall");
        if (p.first_row >= p.rows)
            t.fail("first_row", std::to_string(p.first_row) + " leaves no row to place: rows = " +
                                    std::to_string(p.rows) + " (first_row counts from 0)");
        if (p.clear_of_toe.value_or(false) && p.placement == "grid")
            t.fail("clear_of_toe",
                   "is for placement \"random\" or \"seated\" (a grid faces the slope from its "
                   "first row up)");
        s.patterns.push_back(p);
    }
    // An empty wave flume ([waves] regular or irregular) is a scene too.
    const bool wave_flume = s.waves && s.waves->type != "solitary";
    if (s.bodies.empty() && s.drops.empty() && s.patterns.empty() && !wave_flume)
        root.fail("body", "the scene places no units: add a [[body]], [[drop]] or [[pattern]]");
}

// fluid.settle_stages builds one [[pattern]] a few rows a stage: the
// scene's units must all be its, each stage at least a row.
void check_settle_stages(const Table &root, const Scene &s) {
    if (!s.fluid || s.fluid->settle_stages == 1)
        return;
    const Table t = root.section("fluid");
    if (s.fluid->settle_time <= 0.0)
        t.fail("settle_stages", "stages of a settle need one: fluid.settle_time is 0");
    if (s.patterns.size() != 1 || !s.bodies.empty() || !s.drops.empty())
        t.fail("settle_stages", "builds the layer of one [[pattern]] row by row, and the scene has " +
                                    std::to_string(s.patterns.size()) + " [[pattern]], " +
                                    std::to_string(s.bodies.size()) + " [[body]] and " +
                                    std::to_string(s.drops.size()) + " [[drop]]");
    const ScenePattern &p = s.patterns.front();
    if (p.placement == "grid")
        t.fail("settle_stages", "is for placement \"random\" or \"seated\", which set each stage's rows "
                                "clear of the units settled before them; pattern.0.placement is \"grid\"");
    if (s.fluid->settle_stages > p.rows - p.first_row)
        t.fail("settle_stages", std::to_string(s.fluid->settle_stages) + " stages for the pattern's " +
                                    std::to_string(p.rows - p.first_row) + " rows: at most one stage a row");
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

namespace scene_read {

void check_box(const Table &t, const Eigen::Vector3d &min, const Eigen::Vector3d &max, const Scene &s) {
    const std::string domain = "run.domain_min " + vector_text(s.domain_min) + " .. run.domain_max " +
                               vector_text(s.domain_max) + " m";
    if (!(max.array() > min.array()).all())
        t.fail("max", "must exceed min " + vector_text(min) + " m in every component (got " +
                          vector_text(max) + ")");
    if (!inside(min, s.domain_min, s.domain_max))
        t.fail("min", "must lie inside " + domain + " (got " + vector_text(min) + ")");
    if (!inside(max, s.domain_min, s.domain_max))
        t.fail("max", "must lie inside " + domain + " (got " + vector_text(max) + ")");
}

} // namespace scene_read

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
    root.only(top_level_names());
    read_keys(root, root_keys(), s);
    read_run(root, s);
    read_contact_and_analysis(root, s);
    read_fluid(root, s);
    read_waves(root, s);
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
    read_porous(root, s);
    read_refine(root, s);
    read_series(root, s);
    check_surface_band(root, s);
    if (s.analysis == "damage" &&
        std::none_of(s.walls.begin(), s.walls.end(), [](const SceneWall &w) { return w.type == "slope"; }))
        root.section("analysis")
            .fail("kind", "kind \"damage\" counts units on a slope: the scene needs a "
                          "[[wall]] of type \"slope\"");
    read_placements(root, s);
    check_settle_stages(root, s);
    return s;
}

} // namespace armour
