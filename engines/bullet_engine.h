// Bullet 3.24 (double precision) behind the RigidBodyEngine interface: the exact-shape reference.
//
// Description
//     Every unit is a btCompoundShape of convex hulls built from the unit's
//     `convex_parts` (cube: 1 hull; dolos: shank + 2 flukes) or, without
//     parts, from the convex hull of its exact `mesh` (concave units are then
//     filled in: a stand-in, named in the time-step report's rule).
//     What maps to what:
//       UnitTemplate::props    mass, centroid and principal inertia, used as
//                              given (exact CGAL values); Bullet never
//                              computes mass properties. The compound is built
//                              in the principal frame of props; states are
//                              turned back into the unit frame.
//       collision margin       every hull is shrunk by the margin (its face
//                              planes moved inward, vertices recomputed), so
//                              hull + margin = the true faces; edges and
//                              corners are rounded with the margin's radius.
//       Material / pairs       friction, restitution and rolling friction per
//                              pair exactly as the LIGGGHTS adapter: a pair
//                              override, else the smaller of the two values.
//                              A contact-added callback replaces Bullet's
//                              product rule for every new contact point.
//       Wall                   static btBvhTriangleMeshShape, margin 0.
//       external load          applied at every internal step, held until changed.
//       fixed_translation /    Bullet linear / angular factors (world axes);
//       fixed_rotation         locked components of the initial velocity are zeroed.
//       time step              fixed; advance(span) = whole steps. Bullet is an
//                              impulse solver with rigid contacts: no
//                              spring-dashpot stability limit applies. Default
//                              0.001 s; a step above 1/60 s is refused unless
//                              force_time_step. The report also carries the DEM
//                              contact numbers of the same materials when the
//                              units have sphere clumps (for comparison).
//       contact_force          sum of the last step's contact impulses on the
//                              body (normal + friction) / step, world frame.
//       restitution            exact per impact: a contact point that closes
//                              within the step counts as touching (Bullet's
//                              speculative rule would take gap/dt off the rebound).
//       wall contacts          a contact point inside a wall face is snapped
//                              onto it (normal and wall point) before every
//                              solve: Bullet's multipoint contacts leave
//                              tilted normals that make resting units creep.
//       solver iterations      sequential-impulse iterations per step:
//                              EngineSettings::contact_iterations (the
//                              scene's run.contact_iterations) when > 0,
//                              else BulletOptions::solver_iterations (20).
//     Sleeping is off. Contacts are rigid (Bullet's own; Young's modulus and
//     Poisson's ratio are not used). Details: docs/bullet.md.
//
// Usage
//     auto engine = make_bullet_engine(settings);          // or (settings, options)
//     int cube = engine->add_template(unit);               // unit.convex_parts = {cube mesh}
//     engine->add_body({cube, pose});  engine->add_wall(floor);
//     engine->advance(0.5);  BodyState s = engine->state(0);
#pragma once

#include "engine_registry.h"
#include "rigid_body_engine.h"

#include <memory>
#include <vector>

namespace armour {

struct BulletOptions {
    // m; 0 = per template min(0.04 m, kBulletMarginFraction x Dn), Dn = V^(1/3).
    double collision_margin = 0.0;
    // Sequential-impulse iterations per step (Bullet's default: 10). A settled
    // layer of 99 cubes held dry crept down the face at 20 and 30 (4 units a
    // quarter unit in 15 s at 30), and stood at 50 (docs/bullet.md).
    int solver_iterations = 50;
};

constexpr double kBulletMarginFraction = 0.005;
constexpr double kBulletDefaultStep = 0.001; // s, the largest default step
// The default step is min(kBulletDefaultStep, sqrt(Dn / g) / kBulletStepsPerUnitTime)
// for the smallest unit: Froude-scaled, so a scene and its model at another
// scale take the same steps per unit of their own time (docs/bullet.md "Time step").
constexpr double kBulletStepsPerUnitTime = 256.0;
constexpr double kBulletMaxStep = 1.0 / 60.0; // s, refused above unless force_time_step

std::unique_ptr<RigidBodyEngine> make_bullet_engine(const EngineSettings &settings);

// Name, capabilities and factory for the registry.
EngineStyle bullet_engine_style();
std::unique_ptr<RigidBodyEngine> make_bullet_engine(const EngineSettings &settings,
                                                    const BulletOptions &options);

// Vertices of the convex hull of `points` with every face plane moved inward
// by `margin` (m). Throws InputError (naming `what`) if the hull is thinner
// than 2 x margin.
std::vector<Eigen::Vector3d> shrunk_hull(const std::vector<Eigen::Vector3d> &points, double margin,
                                         const std::string &what);

// What Bullet holds for a body (for tests and reports); `engine` must come
// from make_bullet_engine.
struct BulletBodyInfo {
    double mass = 0.0;                                        // kg, 1 / Bullet's inverse mass
    Eigen::Vector3d local_inertia = Eigen::Vector3d::Zero();  // kg m^2, Bullet's, principal frame
    Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero(); // m, world
    Eigen::Quaterniond principal_to_world = Eigen::Quaterniond::Identity(); // Bullet's body frame
    double margin = 0.0;                                                    // m
    int hulls = 0;                                                          // children of the compound
};
BulletBodyInfo bullet_body_info(const RigidBodyEngine &engine, int body);

// The farthest point of the body's Bullet shape (hulls + margin) along the
// world direction `direction`, world frame.
Eigen::Vector3d bullet_support_point(const RigidBodyEngine &engine, int body,
                                     const Eigen::Vector3d &direction);

} // namespace armour
