// TOML values as the text `--set KEY=VALUE` takes (internal to the sweep: it includes toml++).
#pragma once

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <toml++/toml.h>

namespace armour::sweep_detail {

// The shortest text that reads back as the same double, as a TOML float
// (0.3, not 0.29999999999999999).
inline std::string shortest_float(double v) {
    char text[32];
    for (int precision = 1; precision <= 17; ++precision) {
        std::snprintf(text, sizeof text, "%.*g", precision, v);
        if (std::strtod(text, nullptr) == v)
            break;
    }
    std::string s = text;
    if (s.find_first_of(".eEn") == std::string::npos)
        s += ".0";
    return s;
}

inline std::string toml_text(const toml::node &node) {
    if (const auto d = node.value_exact<double>())
        return shortest_float(*d);
    if (const auto *array = node.as_array()) {
        std::string out = "[";
        for (std::size_t i = 0; i < array->size(); ++i)
            out += (i ? ", " : "") + toml_text(*array->get(i));
        return out + "]";
    }
    std::ostringstream text;
    node.visit([&](const auto &v) { text << toml::toml_formatter{v}; });
    return text.str();
}

} // namespace armour::sweep_detail
