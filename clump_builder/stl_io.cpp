#include "stl_io.h"

#include <Eigen/Geometry>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

namespace armour {

namespace {

[[noreturn]] void fail(const std::string &path, const std::string &reason) {
    throw InputError(path + ": " + reason);
}

// Collects loose STL triangles into an indexed mesh. Only bit-identical
// coordinates are merged: a tolerance would silently change user geometry.
class MeshCollector {
  public:
    void add(const std::array<std::array<double, 3>, 3> &corners) {
        std::array<int, 3> tri{};
        for (int k = 0; k < 3; ++k)
            tri[k] = index_of(corners[k]);
        // A repeated index has no area and no orientation; STL exporters emit such
        // slivers, and keeping them would only fail the manifold checks later.
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
            return;
        mesh_.triangles.push_back(tri);
    }
    TriangleMesh take() { return std::move(mesh_); }

  private:
    int index_of(const std::array<double, 3> &p) {
        auto [it, inserted] = index_.try_emplace(p, static_cast<int>(mesh_.vertices.size()));
        if (inserted)
            mesh_.vertices.emplace_back(p[0], p[1], p[2]);
        return it->second;
    }
    std::map<std::array<double, 3>, int> index_;
    TriangleMesh mesh_;
};

std::uint32_t read_u32(const unsigned char *p) {
    return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
           static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

float read_f32(const unsigned char *p) {
    const std::uint32_t bits = read_u32(p);
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

void put_u32(std::string &out, std::uint32_t v) {
    for (int k = 0; k < 4; ++k)
        out.push_back(static_cast<char>((v >> (8 * k)) & 0xffu));
}

void put_f32(std::string &out, float value) {
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    put_u32(out, bits);
}

TriangleMesh parse_binary(const std::string &path, const std::string &data, std::uint32_t count) {
    MeshCollector collector;
    for (std::uint32_t i = 0; i < count; ++i) {
        const auto *rec = reinterpret_cast<const unsigned char *>(data.data()) + 84 + 50 * std::size_t{i};
        std::array<std::array<double, 3>, 3> corners{};
        for (int k = 0; k < 3; ++k)
            for (int d = 0; d < 3; ++d) {
                const float v = read_f32(rec + 12 + 12 * k + 4 * d); // skip the stored normal
                if (!std::isfinite(v))
                    fail(path, "non-finite vertex coordinate in triangle " + std::to_string(i));
                corners[k][d] = v;
            }
        collector.add(corners);
    }
    return collector.take();
}

std::vector<std::string> split(const std::string &line) {
    std::istringstream in(line);
    return {std::istream_iterator<std::string>(in), std::istream_iterator<std::string>()};
}

bool parse_double(const std::string &token, double &value) {
    // from_chars: locale-independent and exact, unlike strtod under a user locale.
    const char *begin = token.data();
    const char *end = begin + token.size();
    if (begin != end && *begin == '+')
        ++begin;
    const auto result = std::from_chars(begin, end, value);
    return result.ec == std::errc() && result.ptr == end && std::isfinite(value);
}

TriangleMesh parse_ascii(const std::string &path, const std::string &data) {
    std::istringstream in(data);
    std::string line;
    int line_no = 0;
    auto malformed = [&](const std::string &why) {
        fail(path, "malformed ASCII STL at line " + std::to_string(line_no) + ": " + why);
    };

    // States of the facet grammar; the stored normal is ignored (it is
    // recomputed from the vertex order, which is what defines orientation).
    enum class State { Solid, Facet, Loop, Vertex, EndLoop, EndFacet, Done };
    State state = State::Solid;
    MeshCollector collector;
    std::array<std::array<double, 3>, 3> corners{};
    int corner = 0;
    while (std::getline(in, line)) {
        ++line_no;
        const auto tokens = split(line);
        if (tokens.empty())
            continue;
        const std::string &key = tokens[0];
        switch (state) {
        case State::Solid:
            if (key != "solid")
                malformed("expected 'solid'");
            state = State::Facet;
            break;
        case State::Facet:
            if (key == "endsolid") {
                state = State::Done;
            } else if (key == "facet") {
                state = State::Loop;
            } else {
                malformed("expected 'facet' or 'endsolid', got '" + key + "'");
            }
            break;
        case State::Loop:
            if (key != "outer" || tokens.size() < 2 || tokens[1] != "loop")
                malformed("expected 'outer loop', got '" + key + "'");
            state = State::Vertex;
            corner = 0;
            break;
        case State::Vertex:
            if (key != "vertex")
                malformed("expected 'vertex', got '" + key + "'");
            if (tokens.size() != 4)
                malformed("a vertex needs 3 coordinates");
            for (int d = 0; d < 3; ++d)
                if (!parse_double(tokens[d + 1], corners[corner][d]))
                    malformed("bad coordinate '" + tokens[d + 1] + "'");
            if (++corner == 3)
                state = State::EndLoop;
            break;
        case State::EndLoop:
            if (key != "endloop")
                malformed(key == "vertex" ? "more than 3 vertices in a facet"
                                          : "expected 'endloop', got '" + key + "'");
            state = State::EndFacet;
            break;
        case State::EndFacet:
            if (key != "endfacet")
                malformed("expected 'endfacet', got '" + key + "'");
            collector.add(corners);
            state = State::Facet;
            break;
        case State::Done:
            // Several solids in one file are legal; anything else is not.
            if (key != "solid")
                malformed("text after 'endsolid'");
            state = State::Facet;
            break;
        }
    }
    if (state != State::Done && state != State::Facet)
        fail(path, "malformed ASCII STL at line " + std::to_string(line_no) + ": file ends inside a facet");
    if (state == State::Facet)
        fail(path, "malformed ASCII STL at line " + std::to_string(line_no) + ": missing 'endsolid'");
    return collector.take();
}

} // namespace

TriangleMesh read_stl(const std::string &path) {
    std::ifstream file(path, std::ios::binary);
    if (!file)
        fail(path, "cannot open file for reading");
    const std::string data((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    if (file.bad())
        fail(path, "read error");
    if (data.empty())
        fail(path, "file is empty");

    TriangleMesh mesh;
    // Text has no NUL bytes and binary records nearly always do (zero attribute
    // bytes), so a truncated binary file with a "solid..." header is still
    // reported as a truncated binary file.
    const bool ascii = data.compare(0, 5, "solid") == 0 && data.find('\0') == std::string::npos;
    // A binary file's size is fixed by its triangle count. Many exporters put
    // "solid" into the binary header too, so the size test comes first.
    std::uint32_t count = 0;
    if (data.size() >= 84)
        count = read_u32(reinterpret_cast<const unsigned char *>(data.data()) + 80);
    if (data.size() >= 84 && data.size() == 84 + 50 * std::uint64_t{count}) {
        mesh = parse_binary(path, data, count);
    } else if (ascii) {
        mesh = parse_ascii(path, data);
    } else if (data.size() < 84) {
        fail(path, "truncated binary STL (" + std::to_string(data.size()) +
                       " bytes, shorter than the 84-byte header) and not ASCII STL");
    } else {
        fail(path, "truncated binary STL (header declares " + std::to_string(count) +
                       " triangles = " + std::to_string(84 + 50 * std::uint64_t{count}) +
                       " bytes, file has " + std::to_string(data.size()) + ")");
    }
    if (mesh.triangles.empty())
        fail(path, "no triangles");
    return mesh;
}

void write_stl(const TriangleMesh &mesh, const std::string &path, bool binary,
               const std::string &solid_name) {
    std::string out;
    if (binary) {
        // The header must not start with "solid": some readers then take the file for ASCII.
        std::string header = "binary STL " + solid_name;
        header.resize(80, ' ');
        out = header;
        out.reserve(84 + 50 * mesh.triangles.size());
        put_u32(out, static_cast<std::uint32_t>(mesh.triangles.size()));
    } else {
        out = "solid " + solid_name + "\n";
    }
    char buf[512];
    for (const auto &t : mesh.triangles) {
        const Eigen::Vector3d &a = mesh.vertices[t[0]];
        const Eigen::Vector3d &b = mesh.vertices[t[1]];
        const Eigen::Vector3d &c = mesh.vertices[t[2]];
        Eigen::Vector3d n = (b - a).cross(c - a);
        if (n.norm() > 0.0)
            n.normalize();
        if (binary) {
            for (const Eigen::Vector3d *p : std::array<const Eigen::Vector3d *, 4>{&n, &a, &b, &c})
                for (int d = 0; d < 3; ++d)
                    put_f32(out, static_cast<float>((*p)[d]));
            out.append(2, '\0');
        } else {
            // 17 significant digits make the double -> text -> double round trip exact.
            std::snprintf(buf, sizeof buf, "  facet normal %.9g %.9g %.9g\n    outer loop\n", n.x(), n.y(),
                          n.z());
            out += buf;
            for (const Eigen::Vector3d *p : std::array<const Eigen::Vector3d *, 3>{&a, &b, &c}) {
                std::snprintf(buf, sizeof buf, "      vertex %.17g %.17g %.17g\n", p->x(), p->y(), p->z());
                out += buf;
            }
            out += "    endloop\n  endfacet\n";
        }
    }
    if (!binary)
        out += "endsolid " + solid_name + "\n";

    const std::string tmp = path + ".tmp";
    {
        std::ofstream file(tmp, std::ios::binary | std::ios::trunc);
        if (!file)
            fail(tmp, "cannot open file for writing");
        file.write(out.data(), static_cast<std::streamsize>(out.size()));
        file.close();
        if (!file) {
            std::remove(tmp.c_str());
            fail(tmp, "write failed");
        }
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::remove(tmp.c_str());
        fail(path, std::string("cannot rename temporary file: ") + std::strerror(errno));
    }
}

} // namespace armour
