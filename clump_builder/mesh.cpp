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

namespace {

// Sutherland-Hodgman: the part of a convex polygon where (x - point).n <= 0.
std::vector<Eigen::Vector3d> clip_polygon(const std::vector<Eigen::Vector3d> &polygon,
                                          const Eigen::Vector3d &point, const Eigen::Vector3d &n) {
    std::vector<Eigen::Vector3d> kept;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Eigen::Vector3d &p = polygon[i], &q = polygon[(i + 1) % polygon.size()];
        const double hp = (p - point).dot(n), hq = (q - point).dot(n);
        if (hp <= 0.0)
            kept.push_back(p);
        if ((hp < 0.0 && hq > 0.0) || (hp > 0.0 && hq < 0.0))
            kept.push_back(p + (hp / (hp - hq)) * (q - p));
    }
    return kept;
}

} // namespace

PartBelowPlane part_below_plane(const TriangleMesh &mesh, const Eigen::Vector3d &point,
                                const Eigen::Vector3d &up) {
    const Eigen::Vector3d n = up.normalized();
    double six_volume = 0.0;
    Eigen::Vector3d moment = Eigen::Vector3d::Zero(); // 24 x first moment about `point`
    for (const auto &t : mesh.triangles) {
        // Fanned from its first corner; tetrahedra (point, a, b, c).
        const std::vector<Eigen::Vector3d> kept =
            clip_polygon({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]}, point, n);
        for (std::size_t i = 2; i < kept.size(); ++i) {
            const Eigen::Vector3d a = kept[0] - point, b = kept[i - 1] - point, c = kept[i] - point;
            const double v6 = a.dot(b.cross(c));
            six_volume += v6;
            moment += v6 * (a + b + c);
        }
    }
    PartBelowPlane part;
    part.volume = six_volume / 6.0;
    part.centroid = point;
    if (part.volume > 0.0)
        part.centroid += moment / (4.0 * six_volume);
    return part;
}

TriangleMesh clipped_to_box(const TriangleMesh &mesh, const Eigen::Vector3d &lo, const Eigen::Vector3d &hi) {
    TriangleMesh out;
    const double scale = (hi - lo).norm();
    for (const auto &t : mesh.triangles) {
        std::vector<Eigen::Vector3d> kept = {mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
        for (int axis = 0; axis < 3 && !kept.empty(); ++axis) {
            const Eigen::Vector3d e = Eigen::Vector3d::Unit(axis);
            kept = clip_polygon(kept, lo, -e);
            if (!kept.empty())
                kept = clip_polygon(kept, hi, e);
        }
        for (std::size_t i = 2; i < kept.size(); ++i) {
            // Slivers where a corner only grazes a face carry no contact.
            if ((kept[i - 1] - kept[0]).cross(kept[i] - kept[0]).norm() < 1e-12 * scale * scale)
                continue;
            const int base = static_cast<int>(out.vertices.size());
            out.vertices.push_back(kept[0]);
            out.vertices.push_back(kept[i - 1]);
            out.vertices.push_back(kept[i]);
            out.triangles.push_back({base, base + 1, base + 2});
        }
    }
    return out;
}

} // namespace armour
