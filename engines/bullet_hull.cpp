// The collision core of a convex unit for Bullet: its hull shrunk by the
// collision margin (Bullet adds the margin back around it). Apart from the
// adapter so that bullet_engine.cpp stays one job: the world and its contacts.
#include "bullet_engine.h"

// Bullet's headers come in as SYSTEM (PkgConfig::BULLET), so they raise no warnings.
#include <LinearMath/btConvexHullComputer.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace armour {

namespace {

std::string num(double v) {
    std::ostringstream s;
    s.precision(10);
    s << v;
    return s.str();
}

Eigen::Vector3d eig(const btVector3 &v) {
    return {v.x(), v.y(), v.z()};
}

struct Plane {
    Eigen::Vector3d n; // outward unit normal
    double d;          // n . x <= d inside
};

// Hull faces as loops of vertex indices (into computer.vertices).
std::vector<std::vector<int>> hull_faces(const btConvexHullComputer &hull) {
    std::vector<std::vector<int>> faces;
    for (int f = 0; f < hull.faces.size(); ++f) {
        std::vector<int> loop;
        const btConvexHullComputer::Edge *first = &hull.edges[hull.faces[f]];
        const btConvexHullComputer::Edge *e = first;
        do {
            loop.push_back(e->getSourceVertex());
            e = e->getNextEdgeOfFace();
        } while (e != first && loop.size() <= static_cast<std::size_t>(hull.vertices.size()));
        faces.push_back(std::move(loop));
    }
    return faces;
}

btConvexHullComputer compute_hull(const std::vector<Eigen::Vector3d> &points) {
    std::vector<double> coords;
    coords.reserve(3 * points.size());
    for (const auto &p : points)
        coords.insert(coords.end(), {p.x(), p.y(), p.z()});
    btConvexHullComputer hull;
    hull.compute(coords.data(), 3 * static_cast<int>(sizeof(double)), static_cast<int>(points.size()), 0.0,
                 0.0);
    return hull;
}

} // namespace

// Bullet's hull computer works on integer coordinates (about 1e-4 of the
// extent), so it is used for topology only: the face planes are recomputed
// from the original double coordinates, moved inward by the margin, and the
// new vertices are the intersections of the moved planes, found through the
// polar dual (its faces are the primal vertices) and solved in double.
std::vector<Eigen::Vector3d> shrunk_hull(const std::vector<Eigen::Vector3d> &points, double margin,
                                         const std::string &what) {
    if (points.size() < 4)
        throw InputError(what + ": fewer than 4 points, no volume");
    const btConvexHullComputer hull = compute_hull(points);
    if (hull.faces.size() < 4)
        throw InputError(what + ": the points are flat, no volume");
    auto original = [&](int v) {
        const int k = hull.original_vertex_index[v];
        return k >= 0 ? points[static_cast<std::size_t>(k)] : eig(hull.vertices[v]);
    };
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int v = 0; v < hull.vertices.size(); ++v)
        centre += original(v);
    centre /= static_cast<double>(hull.vertices.size());

    std::vector<Plane> planes;
    double size = 0.0;
    for (const auto &p : points)
        size = std::max(size, (p - centre).norm());
    for (const auto &loop : hull_faces(hull)) {
        Eigen::Vector3d n = Eigen::Vector3d::Zero(); // Newell's normal
        for (std::size_t i = 0; i < loop.size(); ++i)
            n += original(loop[i]).cross(original(loop[(i + 1) % loop.size()]));
        if (n.norm() <= 1e-14 * size * size)
            continue;
        n.normalize();
        double d = -HUGE_VAL;
        for (const auto &p : points)
            d = std::max(d, n.dot(p));
        planes.push_back({n, d});
    }
    // Polar dual about `centre` of {x : n.(x - c) <= s}, s = d - margin - n.c.
    std::vector<Eigen::Vector3d> dual;
    std::vector<double> offsets;
    for (const auto &p : planes) {
        const double s = p.d - margin - p.n.dot(centre);
        if (!(s > 1e-9 * size))
            throw InputError(what + ": thinner than twice the collision margin (" + num(margin) +
                             " m); use a smaller margin");
        dual.push_back(p.n / s);
        offsets.push_back(s);
    }
    const btConvexHullComputer polar = compute_hull(dual);
    std::vector<Eigen::Vector3d> vertices;
    for (const auto &loop : hull_faces(polar)) {
        // The primal vertex lies on every plane of this dual face: least squares.
        Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
        Eigen::Vector3d b = Eigen::Vector3d::Zero();
        for (int v : loop) {
            const int k = polar.original_vertex_index[v];
            if (k < 0)
                continue;
            A += planes[static_cast<std::size_t>(k)].n * planes[static_cast<std::size_t>(k)].n.transpose();
            b += planes[static_cast<std::size_t>(k)].n * offsets[static_cast<std::size_t>(k)];
        }
        const Eigen::Vector3d y = A.ldlt().solve(b);
        if (y.allFinite())
            vertices.push_back(centre + y);
    }
    if (vertices.size() < 4)
        throw InputError(what + ": shrinking by the collision margin (" + num(margin) + " m) left no volume");
    return vertices;
}

} // namespace armour
