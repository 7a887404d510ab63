// A refined wave-flume mesh: the graded blockMesh block at coarser base cells
// in x and y, split back to fluid.cells by OpenFOAM's refineMesh in the
// scene's [[refine]] regions (fluid.mesh = "refined").
//
// Description
//     The base block has cells 2^L times larger than fluid.cells in x and y
//     (L the deepest [[refine]] level; z as fluid.cells and the graded box
//     give it). Pass k = 1..L selects, with topoSet, the cells whose centre
//     lies in a region of level >= k, plus one layer of cells around each
//     region of a deeper level (no cell meets one more than one level finer),
//     and refineMesh halves them in x and y. z is never split: the free
//     surface then never crosses a face between cells of different heights,
//     where interFoam's hydrostatic balance breaks (a box split in x, y and z
//     drove 1 m/s air jets across still water; split in x and y only, about
//     the uniform mesh's 0.3-0.5 m/s: docs/openfoam.md). The passes run
//     before the porous zones are made, so the zones are the refined cells'.
//
// Usage
//     const int passes = refine_levels(scene);          // 0: not refined (flume_mesh.h)
//     write_refine_dicts(scene, case_dir);             // system/topoSetDict.refine<k>, refineMeshDict
//     run_tool(...topoSet -dict system/topoSetDict.refine1...); run_tool(...refineMesh -overwrite...);
//     check_units_refined(scene, setup);               // every unit in the finest regions
#pragma once

#include "scene.h"

#include <Eigen/Core>
#include <filesystem>
#include <string>

namespace armour {

struct SceneSetup;

// True when p lies in the region (to `tolerance`, m, outward).
bool in_refine_region(const Scene &scene, const SceneRefine &region, const Eigen::Vector3d &p,
                      double tolerance);

// The topoSet actions that select pass k's cells (1 <= k <= L) into the cellSet "refine".
std::string refine_set_actions(const Scene &scene, int pass);

// Writes system/topoSetDict.refine<k> for k = 1..L and system/refineMeshDict.
void write_refine_dicts(const Scene &scene, const std::filesystem::path &case_dir);

// Throws InputError naming the [[refine]] regions when a unit starts with a
// vertex outside every region of the deepest level (by more than half a
// fine cell): its loads need fluid.cells. Placed units that settle first are
// checked after the settle.
void check_units_refined(const Scene &scene, const SceneSetup &setup);

} // namespace armour
