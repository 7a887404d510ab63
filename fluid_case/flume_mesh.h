// The wave flume's mesh lines: uniform, or graded away from a refined box.
//
// Description
//     The wave_flume template is one blockMesh block. `fluid.cells` (or
//     `cell_size`) gives the fine cell h along each axis; with
//     `fluid.refine_min/refine_max`, along each axis the cells keep h inside
//     the box's interval and grow outside it, by at most kMaxCellGrowth per
//     cell, to `coarse_cell_size`, then stay there to the mesh's end. The axes are
//     graded independently (one block: the z grading holds all along x), so
//     the box's z range is the free-surface band everywhere in the flume.
//     The node lines are computed as blockMesh spaces a multi-section
//     simpleGrading, so gauges can sit mid-column (docs/openfoam.md).
//
// Usage
//     [fluid]
//     cells = [100, 12, 31]             # the fine cells: h = extent / cells
//     refine_min = [1.15, -0.124, 0.20] # m: fine around the armour ...
//     refine_max = [2.0, 0.124, 0.62]   # ... and the free-surface band
//     coarse_cell_size = [0.05, 0.0, 0.03] # m: cells grow to these along x and z
//                                          # outside (y: 0 <= fine, not graded)
//
//     FlumeMesh mesh = flume_mesh(scene);
//     mesh.axes[0].cells;     // blockMesh cells along x
//     mesh.axes[0].grading;   // "1" or "((0.4 0.2 0.5) (0.6 0.8 1))"
//     mesh.axes[0].nodes;     // x of every node line, lo .. hi
#pragma once

#include "scene.h"

#include <array>
#include <string>
#include <vector>

namespace armour {

struct SceneSetup;

// Cells grow away from the refined box by at most 10 % per cell: a common
// limit for wave meshes (truncation error grows with the jump in cell size).
inline constexpr double kMaxCellGrowth = 1.1;

struct MeshAxis {
    int cells = 0;
    std::string grading = "1"; // one simpleGrading entry
    std::vector<double> nodes; // m, cells + 1 node coordinates
    double smallest_cell() const;
    double largest_cell() const;
    double column_centre(double at) const; // the centre of the cell holding `at`
};

struct FlumeMesh {
    std::array<MeshAxis, 3> axes;
    bool graded = false;
    long cells() const { return static_cast<long>(axes[0].cells) * axes[1].cells * axes[2].cells; }
};

// The fine cell along x, y, z (m): run.domain's extent / fluid.cells, the
// size of every cell of a uniform mesh and of those in a graded one's box.
Eigen::Vector3d fine_cell_size(const Scene &scene);

// L: the deepest [[refine]] level of a refined mesh (fluid.mesh = "refined");
// 0 for a graded or uniform one. The block's x and y cells are fluid.cells / 2^L.
int refine_levels(const Scene &scene);

// The blockMesh block of a scene's [fluid] (uniform when it has no refine
// box; a refined mesh's base block: mesh_refinement.h).
FlumeMesh flume_mesh(const Scene &scene);

// The mesh in words, as a run reports it: "70 x 13 x 55 graded block, cells
// halved in x and y in 2 [[refine]] regions" (the block's cells, not the
// case's: a refined mesh's count is known once meshed).
std::string mesh_layout(const Scene &scene);

// Throws InputError when a graded or refined scene cannot run: its template
// has no @GRADING@ token (a fixed block structure), or a unit starts outside
// the refined box (its cells would be coarser than the loads need; the
// [[refine]] regions' own check: check_units_refined, mesh_refinement.h).
void check_flume_grading(const Scene &scene, const SceneSetup &setup, const std::string &template_text);

} // namespace armour
