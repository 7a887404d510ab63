// An analytic rigid-body engine without contacts: the test double behind the
// coupler's tests and the added-mass model problem (coupling/added_mass_problem.h).
//
// Description
//     Each body moves under gravity and its held external load only; nothing
//     collides. Translation is velocity Verlet (exact for a load held constant
//     over advance()). Rotation integrates the world angular momentum
//     (dL/dt = T, exact for a constant torque, and equivalent to Euler's
//     equations in the unit frame) and the orientation quaternion with the
//     implicit-midpoint angular velocity, so |L| is kept exactly without
//     torque. Locked world axes are honoured: locked velocity components are
//     zero, and the free angular velocity components solve the free rows of
//     L = I_world omega (the constraint torque acts only about locked axes).
//     Walls are accepted and ignored (no contacts). The step is
//     settings.time_step, or 1e-4 s when that is 0; there is no stability
//     limit (TimeStepReport::limit = 0).
//
// Usage
//     auto engine = make_free_body_engine(EngineSettings{});
//     int cube = engine->add_template(unit);            // props: mass, inertia
//     int body = engine->add_body({cube, pose});
//     engine->set_external_load(body, force, torque);
//     engine->advance(0.01);
#pragma once

#include "engine_registry.h"
#include "rigid_body_engine.h"

#include <memory>

namespace armour {

std::unique_ptr<RigidBodyEngine> make_free_body_engine(const EngineSettings &settings);

// Name, capabilities and factory for the registry.
EngineStyle free_body_engine_style();

} // namespace armour
