// The --set overrides (scene_overrides.h): the path is walked through the
// parsed file and the key table, then the value is parsed as the key's type.
#include "scene_overrides.h"

#include "input_error.h"
#include "scene_keys.h"
#include "toml_table.h"

#include <algorithm>

namespace armour::scene_detail {

std::vector<std::string> top_level_names() {
    std::vector<std::string> names = names_of(root_keys());
    for (const auto &section : scene_sections())
        if (section.kind != SectionKind::Root)
            names.push_back(section.name);
    return names;
}

namespace {

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

bool is_single_table(const std::string &name) {
    const SceneSection *section = find_section(name);
    return section && section->kind == SectionKind::Table;
}

// The keys a table at `parents` (the path segments leading to it) may hold;
// empty when the path leads to no table of the key table.
std::vector<std::string> known_keys(const std::vector<std::string> &parents) {
    if (parents.empty())
        return top_level_names();
    const SceneSection *section = find_section(parents[0]);
    if (!section || section->kind == SectionKind::Root)
        return {};
    const bool single = section->kind == SectionKind::Table;
    if ((single && parents.size() == 1) || (!single && parents.size() == 2 && is_index(parents[1])))
        return key_names(*section);
    return {};
}

// "--set 'TEXT': reason", the one line of every malformed override.
struct OverrideError {
    std::string text;
    InputError operator()(const std::string &reason) const {
        return InputError("--set '" + text + "': " + reason);
    }
};

std::vector<std::string> split_key(const std::string &key, const OverrideError &bad) {
    std::vector<std::string> segments;
    for (std::size_t start = 0;;) {
        const auto dot = key.find('.', start);
        segments.push_back(
            trimmed(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start)));
        if (segments.back().empty())
            throw bad("empty segment in key '" + key + "'");
        if (dot == std::string::npos)
            return segments;
        start = dot + 1;
    }
}

// The type the key table declares for the key an override sets ("string",
// "number", "[x, y, z]", ...; see KeyInfo::type), or "" where the path names
// no key of the table (an entry of an array such as run.gravity.2, a table).
std::string declared_type(const std::vector<std::string> &segments) {
    const std::vector<std::string> parents(segments.begin(), segments.end() - 1);
    const SceneSection *section = parents.empty() ? find_section("") : nullptr;
    if (const SceneSection *named = parents.empty() ? nullptr : find_section(parents[0]))
        if ((named->kind == SectionKind::Table && parents.size() == 1) ||
            (named->kind == SectionKind::ArrayOfTables && parents.size() == 2 && is_index(parents[1])))
            section = named;
    if (!section)
        return "";
    std::string type;
    for (const KeyInfo &k : section->keys())
        if (k.name == segments.back()) {
            if (!type.empty() && type != k.type)
                return ""; // differs between shapes or wall types: the reader decides
            type = k.type;
        }
    return type == "path" ? "string" : type;
}

// The words for a type of the key table in a message.
std::string type_words(const std::string &type) {
    if (type == "number" || type == "string")
        return "a " + type;
    if (type == "integer")
        return "an integer";
    if (type == "boolean")
        return "true or false";
    if (type.rfind('[', 0) == 0)
        return "an array " + type;
    if (type.rfind("array", 0) == 0)
        return "an " + type;      // "array of numbers"
    return "an array of " + type; // "3 booleans", "3 integers"
}

// An override's value as a TOML table holding it as "v". A string key takes
// the text as it stands (a bare word, waves.type=irregular; a number or a
// date alike: name=2 is the string "2"), unless it begins with a quote (a
// TOML string: the quoted form) or a bracket or brace (an array or inline
// table, which the reader then refuses). Every other key takes TOML syntax.
toml::table parse_value(const std::string &key, const std::string &type, const std::string &value,
                        const OverrideError &bad) {
    const bool text = type == "string" && value.find_first_of("\"'[{") != 0;
    toml::table parsed;
    try {
        parsed = toml::parse("v = " + (text ? toml_string(value) : value) + "\n", kSetSource);
    } catch (const toml::parse_error &e) {
        std::string description(e.description());
        std::replace(description.begin(), description.end(), '\n', ' ');
        if (type == "string") // it begins with a quote
            throw bad("key '" + key + "' takes a string, and " + value +
                      " is not one (a value that begins with a quote must be a whole TOML string)");
        if (!type.empty()) // toml++'s description of "v = abc" would only confuse
            throw bad("key '" + key + "' takes " + type_words(type) + ", and " + value + " is not one");
        throw bad("bad TOML value " + value + ": " + description + " (arrays need brackets)");
    }
    if (parsed.size() != 1)
        throw bad("the value must be a single TOML value");
    return parsed;
}

std::size_t array_index(const toml::array &a, const std::string &at, const std::string &seg,
                        const OverrideError &bad) {
    if (!is_index(seg))
        throw bad("'" + at + "' is an array: index it, e.g. " + at + ".0");
    const std::size_t index = std::stoul(seg);
    if (index >= a.size())
        throw bad("index " + seg + " out of range: '" + at + "' has " + std::to_string(a.size()) +
                  " entries");
    return index;
}

// The table or array an override's last segment lies in, creating a single
// table ([run], [waves], ...) that the file leaves out.
toml::node &parent_of(toml::table &root, const std::vector<std::string> &segments, const OverrideError &bad) {
    toml::node *cur = &root;
    std::string at;
    for (std::size_t i = 0; i + 1 < segments.size(); ++i) {
        const std::string &seg = segments[i];
        const std::string here = at.empty() ? seg : at + "." + seg;
        if (toml::table *t = cur->as_table()) {
            toml::node *child = t->get(seg);
            if (!child && cur == &root && is_single_table(seg)) {
                // Sections with all-default values may be absent from the file.
                toml::table created = toml::parse("t = {}", kSetSource);
                t->insert_or_assign(seg, std::move(*created.get("t")));
                child = t->get(seg);
            }
            if (!child)
                throw bad("'" + here + "' does not exist in the scene");
            cur = child;
        } else if (toml::array *a = cur->as_array()) {
            cur = a->get(array_index(*a, at, seg, bad));
        } else {
            throw bad("'" + at + "' is a single value, not a table");
        }
        at = here;
    }
    return *cur;
}

} // namespace

// Applies one --set KEY=VALUE to the parsed file: the key is found first (a
// path that leads nowhere, or an unknown key, is reported as such whatever
// the value), then the value is read as the key's type asks (parse_value).
void apply_override(toml::table &root, const std::string &text) {
    const OverrideError bad{text};
    const auto eq = text.find('=');
    if (eq == std::string::npos)
        throw bad("expected KEY=VALUE, e.g. run.duration=0.5");
    const std::string value = trimmed(text.substr(eq + 1));
    if (trimmed(text.substr(0, eq)).empty())
        throw bad("empty key");
    if (value.empty())
        throw bad("empty value (an empty string is \"\")");
    const std::vector<std::string> segments = split_key(trimmed(text.substr(0, eq)), bad);
    const std::vector<std::string> parents(segments.begin(), segments.end() - 1);
    const std::string key = join(segments, "."), at = join(parents, ".");
    const std::string &last = segments.back();
    toml::node &parent = parent_of(root, segments, bad);
    if (toml::table *t = parent.as_table()) {
        if (!t->contains(last)) {
            const std::vector<std::string> known = known_keys(parents);
            if (std::find(known.begin(), known.end(), last) == known.end())
                throw bad("unknown key '" + key + "'" + (known.empty() ? std::string() : hint(last, known)));
        }
        toml::table parsed = parse_value(key, declared_type(segments), value, bad);
        t->insert_or_assign(last, std::move(*parsed.get("v")));
    } else if (toml::array *a = parent.as_array()) {
        const std::size_t index = array_index(*a, at, last, bad);
        toml::table parsed = parse_value(key, "", value, bad);
        a->replace(a->cbegin() + static_cast<std::ptrdiff_t>(index), std::move(*parsed.get("v")));
    } else {
        throw bad("'" + at + "' is a single value, not a table");
    }
}

} // namespace armour::scene_detail
