// What is LIGGGHTS' own beyond the conformance suite (test_engines.cpp):
// restitution of its contact laws and its time-step refusal.
#include "engine_test_kit.h"
#include "liggghts_engine.h"
#include "time_step.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

using namespace armour;
using namespace armour::test;

namespace {

EngineSettings settings_for(const std::string &test, Material material) {
    EngineSettings s;
    s.work_dir = (std::filesystem::temp_directory_path() / ("armour_liggghts_" + test)).string();
    s.materials = {std::move(material)};
    s.domain_min = Eigen::Vector3d(-3, -3, -1);
    s.domain_max = Eigen::Vector3d(3, 3, 8);
    return s;
}

std::string current_test() {
    return ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

} // namespace

namespace {

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

} // namespace

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

TEST(LiggghtsEngine, RefusesAnUnstableTimeStepUnlessForced) {
    EngineSettings settings = settings_for(current_test(), concrete(0.5, 0.5));
    const UnitTemplate unit = test_cube(0.5, 2400.0, 0.1);
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
