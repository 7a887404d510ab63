// The OpenFOAM case of a scene with [fluid]: checked, written from its
// template, meshed, resumed from a checkpoint and solved by interFoam with
// the coupling plugin.
//
// Description
//     check_fluid_case() checks the scene against its case before anything is
//     written (the template and its tokens, walls and grading, the plugin and
//     OpenFOAM's tools, the ranks, the units against the mesh box, the walls
//     and the cells, the engine's step). write_case() copies the template
//     foam_cases/<fluid.case> into the case folder and fills its @TOKENS@
//     (mesh box and cells, water level, fluid properties, Courant and
//     time-step limits, waves, plugin, scene: docs/openfoam.md) and fluid
//     models; mesh_case() runs blockMesh, refineMesh, topoSet, subsetMesh,
//     setFields and decomposePar as the case needs; resume_case() restores a
//     checkpoint (foam_restart.h); run_interfoam() runs the solver, serial or
//     through mpirun. A failing tool stops the run with its FOAM FATAL line
//     as one InputError (foam_tool.h); what was written so far stays.
//
// Usage
//     const auto warnings = check_fluid_case(scene, setup, np);
//     const auto paths = case_paths(resolved_scene, cache_dir, out);
//     write_case(scene, setup, paths, out / "case");
//     mesh_case(scene, out / "case");       // or resume_case(scene, checkpoint, paths, out / "case")
//     run_interfoam(scene, out / "case", nullptr);
#pragma once

#include "scene.h"
#include "scene_setup.h"

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace armour {

struct Checkpoint;

// Warnings for a scene whose case can run but may give poor answers (e.g.
// fewer than 4 cells across a unit); throws InputError for one that cannot.
std::vector<std::string> check_fluid_case(const Scene &scene, const SceneSetup &setup, int np);

// The paths the case names (@ARMOUR_PLUGIN@, @ARMOUR_WAVES@, @SCENE@,
// @CACHE@, @OUTPUT@): the plugin ($ARMOUR_FOAM_PLUGIN, else this build's)
// and wave library, the resolved scene, the clump cache, the run's folder.
std::map<std::string, std::string> case_paths(const std::filesystem::path &scene_file,
                                              const std::string &cache_dir, const std::filesystem::path &out);

// A new case in `case_dir` (which must not exist): the template with its
// tokens filled from the scene and `paths`, and its fluid models.
void write_case(const Scene &scene, const SceneSetup &setup, const std::map<std::string, std::string> &paths,
                const std::filesystem::path &case_dir);

// The written case's mesh and initial fields, split over fluid.np ranks.
void mesh_case(const Scene &scene, const std::filesystem::path &case_dir);

// The case in `case_dir` set back to `checkpoint`, its paths filled anew,
// its fields split over fluid.np ranks when the checkpoint's differ.
void resume_case(const Scene &scene, const Checkpoint &checkpoint,
                 const std::map<std::string, std::string> &paths, const std::filesystem::path &case_dir);

// interFoam to run.duration on fluid.np ranks (from the checkpoint's time when resuming).
void run_interfoam(const Scene &scene, const std::filesystem::path &case_dir, const Checkpoint *resume);

// nCells of the mesh as written (templates with several blocks or blocked
// cells are not cells[0] x cells[1] x cells[2]); -1 when unknown.
long mesh_cells(const std::filesystem::path &case_dir);

} // namespace armour
