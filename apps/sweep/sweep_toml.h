// TOML values as the text `--set KEY=VALUE` takes (internal to the sweep: it includes toml++).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <toml++/toml.h>

namespace armour::sweep_detail {

// The shortest text that reads back as the same double, as a TOML float
// (0.3, not 0.29999999999999999), written out in full between 1e-4 and 1e15
// (2050.0, not 2.05e+03: it names a case's column in results.csv).
inline std::string shortest_float(double v) {
    char text[48];
    int precision = 1;
    for (; precision <= 17; ++precision) {
        std::snprintf(text, sizeof text, "%.*g", precision, v);
        if (std::strtod(text, nullptr) == v)
            break;
    }
    const double magnitude = std::fabs(v);
    if (std::strchr(text, 'e') && magnitude >= 1e-4 && magnitude < 1e15) {
        const int exponent = static_cast<int>(std::floor(std::log10(magnitude)));
        std::snprintf(text, sizeof text, "%.*f", std::max(0, precision - 1 - exponent), v);
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
