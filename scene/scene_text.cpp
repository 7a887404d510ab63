// Numbers and strings as scene files and messages write them.
#include "scene_keys.h"

#include <charconv>
#include <cstdio>

namespace armour {

std::string number_text(double v) {
    char buf[64];
    const auto result = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, result.ptr);
}

std::string figure_text(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

// "1" would read back as an integer and "-0" would lose its sign.
std::string toml_float(double v) {
    std::string s = number_text(v);
    if (s.find_first_of(".eEn") == std::string::npos)
        s += ".0";
    return s;
}

std::string vector_text(const Eigen::Ref<const Eigen::VectorXd> &v) {
    std::string out = "[";
    for (Eigen::Index i = 0; i < v.size(); ++i)
        out += (i ? ", " : "") + toml_float(v[i]);
    return out + "]";
}

std::string toml_string(const std::string &s) {
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

} // namespace armour
