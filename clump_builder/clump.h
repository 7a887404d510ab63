// Sphere clumps: overlapping spheres that stand in for an exact unit shape.
//
// Description
//     Two builders fill a Shape with N spheres, both deterministic for a seed:
//       greedy     baseline: maximal inscribed spheres chosen greedily to
//                  cover the most still-uncovered volume (never protrude).
//       optimised  starts from the greedy clump, then moves centres and radii
//                  (spheres may protrude) to minimise the squared distance
//                  between the exact surface and the clump surface, keeping
//                  the interior covered and the exterior empty; finally one
//                  common radius offset makes the clump volume equal the exact
//                  volume. With enough spheres it also holds one small
//                  sphere on every corner of every face the unit rests on,
//                  so that it stands and topples like the unit
//                  (clump_support.h); asked for, also spheres along every
//                  edge of those faces, so that a unit resting on the clump
//                  pivots at its edge (edge_spheres below).
//       inscribed  the optimised clump with every sphere but the corner ones
//                  shrunk until it lies inside the exact shape (no volume
//                  match, so it under-fills); the corner spheres then sit on
//                  the exact corners (a cube's inside, a dolos's up to their
//                  radius out). A cube's clump never reaches out of its
//                  faces, so the poses of a layer the exact hulls settled at
//                  their own size start these clumps in contact or apart
//                  (docs/stability.md, one layer for both unit models).
//     Sphere centres are in the unit frame (origin at the exact centroid), m.
//
// Usage
//     Shape shape = make_dolos_shape(2.0, 0.33, 2400.0);
//     Clump clump = build_clump(shape, ClumpMethod::optimised, 40, 1);
#pragma once

#include "shapes.h"

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace armour {

struct Sphere {
    Eigen::Vector3d center; // m, unit frame
    double radius;          // m
};
using Clump = std::vector<Sphere>;

enum class ClumpMethod { greedy, optimised, inscribed };

std::string method_name(ClumpMethod method);
// Throws InputError for an unknown name; lists the known ones.
ClumpMethod parse_method(const std::string &name);

// Builds a clump of exactly `spheres` spheres (>= 1). `edge_spheres` > 0
// (optimised and inscribed) adds that many support spheres along every edge
// of every resting face besides the corner ones, out of the same count
// (clump_support.h, add_edge_supports); too few spheres for them is an
// InputError.
Clump build_clump(const Shape &shape, ClumpMethod method, int spheres, std::uint64_t seed = 1,
                  int edge_spheres = 0);
// The fewest spheres build_clump accepts with `edge_spheres` > 0: the
// support spheres (corners and edges) and 8 for the body.
int fewest_spheres_with_edges(const Shape &shape, int edge_spheres);

// Volume of the union of the spheres (m^3), by exact chord lengths along a
// grid of lines (2D midpoint rule with `lines` x `lines` lines).
double clump_volume(const Clump &clump, int lines = 400);

// Mass properties of the union of the spheres at `density`, same integration.
MassProperties clump_mass_properties(const Clump &clump, double density, int lines = 400);

} // namespace armour
