// What the engine tests share: a test cube every engine can take, a floor,
// a material, and the tilt-and-hold experiment (slide and topple angles).
#pragma once

#include "rigid_body_engine.h"
#include "shapes.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace armour::test {

constexpr double kPi = 3.14159265358979323846;
inline double deg(double radians) {
    return radians * 180.0 / kPi;
}
inline double rad(double degrees) {
    return degrees * kPi / 180.0;
}

// A cube of edge a as every engine may see it: exact mesh and mass
// properties, the mesh as its one convex part (exact-shape engines), and 8
// corner spheres of radius corner x a touching the faces (DEM): the clump's
// support on a plane is the square of half-width a/2 - r.
inline UnitTemplate test_cube(double a, double density, double corner) {
    const Shape shape = make_cube_shape(a, 0.0, density);
    UnitTemplate unit;
    unit.name = "cube";
    unit.mesh = shape.mesh;
    unit.props = shape.props;
    unit.convex_parts = {shape.mesh};
    const double r = corner * a, c = 0.5 * a - r;
    for (int i = 0; i < 8; ++i)
        unit.clump.push_back({Eigen::Vector3d(i & 1 ? c : -c, i & 2 ? c : -c, i & 4 ? c : -c), r});
    return unit;
}

inline Wall floor_plane(double half, int material = 0) {
    Wall w;
    w.name = "floor";
    w.surface.vertices = {{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}};
    w.surface.triangles = {{0, 1, 2}, {0, 2, 3}};
    w.material = material;
    return w;
}

inline Material concrete(double restitution, double friction, double youngs = 5e9,
                         const std::string &name = "concrete") {
    Material m;
    m.name = name;
    m.youngs_modulus = youngs;
    m.poisson_ratio = 0.25;
    m.restitution = restitution;
    m.friction = friction;
    return m;
}

// Body 0 of `engine` rests on a floor under vertical gravity for 0.3 s; then
// gravity turns about +y to `angle_deg` over 0.2 s (a slowly inclined floor:
// a sudden tilt would overshoot tangential springs) and is held `seconds`.
// Returns the slide along x and the rotation (deg) over the hold.
inline std::pair<double, double> tilt_and_hold(RigidBodyEngine &engine, double angle_deg, double seconds) {
    constexpr double g = 9.81;
    engine.advance(0.3);
    for (int k = 1; k <= 20; ++k) {
        const double t = rad(angle_deg) * k / 20.0;
        engine.set_gravity(Eigen::Vector3d(g * std::sin(t), 0.0, -g * std::cos(t)));
        engine.advance(0.01);
    }
    const BodyState rest = engine.state(0);
    engine.advance(seconds);
    const BodyState end = engine.state(0);
    const double turned =
        2.0 * std::acos(std::min(1.0, std::abs(end.pose.orientation.dot(rest.pose.orientation))));
    return {end.pose.position.x() - rest.pose.position.x(), deg(turned)};
}

} // namespace armour::test
