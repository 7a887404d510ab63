// The DEM run of a scene without [fluid]: `armour run` of a dry scene, and
// the settle before a coupled run (settle_run.cpp), under still water.
#pragma once

#include "checkpoints.h"
#include "output_folder.h"
#include "rigid_body_engine.h"
#include "scene.h"
#include "scene_setup.h"
#include "standard_conditions.h"

#include <memory>
#include <vector>

namespace armour {

// Still water for a settle run (the coupled scene's, at rest): each unit
// carries the buoyancy of its part below the surface, so the layer settles
// under its submerged weight, as in a flume filled slowly.
struct StillWater {
    double level = 0.0;                  // m, z of the surface
    double density = kFreshWaterDensity; // kg/m^3
    double update_interval = 0.0;        // s between buoyancy updates
};

// The scene's engine with its units, walls and bodies, not started.
std::unique_ptr<RigidBodyEngine> scene_engine(const Scene &scene, const SceneSetup &setup,
                                              const EngineSettings &settings);

// The DEM run of a scene without [fluid], dry or (`water`, a settle run)
// under still water's buoyancy, into `folder`; `final_states` (optional)
// receives every body's state at the end. `resume`: continue the run in
// `folder` (resumed already) from this checkpoint.
int run_dem(OutputFolder &folder, const Scene &scene, SceneSetup &setup, std::vector<BodyState> *final_states,
            const StillWater *water = nullptr, const Checkpoint *resume = nullptr);

} // namespace armour
