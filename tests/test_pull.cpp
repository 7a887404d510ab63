// The pull analysis (analysis/pull_analysis.cpp) end to end through `armour
// run`: two free cubes, each resting on a held cube on a slope, are pulled
// straight out of the face. With nothing else holding them, each starts to
// move where statics says: on a 1:3 slope it slides on its neighbour when
// the pull has taken enough of its weight off the contact,
//     F = W (cos a - sin a / mu) = 0.422 W   (mu 0.6, a = atan 1/3),
// and on a nearly flat face (1:100) it lifts off at about its weight. The
// two cubes stand 1.35 Dn apart, closer than a round's 3 Dn: round 0 pulls
// the lower one only, round 1 the other. Seconds each.
#include "scene_run.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

namespace fs = std::filesystem;

namespace {

constexpr double kDn = 0.04; // m

// A dry scene: a `cot` slope, stacks at (s, y) = (0.15, 0) and (0.17, 0.05) m,
// each a held cube 1.5 mm clear of the face and a free cube `drop` m clear of it (5 mm as
// scenes/tilt_cube_pair.toml; the 47-sphere clump's spheres stand up to 1.1 mm out of its faces).
fs::path pull_scene(const fs::path &dir, double cot, double drop = 0.005) {
    const double a = std::atan2(1.0, cot);
    const double along[3] = {std::cos(a), 0.0, std::sin(a)}, normal[3] = {-std::sin(a), 0.0, std::cos(a)};
    std::ostringstream s;
    s << "name = \"pull_pair\"\n"
         "[run]\nengine = \"liggghts\"\nduration = 5.0\noutput_interval = 0.01\n"
         "domain_min = [-0.3, -0.3, -0.1]\ndomain_max = [0.5, 0.3, 0.4]\n"
         "[analysis]\nkind = \"pull\"\npull_rate = 0.5\npull_max = 1.5\n"
         "[[material]]\nname = \"concrete\"\nyoungs_modulus = 5e7\nrestitution = 0.3\nfriction = 0.6\n"
         "[[unit]]\nname = \"cube\"\nshape = \"cube\"\nsize = 0.04\ndensity = 2300.0\ntol_volume = 0.01\n"
         "tol_surface = 0.02\nmethod = \"optimised\"\nmaterial = \"concrete\"\n"
         "[[wall]]\nname = \"slope\"\ntype = \"slope\"\ntoe_x = 0.0\nfloor_z = 0.0\ncot = "
      << cot << "\nheight = " << 0.3 / cot << "\nwidth = 0.5\nmaterial = \"concrete\"\n";
    const double quat[4] = {std::cos(a / 2), 0.0, -std::sin(a / 2), 0.0}; // bottom face on the face
    for (const auto &[sv, y] : {std::pair{0.15, 0.0}, std::pair{0.17, 0.05}})
        for (const double n : {0.5 * kDn + 0.0015, 1.5 * kDn + 0.0015 + drop}) {
            const bool held = n < kDn;
            s << "[[body]]\nunit = \"cube\"\nposition = [" << sv * along[0] + n * normal[0] << ", " << y
              << ", " << sv * along[2] + n * normal[2] << "]\norientation = [" << quat[0] << ", 0.0, "
              << quat[2] << ", 0.0]\n";
            if (held)
                s << "fixed_translation = [true, true, true]\nfixed_rotation = [true, true, true]\n";
        }
    const fs::path path = dir / ("pull_pair_" + std::to_string(static_cast<int>(cot)) + "_" +
                                 std::to_string(static_cast<int>(drop * 1e4)) + ".toml");
    std::ofstream(path) << s.str();
    return path;
}

armour_test::SceneRun pull(double cot, const std::string &sets, const std::string &name,
                           double drop = 0.005) {
    const fs::path dir =
        fs::temp_directory_path() / ("armour_test_pull_scenes_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return armour_test::run_scene(ARMOUR_EXE, pull_scene(dir, cot, drop), name,
                                  sets + " --cache '" + std::string(ARMOUR_TEST_CACHE) + "'");
}

} // namespace

#ifdef ARMOUR_HAS_BULLET
TEST(PullAnalysis, ACubeOnACubeSlidesWhereStaticsSaysAndRoundsTakeUnitsApart) {
    const double a = std::atan2(1.0, 3.0), expected = std::cos(a) - std::sin(a) / 0.6; // 0.422
    for (const int round : {0, 1}) {
        const auto r = pull(3.0, "--engine bullet --set analysis.pull_round=" + std::to_string(round),
                            "pull_round" + std::to_string(round));
        ASSERT_EQ(r.status, 0) << r.output;
        ASSERT_EQ(r.summary.value("pull_units", -1), 1) << r.summary.dump(2);
        EXPECT_NEAR(r.summary["pull_lone_unit_slide"].get<double>(), expected, 1e-9);
        EXPECT_NEAR(r.summary["pull_resistance_median"].get<double>(), expected, 0.05) << r.output;
        EXPECT_EQ(r.summary["pull_stayed"], 0);
        // body 1 is the lower stack's free cube, body 3 the upper one's.
        const std::string csv = armour_test::read_text(r.out / "pull.csv");
        EXPECT_NE(csv.find("\n" + std::to_string(round == 0 ? 1 : 3) + ","), std::string::npos) << csv;
    }
}

// Turned 60 degrees down the face the pull slides the cube sooner:
// F = W (mu cos a - sin a) / (sin 60 + mu cos 60) = 0.217 W, and it never comes near its lift (1.9 W).
TEST(PullAnalysis, APullTurnedDownTheFaceSlidesTheCubeWhereStaticsSays) {
    const double a = std::atan2(1.0, 3.0), b = 60.0 * 3.14159265358979323846 / 180.0;
    const double expected = (0.6 * std::cos(a) - std::sin(a)) / (std::sin(b) + 0.6 * std::cos(b));
    const auto r = pull(3.0, "--engine bullet --set analysis.pull_angle=60", "pull_angle");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NEAR(r.summary["pull_resistance_median"].get<double>(), expected, 0.05) << r.output;
    EXPECT_NEAR(r.summary["pull_lone_unit_lift"].get<double>(), std::cos(a) / std::cos(b), 1e-9);
}
#endif

TEST(PullAnalysis, AClumpOnAClumpLiftsOffAtItsWeightOnAFlatFace) {
    const auto r = pull(100.0, "", "pull_flat");
    ASSERT_EQ(r.status, 0) << r.output;
    ASSERT_EQ(r.summary.value("pull_units", -1), 1) << r.summary.dump(2);
    // Slide (0.983 W) and lift (1.000 W) nearly coincide on a 1:100 face.
    EXPECT_NEAR(r.summary["pull_resistance_median"].get<double>(), 0.99, 0.04) << r.output;
    EXPECT_NEAR(r.summary["pull_lone_unit_lift"].get<double>(), std::cos(std::atan(0.01)), 1e-9);
}

// A unit that the start itself moves from its seat is not a unit that held nothing: the free
// cube starts 15 mm (0.375 Dn) above its bed, falls more than 0.25 Dn during the seat wait and is
// counted as unseated, not pulled and not given a resistance of 0.
TEST(PullAnalysis, AUnitTheStartUnseatsIsCountedApartNotAsHoldingNothing) {
    const auto r = pull(100.0, "", "pull_unseated", 0.015);
    ASSERT_EQ(r.status, 0) << r.output;
    ASSERT_EQ(r.summary.value("pull_units", -1), 1) << r.summary.dump(2);
    EXPECT_EQ(r.summary["pull_unseated"], 1);
    EXPECT_EQ(r.summary["pull_stayed"], 0);
    EXPECT_TRUE(r.summary["pull_resistance_median"].is_null()) << r.summary.dump(2);
    EXPECT_NEAR(r.summary["pull_wait"].get<double>(), 5.0 * std::sqrt(kDn / 9.80665), 1e-3);
    const std::string csv = armour_test::read_text(r.out / "pull.csv");
    EXPECT_NE(csv.find("\n1,"), std::string::npos) << csv;
    EXPECT_NE(csv.find(",,,0,1\n"), std::string::npos) << csv; // no resistance, not stayed, unseated
}

// A coupled scene sets its units' loads itself: the pull is refused before anything runs, and
// so is a pull without its rate.
TEST(PullAnalysis, IsRefusedOnAFluidSceneAndWithoutItsRate) {
    const fs::path scene = fs::path(ARMOUR_SOURCE_DIR) / "scenes" / "stability_cubes.toml";
    const auto fluid = armour_test::run_scene(
        ARMOUR_EXE, scene, "pull_fluid", "--set analysis.kind=pull --set analysis.pull_rate=0.5 --dry-run");
    EXPECT_EQ(fluid.status, 2);
    EXPECT_NE(fluid.output.find("armour: error: --set: key 'analysis.kind': kind \"pull\" is a dry test"),
              std::string::npos)
        << fluid.output;
    EXPECT_FALSE(fs::exists(fluid.out));
    const auto rate =
        armour_test::run_scene(ARMOUR_EXE, scene, "pull_rate", "--set analysis.kind=pull --dry-run");
    EXPECT_EQ(rate.status, 2);
    EXPECT_NE(rate.output.find("key 'analysis.pull_rate': missing required key"), std::string::npos)
        << rate.output;
    // A run that ends before the pull reaches pull_max would report units that held it.
    const fs::path dir =
        fs::temp_directory_path() / ("armour_test_pull_scenes_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const auto short_run = armour_test::run_scene(ARMOUR_EXE, pull_scene(dir, 3.0), "pull_short",
                                                  "--set run.duration=2 --dry-run");
    EXPECT_EQ(short_run.status, 2);
    EXPECT_NE(short_run.output.find("key 'analysis.pull_max': must be reached within run.duration = 2 s"),
              std::string::npos)
        << short_run.output;
    // Long enough for pull_max / pull_rate (3 s) but not for the seat (up to twice the 0.32 s wait)
    // and a second at pull_max.
    const auto no_wait = armour_test::run_scene(ARMOUR_EXE, pull_scene(dir, 3.0), "pull_no_wait",
                                                "--set run.duration=4 --dry-run --cache '" +
                                                    std::string(ARMOUR_TEST_CACHE) + "'");
    EXPECT_EQ(no_wait.status, 2);
    EXPECT_NE(no_wait.output.find("pull needs run.duration >= 4.639 s"), std::string::npos) << no_wait.output;
}
