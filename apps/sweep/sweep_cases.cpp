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

SweepPlan plan_sweep(const SweepSpec &spec) {
    SweepPlan plan;
    plan.spec = spec;
    std::vector<std::vector<KeyValue>> combos = product(spec);
    for (const auto &c : spec.cases)
        combos.push_back(c);
    for (const auto &[key, values] : spec.vary)
        plan.columns.push_back(key);
    for (const auto &c : spec.cases)
        for (const auto &kv : c)
            if (std::find(plan.columns.begin(), plan.columns.end(), kv.first) == plan.columns.end())
                plan.columns.push_back(kv.first);

    // Ids use a key's last name unless two varied keys share it.
    std::map<std::string, int> label_count;
    for (const auto &key : plan.columns)
        ++label_count[short_label(key)];
    auto label = [&](const std::string &key) {
        const std::string s = short_label(key);
        if (label_count[s] == 1)
            return s;
        std::string full = key;
        std::replace(full.begin(), full.end(), '.', '-');
        return full;
    };

    const Scene base = [&] {
        try {
            return load_scene(spec.scene, {});
        } catch (const InputError &e) {
            throw InputError(spec.file + ": key 'scene': " + e.what());
        }
    }();
    std::vector<std::string> seed_keys = spec.seed_keys;
    if (!spec.seeds.empty() && seed_keys.empty()) {
        for (std::size_t k = 0; k < base.drops.size(); ++k)
            seed_keys.push_back("drop." + std::to_string(k) + ".seed");
        if (seed_keys.empty())
            throw InputError(
                spec.file + ": key 'seeds': the scene " + spec.scene +
                " places nothing at random (no [[drop]]); name the key a seed sets with seed_key");
    }
    if (combos.empty())
        combos.emplace_back(); // seeds alone
    std::vector<std::optional<std::int64_t>> seeds;
    for (const auto s : spec.seeds)
        seeds.emplace_back(s);
    if (seeds.empty())
        seeds.emplace_back();

    // Realisation-major: every point's first realisation runs before any
    // point's second, so a sweep stopped part-way (or an array half-run)
    // already spans the whole curve.
    std::set<std::string> ids;
    for (const auto &seed : seeds)
        for (const auto &combo : combos) {
            SweepCase c;
            c.seed = seed;
            for (const auto &[key, value] : spec.fixed)
                c.overrides.push_back(key + "=" + value);
            for (const auto &[key, value] : combo) {
                c.overrides.push_back(key + "=" + value);
                c.id += (c.id.empty() ? "" : "_") + label(key) + "-" + file_safe(unquoted(value));
            }
            if (seed) {
                for (const auto &key : seed_keys)
                    c.overrides.push_back(key + "=" + std::to_string(*seed));
                c.id += (c.id.empty() ? "" : "_") + std::string("seed-") + std::to_string(*seed);
            }
            if (c.id.empty())
                c.id = "base";
            if (!ids.insert(c.id).second)
                throw InputError(spec.file + ": case " + c.id + ": two cases have the same values");
            Scene scene;
            try {
                scene = load_scene(spec.scene, c.overrides);
            } catch (const InputError &e) {
                throw InputError(spec.file + ": case " + c.id + ": " + e.what());
            }
            if (spec.np > 0 && !scene.fluid)
                throw InputError(spec.file + ": key 'run.np': case " + c.id +
                                 ": only for scenes with [fluid] (MPI ranks of interFoam)");
            if (plan.analysis.empty())
                plan.analysis = scene.analysis;
            c.scene_text = resolved_scene_toml(scene);
            c.scene_hash = scene_hash(c.scene_text);
            c.earlier_scene_hash = fnv1a_hex(c.scene_text);
            c.resume_hash = fnv1a_hex(resume_key_text(scene));
            c.duration = scene.duration;
            for (const auto &key : plan.columns)
                c.column_values.push_back(toml_value_at(c.scene_text, key));
            plan.cases.push_back(std::move(c));
        }
    return plan;
}

} // namespace armour
