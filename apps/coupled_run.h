// `armour run` for a scene with [fluid]: interFoam with the armourCoupling plugin.
//
// Description
//     Checks the scene against the fluid mesh first (units inside the box,
//     clear of the walls, cells across a unit, np against the engine), then
//     fills a copy of the case template foam_cases/<fluid.case> in OUT/case
//     (@TOKENS@ in its files: mesh box and cells, water level, fluid
//     properties, Courant and time-step limits, plugin, scene), runs blockMesh,
//     setFields and interFoam (serial, or decomposePar + mpirun), and writes
//     OUT/summary.json from the plugin's OUT/bodies.h5. A failing tool stops
//     the run with its FOAM FATAL line as one InputError; what was written so
//     far stays in OUT.
#pragma once

#include "output_folder.h"
#include "run_command.h"
#include "scene.h"
#include "scene_setup.h"

#include <string>
#include <vector>

namespace armour {

// Warnings for a scene that can run but may give poor answers (e.g. fewer
// than 4 cells across a unit); throws InputError for one that cannot.
std::vector<std::string> check_coupled_scene(const Scene &scene, const SceneSetup &setup, int np);

struct Checkpoint;

// Returns the exit status; `request.np` > 0 overrides fluid.np. Writes into
// `out` (an `armour run` folder; opened here if not yet). `resume`: continue
// the run in `out` (resumed already) from this checkpoint (docs/checkpoints.md).
int run_coupled(const RunRequest &request, const Scene &scene, const SceneSetup &setup, OutputFolder &out,
                const Checkpoint *resume = nullptr);

} // namespace armour
