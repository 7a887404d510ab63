// From a Scene to what an engine needs: unit templates (clumps built or read
// from the cache), materials, wall meshes and initial body poses, all checked.
#pragma once

#include "rigid_body_engine.h"
#include "scene.h"

#include <optional>
#include <string>
#include <vector>

namespace armour {

struct SceneSetup {
    EngineSettings settings;
    std::vector<UnitTemplate> units; // index = scene unit index
    std::vector<Wall> walls;
    std::vector<BodyInit> bodies;
    std::vector<double> unit_Dn; // m
    std::vector<int> unit_spheres;
};

// Dn: before a settle (fluid.settle_time > 0) placed units may stand this far
// above run.domain_max.z (the settle's DEM domain and side walls reach up to
// hold them); the settled scene is held to run.domain itself.
constexpr double kSettleHeadroom = 5.0;

// m: how far above run.domain_max.z the scene's placed units may stand:
// kSettleHeadroom x the largest Dn before a settle, else 0.
double settle_headroom(const Scene &scene, const SceneSetup &setup);

// Builds (or reads from `cache_dir`) every clump, makes the walls and places
// the bodies. Throws InputError naming the scene key for anything that cannot
// run: overlapping bodies (named in pairs), bodies outside the domain, a drop
// region too small for its units, a pattern wall that is not a slope.
SceneSetup build_scene(const Scene &scene, const std::string &cache_dir, bool progress);

// LIGGGHTS units whose clump cannot rest flat on some face (its rest gap,
// clump_evaluator.h, exceeds resting_overlap) and no rolling friction to stop
// the rocking that follows: one warning per unit template, naming the unit,
// the figures and the remedy; and LIGGGHTS units whose smallest spheres sink
// by more than half their radius under half the unit's weight (they may pass
// through walls as the unit tips). Empty for other engines.
std::vector<std::string> rocking_clump_warnings(const Scene &scene, const SceneSetup &setup);

// m: the Hertz overlap of the unit's median sphere on a plane of its own
// material under half the unit's weight (a unit standing on two spheres): a
// third sphere closer than this to the plane touches too.
double resting_overlap(const UnitTemplate &unit, const Material &material, double gravity);
// m: the Hertz overlap of a sphere of `radius` (m) pressed on a plane of its
// own material by `force` (N).
double sphere_overlap(double radius, const Material &material, double force);

// The factor by which the unit's exact shape must grow about its centre for
// every sphere of its clump to lie inside it (>= 1; a clump's spheres stand
// out of the exact faces): a settle in an exact-shape engine grows its units
// by it so that the layer it hands to a clump engine starts no clump inside
// a neighbour or a wall. Each sphere must fit one grown convex part that
// holds the unit's centre (a part that does not moves away as it grows);
// nullopt when no part holds it. A dolos's fluke spheres fit only its
// grown shank (3.25 x): a settle grows cubes only.
std::optional<double> growth_to_hold_clump(const UnitTemplate &unit);

// The default clump cache: $ARMOUR_CACHE, else $XDG_CACHE_HOME/armour-fsi,
// else ~/.cache/armour-fsi, else armour-fsi-cache in the temporary folder.
std::string default_cache_dir();

// The clump cache a command uses: `given` (its --cache) when set, else the default.
std::string cache_dir_or_default(const std::string &given);

// Wall surfaces (m, world frame), exposed for tests.
TriangleMesh plane_wall(const Eigen::Vector3d &point, const Eigen::Vector3d &normal, double size);
TriangleMesh slope_wall(const SceneWall &wall, const Eigen::Vector3d &domain_min,
                        const Eigen::Vector3d &domain_max);
TriangleMesh box_wall(const Eigen::Vector3d &min, const Eigen::Vector3d &max);

} // namespace armour
