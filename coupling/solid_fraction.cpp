// Solid fractions by clipping convex cells: see solid_fraction.h.
#include "solid_fraction.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace armour {

ConvexPolyhedron ConvexPolyhedron::box(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi) {
    ConvexPolyhedron p;
    for (int c = 0; c < 8; ++c)
        p.add_point(
            Eigen::Vector3d(c & 1 ? hi.x() : lo.x(), c & 2 ? hi.y() : lo.y(), c & 4 ? hi.z() : lo.z()));
    for (const auto &loop : kBoxLoops)
        p.add_face(loop, 4);
    return p;
}

void ConvexPolyhedron::add_face(const int *loop, int count) {
    for (int i = 0; i < count; ++i)
        edges.push_back({loop[i], loop[(i + 1) % count], faces});
    ++faces;
}

void ConvexPolyhedron::clip(const HalfSpace &h, ConvexPolyhedron &out, std::vector<double> &side,
                            std::vector<int> &scratch) const {
    out.clear();
    const int n = static_cast<int>(points.size());
    side.resize(n);
    bool any_out = false, all_out = true;
    for (int i = 0; i < n; ++i) {
        side[i] = h.normal.dot(points[i]) - h.offset;
        any_out = any_out || side[i] > 0.0;
        all_out = all_out && side[i] > 0.0;
    }
    if (!any_out) {
        out = *this;
        return;
    }
    if (all_out)
        return;
    // scratch: [0, n) the kept points' new indices; then per face its exit
    // and entry points.
    scratch.assign(static_cast<std::size_t>(n + 2 * faces), -1);
    for (int i = 0; i < n; ++i)
        if (side[i] <= 0.0)
            scratch[i] = out.add_point(points[i]);
    // The crossing of edge ab, computed from its lower index so that both
    // faces sharing the edge get the same point (as two indices: faces need
    // no shared indices, only consistent orientation).
    const auto crossing = [&](int a, int b) {
        const int lo = std::min(a, b), hi = std::max(a, b);
        const double t = side[lo] / (side[lo] - side[hi]);
        return out.add_point(points[lo] + t * (points[hi] - points[lo]));
    };
    for (const Edge &e : edges) {
        const bool in_from = side[e.from] <= 0.0, in_to = side[e.to] <= 0.0;
        if (in_from && in_to) {
            out.edges.push_back({scratch[e.from], scratch[e.to], e.face});
        } else if (in_from) {
            const int x = crossing(e.from, e.to);
            out.edges.push_back({scratch[e.from], x, e.face});
            scratch[n + 2 * e.face] = x; // leaves the kept side here
        } else if (in_to) {
            const int x = crossing(e.from, e.to);
            out.edges.push_back({x, scratch[e.to], e.face});
            scratch[n + 2 * e.face + 1] = x; // comes back here
        }
    }
    if (out.edges.empty()) {
        out.clear();
        return;
    }
    // Each cut face is closed from where it left to where it came back; the
    // cap (a new face) gets that edge the other way round.
    for (int f = 0; f < faces; ++f) {
        const int exit = scratch[n + 2 * f], entry = scratch[n + 2 * f + 1];
        if (exit >= 0 && entry >= 0 && exit != entry) {
            out.edges.push_back({exit, entry, f});
            out.edges.push_back({entry, exit, faces});
        }
    }
    out.faces = faces + 1;
}

SolidPart ConvexPolyhedron::volume_and_centroid() const {
    SolidPart part;
    if (edges.empty())
        return part;
    // Tetrahedra from a vertex p0 over each face's fan from its first point:
    // (p0, x_f, a, b) for every edge ab of face f, all positive for a convex
    // polyhedron with outward faces, whatever order the edges come in.
    // Each face's first point; on the stack for the usual few faces.
    std::array<int, 32> few;
    std::vector<int> many;
    int *first = few.data();
    if (faces > static_cast<int>(few.size())) {
        many.resize(static_cast<std::size_t>(faces));
        first = many.data();
    }
    std::fill(first, first + faces, -1);
    const Eigen::Vector3d p0 = points[edges.front().from];
    double six_volume = 0.0;
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    for (const Edge &e : edges) {
        if (first[e.face] < 0)
            first[e.face] = e.from;
        const Eigen::Vector3d x = points[first[e.face]] - p0, a = points[e.from] - p0, b = points[e.to] - p0;
        const double v6 = x.dot(a.cross(b));
        six_volume += v6;
        moment += v6 * (x + a + b);
    }
    part.volume = six_volume / 6.0;
    part.centroid = six_volume > 0.0 ? Eigen::Vector3d(p0 + moment / (4.0 * six_volume)) : p0;
    return part;
}

void ConvexPolyhedron::planes(std::vector<HalfSpace> &out) const {
    std::vector<Eigen::Vector3d> normal(static_cast<std::size_t>(faces), Eigen::Vector3d::Zero());
    std::vector<int> point(static_cast<std::size_t>(faces), -1);
    for (const Edge &e : edges) {
        normal[e.face] += points[e.from].cross(points[e.to]);
        point[e.face] = e.from;
    }
    out.clear();
    for (int f = 0; f < faces; ++f) {
        const double length = normal[f].norm();
        if (point[f] >= 0 && length > 0.0)
            out.push_back({normal[f] / length, normal[f].dot(points[point[f]]) / length});
    }
}

SolidShape SolidShape::from_mesh(const TriangleMesh &mesh) {
    SolidShape shape;
    double size = 0.0;
    for (const Eigen::Vector3d &v : mesh.vertices)
        size = std::max(size, v.norm());
    const double tolerance = 1e-9 * size;
    std::vector<HalfSpace> planes;
    bool convex = true;
    for (const auto &t : mesh.triangles) {
        const Eigen::Vector3d &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
        const Eigen::Vector3d n = (b - a).cross(c - a);
        if (!(n.norm() > 0.0))
            continue;
        const HalfSpace h{n.normalized(), n.normalized().dot(a)};
        for (const Eigen::Vector3d &v : mesh.vertices)
            if (h.normal.dot(v) - h.offset > tolerance) {
                convex = false;
                break;
            }
        if (!convex)
            break;
        // Coplanar triangles (a cube's face is two) give one plane.
        const bool known = std::any_of(planes.begin(), planes.end(), [&](const HalfSpace &p) {
            return p.normal.dot(h.normal) > 1.0 - 1e-12 && std::abs(p.offset - h.offset) <= tolerance;
        });
        if (!known)
            planes.push_back(h);
    }
    if (convex) {
        shape.planes_ = std::move(planes);
        return shape;
    }
    // Cones from the origin to every triangle (see the header).
    for (const auto &t : mesh.triangles) {
        const Eigen::Vector3d o = Eigen::Vector3d::Zero();
        const Eigen::Vector3d v[4] = {o, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
        const double det = v[1].dot(v[2].cross(v[3]));
        if (!(std::abs(det) > 1e-14 * size * size * size))
            continue; // flat cone: no volume
        Cone cone;
        cone.sign = det > 0.0 ? 1.0 : -1.0;
        cone.lo = v[0].cwiseMin(v[1]).cwiseMin(v[2]).cwiseMin(v[3]);
        cone.hi = v[0].cwiseMax(v[1]).cwiseMax(v[2]).cwiseMax(v[3]);
        for (int k = 0; k < 4; ++k) {
            // The face opposite vertex k, its normal away from v[k].
            const Eigen::Vector3d &p = v[(k + 1) % 4], &q = v[(k + 2) % 4], &r = v[(k + 3) % 4];
            Eigen::Vector3d n = (q - p).cross(r - p).normalized();
            if (n.dot(v[k] - p) > 0.0)
                n = -n;
            cone.faces[k] = {n, n.dot(p)};
        }
        shape.cones_.push_back(cone);
    }
    return shape;
}

double SolidShape::plane_distance(const Eigen::Vector3d &x) const {
    double d = -HUGE_VAL;
    for (const HalfSpace &h : planes_)
        d = std::max(d, h.normal.dot(x) - h.offset);
    return d;
}

SolidShape SolidShape::from_spheres(const Clump &spheres, double line_spacing) {
    SolidShape shape;
    shape.spheres_ = spheres;
    shape.line_spacing_ = line_spacing;
    return shape;
}

const ConvexPolyhedron &SolidShape::clip_all(const ConvexPolyhedron &cell, const HalfSpace *h, int count,
                                             FractionScratch &scratch) {
    const ConvexPolyhedron *current = &cell;
    ConvexPolyhedron *next = &scratch.a, *spare = &scratch.b;
    for (int k = 0; k < count; ++k) {
        bool any_out = false;
        for (const Eigen::Vector3d &x : current->points)
            if (h[k].normal.dot(x) > h[k].offset) {
                any_out = true;
                break;
            }
        if (!any_out)
            continue;
        current->clip(h[k], *next, scratch.side, scratch.indices);
        current = next;
        std::swap(next, spare);
        if (current->empty())
            return *current;
    }
    return *current;
}

SolidPart SolidShape::part_inside(const ConvexPolyhedron &cell, FractionScratch &scratch) const {
    if (!spheres_.empty())
        return spheres_inside(cell, scratch);
    if (!planes_.empty()) {
        const ConvexPolyhedron &inside =
            clip_all(cell, planes_.data(), static_cast<int>(planes_.size()), scratch);
        return inside.volume_and_centroid();
    }
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
    for (const Eigen::Vector3d &x : cell.points) {
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
    }
    double volume = 0.0;
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    for (const Cone &cone : cones_) {
        if ((cone.lo.array() > hi.array()).any() || (cone.hi.array() < lo.array()).any())
            continue;
        const SolidPart part = clip_all(cell, cone.faces, 4, scratch).volume_and_centroid();
        volume += cone.sign * part.volume;
        moment += cone.sign * part.volume * part.centroid;
    }
    SolidPart part;
    part.volume = std::max(0.0, volume);
    part.centroid = volume > 0.0 ? Eigen::Vector3d(moment / volume) : Eigen::Vector3d(0.5 * (lo + hi));
    return part;
}

// Exact chords of the union along lines parallel to z through the cell. The
// fraction is the lines' measure of (cell ∩ union) over their measure of the
// cell, so a cell wholly inside is exactly 1 whatever the cell's orientation
// to the lines; the part's volume is that fraction of the cell's exact volume.
SolidPart SolidShape::spheres_inside(const ConvexPolyhedron &cell, FractionScratch &scratch) const {
    cell.planes(scratch.planes);
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
    for (const Eigen::Vector3d &x : cell.points) {
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
    }
    const int nx = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / line_spacing_)));
    const int ny = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / line_spacing_)));
    const double dx = (hi.x() - lo.x()) / nx, dy = (hi.y() - lo.y()) / ny;
    double cell_length = 0.0, solid_length = 0.0;
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j) {
            const double x = lo.x() + (i + 0.5) * dx, y = lo.y() + (j + 0.5) * dy;
            double z0 = -HUGE_VAL, z1 = HUGE_VAL;
            for (const HalfSpace &h : scratch.planes) {
                const double a = h.normal.z(), b = h.offset - h.normal.x() * x - h.normal.y() * y;
                if (std::abs(a) < 1e-12) {
                    if (b < 0.0)
                        z1 = z0;
                } else if (a > 0.0) {
                    z1 = std::min(z1, b / a);
                } else {
                    z0 = std::max(z0, b / a);
                }
            }
            if (!(z1 > z0))
                continue;
            cell_length += z1 - z0;
            scratch.chords.clear();
            for (const Sphere &s : spheres_) {
                const double rho2 =
                    (x - s.center.x()) * (x - s.center.x()) + (y - s.center.y()) * (y - s.center.y());
                if (rho2 >= s.radius * s.radius)
                    continue;
                const double half = std::sqrt(s.radius * s.radius - rho2);
                const double a = std::max(z0, s.center.z() - half), b = std::min(z1, s.center.z() + half);
                if (b > a)
                    scratch.chords.emplace_back(a, b);
            }
            std::sort(scratch.chords.begin(), scratch.chords.end());
            double end = -HUGE_VAL;
            for (auto [a, b] : scratch.chords) {
                a = std::max(a, end);
                if (b <= a)
                    continue;
                solid_length += b - a;
                moment += Eigen::Vector3d(x * (b - a), y * (b - a), 0.5 * (b * b - a * a));
                end = b;
            }
        }
    SolidPart part;
    if (!(cell_length > 0.0) || !(solid_length > 0.0))
        return part;
    part.volume = solid_length / cell_length * cell.volume_and_centroid().volume;
    part.centroid = moment / solid_length;
    return part;
}

} // namespace armour
