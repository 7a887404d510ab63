#include "slope_profile.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace armour {

Eigen::Vector3d SlopeFrame::local(const Eigen::Vector3d &world) const {
    const Eigen::Vector3d d = world - origin;
    return {d.dot(along), d.dot(across), d.dot(normal)};
}

bool SlopeFrame::seaward_of_foot(const Eigen::Vector3d &world) const {
    const Eigen::Vector3d landward(along.x(), along.y(), 0.0);
    return (world - origin).dot(landward) < 0.0;
}

bool SlopeFrame::rests_on_layer(const Eigen::Vector3d &world, double thickness) const {
    return !seaward_of_foot(world) && local(world).z() > thickness;
}

std::optional<SlopeFrame> slope_frame(const Scene &scene) {
    for (const SceneWall &w : scene.walls) {
        if (w.type != "slope")
            continue;
        const double alpha = std::atan2(1.0, w.cot);
        SlopeFrame f;
        f.origin = Eigen::Vector3d(w.toe_x, 0.0, w.floor_z);
        f.along = Eigen::Vector3d(std::cos(alpha), 0.0, std::sin(alpha));
        f.across = Eigen::Vector3d::UnitY();
        f.normal = Eigen::Vector3d(-std::sin(alpha), 0.0, std::cos(alpha));
        f.length = w.height / std::sin(alpha);
        f.width = w.width;
        f.cot = w.cot;
        return f;
    }
    return std::nullopt;
}

LayerRegion layer_region(const SlopeFrame &frame, const SceneSetup &setup,
                         const std::vector<BodyState> &states) {
    LayerRegion r;
    double s_min = HUGE_VAL, s_max = -HUGE_VAL, y_min = HUGE_VAL, y_max = -HUGE_VAL;
    for (std::size_t i = 0; i < states.size(); ++i) {
        const double Dn = setup.unit_Dn[static_cast<std::size_t>(setup.bodies[i].unit)];
        const Eigen::Vector3d c = frame.local(states[i].pose.position);
        if (c.x() < -Dn || c.x() > frame.length + Dn || c.z() < -Dn)
            continue; // not on the face (fell off seaward, or over the crest)
        r.bodies.push_back(static_cast<int>(i));
        r.Dn = std::max(r.Dn, Dn);
        s_min = std::min(s_min, c.x());
        s_max = std::max(s_max, c.x());
        y_min = std::min(y_min, c.y());
        y_max = std::max(y_max, c.y());
    }
    if (r.bodies.empty())
        return r;
    r.s_lo = std::max(0.0, s_min - 0.5 * r.Dn);
    r.s_hi = std::min(frame.length, s_max + 0.5 * r.Dn);
    r.y_lo = std::max(-0.5 * frame.width, y_min - 0.5 * r.Dn);
    r.y_hi = std::min(0.5 * frame.width, y_max + 0.5 * r.Dn);
    return r;
}

double ArmourProfile::mean() const {
    double sum = 0.0;
    for (const double e : elevation)
        sum += e;
    return elevation.empty() ? 0.0 : sum / static_cast<double>(elevation.size());
}

double ball_contact_height(double s, double y, double r, const Eigen::Vector3d &a, const Eigen::Vector3d &b,
                           const Eigen::Vector3d &c) {
    // The centre's path meets the triangle grown by r (faces shifted by r,
    // edges grown into cylinders, vertices into spheres) highest on one of them.
    double best = -HUGE_VAL;
    const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
    for (const Eigen::Vector3d *v : {&a, &b, &c}) {
        const double d2 = (v->x() - s) * (v->x() - s) + (v->y() - y) * (v->y() - y);
        if (d2 <= r * r)
            best = std::max(best, v->z() + std::sqrt(r * r - d2));
    }
    const Eigen::Vector3d *ends[3][2] = {{&a, &b}, {&b, &c}, {&c, &a}};
    for (const auto &e : ends) {
        const Eigen::Vector3d edge = *e[1] - *e[0];
        const double length = edge.norm();
        if (length <= 0.0)
            continue;
        const Eigen::Vector3d u = edge / length;
        const Eigen::Vector3d w0 = Eigen::Vector3d(s, y, 0.0) - *e[0];
        const Eigen::Vector3d P = w0 - w0.dot(u) * u, Q = up - u.z() * u;
        const double qq = Q.squaredNorm(), pq = P.dot(Q), disc = pq * pq - qq * (P.squaredNorm() - r * r);
        if (qq < 1e-12 || disc < 0.0)
            continue; // an edge along the normal: its end spheres decide
        const double h = (-pq + std::sqrt(disc)) / qq;
        const double along = (w0 + h * up).dot(u);
        if (along >= 0.0 && along <= length)
            best = std::max(best, h);
    }
    Eigen::Vector3d m = (b - a).cross(c - a);
    if (m.norm() > 0.0) {
        m.normalize();
        if (m.z() < 0.0)
            m = -m; // the ball comes from above
        if (m.z() > 1e-9) {
            const double h = a.z() + (r - (s - a.x()) * m.x() - (y - a.y()) * m.y()) / m.z();
            const Eigen::Vector3d foot = Eigen::Vector3d(s, y, h) - r * m;
            // Inside the triangle: on the inner side of all three edges.
            const Eigen::Vector3d n = (b - a).cross(c - a);
            if ((b - a).cross(foot - a).dot(n) >= 0.0 && (c - b).cross(foot - b).dot(n) >= 0.0 &&
                (a - c).cross(foot - c).dot(n) >= 0.0)
                best = std::max(best, h);
        }
    }
    return best;
}

ArmourProfile armour_profile(const SlopeFrame &frame, const SceneSetup &setup,
                             const std::vector<BodyState> &states, const LayerRegion &region) {
    ArmourProfile p;
    p.s_lo = region.s_lo;
    p.y_lo = region.y_lo;
    if (region.bodies.empty() || region.area() <= 0.0)
        return p;
    const double r = 0.25 * region.Dn, spacing = 0.1 * region.Dn;
    p.ns = std::max(1, static_cast<int>(std::ceil((region.s_hi - region.s_lo) / spacing)));
    p.ny = std::max(1, static_cast<int>(std::ceil((region.y_hi - region.y_lo) / spacing)));
    p.ds = (region.s_hi - region.s_lo) / p.ns;
    p.dy = (region.y_hi - region.y_lo) / p.ny;
    p.elevation.assign(static_cast<std::size_t>(p.ns * p.ny), 0.0);

    struct Posed {
        std::vector<Eigen::Vector3d> v; // slope coordinates
        const TriangleMesh *mesh;
        Eigen::Vector3d centre;
        double reach; // m, from the centre in (s, y), ball included
    };
    std::vector<Posed> bodies;
    for (std::size_t i = 0; i < states.size(); ++i) {
        const UnitTemplate &unit = setup.units[static_cast<std::size_t>(setup.bodies[i].unit)];
        Posed b{{}, &unit.mesh, frame.local(states[i].pose.position), 0.0};
        for (const Eigen::Vector3d &v : unit.mesh.vertices) {
            b.v.push_back(frame.local(states[i].pose.position + states[i].pose.orientation * v));
            b.reach = std::max(b.reach, v.norm());
        }
        b.reach += r;
        bodies.push_back(std::move(b));
    }
    for (int i = 0; i < p.ns; ++i)
        for (int j = 0; j < p.ny; ++j) {
            const double s = p.s_lo + (i + 0.5) * p.ds, y = p.y_lo + (j + 0.5) * p.dy;
            double top = r; // the ball on the underlayer
            for (const Posed &b : bodies) {
                const double ds = s - b.centre.x(), dy = y - b.centre.y();
                if (ds * ds + dy * dy > b.reach * b.reach)
                    continue;
                for (const auto &t : b.mesh->triangles) {
                    const Eigen::Vector3d &va = b.v[static_cast<std::size_t>(t[0])],
                                          &vb = b.v[static_cast<std::size_t>(t[1])],
                                          &vc = b.v[static_cast<std::size_t>(t[2])];
                    if (std::max({va.z(), vb.z(), vc.z()}) + r <= top)
                        continue;
                    top = std::max(top, ball_contact_height(s, y, r, va, vb, vc));
                }
            }
            p.elevation[static_cast<std::size_t>(i * p.ny + j)] = top - r;
        }
    return p;
}

LayerFigures layer_figures(const SceneSetup &setup, const LayerRegion &region, const ArmourProfile &profile,
                           int layers) {
    LayerFigures f;
    f.units = static_cast<int>(region.bodies.size());
    if (region.bodies.empty())
        return f;
    double volume = 0.0, dn2 = 0.0, dn = 0.0;
    for (const int b : region.bodies) {
        const auto unit = static_cast<std::size_t>(setup.bodies[static_cast<std::size_t>(b)].unit);
        volume += setup.units[unit].props.volume;
        dn2 += setup.unit_Dn[unit] * setup.unit_Dn[unit];
        dn += setup.unit_Dn[unit];
    }
    f.area = region.area();
    f.thickness = profile.mean();
    f.packing_density = dn2 / f.area;
    f.porosity = 1.0 - volume / (f.area * f.thickness);
    f.layer_coefficient = f.thickness / (layers * dn / f.units);
    return f;
}

double eroded_area(const ArmourProfile &before, const ArmourProfile &after) {
    if (before.ny == 0)
        return 0.0;
    double sum = 0.0;
    for (int i = 0; i < before.ns; ++i) {
        double lowered = 0.0; // summed across y
        for (int j = 0; j < before.ny; ++j)
            lowered += before.at(i, j) - after.at(i, j);
        sum += std::max(0.0, lowered / before.ny) * before.ds;
    }
    return sum;
}

SettleWatch::SettleWatch(const Scene &scene, const SceneSetup &setup)
    : setup_(setup), speed_limit_(scene.settle_speed), energy_limit_(scene.settle_energy),
      span_(scene.settle_span) {
    for (const BodyInit &b : setup.bodies) {
        const auto unit = static_cast<std::size_t>(b.unit);
        scale_ += setup.units[unit].props.mass * scene.gravity.norm() * setup.unit_Dn[unit];
    }
}

void SettleWatch::sample(double t, const std::vector<BodyState> &states) {
    double speed = 0.0, energy = 0.0;
    for (std::size_t i = 0; i < states.size(); ++i) {
        const MassProperties &p = setup_.units[static_cast<std::size_t>(setup_.bodies[i].unit)].props;
        const Eigen::Matrix3d R = states[i].pose.orientation.toRotationMatrix();
        const Eigen::Vector3d &w = states[i].angular_velocity;
        speed = std::max(speed, states[i].velocity.norm());
        energy +=
            0.5 * p.mass * states[i].velocity.squaredNorm() + 0.5 * w.dot(R * p.inertia * R.transpose() * w);
    }
    speed_ = speed;
    energy_ = scale_ > 0.0 ? energy / scale_ : 0.0;
    if (settled_at_)
        return;
    if (speed_ >= speed_limit_ || energy_ >= energy_limit_) {
        quiet_since_.reset();
        return;
    }
    if (!quiet_since_)
        quiet_since_ = t;
    if (t - *quiet_since_ >= span_ - 1e-12)
        settled_at_ = t;
}

} // namespace armour
