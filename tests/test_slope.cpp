// Armour layers on a slope: the profiler's ball on known geometry, the layer
// figures of hand-placed regular layers whose thickness and porosity are
// known, and the settle criterion.
#include "analysis.h"
#include "cli.h"
#include "damage_analysis.h"
#include "engine_registry.h"
#include "shapes.h"
#include "slope_profile.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

using armour::BodyState;
using Eigen::Vector3d;

namespace {

constexpr double kA = 0.2; // m, cube edge

// Cubes of edge kA lying face-down on a 1:1.5 slope, as placed by hand.
struct CubeSlope {
    armour::Scene scene;
    armour::SceneSetup setup;
    armour::SlopeFrame frame;
    std::vector<BodyState> states;
    Eigen::Quaterniond turn;
    CubeSlope() {
        armour::SceneWall slope;
        slope.type = "slope";
        slope.cot = 1.5;
        slope.height = 2.0;
        slope.width = 3.0;
        scene.walls.push_back(slope);
        scene.analysis = "slope";
        const armour::Shape cube = armour::make_cube_shape(kA, 0.0, 2400.0);
        armour::UnitTemplate unit;
        unit.mesh = cube.mesh;
        unit.props = cube.props;
        setup.units.push_back(unit);
        setup.unit_Dn.push_back(cube.Dn());
        frame = *armour::slope_frame(scene);
        turn = Eigen::AngleAxisd(-std::atan2(1.0, 1.5), Vector3d::UnitY());
    }
    // A cube centred at slope coordinates (s, y, n).
    void place(double s, double y, double n) {
        armour::BodyInit b;
        b.pose.position = frame.origin + s * frame.along + y * frame.across + n * frame.normal;
        b.pose.orientation = turn;
        setup.bodies.push_back(b);
        BodyState st;
        st.pose = b.pose;
        states.push_back(st);
    }
    // rows x columns cubes, touching up the slope, `pitch` apart across it, at height n.
    void layer(int rows, int columns, double pitch, double n) {
        for (int i = 0; i < rows; ++i)
            for (int j = 0; j < columns; ++j)
                place((i + 0.5) * kA, (j - 0.5 * (columns - 1)) * pitch, n);
    }
};

// A 1 m wide slope of 2400 kg/m^3 cubes for the damage analysis, under waves
// 0.28 m high of `wave_period` s; its records a coupled run's, the first of
// them the settled pose.
CubeSlope damage_slope(double wave_period) {
    CubeSlope c;
    c.scene.walls[0].width = 1.0;
    c.scene.analysis = "damage";
    c.scene.fluid = armour::SceneFluid();
    armour::SceneUnit unit;
    unit.name = c.setup.units[0].name;
    unit.density = 2400.0;
    c.scene.units.push_back(unit);
    c.scene.wave_height = 0.28;
    c.scene.wave_period = wave_period;
    return c;
}

} // namespace

TEST(SlopeProfile, BallRestsOnAFaceAnEdgeAndAVertex) {
    const double r = 0.25;
    const Vector3d a(0, 0, 1), b(1, 0, 1), c(0, 1, 1);
    EXPECT_NEAR(armour::ball_contact_height(0.2, 0.2, r, a, b, c), 1.0 + r, 1e-12);
    // 0.1 beyond the edge x = 0: the ball hangs on the edge.
    EXPECT_NEAR(armour::ball_contact_height(-0.1, 0.5, r, a, b, c), 1.0 + std::sqrt(r * r - 0.01), 1e-12);
    // Beyond the corner at the origin, 0.1 in x and y.
    EXPECT_NEAR(armour::ball_contact_height(-0.1, -0.1, r, a, b, c), 1.0 + std::sqrt(r * r - 0.02), 1e-12);
    EXPECT_EQ(armour::ball_contact_height(-0.3, 0.5, r, a, b, c), -HUGE_VAL); // out of reach
    // A 45 degree face z = x: the centre sits r sqrt(2) above it.
    const Vector3d p(0, 0, 0), q(1, 0, 1), s(0, 1, 0);
    EXPECT_NEAR(armour::ball_contact_height(0.5, 0.2, r, p, q, s), 0.5 + r * std::sqrt(2.0), 1e-12);
}

// One layer of 4 x 10 cubes, rows touching, columns 0.1 a apart: the ball
// (0.5 a) cannot enter the 0.1 a gaps (it sags at most 0.005 a there), so the
// profiler reads t = a; the covered area is 4 a by 10.9 a, so
// packing = 40 / 43.6 and porosity = 1 - 40 a^3 / (43.6 a^2 t) = 0.0826.
// Stacking the same layer again doubles t and the packing, not the porosity.
TEST(SlopeProfile, RegularCubeLayersHaveTheirKnownThicknessAndPorosity) {
    CubeSlope one;
    one.layer(4, 10, 1.1 * kA, 0.5 * kA);
    const armour::LayerRegion region = armour::layer_region(one.frame, one.setup, one.states);
    ASSERT_EQ(region.bodies.size(), 40u);
    EXPECT_NEAR(region.area(), 4 * kA * 10.9 * kA, 1e-12);
    const armour::ArmourProfile profile = armour::armour_profile(one.frame, one.setup, one.states, region);
    const armour::LayerFigures f = armour::layer_figures(one.setup, region, profile, 1);
    EXPECT_NEAR(f.thickness, kA, 1e-3 * kA);
    EXPECT_LE(f.thickness, kA + 1e-12); // the envelope never rises above the tops
    EXPECT_NEAR(f.packing_density, 40.0 / 43.6, 1e-12);
    EXPECT_NEAR(f.porosity, 1.0 - 40.0 / 43.6, 1e-3);
    EXPECT_NEAR(f.layer_coefficient, 1.0, 1e-3);

    CubeSlope two;
    two.layer(4, 10, 1.1 * kA, 0.5 * kA);
    two.layer(4, 10, 1.1 * kA, 1.5 * kA);
    const armour::LayerRegion region2 = armour::layer_region(two.frame, two.setup, two.states);
    const armour::LayerFigures f2 = armour::layer_figures(
        two.setup, region2, armour::armour_profile(two.frame, two.setup, two.states, region2), 2);
    EXPECT_NEAR(f2.thickness, 2 * kA, 1e-3 * kA);
    EXPECT_NEAR(f2.packing_density, 80.0 / 43.6, 1e-12);
    EXPECT_NEAR(f2.porosity, 1.0 - 40.0 / 43.6, 1e-3);
    EXPECT_NEAR(f2.layer_coefficient, 1.0, 1e-3);
}

// A lone cube: where the ball misses it, it reads the underlayer (0).
TEST(SlopeProfile, HolesReadTheUnderlayer) {
    CubeSlope c;
    c.place(0.5 * kA, 0.0, 0.5 * kA);
    c.place(2.5 * kA, 0.0, 0.5 * kA); // a hole 1 a long between the two, wider than the ball
    const armour::LayerRegion region = armour::layer_region(c.frame, c.setup, c.states);
    const armour::ArmourProfile p = armour::armour_profile(c.frame, c.setup, c.states, region);
    ASSERT_EQ(p.ny, 10);
    const int middle = p.ns / 2; // s = 1.5 a, 0.5 a from both cubes
    EXPECT_NEAR(p.s_lo + (middle + 0.5) * p.ds, 1.5 * kA, 0.1 * kA);
    EXPECT_NEAR(p.at(middle, 5), 0.0, 1e-12);
    EXPECT_NEAR(p.at(0, 5), kA, 1e-12);
    // Taking the upper cube away erodes its a x a section and the ball's
    // overhang on its seaward edge, (a - r) r + pi r^2 / 4 (r = a / 4), on
    // every line across; the 0.1 a grid reads it within 4 %.
    std::vector<BodyState> after = c.states;
    after[1].pose.position += 5.0 * c.frame.across;
    const armour::ArmourProfile q = armour::armour_profile(c.frame, c.setup, after, region);
    const double r = 0.25 * kA, expected = kA * kA + (kA - r) * r + 0.25 * M_PI * r * r;
    EXPECT_NEAR(armour::eroded_area(p, q), expected, 0.04 * expected);
    EXPECT_EQ(armour::eroded_area(q, p), 0.0); // nothing below the first profile
}

// S from the profiles averaged across the slope: a cube that shifts across
// it (half a cube, staying on the layer) erodes nothing, though each line it
// left reads a cube's height lost.
TEST(SlopeProfile, AUnitShiftedAcrossTheSlopeErodesNothing) {
    CubeSlope c;
    c.place(0.5 * kA, -1.5 * kA, 0.5 * kA);
    c.place(0.5 * kA, 1.5 * kA, 0.5 * kA);
    const armour::LayerRegion region = armour::layer_region(c.frame, c.setup, c.states);
    const armour::ArmourProfile p = armour::armour_profile(c.frame, c.setup, c.states, region);
    std::vector<BodyState> after = c.states;
    after[1].pose.position -= 0.5 * kA * c.frame.across;
    const armour::ArmourProfile q = armour::armour_profile(c.frame, c.setup, after, region);
    double per_line = 0.0; // the lines' own eroded areas, averaged (the former S)
    for (int i = 0; i < p.ns; ++i)
        for (int j = 0; j < p.ny; ++j)
            per_line += std::max(0.0, p.at(i, j) - q.at(i, j)) * p.ds / p.ny;
    EXPECT_GT(per_line, 0.05 * kA * kA);
    EXPECT_EQ(armour::eroded_area(p, q), 0.0);
    // Taken away instead, its whole section is eroded: a cube of 4 a across.
    after[1].pose.position += 5.0 * c.frame.across;
    const armour::ArmourProfile gone = armour::armour_profile(c.frame, c.setup, after, region);
    const double r = 0.25 * kA, section = kA * kA + (kA - r) * r + 0.25 * M_PI * r * r;
    EXPECT_NEAR(armour::eroded_area(p, gone), section / 4.0, 0.1 * section / 4.0);
}

TEST(SlopeAnalysis, ReportsTheLayerAndWhetherThePileSettled) {
    CubeSlope c;
    c.layer(4, 10, 1.1 * kA, 0.5 * kA);
    c.scene.layers = 1;
    c.scene.settle_span = 0.2;
    const auto analysis = armour::make_analysis({c.scene, c.setup, "", ""});
    std::vector<BodyState> moving = c.states;
    moving[3].velocity = Vector3d(0.05, 0, 0); // faster than settle_speed 0.01 m/s
    analysis->sample(0.0, moving);
    analysis->sample(0.1, c.states);
    analysis->sample(0.2, c.states);
    EXPECT_FALSE(analysis->finished()); // quiet for 0.1 s only
    nlohmann::json summary = nlohmann::json::object();
    EXPECT_NE(analysis->write(summary), "");
    EXPECT_FALSE(summary["settled"].get<bool>());
    analysis->sample(0.3, c.states);
    EXPECT_TRUE(analysis->finished());
    summary = nlohmann::json::object();
    EXPECT_EQ(analysis->write(summary), "");
    EXPECT_TRUE(summary["settled"].get<bool>());
    EXPECT_NEAR(summary["settled_at"].get<double>(), 0.3, 1e-12);
    EXPECT_NEAR(summary["layer_thickness"].get<double>(), kA, 1e-3 * kA);
    EXPECT_NEAR(summary["porosity"].get<double>(), 1.0 - 40.0 / 43.6, 1e-3);
    EXPECT_NEAR(summary["packing_density"].get<double>(), 40.0 / 43.6, 1e-12);
    EXPECT_NEAR(summary["layer_coefficient"].get<double>(), 1.0, 1e-3);
}

TEST(SlopeAnalysis, SlowButEnergeticPilesHaveNotSettled) {
    CubeSlope c;
    c.layer(1, 2, 1.1 * kA, 0.5 * kA);
    c.scene.settle_energy = 1e-4;
    armour::SettleWatch watch(c.scene, c.setup);
    std::vector<BodyState> spinning = c.states;
    // 5 rad/s about the normal: centres at rest, kinetic energy 0.5 I w^2 =
    // 0.5 (m a^2/6) 25 = 2.08 a^2 m, far above 1e-4 of m g a per unit.
    spinning[0].angular_velocity = 5.0 * c.frame.normal;
    for (int k = 0; k <= 10; ++k)
        watch.sample(0.1 * k, spinning);
    EXPECT_FALSE(watch.settled());
    EXPECT_EQ(watch.max_speed(), 0.0);
    EXPECT_GT(watch.kinetic_energy_ratio(), 1e-4);
}

namespace {

// The slope_cubes flume (toe step 0.1 m) with a [[pattern]] of 0.2 m cubes.
std::string pattern_scene(const std::string &engine, const std::string &pattern) {
    return "name = \"pattern\"\n[run]\nengine = \"" + engine +
           "\"\nduration = 0.01\ndomain_min = [-1.6, -0.6, -0.1]\ndomain_max = [2.1, 0.6, 2.5]\n"
           "[[material]]\nname = \"concrete\"\n"
           "[[unit]]\nname = \"cube\"\nshape = \"cube\"\nsize = 0.2\nspheres = 8\n"
           "[[wall]]\nname = \"slope\"\ntype = \"slope\"\ncot = 1.5\nheight = 1.0\nwidth = 1.0\n"
           "toe_height = 0.1\n"
           "[[pattern]]\nunit = \"cube\"\nwall = \"slope\"\n" +
           pattern;
}

// A temporary path of this process's own (test runs may overlap on one machine).
std::filesystem::path temporary(const std::string &name) {
    return std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name);
}

// temporary(name) as an empty folder: an analysis's output folder.
std::filesystem::path empty_folder(const std::string &name) {
    const std::filesystem::path out = temporary(name);
    std::filesystem::remove_all(out);
    std::filesystem::create_directories(out);
    return out;
}

armour::Scene write_and_load(const std::string &name, const std::string &text) {
    const std::filesystem::path file = temporary(name);
    std::ofstream(file) << text;
    struct Removed {
        std::filesystem::path path;
        ~Removed() { std::filesystem::remove(path); }
    } removed{file};
    return armour::load_scene(file.string());
}

// The clump cache, shared by this build's test processes (each test is one process
// under ctest) but not with another checkout's, which may run its suite at the same time.
std::string cache_dir() {
    return ARMOUR_TEST_CACHE;
}

} // namespace

// With its defaults a pattern clears the toe step and places its units apart,
// as the engine collides them: the clump's spheres on a DEM engine, the
// exact cube on an exact-shape one (build_scene refuses overlaps and cuts).
TEST(SlopePattern, DefaultsPlaceClearOfTheToeAndOfEachOther) {
    for (const armour::EngineStyle &style : armour::engine_styles()) {
        if (style.capabilities.contacts == armour::ContactKind::none)
            continue;
        const armour::Scene scene =
            write_and_load("armour_test_pattern.toml", pattern_scene(style.name, "rows = 3\ncolumns = 4\n"));
        armour::SceneSetup setup;
        ASSERT_NO_THROW(setup = armour::build_scene(scene, cache_dir(), false)) << style.name;
        ASSERT_EQ(setup.bodies.size(), 12u) << style.name;
        // Neighbours at least a unit apart, centres off the slope by half a unit.
        const armour::SlopeFrame frame = *armour::slope_frame(scene);
        for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
            const Vector3d c = frame.local(setup.bodies[i].pose.position);
            EXPECT_GE(c.z(), 0.5 * kA) << style.name;
            EXPECT_GE(c.x() - 0.5 * kA, 0.0) << style.name; // landward of the toe
            for (std::size_t j = i + 1; j < setup.bodies.size(); ++j)
                EXPECT_GE((setup.bodies[i].pose.position - setup.bodies[j].pose.position).norm(), kA)
                    << style.name;
        }
    }
}

// packing_density sets the spacing Dn sqrt(layers / phi): 1.17 units per
// Dn^2 in two layers (Rock Manual, double-layer cubes), the upper layer in
// the gaps of the lower. A density no regular pattern reaches is refused.
TEST(SlopePattern, TargetsAPackingDensity) {
    const armour::Scene scene = write_and_load(
        "armour_test_packing.toml",
        pattern_scene("liggghts", "rows = 3\ncolumns = 3\nlayers = 2\npacking_density = 1.17\n"));
    const armour::SceneSetup setup = armour::build_scene(scene, cache_dir(), false);
    ASSERT_EQ(setup.bodies.size(), 9u + 6u);
    const double spacing = setup.unit_Dn[0] * std::sqrt(2.0 / 1.17);
    EXPECT_NEAR((setup.bodies[1].pose.position - setup.bodies[0].pose.position).norm(), spacing, 1e-9);
    EXPECT_NEAR((setup.bodies[3].pose.position - setup.bodies[0].pose.position).norm(), spacing, 1e-9);
    const armour::SlopeFrame frame = *armour::slope_frame(scene);
    const Vector3d lower = frame.local(setup.bodies[0].pose.position),
                   upper = frame.local(setup.bodies[9].pose.position);
    EXPECT_NEAR(upper.x() - lower.x(), 0.5 * spacing, 1e-9);
    EXPECT_NEAR(upper.y() - lower.y(), 0.5 * spacing, 1e-9);
    EXPECT_GT(upper.z() - lower.z(), kA);

    const armour::Scene dense =
        write_and_load("armour_test_dense.toml", pattern_scene("liggghts", "packing_density = 1.17\n"));
    try {
        armour::build_scene(dense, cache_dir(), false);
        FAIL() << "1.17 units per Dn^2 in one layer was placed";
    } catch (const armour::InputError &e) {
        EXPECT_NE(std::string(e.what()).find("key 'pattern.0.packing_density'"), std::string::npos)
            << e.what();
    }
}

// A [[drop]] keeps units apart by the shape the engine collides, not by
// their enclosing spheres (a 20-sphere cube clump's reach 0.197 m, ~2 Dn
// apart): 24 cubes of 0.2 m go into a 0.8 m box of centres, which a pile at
// the Rock Manual's porosity 0.47 fills with 66 (0.53 x 1 m^3 / 0.008 m^3),
// units placed one by one at random without settling with ~30 (the clumps:
// measured 30 of 33), and enclosing spheres with 12-16 (slope_cubes' 30 took
// 22 so).
TEST(SlopeDrop, FillsARegionAsALoosePileWould) {
    for (const armour::EngineStyle &style : armour::engine_styles()) {
        if (style.capabilities.contacts == armour::ContactKind::none)
            continue;
        const armour::Scene scene = write_and_load(
            "armour_test_drop.toml",
            "name = \"drop\"\n[run]\nengine = \"" + style.name +
                "\"\nduration = 0.01\ndomain_min = [-1, -1, -1]\ndomain_max = [1, 1, 1]\n"
                "[[material]]\nname = \"concrete\"\n"
                "[[unit]]\nname = \"cube\"\nshape = \"cube\"\nsize = 0.2\nspheres = 20\n"
                "[[drop]]\nunit = \"cube\"\ncount = 24\nmin = [-0.4, -0.4, -0.4]\nmax = [0.4, 0.4, 0.4]\n");
        armour::SceneSetup setup;
        ASSERT_NO_THROW(setup = armour::build_scene(scene, cache_dir(), false)) << style.name;
        ASSERT_EQ(setup.bodies.size(), 24u) << style.name;
        // No two apart by less than their collided shapes: no clump spheres
        // overlapping, no exact cube's corner inside another.
        const bool spheres = style.capabilities.shape == armour::ShapeModel::sphere_clumps;
        const armour::Clump &clump = setup.units[0].clump;
        int overlaps = 0, within_reach = 0;
        for (const armour::BodyInit &a : setup.bodies)
            for (const armour::BodyInit &b : setup.bodies) {
                if (&a == &b)
                    continue;
                within_reach += (a.pose.position - b.pose.position).norm() < 2.0 * 0.197;
                if (spheres) {
                    for (const auto &sa : clump)
                        for (const auto &sb : clump)
                            overlaps += ((a.pose.position + a.pose.orientation * sa.center) -
                                         (b.pose.position + b.pose.orientation * sb.center))
                                            .norm() < sa.radius + sb.radius;
                } else {
                    for (const Vector3d &v : setup.units[0].mesh.vertices) {
                        const Vector3d in_b = b.pose.orientation.inverse() *
                                              (a.pose.position + a.pose.orientation * v - b.pose.position);
                        overlaps += in_b.cwiseAbs().maxCoeff() < 0.5 * kA;
                    }
                }
            }
        EXPECT_EQ(overlaps, 0) << style.name;
        EXPECT_GT(within_reach, 0) << style.name << ": no two units within each other's enclosing spheres";
    }
}

// ---------------------------------------------------------------- damage

TEST(Damage, FormulasGiveThePublishedNumbers) {
    // stability.md's table (Van der Meer 1988, N = 1000, s_om = 0.03) and Hudson at cot 1.5.
    EXPECT_NEAR(armour::van_der_meer_cubes_ns(0.0, 1000, 0.03), 1.42, 0.005);
    EXPECT_NEAR(armour::van_der_meer_cubes_ns(0.5, 1000, 0.03), 2.33, 0.005);
    EXPECT_NEAR(armour::van_der_meer_cubes_ns(2.0, 1000, 0.03), 3.00, 0.005);
    EXPECT_NEAR(armour::van_der_meer_cubes_ns(0.5, 3000, 0.02), 2.16, 0.005);
    // Solved for N_od: the same points back, and nothing below the curve's floor.
    for (const double n : {0.1, 0.5, 2.0})
        EXPECT_NEAR(armour::van_der_meer_cubes_n_od(armour::van_der_meer_cubes_ns(n, 1000, 0.03), 1000, 0.03),
                    n, 1e-9 * n);
    EXPECT_EQ(armour::van_der_meer_cubes_n_od(1.4, 1000, 0.03), 0.0); // floor 1.42
    EXPECT_NEAR(armour::van_der_meer_cubes_n_od(2.33, 1000, 0.03), 0.5, 0.01);
    EXPECT_NEAR(armour::hudson_ns(6.5, 1.5), 2.14, 0.005);
    EXPECT_NEAR(armour::hudson_ns(7.5, 1.5), 2.24, 0.005);
    EXPECT_DOUBLE_EQ(armour::stability_number(0.28, 2400, 1000, 0.2), 1.0);
    EXPECT_DOUBLE_EQ(armour::n_od(3, 1.0, 0.2), 0.6);
}

TEST(Damage, RockingIsAnExcursionThatComesBack) {
    armour::Pose rest;
    armour::UnitDamageTracker unit(rest, 0.2, 5.0, 2.0);
    const auto turned = [&](double deg) {
        armour::Pose p = rest;
        p.orientation = Eigen::AngleAxisd(deg * M_PI / 180.0, Vector3d::UnitX());
        return p;
    };
    double t = 0.0;
    for (const double deg : {0.0, 3.0, 6.0, 4.0, 2.0, 7.0, 1.0, 4.9, 2.6, 9.0, 8.0})
        unit.sample(t += 0.1, turned(deg));
    // 6 -> 2 and 7 -> 1 return below half the threshold; 4.9 never passed
    // it; 9 -> 8 has not come back.
    EXPECT_EQ(unit.rocking_events(), 2);
    EXPECT_NEAR(unit.max_rotation_deg(), 9.0, 1e-9);
    EXPECT_EQ(unit.max_displacement(), 0.0);

    // It comes to rest at 8 degrees (within a tenth of the threshold for the
    // rest time, 2 s, in records 0.4 s apart: under a quarter of it): a new
    // seat, not an event. It then rocks about that seat twice (past 5
    // degrees from it and back below 2.5), which counted from the settled
    // pose, never back below 2.5 degrees, would be no event.
    for (const double deg : {8.2, 7.9, 8.0, 8.1, 7.95, 8.0, 8.05})
        unit.sample(t += 0.4, turned(deg));
    EXPECT_EQ(unit.rocking_events(), 2);
    for (const double deg : {10.0, 14.0, 9.0, 8.1, 12.0, 13.5, 10.0, 7.5, 8.0})
        unit.sample(t += 0.1, turned(deg));
    EXPECT_EQ(unit.rocking_events(), 4);
    EXPECT_NEAR(unit.max_rotation_deg(), 14.0, 1e-9);
    // Resting less than the rest time is no new seat: 13.5 -> 8 is one more
    // event about the 8-degree seat.
    for (const double deg : {13.5, 13.6, 13.5})
        unit.sample(t += 0.4, turned(deg));
    unit.sample(t += 0.1, turned(8.0));
    EXPECT_EQ(unit.rocking_events(), 5);

    // Records 2.5 s apart: two alike are no rest (kRestSamples), so 8 -> 8 -> 1
    // is an excursion that came back.
    armour::UnitDamageTracker coarse(rest, 0.2, 5.0, 2.0);
    t = 0.0;
    for (const double deg : {0.0, 8.0, 8.0, 1.0})
        coarse.sample(t += 2.5, turned(deg));
    EXPECT_EQ(coarse.rocking_events(), 1);
    // However long it holds a pose: records 2.5 s apart may catch a unit
    // rocking once a wave at one phase of its swing, so they never rest.
    armour::UnitDamageTracker held(rest, 0.2, 5.0, 2.0);
    t = 0.0;
    for (const double deg : {0.0, 8.0, 8.0, 8.0, 8.0, 8.0, 1.0})
        held.sample(t += 2.5, turned(deg));
    EXPECT_EQ(held.rocking_events(), 1);

    // The rest time is a wave period, at least 2 s.
    armour::Scene scene;
    EXPECT_EQ(armour::rest_time(scene), 2.0);
    scene.wave_period = 2.6;
    EXPECT_EQ(armour::rest_time(scene), 2.6);
    scene.waves = armour::SceneWaves();
    scene.waves->type = "irregular";
    scene.waves->tp = 3.1;
    EXPECT_EQ(armour::rest_time(scene), 3.1);
}

TEST(Damage, WaveConditionsPreferTheMeasuredIncidentWave) {
    armour::Scene scene;
    scene.wave_height = 0.3;
    scene.wave_period = 2.0;
    const armour::WaveConditions target = armour::wave_conditions(nlohmann::json::object(), scene, 100.0);
    EXPECT_EQ(target.source, "scene");
    EXPECT_DOUBLE_EQ(*target.Hs, 0.3);
    EXPECT_NEAR(*target.s_om, 2 * M_PI * 0.3 / (9.81 * 4.0), 1e-3);
    EXPECT_DOUBLE_EQ(*target.waves, 50.0);
    const nlohmann::json measured = {{"incident_height", 0.25}, {"s_om", 0.03}, {"waves", 480}};
    const armour::WaveConditions m = armour::wave_conditions(measured, scene, 100.0);
    EXPECT_EQ(m.source, "measured");
    EXPECT_DOUBLE_EQ(*m.Hs, 0.25);
    EXPECT_DOUBLE_EQ(*m.s_om, 0.03);
    EXPECT_DOUBLE_EQ(*m.waves, 480.0);
    scene.wave_height = 0.0;
    EXPECT_EQ(armour::wave_conditions(nlohmann::json::object(), scene, 100.0).source, "none");
    // A waves object without a measured height (a record too short for the
    // analysis) lends none of its figures.
    const nlohmann::json unmeasured = {{"s_om", 0.03}, {"waves", 480}};
    const armour::WaveConditions none = armour::wave_conditions(unmeasured, scene, 100.0);
    EXPECT_EQ(none.source, "none");
    EXPECT_FALSE(none.s_om || none.waves || none.Hs);

    // No measured waves and no analysis.wave_height: the [waves] train's target.
    scene.waves = armour::SceneWaves();
    scene.waves->height = 0.1;
    scene.waves->period = 2.0;
    const armour::WaveConditions regular = armour::wave_conditions(nlohmann::json::object(), scene, 100.0);
    EXPECT_EQ(regular.source, "target");
    EXPECT_DOUBLE_EQ(*regular.Hs, 0.1);
    EXPECT_NEAR(*regular.s_om, 2 * M_PI * 0.1 / (9.81 * 4.0), 1e-3 * *regular.s_om);
    EXPECT_DOUBLE_EQ(*regular.waves, 50.0);
    // Irregular: Hs and the mean period Tm0,2 of the generated JONSWAP band
    // (0.5-2.5 fp, gamma 3.3; 0.84 Tp): above the ~0.78 Tp of the untruncated
    // spectrum (its tail adds to m2), below the 0.885 Tp measured in the flume.
    scene.waves->type = "irregular";
    scene.waves->hs = 0.12;
    scene.waves->tp = 1.8;
    scene.waves->components = 200;
    const armour::WaveConditions irregular = armour::wave_conditions(nlohmann::json::object(), scene, 100.0);
    EXPECT_EQ(irregular.source, "target");
    EXPECT_DOUBLE_EQ(*irregular.Hs, 0.12);
    const double tm = 100.0 / *irregular.waves;
    EXPECT_GT(tm / 1.8, 0.78);
    EXPECT_LT(tm / 1.8, 0.92);
    EXPECT_NEAR(*irregular.s_om, 2 * M_PI * 0.12 / (9.81 * tm * tm), 1e-12);
    // analysis.wave_height, when set, is the user's figure and comes first.
    scene.wave_height = 0.3;
    EXPECT_EQ(armour::wave_conditions(nlohmann::json::object(), scene, 100.0).source, "scene");
    // The measured incident wave comes before both.
    EXPECT_EQ(armour::wave_conditions(measured, scene, 100.0).source, "measured");
}

// N counts the waves at the structure: from the front's arrival at the toe,
// at the group velocity; deep water (T = 1 s, h = 10 m, kh = 40): g T / (4 pi).
TEST(Damage, WavesActFromTheFrontsArrivalAtTheToe) {
    armour::Scene scene;
    scene.domain_min = Eigen::Vector3d(-2.0, 0.0, 0.0);
    scene.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
    EXPECT_DOUBLE_EQ(armour::acting_seconds(scene, 5.0, 1.0, 30.0), 29.0); // no train: the record
    scene.fluid = armour::SceneFluid();
    scene.fluid->water_level = 10.0;
    scene.waves = armour::SceneWaves();
    scene.waves->type = "regular";
    scene.waves->period = 1.0;
    const double cg = 9.81 / (4.0 * M_PI);
    const double toe_x = 10.0 * cg - 2.0; // 10 s from the maker at x = -2 m
    ASSERT_TRUE(armour::wave_front_arrival(scene, toe_x).has_value());
    EXPECT_NEAR(*armour::wave_front_arrival(scene, toe_x), 10.0, 1e-6);
    EXPECT_NEAR(armour::acting_seconds(scene, toe_x, 0.0, 30.0), 20.0, 1e-6);
    EXPECT_NEAR(armour::acting_seconds(scene, toe_x, 12.0, 30.0), 18.0, 1e-12); // a record after it
    EXPECT_EQ(armour::acting_seconds(scene, toe_x, 0.0, 8.0), 0.0);             // before it
    scene.waves->type = "solitary";
    EXPECT_DOUBLE_EQ(armour::acting_seconds(scene, toe_x, 0.0, 30.0), 30.0);
    EXPECT_FALSE(armour::wave_front_arrival(scene, toe_x).has_value());
}

// A layer of 4 rows x 5 touching cubes across a 1 m slope (5 strips of Dn):
// the second row is washed away (5 displaced: N_od = 1), a row-1 cube rocks
// 10 degrees twice about the face's normal and comes back, a row-4 cube
// turns 8 degrees and stays. The profiler reads the lost row as a^2 less
// the ball's overhang on both edges: S = 1 - 2 ((a - r) r + pi r^2 / 4) / a^2
// = 0.527 (r = a / 4).
TEST(Damage, SyntheticTrajectoriesGiveTheirKnownFigures) {
    CubeSlope c = damage_slope(2.0);
    c.layer(4, 5, kA, 0.5 * kA);
    const std::filesystem::path out = empty_folder("armour_test_damage");
    const auto analysis = armour::make_analysis({c.scene, c.setup, out.string(), ""});
    const auto spun = [&](const BodyState &s, double deg) {
        BodyState t = s;
        t.pose.orientation = Eigen::AngleAxisd(deg * M_PI / 180.0, c.frame.normal) * s.pose.orientation;
        return t;
    };
    std::vector<BodyState> now = c.states;
    double t = 0.0;
    analysis->sample(t, now);
    for (const double deg : {10.0, 0.0, 10.0, 0.0}) {
        now[2] = spun(c.states[2], deg);
        now[17] = spun(c.states[17], 8.0);
        analysis->sample(t += 0.5, now);
    }
    for (int k = 5; k < 10; ++k)
        now[static_cast<std::size_t>(k)].pose.position += 10.0 * c.frame.across; // washed off the slope
    analysis->sample(t += 0.5, now);
    nlohmann::json summary = nlohmann::json::object();
    analysis->write(summary);
    EXPECT_FALSE(summary.contains("warnings"))
        << summary["warnings"].dump(); // records a quarter of 2 s apart
    EXPECT_EQ(summary["units"].get<int>(), 20);
    EXPECT_EQ(summary["units_displaced"].get<int>(), 5);
    EXPECT_DOUBLE_EQ(summary["N_od"].get<double>(), 1.0);
    EXPECT_EQ(summary["rocking_units"].get<int>(), 1);
    const double r = 0.25 * kA, S = 1.0 - 2.0 * ((kA - r) * r + 0.25 * M_PI * r * r) / (kA * kA);
    EXPECT_NEAR(summary["damage_S"].get<double>(), S, 0.05 * S);
    EXPECT_NEAR(summary["Ns"].get<double>(), 0.28 / (1.4 * kA), 1e-12);
    const double s_om = 2 * M_PI * 0.28 / (9.81 * 4.0);
    EXPECT_NEAR(summary["s_om"].get<double>(), s_om, 1e-3 * s_om);
    EXPECT_NEAR(summary["waves"].get<double>(), 1.25, 1e-12); // 2.5 s of 2 s waves
    EXPECT_NEAR(summary["Ns_van_der_meer"].get<double>(), armour::van_der_meer_cubes_ns(1.0, 1.25, s_om),
                1e-3);
    const double predicted = armour::van_der_meer_cubes_n_od(0.28 / (1.4 * kA), 1.25, s_om);
    EXPECT_NEAR(summary["N_od_van_der_meer"].get<double>(), predicted, 1e-3 * predicted + 1e-12);
    EXPECT_DOUBLE_EQ(summary["damage"]["layer_width"].get<double>(), 1.0); // wall to wall
    EXPECT_TRUE(summary["damage"]["van_der_meer_outside"].empty());        // 1:1.5, s_om 0.045
    EXPECT_NEAR(summary["units_displaced_van_der_meer"].get<double>() /
                    summary["damage"]["layer_width"].get<double>() * kA,
                predicted, 1e-3 * predicted + 1e-12);
    EXPECT_NEAR(summary["Ns_hudson_breaking"].get<double>(), std::cbrt(6.5 * 1.5), 1e-12);
    EXPECT_NEAR(summary["Ns_hudson_nonbreaking"].get<double>(), std::cbrt(7.5 * 1.5), 1e-12);

    std::ifstream csv(out / "damage.csv");
    std::vector<std::string> lines;
    for (std::string line; std::getline(csv, line);)
        lines.push_back(line);
    ASSERT_EQ(lines.size(), 2u + 20u); // comment, header, one row per unit
    // rocking_events, displaced, left_at_s, turn_per_Dn_deg: unit 2 rocked twice and stays; unit 5
    // left at 2.5 s without turning.
    EXPECT_EQ(lines[2 + 2].substr(lines[2 + 2].size() - 6), ",2,0,,");
    EXPECT_EQ(lines[2 + 5].substr(lines[2 + 5].size() - 8), ",1,2.5,0");
    EXPECT_TRUE(std::filesystem::is_regular_file(out / "damage_history.csv"));
    EXPECT_GT(std::filesystem::file_size(out / "damage.png"), 1000u);
    std::filesystem::remove_all(out);
}

// N_od counts the strips of Dn the layer has, not the wall's: a layer two
// cubes wide in the middle of a 1 m wall (0.3 m to either side, more than a
// Dn) has 2 strips, and one cube washed off is N_od = 0.5 (the wall's 5
// strips would read 0.2); four cubes wide (0.1 m gaps, no room for a unit)
// the layer reaches the walls: 5 strips. A run past Van der Meer's tested
// range (s_om 0.18 on a 1:2 slope) says which limits it is outside.
TEST(Damage, NodCountsTheLayersStripsAndVanDerMeersRangeIsStated) {
    for (const int columns : {2, 4}) {
        CubeSlope c = damage_slope(columns == 2 ? 2.0 : 1.0);
        if (columns == 4) {
            c.scene.walls[0].cot = 2.0;
            c.frame = *armour::slope_frame(c.scene);
            c.turn = Eigen::AngleAxisd(-std::atan2(1.0, 2.0), Vector3d::UnitY());
        }
        c.layer(3, columns, kA, 0.5 * kA);
        const std::filesystem::path out = empty_folder("armour_test_damage_strips");
        const auto analysis = armour::make_analysis({c.scene, c.setup, out.string(), ""});
        std::vector<BodyState> now = c.states;
        analysis->sample(0.0, now);
        now[1].pose.position += 10.0 * c.frame.across; // washed off the slope
        analysis->sample(1.0, now);
        nlohmann::json summary = nlohmann::json::object();
        const std::string line = analysis->write(summary);
        EXPECT_EQ(summary["units_displaced"].get<int>(), 1);
        const double width = columns == 2 ? 2 * kA : 1.0;
        EXPECT_NEAR(summary["damage"]["layer_width"].get<double>(), width, 1e-12);
        EXPECT_DOUBLE_EQ(summary["damage"]["slope_width"].get<double>(), 1.0);
        EXPECT_NEAR(summary["N_od"].get<double>(), 1.0 / (width / kA), 1e-12);
        // Records 1 s apart, over a quarter of the rest time (2 s): said so.
        ASSERT_EQ(summary["warnings"].size(), 1u) << summary.dump();
        EXPECT_NE(summary["warnings"][0].get<std::string>().find("records up to 1 s apart"),
                  std::string::npos);
        EXPECT_NE(line.find("no unit finds a new seat"), std::string::npos) << line;
        const nlohmann::json &outside = summary["damage"]["van_der_meer_outside"];
        if (columns == 2) {
            EXPECT_TRUE(outside.empty()) << outside.dump();
        } else {
            ASSERT_EQ(outside.size(), 2u) << outside.dump();
            EXPECT_NE(outside[0].get<std::string>().find("1:1.5"), std::string::npos) << outside.dump();
            EXPECT_NE(outside[1].get<std::string>().find("s_om 0.179"), std::string::npos) << outside.dump();
            EXPECT_NE(line.find("outside Van der Meer's tested range"), std::string::npos) << line;
        }
        std::filesystem::remove_all(out);
    }
}

namespace {

// A CSV file's rows as cells, its '#' comment lines and empty lines left out.
std::vector<std::vector<std::string>> csv_cells(const std::filesystem::path &path) {
    std::ifstream csv(path);
    std::vector<std::vector<std::string>> rows;
    for (std::string line; std::getline(csv, line);) {
        if (line.empty() || line[0] == '#')
            continue;
        std::vector<std::string> cells;
        std::stringstream in(line);
        for (std::string cell; std::getline(in, cell, ',');)
            cells.push_back(cell);
        rows.push_back(cells);
    }
    return rows;
}

} // namespace

// The units at the foot: a cube whose settled centre lies seaward of the
// face's foot (0.2 a up the face but 1.5 a out of it: x = a (0.2 cos - 1.5
// sin) < 0, over the toe) is counted apart from one on the face (2.5 a up,
// 0.5 a out). Both washed away: 2 displaced, 1 of them at the foot;
// damage.csv gives each its height out of the face and its flag.
TEST(Damage, UnitsSeawardOfTheFacesFootAreCountedApart) {
    CubeSlope c = damage_slope(2.0);
    c.place(0.2 * kA, 0.0, 1.5 * kA);
    c.place(2.5 * kA, 0.0, 0.5 * kA);
    c.place(2.5 * kA, 2.0 * kA, 0.5 * kA); // stays
    const std::filesystem::path out = empty_folder("armour_test_damage_foot");
    const auto analysis = armour::make_analysis({c.scene, c.setup, out.string(), ""});
    std::vector<BodyState> now = c.states;
    analysis->sample(0.0, now);
    for (const std::size_t k : {0u, 1u})
        now[k].pose.position += 10.0 * c.frame.across;
    analysis->sample(1.0, now);
    nlohmann::json summary = nlohmann::json::object();
    const std::string result = analysis->write(summary);
    EXPECT_EQ(summary["units_displaced"].get<int>(), 2);
    EXPECT_EQ(summary["units_displaced_at_foot"].get<int>(), 1);
    EXPECT_EQ(result.rfind("2 of 3 units displaced (1 at the foot), N_od ", 0), 0u) << result;

    const auto rows = csv_cells(out / "damage.csv");
    ASSERT_EQ(rows.size(), 4u); // header, three units
    EXPECT_EQ(rows[0][4], "n_m");
    EXPECT_EQ(rows[0][5], "at_foot");
    EXPECT_NEAR(std::stod(rows[1][4]), 1.5 * kA, 1e-9);
    EXPECT_EQ(rows[1][5], "1");
    EXPECT_NEAR(std::stod(rows[2][4]), 0.5 * kA, 1e-9);
    EXPECT_EQ(rows[2][5], "0");
    EXPECT_EQ(rows[3][5], "0");
    std::filesystem::remove_all(out);
}

// A cube resting on the layer (its centre 1.5 a out of the face, over a layer
// of cubes lying flat, a thick) is on top of it: flagged in damage.csv's
// on_top, counted in the settled layer's units_on_top, and when it washes
// off, in units_displaced_on_top and the result line; the layer's own cubes
// (centres 0.5 a out) are not. Its left_at_s is when it went for good.
TEST(Damage, UnitsRestingOnTheLayerAreCountedApart) {
    CubeSlope c = damage_slope(2.0);
    c.layer(4, 4, 1.1 * kA, 0.5 * kA);
    c.place(0.2 * kA, 2.2 * kA, 1.5 * kA); // as high, but seaward of the face's foot: at_foot, not on_top
    c.place(2.0 * kA, 0.0, 1.5 * kA);
    const std::filesystem::path out = empty_folder("armour_test_damage_on_top");
    const auto analysis = armour::make_analysis({c.scene, c.setup, out.string(), ""});
    // The top cube washes off at 1 s, is set back at 2 s and washes off again at 3 s: it left at 3 s.
    std::vector<BodyState> now = c.states;
    analysis->sample(0.0, now);
    for (const double t : {1.0, 2.0, 3.0}) {
        now.back().pose.position = c.states.back().pose.position + (t == 2.0 ? 0.0 : 10.0) * c.frame.across;
        analysis->sample(t, now);
    }
    nlohmann::json summary = nlohmann::json::object();
    const std::string result = analysis->write(summary);
    const double thickness = summary["damage"]["settled_layer"]["layer_thickness"].get<double>();
    EXPECT_GT(thickness, 0.5 * kA);
    EXPECT_LT(thickness, 1.5 * kA);
    EXPECT_EQ(summary["damage"]["settled_layer"]["units_on_top"].get<int>(), 1);
    EXPECT_EQ(summary["units_displaced"].get<int>(), 1);
    EXPECT_EQ(summary["units_displaced_on_top"].get<int>(), 1);
    EXPECT_EQ(result.rfind("1 of 18 units displaced (1 from on top of the layer), N_od ", 0), 0u) << result;

    std::vector<std::string> flags, left; // on_top and left_at_s, a row per unit
    for (const auto &cells : csv_cells(out / "damage.csv")) {
        flags.push_back(cells[6]);
        left.push_back(cells.size() > 12 ? cells[12] : "");
    }
    ASSERT_EQ(flags.size(), 19u); // header, 18 units
    EXPECT_EQ(flags[0], "on_top");
    EXPECT_EQ(std::count(flags.begin() + 1, flags.end(), "1"), 1);
    EXPECT_EQ(flags.back(), "1");
    EXPECT_EQ(left[0], "left_at_s");
    EXPECT_EQ(left.back(), "3");
    EXPECT_EQ(std::count(left.begin() + 1, left.end(), ""), 17); // the others stayed
    std::filesystem::remove_all(out);
}

// A displaced unit's way out over its last move, from its last record under a
// fifth of the threshold (0.1 Dn here) to its pass (1.1 Dn): two cubes of the
// layer move 1 Dn across the face in the same records; the first keeps its
// pose's turn (0 deg per Dn: slid), the second turns about the across axis 45
// deg and then 90 deg from that start (90 deg per Dn: a cube's roll over an
// edge), so it counts in units_displaced_rolled; the others stay (no figure).
TEST(Damage, EachDisplacedUnitSaysHowFarItTurnedPerDnItMoved) {
    CubeSlope c = damage_slope(2.0);
    c.layer(4, 4, 1.1 * kA, 0.5 * kA);
    const std::filesystem::path out = empty_folder("armour_test_damage_way_out");
    const auto analysis = armour::make_analysis({c.scene, c.setup, out.string(), ""});
    std::vector<BodyState> now = c.states;
    analysis->sample(0.0, now);
    const double moved[] = {0.1, 0.6, 1.1}, turned[] = {0.0, 45.0, 90.0}; // Dn, deg at 1, 2 and 3 s
    for (int k = 0; k < 3; ++k) {
        for (const int b : {0, 1})
            now[b].pose.position = c.states[b].pose.position + moved[k] * kA * c.frame.across;
        now[1].pose.orientation = Eigen::AngleAxisd(turned[k] * M_PI / 180.0, c.frame.across) * c.turn;
        analysis->sample(1.0 + k, now);
    }
    nlohmann::json summary = nlohmann::json::object();
    const std::string result = analysis->write(summary);
    EXPECT_EQ(result.rfind("2 of 16 units displaced (1 rolled out), N_od ", 0), 0u) << result;
    EXPECT_EQ(summary["units_displaced"].get<int>(), 2);
    EXPECT_EQ(summary["units_displaced_rolled"].get<int>(), 1);
    const auto rows = csv_cells(out / "damage.csv");
    ASSERT_EQ(rows.size(), 17u); // header, 16 units
    ASSERT_EQ(rows[0].size(), 14u);
    EXPECT_EQ(rows[0][13], "turn_per_Dn_deg");
    EXPECT_NEAR(std::stod(rows[1][13]), 0.0, 1e-6);
    EXPECT_NEAR(std::stod(rows[2][13]), 90.0, 1e-6);
    for (std::size_t r = 3; r < rows.size(); ++r)
        EXPECT_TRUE(rows[r].size() < 14 || rows[r][13].empty()) << "unit " << r - 1;
    std::filesystem::remove_all(out);
}

// A layer of two sizes, or of two densities, has no one Dn for N_od's strips
// and no one delta for Ns: refused before any tool runs, naming both units.
TEST(Damage, MixedUnitsAreRefusedNamingBoth) {
    CubeSlope c;
    c.scene.analysis = "damage";
    for (const char *name : {"cube", "big"}) {
        armour::SceneUnit unit;
        unit.name = name;
        unit.density = 2400.0;
        c.scene.units.push_back(unit);
    }
    c.setup.units[0].name = "cube";
    c.layer(1, 2, kA, 0.5 * kA);
    EXPECT_EQ(armour::analysis_refusal(c.scene, c.setup), "");
    c.setup.units.push_back(c.setup.units[0]);
    c.setup.units[1].name = "big";
    c.setup.unit_Dn.push_back(1.5 * kA);
    c.setup.bodies[1].unit = 1;
    const std::string why = armour::analysis_refusal(c.scene, c.setup);
    EXPECT_NE(why.find("one size and density"), std::string::npos) << why;
    EXPECT_NE(why.find("'cube' (Dn 0.2 m, 2400 kg/m^3) and 'big' (Dn 0.3 m, 2400 kg/m^3)"), std::string::npos)
        << why;
    c.setup.unit_Dn[1] = kA; // the same size, a lighter concrete
    c.scene.units[1].density = 2300.0;
    EXPECT_NE(armour::analysis_refusal(c.scene, c.setup).find("'big' (Dn 0.2 m, 2300 kg/m^3) differ"),
              std::string::npos);
    EXPECT_EQ(armour::analysis_refusal(c.scene, armour::SceneSetup()), "needs a body");
}

TEST(Damage, ASceneWithoutASlopeIsRefusedNamingTheKey) {
    const std::string text = "name = \"flat\"\n[analysis]\nkind = \"damage\"\n[[material]]\nname = \"m\"\n"
                             "[[unit]]\nname = \"u\"\nshape = \"cube\"\nsize = 0.2\n"
                             "[[wall]]\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, "
                             "1]\n[[body]]\nunit = \"u\"\nposition = [0, 0, 0.2]\n";
    try {
        write_and_load("armour_test_flat_damage.toml", text);
        FAIL() << "a damage analysis without a slope was accepted";
    } catch (const armour::InputError &e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("key 'analysis.kind'"), std::string::npos) << what;
        EXPECT_NE(what.find("[[wall]] of type \"slope\""), std::string::npos) << what;
    }
}

// A short dry run of the slope_cubes scene with kind damage writes every
// file and headline key.
TEST(Damage, ADrySlopeRunWritesEveryFileAndKey) {
    const std::filesystem::path dir = temporary("armour_test_damage_run");
    std::filesystem::remove_all(dir);
    const std::string scene =
        (std::filesystem::path(ARMOUR_SOURCE_DIR) / "scenes" / "slope_cubes.toml").string();
    const std::vector<std::string> args = {"armour",
                                           "run",
                                           scene,
                                           "--out",
                                           (dir / "out").string(),
                                           "--cache",
                                           cache_dir(),
                                           "--set",
                                           "analysis.kind=\"damage\"",
                                           "--set",
                                           "run.duration=0.1",
                                           "--set",
                                           "drop.0.count=6",
                                           "--set",
                                           "analysis.wave_height=0.3",
                                           "--set",
                                           "analysis.wave_period=2.0"};
    std::vector<const char *> argv;
    for (const auto &a : args)
        argv.push_back(a.c_str());
    ASSERT_EQ(armour::armour_main(static_cast<int>(argv.size()), argv.data()), 0);
    for (const char *file : {"damage.csv", "damage_history.csv", "damage.png", "summary.json", "bodies.h5"})
        EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out" / file)) << file;
    std::ifstream in(dir / "out" / "summary.json");
    const nlohmann::json summary = nlohmann::json::parse(in);
    // With analysis.wave_height and wave_period every figure has a source: a number.
    for (const char *key : {"units", "units_displaced", "N_od", "rocking_units", "Ns", "s_om", "waves",
                            "damage_S", "Ns_van_der_meer", "N_od_van_der_meer",
                            "units_displaced_van_der_meer", "Ns_hudson_breaking", "Ns_hudson_nonbreaking"})
        EXPECT_TRUE(summary.contains(key) && summary[key].is_number()) << key;
    EXPECT_TRUE(summary["damage"].is_object());
    EXPECT_EQ(summary["units"].get<int>(), 6);
    EXPECT_NEAR(summary["Ns"].get<double>(), 0.3 / (1.4 * 0.2), 1e-9);
    EXPECT_NEAR(summary["s_om"].get<double>(), 2 * M_PI * 0.3 / (9.81 * 4.0),
                1e-3 * summary["s_om"].get<double>());
    std::filesystem::remove_all(dir);
}
