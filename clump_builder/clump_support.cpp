// Resting faces of the exact unit and topple angles of the unit and its clump.
#include "clump_support.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace armour {

namespace detail {

std::vector<Eigen::Vector2d> hull_2d(std::vector<Eigen::Vector2d> points) {
    // Andrew's monotone chain.
    std::sort(points.begin(), points.end(), [](const Eigen::Vector2d &a, const Eigen::Vector2d &b) {
        return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    });
    if (points.size() < 3)
        return points;
    auto cross = [](const Eigen::Vector2d &o, const Eigen::Vector2d &a, const Eigen::Vector2d &b) {
        return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
    };
    std::vector<Eigen::Vector2d> hull(2 * points.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0)
            --k;
        hull[k++] = points[i];
    }
    for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0)
            --k;
        hull[k++] = points[i];
    }
    hull.resize(k - 1);
    return hull;
}

double depth_inside(const std::vector<Eigen::Vector2d> &polygon, const Eigen::Vector2d &p) {
    if (polygon.size() < 3)
        return -1.0;
    double depth = HUGE_VAL;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Eigen::Vector2d &a = polygon[i];
        const Eigen::Vector2d edge = polygon[(i + 1) % polygon.size()] - a;
        depth = std::min(depth, (edge.x() * (p - a).y() - edge.y() * (p - a).x()) / edge.norm());
    }
    return depth;
}

double exit_distance(const std::vector<Eigen::Vector2d> &polygon, const Eigen::Vector2d &p,
                     const Eigen::Vector2d &towards) {
    if (!(depth_inside(polygon, p) > 0.0))
        return 0.0;
    double travel = HUGE_VAL;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Eigen::Vector2d &a = polygon[i];
        const Eigen::Vector2d edge = polygon[(i + 1) % polygon.size()] - a;
        const Eigen::Vector2d outward = Eigen::Vector2d(edge.y(), -edge.x()).normalized();
        const double approach = outward.dot(towards);
        if (approach > 1e-12)
            travel = std::min(travel, outward.dot(a - p) / approach);
    }
    return travel;
}

} // namespace detail

std::vector<RestingFace> resting_faces(const TriangleMesh &mesh, const Eigen::Vector3d &centre_of_mass,
                                       double Dn) {
    const TriangleMesh hull = convex_hull(mesh.vertices);
    const double tolerance = 1e-9 * Dn;
    // Hull faces: coplanar triangles grouped by their outward plane.
    struct Plane {
        Eigen::Vector3d normal;
        double offset;
        std::vector<int> triangles;
    };
    std::vector<Plane> planes;
    for (std::size_t t = 0; t < hull.triangles.size(); ++t) {
        const auto &tri = hull.triangles[t];
        const Eigen::Vector3d &a = hull.vertices[tri[0]];
        const Eigen::Vector3d n = (hull.vertices[tri[1]] - a).cross(hull.vertices[tri[2]] - a).normalized();
        auto same = std::find_if(planes.begin(), planes.end(), [&](const Plane &f) {
            return (f.normal - n).norm() < 1e-9 && std::abs(f.offset - n.dot(a)) < tolerance;
        });
        if (same == planes.end())
            planes.push_back({n, n.dot(a), {static_cast<int>(t)}});
        else
            same->triangles.push_back(static_cast<int>(t));
    }
    std::vector<RestingFace> faces;
    for (const Plane &plane : planes) {
        RestingFace f;
        f.normal = plane.normal;
        f.offset = plane.offset;
        f.u = plane.normal.unitOrthogonal();
        f.v = plane.normal.cross(f.u);
        std::vector<Eigen::Vector2d> corners;
        for (int t : plane.triangles)
            for (int c : hull.triangles[t])
                corners.push_back(f.in_plane(hull.vertices[c]));
        f.polygon = detail::hull_2d(corners);
        f.foot = f.in_plane(centre_of_mass);
        f.height = plane.offset - plane.normal.dot(centre_of_mass);
        // The centre of mass, projected along the normal, must land inside
        // the face for the unit to rest on it.
        f.support = detail::depth_inside(f.polygon, f.foot);
        if (f.support <= tolerance)
            continue;
        for (const Eigen::Vector2d &c : f.polygon)
            f.corners.push_back(c.x() * f.u + c.y() * f.v + f.offset * f.normal);
        faces.push_back(std::move(f));
    }
    return faces;
}

std::vector<FaceTopple> topple_angles(const TriangleMesh &mesh, const Eigen::Vector3d &centre_of_mass,
                                      const Clump &clump, double Dn) {
    constexpr double kDegrees = 180.0 / 3.14159265358979323846;
    std::vector<FaceTopple> result;
    for (const RestingFace &face : resting_faces(mesh, centre_of_mass, Dn)) {
        FaceTopple t;
        t.normal = face.normal;
        // The clump's plane touches its lowest sphere; the spheres within
        // kSupportContact Dn of it carry load.
        double reach = -HUGE_VAL;
        for (const Sphere &s : clump)
            reach = std::max(reach, face.normal.dot(s.center) + s.radius);
        std::vector<Eigen::Vector2d> touching;
        for (std::size_t j = 0; j < clump.size(); ++j)
            if (reach - (face.normal.dot(clump[j].center) + clump[j].radius) <= kSupportContact * Dn) {
                touching.push_back(face.in_plane(clump[j].center));
                t.clump_supports.push_back(static_cast<int>(j));
            }
        const std::vector<Eigen::Vector2d> support = detail::hull_2d(touching);
        const double clump_height = reach - face.normal.dot(centre_of_mass);
        const std::size_t n = face.polygon.size();
        for (std::size_t e = 0; e < n; ++e) {
            const Eigen::Vector2d edge = face.polygon[(e + 1) % n] - face.polygon[e];
            const Eigen::Vector2d outward = Eigen::Vector2d(edge.y(), -edge.x()).normalized();
            // Where the foot's perpendicular to the edge misses the edge, the
            // vertical leaves the face through a neighbouring edge first.
            t.exact_deg.push_back(
                kDegrees * std::atan2(detail::exit_distance(face.polygon, face.foot, outward), face.height));
            t.clump_deg.push_back(
                kDegrees * std::atan2(detail::exit_distance(support, face.foot, outward), clump_height));
        }
        result.push_back(std::move(t));
    }
    return result;
}

namespace {
// The direction s with n_f . s = 1 on each of the given faces (least
// squares, minimum norm): a sphere moved along it gains the same reach
// beyond every one of them.
Eigen::Vector3d bisector_of(const std::vector<RestingFace> &faces, const std::vector<int> &on) {
    Eigen::MatrixXd normals(static_cast<Eigen::Index>(on.size()), 3);
    for (std::size_t i = 0; i < on.size(); ++i)
        normals.row(static_cast<Eigen::Index>(i)) = faces[static_cast<std::size_t>(on[i])].normal.transpose();
    return normals.completeOrthogonalDecomposition().solve(
        Eigen::VectorXd::Ones(static_cast<Eigen::Index>(on.size())));
}
} // namespace

std::vector<SupportCorner> support_corners(const std::vector<RestingFace> &faces, double Dn) {
    std::vector<SupportCorner> corners;
    for (std::size_t f = 0; f < faces.size(); ++f)
        for (const Eigen::Vector3d &c : faces[f].corners) {
            auto same = std::find_if(corners.begin(), corners.end(), [&](const SupportCorner &k) {
                return (k.vertex - c).norm() < 1e-9 * Dn;
            });
            if (same == corners.end())
                corners.push_back({c, Eigen::Vector3d::Zero(), {static_cast<int>(f)}});
            else
                same->faces.push_back(static_cast<int>(f));
        }
    for (SupportCorner &k : corners)
        k.bisector = bisector_of(faces, k.faces);
    return corners;
}

void add_edge_supports(std::vector<SupportCorner> &corners, const std::vector<RestingFace> &faces,
                       int per_edge, double Dn) {
    auto corner_index = [&](const Eigen::Vector3d &p) {
        for (std::size_t k = 0; k < corners.size(); ++k)
            if ((corners[k].vertex - p).norm() < 1e-9 * Dn)
                return static_cast<int>(k);
        return -1;
    };
    auto holds = [](const SupportCorner &k, int face) {
        return std::find(k.faces.begin(), k.faces.end(), face) != k.faces.end();
    };
    std::vector<std::pair<int, int>> done; // an edge shared by two faces gets its spheres once
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const std::size_t n = faces[f].corners.size();
        for (std::size_t e = 0; e < n; ++e) {
            const int a = corner_index(faces[f].corners[e]);
            const int b = corner_index(faces[f].corners[(e + 1) % n]);
            const std::pair<int, int> edge{std::min(a, b), std::max(a, b)};
            if (a < 0 || b < 0 || std::find(done.begin(), done.end(), edge) != done.end())
                continue;
            done.push_back(edge);
            // The faces the edge bounds: those both its corners lie on.
            std::vector<int> edge_faces;
            for (int g : corners[static_cast<std::size_t>(a)].faces)
                if (holds(corners[static_cast<std::size_t>(b)], g))
                    edge_faces.push_back(g);
            const Eigen::Vector3d bisector = bisector_of(faces, edge_faces);
            const Eigen::Vector3d pa =
                corners[static_cast<std::size_t>(a)].vertex; // copies: push_back moves them
            const Eigen::Vector3d pb = corners[static_cast<std::size_t>(b)].vertex;
            for (int i = 1; i <= per_edge; ++i)
                corners.push_back(
                    {pa + (pb - pa) * (static_cast<double>(i) / (per_edge + 1)), bisector, edge_faces});
        }
    }
}

void place_support_spheres(Clump &clump, const std::vector<SupportCorner> &corners,
                           const std::vector<RestingFace> &faces, double radius) {
    // How far the other spheres reach beyond any face (never less than the
    // face). One reach for all corners: a corner shared by several faces
    // then reaches the same plane on each, and every face stands on all its
    // corners.
    double reach = 0.0;
    for (const RestingFace &face : faces)
        for (std::size_t j = corners.size(); j < clump.size(); ++j)
            reach = std::max(reach, face.normal.dot(clump[j].center) + clump[j].radius - face.offset);
    for (std::size_t k = 0; k < corners.size() && k < clump.size(); ++k)
        clump[k] = {corners[k].vertex + (reach - radius) * corners[k].bisector, radius};
}

double topple_error_deg(const TriangleMesh &mesh, const Eigen::Vector3d &centre_of_mass, const Clump &clump,
                        double Dn) {
    double worst = 0.0;
    for (const FaceTopple &f : topple_angles(mesh, centre_of_mass, clump, Dn))
        for (std::size_t e = 0; e < f.exact_deg.size(); ++e)
            worst = std::max(worst, std::abs(f.clump_deg[e] - f.exact_deg[e]));
    return worst;
}

} // namespace armour
