#include "sweep_cases.h"

#include "input_error.h"
#include "run_command.h"
#include "scene.h"
#include "scene_text.h"
#include "sweep_toml.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

namespace armour {

namespace {

std::vector<std::string> split(const std::string &key) {
    std::vector<std::string> parts;
    std::stringstream in(key);
    for (std::string part; std::getline(in, part, '.');)
        parts.push_back(part);
    return parts;
}

bool is_index(const std::string &s) {
    return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}

// The short name of a key in case ids: its last part that is not an index.
std::string short_label(const std::string &key) {
    const std::vector<std::string> parts = split(key);
    for (auto it = parts.rbegin(); it != parts.rend(); ++it)
        if (!is_index(*it))
            return *it;
    return key;
}

// Letters, digits and . + - stay; anything else (quotes, spaces, slashes) becomes '_'.
std::string file_safe(const std::string &text) {
    std::string out;
    for (const char ch : text) {
        const bool keep = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
                          ch == '.' || ch == '+' || ch == '-';
        out += keep ? ch : '_';
    }
    return out;
}

std::string unquoted(const std::string &toml_text) {
    if (toml_text.size() >= 2 && (toml_text.front() == '"' || toml_text.front() == '\''))
        return toml_text.substr(1, toml_text.size() - 2);
    return toml_text;
}

// The cartesian product of [vary], first key slowest.
std::vector<std::vector<KeyValue>> product(const SweepSpec &spec) {
    std::vector<std::vector<KeyValue>> combos{{}};
    for (const auto &[key, values] : spec.vary) {
        std::vector<std::vector<KeyValue>> next;
        for (const auto &combo : combos)
            for (const auto &v : values) {
                next.push_back(combo);
                next.back().emplace_back(key, v);
            }
        combos = std::move(next);
    }
    if (spec.vary.empty())
        combos.clear();
    return combos;
}

} // namespace

namespace {

std::string fnv1a_hex(const std::string &text) {
    std::uint64_t h = 1469598103934665603ull;
    for (const unsigned char ch : text) {
        h ^= ch;
        h *= 1099511628211ull;
    }
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
    return hex;
}

} // namespace

std::string scene_hash(const std::string &text) {
    return fnv1a_hex(scene_keys_text(text));
}

bool same_scene(const std::string &recorded_hash, const SweepCase &c) {
    return recorded_hash == c.scene_hash ||
           (!c.earlier_scene_hash.empty() && recorded_hash == c.earlier_scene_hash);
}

std::string toml_value_at(const std::string &document, const std::string &key) {
    toml::table root;
    try {
        root = toml::parse(document);
    } catch (const toml::parse_error &) {
        return "";
    }
    toml::node *node = &root;
    for (const std::string &part : split(key)) {
        if (node->is_table())
            node = node->as_table()->get(part);
        else if (node->is_array() && is_index(part))
            node = node->as_array()->get(std::stoul(part));
        else
            node = nullptr;
        if (!node)
            return "";
    }
    if (const auto s = node->value_exact<std::string>())
        return *s;
    return sweep_detail::toml_text(*node);
}

namespace {

// The results table's columns: the [vary] keys in order, then the keys the
// [[case]] tables add.
std::vector<std::string> plan_columns(const SweepSpec &spec) {
    std::vector<std::string> columns;
    for (const auto &[key, values] : spec.vary)
        columns.push_back(key);
    for (const auto &c : spec.cases)
        for (const auto &kv : c)
            if (std::find(columns.begin(), columns.end(), kv.first) == columns.end())
                columns.push_back(kv.first);
    return columns;
}

// Each column's name in case ids: the key's last name unless two columns
// share it, then the whole key with '-' for '.'.
std::map<std::string, std::string> id_labels(const std::vector<std::string> &columns) {
    std::map<std::string, int> count;
    for (const auto &key : columns)
        ++count[short_label(key)];
    std::map<std::string, std::string> labels;
    for (const auto &key : columns) {
        std::string label = short_label(key);
        if (count[label] > 1) {
            label = key;
            std::replace(label.begin(), label.end(), '.', '-');
        }
        labels[key] = label;
    }
    return labels;
}

// The sweep's scene as its file stands: it must load without the sweep's
// overrides too.
Scene base_scene(const SweepSpec &spec) {
    try {
        return load_scene(spec.scene, {});
    } catch (const InputError &e) {
        throw InputError(spec.file + ": key 'scene': " + e.what());
    }
}

// The keys a realisation's seed sets: seed_key, or each [[drop]]'s seed.
std::vector<std::string> seed_keys_of(const SweepSpec &spec, const Scene &base) {
    if (spec.seeds.empty() || !spec.seed_keys.empty())
        return spec.seed_keys;
    std::vector<std::string> keys;
    for (std::size_t k = 0; k < base.drops.size(); ++k)
        keys.push_back("drop." + std::to_string(k) + ".seed");
    if (keys.empty())
        throw InputError(spec.file + ": key 'seeds': the scene " + spec.scene +
                         " places nothing at random (no [[drop]]); name the key a seed sets with seed_key");
    return keys;
}

// One case of the plan, not yet resolved: its seed, overrides (the file's [set], then its point's
// keys, then its seed) and id.
SweepCase make_case(const SweepSpec &spec, const std::vector<KeyValue> &point,
                    const std::optional<std::int64_t> &seed, const std::vector<std::string> &seed_keys,
                    const std::map<std::string, std::string> &labels) {
    SweepCase c;
    c.seed = seed;
    for (const auto &[key, value] : spec.fixed)
        c.overrides.push_back(key + "=" + value);
    for (const auto &[key, value] : point) {
        c.overrides.push_back(key + "=" + value);
        c.id += (c.id.empty() ? "" : "_") + labels.at(key) + "-" + file_safe(unquoted(value));
    }
    if (seed) {
        for (const auto &key : seed_keys)
            c.overrides.push_back(key + "=" + std::to_string(*seed));
        c.id += (c.id.empty() ? "" : "_") + std::string("seed-") + std::to_string(*seed);
    }
    if (c.id.empty())
        c.id = "base";
    return c;
}

// The case's scene, resolved and checked, with what the sweep compares
// across runs (hashes) and reports (the columns' values).
void resolve_case(const SweepSpec &spec, const std::vector<std::string> &columns, SweepCase &c,
                  std::string &analysis) {
    Scene scene;
    try {
        scene = load_scene(spec.scene, c.overrides);
    } catch (const InputError &e) {
        throw InputError(spec.file + ": case " + c.id + ": " + e.what());
    }
    if (spec.np > 0 && !scene.fluid)
        throw InputError((spec.np_option.empty() ? spec.file + ": key 'run.np'" : spec.np_option) +
                         ": case " + c.id + ": only for scenes with [fluid] (MPI ranks of interFoam)");
    if (analysis.empty())
        analysis = scene.analysis;
    c.scene_text = resolved_scene_toml(scene);
    c.scene_hash = scene_hash(c.scene_text);
    c.earlier_scene_hash = fnv1a_hex(c.scene_text);
    c.resume_hash = fnv1a_hex(resume_key_text(scene));
    c.duration = scene.duration;
    for (const auto &key : columns)
        c.column_values.push_back(toml_value_at(c.scene_text, key));
}

} // namespace

SweepPlan plan_sweep(const SweepSpec &spec) {
    SweepPlan plan;
    plan.spec = spec;
    plan.columns = plan_columns(spec);
    const std::map<std::string, std::string> labels = id_labels(plan.columns);
    const Scene base = base_scene(spec); // refused here if the scene file alone does not load
    const std::vector<std::string> seed_keys = seed_keys_of(spec, base);
    std::vector<std::vector<KeyValue>> points = product(spec);
    for (const auto &c : spec.cases)
        points.push_back(c);
    if (points.empty())
        points.emplace_back(); // seeds alone
    std::vector<std::optional<std::int64_t>> seeds(spec.seeds.begin(), spec.seeds.end());
    if (seeds.empty())
        seeds.emplace_back();

    // Realisation-major: every point's first realisation runs before any
    // point's second, so a sweep stopped part-way (or an array half-run)
    // already spans the whole curve.
    std::set<std::string> ids;
    for (const auto &seed : seeds)
        for (const auto &point : points) {
            SweepCase c = make_case(spec, point, seed, seed_keys, labels);
            if (!ids.insert(c.id).second)
                throw InputError(spec.file + ": case " + c.id + ": two cases have the same values");
            resolve_case(spec, plan.columns, c, plan.analysis);
            plan.cases.push_back(std::move(c));
        }
    return plan;
}

} // namespace armour
