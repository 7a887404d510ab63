#include "collider.h"
#include "scene_setup.h"

#include "mesh.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace armour {

namespace {

// Deepest cut of a posed clump into any wall (m, <= 0 when clear) and the wall's index.
std::pair<double, int> wall_penetration(const BodyInit &b, const Clump &clump,
                                        const std::vector<Wall> &walls) {
    double deepest = -HUGE_VAL;
    int which = -1;
    for (std::size_t w = 0; w < walls.size(); ++w)
        for (const auto &sph : clump) {
            const Eigen::Vector3d c = b.pose.position + b.pose.orientation * sph.center;
            for (const auto &t : walls[w].surface.triangles) {
                const auto &v = walls[w].surface.vertices;
                const double depth =
                    sph.radius - (c - closest_point_on_triangle(c, v[t[0]], v[t[1]], v[t[2]])).norm();
                if (depth > deepest) {
                    deepest = depth;
                    which = static_cast<int>(w);
                }
            }
        }
    return {deepest, which};
}

// m: how deep p lies inside the convex part (<= 0: outside), the least of the planes' d - n.p.
double depth_in_part(const std::vector<HalfSpace> &part, const Eigen::Vector3d &p) {
    double depth = HUGE_VAL;
    for (const HalfSpace &h : part)
        depth = std::min(depth, h.d - h.n.dot(p));
    return depth;
}

// m: how deep the deepest point of segment p0-p1 (unit frame) lies inside
// the convex part (<= 0: outside). Each plane's depth is linear along the
// segment, so the deepest point is an end or where two planes' depths cross.
double deepest_on_segment(const std::vector<HalfSpace> &part, const Eigen::Vector3d &p0,
                          const Eigen::Vector3d &p1) {
    const auto depth_at = [&](double t) { return depth_in_part(part, p0 + t * (p1 - p0)); };
    double deepest = std::max(depth_at(0.0), depth_at(1.0));
    for (std::size_t i = 0; i < part.size(); ++i)
        for (std::size_t j = i + 1; j < part.size(); ++j) {
            const double a = part[i].d - part[i].n.dot(p0), b = part[j].d - part[j].n.dot(p0);
            const double slope = (part[j].n - part[i].n).dot(p1 - p0); // d(depth_i - depth_j)/dt
            if (slope == 0.0)
                continue;
            const double t = (a - b) / -slope;
            if (t > 0.0 && t < 1.0)
                deepest = std::max(deepest, depth_at(t));
        }
    return deepest;
}

// m: how deep wall w's deepest edge point lies inside a posed exact shape's
// parts. The shape's surface points alone miss a wall's convex edge (a toe
// step's) pushed into a face between them; its vertices are the edges' ends.
double wall_edges_inside(const BodyInit &b, const Collider &c, const Wall &w) {
    const Eigen::Matrix3d to_unit = b.pose.orientation.inverse().toRotationMatrix();
    const auto &v = w.surface.vertices;
    double deepest = -HUGE_VAL;
    for (const auto &t : w.surface.triangles)
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector3d p0 = to_unit * (v[t[k]] - b.pose.position),
                                  p1 = to_unit * (v[t[(k + 1) % 3]] - b.pose.position);
            // Farther from the centre than the shape reaches: cannot be inside.
            const Eigen::Vector3d along = p1 - p0;
            const double s =
                along.squaredNorm() > 0.0 ? std::clamp(-p0.dot(along) / along.squaredNorm(), 0.0, 1.0) : 0.0;
            if ((p0 + s * along).norm() > c.reach)
                continue;
            for (const auto &part : c.parts)
                deepest = std::max(deepest, deepest_on_segment(part, p0, p1));
        }
    return deepest;
}

// Deepest cut of a posed exact shape into any wall (m) and the wall's index:
// the shape's surface points behind the wall, or the wall's edges inside the shape.
std::pair<double, int> exact_wall_penetration(const BodyInit &b, const Collider &c,
                                              const std::vector<Wall> &walls) {
    double deepest = -HUGE_VAL;
    int which = -1;
    for (std::size_t w = 0; w < walls.size(); ++w) {
        const double front = wall_front(walls[w], b.pose.position);
        double depth = wall_edges_inside(b, c, walls[w]);
        for (const Eigen::Vector3d &local : c.points)
            depth = std::max(depth, depth_behind_wall(b.pose.position + b.pose.orientation * local, walls[w],
                                                      b.pose.position, front));
        if (depth > deepest) {
            deepest = depth;
            which = static_cast<int>(w);
        }
    }
    return {deepest, which};
}

// The wall's nearest point to p and the summed normals of the triangles tied
// for it (a pseudo-normal at an edge), each as turn(normal, its nearest point).
struct WallPoint {
    double distance = HUGE_VAL;
    Eigen::Vector3d point = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
};
template <class Turn> WallPoint nearest_on_wall(const Eigen::Vector3d &p, const Wall &w, Turn turn) {
    const auto &v = w.surface.vertices;
    WallPoint q;
    for (const auto &t : w.surface.triangles) {
        const Eigen::Vector3d on = closest_point_on_triangle(p, v[t[0]], v[t[1]], v[t[2]]);
        const double d = (p - on).norm();
        if (d > q.distance + 1e-12)
            continue;
        if (d < q.distance - 1e-12)
            q.normal.setZero(); // a nearer triangle: the earlier ties do not count
        q.distance = std::min(q.distance, d);
        q.point = on;
        q.normal += turn((v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]).normalized(), on);
    }
    return q;
}

} // namespace

double wall_front(const Wall &w, const Eigen::Vector3d &centre) {
    if (w.oriented)
        return 1.0;
    if (!w.wound)
        return 0.0;
    const WallPoint c =
        nearest_on_wall(centre, w, [](const Eigen::Vector3d &n, const Eigen::Vector3d &) { return n; });
    return (centre - c.point).dot(c.normal) < 0.0 ? -1.0 : 1.0;
}

double depth_behind_wall(const Eigen::Vector3d &p, const Wall &w, const Eigen::Vector3d &centre,
                         double front) {
    const WallPoint q = nearest_on_wall(p, w, [&](const Eigen::Vector3d &n, const Eigen::Vector3d &on) {
        if (front == 0.0)
            return Eigen::Vector3d((centre - on).dot(n) < 0.0 ? -n : n);
        return Eigen::Vector3d(front * n);
    });
    if (q.distance == HUGE_VAL)
        return -HUGE_VAL;
    // The distance, signed by the summed normals.
    return (p - q.point).dot(q.normal) < 0.0 ? q.distance : -q.distance;
}

double depth_behind_wall(const Eigen::Vector3d &p, const Wall &w, const Eigen::Vector3d &centre) {
    return depth_behind_wall(p, w, centre, wall_front(w, centre));
}

bool consistently_wound(const TriangleMesh &surface) {
    std::vector<std::pair<int, int>> runs; // each triangle's edges as run, from -> to
    runs.reserve(3 * surface.triangles.size());
    for (const auto &t : surface.triangles)
        for (int k = 0; k < 3; ++k)
            runs.emplace_back(t[k], t[(k + 1) % 3]);
    std::sort(runs.begin(), runs.end());
    // Two triangles running an edge the same way face opposite sides.
    return std::adjacent_find(runs.begin(), runs.end()) == runs.end();
}

double bounding_radius(const Clump &clump) {
    double r = 0.0;
    for (const auto &s : clump)
        r = std::max(r, s.center.norm() + s.radius);
    return r;
}

Collider make_collider(const UnitTemplate &unit, ShapeModel model, double Dn) {
    Collider c;
    c.spheres = model == ShapeModel::sphere_clumps;
    if (c.spheres) {
        c.reach = bounding_radius(unit.clump);
        return c;
    }
    const std::vector<TriangleMesh> parts =
        unit.convex_parts.empty() ? std::vector<TriangleMesh>{unit.mesh} : unit.convex_parts;
    const double spacing = 0.05 * Dn;
    for (const TriangleMesh &part : parts) {
        std::vector<HalfSpace> planes;
        for (const auto &t : part.triangles) {
            const Eigen::Vector3d &a = part.vertices[t[0]], &b = part.vertices[t[1]],
                                  &d = part.vertices[t[2]];
            const Eigen::Vector3d n = (b - a).cross(d - a);
            if (n.norm() <= 0.0)
                continue;
            planes.push_back({n.normalized(), n.normalized().dot(a)});
            const double longest = std::max({(b - a).norm(), (d - b).norm(), (a - d).norm()});
            const int k = std::max(1, static_cast<int>(std::ceil(longest / spacing)));
            for (int i = 0; i <= k; ++i)
                for (int j = 0; i + j <= k; ++j)
                    c.points.push_back(a + (b - a) * (double(i) / k) + (d - a) * (double(j) / k));
        }
        c.parts.push_back(std::move(planes));
        c.corners.insert(c.corners.end(), part.vertices.begin(), part.vertices.end());
    }
    for (const Eigen::Vector3d &v : c.corners)
        c.reach = std::max(c.reach, v.norm());
    return c;
}

std::optional<double> growth_to_hold_clump(const UnitTemplate &unit) {
    const Collider exact = make_collider(unit, ShapeModel::convex_hulls, 1.0);
    double growth = 1.0;
    for (const auto &sph : unit.clump) {
        // The least growth of any part that holds this sphere once grown: a
        // part grows about the unit's centre only if the centre lies inside
        // it (every plane in front of the centre), else growth moves it away.
        double least = HUGE_VAL;
        for (const auto &planes : exact.parts) {
            double need = 1.0;
            for (const HalfSpace &h : planes)
                need = h.d > 0.0 ? std::max(need, (h.n.dot(sph.center) + sph.radius) / h.d) : HUGE_VAL;
            least = std::min(least, need);
        }
        if (!std::isfinite(least))
            return std::nullopt;
        growth = std::max(growth, least);
    }
    return growth;
}

double depth_outside_clump(const Clump &clump, const std::vector<Eigen::Vector3d> &points) {
    double deepest = 0.0;
    for (const Eigen::Vector3d &p : points) {
        double outside = HUGE_VAL; // m beyond the nearest sphere's surface
        for (const auto &sph : clump)
            outside = std::min(outside, (p - sph.center).norm() - sph.radius);
        deepest = std::max(deepest, outside);
    }
    return clump.empty() ? 0.0 : deepest;
}

double depth_inside(const Collider &c, const Eigen::Vector3d &p) {
    double deepest = -HUGE_VAL;
    for (const auto &part : c.parts)
        deepest = std::max(deepest, depth_in_part(part, p));
    return deepest;
}

std::pair<double, int> body_wall_penetration(const BodyInit &b, const UnitTemplate &unit, const Collider &c,
                                             const std::vector<Wall> &walls) {
    return c.spheres ? wall_penetration(b, unit.clump, walls) : exact_wall_penetration(b, c, walls);
}

bool none_deeper_than(const BodyInit &from, const Collider &cf, const BodyInit &to, const Collider &ct,
                      double depth) {
    // from's unit frame into to's: p_to = turn p_from + shift
    const Eigen::Matrix3d turn = (to.pose.orientation.inverse() * from.pose.orientation).toRotationMatrix();
    const Eigen::Vector3d shift = to.pose.orientation.inverse() * (from.pose.position - to.pose.position);
    const auto beyond = [&](const HalfSpace &h) { // every corner of `from` at most `depth` inside h
        return std::all_of(cf.corners.begin(), cf.corners.end(), [&](const Eigen::Vector3d &v) {
            return h.d - h.n.dot(turn * v + shift) <= depth;
        });
    };
    if (std::all_of(ct.parts.begin(), ct.parts.end(),
                    [&](const auto &part) { return std::any_of(part.begin(), part.end(), beyond); }))
        return true;
    return std::none_of(cf.points.begin(), cf.points.end(),
                        [&](const Eigen::Vector3d &q) { return depth_inside(ct, turn * q + shift) > depth; });
}

bool closer_than(const BodyInit &a, const UnitTemplate &unit_a, const Collider &ca, const BodyInit &b,
                 const UnitTemplate &unit_b, const Collider &cb, double clearance) {
    if (ca.spheres) {
        for (const auto &sa : unit_a.clump) {
            const Eigen::Vector3d centre_a = a.pose.position + a.pose.orientation * sa.center;
            // No sphere of b can come that close (1 nm spare keeps the answer the pairs' own).
            if ((centre_a - b.pose.position).norm() >= sa.radius + cb.reach + clearance + 1e-9)
                continue;
            for (const auto &sb : unit_b.clump)
                if ((centre_a - b.pose.position - b.pose.orientation * sb.center).norm() <
                    sa.radius + sb.radius + clearance)
                    return true;
        }
        return false;
    }
    return !none_deeper_than(a, ca, b, cb, -clearance) || !none_deeper_than(b, cb, a, ca, -clearance);
}

bool closer_than(const BodyInit &a, const BodyInit &b, const UnitTemplate &unit, const Collider &c,
                 double clearance) {
    return closer_than(a, unit, c, b, unit, c, clearance);
}

} // namespace armour
