// CGAL translation unit: exact predicates for degeneracy and self-intersection.
#include "mesh_check.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace armour {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

Point to_point(const Eigen::Vector3d &p) {
    return {p.x(), p.y(), p.z()};
}

std::uint64_t edge_key(int a, int b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

std::string vertex_text(const TriangleMesh &mesh, int v) {
    std::ostringstream out;
    const auto &p = mesh.vertices[v];
    out << "vertex " << v << " at (" << p.x() << ", " << p.y() << ", " << p.z() << ")";
    return out.str();
}

std::string edge_text(const TriangleMesh &mesh, int a, int b) {
    return "edge from " + vertex_text(mesh, a) + " to " + vertex_text(mesh, b);
}

std::string count_of(std::size_t n, const std::string &singular, const std::string &plural) {
    return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

// Each check throws InputError naming `name` and the first offending element.
[[noreturn]] void fail(const std::string &name, const std::string &reason) {
    throw InputError(name + ": " + reason);
}

// Union-find over the triangles around one vertex.
int find_root(std::vector<int> &parent, int i) {
    while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
    return i;
}

// On a closed edge-manifold mesh the triangles around a vertex form one or
// more closed fans; more than one means surface sheets pinched at a point.
void check_vertex_fans(const TriangleMesh &mesh, const std::string &name) {
    const int nv = static_cast<int>(mesh.vertices.size());
    std::vector<std::vector<int>> around(nv);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (int v : mesh.triangles[t])
            around[v].push_back(static_cast<int>(t));
    std::size_t count = 0;
    int example = -1;
    std::vector<int> parent;
    std::unordered_map<int, int> first_use; // other edge endpoint -> local triangle
    for (int v = 0; v < nv; ++v) {
        const auto &tris = around[v];
        if (tris.empty())
            continue; // unused vertices do not affect the solid
        parent.resize(tris.size());
        std::iota(parent.begin(), parent.end(), 0);
        first_use.clear();
        for (int i = 0; i < static_cast<int>(tris.size()); ++i)
            for (int w : mesh.triangles[tris[i]]) {
                if (w == v)
                    continue;
                auto [it, inserted] = first_use.try_emplace(w, i);
                if (!inserted)
                    parent[find_root(parent, i)] = find_root(parent, it->second);
            }
        int fans = 0;
        for (int i = 0; i < static_cast<int>(tris.size()); ++i)
            fans += find_root(parent, i) == i;
        if (fans > 1 && count++ == 0)
            example = v;
    }
    if (count > 0)
        fail(name, "mesh is not vertex-manifold (separate sheets meet at a vertex): " +
                       count_of(count, "vertex", "vertices") + ", e.g. " + vertex_text(mesh, example));
}

void check_indices(const TriangleMesh &mesh, const std::string &name) {
    const int nv = static_cast<int>(mesh.vertices.size());
    if (mesh.triangles.empty())
        fail(name, "mesh has no triangles");
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (int v : mesh.triangles[t])
            if (v < 0 || v >= nv)
                fail(name, "triangle " + std::to_string(t) + " has vertex index " + std::to_string(v) +
                               " outside [0, " + std::to_string(nv) + ")");
    for (int v = 0; v < nv; ++v)
        if (!mesh.vertices[v].allFinite())
            fail(name, "vertex " + std::to_string(v) + " has a non-finite coordinate");
}

// Exact collinearity: a near-degenerate sliver is still a valid triangle.
void check_degenerate(const TriangleMesh &mesh, const std::string &name) {
    std::size_t count = 0, example = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto &tri = mesh.triangles[t];
        const bool repeated = tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2];
        if (repeated || CGAL::collinear(to_point(mesh.vertices[tri[0]]), to_point(mesh.vertices[tri[1]]),
                                        to_point(mesh.vertices[tri[2]]))) {
            if (count++ == 0)
                example = t;
        }
    }
    if (count > 0)
        fail(name, count_of(count, "degenerate (zero-area) triangle", "degenerate (zero-area) triangles") +
                       ", e.g. triangle " + std::to_string(example));
}

// Closed and edge-manifold (every edge used by exactly two triangles), and
// consistently oriented: the two traverse it in opposite directions.
void check_edges(const TriangleMesh &mesh, const std::string &name) {
    // Undirected edge -> number of uses, and directed edge -> number of uses.
    std::unordered_map<std::uint64_t, int> undirected, directed;
    undirected.reserve(3 * mesh.triangles.size());
    directed.reserve(3 * mesh.triangles.size());
    for (const auto &tri : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            const int a = tri[k], b = tri[(k + 1) % 3];
            ++undirected[edge_key(std::min(a, b), std::max(a, b))];
            ++directed[edge_key(a, b)];
        }
    const auto report_edges = [&](const std::unordered_map<std::uint64_t, int> &edges, auto predicate,
                                  const std::string &what) {
        std::size_t count = 0;
        std::uint64_t example = 0;
        for (const auto &[key, uses] : edges)
            if (predicate(uses) && count++ == 0)
                example = key;
        if (count > 0)
            fail(name, what + count_of(count, "edge", "edges") + ", e.g. " +
                           edge_text(mesh, static_cast<int>(example >> 32),
                                     static_cast<int>(example & 0xffffffffu)));
    };
    report_edges(
        undirected, [](int uses) { return uses == 1; },
        "mesh is not closed (boundary edges used by one triangle): ");
    report_edges(
        undirected, [](int uses) { return uses > 2; },
        "mesh is not edge-manifold (edges shared by more than 2 triangles): ");
    check_vertex_fans(mesh, name);
    report_edges(
        directed, [](int uses) { return uses > 1; },
        "inconsistent orientation (neighbouring triangles traverse a shared edge in the same "
        "direction): ");
}

// Exact predicates: no two triangles cross.
void check_self_intersection(const TriangleMesh &mesh, const std::string &name) {
    SurfaceMesh sm;
    sm.reserve(static_cast<SurfaceMesh::size_type>(mesh.vertices.size()),
               static_cast<SurfaceMesh::size_type>(3 * mesh.triangles.size() / 2),
               static_cast<SurfaceMesh::size_type>(mesh.triangles.size()));
    for (const auto &p : mesh.vertices)
        sm.add_vertex(to_point(p));
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto &tri = mesh.triangles[t];
        const auto f = sm.add_face(SurfaceMesh::Vertex_index(tri[0]), SurfaceMesh::Vertex_index(tri[1]),
                                   SurfaceMesh::Vertex_index(tri[2]));
        if (f == SurfaceMesh::null_face())
            fail(name, "triangle " + std::to_string(t) + " cannot be connected to its neighbours");
    }
    if (PMP::does_self_intersect(sm)) {
        std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> pairs;
        PMP::self_intersections(sm, std::back_inserter(pairs));
        std::string example;
        if (!pairs.empty())
            example = ", e.g. triangles " + std::to_string(static_cast<std::size_t>(pairs[0].first)) +
                      " and " + std::to_string(static_cast<std::size_t>(pairs[0].second));
        fail(name, "mesh intersects itself: " + count_of(pairs.size(), "pair", "pairs") + " of triangles" +
                       example);
    }
}

// A solid: a volume above rounding noise, faces pointing out.
void check_volume(const TriangleMesh &mesh, const std::string &name) {
    Eigen::Vector3d lower = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d upper = -lower;
    for (const auto &tri : mesh.triangles)
        for (int v : tri) {
            lower = lower.cwiseMin(mesh.vertices[v]);
            upper = upper.cwiseMax(mesh.vertices[v]);
        }
    const double extent = (upper - lower).maxCoeff();
    const double volume = signed_volume(mesh);
    std::ostringstream vol;
    vol << volume;
    // Rounding noise in the volume sum scales with the bounding box.
    if (std::abs(volume) <= 1e-12 * extent * extent * extent)
        fail(name, "zero volume (signed volume " + vol.str() + " m^3): the mesh is flat");
    if (volume < 0.0)
        fail(name, "faces point inward (signed volume " + vol.str() + " m^3)");
}

} // namespace

void validate_mesh(const TriangleMesh &mesh, const std::string &name) {
    check_indices(mesh, name);
    check_degenerate(mesh, name);
    check_edges(mesh, name);
    check_self_intersection(mesh, name);
    check_volume(mesh, name);
}

} // namespace armour
