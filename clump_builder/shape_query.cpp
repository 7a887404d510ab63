// CGAL translation unit: AABB tree for distance and inside queries.
#include "shape_query.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>

namespace armour {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using Inside = CGAL::Side_of_triangle_mesh<Mesh, Kernel>;

Point to_point(const Eigen::Vector3d &p) {
    return {p.x(), p.y(), p.z()};
}
} // namespace

struct ShapeQuery::Impl {
    Mesh mesh;
    Tree tree;
    std::unique_ptr<Inside> inside;
    Eigen::Vector3d lower, upper;
};

ShapeQuery::ShapeQuery(const TriangleMesh &input) : impl_(std::make_unique<Impl>()) {
    std::vector<Mesh::Vertex_index> index;
    index.reserve(input.vertices.size());
    impl_->lower = Eigen::Vector3d::Constant(HUGE_VAL);
    impl_->upper = Eigen::Vector3d::Constant(-HUGE_VAL);
    for (const auto &v : input.vertices) {
        index.push_back(impl_->mesh.add_vertex(to_point(v)));
        impl_->lower = impl_->lower.cwiseMin(v);
        impl_->upper = impl_->upper.cwiseMax(v);
    }
    for (const auto &t : input.triangles)
        impl_->mesh.add_face(index[t[0]], index[t[1]], index[t[2]]);
    impl_->tree.insert(faces(impl_->mesh).first, faces(impl_->mesh).second, impl_->mesh);
    impl_->tree.accelerate_distance_queries();
    impl_->inside = std::make_unique<Inside>(impl_->tree);
}

ShapeQuery::~ShapeQuery() = default;

bool ShapeQuery::inside(const Eigen::Vector3d &p) const {
    return (*impl_->inside)(to_point(p)) != CGAL::ON_UNBOUNDED_SIDE;
}

double ShapeQuery::distance(const Eigen::Vector3d &p) const {
    return std::sqrt(impl_->tree.squared_distance(to_point(p)));
}

double ShapeQuery::signed_distance(const Eigen::Vector3d &p) const {
    const double d = distance(p);
    return inside(p) ? -d : d;
}

Eigen::Vector3d ShapeQuery::lower() const {
    return impl_->lower;
}
Eigen::Vector3d ShapeQuery::upper() const {
    return impl_->upper;
}

} // namespace armour
