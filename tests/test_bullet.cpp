// What is Bullet's own beyond the conformance suite (test_engines.cpp): the
// exact-shape facts (mass properties, frames, margin), pair friction, rigid
// restitution and edge landings.
#include "bullet_engine.h"
#include "engine_test_kit.h"
#include "shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

using namespace armour;
using namespace armour::test;

namespace {

// A unit as the exact-shape engine sees it: exact mesh, convex parts (cube:
// the cube itself; dolos: shank and flukes) and mass properties.
UnitTemplate exact_unit(const Shape &shape) {
    UnitTemplate unit;
    unit.name = shape.kind;
    unit.mesh = shape.mesh;
    unit.props = shape.props;
    unit.convex_parts = shape.convex_parts;
    return unit;
}

UnitTemplate cube_unit(double a, double density) {
    return exact_unit(make_cube_shape(a, 0.0, density));
}

UnitTemplate dolos_unit(double height, double waist, double density) {
    return exact_unit(make_dolos_shape(height, waist, density));
}

EngineSettings settings_for(std::vector<Material> materials) {
    EngineSettings s;
    s.materials = std::move(materials);
    s.domain_min = Eigen::Vector3d(-3, -3, -1);
    s.domain_max = Eigen::Vector3d(3, 3, 8);
    return s;
}

// The tilt experiment (engine_test_kit.h) with the cube and floor of given materials.
std::pair<double, double> tilt_cube(const EngineSettings &settings, int cube_material, int floor_material,
                                    double angle_deg, double seconds) {
    auto engine = make_bullet_engine(settings);
    UnitTemplate unit = cube_unit(1.0, 2400.0);
    unit.material = cube_material;
    BodyInit body;
    body.unit = engine->add_template(unit);
    body.pose.position = Eigen::Vector3d(0, 0, 0.5 + 1e-4);
    engine->add_body(body);
    engine->add_wall(floor_plane(3.0, floor_material));
    return tilt_and_hold(*engine, angle_deg, seconds);
}

} // namespace

TEST(BulletEngine, LockedAxesHoldTheirComponents) {
    EngineSettings settings = settings_for({concrete(0.5, 0.5)});
    auto engine = make_bullet_engine(settings);
    engine->add_template(cube_unit(0.5, 2400.0));
    BodyInit body;
    body.pose.position = Eigen::Vector3d(0, 0, 3);
    body.fixed_translation = {{false, false, true}}; // gravity cannot move it
    body.fixed_rotation = {{true, true, false}};     // only spin about z
    engine->add_body(body);
    engine->set_external_load(0, Eigen::Vector3d(10, 0, 0), Eigen::Vector3d(5, 5, 5));
    engine->advance(0.1);
    const BodyState s = engine->state(0);
    EXPECT_EQ(s.pose.position.z(), 3.0);
    EXPECT_GT(s.pose.position.x(), 0.0);
    EXPECT_EQ(s.angular_velocity.x(), 0.0);
    EXPECT_EQ(s.angular_velocity.y(), 0.0);
    EXPECT_GT(s.angular_velocity.z(), 0.0);
}

TEST(BulletEngine, PairFrictionIsTheOverrideElseTheSmaller) {
    // Cube 0.7 on floor 0.9: the smaller, 0.7 (product: 0.63).
    EngineSettings s = settings_for({concrete(0.3, 0.7, 5e9, "unit"), concrete(0.3, 0.9, 5e9, "floor")});
    const double onset_min = deg(std::atan(0.7));
    EXPECT_LT(std::abs(tilt_cube(s, 0, 1, onset_min - 0.5, 0.6).first), 1e-3);
    EXPECT_GT(tilt_cube(s, 0, 1, onset_min + 0.5, 0.6).first, 0.01);
    // With an override of 0.5 for the pair.
    s.pairs.push_back({"floor", "unit", -1.0, 0.5, -1.0});
    const double onset = deg(std::atan(0.5));
    EXPECT_LT(std::abs(tilt_cube(s, 0, 1, onset - 0.5, 0.6).first), 1e-3);
    EXPECT_GT(tilt_cube(s, 0, 1, onset + 0.5, 0.6).first, 0.01);
}

TEST(BulletEngine, BounceHeightRatioIsRestitutionSquared) {
    // A cube landing flat: all four corner contacts at once, symmetric. Several
    // drop heights, so that the last step before the impact ends at different
    // gaps (Bullet's own speculative contacts make the rebound depend on it).
    const double e = 0.6, a = 0.2;
    for (double drop : {0.13, 0.21, 0.37, 0.5}) {
        auto engine = make_bullet_engine(settings_for({concrete(e, 0.5)}));
        engine->add_template(cube_unit(a, 2400.0));
        BodyInit body;
        body.pose.position = Eigen::Vector3d(0, 0, 0.5 * a + drop);
        engine->add_body(body);
        engine->add_wall(floor_plane(2.0));
        double apex = -HUGE_VAL;
        bool bounced = false;
        for (int k = 0; k < 3000 && !(bounced && engine->state(0).velocity.z() < 0.0); ++k) {
            engine->advance(0.001);
            const BodyState s = engine->state(0);
            if (s.velocity.z() > 0.0 && s.contact_force.norm() == 0.0)
                bounced = true;
            if (bounced)
                apex = std::max(apex, s.pose.position.z());
        }
        ASSERT_TRUE(bounced);
        EXPECT_NEAR((apex - 0.5 * a) / drop, e * e, 0.05 * e * e) << "drop " << drop << " m";
    }
}

// Bullet integrates semi-implicitly (v += g dt, then x += v dt). In free
// flight that scheme conserves E_d = 1/2 m v^2 - m g.x + 1/2 m dt g.v exactly
// (the plain energy oscillates by m g v dt / 2, 0.35 % here), so E_d isolates
// what the contacts do.
double elastic_drop_energy_gain(double tilt, long steps) {
    auto engine = make_bullet_engine(settings_for({concrete(1.0, 0.0)}));
    const UnitTemplate unit = cube_unit(0.2, 2400.0);
    engine->add_template(unit);
    BodyInit body;
    body.pose.position = Eigen::Vector3d(0, 0, 0.1 + 0.1);
    body.pose.orientation =
        Eigen::Quaterniond(Eigen::AngleAxisd(tilt, Eigen::Vector3d(1, 1, 0).normalized()));
    engine->add_body(body);
    engine->add_wall(floor_plane(2.0));
    const double m = unit.props.mass, dt = engine->time_step();
    const Eigen::Vector3d g(0, 0, -9.81);
    auto energy = [&](const BodyState &s) {
        return 0.5 * m * s.velocity.squaredNorm() - m * g.dot(s.pose.position) +
               0.5 * m * dt * g.dot(s.velocity) +
               0.5 * unit.props.principal_moments[0] * s.angular_velocity.squaredNorm();
    };
    const double start = energy(engine->state(0));
    double highest = start;
    while (engine->steps() < steps) {
        engine->advance(dt);
        const BodyState s = engine->state(0);
        if (s.contact_force.norm() == 0.0) // between contacts
            highest = std::max(highest, energy(s));
    }
    EXPECT_GE(engine->steps(), steps);
    return highest / start - 1.0;
}

TEST(BulletEngine, NoEnergyGainLandingOnAnEdge) {
    // Flat landings are in the conformance suite. Landing on an edge, then rocking (it comes to rest: see
    // docs/bullet.md).
    const double tilted = elastic_drop_energy_gain(0.3, 20000);
    EXPECT_LT(tilted, 1e-3) << "energy grew by " << tilted;
}

// The default step follows the smallest unit's own time sqrt(Dn / g) (Froude),
// up to 1 ms: a layer of 4 cm cubes gets 0.25 ms, metre units 1 ms, and so
// does a scene without gravity.
TEST(BulletEngine, DefaultStepFollowsTheSmallestUnit) {
    const auto used = [](std::vector<double> sizes, double g) {
        EngineSettings settings = settings_for({concrete(0.5, 0.5)});
        settings.gravity = Eigen::Vector3d(0, 0, -g);
        auto engine = make_bullet_engine(settings);
        for (const double a : sizes)
            engine->add_template(cube_unit(a, 2400.0));
        return engine->time_step_report().used;
    };
    EXPECT_NEAR(used({0.04}, 9.81), 2.494e-4, 1e-7);
    EXPECT_NEAR(used({1.0, 0.04}, 9.81), 2.494e-4, 1e-7);
    EXPECT_EQ(used({1.0}, 9.81), kBulletDefaultStep);
    EXPECT_EQ(used({0.04}, 0.0), kBulletDefaultStep);
    EXPECT_NEAR(used({0.04 * 25.0}, 9.81 / 25.0), kBulletDefaultStep, 1e-12); // sqrt(1/0.392)/256 > 1 ms
}

TEST(BulletEngine, RefusesATooLargeStepUnlessForced) {
    EngineSettings settings = settings_for({concrete(0.5, 0.5)});
    {
        auto engine = make_bullet_engine(settings);
        engine->add_template(cube_unit(0.5, 2400.0));
        const TimeStepReport r = engine->time_step_report();
        EXPECT_DOUBLE_EQ(r.used, std::sqrt(0.5 / settings.gravity.norm()) / kBulletStepsPerUnitTime);
        EXPECT_EQ(r.limit, kBulletMaxStep);
        EXPECT_NE(r.rule.find("impulse"), std::string::npos) << r.rule;
    }
    settings.time_step = 1.5 * kBulletMaxStep;
    auto engine = make_bullet_engine(settings);
    engine->add_template(cube_unit(0.5, 2400.0));
    EXPECT_THROW(engine->time_step_report(), InputError);
    EXPECT_THROW(engine->advance(0.1), InputError);
    settings.force_time_step = true;
    auto forced = make_bullet_engine(settings);
    forced->add_template(cube_unit(0.5, 2400.0));
    EXPECT_TRUE(forced->time_step_report().forced);
    EXPECT_EQ(forced->time_step(), 1.5 * kBulletMaxStep);
}

TEST(BulletEngine, ValidatesInputWithOneLineErrors) {
    Material bad = concrete(0.5, 0.5);
    bad.restitution = 1.5;
    EXPECT_THROW(make_bullet_engine(settings_for({bad})), InputError);
    EngineSettings pair = settings_for({concrete(0.5, 0.5)});
    pair.pairs.push_back({"concrete", "steel", 0.5, 0.5, -1.0});
    EXPECT_THROW(make_bullet_engine(pair), InputError);
    auto engine = make_bullet_engine(settings_for({concrete(0.5, 0.5)}));
    UnitTemplate unit = cube_unit(0.5, 2400.0);
    unit.material = 3;
    EXPECT_THROW(engine->add_template(unit), InputError);
    unit.material = 0;
    engine->add_template(unit);
    BodyInit body;
    body.unit = 2;
    EXPECT_THROW(engine->add_body(body), InputError);
    body.unit = 0;
    body.pose.position = Eigen::Vector3d(0, 0, 7.9); // the cube reaches z = 8.15 > 8
    EXPECT_THROW(engine->add_body(body), InputError);
    EXPECT_THROW(engine->state(0), InputError);
    EXPECT_THROW(engine->set_external_load(1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), InputError);
    Wall wall = floor_plane(1.0);
    wall.material = 1;
    EXPECT_THROW(engine->add_wall(wall), InputError);
    BulletOptions thick;
    thick.collision_margin = 0.3; // more than half the 0.5 m cube
    auto thick_engine = make_bullet_engine(settings_for({concrete(0.5, 0.5)}), thick);
    EXPECT_THROW(thick_engine->add_template(cube_unit(0.5, 2400.0)), InputError);
}

TEST(BulletEngine, ShrunkHullMovesEveryFaceInwardByTheMargin) {
    const double a = 1.0, m = 0.04;
    const std::vector<Eigen::Vector3d> core =
        shrunk_hull(make_cube_shape(a, 0.0, 1.0).mesh.vertices, m, "cube");
    ASSERT_EQ(core.size(), 8u);
    for (const auto &v : core)
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(std::abs(v[k]), 0.5 * a - m, 1e-12);
}

TEST(BulletEngine, CubeRestsWithItsCentreAtHalfTheEdge) {
    // Hull + margin = the true cube: the centre rests at a/2 (an unshrunk hull
    // would rest at a/2 + margin). Checked with a large margin and the default.
    const double a = 1.0;
    for (double margin : {0.04, 0.0}) {
        BulletOptions options;
        options.collision_margin = margin;
        auto engine = make_bullet_engine(settings_for({concrete(0.3, 0.6)}), options);
        const UnitTemplate unit = cube_unit(a, 2400.0);
        engine->add_template(unit);
        BodyInit body;
        body.pose.position = Eigen::Vector3d(0.2, 0.1, 0.5 * a + 0.01);
        engine->add_body(body);
        engine->add_wall(floor_plane(3.0));
        engine->advance(1.0);
        const BodyState s = engine->state(0);
        const double used = bullet_body_info(*engine, 0).margin;
        EXPECT_NEAR(s.pose.position.z(), 0.5 * a, 0.01 * 0.5 * a) << "margin " << used;
        EXPECT_NEAR(s.pose.position.z(), 0.5 * a, 0.1 * used) << "margin " << used;
        // At rest the floor carries the weight.
        EXPECT_NEAR(s.contact_force.z(), unit.props.mass * 9.81, 0.005 * unit.props.mass * 9.81);
        EXPECT_LT(s.velocity.norm(), 1e-3);
    }
}

TEST(BulletEngine, DolosMassPropertiesAreTheExactOnes) {
    const UnitTemplate unit = dolos_unit(2.0, 0.33, 2400.0);
    EngineSettings settings = settings_for({concrete(0.5, 0.5)});
    settings.gravity = Eigen::Vector3d::Zero();
    auto engine = make_bullet_engine(settings);
    engine->add_template(unit);
    BodyInit body;
    body.pose.position = Eigen::Vector3d(0.3, -0.2, 3.0);
    body.pose.orientation =
        Eigen::Quaterniond(Eigen::AngleAxisd(0.9, Eigen::Vector3d(-1, 2, 0.5).normalized()));
    engine->add_body(body);
    const BulletBodyInfo info = bullet_body_info(*engine, 0);
    EXPECT_EQ(info.hulls, 3);
    EXPECT_NEAR(info.mass, unit.props.mass, 1e-9 * unit.props.mass);
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(info.local_inertia[k], unit.props.principal_moments[k],
                    1e-9 * unit.props.principal_moments[k]);
    EXPECT_LT((info.center_of_mass - body.pose.position).norm(), 1e-12);
    // Bullet's body frame is the principal frame: R_body = R_unit A.
    const Eigen::Matrix3d expected = body.pose.orientation.toRotationMatrix() * unit.props.principal_axes;
    EXPECT_LT((info.principal_to_world.toRotationMatrix() - expected).cwiseAbs().maxCoeff(), 1e-12);

    // Spin it, then the exact mesh placed at the reported pose has its
    // centroid at the reported position, and Bullet's shape (hulls + margin)
    // lies inside it, touching it to within a few margins in every direction.
    engine->set_external_load(0, Eigen::Vector3d(50, 0, 0), Eigen::Vector3d(400, -300, 200));
    engine->advance(0.3);
    const BodyState s = engine->state(0);
    TriangleMesh placed = unit.mesh;
    for (auto &v : placed.vertices)
        v = s.pose.position + s.pose.orientation * v;
    const MassProperties world = mass_properties(placed, 2400.0);
    EXPECT_LT((world.centroid - s.pose.position).norm(), 1e-9 * 2.0);
    std::mt19937 rng(7);
    std::normal_distribution<double> normal;
    for (int k = 0; k < 200; ++k) {
        const Eigen::Vector3d d = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
        double exact = -HUGE_VAL;
        for (const auto &v : placed.vertices)
            exact = std::max(exact, d.dot(v));
        const double bullet = d.dot(bullet_support_point(*engine, 0, d));
        EXPECT_LT(bullet - exact, 1e-9) << "outside the exact shape along " << d.transpose();
        EXPECT_GT(bullet - exact, -3.0 * info.margin) << "short of the exact shape along " << d.transpose();
    }
}

namespace {

// The shipped tilt scene (scenes/tilt_cube.toml) at the engine: a 0.2 m cube
// dropped onto the plate from `height` (m, centre), gravity turning about +y
// at 5 deg/s in steps of at most 0.1 deg, cut at every 0.05 s output as
// `armour run` does. Returns, per step, the tilt (deg), the slide along x (m)
// and the rotation (deg) from the pose at rest at 2 deg, and the speeds.
struct TiltSample {
    double tilt, slide, turned, speed, spin;
};
std::vector<TiltSample> tilt_ramp(double mu, double until_deg, double height) {
    auto engine = make_bullet_engine(settings_for({concrete(0.5, mu, 5e7)}));
    engine->add_template(cube_unit(0.2, 2400.0));
    BodyInit body;
    body.pose.position = Eigen::Vector3d(0, 0, height);
    engine->add_body(body);
    // The plate as scene_setup.cpp builds a plane wall of size 4 m (its diagonal matters).
    Wall plate;
    plate.name = "plate";
    const Eigen::Vector3d n(0, 0, 1), u = n.unitOrthogonal() * 2.0, v = n.cross(u);
    plate.surface.vertices = {-u - v, u - v, u + v, v - u};
    plate.surface.triangles = {{0, 1, 2}, {0, 2, 3}};
    engine->add_wall(plate);
    const double g = 9.81, rate = 5.0, dt = engine->time_step(); // deg/s, s
    std::vector<TiltSample> samples;
    BodyState rest;
    long step = 0; // whole time steps: 20 per 0.02 s span, 50 per output
    while (static_cast<double>(step) * dt * rate <= until_deg) {
        const double tilt = static_cast<double>(step) * dt * rate;
        engine->set_gravity(Eigen::Vector3d(g * std::sin(rad(tilt)), 0.0, -g * std::cos(rad(tilt))));
        const long span = std::min(20L, 50L - step % 50L);
        engine->advance(static_cast<double>(span) * dt);
        step += span;
        const BodyState s = engine->state(0);
        if (tilt <= 2.0) // landed and at rest by then
            rest = s;
        const double turned =
            2.0 * std::acos(std::min(1.0, std::abs(s.pose.orientation.dot(rest.pose.orientation))));
        samples.push_back({static_cast<double>(step) * dt * rate,
                           s.pose.position.x() - rest.pose.position.x(), deg(turned), s.velocity.x(),
                           s.angular_velocity.norm()});
    }
    return samples;
}

} // namespace

// Bullet's multipoint contacts left tilted normals and raised wall points in
// the resting cube's manifold (docs/bullet.md): it crept 2 mm and "slid" at
// 25.0 deg for mu = 0.5 and rested askew. With them snapped onto the plate it
// holds still until atan(mu) and slides within 0.5 deg after it, at the
// scene's tilt rate.
TEST(BulletEngine, SlidesAtAtanMuAtTheTiltScenesRate) {
    for (double mu : {0.3, 0.5})
        for (double height : {0.13, 0.125, 0.12, 0.115}) {
            const double onset = deg(std::atan(mu));
            double first_moving = HUGE_VAL, slide_before = 0.0;
            for (const TiltSample &s : tilt_ramp(mu, onset + 1.0, height)) {
                if (s.tilt <= onset - 0.25)
                    slide_before = std::max(slide_before, std::abs(s.slide));
                if (s.speed > 1e-3 && s.tilt > 2.0)
                    first_moving = std::min(first_moving, s.tilt);
            }
            EXPECT_LT(slide_before, 5e-5) << "mu " << mu << ", from " << height << " m"
                                          << ": crept before atan(mu) - 0.25 deg";
            // A Coulomb block reaches 1 mm/s 0.23 deg after the onset at 5 deg/s.
            EXPECT_GE(first_moving, onset) << "mu " << mu << ", from " << height << " m";
            EXPECT_LE(first_moving, onset + 0.5) << "mu " << mu << ", from " << height << " m";
        }
}

TEST(BulletEngine, TopplesAtTheRoundedEdgesAngleAtTheTiltScenesRate) {
    // Edges rounded by the margin m = 0.005 Dn: the cube tips at atan((a/2 - m) / (a/2)) = 44.71 deg.
    const double a = 0.2, m = kBulletMarginFraction * a, onset = deg(std::atan((0.5 * a - m) / (0.5 * a)));
    double turned_before = 0.0, first_spinning = HUGE_VAL;
    for (const TiltSample &s : tilt_ramp(1.2, onset + 1.5, 0.13)) {
        if (s.tilt <= onset - 0.5)
            turned_before = std::max(turned_before, s.turned);
        if (s.spin > 0.05 && s.tilt > 2.0)
            first_spinning = std::min(first_spinning, s.tilt);
    }
    EXPECT_LT(turned_before, 0.05);
    EXPECT_GE(first_spinning, onset);
    EXPECT_LE(first_spinning, onset + 1.0);
}

namespace {

// The stability scene's toe (scenes/stability_cubes.toml) as its x-z profile
// across the flume (m): the berm's top (z = 0.24 m) to x = 1.40 m, the
// step's face down to the slope's foot (z = 0.20 m), the 1:1.5 slope, the crest.
const std::vector<Eigen::Vector2d> &toe_profile() {
    static const std::vector<Eigen::Vector2d> profile = {
        {0.0, 0.24}, {1.40, 0.24}, {1.40, 0.20}, {1.91, 0.54}, {2.0, 0.54}};
    return profile;
}

// The toe in one wall mesh, across the flume's width (y within +-0.124 m).
Wall toe_wall() {
    const auto &profile = toe_profile();
    Wall w;
    w.name = "slope";
    for (const auto &p : profile) {
        w.surface.vertices.emplace_back(p.x(), -0.124, p.y());
        w.surface.vertices.emplace_back(p.x(), 0.124, p.y());
    }
    for (int i = 0; i + 1 < static_cast<int>(profile.size()); ++i) {
        w.surface.triangles.push_back({2 * i, 2 * i + 2, 2 * i + 3});
        w.surface.triangles.push_back({2 * i, 2 * i + 3, 2 * i + 1});
    }
    return w;
}

// How deep a point lies inside the toe wall's solid (m; < 0 outside): its
// distance to the profile, inside where it lies below a sloping or flat piece.
double toe_depth(const Eigen::Vector3d &p) {
    const auto &profile = toe_profile();
    const Eigen::Vector2d q(p.x(), p.z());
    double d = std::numeric_limits<double>::max();
    bool inside = false;
    for (std::size_t i = 0; i + 1 < profile.size(); ++i) {
        const Eigen::Vector2d a = profile[i], b = profile[i + 1];
        const double t = std::clamp((q - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
        d = std::min(d, (q - a - t * (b - a)).norm());
        if (a.x() <= q.x() && q.x() < b.x()) // not the step's vertical face
            inside = q.y() < a.y() + (q.x() - a.x()) / (b.x() - a.x()) * (b.y() - a.y());
    }
    return inside ? d : -d;
}

// How deep the step's convex edge (x = 1.40 m, z = 0.24 m) lies in a cube of edge a (m; < 0 clear of it).
double toe_edge_in_cube(const BodyState &s, double a) {
    // Along the edge, y -> local(y) = c + y d in the cube's frame, and the
    // depth a/2 - max |local_i| is concave and piecewise linear in y: its
    // largest value lies where two |local_i| meet or one is 0. Try them all.
    const Eigen::Vector3d c =
        s.pose.orientation.conjugate() * (Eigen::Vector3d(1.40, 0, 0.24) - s.pose.position);
    const Eigen::Vector3d d = s.pose.orientation.conjugate() * Eigen::Vector3d::UnitY();
    std::vector<double> ys;
    for (int i = 0; i < 3; ++i) {
        if (d[i] != 0.0)
            ys.push_back(-c[i] / d[i]);
        for (int j = 0; j < 3; ++j)
            for (double sign : {1.0, -1.0})
                if (i != j && d[i] != sign * d[j])
                    ys.push_back((sign * c[j] - c[i]) / (d[i] - sign * d[j]));
    }
    double deepest = -a;
    for (double y : ys)
        if (std::abs(y) <= 0.124) // the wall's width
            deepest = std::max(deepest, 0.5 * a - (c + y * d).cwiseAbs().maxCoeff());
    return deepest;
}

// How deep a cube of edge a lies in the toe wall: its corners in the wall, the step's edge in the cube.
double cube_in_toe(const BodyState &s, double a) {
    double deepest = toe_edge_in_cube(s, a);
    for (int k = 0; k < 8; ++k) {
        const Eigen::Vector3d corner(k & 1 ? 0.5 * a : -0.5 * a, k & 2 ? 0.5 * a : -0.5 * a,
                                     k & 4 ? 0.5 * a : -0.5 * a);
        deepest = std::max(deepest, toe_depth(s.pose.position + s.pose.orientation * corner));
    }
    return deepest;
}

} // namespace

TEST(BulletEngine, ACubePressedIntoTheToesNotchRestsOutOfTheWall) {
    // The scene's cube (Dn 0.04 m, 1540 kg/m^3) set on the slope at its foot,
    // square to the slope's edges or turned 0.3 rad about its normal, pressed
    // down by 20 x its weight besides it (the rows above it): it comes to
    // rest against the step's edge, out of every face to 0.1 % of Dn at every
    // 0.05 s. One collision object per plane of the wall instead of one mesh
    // broke this (tried: the square cube jittered at 0.04-0.17 m/s and sank
    // 0.6-1.5 mm), so it stays one mesh.
    const double a = 0.04, slope = std::atan(1.0 / 1.5);
    const Eigen::Vector3d normal(-std::sin(slope), 0, std::cos(slope)),
        up(std::cos(slope), 0, std::sin(slope));
    for (double turn : {0.0, 0.3}) {
        auto engine = make_bullet_engine(settings_for({concrete(0.1, 0.6)}));
        const UnitTemplate unit = cube_unit(a, 1540.0);
        engine->add_template(unit);
        BodyInit body;
        body.pose.orientation = Eigen::AngleAxisd(-slope, Eigen::Vector3d::UnitY()) *
                                Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ());
        body.pose.position = Eigen::Vector3d(1.40, 0, 0.20) + 0.05 * up + (0.5 * a + 0.003) * normal;
        engine->add_body(body);
        engine->add_wall(toe_wall());
        const double weight = unit.props.mass * 9.81;
        engine->set_external_load(0, Eigen::Vector3d(0, 0, -20.0 * weight), Eigen::Vector3d::Zero());
        double deepest = -a;
        for (int i = 0; i < 40; ++i) {
            engine->advance(0.05);
            deepest = std::max(deepest, cube_in_toe(engine->state(0), a));
        }
        EXPECT_LT(deepest, 1e-3 * a) << "turned " << turn << " rad";
        EXPECT_LT(engine->state(0).velocity.norm(), 1e-3) << "turned " << turn << " rad";
        EXPECT_LT(engine->state(0).angular_velocity.norm(), 0.05)
            << "turned " << turn << " rad"; // < 2 mm/s at its corners
        // Held by the step: the step's edge touches it (within 0.1 mm).
        EXPECT_GT(toe_edge_in_cube(engine->state(0), a), -1e-4) << "turned " << turn << " rad";
    }
}

namespace {

// How far the top of a column of n cubes of edge a, each turned 0.2 rad from
// the one below, sinks below its height (m: the overlaps summed down the
// column) after 2 s on the floor, and the fastest cube's speed (m/s).
std::pair<double, double> column_sink(int n, double a, int contact_iterations) {
    EngineSettings settings = settings_for({concrete(0.1, 0.6)});
    settings.contact_iterations = contact_iterations;
    auto engine = make_bullet_engine(settings);
    engine->add_template(cube_unit(a, 1540.0));
    for (int k = 0; k < n; ++k) {
        BodyInit body;
        body.pose.position = Eigen::Vector3d(0.001 * (k % 3), 0, 0.5 * a + k * (a + 1e-5));
        body.pose.orientation = Eigen::AngleAxisd(0.2 * k, Eigen::Vector3d::UnitZ());
        engine->add_body(body);
    }
    engine->add_wall(floor_plane(1.0));
    engine->advance(2.0);
    double fastest = 0.0;
    for (int k = 0; k < n; ++k)
        fastest = std::max(fastest, engine->state(k).velocity.norm());
    return {(n - 0.5) * a - engine->state(n - 1).pose.position.z(), fastest};
}

} // namespace

TEST(BulletEngine, MoreContactIterationsHoldATallColumnOutOfItself) {
    // 30 of the stability scene's cubes (Dn 0.04 m) in a column: the lower
    // ones carry many units' weight, as a layer's toe carries the rows above.
    // The sequential-impulse solve leaves overlaps that shrink with its
    // iterations (run.contact_iterations; measured, friction in two
    // directions: 20, the adapter's former default, 0.60 mm summed and still
    // moving at 0.04 m/s; 50, the default now, 0.03 mm and 0.007 m/s; 100,
    // 0.007 mm and 0.003 m/s).
    const double a = 0.04;
    const auto [sink_20, fastest_20] = column_sink(30, a, 20);
    const auto [sink_100, fastest_100] = column_sink(30, a, 100);
    EXPECT_LT(sink_100, 1e-3 * a); // 0.1 % of Dn summed over 30 contacts
    EXPECT_LT(fastest_100, 5e-3);
    EXPECT_GT(sink_20, 10.0 * std::max(sink_100, 1e-7)) << "the iterations do not reach the solver";
    EXPECT_GT(fastest_20, fastest_100);
}
