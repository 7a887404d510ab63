// The shape an engine collides, for placing and checking initial poses:
// a DEM engine's clump spheres or an exact-shape engine's convex parts.
// Internal to the scene library (scene_setup.cpp).
#pragma once

#include "engine_registry.h"
#include "rigid_body_engine.h"

#include <Eigen/Geometry>
#include <utility>
#include <vector>

namespace armour {

// The shape an engine collides (engine_registry.h, ShapeModel): a DEM
// engine its clump's spheres, an exact-shape engine the unit's convex parts
// (the exact mesh where the shape has none: an STL unit). Placement is
// checked against this shape, not another engine's.
struct HalfSpace {
    Eigen::Vector3d n; // outward unit normal
    double d;          // m: inside where n.x <= d
};
struct Collider {
    bool spheres = true;                       // the clump (else the exact convex parts)
    std::vector<Eigen::Vector3d> points;       // m, unit frame: the parts' surface, <= 0.05 Dn apart
    std::vector<std::vector<HalfSpace>> parts; // the convex parts as half-spaces
    std::vector<Eigen::Vector3d> corners; // m, unit frame: the parts' vertices (points lie in their hull)
    double reach = 0.0;                   // m: the spheres (or the parts) all lie within this of its centre
};

// m: the farthest any of the clump's spheres reaches from the unit's centre.
double bounding_radius(const Clump &clump);

Collider make_collider(const UnitTemplate &unit, ShapeModel model, double Dn);

// m: how far the farthest of `points` (unit frame: an exact collider's
// surface points) lies outside the clump's spheres (0 when all are inside).
double depth_outside_clump(const Clump &clump, const std::vector<Eigen::Vector3d> &points);

// m: how deep point p (unit frame) lies inside the collider's parts (<= 0: outside).
double depth_inside(const Collider &c, const Eigen::Vector3d &p);

// Whether posed body `from`'s surface points (exact collider cf) all lie no
// deeper than `depth` (m; negative: that far outside) in posed body `to`'s
// parts (exact collider ct): the point-by-point test, exactly, but decided
// at once where each of to's parts has a face plane that every one of
// from's corners stands beyond (the points lie in the corners' hull).
bool none_deeper_than(const BodyInit &from, const Collider &cf, const BodyInit &to, const Collider &ct,
                      double depth);

// m: how far world point p lies behind wall w's surface (<= 0: on the
// bodies' side). The nearest triangles decide, their normals summed where
// several are nearest (the wall's edges and corners: a point above a step's
// edge lies behind the step face's plane, and outside the step). Walls the
// scene builds face the bodies (Wall). An STL wall's triangles may face
// either way: wound consistently (Wall::wound), the side of the wall that
// `centre` (the body's centre) lies on is the front, edges and all; else
// each nearest triangle is turned towards `centre` (a point above a step's
// edge, with the centre below the step's top, then reads as inside).
double depth_behind_wall(const Eigen::Vector3d &p, const Wall &w, const Eigen::Vector3d &centre);
// The same for many points of one body: which way wall w's normals face the
// body (+1 or -1; 0 for an STL wound either way, each triangle then turned
// to `centre`), worked out once per body and wall.
double wall_front(const Wall &w, const Eigen::Vector3d &centre);
double depth_behind_wall(const Eigen::Vector3d &p, const Wall &w, const Eigen::Vector3d &centre,
                         double front);

// Whether every edge two triangles share is run once each way (a surface's
// normals then all face one of its sides). Vertices must be merged
// (read_stl merges them).
bool consistently_wound(const TriangleMesh &surface);

// The deepest cut of posed body b into any wall, as its engine collides it
// (m, <= 0 when clear), and the wall's index.
std::pair<double, int> body_wall_penetration(const BodyInit &b, const UnitTemplate &unit, const Collider &c,
                                             const std::vector<Wall> &walls);

// Whether posed bodies a and b come closer than `clearance` (m) as the
// engine collides them: clump spheres, or exact surface points (<= 0.05 Dn
// apart) within the clearance of the other's parts. Both colliders are of
// one engine (both clumps or both exact shapes).
bool closer_than(const BodyInit &a, const UnitTemplate &unit_a, const Collider &ca, const BodyInit &b,
                 const UnitTemplate &unit_b, const Collider &cb, double clearance);
// The same for two bodies of one unit.
bool closer_than(const BodyInit &a, const BodyInit &b, const UnitTemplate &unit, const Collider &c,
                 double clearance);

} // namespace armour
