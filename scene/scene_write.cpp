// scene.resolved.toml: every key of the table (scene_keys.h) with its value
// after overrides and defaults, written so that it reads back exactly.
#include "scene.h"

#include "scene_keys.h"
#include "scene_text.h"
#include "toml_table.h"

#include <optional>
#include <sstream>

namespace armour {

using namespace scene_detail;

namespace {

// The TOML text of a key's value; none for an optional left unset.
template <class S> std::optional<std::string> value_text(const Key<S> &k, const S &obj) {
    const auto flag = [](bool b) { return std::string(b ? "true" : "false"); };
    return std::visit(
        overloaded{
            [&](std::string S::*f) -> std::optional<std::string> { return toml_string(obj.*f); },
            [&](double S::*f) -> std::optional<std::string> { return toml_float(obj.*f); },
            [&](int S::*f) -> std::optional<std::string> { return std::to_string(obj.*f); },
            [&](std::uint64_t S::*f) -> std::optional<std::string> { return std::to_string(obj.*f); },
            [&](bool S::*f) -> std::optional<std::string> { return flag(obj.*f); },
            [&](Eigen::Vector3d S::*f) -> std::optional<std::string> { return vector_text(obj.*f); },
            [&](Eigen::Vector4d S::*f) -> std::optional<std::string> { return vector_text(obj.*f); },
            [&](std::array<bool, 3> S::*f) -> std::optional<std::string> {
                const auto &b = obj.*f;
                return "[" + flag(b[0]) + ", " + flag(b[1]) + ", " + flag(b[2]) + "]";
            },
            [&](std::array<int, 3> S::*f) -> std::optional<std::string> {
                const auto &c = obj.*f;
                return "[" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " +
                       std::to_string(c[2]) + "]";
            },
            [&](std::optional<double> S::*f) -> std::optional<std::string> {
                return (obj.*f) ? std::optional<std::string>(toml_float(*(obj.*f))) : std::nullopt;
            },
            [&](std::optional<bool> S::*f) -> std::optional<std::string> {
                return (obj.*f) ? std::optional<std::string>(flag(*(obj.*f))) : std::nullopt;
            },
            [&](std::optional<Eigen::Vector3d> S::*f) -> std::optional<std::string> {
                return (obj.*f) ? std::optional<std::string>(vector_text(*(obj.*f))) : std::nullopt;
            },
            [&](std::vector<double> S::*f) -> std::optional<std::string> {
                if ((obj.*f).empty())
                    return std::nullopt;
                std::string text;
                for (const double v : obj.*f)
                    text += (text.empty() ? "" : ", ") + toml_float(v);
                return "[" + text + "]";
            },
        },
        k.field);
}

template <class S>
void write_keys(std::ostream &o, const std::vector<Key<S>> &keys, const S &obj,
                const std::string &variant = "") {
    for (const auto &k : keys) {
        if ((*k.when && variant != k.when) || (k.written && !k.written(obj)))
            continue;
        if (const auto value = value_text(k, obj))
            o << k.name << " = " << *value << (*k.unit ? std::string(" # ") + k.unit : "") << "\n";
    }
}

template <class S>
void write_table(std::ostream &o, const char *name, const std::vector<Key<S>> &keys, const S &obj) {
    o << "\n[" << name << "]\n";
    write_keys(o, keys, obj);
}

template <class S, class Variant>
void write_entries(std::ostream &o, const char *name, const std::vector<Key<S>> &keys,
                   const std::vector<S> &entries, Variant variant) {
    for (const S &e : entries) {
        o << "\n[[" << name << "]]\n";
        write_keys(o, keys, e, variant(e));
    }
}

} // namespace

std::string scene_keys_text(const std::string &resolved_toml) {
    std::istringstream lines(resolved_toml);
    std::string keys;
    for (std::string line; std::getline(lines, line);)
        if (line.rfind('#', 0) != 0)
            keys += line + '\n';
    return keys;
}

std::string resolved_scene_toml(const Scene &s) {
    std::ostringstream o;
    const auto none = [](const auto &) { return std::string(); };
    o << "# Resolved scene: " << s.file << " after --set overrides, every default filled in (SI units).\n";
    write_keys(o, root_keys(), s);
    write_table(o, "run", run_keys(), s);
    write_table(o, "contact", contact_keys(), s);
    write_table(o, "analysis", analysis_keys(), s);
    if (s.fluid)
        write_table(o, "fluid", fluid_keys(), *s.fluid);
    if (s.waves) {
        o << "\n[waves]\n";
        write_keys(o, wave_keys(), *s.waves, s.waves->type);
    }
    write_entries(o, "material", material_keys(), s.materials, none);
    write_entries(o, "material_pair", material_pair_keys(), s.material_pairs, none);
    write_entries(o, "unit", unit_keys(), s.units, [](const SceneUnit &u) { return u.shape; });
    write_entries(o, "wall", wall_keys(), s.walls, [](const SceneWall &w) { return w.type; });
    write_entries(o, "body", body_keys(), s.bodies, none);
    write_entries(o, "drop", drop_keys(), s.drops, none);
    write_entries(o, "pattern", pattern_keys(), s.patterns, none);
    write_entries(o, "porous", porous_keys(), s.porous, [](const ScenePorous &p) { return p.type; });
    write_entries(o, "series", series_keys(), s.series, none);
    write_entries(o, "refine", refine_keys(), s.refine, [](const SceneRefine &r) { return r.type; });
    return o.str();
}

} // namespace armour
