// The LIGGGHTS engine against analytic solutions.
#include "liggghts_engine.h"
#include "time_step.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

using namespace armour;

namespace {

constexpr double kPi = 3.14159265358979323846;
double deg(double radians) {
    return radians * 180.0 / kPi;
}
double rad(double degrees) {
    return degrees * kPi / 180.0;
}

// A cube of edge a whose clump is 8 corner spheres of radius r touching the
// cube's faces: its support on a plane is the square of half-width a/2 - r,
// so it topples at atan((a/2 - r) / (a/2)) and slides at atan(mu).
UnitTemplate corner_cube(double a, double r, double density) {
    const Shape shape = make_cube_shape(a, 0.0, density);
    UnitTemplate unit;
    unit.name = "corner_cube";
    unit.mesh = shape.mesh;
    unit.props = shape.props;
    const double c = 0.5 * a - r;
    for (int i = 0; i < 8; ++i)
        unit.clump.push_back({Eigen::Vector3d(i & 1 ? c : -c, i & 2 ? c : -c, i & 4 ? c : -c), r});
    return unit;
}

Wall floor_plane(double half) {
    Wall w;
    w.name = "floor";
    w.surface.vertices = {{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}};
    w.surface.triangles = {{0, 1, 2}, {0, 2, 3}};
    return w;
}

EngineSettings settings_for(const std::string &test, Material material) {
    EngineSettings s;
    s.work_dir = (std::filesystem::temp_directory_path() / ("armour_liggghts_" + test)).string();
    s.materials = {std::move(material)};
    s.domain_min = Eigen::Vector3d(-3, -3, -1);
    s.domain_max = Eigen::Vector3d(3, 3, 8);
    return s;
}

Material concrete(double restitution, double friction, double youngs = 5e9) {
    Material m;
    m.name = "concrete";
    m.youngs_modulus = youngs;
    m.poisson_ratio = 0.25;
    m.restitution = restitution;
    m.friction = friction;
    return m;
}

std::string current_test() {
    return ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

// Rests the cube on the floor under vertical gravity, turns gravity about +y
// to `angle` over 0.2 s (as if the floor were slowly inclined: a sudden tilt
// would overshoot the tangential springs), then holds it for `seconds`.
// Returns (slide distance along x, rotation angle) over the hold.
std::pair<double, double> tilt_cube(double mu, double angle_deg, double seconds) {
    auto engine = make_liggghts_engine(settings_for(current_test(), concrete(0.3, mu)));
    const double a = 1.0, r = 0.015;
    const int unit = engine->add_template(corner_cube(a, r, 2400.0));
    BodyInit body;
    body.unit = unit;
    body.pose.position = Eigen::Vector3d(0, 0, 0.5 * a + 1e-4);
    engine->add_body(body);
    engine->add_wall(floor_plane(3.0));
    engine->advance(0.3);
    const double g = 9.81;
    for (int k = 1; k <= 20; ++k) {
        const double t = rad(angle_deg) * k / 20.0;
        engine->set_gravity(Eigen::Vector3d(g * std::sin(t), 0.0, -g * std::cos(t)));
        engine->advance(0.01);
    }
    const BodyState rest = engine->state(0);
    engine->advance(seconds);
    const BodyState end = engine->state(0);
    const double turned =
        2.0 * std::acos(std::min(1.0, std::abs(end.pose.orientation.dot(rest.pose.orientation))));
    return {end.pose.position.x() - rest.pose.position.x(), deg(turned)};
}

} // namespace

TEST(LiggghtsEngine, FreeFallMatchesAnalytic) {
    auto engine = make_liggghts_engine(settings_for(current_test(), concrete(0.5, 0.5)));
    engine->add_template(corner_cube(0.5, 0.05, 2400.0));
    BodyInit body;
    body.pose.position = Eigen::Vector3d(0.1, -0.2, 6.0);
    body.velocity = Eigen::Vector3d(0.3, 0.0, 1.0);
    engine->add_body(body);
    engine->advance(0.8);
    const double t = engine->time();
    EXPECT_NEAR(t, 0.8, engine->time_step());
    const BodyState s = engine->state(0);
    const double z = 6.0 + 1.0 * t - 0.5 * 9.81 * t * t;
    EXPECT_NEAR(s.pose.position.z(), z, 0.005 * (6.0 - z));
    EXPECT_NEAR(s.pose.position.x(), 0.1 + 0.3 * t, 1e-6);
    EXPECT_NEAR(s.velocity.z(), 1.0 - 9.81 * t, 0.005 * 9.81 * t);
    EXPECT_NEAR(s.contact_force.norm(), 0.0, 1e-9);
}

TEST(LiggghtsEngine, ExternalForceAndTorqueGiveFOverMAndTOverI) {
    EngineSettings settings = settings_for(current_test(), concrete(0.5, 0.5));
    settings.gravity = Eigen::Vector3d::Zero();
    auto engine = make_liggghts_engine(settings);
    const UnitTemplate unit = corner_cube(0.5, 0.05, 2400.0);
    engine->add_template(unit);
    BodyInit body;
    body.pose.position = Eigen::Vector3d(0, 0, 3);
    body.pose.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
    engine->add_body(body);
    const Eigen::Vector3d force(100.0, -200.0, 50.0), torque(3.0, -2.0, 1.0);
    engine->set_external_load(0, force, torque);
    engine->advance(0.2);
    const double t = engine->time();
    const BodyState s = engine->state(0);
    const double m = unit.props.mass, I = unit.props.principal_moments[0]; // a cube: isotropic
    EXPECT_LT((s.velocity - force / m * t).norm(), 0.005 * (force / m * t).norm());
    EXPECT_LT((s.angular_velocity - torque / I * t).norm(), 0.005 * (torque / I * t).norm());
    EXPECT_EQ(s.external_force, force);
}

TEST(LiggghtsEngine, SlidesAtTanThetaEqualsMu) {
    const double mu = 0.5, onset = deg(std::atan(mu)); // 26.57 deg
    const auto below = tilt_cube(mu, onset - 0.5, 0.6);
    const auto above = tilt_cube(mu, onset + 0.5, 0.6);
    EXPECT_LT(std::abs(below.first), 1e-3) << "slid below tan(theta) = mu";
    // Above onset it slides with a = g (sin t - mu cos t): 0.5 a t^2 over 0.6 s.
    const double t = rad(onset + 0.5), accel = 9.81 * (std::sin(t) - mu * std::cos(t));
    EXPECT_GT(above.first, 0.5 * 0.5 * accel * 0.36) << "did not slide above tan(theta) = mu";
    EXPECT_LT(above.second, 1.0); // it slides, it does not tip
}

TEST(LiggghtsEngine, CubeTopplesAtFortyFiveDegreesWhenFrictionHolds) {
    const double a = 1.0, r = 0.015;
    const double onset = deg(std::atan((0.5 * a - r) / (0.5 * a))); // 44.1 deg for this clump
    ASSERT_NEAR(onset, 45.0, 1.0);
    const auto below = tilt_cube(2.0, onset - 0.7, 1.0);
    const auto above = tilt_cube(2.0, onset + 0.7, 1.5); // tipping starts slowly just past the angle
    EXPECT_LT(below.second, 1.0) << "toppled below the analytic angle";
    EXPECT_GT(above.second, 10.0) << "did not topple above the analytic angle";
    EXPECT_LT(std::abs(below.first), 2e-3);
}

// A vertical two-sphere clump lands on one sphere: one contact, through the
// centre of mass. (Several simultaneous contacts damp more: LIGGGHTS sizes
// each contact's dashpot with the whole body's mass; see docs/dem.md.)
double bounce_ratio(ContactModel model, double e, double drop) {
    EngineSettings settings = settings_for(current_test(), concrete(e, 0.5, 5e8));
    settings.contact = model;
    settings.characteristic_velocity = std::sqrt(2.0 * 9.81 * drop);
    auto engine = make_liggghts_engine(settings);
    UnitTemplate dumbbell;
    dumbbell.name = "dumbbell";
    dumbbell.clump = {{Eigen::Vector3d(0, 0, -0.05), 0.05}, {Eigen::Vector3d(0, 0, 0.05), 0.05}};
    dumbbell.props = clump_mass_properties(dumbbell.clump, 2400.0);
    engine->add_template(dumbbell);
    BodyInit body;
    body.pose.position = Eigen::Vector3d(0, 0, 0.1 + drop);
    engine->add_body(body);
    engine->add_wall(floor_plane(2.0));
    double lowest = HUGE_VAL, apex = -HUGE_VAL;
    bool bounced = false;
    for (int k = 0; k < 1500 && !(bounced && engine->state(0).velocity.z() < 0.0); ++k) {
        engine->advance(0.0005);
        const BodyState s = engine->state(0);
        lowest = std::min(lowest, s.pose.position.z());
        if (s.velocity.z() > 0.0 && s.contact_force.norm() == 0.0)
            bounced = true;
        if (bounced)
            apex = std::max(apex, s.pose.position.z());
    }
    EXPECT_TRUE(bounced);
    // Heights of the clump's lowest point above the floor (sphere bottom at z - 0.1).
    return (apex - 0.1) / drop;
}

// Restitution of a linear spring-dashpot whose damping is set for `e` (as
// LIGGGHTS does, zeta = -ln e / sqrt(pi^2 + ln^2 e)) when the contact ends as
// soon as the force would pull (k d + c d' = 0), not when the overlap closes:
// d = (v0/w_d) exp(-zeta w t) sin(w_d t), with w = 1, m = 1, c = 2 zeta.
double restitution_with_force_cutoff(double e) {
    const double zeta = -std::log(e) / std::sqrt(kPi * kPi + std::log(e) * std::log(e));
    const double wd = std::sqrt(1.0 - zeta * zeta), c = 2.0 * zeta;
    const double theta = kPi - std::atan(c * wd / (1.0 - c * zeta)); // force zero in (pi/2, pi)
    const double t = theta / wd;
    return -std::exp(-zeta * t) * (-zeta * std::sin(theta) + wd * std::cos(theta)) / wd;
}

TEST(LiggghtsEngine, BounceHeightRatioIsRestitutionSquared) {
    const double e = 0.6;
    EXPECT_NEAR(bounce_ratio(ContactModel::hertz, e, 0.5), e * e, 0.05 * e * e);
    // hooke: LIGGGHTS ends the contact when the force would turn tensile, so
    // the rebound follows the cut-off restitution (0.632 for e = 0.6), the
    // same at every impact speed.
    const double linear = restitution_with_force_cutoff(e);
    EXPECT_NEAR(linear, 0.6323, 1e-3);
    EXPECT_NEAR(bounce_ratio(ContactModel::hooke, e, 0.5), linear * linear, 0.02 * linear * linear);
    EXPECT_NEAR(bounce_ratio(ContactModel::hooke, e, 0.2), linear * linear, 0.02 * linear * linear);
}

TEST(LiggghtsEngine, NoEnergyGainOverManyStepsWithElasticContacts) {
    auto engine = make_liggghts_engine(settings_for(current_test(), concrete(1.0, 0.0, 5e8)));
    const UnitTemplate unit = corner_cube(0.2, 0.02, 2400.0);
    engine->add_template(unit);
    BodyInit body;
    body.pose.position = Eigen::Vector3d(0, 0, 0.1 + 0.1);
    engine->add_body(body);
    engine->add_wall(floor_plane(2.0));
    const double m = unit.props.mass, g = 9.81;
    auto energy = [&](const BodyState &s) {
        return 0.5 * m * s.velocity.squaredNorm() + m * g * s.pose.position.z() +
               0.5 * unit.props.principal_moments[0] * s.angular_velocity.squaredNorm();
    };
    const double start = energy(engine->state(0));
    double highest = start;
    const double chunk = 200 * engine->time_step();
    while (engine->steps() < 100000) {
        engine->advance(chunk);
        const BodyState s = engine->state(0);
        if (s.contact_force.norm() == 0.0) // elastic energy is zero only between contacts
            highest = std::max(highest, energy(s));
    }
    EXPECT_GE(engine->steps(), 100000);
    EXPECT_LT(highest, start * (1.0 + 1e-3)) << "energy grew by " << (highest / start - 1.0);
}

TEST(LiggghtsEngine, RefusesAnUnstableTimeStepUnlessForced) {
    EngineSettings settings = settings_for(current_test(), concrete(0.5, 0.5));
    const UnitTemplate unit = corner_cube(0.5, 0.05, 2400.0);
    const TimeStepReport limit = compute_time_step(settings, {unit}, {0});
    EXPECT_NEAR(limit.used, kDefaultSafety * limit.limit, 1e-15);
    settings.time_step = 1.5 * limit.limit;
    EXPECT_THROW(compute_time_step(settings, {unit}, {0}), InputError);
    auto engine = make_liggghts_engine(settings);
    engine->add_template(unit);
    EXPECT_THROW(engine->time_step_report(), InputError);
    settings.force_time_step = true;
    const TimeStepReport forced = compute_time_step(settings, {unit}, {0});
    EXPECT_TRUE(forced.forced);
    EXPECT_EQ(forced.used, 1.5 * limit.limit);
}

TEST(LiggghtsEngine, OrientationRoundTripsThroughThePrincipalFrame) {
    // Three unequal spheres: principal axes are nowhere near the unit axes.
    UnitTemplate unit;
    unit.name = "lopsided";
    unit.clump = {{Eigen::Vector3d(0.3, 0.1, 0.0), 0.15},
                  {Eigen::Vector3d(-0.2, 0.2, 0.1), 0.1},
                  {Eigen::Vector3d(0.0, -0.25, -0.15), 0.12}};
    unit.props = clump_mass_properties(unit.clump, 2400.0);
    for (auto &s : unit.clump) // the unit frame has its origin at the centroid
        s.center -= unit.props.centroid;
    unit.props = clump_mass_properties(unit.clump, 2400.0);
    ASSERT_GT(std::abs(unit.props.inertia(0, 1)), 1e-3 * unit.props.inertia(0, 0));

    EngineSettings settings = settings_for(current_test(), concrete(0.5, 0.5));
    settings.gravity = Eigen::Vector3d::Zero();
    auto engine = make_liggghts_engine(settings);
    engine->add_template(unit);
    const Eigen::Quaterniond q0(Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()));
    const Eigen::Quaterniond q1(Eigen::AngleAxisd(-2.0, Eigen::Vector3d(-0.7, 0.1, 0.2).normalized()));
    for (int k = 0; k < 2; ++k) {
        BodyInit body;
        body.pose.orientation = k == 0 ? q0 : q1;
        body.pose.position = Eigen::Vector3d(k == 0 ? -1.5 : 1.5, 0, 3);
        engine->add_body(body);
    }
    // A torque about world z from rest: omega(t) = I_world^-1 T t, with
    // I_world = R I_unit R^T built from the orientation the engine reports.
    const Eigen::Vector3d torque(0.0, 0.0, 2.0);
    engine->set_external_load(1, Eigen::Vector3d::Zero(), torque);
    engine->advance(engine->time_step());
    EXPECT_GT(std::abs(engine->state(0).pose.orientation.dot(q0)), 1.0 - 1e-12);
    EXPECT_GT(std::abs(engine->state(1).pose.orientation.dot(q1)), 1.0 - 1e-9);
    engine->advance(0.01);
    const BodyState s = engine->state(1);
    const Eigen::Matrix3d R = s.pose.orientation.toRotationMatrix();
    const Eigen::Vector3d expected =
        (R * unit.props.inertia * R.transpose()).inverse() * torque * engine->time();
    EXPECT_LT((s.angular_velocity - expected).norm(), 0.01 * expected.norm())
        << s.angular_velocity.transpose() << " vs " << expected.transpose();
}
