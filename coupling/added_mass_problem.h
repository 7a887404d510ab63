// The added-mass model problem: the coupler on a free body in a synthetic fluid.
//
// Description
//     No CFD: the "measured" fluid load is what a partitioned coupling sees
//     for a body in an ideal fluid, so the coupler's added-mass scheme can be
//     checked against the analytic acceleration and its failure boundary
//     charted (bench/run_density_ratio.sh, tests/test_coupler.cpp).
//
// Usage
//     AddedMassProblem p;  p.density_ratio = 0.3;  p.coupler_added_mass_coefficient = 0.5;
//     AddedMassResult r = run_added_mass_problem(p);   // r.diverged, r.max_relative_error
#pragma once

#include "standard_conditions.h"

#include <vector>

namespace armour {

// Added-mass model problem (no CFD): a cube released from rest in still
// fluid whose measured load is buoyancy minus the added-mass reaction to the
// body's acceleration over the PREVIOUS fluid step,
//     F_n = -rho_f V g - m_a,true a_{n-1},   m_a,true = C_true rho_f V,
// exactly what a partitioned CFD coupling measures for a body in an ideal
// fluid. The coupler (with its own C_a) turns it into the applied load and
// advances a free-body engine. Sweep density_ratio to chart the boundary
// where plain explicit coupling (C_a = 0) fails: rho_s / rho_f < C_true.
struct AddedMassProblem {
    double density_ratio = 1.0;                // rho_s / rho_f
    double true_added_mass_coefficient = 0.5;  // of the synthetic fluid (0.5: sphere)
    double coupler_added_mass_coefficient = 0; // C_a given to the coupler; 0 = plain explicit
    double fluid_density = kFreshWaterDensity; // kg/m^3
    double edge = 1.0;                         // m, cube edge
    double dt_fluid = 1e-3;                    // s
    int steps = 40;                            // fluid steps
    int substeps = 10;                         // engine steps per fluid step
};

struct AddedMassResult {
    std::vector<double> acceleration; // m/s^2, vertical, per fluid step (velocity change / dt)
    double analytic = 0.0;            // m/s^2, (rho_s - rho_f) g_z V / (m + m_a,true)
    double first_error = 0.0;         // |a_1 - analytic|
    double last_error = 0.0;          // |a_N - analytic|
    double max_relative_error = 0.0;  // max_n |a_n - analytic| / |analytic|
    bool diverged = false;            // the error grew from the first step to the last, or stopped
    bool stopped = false;             // Coupler::advance refused to go on (an unstable exchange)
};

AddedMassResult run_added_mass_problem(const AddedMassProblem &problem);

} // namespace armour
