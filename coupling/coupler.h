// The fluid-structure coupler core: knows no engine by name and no OpenFOAM type.
//
// Description
//     Called once per fluid time step by a thin CFD plugin (coupling/openfoam/):
//       1. poses and velocities from the engine (any RigidBodyEngine),
//       2. solid volume fraction chi per fluid cell: the fraction of the
//          cell's volume inside the unit's exact shape or its clump spheres
//          (solid_fraction.h), and the rigid-body velocity there; or, with
//          SolidFraction::sampled_ramp, a cosine ramp of the signed distance
//          sampled at the cell centre (the former mask, kept for comparison),
//       3. the penalisation (Brinkman) coefficients the plugin puts into the
//          momentum equation: source = -rho K chi (U - U_body),
//       4. the fluid load on each unit from this rank's cells,
//              F = sum_i chi_i V_i f_i,   M = sum_i chi_i V_i (s_i - x_c) x f_i,
//          s_i the centroid of the solid part of cell i,
//          with f = -grad p + div(tau) the fluid force density (N/m^3; it
//          contains buoyancy through the hydrostatic part of grad p),
//       5. loads summed over MPI ranks by the plugin, handed to the engine,
//          engine advanced by the fluid step in its own stable sub-steps.
//     Light units make plain explicit coupling unstable (added mass); with
//     added_mass_coefficient C_a > 0 the applied load is corrected with the
//     added mass m_a = C_a rho_f V (see docs/coupling.md).
//
// Usage
//     Coupler coupler(*engine, units, body_unit, settings);
//     const CellMask &mask = coupler.update_mask(cells);      // start of a fluid step
//     BodyLoads local = coupler.integrate_loads(cells, force_density);
//     // ... sum local over ranks (every field) into total ...
//     centre_torque_on_mask(total);
//     coupler.advance(total, dt_fluid);
#pragma once

#include "rigid_body_engine.h"

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace armour {

// This rank's fluid cells, plain arrays in SI units.
struct CellSet {
    std::vector<Eigen::Vector3d> centres; // m
    std::vector<double> volumes;          // m^3
    // Optional cell shapes for the exact solid fraction: the mesh's points
    // and each cell's faces as loops of point indices; every cell convex (a
    // blockMesh hex). Left empty, each cell is the axis-aligned cube of edge
    // V^(1/3) about its centre, which is what a uniform blockMesh grid holds.
    std::vector<Eigen::Vector3d> points; // m
    std::vector<std::vector<int>> faces; // loops of indices into points
    // Per cell, its faces: f where face f's loop runs counter-clockwise seen
    // from outside the cell (OpenFOAM: the cell owns it), ~f where it runs
    // the other way (the cell is its neighbour).
    std::vector<std::vector<int>> cell_faces;
};

enum class MaskSource { exact_shape, clump_spheres };

// exact: chi = the fraction of the cell's volume inside the unit (exact for
// meshes, chords for spheres; solid_fraction.h). sampled_ramp: the former
// mask, a cosine ramp of the signed distance at the cell centre, about
// smoothing_cells wide (it over-counts edges and depends on where the unit
// sits in the grid: docs/coupling.md).
enum class SolidFraction { exact, sampled_ramp };

struct CouplerSettings {
    MaskSource mask = MaskSource::exact_shape;
    SolidFraction fraction = SolidFraction::exact;
    double smoothing_cells = 1.0;              // sampled_ramp only: ramp width, in cell sizes (V^(1/3))
    double fluid_density = kFreshWaterDensity; // kg/m^3, for the added mass
    double added_mass_coefficient = 0.0;       // C_a >= 0; 0 = plain explicit coupling
    // m/s^2: the gravity the ENGINE applies. The added-mass correction must
    // take the engine's own gravity load back out of the applied force, and
    // RigidBodyEngine does not expose its settings; keep equal to
    // EngineSettings::gravity.
    Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -kStandardGravity);
};

struct CellMask {
    std::vector<double> chi;               // solid fraction in [0, 1]
    std::vector<int> body;                 // owning body, -1 where chi = 0
    std::vector<Eigen::Vector3d> velocity; // m/s, rigid-body velocity at the cell centre
    std::vector<Eigen::Vector3d> centroid; // m, of the solid part of an owned cell (ramp: its centre)
};

struct BodyLoads {
    std::vector<Eigen::Vector3d> force;  // N, per body, world frame
    std::vector<Eigen::Vector3d> torque; // N m, about each body's centre of mass
    // The mask's volume and first moment about the centre of mass, sum chi V
    // and sum chi V (x - x_c): rank-additive like force and torque, so that
    // after the sum over ranks centre_torque_on_mask() can use them.
    std::vector<double> mask_volume;                // m^3
    std::vector<Eigen::Vector3d> mask_first_moment; // m^4
};

// Takes each torque about the MASK's centroid x_m instead of the centre of
// mass x_c, M = sum chi V (x - x_m) x f = M_c - (x_m - x_c) x F, mapping the
// mask's centroid onto the centre of mass. The smoothed mask's centroid sits
// off x_c by a fraction of a cell whenever the unit's faces sit off the cell
// faces; about x_c a uniform force density (the hydrostatic -grad p of a
// submerged unit) would then give a spurious moment of F |x_m - x_c|, about
// 0.5 % of the buoyancy times the edge at 4 cells across: enough to tip a
// floating cube. About x_m a uniform density gives exactly none, as the
// continuum does about the centroid. Call once, on the loads summed over ranks.
void centre_torque_on_mask(BodyLoads &loads);

class Coupler {
  public:
    // body_unit[i] = index in `units` of engine body i.
    Coupler(RigidBodyEngine &engine, std::vector<UnitTemplate> units, std::vector<int> body_unit,
            CouplerSettings settings);
    ~Coupler();
    Coupler(const Coupler &) = delete;
    Coupler &operator=(const Coupler &) = delete;

    const CellMask &update_mask(const CellSet &cells);
    // What the last update_mask did: its cost as counts (tests assert them;
    // bench/run_mask_bench.sh times it).
    struct MaskWork {
        long bodies_recomputed = 0; // bodies whose cells were found anew (the others kept theirs)
        long cells_visited = 0;     // cells looked at in the bins near those bodies
        long cells_resolved = 0;    // of these, the ones culling left to a distance or a clipping
    };
    const MaskWork &last_mask_work() const;
    BodyLoads integrate_loads(const CellSet &cells, const std::vector<Eigen::Vector3d> &force_density) const;
    void advance(const BodyLoads &total, double dt_fluid);

    // What the scheme keeps between steps (each body's previous acceleration
    // and angular acceleration for the added-mass correction, its last
    // fluid force, force change and swing count for the stability check),
    // as plain numbers for a checkpoint; set_state takes them back.
    std::vector<double> state() const;
    void set_state(const std::vector<double> &values);
    // The exact fractions kept for units at rest (computed at an earlier
    // pose, within kRestTolerance) go: the next update_mask computes every
    // unit's at its pose. set_state does it, for a coupler restored from a
    // checkpoint has none kept; the run that writes the checkpoint calls it
    // and updates the mask, so that both go on with the same mask.
    void forget_kept_fractions();

  private:
    // Throws when the loads show the signature of an unstable exchange.
    void check_stability(const BodyLoads &total);

    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace armour
