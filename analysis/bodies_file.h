// Reading a run's bodies.h5, as results/body_recorder.h writes it.
//
// Description
//     The one reader of the rigid-body record for the run drivers, the
//     analyses, `armour compare` and the tests. It loads the whole record:
//     per-step time and per-step, per-body state, SI units as written:
//         time                         s
//         position                     m, centre of mass, world frame
//         orientation                  -, unit quaternion, unit frame -> world
//         velocity                     m/s
//         angular_velocity             rad/s, world frame
//         external_force, contact_force  N
//         external_torque              N m
//     and the root string attributes (scene, engine, dt, units_system, ...).
//     HDF5 stays inside bodies_file.cpp. The file is opened read-only with
//     HDF5's file locking off, so a record still open in a running solver
//     can be read (it holds every completed step).
//
// Usage
//     const BodiesFile rec = read_bodies_file("out/bodies.h5");
//     const Eigen::Vector3d last = rec.position.back()[0]; // last step, body 0
//     const std::string engine = rec.attribute("engine");
#pragma once

#include "rigid_body_engine.h"

#include <Eigen/Geometry>

#include <map>
#include <string>
#include <vector>

namespace armour {

struct BodiesFile {
    template <class T> using Series = std::vector<std::vector<T>>; // [step][body]

    std::vector<double> time; // s, one per step
    std::vector<int> unit;    // per body: index k of its unit shape, /units/<k>
    Series<Eigen::Vector3d> position, velocity, angular_velocity, external_force, external_torque,
        contact_force;
    Series<Eigen::Quaterniond> orientation;
    std::map<std::string, std::string> attributes; // root string attributes

    std::size_t steps() const { return time.size(); }
    std::size_t bodies() const { return unit.size(); }
    // The root attribute `name`, or "" when the file has none.
    std::string attribute(const std::string &name) const;
    // Keeps the first `steps` steps (all of them when there are fewer).
    void keep_steps(std::size_t steps);
    // The recorded state of every body at `step` (what the analyses sample).
    void states_at(std::size_t step, std::vector<BodyState> &states) const;
};

// Throws InputError("PATH: reason") when the file cannot be opened or lacks
// a dataset the recorder writes.
BodiesFile read_bodies_file(const std::string &path);

} // namespace armour
