#include "mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

namespace armour {

double signed_volume(const TriangleMesh &mesh) {
    double six_volume = 0.0;
    for (const auto &t : mesh.triangles) {
        const auto &a = mesh.vertices[t[0]];
        const auto &b = mesh.vertices[t[1]];
        const auto &c = mesh.vertices[t[2]];
        six_volume += a.dot(b.cross(c));
    }
    return six_volume / 6.0;
}

double surface_area(const TriangleMesh &mesh) {
    double area = 0.0;
    for (const auto &t : mesh.triangles) {
        const auto &a = mesh.vertices[t[0]];
        area += 0.5 * (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm();
    }
    return area;
}

std::vector<Eigen::Vector3d> sample_surface(const TriangleMesh &mesh, int count, std::uint64_t seed,
                                            std::vector<Eigen::Vector3d> *normals) {
    std::vector<double> cumulative_area;
    cumulative_area.reserve(mesh.triangles.size());
    double total = 0.0;
    for (const auto &t : mesh.triangles) {
        const auto &a = mesh.vertices[t[0]];
        total += 0.5 * (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm();
        cumulative_area.push_back(total);
    }
    std::vector<Eigen::Vector3d> points;
    if (count <= 0 || total <= 0.0)
        return points;
    points.reserve(count);
    if (normals) {
        normals->clear();
        normals->reserve(count);
    }
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int i = 0; i < count; ++i) {
        const double pick = uniform(rng) * total;
        auto it = std::upper_bound(cumulative_area.begin(), cumulative_area.end(), pick);
        const std::size_t k = std::min<std::size_t>(it - cumulative_area.begin(), mesh.triangles.size() - 1);
        const auto &t = mesh.triangles[k];
        const auto &a = mesh.vertices[t[0]];
        const auto &b = mesh.vertices[t[1]];
        const auto &c = mesh.vertices[t[2]];
        double u = uniform(rng);
        double v = uniform(rng);
        if (u + v > 1.0) { // reflect into the triangle: keeps the density uniform
            u = 1.0 - u;
            v = 1.0 - v;
        }
        points.push_back(a + u * (b - a) + v * (c - a));
        if (normals)
            normals->push_back((b - a).cross(c - a).normalized());
    }
    return points;
}

// Ericson's Voronoi-region walk: vertex, edge or face region, in that order.
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d &p, const Eigen::Vector3d &a,
                                          const Eigen::Vector3d &b, const Eigen::Vector3d &c) {
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0)
        return a;
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3)
        return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
        return a + d1 / (d1 - d3) * ab;
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6)
        return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
        return a + d2 / (d2 - d6) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
    const double denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

TriangleMesh translated(const TriangleMesh &mesh, const Eigen::Vector3d &offset) {
    TriangleMesh moved = mesh;
    for (auto &v : moved.vertices)
        v += offset;
    return moved;
}

std::optional<Eigen::Vector3d> axis_aligned_box_half_extents(const TriangleMesh &mesh) {
    if (mesh.vertices.empty() || mesh.triangles.empty())
        return std::nullopt;
    Eigen::Vector3d half = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d &v : mesh.vertices)
        half = half.cwiseMax(v.cwiseAbs());
    const double tolerance = 1e-9 * half.maxCoeff();
    if (!(half.minCoeff() > tolerance))
        return std::nullopt;
    // Every vertex at a corner, and the full box's volume enclosed: a closed
    // surface spanned by the corners alone that encloses all of the box IS
    // the box (any missing piece would cut the volume).
    for (const Eigen::Vector3d &v : mesh.vertices)
        if (((v.cwiseAbs() - half).cwiseAbs().array() > tolerance).any())
            return std::nullopt;
    const double box_volume = 8.0 * half.prod();
    if (std::abs(signed_volume(mesh) - box_volume) > 1e-9 * box_volume)
        return std::nullopt;
    return half;
}

double box_signed_distance(const Eigen::Vector3d &p, const Eigen::Vector3d &half) {
    const Eigen::Vector3d q = p.cwiseAbs() - half;
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

PartBelowPlane part_below_plane(const TriangleMesh &mesh, const Eigen::Vector3d &point,
                                const Eigen::Vector3d &up) {
    const Eigen::Vector3d n = up.normalized();
    double six_volume = 0.0;
    Eigen::Vector3d moment = Eigen::Vector3d::Zero(); // 24 x first moment about `point`
    auto add = [&](const Eigen::Vector3d &a, const Eigen::Vector3d &b, const Eigen::Vector3d &c) {
        const double v6 = a.dot(b.cross(c)); // tetrahedron (point, a, b, c), relative to point
        six_volume += v6;
        moment += v6 * (a + b + c);
    };
    for (const auto &t : mesh.triangles) {
        // Sutherland-Hodgman against the half-space h <= 0: a triangle gives
        // a polygon of at most 4 corners, fanned into triangles.
        std::array<Eigen::Vector3d, 4> kept;
        int count = 0;
        for (int i = 0; i < 3; ++i) {
            const Eigen::Vector3d p = mesh.vertices[t[i]] - point;
            const Eigen::Vector3d q = mesh.vertices[t[(i + 1) % 3]] - point;
            const double hp = p.dot(n), hq = q.dot(n);
            if (hp <= 0.0)
                kept[count++] = p;
            if ((hp < 0.0 && hq > 0.0) || (hp > 0.0 && hq < 0.0))
                kept[count++] = p + (hp / (hp - hq)) * (q - p);
        }
        for (int i = 2; i < count; ++i)
            add(kept[0], kept[i - 1], kept[i]);
    }
    PartBelowPlane part;
    part.volume = six_volume / 6.0;
    part.centroid = point;
    if (part.volume > 0.0)
        part.centroid += moment / (4.0 * six_volume);
    return part;
}

} // namespace armour
