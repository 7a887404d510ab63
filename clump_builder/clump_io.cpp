#include "clump_io.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

namespace armour {

void write_sphere_file(const Clump &clump, const std::string &path, const std::string &comment) {
    const std::string temporary = path + ".tmp";
    {
        std::ofstream out(temporary);
        if (!out)
            throw InputError(path + ": cannot write the sphere file");
        out << "# " << comment << "\n# x y z r [m], unit frame: origin at the exact centroid\n";
        out.precision(17);
        for (const auto &s : clump)
            out << s.center.x() << ' ' << s.center.y() << ' ' << s.center.z() << ' ' << s.radius << '\n';
        if (!out.flush())
            throw InputError(path + ": write failed");
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0)
        throw InputError(path + ": cannot rename the finished sphere file into place");
}

std::string liggghts_template_snippet(const Shape &shape, const Clump &clump, const std::string &sphere_file,
                                      const std::string &fix_id, int template_type) {
    const MassProperties &p = shape.props;
    // LIGGGHTS diagonalises the tensor with Jacobi rotations and keeps the
    // file frame only if the products are exactly zero: round-off products
    // of a symmetric unit would turn its principal frame by an arbitrary angle.
    const double scale = p.inertia.cwiseAbs().maxCoeff();
    auto entry = [&](int i, int j) {
        const double v = p.inertia(i, j);
        return (i != j && std::abs(v) < 1e-12 * scale) ? 0.0 : v;
    };
    std::ostringstream s;
    s.precision(12);
    s << "# armour-fsi unit template: " << shape.description << ", " << clump.size() << " spheres\n"
      << "# SI units. Exact mass " << p.mass << " kg at density " << p.density << " kg/m^3, volume "
      << p.volume << " m^3.\n"
      << "# inertia_tensor = Ixx Ixy Ixz Iyy Iyz Izz [kg m^2] about the centroid in the unit frame.\n"
      << "# use_density: the sphere file's origin is the centre of mass (no Monte Carlo step).\n";
    if (clump.size() < 2)
        s << "# WARNING: LIGGGHTS multisphere templates need at least 2 spheres.\n";
    s << "fix " << fix_id << " all particletemplate/multisphere 15485863 atom_type 1 density constant "
      << p.density << " nspheres " << clump.size() << " ntry 1000000 spheres file " << sphere_file
      << " scale 1.0 type " << template_type << " mass " << p.mass << " use_density inertia_tensor "
      << entry(0, 0) << ' ' << entry(0, 1) << ' ' << entry(0, 2) << ' ' << entry(1, 1) << ' ' << entry(1, 2)
      << ' ' << entry(2, 2) << '\n';
    return s.str();
}

TriangleMesh clump_surface_mesh(const Clump &clump, int subdivisions) {
    // Icosphere: an icosahedron with each triangle split in four per level.
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    TriangleMesh unit;
    for (const auto &v : {Eigen::Vector3d(-1, t, 0), Eigen::Vector3d(1, t, 0), Eigen::Vector3d(-1, -t, 0),
                          Eigen::Vector3d(1, -t, 0), Eigen::Vector3d(0, -1, t), Eigen::Vector3d(0, 1, t),
                          Eigen::Vector3d(0, -1, -t), Eigen::Vector3d(0, 1, -t), Eigen::Vector3d(t, 0, -1),
                          Eigen::Vector3d(t, 0, 1), Eigen::Vector3d(-t, 0, -1), Eigen::Vector3d(-t, 0, 1)})
        unit.vertices.push_back(v.normalized());
    unit.triangles = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int level = 0; level < subdivisions; ++level) {
        std::map<std::pair<int, int>, int> midpoint;
        auto middle = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            auto it = midpoint.find(key);
            if (it != midpoint.end())
                return it->second;
            unit.vertices.push_back((unit.vertices[a] + unit.vertices[b]).normalized());
            const int index = static_cast<int>(unit.vertices.size()) - 1;
            midpoint.emplace(key, index);
            return index;
        };
        std::vector<std::array<int, 3>> finer;
        for (const auto &tri : unit.triangles) {
            const int ab = middle(tri[0], tri[1]), bc = middle(tri[1], tri[2]), ca = middle(tri[2], tri[0]);
            finer.push_back({tri[0], ab, ca});
            finer.push_back({tri[1], bc, ab});
            finer.push_back({tri[2], ca, bc});
            finer.push_back({ab, bc, ca});
        }
        unit.triangles.swap(finer);
    }
    TriangleMesh all;
    for (const auto &s : clump) {
        const int base = static_cast<int>(all.vertices.size());
        for (const auto &v : unit.vertices)
            all.vertices.push_back(s.center + s.radius * v);
        for (const auto &tri : unit.triangles)
            all.triangles.push_back({base + tri[0], base + tri[1], base + tri[2]});
    }
    return all;
}

} // namespace armour
