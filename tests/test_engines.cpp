// One conformance suite for every registered engine: the facts any rigid-body
// engine of armour-fsi must get right, each engine's tolerances in one table.
// A new engine gets all of it by registering (engines/engine_registry.cpp)
// and adding its row to kTolerances; tests of contacts run for engines whose
// capabilities say they have contacts.
#include "engine_registry.h"
#include "engine_test_kit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

using namespace armour;
using namespace armour::test;

namespace {

constexpr double kG = 9.81;

// The clump of the conformance cube: 8 corner spheres touching the faces,
// radius a fraction of the edge. Its support on a plane is the square of
// half-width a/2 - r. The tilt tests need small corners (the cube tips near
// 45 deg); elsewhere larger ones keep the DEM step (Rayleigh time ~ r) long.
constexpr double kCornerRadius = 0.1;
constexpr double kTiltCornerRadius = 0.015;

struct Tolerances {
    std::string style;
    double kinematics;     // relative error of free fall, F/m and T/I
    double support_inset;  // how far the tilt cube's support edge lies inside its edge, fraction of the edge
    double topple_bracket; // deg either side of the geometric topple angle
    // Energy measured as the invariant of a semi-implicit (symplectic Euler)
    // integrator, 1/2 m v^2 - m g.x + 1/2 m dt g.v: its plain energy
    // oscillates by m g v dt / 2 in free flight, which is not a gain.
    bool symplectic_euler;
};

// Why each value: LIGGGHTS and Bullet integrate free flight to O(dt) in the
// velocity (0.5 % over the tests' spans); the free body is exact for loads
// held constant. The LIGGGHTS cube tips about its corner spheres' contact
// points (inset r); Bullet's hull edges are rounded by its collision margin
// (kBulletMarginFraction = 0.005 of the edge) and its impulse solver lets
// tipping start slowly, so its bracket is wider.
const std::vector<Tolerances> kTolerances = {
    {"liggghts", 0.005, kTiltCornerRadius, 0.7, false},
    {"bullet", 0.005, 0.005, 1.0, true},
    {"free_body", 1e-6, 0.0, 0.0, false},
};

const Tolerances &tolerances(const std::string &style) {
    for (const auto &t : kTolerances)
        if (t.style == style)
            return t;
    throw std::runtime_error("no conformance tolerances for engine '" + style +
                             "': add its row to kTolerances");
}

// This process's scratch folder for the engines' work files, removed when the
// process ends: per process, so two checkouts can run their suites at once.
const std::filesystem::path &scratch() {
    static const struct Scratch {
        std::filesystem::path path =
            std::filesystem::temp_directory_path() / ("armour_test_engines_" + std::to_string(::getpid()));
        ~Scratch() {
            std::error_code ec;
            std::filesystem::remove_all(path, ec);
        }
    } folder;
    return folder.path;
}

class Conformance : public ::testing::TestWithParam<std::string> {
  protected:
    const Tolerances &tol() const { return tolerances(GetParam()); }
    const EngineCapabilities &caps() const { return engine_style(GetParam()).capabilities; }

    EngineSettings settings(Material material) const {
        EngineSettings s;
        const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = std::string(info->name());
        std::replace(name.begin(), name.end(), '/', '_');
        s.work_dir = (scratch() / ("conformance_" + name)).string();
        s.materials = {std::move(material)};
        s.domain_min = Eigen::Vector3d(-3, -3, -1);
        s.domain_max = Eigen::Vector3d(3, 3, 8);
        return s;
    }

    std::unique_ptr<RigidBodyEngine> make(const EngineSettings &s) const {
        return make_engine(GetParam(), s);
    }

    // The tilt experiment (engine_test_kit.h) on a resting unit-edge cube.
    std::pair<double, double> tilt_cube(double mu, double angle_deg, double seconds) const {
        auto engine = make(settings(concrete(0.3, mu)));
        engine->add_template(test_cube(1.0, 2400.0, kTiltCornerRadius));
        BodyInit body;
        body.pose.position = Eigen::Vector3d(0, 0, 0.5 + 1e-4);
        engine->add_body(body);
        engine->add_wall(floor_plane(3.0));
        return tilt_and_hold(*engine, angle_deg, seconds);
    }

    bool has_contacts() const { return caps().contacts != ContactKind::none; }
};

std::vector<std::string> registered_styles() {
    std::vector<std::string> names;
    for (const auto &s : engine_styles())
        names.push_back(s.name);
    return names;
}

} // namespace

TEST(EngineRegistry, EveryStyleHasConformanceTolerancesAndAFactory) {
    ASSERT_FALSE(engine_styles().empty());
    for (const auto &s : engine_styles()) {
        EXPECT_NO_THROW(tolerances(s.name)) << s.name;
        EngineSettings settings;
        settings.materials = {concrete(0.5, 0.5)};
        settings.work_dir = (scratch() / "registry").string();
        auto engine = s.make(settings);
        ASSERT_TRUE(engine) << s.name;
        EXPECT_EQ(engine->name(), s.name);
        EXPECT_EQ(engine->time(), 0.0);
    }
    try {
        engine_style("havok");
        FAIL() << "an unknown engine was accepted";
    } catch (const InputError &e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("run.engine: 'havok' is not available"), std::string::npos) << what;
        EXPECT_NE(what.find("liggghts"), std::string::npos) << what;
    }
}

TEST(EngineRegistry, DescribesOneStylePerLineWithItsCapabilities) {
    const std::string text = describe_engine_styles();
    EXPECT_EQ(static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')), engine_styles().size());
    EXPECT_NE(text.find("liggghts: contacts=spring_dashpot (hooke, hertz) shape=sphere_clumps"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("free_body: contacts=none shape=none parallel=replica_per_rank pivot=yes"),
              std::string::npos)
        << text;
}

TEST_P(Conformance, FreeFallMatchesAnalytic) {
    auto engine = make(settings(concrete(0.5, 0.5)));
    engine->add_template(test_cube(0.5, 2400.0, kCornerRadius));
    BodyInit body;
    body.pose.position = Eigen::Vector3d(0.1, -0.2, 6.0);
    body.velocity = Eigen::Vector3d(0.3, 0.0, 1.0);
    engine->add_body(body);
    engine->advance(0.8);
    const double t = engine->time();
    EXPECT_NEAR(t, 0.8, 0.5 * engine->time_step());
    const BodyState s = engine->state(0);
    const double z = 6.0 + 1.0 * t - 0.5 * kG * t * t;
    EXPECT_NEAR(s.pose.position.z(), z, tol().kinematics * (6.0 - z));
    EXPECT_NEAR(s.pose.position.x(), 0.1 + 0.3 * t, 1e-6);
    EXPECT_NEAR(s.velocity.z(), 1.0 - kG * t, tol().kinematics * kG * t);
    EXPECT_NEAR(s.contact_force.norm(), 0.0, 1e-9);
}

TEST_P(Conformance, ExternalForceAndTorqueGiveFOverMAndTOverI) {
    EngineSettings es = settings(concrete(0.5, 0.5));
    es.gravity = Eigen::Vector3d::Zero();
    auto engine = make(es);
    const UnitTemplate unit = test_cube(0.5, 2400.0, kCornerRadius);
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
    EXPECT_LT((s.velocity - force / m * t).norm(), tol().kinematics * (force / m * t).norm());
    EXPECT_LT((s.angular_velocity - torque / I * t).norm(), tol().kinematics * (torque / I * t).norm());
    EXPECT_EQ(s.external_force, force);
    EXPECT_EQ(s.external_torque, torque);
}

TEST_P(Conformance, SlidesAtTanThetaEqualsMu) {
    if (!has_contacts())
        GTEST_SKIP() << GetParam() << " has no contacts";
    const double mu = 0.5, onset = deg(std::atan(mu)); // 26.57 deg
    const auto below = tilt_cube(mu, onset - 0.5, 0.6);
    const auto above = tilt_cube(mu, onset + 0.5, 0.6);
    EXPECT_LT(std::abs(below.first), 1e-3) << "slid below tan(theta) = mu";
    // Above onset it slides with a = g (sin t - mu cos t): at least half of 0.5 a t^2 over 0.6 s.
    const double t = rad(onset + 0.5), accel = kG * (std::sin(t) - mu * std::cos(t));
    EXPECT_GT(above.first, 0.5 * 0.5 * accel * 0.36) << "did not slide above tan(theta) = mu";
    EXPECT_LT(above.second, 1.0); // it slides, it does not tip
}

TEST_P(Conformance, CubeTopplesAtTheGeometricAngleWhenFrictionHolds) {
    if (!has_contacts())
        GTEST_SKIP() << GetParam() << " has no contacts";
    const double a = 1.0, inset = tol().support_inset * a;
    const double onset = deg(std::atan((0.5 * a - inset) / (0.5 * a)));
    ASSERT_NEAR(onset, 45.0, 1.0);
    const auto below = tilt_cube(2.0, onset - tol().topple_bracket, 1.0);
    const auto above = tilt_cube(2.0, onset + tol().topple_bracket, 1.5); // tipping starts slowly
    EXPECT_LT(below.second, 1.0) << "toppled below the geometric angle " << onset;
    EXPECT_GT(above.second, 10.0) << "did not topple above the geometric angle " << onset;
    EXPECT_LT(std::abs(below.first), 2e-3);
}

// A cube dropped flat on the floor with elastic, frictionless contacts,
// 1e5 steps (engines without contacts: free flight). Between contacts the
// mechanical energy may only fall.
TEST_P(Conformance, NoEnergyGainOverManyStepsWithElasticContacts) {
    auto engine = make(settings(concrete(1.0, 0.0, 5e8)));
    const UnitTemplate unit = test_cube(0.2, 2400.0, kCornerRadius);
    engine->add_template(unit);
    BodyInit body;
    body.pose.position = Eigen::Vector3d(0, 0, 0.1 + 0.1);
    engine->add_body(body);
    engine->add_wall(floor_plane(2.0));
    const double m = unit.props.mass, dt = engine->time_step();
    const Eigen::Vector3d g(0, 0, -kG);
    const double discrete = tol().symplectic_euler ? 0.5 * m * dt : 0.0;
    auto energy = [&](const BodyState &s) {
        return 0.5 * m * s.velocity.squaredNorm() - m * g.dot(s.pose.position) +
               discrete * g.dot(s.velocity) +
               0.5 * unit.props.principal_moments[0] * s.angular_velocity.squaredNorm();
    };
    const double start = energy(engine->state(0));
    double highest = start;
    const double chunk = 200 * dt;
    while (engine->steps() < 100000) {
        engine->advance(chunk);
        const BodyState s = engine->state(0);
        if (s.contact_force.norm() == 0.0) // elastic energy is zero only between contacts
            highest = std::max(highest, energy(s));
    }
    EXPECT_GE(engine->steps(), 100000);
    EXPECT_LT(highest, start * (1.0 + 1e-3)) << "energy grew by " << (highest / start - 1.0);
}

// Fluid steps that are no multiple of the engine step (1.4 and 1.6 steps, as a
// 1.4 ms interFoam step against Bullet's 1 ms), and random adaptive ones over
// several seeds: the engine's clock stays within half a step of the fluid's,
// and the state is the state at the engine's own time.
TEST_P(Conformance, ClockKeepsTheSumOfNonCommensurateSpans) {
    for (const double ratio : {1.4, 1.6, 0.3, 2.5}) {
        auto engine = make(settings(concrete(0.5, 0.5)));
        engine->add_template(test_cube(0.5, 2400.0, kCornerRadius));
        BodyInit body;
        body.pose.position = Eigen::Vector3d(0, 0, 7);
        engine->add_body(body);
        const double dt = engine->time_step(), span = ratio * dt;
        double fluid = 0.0;
        for (int k = 0; k < 300; ++k) {
            engine->advance(span);
            fluid += span;
            ASSERT_LE(std::abs(engine->time() - fluid), 0.5 * dt * (1.0 + 1e-9))
                << "ratio " << ratio << " call " << k;
        }
        EXPECT_NEAR(engine->requested_time(), fluid, 1e-12 * fluid);
        EXPECT_NEAR(engine->time(), static_cast<double>(engine->steps()) * dt, 1e-12);
        // Free fall from rest: v = g t at the engine's own time (to one step's
        // g dt, the lag of a first-order integrator over these short spans).
        EXPECT_NEAR(engine->state(0).velocity.z(), -kG * engine->time(),
                    tol().kinematics * kG * engine->time() + kG * dt)
            << "ratio " << ratio;
    }
    for (unsigned seed : {1u, 2u, 3u}) {
        auto engine = make(settings(concrete(0.5, 0.5)));
        engine->add_template(test_cube(0.5, 2400.0, kCornerRadius));
        BodyInit body;
        body.pose.position = Eigen::Vector3d(0, 0, 7);
        engine->add_body(body);
        const double dt = engine->time_step();
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> factor(0.2, 3.7);
        double fluid = 0.0, worst = 0.0;
        for (int k = 0; k < 300; ++k) {
            const double span = factor(rng) * dt;
            engine->advance(span);
            fluid += span;
            worst = std::max(worst, std::abs(engine->time() - fluid));
        }
        EXPECT_LE(worst, 0.5 * dt * (1.0 + 1e-9)) << "seed " << seed;
    }
}

TEST_P(Conformance, OrientationRoundTripsThroughThePrincipalFrame) {
    // A 1 x 2 x 3 m box turned inside its unit frame: principal axes nowhere
    // near the unit axes, three different moments. Its clump: 2 x 4 x 6
    // spheres filling it (the engines take the exact mass properties as given).
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(0.6, Eigen::Vector3d(1.0, -0.4, 0.7).normalized()).toRotationMatrix();
    UnitTemplate unit;
    unit.name = "box123";
    unit.mesh = make_cube_mesh(1.0);
    for (auto &v : unit.mesh.vertices)
        v = turn * Eigen::Vector3d(v.x(), 2.0 * v.y(), 3.0 * v.z());
    unit.convex_parts = {unit.mesh};
    unit.props = mass_properties(unit.mesh, 2400.0);
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 6; ++k)
                unit.clump.push_back(
                    {turn * Eigen::Vector3d(-0.25 + 0.5 * i, -0.75 + 0.5 * j, -1.25 + 0.5 * k), 0.25});
    ASSERT_GT(std::abs(unit.props.inertia(0, 1)), 1e-2 * unit.props.inertia(0, 0));
    ASSERT_GT(unit.props.principal_moments[1] - unit.props.principal_moments[0],
              0.1 * unit.props.principal_moments[0]);

    EngineSettings es = settings(concrete(0.5, 0.5));
    es.gravity = Eigen::Vector3d::Zero();
    // No contacts here: the step only sets the integration error of the
    // spin-up (LIGGGHTS' is first order in it), so it is pinned below the
    // multisphere default (0.5 ms for this box) to check frames, not steps.
    es.time_step = 1e-4;
    es.domain_min = Eigen::Vector3d(-6, -6, -6);
    es.domain_max = Eigen::Vector3d(6, 6, 10);
    auto engine = make(es);
    engine->add_template(unit);
    const Eigen::Quaterniond q0(Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()));
    const Eigen::Quaterniond q1(Eigen::AngleAxisd(-2.0, Eigen::Vector3d(-0.7, 0.1, 0.2).normalized()));
    for (int k = 0; k < 2; ++k) {
        BodyInit body;
        body.pose.orientation = k == 0 ? q0 : q1;
        body.pose.position = Eigen::Vector3d(k == 0 ? -3.0 : 3.0, 0, 4);
        engine->add_body(body);
    }
    // A torque about world z from rest: omega(t) = I_world^-1 T t, with
    // I_world = R I_unit R^T built from the orientation the engine reports.
    const Eigen::Vector3d torque(0.0, 0.0, 2000.0);
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

// A restart continues the same run: one engine runs through, another loads
// the first one's state at 0.4 s (a cube bouncing on the floor, its contacts
// live, and a spinning cube under a held load and a turned gravity) and
// runs to the same end, bit for bit: the saving engine drops what it does
// not save (Bullet's manifolds and broadphase, LIGGGHTS' neighbour lists),
// so both continue from the same state (docs/checkpoints.md).
TEST_P(Conformance, RestartContinuesTheSameRun) {
    if (!caps().restart)
        GTEST_SKIP() << GetParam() << " has no restart";
    const auto build = [&](const std::string &suffix) {
        EngineSettings es = settings(concrete(0.3, 0.6));
        es.work_dir += suffix;
        auto engine = make(es);
        engine->add_template(test_cube(0.5, 2400.0, kCornerRadius));
        BodyInit dropped;
        dropped.pose.position = Eigen::Vector3d(-1.0, 0.0, 0.45);
        dropped.pose.orientation =
            Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 1, 0).normalized()));
        dropped.angular_velocity = Eigen::Vector3d(0.0, 2.0, 0.0);
        engine->add_body(dropped);
        BodyInit flying;
        flying.pose.position = Eigen::Vector3d(1.0, 0.0, 5.0);
        flying.angular_velocity = Eigen::Vector3d(1.0, -2.0, 3.0);
        engine->add_body(flying);
        if (has_contacts())
            engine->add_wall(floor_plane(3.0));
        return engine;
    };
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("armour_restart_" + GetParam() + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);

    auto through = build("_through");
    through->set_external_load(1, Eigen::Vector3d(0, 0, 3000.0), Eigen::Vector3d(5.0, 0, 0));
    through->advance(0.2);
    through->set_gravity(Eigen::Vector3d(0.5, 0.0, -kG));
    through->advance(0.2003); // not a whole number of steps: the clock keeps the remainder
    through->save_state(dir.string());
    const double saved_requested = through->requested_time();
    const long saved_steps = through->steps();
    through->advance(0.4);

    auto resumed = build("_resumed");
    resumed->load_state(dir.string());
    EXPECT_EQ(resumed->steps(), saved_steps);
    EXPECT_EQ(resumed->requested_time(), saved_requested);
    resumed->advance(0.4);
    EXPECT_EQ(resumed->steps(), through->steps());
    EXPECT_EQ(resumed->time(), through->time());
    double largest = 0.0;
    for (int b = 0; b < 2; ++b) {
        const BodyState a = through->state(b), r = resumed->state(b);
        EXPECT_EQ(r.external_force, a.external_force) << "body " << b;
        EXPECT_EQ(r.external_torque, a.external_torque) << "body " << b;
        const double moved = (r.pose.position - a.pose.position).norm();
        const double turned =
            2.0 * std::acos(std::min(1.0, std::abs(r.pose.orientation.dot(a.pose.orientation))));
        largest = std::max({largest, moved, 0.5 * turned}); // a turn of 2 rad moves a corner ~ the edge
        EXPECT_EQ(r.pose.position, a.pose.position) << "body " << b;
        EXPECT_EQ(r.pose.orientation.coeffs(), a.pose.orientation.coeffs()) << "body " << b;
        EXPECT_EQ(r.velocity, a.velocity) << "body " << b;
        EXPECT_EQ(r.angular_velocity, a.angular_velocity) << "body " << b;
        EXPECT_EQ(r.contact_force, a.contact_force) << "body " << b;
    }
    EXPECT_LT(largest, 1e-3 * 0.5);
    std::printf("[ restart  ] %s: largest difference after 0.4 s resumed: %.3g m (edge 0.5 m)\n",
                GetParam().c_str(), largest);
    std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Registered, Conformance, ::testing::ValuesIn(registered_styles()),
                         [](const ::testing::TestParamInfo<std::string> &p) { return p.param; });
