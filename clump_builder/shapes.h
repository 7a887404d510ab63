// Exact armour unit shapes.
//
// Description
//     Cube (optional chamfer on edges and corners) and dolos, built as exact
//     closed triangle meshes in the unit's own frame, plus the Shape record
//     that ties a mesh to its mass properties. Proportions of the dolos are
//     documented in docs/dolos.md.
//
// Usage
//     Shape cube  = make_cube_shape(1.0, 0.0, 2400.0);   // edge 1 m, 2400 kg/m^3
//     Shape dolos = make_dolos_shape(2.0, 0.33, 2400.0); // height 2 m, waist ratio 0.33
//     Shape stl   = make_stl_shape("unit.stl", 2400.0);
#pragma once

#include "mass_properties.h"
#include "mesh.h"

#include <string>
#include <vector>

namespace armour {

constexpr double kDolosWaistMin = 0.25;
constexpr double kDolosWaistMax = 0.50;
constexpr double kDolosWaistDefault = 0.33;

// Cube of edge `edge` (m) centred at the origin, faces normal to x, y, z.
// `chamfer` (m, 0 <= chamfer < edge/2) cuts every edge at 45 degrees, the cut
// reaching `chamfer` into each adjacent face; corners become triangles.
TriangleMesh make_cube_mesh(double edge, double chamfer = 0.0);

// Convex parts of a dolos of overall height `height` (m) and waist ratio
// `waist_ratio` (shank across-flats / height): [0] octagonal shank along x,
// [1] fluke along y at +x, [2] fluke along z at -x. Parts overlap.
std::vector<TriangleMesh> make_dolos_parts(double height, double waist_ratio);

// Exact union of the dolos parts (CGAL exact constructions).
TriangleMesh make_dolos_mesh(double height, double waist_ratio);

// Convex hull of `points` (m), triangulated, faces outward.
TriangleMesh convex_hull(const std::vector<Eigen::Vector3d> &points);

// A unit ready for clump building: its mesh in the unit frame (origin at the
// exact centroid, reference axes kept) and its exact mass properties.
struct Shape {
    std::string kind;                       // "cube", "dolos" or "stl"
    std::string description;                // e.g. "cube a=1 m chamfer=0 m"
    TriangleMesh mesh;                      // m, unit frame
    std::vector<TriangleMesh> convex_parts; // m, unit frame: cube {mesh}, dolos shank + flukes, STL none
    MassProperties props;                   // at the given density
    double Dn() const;                      // nominal diameter V^(1/3), m
};

// These validate their arguments and throw InputError naming the option.
Shape make_cube_shape(double edge, double chamfer, double density);
Shape make_dolos_shape(double height, double waist_ratio, double density);
Shape make_stl_shape(const std::string &path, double density); // validates the mesh

} // namespace armour
