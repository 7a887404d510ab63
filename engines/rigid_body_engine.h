// The one interface between armour-fsi and any rigid-body engine.
//
// Description
//     Everything the DEM driver and the fluid coupler need from an
//     engine: unit templates with exact mass properties, bodies, static walls,
//     per-body external loads (held until changed), advance in time, and the
//     state of each body in the unit's OWN frame (engines that work in a
//     principal frame convert). Plain types only: no LIGGGHTS, Bullet or
//     OpenFOAM type crosses this header. SI units throughout.
//
// Usage
//     std::unique_ptr<RigidBodyEngine> engine = make_engine("liggghts", settings); // engine_registry.h
//     int cube = engine->add_template(unit);
//     int body = engine->add_body({cube, pose, velocity, angular_velocity});
//     engine->add_wall(wall);
//     engine->set_external_load(body, force, torque);
//     engine->advance(0.01);                       // s, any span: the clock keeps the remainder
//     BodyState s = engine->state(body);
//     engine->save_state("OUT/checkpoints/0.5/engine");  // restart-capable engines (engine_registry.h)
//     other->load_state("OUT/checkpoints/0.5/engine");   // same scene, before its first advance
#pragma once

#include "clump.h"
#include "mass_properties.h"
#include "mesh.h"
#include "standard_conditions.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace armour {

// Position of the centre of mass (m) and orientation of the unit frame
// (unit frame -> world), as in x_world = position + orientation * x_unit.
struct Pose {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

struct BodyState {
    Pose pose;
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();         // m/s, of the centre of mass
    Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero(); // rad/s, world frame
    Eigen::Vector3d contact_force = Eigen::Vector3d::Zero();    // N, from walls and other bodies
    Eigen::Vector3d external_force = Eigen::Vector3d::Zero();   // N, as set
    Eigen::Vector3d external_torque = Eigen::Vector3d::Zero();  // N m, about the centre of mass
};

// Contact material. Pair values (friction, restitution) are combined per
// pair as the engine allows; see the adapter's documentation.
struct Material {
    std::string name;
    double youngs_modulus = 5e7;   // Pa
    double poisson_ratio = 0.25;   // -
    double restitution = 0.5;      // -, normal coefficient of restitution
    double friction = 0.6;         // -, Coulomb (sliding)
    double rolling_friction = 0.0; // -, 0 = off
};

// A pair override: friction and restitution between materials a and b.
struct MaterialPair {
    std::string a, b;
    double restitution = -1.0; // < 0: not overridden
    double friction = -1.0;
    double rolling_friction = -1.0;
};

enum class ContactModel { hooke, hertz };

struct UnitTemplate {
    std::string name;
    Clump clump;                            // spheres in the unit frame (DEM)
    TriangleMesh mesh;                      // exact shape in the unit frame
    std::vector<TriangleMesh> convex_parts; // exact convex pieces (exact-shape engines)
    MassProperties props;                   // exact, unit frame, about the centroid at the origin
    int material = 0;                       // index into EngineSettings::materials
};

struct BodyInit {
    int unit = 0; // template index
    Pose pose;
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
    Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
    std::array<bool, 3> fixed_translation{{false, false, false}}; // world x, y, z held
    std::array<bool, 3> fixed_rotation{{false, false, false}};    // rotation about world x, y, z held
    // m, world, at the initial pose: the body point that fixed_translation
    // holds (a hinge or slider off the centre of mass, as OpenFOAM's sixDoF
    // centreOfRotation). Empty: the centre of mass. Engines that cannot
    // hold a point off the centre of mass throw InputError.
    std::optional<Eigen::Vector3d> pivot;
};

// A static wall: a closed or open triangle surface (planes are big quads).
struct Wall {
    std::string name;
    TriangleMesh surface; // m, world frame; normals towards the bodies' side
    int material = 0;
    bool oriented = true; // false: the normals may face either way (an STL file's)
    // Unoriented but consistently wound (every shared edge run once each
    // way): the normals all face one of its sides, not known which.
    bool wound = false;
};

struct EngineSettings {
    ContactModel contact = ContactModel::hertz;
    double characteristic_velocity = 1.0; // m/s, sets the hooke stiffness and the Hertz stiffness used for dt
    std::vector<Material> materials;
    std::vector<MaterialPair> pairs;
    Eigen::Vector3d domain_min = Eigen::Vector3d::Constant(-10.0);          // m
    Eigen::Vector3d domain_max = Eigen::Vector3d::Constant(10.0);           // m
    Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -kStandardGravity); // m/s^2
    double time_step = 0.0;       // s; 0 = the default (safety factor x stability limit)
    bool force_time_step = false; // accept a step above the stability limit (stability studies)
    int contact_iterations = 0;   // rigid contacts' solver iterations per step (bullet); 0 = the engine's own
    std::string work_dir;         // where the engine may write its own files (logs, meshes)
};

// What the engine will use and why (recorded in every summary).
struct TimeStepReport {
    double limit = 0.0;            // s, stability limit
    double rayleigh = 0.0;         // s, Rayleigh time of the smallest sphere (Hertz), 0 otherwise
    double contact_duration = 0.0; // s, at the characteristic velocity
    double used = 0.0;             // s
    bool forced = false;           // true if used > limit by request
    std::string rule;              // how the limit and the default were computed
};

class RigidBodyEngine {
  public:
    virtual ~RigidBodyEngine() = default;
    virtual std::string name() const = 0;

    virtual int add_template(const UnitTemplate &unit) = 0;
    virtual int add_body(const BodyInit &body) = 0;
    virtual void add_wall(const Wall &wall) = 0;
    // Held until changed; the force acts at the centre of mass.
    virtual void set_external_load(int body, const Eigen::Vector3d &force, const Eigen::Vector3d &torque) = 0;
    virtual void set_gravity(const Eigen::Vector3d &gravity) = 0;

    // The clock. Engines move in whole steps of time_step(): a partial step
    // would integrate contacts with a different step than the one their
    // stiffness and damping (and LIGGGHTS' neighbour lists) were set for.
    // So the requested time is kept apart from the engine's own, and each
    // call runs the whole steps that bring time() nearest to it: after any
    // sequence of spans, |time() - requested_time()| <= time_step() / 2,
    // and a span shorter than half a step runs nothing now but counts later.
    void advance(double span);                           // s, > 0 (0 allowed)
    void advance_to(double t);                           // s, absolute; t >= requested_time()
    double time() const;                                 // s, steps() x time_step()
    double requested_time() const { return requested_; } // s, the sum of the spans asked for
    long steps() const { return steps_; }

    virtual int body_count() const = 0;
    virtual BodyState state(int body) const = 0;
    virtual double time_step() const = 0; // s, the step in use
    virtual TimeStepReport time_step_report() const = 0;

    // Restart (EngineCapabilities::restart). save_state writes into the
    // existing folder `dir` everything the next steps depend on: bodies,
    // contacts, held loads, gravity and the clock. load_state reads it into
    // an engine built from the same scene (templates, walls and bodies
    // added) that has not advanced yet. Engines without restart throw
    // InputError naming themselves.
    void save_state(const std::string &dir) const;
    void load_state(const std::string &dir);

  protected:
    // The engine's own part of save_state/load_state (the clock is the base's).
    virtual void write_state(const std::string &dir) const;
    virtual void read_state(const std::string &dir);

    // Runs `steps` (>= 1) steps of time_step(); steps() and time() already
    // count them, so messages about the end of this call can use time().
    virtual void run_steps(long steps) = 0;

  private:
    long steps_ = 0;
    double requested_ = 0.0;
};

// Doubles as exact text (hexadecimal floating point, one per line), for
// state files that must read back bit for bit; integers up to 2^53 fit.
// read_state_values throws InputError naming the file.
void write_state_values(const std::string &path, const std::vector<double> &values);
std::vector<double> read_state_values(const std::string &path);

} // namespace armour
