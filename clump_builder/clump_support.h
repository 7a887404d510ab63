// Support polygons and topple angles of a unit and of its clump.
//
// Description
//     A unit can rest on a face of its convex hull when its centre of mass,
//     projected along the face normal, falls inside the face (a resting
//     face). Tilted towards an edge of that face (gravity turning in the
//     plane normal to the edge, as on a tilting plate) it topples when the
//     vertical through the centre of mass leaves the face:
//         tan(theta) = d / h,
//     d the distance the foot of the centre of mass travels along the edge's
//     outward normal before it leaves the face (the distance to the edge when
//     its perpendicular lands on the edge, less on a slanted face), h the
//     centre of mass's height above the face. A clump stands on its spheres instead: lowered onto the
//     face's plane it touches with its lowest sphere, and every sphere within
//     kSupportContact Dn of that plane (about the Hertz overlap under the
//     unit's weight) carries load; its support polygon is the convex hull of
//     their touching points, and h is measured from the plane it touches.
//     Tilted in the same direction (the exact edge's outward normal), it
//     topples when the vertical leaves its own polygon. A clump whose
//     polygon does not surround the foot topples at 0 degrees.
//     The centre of mass is the exact one for both (the DEM template keeps
//     the exact centroid and inertia, docs/clump_builder.md).
//
// Usage
//     for (const FaceTopple &f : topple_angles(shape.mesh, centroid, clump, shape.Dn()))
//         ... f.exact_deg[e], f.clump_deg[e] ...
//     double worst = topple_error_deg(shape.mesh, centroid, clump, shape.Dn());
#pragma once

#include "clump.h"

#include <Eigen/Core>
#include <vector>

namespace armour {

// Spheres this close to the lowest (fraction of Dn) touch the plane too.
constexpr double kSupportContact = 0.003;

struct RestingFace {
    Eigen::Vector3d normal;               // outward unit normal, mesh frame
    double offset = 0.0;                  // the face's plane is normal . x = offset, m
    Eigen::Vector3d u, v;                 // in-plane axes; (u, v, normal) is right-handed
    std::vector<Eigen::Vector2d> polygon; // the face, counter-clockwise in (u, v), m
    std::vector<Eigen::Vector3d> corners; // the same corners in the mesh frame, m
    Eigen::Vector2d foot;                 // the centre of mass projected onto the plane, (u, v), m
    double height = 0.0;                  // centre of mass above the plane, m
    double support = 0.0;                 // foot's distance inside the polygon's edges, m
    Eigen::Vector2d in_plane(const Eigen::Vector3d &p) const { return {u.dot(p), v.dot(p)}; }
};

// The faces of the convex hull of `mesh` that the unit rests on.
std::vector<RestingFace> resting_faces(const TriangleMesh &mesh, const Eigen::Vector3d &centre_of_mass,
                                       double Dn);

struct FaceTopple {
    Eigen::Vector3d normal;          // the resting face's outward normal
    std::vector<double> exact_deg;   // per edge of the exact face (counter-clockwise order)
    std::vector<double> clump_deg;   // the clump tilted towards the same edge
    std::vector<int> clump_supports; // indices of the spheres that touch the plane
};
std::vector<FaceTopple> topple_angles(const TriangleMesh &mesh, const Eigen::Vector3d &centre_of_mass,
                                      const Clump &clump, double Dn);
// Largest |clump - exact| over every resting face and edge, degrees (0 with no resting face).
double topple_error_deg(const TriangleMesh &mesh, const Eigen::Vector3d &centre_of_mass, const Clump &clump,
                        double Dn);

// Support spheres (the optimised method): one small sphere on every corner
// of every resting face, so that the clump stands on the exact face's
// corners. Its radius is kSupportRadius Dn; it reaches as far beyond its
// faces as the clump's other spheres reach beyond any resting face (at least
// to the face), moved outward along the corner's bisector s (n_f . s = 1 on
// each of its faces): the clump then touches each face's plane on its corner
// spheres, whose touching points lie on or just outside the exact corners,
// which offsets most of the extra height of the lifted plane.
constexpr double kSupportRadius = 0.01;
struct SupportCorner {
    Eigen::Vector3d vertex;   // m, mesh frame
    Eigen::Vector3d bisector; // n_f . bisector = 1 on its faces (least squares, minimum norm)
    std::vector<int> faces;   // indices into the resting faces
};
std::vector<SupportCorner> support_corners(const std::vector<RestingFace> &faces, double Dn);
// Edge spheres (optional, `edge_spheres` per edge): a clump resting on
// another clump pivots on the last high sphere cap short of its
// neighbour's edge, 3-5 mm (0.08-0.12 Dn) back on the stability scene's
// cube whatever the sphere count (docs/validation/stability.md, a cube on a
// cube). So `per_edge` more support points, evenly spaced along every edge
// of every resting face between its corners, are appended to `corners`:
// each gets a sphere as a corner does, reaching the same plane on both of
// the edge's faces, so that the face stands as high at its edge as anywhere.
void add_edge_supports(std::vector<SupportCorner> &corners, const std::vector<RestingFace> &faces,
                       int per_edge, double Dn);
// Sets clump[k] for k < corners.size() to the corner spheres, fitted to the
// other spheres clump[corners.size()...].
void place_support_spheres(Clump &clump, const std::vector<SupportCorner> &corners,
                           const std::vector<RestingFace> &faces, double radius);

namespace detail {
// Counter-clockwise convex hull of 2-D points (collinear points dropped).
std::vector<Eigen::Vector2d> hull_2d(std::vector<Eigen::Vector2d> points);
// Distance from p inside the counter-clockwise polygon to its nearest edge
// line (<= 0 outside; -1 for fewer than three corners).
double depth_inside(const std::vector<Eigen::Vector2d> &polygon, const Eigen::Vector2d &p);
// How far p travels along the unit direction `towards` before it leaves the
// polygon (p inside); 0 when p is not inside.
double exit_distance(const std::vector<Eigen::Vector2d> &polygon, const Eigen::Vector2d &p,
                     const Eigen::Vector2d &towards);
} // namespace detail

} // namespace armour
