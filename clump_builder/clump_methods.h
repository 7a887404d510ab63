// Private to clump_builder: the individual builders behind build_clump().
#pragma once

#include "clump.h"
#include "shape_query.h"

namespace armour::detail {

// The smallest sphere the optimised methods keep, as a fraction of Dn: below
// it a sphere adds contact cost and shrinks the DEM's step without improving
// the fit measurably.
constexpr double kMinSphereRadius = 0.03;

// Greedy maximal inscribed spheres on a lattice of ~`lattice_points` interior points.
Clump greedy_inscribed(const Shape &shape, const ShapeQuery &query, int spheres, std::uint64_t seed,
                       int lattice_points = 30000);

// Moves centres and radii of `start` to fit the exact surface, then matches
// volume; the first `fixed` spheres stay as they are.
Clump optimise_clump(const Shape &shape, const ShapeQuery &query, Clump start, std::uint64_t seed,
                     std::size_t fixed = 0);

// Shrinks every sphere but the first `fixed` ones until it lies inside the
// exact shape (radius at most its centre's depth); a centre shallower than
// kMinSphereRadius Dn moves towards the centroid first.
void hold_inside(Clump &clump, const Shape &shape, const ShapeQuery &query, std::size_t fixed = 0);

// Adds one common offset to every radius but the first `fixed` ones so that
// the union volume equals `volume`.
Clump match_volume(Clump clump, double volume, std::size_t fixed = 0);

} // namespace armour::detail
