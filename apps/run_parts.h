// The parts of `armour run` (run_command.cpp, settle_run.cpp) that a test series
// (series_run.h) runs again for each of its steps: the settle before the
// waves, the checks of a resume, the warnings a run prints before it starts.
#pragma once

#include "checkpoints.h"
#include "output_folder.h"
#include "run_command.h"
#include "scene.h"
#include "scene_setup.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace armour {

// Every run's inputs beside its results (a DEM run's and a coupled run's):
// OUT/scene.resolved.toml (returned) and each unit's clump and exact shape
// under OUT/units/<unit>/ (clump.spheres, shape.stl: what bodies.xdmf draws).
std::filesystem::path write_scene_and_units(OutputFolder &folder, const Scene &scene,
                                            const SceneSetup &setup);

// OUT/settle/settled.json, with the speed below which the layer counts as still.
nlohmann::json settle_report(const std::filesystem::path &dir, const SceneSetup &setup);
// The warning for a settle report whose layer still moved at its end ("" when still).
std::string unsettled_warning(const nlohmann::json &report);
// Adds `report` to OUT/summary.json as its "settle" object, and its warning
// to the summary's (status 0 only); returns `status`.
int with_settle_report(OutputFolder &folder, int status, nlohmann::json report);

// The settle's own scene (OUT/settle/scene.resolved.toml): the scene without
// its fluid and waves, in fluid.settle_engine, with fluid.settle_friction and
// fluid.settle_density.
Scene settle_scene(const Scene &scene, const SceneSetup &setup);
// Every unit as an explicit [[body]] at its state's pose, at rest (a
// settle's end, a series step's end); the scene's explicit bodies keep their held axes.
std::vector<SceneBody> bodies_at_rest(const Scene &scene, const SceneSetup &setup,
                                      const std::vector<BodyState> &states);
// The scene the waves start from after the settle: every unit an explicit
// [[body]] at `bodies`, no settle; `growth` the settle's (settle_growth).
Scene settled_scene(const Scene &scene, std::vector<SceneBody> bodies, double growth);
// How much the settle's scene `dry` (settle_scene) grew the scene's units to
// hold their clumps: the largest ratio of their sizes, 1 when none grew.
double settle_growth(const Scene &scene, const Scene &dry);
// Settles a coupled scene's units in the DEM (a forked child) into OUT/settle
// and returns the settled scene; `setup` becomes its set-up, `report` the
// settle's (settled.json).
Scene settle_before_coupling(const RunRequest &r, OutputFolder &folder, const Scene &scene, SceneSetup &setup,
                             nlohmann::json &report);

// `armour run --settle-only`: the settle alone (settle_before_coupling) and
// OUT/summary.json with the settled layer's figures; returns the exit status.
int settle_only(const RunRequest &r, const Scene &scene);

// A run whose checkpoints all fall at or after its end: one warning.
void warn_if_no_checkpoint(const Scene &scene);
// fluid.settle_friction, settle_density or settle_engine without a settle: one
// warning each.
void warn_if_settle_keys_unused(const Scene &scene);
// fluid.settle_engine of sphere clumps handing its layer to exact hulls, or
// exact hulls run from a layer of cubes grown to hold clumps
// (fluid.settled_growth): one warning (measured: the hulls slump off the
// first and drop into the second's gaps before the waves).
void warn_if_hulls_inherit_a_layer(const Scene &scene);
// The options that do not fit the scene (--np without [fluid], --resume of
// an engine that cannot restore its state): InputError.
void check_options(const RunRequest &r, const Scene &scene);
// Engine keys the scene's engines (run.engine, fluid.settle_engine) do not
// take: run.contact_iterations for engines without an iterative contact
// solve. InputError naming the scene file and the key.
void check_engine_keys(const Scene &scene);

// The scene as far as a resume may not change it (resumable_keys: the keys a
// resume may change set to fixed values), as text to compare.
std::string resumable_form(Scene s, bool resumable_keys = true);
// InputError naming `scene_file` and the first line that differs, when `now` and `before` differ.
void refuse_if_differs(const std::string &scene_file, const std::string &now, const std::string &before,
                       const std::string &where);
// The checkpoint `armour run --resume` continues the run in `out` from, after
// checking that `scene` is the one that ran there but for the resumable keys.
Checkpoint checked_resume(const RunRequest &r, const Scene &scene, const std::filesystem::path &out);
// A resume's settle: `out`/settle must have ended and settled this scene;
// returns the settled scene (nothing is run again).
Scene checked_settle(const RunRequest &r, const Scene &scene, const SceneSetup &setup,
                     const std::filesystem::path &out);
// checked_settle, then checked_resume of the settled scene in `out`.
std::pair<Scene, Checkpoint> checked_settled_resume(const RunRequest &r, const Scene &scene,
                                                    const SceneSetup &setup,
                                                    const std::filesystem::path &out);

} // namespace armour
