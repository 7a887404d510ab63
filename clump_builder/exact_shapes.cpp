// CGAL translation unit: convex hulls and the exact boolean union of the dolos.
#include "shapes.h"

// GCC 12 reports a false -Wmaybe-uninitialized inside CGAL 5.5's
// self_intersections.h (pulled in by corefinement); the warning is in CGAL's
// code, not ours, so it is silenced for the CGAL headers only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>
#pragma GCC diagnostic pop

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace armour {

namespace {
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using HullMesh = CGAL::Surface_mesh<Epick::Point_3>;
using ExactMesh = CGAL::Surface_mesh<Epeck::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

template <class SM, class ToDouble> TriangleMesh to_triangle_mesh(const SM &sm, ToDouble to_double) {
    TriangleMesh mesh;
    std::unordered_map<std::size_t, int> index;
    for (auto v : sm.vertices()) {
        index[static_cast<std::size_t>(v)] = static_cast<int>(mesh.vertices.size());
        const auto &p = sm.point(v);
        mesh.vertices.emplace_back(to_double(p.x()), to_double(p.y()), to_double(p.z()));
    }
    for (auto f : sm.faces()) {
        std::array<int, 3> tri{};
        int k = 0;
        for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
            if (k == 3)
                throw std::logic_error("to_triangle_mesh: face is not a triangle");
            tri[k++] = index.at(static_cast<std::size_t>(v));
        }
        mesh.triangles.push_back(tri);
    }
    return mesh;
}

// Regular octagon with across-flats `flats`, flats normal to u, v and the two
// diagonals, centred at `centre` in the plane spanned by unit vectors u and v.
void add_octagon(std::vector<Eigen::Vector3d> &points, const Eigen::Vector3d &centre,
                 const Eigen::Vector3d &u, const Eigen::Vector3d &v, double flats) {
    const double pi = std::acos(-1.0);
    const double circumradius = 0.5 * flats / std::cos(pi / 8.0);
    for (int k = 0; k < 8; ++k) {
        // Corners half-way between the flat normals at k * 45 degrees.
        const double angle = pi / 8.0 + k * pi / 4.0;
        points.push_back(centre + circumradius * (std::cos(angle) * u + std::sin(angle) * v));
    }
}

ExactMesh to_exact(const TriangleMesh &mesh) {
    ExactMesh sm;
    for (const auto &p : mesh.vertices)
        sm.add_vertex(Epeck::Point_3(p.x(), p.y(), p.z()));
    for (const auto &t : mesh.triangles)
        sm.add_face(ExactMesh::Vertex_index(t[0]), ExactMesh::Vertex_index(t[1]),
                    ExactMesh::Vertex_index(t[2]));
    return sm;
}
} // namespace

// CGAL orients hull faces outward.
TriangleMesh convex_hull(const std::vector<Eigen::Vector3d> &points) {
    std::vector<Epick::Point_3> pts;
    pts.reserve(points.size());
    for (const auto &p : points)
        pts.emplace_back(p.x(), p.y(), p.z());
    HullMesh hull;
    CGAL::convex_hull_3(pts.begin(), pts.end(), hull);
    return to_triangle_mesh(hull, [](double x) { return x; });
}

TriangleMesh make_cube_mesh(double edge, double chamfer) {
    const double h = 0.5 * edge;
    std::vector<Eigen::Vector3d> points;
    if (chamfer <= 0.0) {
        for (int i = 0; i < 8; ++i)
            points.emplace_back(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
    } else {
        // Every permutation of (+-h, +-(h - c), +-(h - c)): the corners of the faces
        // shrunk by the chamfer; their hull has the chamfer faces in between.
        const double g = h - chamfer;
        for (int axis = 0; axis < 3; ++axis)
            for (int s = 0; s < 8; ++s) {
                Eigen::Vector3d p = Eigen::Vector3d::Constant(g);
                p[axis] = h;
                for (int d = 0; d < 3; ++d)
                    if (s & (1 << d))
                        p[d] = -p[d];
                points.push_back(p);
            }
    }
    return convex_hull(points);
}

std::vector<TriangleMesh> make_dolos_parts(double height, double waist_ratio) {
    const double C = waist_ratio * height; // shank across-flats
    const double F = 1.1 * C;              // fluke across-flats at its middle
    const double T = 0.8 * C;              // fluke across-flats at its tips
    // The shank ends on the fluke axes, well inside the flukes: no face of the
    // shank is tangent to a fluke face, which would break the rounded union.
    const double xA = 0.5 * height - 0.5 * F;
    const Eigen::Vector3d ex = Eigen::Vector3d::UnitX(), ey = Eigen::Vector3d::UnitY(),
                          ez = Eigen::Vector3d::UnitZ();

    std::vector<Eigen::Vector3d> shank;
    add_octagon(shank, -xA * ex, ey, ez, C);
    add_octagon(shank, xA * ex, ey, ez, C);

    auto fluke = [&](const Eigen::Vector3d &centre, const Eigen::Vector3d &axis, const Eigen::Vector3d &u,
                     const Eigen::Vector3d &v) {
        std::vector<Eigen::Vector3d> points;
        add_octagon(points, centre - 0.5 * height * axis, u, v, T);
        add_octagon(points, centre, u, v, F);
        add_octagon(points, centre + 0.5 * height * axis, u, v, T);
        return convex_hull(points);
    };
    return {convex_hull(shank), fluke(xA * ex, ey, ez, ex), fluke(-xA * ex, ez, ex, ey)};
}

TriangleMesh make_dolos_mesh(double height, double waist_ratio) {
    const auto parts = make_dolos_parts(height, waist_ratio);
    // Exact constructions: with Epick the intersection points are rounded
    // during corefinement and the union can self-intersect or fail.
    ExactMesh result = to_exact(parts[0]);
    for (std::size_t i = 1; i < parts.size(); ++i) {
        ExactMesh other = to_exact(parts[i]);
        ExactMesh out;
        if (!PMP::corefine_and_compute_union(result, other, out))
            throw std::runtime_error("make_dolos_mesh: CGAL union failed");
        result = std::move(out);
    }
    PMP::triangulate_faces(result);
    return to_triangle_mesh(result, [](const Epeck::FT &x) { return CGAL::to_double(x); });
}

} // namespace armour
