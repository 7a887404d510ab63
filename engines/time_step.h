// Stable time step of a spring-dashpot DEM, from material data and the smallest sphere.
//
// Description
//     The stiffest contact is the one of the smallest sphere (mass m = rho 4/3 pi r^3)
//     with a wall (effective mass m) or with an equal sphere (m/2). Its normal
//     stiffness k comes from the contact model at the characteristic impact
//     velocity v: hooke uses LIGGGHTS' own rule
//         k = 16/15 sqrt(R*) Y* (15 m* v^2 / (16 sqrt(R*) Y*))^(1/5),
//     hertz the tangent stiffness 2 Y* sqrt(R* d) at the peak overlap d of an
//     impact at v. With w = sqrt(k/m*) and the damping ratio z of the
//     restitution coefficient e, z = -ln e / sqrt(pi^2 + ln^2 e), the explicit
//     (velocity Verlet) integration is stable below
//         dt_crit = (2 / w) (sqrt(1 + z^2) - z).
//     For hertz the limit is also at most the Rayleigh time of the smallest
//     sphere, t_R = pi r sqrt(rho/G) / (0.1631 nu + 0.8766). The default step is
//     kDefaultSafety x limit (about 15 steps per contact).
#pragma once

#include "rigid_body_engine.h"

#include <vector>

namespace armour {

constexpr double kDefaultSafety = 0.2;

// `settings.time_step` = 0 selects the default; a larger step than the limit
// throws InputError unless settings.force_time_step.
TimeStepReport compute_time_step(const EngineSettings &settings, const std::vector<UnitTemplate> &units,
                                 const std::vector<int> &wall_materials);

} // namespace armour
