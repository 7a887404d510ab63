// Clump files for LIGGGHTS and ParaView.
//
// Description
//     The sphere file is what LIGGGHTS' `fix particletemplate/multisphere ...
//     spheres file FILE scale 1` reads: one sphere per line, "x y z r" in
//     metres, in the unit frame (origin at the exact centroid). The template
//     snippet passes the exact mass and the exact inertia tensor (about the
//     centroid, unit axes) with `use_density`, so LIGGGHTS neither estimates
//     them by Monte Carlo nor moves the origin. See docs/clump_builder.md.
#pragma once

#include "clump.h"

#include <string>

namespace armour {

void write_sphere_file(const Clump &clump, const std::string &path, const std::string &comment);

// A ready `fix particletemplate/multisphere` line (plus comments) for `clump`.
std::string liggghts_template_snippet(const Shape &shape, const Clump &clump, const std::string &sphere_file,
                                      const std::string &fix_id = "unit_template", int template_type = 1);

// All spheres tessellated into one STL for viewing (overlaps are not removed).
TriangleMesh clump_surface_mesh(const Clump &clump, int subdivisions = 2);

} // namespace armour
