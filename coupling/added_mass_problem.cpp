// The added-mass model problem (see added_mass_problem.h).
#include "added_mass_problem.h"

#include "coupler.h"
#include "free_body_engine.h"
#include "shapes.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace armour {

AddedMassResult run_added_mass_problem(const AddedMassProblem &problem) {
    if (!(problem.density_ratio > 0.0) || !(problem.fluid_density > 0.0) || !(problem.edge > 0.0) ||
        !(problem.dt_fluid > 0.0) || problem.steps < 1 || problem.substeps < 1 ||
        problem.true_added_mass_coefficient < 0.0 || problem.coupler_added_mass_coefficient < 0.0)
        throw std::invalid_argument("run_added_mass_problem: every parameter must be positive");

    const double rho_f = problem.fluid_density;
    const Shape cube = make_cube_shape(problem.edge, 0.0, problem.density_ratio * rho_f);
    UnitTemplate unit;
    unit.name = "cube";
    unit.mesh = cube.mesh;
    unit.props = cube.props;

    EngineSettings es;
    es.time_step = problem.dt_fluid / problem.substeps;
    auto engine = make_free_body_engine(es);
    engine->add_template(unit);
    engine->add_body(BodyInit{});

    CouplerSettings cs;
    cs.fluid_density = rho_f;
    cs.added_mass_coefficient = problem.coupler_added_mass_coefficient;
    cs.gravity = es.gravity;
    Coupler coupler(*engine, {unit}, {0}, cs);

    const double V = unit.props.volume;
    const double m = unit.props.mass;
    const double m_a = problem.true_added_mass_coefficient * rho_f * V;
    const Eigen::Vector3d g = es.gravity;
    AddedMassResult result;
    result.analytic = (m - rho_f * V) * g.z() / (m + m_a);

    Eigen::Vector3d a_prev = Eigen::Vector3d::Zero(); // the body's true acceleration, last step
    BodyLoads loads;
    loads.force.resize(1);
    loads.torque.assign(1, Eigen::Vector3d::Zero());
    for (int n = 0; n < problem.steps; ++n) {
        loads.force[0] = -rho_f * V * g - m_a * a_prev;
        const Eigen::Vector3d v0 = engine->state(0).velocity;
        const double t0 = engine->time();
        try {
            coupler.advance(loads, problem.dt_fluid);
        } catch (const std::runtime_error &) {
            result.stopped = true; // the coupler recognised the instability
            break;
        }
        a_prev = (engine->state(0).velocity - v0) / (engine->time() - t0);
        result.acceleration.push_back(a_prev.z());
    }
    if (result.acceleration.empty())
        result.acceleration.push_back(a_prev.z());
    auto error = [&](double a) { return std::abs(a - result.analytic); };
    result.first_error = error(result.acceleration.front());
    result.last_error = error(result.acceleration.back());
    // Neutral buoyancy (ratio 1) has a zero analytic value: measure against g there.
    const double scale = std::max(std::abs(result.analytic), 1e-6 * g.norm());
    for (double a : result.acceleration)
        result.max_relative_error = std::max(result.max_relative_error, error(a) / scale);
    // An error at rounding level is not growth, however it fluctuates.
    const double noise = 1e-9 * std::max(std::abs(result.analytic), g.norm());
    result.diverged = result.stopped || result.last_error > std::max(result.first_error, noise);
    return result;
}

} // namespace armour
