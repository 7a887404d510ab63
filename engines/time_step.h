// Stable time step of a DEM of rigid sphere clumps, from material data and each unit's mass.
//
// Description
//     A clump is one rigid body: its spheres do not oscillate on their own,
//     the body does, on the contact springs of the spheres that touch. For
//     each unit and each of kTimeStepDirections directions n, the spheres that
//     touch a plane normal to n at once (within their impact overlap of the
//     extreme one) act as springs k_j at their contact points p_j; the body's
//     highest natural frequency on them is
//         w^2 = largest eigenvalue of  K x = w^2 M x,
//         K = sum_j k_j J_j^T J_j,  J_j = [n^T, (p_j x n)^T],  M = diag(m, m, m, I),
//     which covers a corner hit (one sphere, effective mass below m through the
//     rotation) and a flat face (many springs in parallel). Each k_j is the
//     stiffness at the peak overlap of the whole mass m hitting on sphere j
//     alone at the characteristic velocity v (an upper bound on any contact's
//     overlap, so on its stiffness): hooke uses LIGGGHTS' own rule
//         k = 16/15 sqrt(R) Y* (15 m v^2 / (16 sqrt(R) Y*))^(1/5),
//     hertz the tangent stiffness 2 Y* sqrt(R d) at that overlap d. Walls:
//     R = r_j. Two units: R = r_j (at least R* = r_j r_k / (r_j + r_k)) and
//     w^2 doubled (two bodies on the same springs: w^2 <= 2 max(w_A^2, w_B^2)).
//     With the damping ratio z of the restitution coefficient e,
//     z = -ln e / sqrt(pi^2 + ln^2 e), velocity Verlet is stable below
//         dt_crit = (2 / w) (sqrt(1 + z^2) - z),
//     the limit reported. The default step is kDefaultSafety x limit; measured
//     blow-up in docs/dem.md ("Time step"). The Rayleigh time of the smallest
//     sphere, the rule for deformable single grains, is reported for
//     comparison only: a clump's spheres carry no elastic waves.
//
// Usage
//     TimeStepReport dt = compute_time_step(settings, units, wall_materials);
//     engine runs at dt.used; dt.limit and dt.rule go into the summary.
#pragma once

#include "rigid_body_engine.h"

#include <vector>

namespace armour {

constexpr double kDefaultSafety = 0.2;
constexpr int kTimeStepDirections = 400;

// `settings.time_step` = 0 selects the default; a larger step than the limit
// throws InputError unless settings.force_time_step.
TimeStepReport compute_time_step(const EngineSettings &settings, const std::vector<UnitTemplate> &units,
                                 const std::vector<int> &wall_materials);

} // namespace armour
