// Solid fractions: the part of a fluid cell's volume that lies inside a unit.
//
// Description
//     Plain geometry (Eigen only, no OpenFOAM, no CGAL), used by the coupler
//     for chi = |cell inside the unit| / |cell|. The cell is a convex
//     polyhedron (a blockMesh hex, or any convex cell given by its faces),
//     expressed in the unit's own frame. The unit is one of
//       - convex (a cube, a box, any convex hull): the intersection of its
//         face planes; the cell is clipped by each plane that cuts it. Exact
//         (to rounding).
//       - any closed outward triangle mesh (a dolos, an STL): the indicator
//         of the solid is, almost everywhere, the signed sum of the
//         indicators of the cones (tetrahedra) from the unit's origin to each
//         triangle, sign = orientation of the tetrahedron. So the part inside
//         is sum_t sign_t |cell ∩ tet_t|, each a convex clip. Exact for any
//         closed mesh, convex or not, star-shaped or not.
//       - a union of spheres (a clump): exact chord lengths of the union along
//         a grid of lines through the cell (the rule clump_volume uses), with
//         lines at most `line_spacing` apart: an approximation whose error
//         the tests measure (tests/test_solid_fraction.cpp).
//     Each answer carries the centroid of the part inside, so loads can be
//     taken about where the solid in a cell really is.
//
// Usage
//     const SolidShape cube = SolidShape::from_mesh(unit.mesh);   // convex: planes
//     const SolidShape dolos = SolidShape::from_mesh(dolos_mesh);  // not convex: cones
//     const SolidShape clump = SolidShape::from_spheres(unit.clump, 0.01);
//     ConvexPolyhedron cell = ConvexPolyhedron::box(lo, hi);       // unit frame
//     FractionScratch scratch;
//     const SolidPart part = cube.part_inside(cell, scratch);     // m^3 and m
#pragma once

#include "clump.h"
#include "mesh.h"

#include <Eigen/Core>
#include <vector>

namespace armour {

// The half-space normal . x <= offset.
struct HalfSpace {
    Eigen::Vector3d normal; // unit length
    double offset;          // m
};

struct SolidPart {
    double volume = 0.0;                                // m^3
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero(); // m; meaningless when volume is 0
};

// A convex polyhedron as the oriented edges of its faces: every face's edges
// run counter-clockwise seen from outside, so each edge appears once in
// either direction (closed and consistently oriented). A face needs no order
// of its edges: clipping keeps edges, adds one closing edge per cut face and
// the cap's edges, with no sorting.
class ConvexPolyhedron {
  public:
    struct Edge {
        int from, to, face;
    };
    // Corner loops of a box's faces, counter-clockwise seen from outside;
    // corner c is (c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z).
    static constexpr int kBoxLoops[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                            {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    static ConvexPolyhedron box(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi);

    void clear() {
        points.clear();
        edges.clear();
        faces = 0;
    }
    int add_point(const Eigen::Vector3d &p) {
        points.push_back(p);
        return static_cast<int>(points.size()) - 1;
    }
    // A loop of point indices, counter-clockwise seen from outside.
    void add_face(const int *loop, int count);
    bool empty() const { return edges.empty(); }

    // The part on the kept side of h written into `out` (empty when nothing
    // is left); the cut adds one cap face in the plane.
    void clip(const HalfSpace &h, ConvexPolyhedron &out, std::vector<double> &side,
              std::vector<int> &scratch) const;
    SolidPart volume_and_centroid() const;
    // The outward face planes, for line intersections.
    void planes(std::vector<HalfSpace> &out) const;

    std::vector<Eigen::Vector3d> points;
    std::vector<Edge> edges;
    int faces = 0;
};

// Buffers reused between calls (no allocation per cell once warm).
struct FractionScratch {
    ConvexPolyhedron a, b;
    std::vector<double> side;
    std::vector<int> indices;
    std::vector<HalfSpace> planes;
    std::vector<std::pair<double, double>> chords;
};

class SolidShape {
  public:
    // Convex meshes become their face planes, others signed cones.
    static SolidShape from_mesh(const TriangleMesh &mesh);
    // line_spacing (m): the largest distance between integration lines.
    static SolidShape from_spheres(const Clump &spheres, double line_spacing);

    bool convex() const { return !planes_.empty(); }
    const std::vector<HalfSpace> &planes() const { return planes_; }
    // Convex units: max over the face planes of normal . x - offset (m):
    // the signed distance inside, at most the distance outside.
    double plane_distance(const Eigen::Vector3d &x) const;
    // The part of `cell` (unit frame) inside the unit.
    SolidPart part_inside(const ConvexPolyhedron &cell, FractionScratch &scratch) const;
    // The part of `cell` inside `count` half-spaces (a convex unit's planes
    // that cut it, when the caller knows which).
    static SolidPart part_within(const ConvexPolyhedron &cell, const HalfSpace *planes, int count,
                                 FractionScratch &scratch) {
        return clip_all(cell, planes, count, scratch).volume_and_centroid();
    }

  private:
    struct Cone {
        HalfSpace faces[4];
        Eigen::Vector3d lo, hi; // bounding box
        double sign;            // +1 or -1: the tetrahedron's orientation
    };
    // Clips `cell` successively by `count` half-spaces; the result is in
    // scratch.a or scratch.b (returned), empty when nothing is left.
    static const ConvexPolyhedron &clip_all(const ConvexPolyhedron &cell, const HalfSpace *h, int count,
                                            FractionScratch &scratch);
    SolidPart spheres_inside(const ConvexPolyhedron &cell, FractionScratch &scratch) const;

    std::vector<HalfSpace> planes_; // convex unit
    std::vector<Cone> cones_;       // any closed mesh
    Clump spheres_;                 // union of spheres
    double line_spacing_ = 0.0;
};

} // namespace armour
