// Random placement of a [[pattern]] (placement = "random"): the shipped
// stability scene (scenes/stability_cubes.toml, 99 cubes in two layers on a
// 1:1.5 slope between side walls, over a toe step) placed by several seeds.
// Each pose is reproducible from its seed, clear of every other unit and of
// every wall as the engine collides it, and turned at random. The settled
// layer's packing and porosity are tested in test_stability.cpp.
#include "collider.h"
#include "mesh.h"
#include "scene.h"
#include "scene_setup.h"
#include "slope_profile.h"
#include "stl_io.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

constexpr double kDn = 0.04;   // m, the scene's cube
constexpr double kGap = 0.002; // m, the scene's pattern.0.gap
constexpr int kUnits = 5 * 9;  // 5 rows of 5 + 4: the CI-sized scene of test_stability

// The shipped scene (placed at random) with 5 rows instead of 11: the
// CI-sized layer of test_stability, placed in one piece (the placement
// alone: a settle's stages place a few of its rows each).
armour::Scene stability_scene(std::vector<std::string> overrides) {
    overrides.insert(overrides.begin(), {"pattern.0.rows=5", "fluid.settle_stages=1"});
    return armour::load_scene(std::string(ARMOUR_SOURCE_DIR) + "/scenes/stability_cubes.toml", overrides);
}

armour::SceneSetup random_setup(std::uint64_t seed, std::vector<std::string> more = {}) {
    more.push_back("pattern.0.placement=\"random\"");
    more.push_back("pattern.0.seed=" + std::to_string(seed));
    return armour::build_scene(stability_scene(more), ARMOUR_TEST_CACHE, false);
}

// m: the smallest gap between the clump spheres of bodies a and b (< 0: they overlap).
double sphere_gap(const armour::SceneSetup &setup, const armour::BodyInit &a, const armour::BodyInit &b) {
    double gap = HUGE_VAL;
    for (const auto &sa : setup.units[a.unit].clump)
        for (const auto &sb : setup.units[b.unit].clump)
            gap = std::min(gap, (a.pose.position + a.pose.orientation * sa.center - b.pose.position -
                                 b.pose.orientation * sb.center)
                                        .norm() -
                                    sa.radius - sb.radius);
    return gap;
}

// m: the smallest gap between body b's clump spheres and any wall triangle.
double wall_gap(const armour::SceneSetup &setup, const armour::BodyInit &b) {
    double gap = HUGE_VAL;
    for (const auto &s : setup.units[b.unit].clump) {
        const Eigen::Vector3d c = b.pose.position + b.pose.orientation * s.center;
        for (const auto &w : setup.walls)
            for (const auto &t : w.surface.triangles) {
                const auto &v = w.surface.vertices;
                gap = std::min(gap,
                               (c - armour::closest_point_on_triangle(c, v[t[0]], v[t[1]], v[t[2]])).norm() -
                                   s.radius);
            }
    }
    return gap;
}

// m: the smallest gap between any two units' clump spheres, and between any
// unit's and a wall.
std::pair<double, double> closest_gaps(const armour::SceneSetup &setup) {
    double closest = HUGE_VAL, nearest_wall = HUGE_VAL;
    for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
        nearest_wall = std::min(nearest_wall, wall_gap(setup, setup.bodies[i]));
        for (std::size_t j = i + 1; j < setup.bodies.size(); ++j)
            closest = std::min(closest, sphere_gap(setup, setup.bodies[i], setup.bodies[j]));
    }
    return {closest, nearest_wall};
}

// rad: the angle between the slope's normal and the nearest of the cube's
// face normals, 0 for a cube lying flat on the slope, at most 54.7 deg.
double tilt(const Eigen::Quaterniond &orientation, const Eigen::Vector3d &normal) {
    const Eigen::Matrix3d r = orientation.toRotationMatrix();
    double largest = 0.0;
    for (int k = 0; k < 3; ++k)
        largest = std::max(largest, std::abs(r.col(k).dot(normal)));
    return std::acos(std::min(1.0, largest));
}

// A pose turned at random, its centre `distance` m from the origin in a random direction.
armour::BodyInit random_pose(std::mt19937_64 &rng, double distance) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    armour::BodyInit b;
    b.pose.orientation = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized());
    b.pose.position = distance * Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    return b;
}

} // namespace

// The same seed gives the same poses, bit for bit; another seed other ones.
TEST(RandomPlacement, ASeedGivesItsPosesAndAnotherSeedOthers) {
    const armour::SceneSetup a = random_setup(3), b = random_setup(3), c = random_setup(4);
    ASSERT_EQ(a.bodies.size(), static_cast<std::size_t>(kUnits));
    ASSERT_EQ(b.bodies.size(), a.bodies.size());
    ASSERT_EQ(c.bodies.size(), a.bodies.size());
    int moved = 0;
    for (std::size_t i = 0; i < a.bodies.size(); ++i) {
        EXPECT_EQ(a.bodies[i].pose.position, b.bodies[i].pose.position) << i;
        EXPECT_EQ(a.bodies[i].pose.orientation.coeffs(), b.bodies[i].pose.orientation.coeffs()) << i;
        // Another seed: another turn (more than 1 degree) for every unit.
        EXPECT_GT(a.bodies[i].pose.orientation.angularDistance(c.bodies[i].pose.orientation),
                  1.0 * M_PI / 180)
            << i;
        moved += (a.bodies[i].pose.position - c.bodies[i].pose.position).norm() > 0.01 * kDn ? 1 : 0;
    }
    EXPECT_GT(moved, kUnits / 2);
}

// Over several seeds, including large ones: no two units' clumps overlap and
// every unit clears every wall (the slope's face, its toe step and side
// walls, the flume's ends), each by the pattern's gap less a rounding, as the
// DEM collides them (build_scene's own check allows resting overlaps; this
// one does not).
TEST(RandomPlacement, UnitsClearEachOtherAndTheWalls) {
    const armour::SlopeFrame frame = *armour::slope_frame(stability_scene({}));
    for (const std::uint64_t seed : {1ull, 2ull, 17ull, 4000000007ull}) {
        const armour::SceneSetup setup = random_setup(seed);
        ASSERT_EQ(setup.bodies.size(), static_cast<std::size_t>(kUnits)) << seed;
        const auto [closest, nearest_wall] = closest_gaps(setup);
        std::printf("seed %llu: closest units %.3g mm apart, closest wall %.3g mm\n",
                    static_cast<unsigned long long>(seed), 1e3 * closest, 1e3 * nearest_wall);
        EXPECT_GE(closest, kGap - 1e-9) << seed;
        EXPECT_GE(nearest_wall, 0.0) << seed;
        // No cube reaches below its half-size (less the clump's rounding).
        for (const auto &b : setup.bodies)
            EXPECT_GT(frame.local(b.pose.position).z(), 0.45 * kDn) << seed;
    }
}

// The units are turned at random: their tilt from the slope (the angle from
// the nearest face normal to the slope's normal) spreads as for orientations
// drawn uniformly (reference: 200 000 of Eigen's UnitRandom). A grid lies
// flat: tilt 0 for every unit. Rejected draws (a unit that would cut a wall
// or a neighbour is drawn again) favour flatter units a little: the mean may
// sit below the uniform's, within 20 %.
TEST(RandomPlacement, OrientationsSpreadAsUniformRotations) {
    const armour::SlopeFrame frame = *armour::slope_frame(stability_scene({}));
    std::srand(12345);
    double uniform_mean = 0.0, uniform_sq = 0.0;
    const int draws = 200000;
    for (int k = 0; k < draws; ++k) {
        const double t = tilt(Eigen::Quaterniond::UnitRandom(), frame.normal);
        uniform_mean += t / draws;
        uniform_sq += t * t / draws;
    }
    const double uniform_sd = std::sqrt(uniform_sq - uniform_mean * uniform_mean);
    for (const std::uint64_t seed : {1ull, 5ull}) {
        const armour::SceneSetup setup = random_setup(seed);
        double mean = 0.0, sq = 0.0;
        for (const auto &b : setup.bodies) {
            const double t = tilt(b.pose.orientation, frame.normal);
            mean += t / kUnits;
            sq += t * t / kUnits;
        }
        const double sd = std::sqrt(sq - mean * mean);
        std::printf("seed %llu: tilt mean %.1f deg sd %.1f deg (uniform rotations: %.1f, %.1f)\n",
                    static_cast<unsigned long long>(seed), mean * 180 / M_PI, sd * 180 / M_PI,
                    uniform_mean * 180 / M_PI, uniform_sd * 180 / M_PI);
        // 99 units: the mean's sampling error is uniform_sd / sqrt(99) = 1.1 deg.
        EXPECT_NEAR(mean, uniform_mean, 0.2 * uniform_mean) << seed;
        EXPECT_GT(sd, 0.6 * uniform_sd) << seed;
        EXPECT_LT(sd, 1.4 * uniform_sd) << seed;
    }
    const armour::SceneSetup grid =
        armour::build_scene(stability_scene({"pattern.0.placement=\"grid\""}), ARMOUR_TEST_CACHE, false);
    for (const auto &b : grid.bodies)
        EXPECT_LT(tilt(b.pose.orientation, frame.normal), 1e-9);
}

// A slope 1.06 Dn wide holds one cube facing it (the grid) but no turned
// one with the 0.05 Dn gap to each side wall (a cube is at least 1 Dn
// across in any orientation): refused naming the key, with the remedy.
TEST(RandomPlacement, ASlotNoTurnedUnitFitsIsRefusedNamingTheKey) {
    const std::vector<std::string> narrow = {"wall.0.width=0.0425", "pattern.0.columns=1"};
    std::vector<std::string> grid = narrow;
    grid.push_back("pattern.0.placement=\"grid\"");
    EXPECT_NO_THROW(armour::build_scene(stability_scene(grid), ARMOUR_TEST_CACHE, false));
    try {
        random_setup(1, narrow);
        FAIL() << "a turned cube was placed in a slope 1.06 Dn wide";
    } catch (const armour::InputError &e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("stability_cubes.toml: key 'pattern.0.placement'"), std::string::npos) << what;
        EXPECT_NE(what.find("cuts a wall"), std::string::npos) << what;
        EXPECT_NE(what.find("fewer rows, columns"), std::string::npos) << what;
    }
}

// Placement "seated" takes the slots from the toe up and slides each unit
// down the face into the first trough, as a placer lets a unit down onto the
// rows below: the same seed gives the same poses; every unit still clears the
// others and the walls; and the pile stands closer to the face and lower down
// it than the random placement of the same seed (whose loose pile the settle
// slides a median 1.6 Dn down the face: docs/results/stability_one_layer_dn4).
TEST(SeatedPlacement, UnitsClearEverythingAndSitLowerThanTheRandomPile) {
    const armour::SlopeFrame frame = *armour::slope_frame(stability_scene({}));
    const auto seated = [](std::uint64_t seed) {
        return armour::build_scene(
            stability_scene({"pattern.0.placement=\"seated\"", "pattern.0.seed=" + std::to_string(seed)}),
            ARMOUR_TEST_CACHE, false);
    };
    const armour::SceneSetup again = seated(1);
    for (const std::uint64_t seed : {1ull, 2ull, 17ull}) {
        const armour::SceneSetup setup = seated(seed), loose = random_setup(seed);
        ASSERT_EQ(setup.bodies.size(), static_cast<std::size_t>(kUnits)) << seed;
        const auto [closest, nearest_wall] = closest_gaps(setup);
        for (std::size_t i = 0; seed == 1 && i < setup.bodies.size(); ++i) {
            EXPECT_EQ(setup.bodies[i].pose.position, again.bodies[i].pose.position) << i;
            EXPECT_EQ(setup.bodies[i].pose.orientation.coeffs(), again.bodies[i].pose.orientation.coeffs())
                << i;
        }
        EXPECT_GE(closest, kGap - 1e-9) << seed;
        EXPECT_GE(nearest_wall, 0.0) << seed;
        // Dn: the mean centre out of the face and up it, seated and random.
        double out = 0.0, up = 0.0, loose_out = 0.0, loose_up = 0.0;
        for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
            const Eigen::Vector3d a = frame.local(setup.bodies[i].pose.position),
                                  b = frame.local(loose.bodies[i].pose.position);
            out += a.z() / (kDn * kUnits);
            up += a.x() / (kDn * kUnits);
            loose_out += b.z() / (kDn * kUnits);
            loose_up += b.x() / (kDn * kUnits);
        }
        std::printf("seed %llu: closest units %.3g mm, wall %.3g mm; mean centre out of the face %.2f Dn "
                    "(random %.2f), up it %.2f Dn (random %.2f)\n",
                    static_cast<unsigned long long>(seed), 1e3 * closest, 1e3 * nearest_wall, out, loose_out,
                    up, loose_up);
        EXPECT_LT(out, loose_out) << seed;
        EXPECT_LT(up, loose_up) << seed;
    }
}

// pattern.0.clear_of_toe: the random pile lifts its lowest units out of
// the face, whose normal leans seaward, and sets some of their centres over
// the toe in front of the face's foot (the study's layers: 6-9 of 99); with
// the key each such unit is set higher up the face instead: no centre
// seaward of the foot, on the scene's toe step and on one 2 Dn high, every
// unit still clear of the others and the walls, while the same seeds without
// it set some there (the check can fail).
TEST(RandomPlacement, ClearOfToeSetsNoCentreSeawardOfTheFoot) {
    const armour::SlopeFrame frame = *armour::slope_frame(stability_scene({}));
    const auto seaward = [&](const armour::SceneSetup &setup) {
        return std::count_if(setup.bodies.begin(), setup.bodies.end(), [&](const armour::BodyInit &b) {
            return frame.seaward_of_foot(b.pose.position);
        });
    };
    long loose_seaward = 0;
    for (const std::string toe : {"0.04", "0.08"})
        for (const std::uint64_t seed : {1ull, 2ull, 17ull}) {
            const armour::SceneSetup clear =
                random_setup(seed, {"pattern.0.clear_of_toe=true", "wall.0.toe_height=" + toe});
            ASSERT_EQ(clear.bodies.size(), static_cast<std::size_t>(kUnits)) << seed;
            EXPECT_EQ(seaward(clear), 0) << seed << " toe " << toe;
            const auto [closest, nearest_wall] = closest_gaps(clear);
            EXPECT_GE(closest, kGap - 1e-9) << seed;
            EXPECT_GE(nearest_wall, 0.0) << seed;
            loose_seaward += seaward(random_setup(seed, {"wall.0.toe_height=" + toe}));
        }
    EXPECT_GT(loose_seaward, 0);
    // A grid faces the slope from its first row up: the key is refused there.
    try {
        stability_scene({"pattern.0.placement=\"grid\"", "pattern.0.clear_of_toe=true"});
        ADD_FAILURE() << "clear_of_toe with a grid was read";
    } catch (const armour::InputError &e) {
        EXPECT_NE(std::string(e.what()).find("key 'pattern.0.clear_of_toe'"), std::string::npos) << e.what();
    }
}

// pattern.0.first_row with units already there (a settle in stages,
// fluid.settle_stages, places each stage's rows on the rows settled before,
// as [[body]]): rows 3-5 of the CI-sized layer placed over rows 1-2 of
// another seed set each unit clear of those bodies by the pattern's gap;
// placed without them, the same rows reach into where they stand (the
// check can fail). Both placements: 27 units, none below the third row.
TEST(RandomPlacement, LaterRowsClearTheUnitsAlreadyThere) {
    for (const std::string placement : {"random", "seated"}) {
        armour::Scene base = stability_scene(
            {"pattern.0.rows=2", "pattern.0.seed=5", "pattern.0.placement=\"" + placement + "\""});
        const armour::SceneSetup lower = armour::build_scene(base, ARMOUR_TEST_CACHE, false);
        ASSERT_EQ(lower.bodies.size(), 18u);
        armour::Scene upper = stability_scene(
            {"pattern.0.first_row=2", "pattern.0.seed=6", "pattern.0.placement=\"" + placement + "\""});
        const armour::SceneSetup alone = armour::build_scene(upper, ARMOUR_TEST_CACHE, false);
        for (const armour::BodyInit &b : lower.bodies) {
            armour::SceneBody body;
            body.unit = "cube";
            body.position = b.pose.position;
            const Eigen::Quaterniond q = b.pose.orientation;
            body.orientation = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
            upper.bodies.push_back(body);
        }
        const armour::SceneSetup both = armour::build_scene(upper, ARMOUR_TEST_CACHE, false);
        ASSERT_EQ(alone.bodies.size(), 27u);
        ASSERT_EQ(both.bodies.size(), 45u);
        double cleared = HUGE_VAL, reached = HUGE_VAL;
        for (std::size_t i = 18; i < both.bodies.size(); ++i)
            for (std::size_t j = 0; j < 18; ++j) {
                cleared = std::min(cleared, sphere_gap(both, both.bodies[i], both.bodies[j]));
                reached = std::min(reached, sphere_gap(both, alone.bodies[i - 18], both.bodies[j]));
            }
        std::printf("%s: rows 3-5 over rows 1-2: closest %.3g mm; placed without them %.3g mm\n",
                    placement.c_str(), 1e3 * cleared, 1e3 * reached);
        EXPECT_GE(cleared, kGap - 1e-9) << placement;
        EXPECT_LT(reached, kGap) << placement;
        EXPECT_GE(closest_gaps(both).second, 0.0) << placement;
    }
}

// The keys of a settle in stages, refused as read, naming the key.
TEST(RandomPlacement, StagesAndFirstRowsThatCannotBeBuiltAreRefused) {
    const std::vector<std::pair<std::vector<std::string>, std::string>> refused = {
        {{"pattern.0.first_row=5"}, "key 'pattern.0.first_row': 5 leaves no row to place: rows = 5"},
        {{"fluid.settle_stages=6"}, "key 'fluid.settle_stages': 6 stages for the pattern's 5 rows"},
        {{"fluid.settle_stages=2", "pattern.0.placement=\"grid\""},
         "key 'fluid.settle_stages': is for placement \"random\" or \"seated\""},
        {{"fluid.settle_stages=2", "fluid.settle_time=0"},
         "key 'fluid.settle_stages': stages of a settle need one"},
        {{"fluid.settle_stages=0"}, "key 'fluid.settle_stages'"},
    };
    for (const auto &[sets, message] : refused)
        try {
            stability_scene(sets);
            ADD_FAILURE() << sets.back() << " was read";
        } catch (const armour::InputError &e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        }
}

TEST(SeatedPlacement, ASlotNoTurnedUnitFitsIsRefusedNamingThePlacement) {
    try {
        armour::build_scene(
            stability_scene({"wall.0.width=0.0425", "pattern.0.columns=1", "pattern.0.placement=\"seated\""}),
            ARMOUR_TEST_CACHE, false);
        FAIL() << "a turned cube was placed in a slope 1.06 Dn wide";
    } catch (const armour::InputError &e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("key 'pattern.0.placement': \"seated\": the unit of layer 1, row 1"),
                  std::string::npos)
            << what;
    }
}

// An exact-shape engine (Bullet) collides the exact cube: placed against
// it, 2 rows (18 cubes), they pass build_scene's own check (no surface point
// of one deeper than 0.01 Dn inside another) and every corner of every cube
// lies at least the gap above the slope's face.
TEST(RandomPlacement, ExactShapesAreKeptApartToo) {
    const armour::SceneSetup setup = random_setup(6, {"run.engine=\"bullet\"", "pattern.0.rows=2"});
    ASSERT_EQ(setup.bodies.size(), 18u);
    const armour::SlopeFrame frame = *armour::slope_frame(stability_scene({}));
    double lowest = HUGE_VAL;
    for (const auto &b : setup.bodies)
        for (const Eigen::Vector3d &v : setup.units[b.unit].mesh.vertices)
            lowest = std::min(lowest, frame.local(b.pose.position + b.pose.orientation * v).z());
    EXPECT_GE(lowest, kGap - 1e-9);
}

// none_deeper_than (collider.h) decides most pairs of exact shapes by one face plane with every
// corner of the other unit beyond it; where it does, the point-by-point test it stands for must say
// the same. 2000 cube pairs in random poses 0.8-2 Dn apart, at the clearances placement and the
// overlap check use (-0.02 Dn, +0.01 Dn): the two agree on every one, and both kinds of answer occur.
TEST(RandomPlacement, ThePlaneShortcutAgreesWithThePointByPointTest) {
    const armour::SceneSetup setup = random_setup(6, {"run.engine=\"bullet\"", "pattern.0.rows=1"});
    const double Dn = setup.unit_Dn[0];
    const armour::Collider c = armour::make_collider(setup.units[0], armour::ShapeModel::convex_hulls, Dn);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int near = 0, apart = 0;
    for (int k = 0; k < 2000; ++k) {
        const armour::BodyInit a = random_pose(rng, 0.0), b = random_pose(rng, Dn * (1.4 + 0.6 * u(rng)));
        for (const double depth : {-0.02 * Dn, 0.01 * Dn}) {
            bool brute = true; // every surface point of a no deeper than `depth` in b
            for (const Eigen::Vector3d &q : c.points)
                brute = brute && armour::depth_inside(c, b.pose.orientation.inverse() *
                                                             (a.pose.position + a.pose.orientation * q -
                                                              b.pose.position)) <= depth;
            ASSERT_EQ(armour::none_deeper_than(a, c, b, c, depth), brute)
                << "pair " << k << " depth " << depth;
            (brute ? apart : near) += 1;
        }
    }
    EXPECT_GT(near, 100);
    EXPECT_GT(apart, 100);
}

// closer_than for clumps skips a sphere of one unit that stands farther from the other's centre
// than that unit's reach; the answer must be the sphere pairs' own. 2000 pairs of the scene's
// 47-sphere cube in random poses 0.8-2 Dn apart, at the clearances the placers use.
TEST(RandomPlacement, TheClumpReachShortcutAgreesWithEverySpherePair) {
    const armour::SceneSetup setup = random_setup(6, {"pattern.0.rows=1"});
    const armour::UnitTemplate &unit = setup.units[0];
    const double Dn = setup.unit_Dn[0];
    const armour::Collider c = armour::make_collider(unit, armour::ShapeModel::sphere_clumps, Dn);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int near = 0, apart = 0;
    for (int k = 0; k < 2000; ++k) {
        const armour::BodyInit a = random_pose(rng, 0.0), b = random_pose(rng, Dn * (1.4 + 0.6 * u(rng)));
        for (const double clearance : {0.0, 0.02 * Dn}) {
            bool brute = false;
            for (const auto &sa : unit.clump)
                for (const auto &sb : unit.clump)
                    brute = brute || ((a.pose.position + a.pose.orientation * sa.center) -
                                      (b.pose.position + b.pose.orientation * sb.center))
                                             .norm() < sa.radius + sb.radius + clearance;
            ASSERT_EQ(armour::closer_than(a, b, unit, c, clearance), brute) << "pair " << k;
            (brute ? near : apart) += 1;
        }
    }
    EXPECT_GT(near, 100);
    EXPECT_GT(apart, 100);
}

namespace {

// depth_behind_wall (collider.h), which checks a unit's exact shape against
// the walls before a coupled run: the shipped stability scene's slope wall,
// its 0.04 m toe step at x = 1.40 m (top z = 0.24 m) and its 1:1.5 face.
// A cube settled at the toe leans over the step's edge with its centre below
// the step's top: a corner above the edge and seaward of the step's face is
// outside the wall, though behind the face's plane (the nearest-triangle
// rule with the normal turned to the centre called it 7 mm inside, and
// refused the settled layer at the scene's 1 cm cells).
TEST(WallDepth, AStepsEdgeIsOutsideAboveAndInsideBelow) {
    armour::SceneWall slope;
    slope.type = "slope";
    slope.toe_x = 1.40;
    slope.floor_z = 0.20;
    slope.cot = 1.5;
    slope.height = 0.34;
    slope.width = 0.248;
    slope.toe_height = 0.04;
    armour::Wall wall;
    wall.surface = armour::slope_wall(slope, {0.0, -0.124, 0.0}, {2.0, 0.124, 0.62});
    const Eigen::Vector3d centre(1.42, 0.013, 0.222); // below the step's top
    // 7 mm seaward of the step's face, 10 mm above its top: outside.
    EXPECT_NEAR(armour::depth_behind_wall({1.393, 0.013, 0.25}, wall, centre), -0.01, 1e-9);
    // 3 mm landward of the face, 5 mm above the top: nearest to the edge
    // itself, both faces' nearest point; outside by the distance to it.
    EXPECT_NEAR(armour::depth_behind_wall({1.403, 0.0, 0.245}, wall, centre), -std::hypot(0.003, 0.005),
                1e-9);
    // Inside the step: 3 mm behind its face, 10 mm under its top.
    EXPECT_NEAR(armour::depth_behind_wall({1.397, 0.0, 0.23}, wall, centre), 0.003, 1e-9);
    // On the slope: 5 mm in front of the face, and 2 mm into it.
    const Eigen::Vector3d normal = Eigen::Vector3d(-1.0, 0.0, 1.5).normalized();
    const Eigen::Vector3d on_face(1.40 + 1.5 * 0.1, 0.05, 0.30);
    EXPECT_NEAR(armour::depth_behind_wall(on_face + 0.005 * normal, wall, centre), -0.005, 1e-9);
    EXPECT_NEAR(armour::depth_behind_wall(on_face - 0.002 * normal, wall, centre), 0.002, 1e-9);
    // A side wall, 1 mm through it.
    EXPECT_NEAR(armour::depth_behind_wall({1.6, 0.125, 0.45}, wall, centre), 0.001, 1e-9);
    // 8 mm into the face, 2 mm from a side wall: inside, by the face (the
    // side walls stand above the profile only; down through the solid they
    // were nearer, and read the point as 2 mm in front of them).
    const Eigen::Vector3d by_side(on_face.x(), 0.122, on_face.z());
    EXPECT_NEAR(armour::depth_behind_wall(by_side - 0.008 * normal, wall, centre), 0.008, 1e-9);

    // The same wall wound the other way, as an STL file may be: turned to the
    // body's centre, triangle by triangle; in front of the face and into it.
    armour::Wall unoriented = wall;
    unoriented.oriented = false;
    for (auto &t : unoriented.surface.triangles)
        std::swap(t[1], t[2]);
    const Eigen::Vector3d above_face = on_face + 0.03 * normal;
    EXPECT_NEAR(armour::depth_behind_wall(on_face + 0.005 * normal, unoriented, above_face), -0.005, 1e-9);
    EXPECT_NEAR(armour::depth_behind_wall(on_face - 0.002 * normal, unoriented, above_face), 0.002, 1e-9);

    // Written to an STL file and read back (vertices merged), as a scene's
    // STL wall is: consistently wound, so the body's centre picks the front
    // of the whole wall, and the step's edge reads as on the built wall with
    // the centre below the step's top.
    const std::string stl = testing::TempDir() + "wall_depth_step.stl";
    armour::write_stl(unoriented.surface, stl);
    armour::Wall from_file;
    from_file.surface = armour::read_stl(stl);
    std::remove(stl.c_str());
    from_file.oriented = false;
    from_file.wound = armour::consistently_wound(from_file.surface);
    ASSERT_TRUE(from_file.wound);
    const double kFloat = 1e-7; // m: binary STL stores float coordinates
    EXPECT_NEAR(armour::depth_behind_wall({1.393, 0.013, 0.25}, from_file, centre), -0.01, kFloat);
    EXPECT_NEAR(armour::depth_behind_wall({1.403, 0.0, 0.245}, from_file, centre), -std::hypot(0.003, 0.005),
                kFloat);
    EXPECT_NEAR(armour::depth_behind_wall({1.397, 0.0, 0.23}, from_file, centre), 0.003, kFloat);
    EXPECT_NEAR(armour::depth_behind_wall(on_face - 0.002 * normal, from_file, centre), 0.002, kFloat);
    EXPECT_NEAR(armour::depth_behind_wall(by_side - 0.008 * normal, from_file, centre), 0.008, kFloat);
    // A body on the other side of the same wall (under the berm's top):
    // its front is the other side.
    EXPECT_NEAR(armour::depth_behind_wall({1.30, 0.0, 0.23}, from_file, {1.30, 0.0, 0.20}), -0.01, kFloat);
    // Without the winding each nearest triangle turns to the centre, and the
    // point above the step's edge reads as 10 mm inside: why winding counts.
    armour::Wall turned = from_file;
    turned.wound = false;
    EXPECT_NEAR(armour::depth_behind_wall({1.393, 0.013, 0.25}, turned, centre), 0.01, kFloat);
    // One triangle turned over: no longer consistently wound.
    std::swap(turned.surface.triangles[0][1], turned.surface.triangles[0][2]);
    EXPECT_FALSE(armour::consistently_wound(turned.surface));
}

// A wall's convex edge pushed into a hull's face between the face's surface
// points (0.05 Dn apart): the start check must see it. A step with its edge
// along y at the origin (solid where x < 0 and z < 0) and the scene's cube
// turned 45 degrees about y, a face square to the edge's bisector and the
// edge delta into it. The face's points behind the step lie in a strip 2
// delta wide and read at most delta / sqrt(2) deep (seed 1's toe, docs/results/
// severe_sea_one_layer_at_rest: 0.16 mm read, 0.44+ mm in); the edge itself
// lies delta inside. Backed off by delta, the cube is clear.
TEST(WallDepth, AStepsEdgeInAHullsFaceIsSeenAtItsDepth) {
    const armour::SceneSetup setup = random_setup(6, {"run.engine=\"bullet\"", "pattern.0.rows=1"});
    const double Dn = setup.unit_Dn[0];
    const armour::Collider c = armour::make_collider(setup.units[0], armour::ShapeModel::convex_hulls, Dn);
    armour::Wall step;
    step.name = "step";
    auto &v = step.surface.vertices;
    v = {{-0.1, -0.1, 0.0}, {0.0, -0.1, 0.0}, {0.0, 0.1, 0.0}, {-0.1, 0.1, 0.0}, // top, normal +z
         {0.0, -0.1, -0.1}, {0.0, 0.1, -0.1}};                                   // face, normal +x
    step.surface.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 2}, {4, 2, 1}};
    for (const auto &t : step.surface.triangles) // the normals face the bodies' side
        ASSERT_GT((v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]).dot(Eigen::Vector3d(1.0, 0.0, 1.0)), 0.0);
    const Eigen::Vector3d bisector = Eigen::Vector3d(1.0, 0.0, 1.0).normalized();
    for (const double delta : {0.025 * Dn, -0.025 * Dn}) {
        armour::BodyInit b;
        b.unit = 0;
        // The cube's -z face turned to face -bisector, its plane delta beyond the edge.
        b.pose.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4.0, Eigen::Vector3d::UnitY()));
        b.pose.position = (0.5 * Dn - delta) * bisector + Eigen::Vector3d(0.0, 0.003, 0.0);
        const auto [depth, wall] = armour::body_wall_penetration(b, setup.units[0], c, {step});
        EXPECT_EQ(wall, 0);
        EXPECT_NEAR(depth, delta, 1e-9) << "delta " << delta;
        // The face's points alone: no deeper than delta / sqrt(2).
        double points = -HUGE_VAL;
        for (const Eigen::Vector3d &q : c.points)
            points = std::max(points, armour::depth_behind_wall(b.pose.position + b.pose.orientation * q,
                                                                step, b.pose.position));
        EXPECT_LE(points, std::max(delta, 0.0) / std::sqrt(2.0) + 1e-9) << "delta " << delta;
    }
}

} // namespace

// A layer the exact hulls settled for themselves (fluid.settled_by bullet)
// passes the start check as settled; a hull deeper in a wall than the check
// allows (the depth the exact shape stands out of its clump, ~2.1 mm for the
// 118-sphere cube) is refused naming the settle, since Bullet's triangle-mesh
// walls let a pressed hull sink (seed 5's staged settle: 2.25 mm). The kept
// at-rest layer of seed 2, its unit nearest a wall pushed down the slope's
// normal past that allowance; without the record, the message names no settle.
TEST(SettledPoses, AHullSettledIntoAWallIsRefusedNamingTheSettle) {
    armour::Scene scene = armour::load_scene(
        std::string(ARMOUR_SOURCE_DIR) + "/docs/results/severe_sea_one_layer_at_rest/layers/seed-2.toml",
        {"run.engine=\"bullet\""});
    ASSERT_EQ(scene.fluid->settled_by, "bullet");
    const armour::SceneSetup settled = armour::build_scene(scene, ARMOUR_TEST_CACHE, false);
    const armour::UnitTemplate &unit = settled.units[0];
    const armour::Collider c = armour::make_collider(unit, armour::ShapeModel::convex_hulls, kDn);
    const auto depth_of = [&](const armour::BodyInit &b) {
        return armour::body_wall_penetration(b, unit, c, settled.walls).first;
    };
    std::size_t nearest = 0;
    for (std::size_t i = 1; i < settled.bodies.size(); ++i)
        if (depth_of(settled.bodies[i]) > depth_of(settled.bodies[nearest]))
            nearest = i;
    const double allowed = armour::depth_outside_clump(unit.clump, c.points);
    armour::BodyInit pushed = settled.bodies[nearest];
    const Eigen::Vector3d inward = Eigen::Vector3d(1.0, 0.0, -1.5).normalized();
    for (int step = 0; step < 200 && depth_of(pushed) < allowed + 2e-4; ++step)
        pushed.pose.position += 1e-4 * inward;
    ASSERT_GE(depth_of(pushed), allowed + 2e-4);
    scene.bodies[nearest].position = pushed.pose.position;
    const std::string cut = "body " + std::to_string(nearest) + " (unit 'cube') cuts into wall";
    const std::string remedy =
        "(fluid.settled_by bullet left it so: a pressed unit can sink into a wall's triangle mesh";
    try {
        armour::build_scene(scene, ARMOUR_TEST_CACHE, false);
        ADD_FAILURE() << "a hull " << depth_of(pushed) << " m into a wall was accepted";
    } catch (const armour::InputError &e) {
        EXPECT_NE(std::string(e.what()).find(cut), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(remedy), std::string::npos) << e.what();
    }
    scene.fluid->settled_by.clear();
    try {
        armour::build_scene(scene, ARMOUR_TEST_CACHE, false);
        ADD_FAILURE() << "a hull " << depth_of(pushed) << " m into a wall was accepted";
    } catch (const armour::InputError &e) {
        EXPECT_NE(std::string(e.what()).find(cut), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find("settled_by"), std::string::npos) << e.what();
    }
}

namespace {

// The shipped scene's 11 rows placed at random stand as a loose pile higher
// than the layer they settle into: under the crest above the flume's top
// (0.62 m). Placed for a settle they may, up to kSettleHeadroom Dn above it,
// and the settle's engine domain and side walls reach up to hold them; the
// same pile without a settle is refused naming the key.
TEST(RandomPlacement, TheFullPileStandsAboveTheFlumeOnlyForASettle) {
    const armour::Scene scene =
        armour::load_scene(std::string(ARMOUR_SOURCE_DIR) + "/scenes/stability_cubes.toml", {});
    const armour::SceneSetup setup = armour::build_scene(scene, ARMOUR_TEST_CACHE, false);
    ASSERT_EQ(setup.bodies.size(), 99u);
    double top = -HUGE_VAL; // m, the pile's highest sphere
    for (const auto &b : setup.bodies)
        for (const auto &s : setup.units[b.unit].clump)
            top = std::max(top, (b.pose.position + b.pose.orientation * s.center).z() + s.radius);
    std::printf("the pile's top: %.4f m (flume top %.2f m)\n", top, scene.domain_max.z());
    EXPECT_GT(top, scene.domain_max.z());
    EXPECT_LE(top, scene.domain_max.z() + armour::kSettleHeadroom * kDn);
    EXPECT_GE(setup.settings.domain_max.z(), top);
    double walls_top = -HUGE_VAL;
    for (const auto &v : setup.walls[0].surface.vertices) // the slope, its side walls
        walls_top = std::max(walls_top, v.z());
    EXPECT_GE(walls_top, top);

    const armour::Scene unsettled =
        armour::load_scene(std::string(ARMOUR_SOURCE_DIR) + "/scenes/stability_cubes.toml",
                           {"fluid.settle_time=0", "fluid.settle_stages=1"});
    try {
        armour::build_scene(unsettled, ARMOUR_TEST_CACHE, false);
        FAIL() << "a pile above the flume's top was placed without a settle";
    } catch (const armour::InputError &e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("key 'pattern.0.placement'"), std::string::npos) << what;
        EXPECT_NE(what.find("leaves run.domain_min/domain_max"), std::string::npos) << what;
    }
}

// A settle in exact hulls for a clump run grows each cube until its clump's
// spheres all lie inside (growth_to_hold_clump, the settle's cubes): for the
// scene's 118-sphere cube the factor is its spheres' farthest reach along the
// cube's axes over the half edge (every sphere inside, the farthest
// touching). A dolos's flukes are convex parts that do not hold its centre,
// so its fluke spheres fit only its shank grown more than twice (measured
// 3.25 x): why a settle grows cubes only.
TEST(SettleGrowth, ACubeGrowsUntilItsClumpIsInsideADolosOnlyPastTwice) {
    const armour::SceneSetup setup = armour::build_scene(stability_scene({}), ARMOUR_TEST_CACHE, false);
    const armour::UnitTemplate &cube = setup.units[0];
    const std::optional<double> growth = armour::growth_to_hold_clump(cube);
    ASSERT_TRUE(growth.has_value());
    double reach = 0.0; // m from the centre, along the cube's axes (its unit frame)
    for (const auto &sphere : cube.clump)
        reach = std::max(reach, sphere.center.cwiseAbs().maxCoeff() + sphere.radius);
    EXPECT_NEAR(*growth, reach / (0.5 * kDn), 1e-12);
    // The spheres stand out of the faces (the corner spheres, by design),
    // by less than 0.05 Dn.
    EXPECT_GT(*growth, 1.0);
    EXPECT_LT(*growth, 1.1);
    std::printf("[ growth   ] the 118-sphere cube's clump reaches %.3g mm beyond its faces: grown %.4f x\n",
                1e3 * (reach - 0.5 * kDn), *growth);

    const armour::SceneSetup dolosse = armour::build_scene(
        armour::load_scene(std::string(ARMOUR_SOURCE_DIR) + "/scenes/slope_dolosse.toml", {}),
        ARMOUR_TEST_CACHE, false);
    const std::optional<double> dolos = armour::growth_to_hold_clump(dolosse.units[0]);
    ASSERT_TRUE(dolos.has_value());
    EXPECT_GT(*dolos, 2.0);
    std::printf("[ growth   ] the dolos's fluke spheres fit only its shank grown %.3g x\n", *dolos);

    // The inscribed clump of the same cube needs no growth: a layer the hulls
    // settle at their own size hands over to it as it is.
    const armour::SceneSetup inscribed = armour::build_scene(
        stability_scene({"unit.0.method=\"inscribed\"", "unit.0.spheres=118"}), ARMOUR_TEST_CACHE, false);
    const std::optional<double> none = armour::growth_to_hold_clump(inscribed.units[0]);
    ASSERT_TRUE(none.has_value());
    EXPECT_NEAR(*none, 1.0, 1e-12);
}

} // namespace
