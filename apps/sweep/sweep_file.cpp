#include "sweep_file.h"

#include "input_error.h"
#include "sweep_toml.h"

#include <cmath>
#include <filesystem>
#include <limits>

namespace armour {

namespace fs = std::filesystem;

namespace {

std::string one_line(const std::string &text) {
    std::string out;
    for (const char c : text) {
        if (c == '\n')
            out += "\\n";
        else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            out += '?';
        else
            out += c;
    }
    return out;
}

class Reader {
  public:
    explicit Reader(std::string file) : file_(std::move(file)) {}

    // Keys and values come from the file and may hold control characters (a
    // quoted key "a\nb"): escaped, so that the error stays one line.
    [[noreturn]] void fail(const std::string &key, const std::string &reason) const {
        throw InputError(file_ + ": key '" + one_line(key) + "': " + one_line(reason));
    }

    // A value as --set takes it: TOML text of a scalar or an array.
    std::string value_text(const std::string &key, const toml::node &node) const {
        if (node.is_table() || node.is_array_of_tables())
            fail(key, "must be a value (number, string, boolean or array), not a table");
        return sweep_detail::toml_text(node);
    }

    std::vector<KeyValue> key_values(const std::string &where, const toml::table &table) const {
        std::vector<KeyValue> out;
        for (const auto &[k, v] : table) {
            const std::string key(k.str());
            out.emplace_back(key, value_text(where + ".\"" + key + "\"", v));
        }
        return out;
    }

    template <class T>
    T number(const toml::table &t, const std::string &section, const char *key, T fallback, T minimum) const {
        const toml::node *n = t.get(key);
        if (!n)
            return fallback;
        const std::string full = section + "." + key;
        std::optional<double> v = n->value<double>();
        if (!v || (std::is_integral_v<T> && !n->is_integer()))
            fail(full, std::is_integral_v<T> ? "must be an integer" : "must be a number");
        if (!std::isfinite(*v))
            fail(full, "must be a finite number");
        if (*v < static_cast<double>(minimum))
            fail(full, "must be at least " + std::to_string(minimum));
        // The cast below is undefined past the type's range (np = 3000000000).
        if (*v > static_cast<double>(std::numeric_limits<T>::max()))
            fail(full, "must be at most " + std::to_string(std::numeric_limits<T>::max()));
        return static_cast<T>(*v);
    }

    std::string text(const toml::table &t, const std::string &section, const char *key) const {
        const toml::node *n = t.get(key);
        if (!n)
            return "";
        if (!n->is_string())
            fail(section.empty() ? key : section + "." + key, "must be a string");
        return std::string(*n->value<std::string>());
    }

    void only_keys(const toml::table &t, const std::string &section,
                   std::initializer_list<const char *> known) const {
        for (const auto &[k, v] : t) {
            bool ok = false;
            std::string list;
            for (const char *name : known) {
                ok = ok || k.str() == name;
                list += std::string(list.empty() ? "" : ", ") + name;
            }
            if (!ok)
                fail((section.empty() ? "" : section + ".") + std::string(k.str()),
                     "unknown key (known: " + list + ")");
        }
    }

  private:
    std::string file_;
};

// What a sweep varies: [vary], [[case]] tables, [set] (what every case shares) and the seeds.
void read_varied(const Reader &r, const toml::table &root, SweepSpec &spec) {
    if (const toml::node *vary = root.get("vary")) {
        if (!vary->is_table())
            r.fail("vary", "must be a table of \"KEY\" = [values]");
        for (const auto &[k, v] : *vary->as_table()) {
            const std::string key(k.str()), where = "vary.\"" + key + "\"";
            if (!v.is_array())
                r.fail(where, "must be a list of values, e.g. [0.3, 0.5]");
            if (v.as_array()->empty())
                r.fail(where, "empty list: give at least one value");
            std::vector<std::string> values;
            for (const auto &item : *v.as_array())
                values.push_back(r.value_text(where, item));
            spec.vary.emplace_back(key, values);
        }
    }
    if (const toml::node *cases = root.get("case")) {
        if (!cases->is_array_of_tables())
            r.fail("case", "must be [[case]] tables of \"KEY\" = value");
        std::size_t i = 0;
        for (const auto &c : *cases->as_array()) {
            const std::string where = "case." + std::to_string(i++);
            if (c.as_table()->empty())
                r.fail(where, "empty table: give at least one \"KEY\" = value");
            spec.cases.push_back(r.key_values(where, *c.as_table()));
        }
    }
    if (const toml::node *set = root.get("set")) {
        if (!set->is_table())
            r.fail("set", "must be a table of \"KEY\" = value");
        spec.fixed = r.key_values("set", *set->as_table());
    }
    if (const toml::node *seeds = root.get("seeds")) {
        if (!seeds->is_array() || seeds->as_array()->empty())
            r.fail("seeds", "must be a non-empty list of integers, e.g. [1, 2]");
        for (const auto &s : *seeds->as_array()) {
            if (!s.is_integer() || *s.value<std::int64_t>() < 0)
                r.fail("seeds", "every seed must be an integer >= 0");
            spec.seeds.push_back(*s.value<std::int64_t>());
        }
    }
    if (const toml::node *k = root.get("seed_key")) {
        if (k->is_string())
            spec.seed_keys.push_back(*k->value<std::string>());
        else if (k->is_array() && !k->as_array()->empty()) {
            for (const auto &s : *k->as_array()) {
                if (!s.is_string())
                    r.fail("seed_key", "must be a key or a list of keys (strings)");
                spec.seed_keys.push_back(*s.value<std::string>());
            }
        } else
            r.fail("seed_key", "must be a key or a non-empty list of keys (strings)");
        if (spec.seeds.empty())
            r.fail("seed_key", "given without seeds = [...]");
    }
    if (spec.vary.empty() && spec.cases.empty() && spec.seeds.empty())
        r.fail("vary", "nothing varies: give [vary], [[case]] tables or seeds");
}

// How each case runs: [run] (ranks, time limit) and [slurm] (the job array's options).
void read_run_and_slurm(const Reader &r, const toml::table &root, SweepSpec &spec) {
    if (const toml::node *run = root.get("run")) {
        if (!run->is_table())
            r.fail("run", "must be a table");
        const toml::table &t = *run->as_table();
        r.only_keys(t, "run", {"np", "timeout"});
        spec.np = r.number<int>(t, "run", "np", 0, 1);
        spec.timeout = r.number<double>(t, "run", "timeout", 0.0, 0.0);
    }
    if (const toml::node *slurm = root.get("slurm")) {
        if (!slurm->is_table())
            r.fail("slurm", "must be a table");
        const toml::table &t = *slurm->as_table();
        r.only_keys(t, "slurm", {"partition", "time", "memory", "cpus_per_case", "max_concurrent", "extra"});
        spec.slurm.partition = r.text(t, "slurm", "partition");
        spec.slurm.time = r.text(t, "slurm", "time");
        spec.slurm.memory = r.text(t, "slurm", "memory");
        spec.slurm.cpus_per_case = r.number<int>(t, "slurm", "cpus_per_case", 0, 1);
        spec.slurm.max_concurrent = r.number<int>(t, "slurm", "max_concurrent", 0, 1);
        if (const toml::node *extra = t.get("extra")) {
            if (!extra->is_array())
                r.fail("slurm.extra", "must be a list of sbatch options, e.g. [\"--account=coastal\"]");
            for (const auto &e : *extra->as_array()) {
                if (!e.is_string() || e.value<std::string>()->find('\n') != std::string::npos)
                    r.fail("slurm.extra", "every entry must be one sbatch option (a string, one line)");
                spec.slurm.extra.push_back(*e.value<std::string>());
            }
        }
    }
}

} // namespace

SweepSpec read_sweep_file(const std::string &path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        throw InputError(path + ": cannot read the sweep file (no such file)");
    toml::table root;
    try {
        root = toml::parse_file(path);
    } catch (const toml::parse_error &e) {
        throw InputError(path + ":" + std::to_string(e.source().begin.line) + ": " +
                         one_line(std::string(e.description())));
    }
    const Reader r(path);
    r.only_keys(root, "", {"scene", "seeds", "seed_key", "vary", "case", "set", "run", "slurm"});

    SweepSpec spec;
    spec.file = path;
    const std::string scene = r.text(root, "", "scene");
    if (scene.empty())
        r.fail("scene", "required: the base scene file, relative to the sweep file's folder");
    fs::path scene_path(scene);
    if (scene_path.is_relative())
        scene_path = fs::absolute(path).parent_path() / scene_path;
    spec.scene = scene_path.lexically_normal().string();

    read_varied(r, root, spec);
    read_run_and_slurm(r, root, spec);
    // Checked last, so that every other key is checked too when the sweep
    // file is read away from its scene (the fuzzer reads a copy in /tmp).
    if (!fs::is_regular_file(spec.scene, ec))
        r.fail("scene", "no such file: " + spec.scene);
    return spec;
}

} // namespace armour
