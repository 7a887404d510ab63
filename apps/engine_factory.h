// Engines by name, as a scene's run.engine names them.
#pragma once

#include "rigid_body_engine.h"

#include <memory>
#include <string>
#include <vector>

namespace armour {

// The contact engines of this build (what `armour compare` sweeps). make_engine
// also knows "free_body": no contacts, for coupled runs and tests of the fluid load.
std::vector<std::string> available_engines();

// Throws InputError naming run.engine for an engine this build does not have.
std::unique_ptr<RigidBodyEngine> make_engine(const std::string &name, const EngineSettings &settings);

} // namespace armour
