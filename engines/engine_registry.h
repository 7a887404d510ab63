// Engines by name, with what each can do: the one place that knows them all.
//
// Description
//     Each engine adapter describes itself in an EngineStyle (its name, a
//     one-line summary, its capabilities and its factory), defined in the
//     adapter's own file; the registry lists those styles (engine_registry.cpp,
//     in the habit of LAMMPS' style lists: an explicit list, because a
//     self-registering static object in a static library is dropped by the
//     linker when nothing else refers to its file). Callers choose an engine
//     by what it can do (find_engine_style) or by the name a scene gives
//     (make_engine), never by comparing names.
//
// Usage
//     auto engine = make_engine(scene.engine, settings);        // run.engine
//     if (engine_style(scene.engine).capabilities.shape == ShapeModel::sphere_clumps) ...
//     const EngineStyle *exact = find_engine_style([](const EngineCapabilities &c) {
//         return c.shape == ShapeModel::convex_hulls; });
//     `armour engines` prints every style with its capabilities.
#pragma once

#include "rigid_body_engine.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace armour {

// How bodies touch: not at all, through spring-dashpot overlaps of spheres
// (soft: a stability limit on the step, contacts vibrate), or through
// rigid-contact impulses (no stability limit of that kind).
enum class ContactKind { none, spring_dashpot, rigid_impulse };

// Which geometry of a unit the engine collides: none, the sphere clump, or
// the convex parts (or the hull of the exact mesh).
enum class ShapeModel { none, sphere_clumps, convex_hulls };

struct EngineCapabilities {
    ContactKind contacts = ContactKind::none;
    std::vector<ContactModel> contact_models; // the laws EngineSettings::contact may pick; empty: ignored
    ShapeModel shape = ShapeModel::none;
    // Deterministic and serial: an MPI job runs one identical replica per
    // interFoam rank, fed the same summed loads (checked by the plugin).
    bool replica_per_rank = false;
    bool pivot = false;   // holds a body point off the centre of mass (BodyInit::pivot)
    bool restart = false; // saves and restores its state
};

struct EngineStyle {
    std::string name;    // as run.engine names it
    std::string summary; // one line
    EngineCapabilities capabilities;
    std::function<std::unique_ptr<RigidBodyEngine>(const EngineSettings &)> make;
};

// Every style of this build, in the order a capability query prefers them.
const std::vector<EngineStyle> &engine_styles();

// Their names, in that order (what run.engine accepts).
std::vector<std::string> engine_style_names();

// Throws InputError naming run.engine and listing the styles of this build.
const EngineStyle &engine_style(const std::string &name);

// The first style whose capabilities satisfy `wanted`, or nullptr.
const EngineStyle *find_engine_style(const std::function<bool(const EngineCapabilities &)> &wanted);

std::unique_ptr<RigidBodyEngine> make_engine(const std::string &name, const EngineSettings &settings);

// One line per style: name, capabilities, summary (`armour engines`).
std::string describe_engine_styles();

} // namespace armour
