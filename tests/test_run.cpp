// `armour run`: a scene runs end to end, and every bad scene stops with one
// error line before anything is written (or, mid-run, keeps what was written).
#include "bodies_file.h"
#include "cli.h"
#include "clump_evaluator.h"
#include "engine_registry.h"
#include "output_folder_rule.h"
#include "paraview_poses.h"
#include "run_command.h"
#include "scene.h"
#include "scene_setup.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace {

// One 0.2 m cube falling onto a floor; `extra` is appended (more tables).
std::string scene_text(const std::string &body_position, const std::string &extra = "",
                       const std::string &run_extra = "") {
    return "name = \"test\"\n"
           "[run]\nduration = 0.05\noutput_interval = 0.01\ndomain_min = [-1, -1, -0.5]\n"
           "domain_max = [1, 1, 1.5]\n" +
           run_extra +
           "[[material]]\nname = \"concrete\"\n"
           "[[unit]]\nname = \"cube\"\nshape = \"cube\"\nsize = 0.2\nspheres = 8\n"
           "[[wall]]\nname = \"floor\"\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nsize = 2\n"
           "[[body]]\nunit = \"cube\"\nposition = " +
           body_position + "\n" + extra;
}

class Run : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("armour_run_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        cache_ = (dir_ / "cache").string();
    }
    void TearDown() override { fs::remove_all(dir_); }

    int run(const std::string &scene, std::vector<std::string> extra = {}) {
        const fs::path file = dir_ / "scene.toml";
        std::ofstream(file) << scene;
        std::vector<std::string> args = {"run", file.string(), "--out", out().string(), "--cache", cache_};
        args.insert(args.end(), extra.begin(), extra.end());
        const output_rule::Outcome o = output_rule::armour(std::move(args));
        err_ = o.err;
        return o.code;
    }
    fs::path out() const { return dir_ / "out"; }
    nlohmann::json summary() const {
        std::ifstream in(out() / "summary.json");
        return nlohmann::json::parse(in);
    }
    // A scene of scenes/ as shipped, as text for run().
    static std::string shipped_scene(const std::string &file) {
        std::ifstream in(fs::path(ARMOUR_SOURCE_DIR) / "scenes" / file);
        std::stringstream text;
        text << in.rdbuf();
        return text.str();
    }
    // The exact-hull engine, or nullptr in a build without one.
    static const armour::EngineStyle *hull_engine() {
        return armour::find_engine_style(
            [](const armour::EngineCapabilities &c) { return c.shape == armour::ShapeModel::convex_hulls; });
    }
    std::string error_line() const {
        const std::size_t at = err_.find("armour: error: ");
        return at == std::string::npos ? "" : err_.substr(at, err_.find('\n', at) - at);
    }

    fs::path dir_;
    std::string cache_, err_;
};

} // namespace

TEST_F(Run, WritesSummaryTrajectoriesAndResolvedScene) {
    ASSERT_EQ(run(scene_text("[0, 0, 0.3]")), 0) << err_;
    for (const char *name : {"summary.json", "bodies.h5", "bodies.xdmf", "scene.resolved.toml",
                             "units/cube/clump.spheres", "units/cube/shape.stl", "liggghts/input.liggghts"})
        EXPECT_TRUE(fs::exists(out() / name)) << name;
    std::ifstream in(out() / "summary.json");
    const auto s = nlohmann::json::parse(in);
    for (const char *key : {"engine", "spheres_per_unit", "dt", "steps", "wall_seconds"})
        EXPECT_TRUE(s.contains(key)) << key;
    EXPECT_EQ(s["engine"], "liggghts");
    EXPECT_EQ(s["spheres_per_unit"]["cube"], 8);
    // Steps times the step is the simulated time (to one step).
    EXPECT_NEAR(s["steps"].get<double>() * s["dt"].get<double>(), 0.05, s["dt"].get<double>());
    // Six records (t = 0 .. 0.05 s) of a cube in free fall: z(t) = 0.3 - g t^2 / 2.
    const armour::BodiesFile rec = armour::read_bodies_file((out() / "bodies.h5").string());
    ASSERT_EQ(rec.steps(), 6u);
    EXPECT_NEAR(rec.position[5][0].z(), 0.3 - 0.5 * 9.81 * 0.05 * 0.05, 2e-4);
}

TEST_F(Run, SetOverridesAScalar) {
    ASSERT_EQ(run(scene_text("[0, 0, 0.3]"), {"--set", "run.duration=0.02"}), 0) << err_;
    std::ifstream in(out() / "summary.json");
    EXPECT_NEAR(nlohmann::json::parse(in)["simulated_seconds"].get<double>(), 0.02, 1e-3);
}

// A duration shorter than one step runs no step: the costs per simulated second
// and per unit-step are null, not a wall time over 1e-300 s.
TEST_F(Run, ARunOfNoStepReportsNoCostPerStep) {
    ASSERT_EQ(
        run(scene_text("[0, 0, 0.3]"), {"--set", "run.duration=1e-6", "--set", "run.output_interval=1e-6"}),
        0)
        << err_;
    std::ifstream in(out() / "summary.json");
    const auto s = nlohmann::json::parse(in);
    ASSERT_EQ(s["steps"], 0);
    EXPECT_TRUE(s["wall_seconds_per_simulated_second"].is_null());
    EXPECT_TRUE(s["seconds_per_unit_step"].is_null());
}

TEST_F(Run, RefusesOverlappingBodiesNamingThePair) {
    EXPECT_EQ(run(scene_text("[0, 0, 0.3]", "[[body]]\nunit = \"cube\"\nposition = [0.05, 0, 0.3]\n")), 2);
    EXPECT_NE(error_line().find("bodies overlap (pairs 0-1)"), std::string::npos) << err_;
    EXPECT_FALSE(fs::exists(out()));
}

// A settled layer starts with its contacts pressed: the start check allows
// two clump spheres the Hertz overlap under 10 unit weights, with the pair's
// effective radius ra rb / (ra + rb) (two equal spheres press 1.26 x deeper
// than one on a plane). Two one-sphere cubes, at 0.95 and 1.05 x that
// overlap: the first passes the check, the second is refused. (With a plane's radius
// the check allowed 0.79 x and refused both.) E = 5e6 Pa, so that the
// Hertz figure, not the floor of 5 % of the radius, decides.
TEST_F(Run, StartCheckAllowsTwoSpheresTheirHertzOverlapUnderTenUnitWeights) {
    const auto scene = [](double centres) {
        return "name = \"pair\"\n[run]\nduration = 0.001\noutput_interval = 0.001\n"
               "domain_min = [-1, -1, -0.5]\ndomain_max = [1, 1, 1.5]\n"
               "[[material]]\nname = \"concrete\"\nyoungs_modulus = 5e6\n"
               "[[unit]]\nname = \"cube\"\nshape = \"cube\"\nsize = 0.2\nspheres = 1\n"
               "[[body]]\nunit = \"cube\"\nposition = [0, 0, 0.5]\n[[body]]\nunit = \"cube\"\nposition = [" +
               std::to_string(centres) + ", 0, 0.5]\n";
    };
    const fs::path file = dir_ / "pair.toml";
    std::ofstream(file) << scene(0.5); // apart: to read the clump
    const armour::SceneSetup setup = armour::build_scene(armour::load_scene(file.string()), cache_, false);
    const armour::UnitTemplate &unit = setup.units[0];
    ASSERT_EQ(unit.clump.size(), 1u);
    const double r = unit.clump[0].radius;
    // (Both cubes unturned: their spheres lie as far apart as their centres.)
    const armour::Material &m = setup.settings.materials[unit.material];
    const double e_star = m.youngs_modulus / (2.0 * (1.0 - m.poisson_ratio * m.poisson_ratio));
    const double force = 10.0 * unit.props.mass * 9.81; // N
    const double hertz = std::pow(3.0 * force / (4.0 * e_star * std::sqrt(r / 2.0)), 2.0 / 3.0);
    std::printf("[ pair     ] sphere r = %.2f mm: Hertz pair overlap under 10 unit weights %.2f mm\n",
                1e3 * r, 1e3 * hertz);
    ASSERT_GT(hertz, 0.05 * r); // the Hertz figure decides, not the 5 % floor
    // build_scene holds the start check (a one-sphere clump is no LIGGGHTS
    // multisphere, so `armour run` would refuse it for that first).
    const auto build = [&](double overlap) {
        std::ofstream(file) << scene(2.0 * r - overlap);
        return armour::build_scene(armour::load_scene(file.string()), cache_, false);
    };
    EXPECT_NO_THROW(build(0.95 * hertz));
    try {
        build(1.05 * hertz);
        ADD_FAILURE() << "1.05 x the Hertz overlap started";
    } catch (const armour::InputError &e) {
        EXPECT_NE(std::string(e.what()).find("bodies overlap (pairs 0-1)"), std::string::npos) << e.what();
    }
}

TEST_F(Run, RefusesABodyCuttingIntoAWall) {
    EXPECT_EQ(run(scene_text("[0, 0, 0.05]")), 2);
    EXPECT_NE(error_line().find("cuts into wall 'floor'"), std::string::npos) << err_;
    EXPECT_FALSE(fs::exists(out()));
}

TEST_F(Run, RefusesAnUnstableTimeStepUnlessForced) {
    EXPECT_EQ(run(scene_text("[0, 0, 0.3]", "", "time_step = 0.005\n")), 2);
    EXPECT_NE(error_line().find("exceeds the stability limit"), std::string::npos) << err_;
    EXPECT_FALSE(fs::exists(out()));
    ASSERT_EQ(run(scene_text("[0, 0, 0.3]", "", "time_step = 0.005\nforce_time_step = true\n")), 0) << err_;
    std::ifstream in(out() / "summary.json");
    EXPECT_TRUE(nlohmann::json::parse(in)["dt_forced"].get<bool>());
}

// run.contact_iterations sets the iterations of an engine with rigid
// contacts (the summary's step rule says how many); the clumps' engine has
// springs and dashpots, nothing to iterate, and refuses the key by name.
TEST_F(Run, ContactIterationsGoToTheRigidContactEngineAndAreRefusedByTheClumps) {
    EXPECT_EQ(run(scene_text("[0, 0, 0.3]", "", "contact_iterations = 50\n")), 2);
    EXPECT_NE(error_line().find("scene.toml: key 'run.contact_iterations'"), std::string::npos) << err_;
    EXPECT_FALSE(fs::exists(out()));
    // A settle alone is refused alike, before anything is written.
    EXPECT_EQ(
        run(shipped_scene("stability_cubes.toml"), {"--settle-only", "--set", "run.contact_iterations=5"}),
        2);
    EXPECT_NE(error_line().find("scene.toml: key 'run.contact_iterations'"), std::string::npos) << err_;
    EXPECT_FALSE(fs::exists(out()));
    EXPECT_EQ(run(scene_text("[0, 0, 0.3]", "", "contact_iterations = -1\n")), 2);
    EXPECT_NE(error_line().find("run.contact_iterations"), std::string::npos) << err_;
    const armour::EngineStyle *hulls = hull_engine();
    if (!hulls)
        GTEST_SKIP() << "no exact-hull engine in this build";
    const std::string engine = "engine = \"" + hulls->name + "\"\n";
    ASSERT_EQ(run(scene_text("[0, 0, 0.3]", "", engine + "contact_iterations = 80\n")), 0) << err_;
    EXPECT_NE(summary()["dt_rule"].get<std::string>().find("80 solver iterations"), std::string::npos);
    ASSERT_EQ(run(scene_text("[0, 0, 0.3]", "", engine)), 0) << err_;
    EXPECT_NE(summary()["dt_rule"].get<std::string>().find("50 solver iterations"), std::string::npos);
}

TEST_F(Run, RefusesAnUnknownUnitAndNamesTheKey) {
    EXPECT_EQ(run(scene_text("[0, 0, 0.3]", "[[body]]\nunit = \"dolos\"\nposition = [0.5, 0, 0.3]\n")), 2);
    EXPECT_NE(error_line().find("body.1.unit"), std::string::npos) << err_;
}

// A damage analysis of a layer of two sizes has no one Dn to count N_od in:
// the run and a sweep's check of its cases refuse it, naming both units,
// before anything is written.
TEST_F(Run, RefusesADamageAnalysisOfMixedUnits) {
    const std::string scene =
        "name = \"mixed\"\n[run]\nduration = 0.02\ndomain_min = [-1.6, -0.6, -0.1]\n"
        "domain_max = [2, 0.6, 1.5]\n[analysis]\nkind = \"damage\"\n[[material]]\nname = \"concrete\"\n"
        "[[unit]]\nname = \"small\"\nshape = \"cube\"\nsize = 0.1\nspheres = 8\n"
        "[[unit]]\nname = \"large\"\nshape = \"cube\"\nsize = 0.15\nspheres = 8\n"
        "[[wall]]\nname = \"slope\"\ntype = \"slope\"\ntoe_x = 0.0\nfloor_z = 0.0\ncot = 1.5\n"
        "height = 1.0\nwidth = 1.0\nmaterial = \"concrete\"\n"
        "[[body]]\nunit = \"small\"\nposition = [0.6, -0.2, 0.6]\n"
        "[[body]]\nunit = \"large\"\nposition = [0.6, 0.2, 0.6]\n";
    EXPECT_EQ(run(scene), 2);
    EXPECT_NE(error_line().find("key 'analysis.kind': \"damage\" counts units of one size and density"),
              std::string::npos)
        << err_;
    EXPECT_NE(error_line().find("'small' (Dn 0.1 m"), std::string::npos) << err_;
    EXPECT_NE(error_line().find("'large' (Dn 0.15 m"), std::string::npos) << err_;
    EXPECT_FALSE(fs::exists(out()));
    const armour::Scene loaded = armour::load_scene((dir_ / "scene.toml").string());
    EXPECT_THROW(armour::check_scene_runs(loaded, cache_, 0), armour::InputError);
}

TEST_F(Run, ABodyLeavingTheDomainStopsTheRunAndKeepsItsRecord) {
    // Thrown upwards at 30 m/s: it leaves the 1.5 m high domain within 0.05 s.
    EXPECT_EQ(run(scene_text("[0, 0, 0.3]", "velocity = [0, 0, 30]\n")), 2);
    EXPECT_NE(error_line().find("left the domain"), std::string::npos) << err_;
    EXPECT_FALSE(fs::exists(out() / "summary.json"));
    // The trajectory file must be closed cleanly: read_bodies_file throws otherwise.
    EXPECT_GE(armour::read_bodies_file((out() / "bodies.h5").string()).steps(), 1u);
}

TEST_F(Run, TiltSceneSlidesAtTheFrictionAngle) {
    // The example scene as shipped: a 20-sphere cube lands on the plate from
    // 3 cm, settles, and gravity turns at 5 deg/s. It must slide, not topple,
    // within 0.5 deg of atan(mu) (the engine-level bracket in test_liggghts).
    const std::string scene = shipped_scene("tilt_cube.toml");
    ASSERT_EQ(run(scene), 0) << err_;
    const nlohmann::json s = summary();
    ASSERT_TRUE(s["slide_angle_deg"].is_number()) << s.dump();
    EXPECT_TRUE(s["topple_angle_deg"].is_null());
    EXPECT_NEAR(s["slide_angle_deg"].get<double>(), s["slide_angle_analytic_deg"].get<double>(), 0.5);
    // It leaves its seat by that slide, read at the last still sample: after
    // the onset, by 0.26-0.51 deg at this rate (the analysis' comment).
    EXPECT_EQ(s["left_by"], "slid") << s.dump();
    EXPECT_GE(s["leave_angle_deg"].get<double>(), s["slide_angle_deg"].get<double>()) << s.dump();
    EXPECT_LE(s["leave_angle_deg"].get<double>(), s["slide_angle_deg"].get<double>() + 0.75) << s.dump();
}

TEST_F(Run, TiltSceneTopplesAtFortyFiveDegreesWhenFrictionHolds) {
    // The example scene with friction 1.2: the cube must topple about its
    // downhill edge at atan(1) = 45 deg (sliding would need 50.2 deg). The
    // 20-sphere clump stands on its corner spheres (clump_support.h):
    // geometric topple angle 44.50 deg. Before them it toppled at 29.5 deg.
    const std::string scene = shipped_scene("tilt_cube.toml");
    ASSERT_EQ(run(scene, {"--set", "material.0.friction=1.2"}), 0) << err_;
    const nlohmann::json s = summary();
    ASSERT_TRUE(s["topple_angle_deg"].is_number()) << s.dump();
    EXPECT_NEAR(s["topple_angle_deg"].get<double>(), 45.0, 1.0);
}

namespace {

// Horizontal excursion (m) of the only body of a one-body run from its
// position at t_from, over the records from t_from on, and the range of its
// tilt (deg) over them.
struct Rest {
    double wander = 0.0, tilt_min = HUGE_VAL, tilt_max = 0.0;
};
Rest rest_after(const fs::path &h5, double t_from) {
    const armour::BodiesFile rec = armour::read_bodies_file(h5.string());
    Rest r;
    std::size_t from = 0;
    while (from < rec.steps() && rec.time[from] < t_from)
        ++from;
    for (std::size_t i = from; i < rec.steps(); ++i) {
        const Eigen::Vector3d p = rec.position[i][0], p0 = rec.position[from][0];
        r.wander = std::max(r.wander, std::hypot(p.x() - p0.x(), p.y() - p0.y()));
        const double tilt =
            2.0 * std::acos(std::min(1.0, std::abs(rec.orientation[i][0].w()))) * 57.29577951308232; // deg
        r.tilt_min = std::min(r.tilt_min, tilt);
        r.tilt_max = std::max(r.tilt_max, tilt);
    }
    return r;
}

} // namespace

TEST_F(Run, FewSphereCubeRestsOnAFaceOnlyWithRollingFriction) {
    // An 8-sphere cube (a = 0.2 m) lands on a plane from 1.5 cm. Its lowest
    // spheres differ in height by ~4 mm, more than the ~0.6 mm contact
    // overlap, so it stands on two of them and rocks about that line: a
    // rolling motion that sliding friction and the normal dashpot barely
    // damp. A resting unit must stay put; the edge is the rest gap
    // (docs/dem.md). Between 0.5 and 1.5 s: without rolling friction it still
    // rocks (measured: tilt 1.9-3.2 deg, 2.2 mm wander; the run warns), with
    // rolling friction 0.05 it rests (0.015 mm). Bounds: 1 mm (0.5 % of a)
    // for rocking and 0.1 mm (0.05 % of a, 15 um of contact creep measured)
    // for rest.
    const auto scene = [](double rolling) {
        return "name = \"rest\"\n[run]\nduration = 1.5\noutput_interval = 0.01\ndomain_min = [-1, -1, -0.5]\n"
               "domain_max = [1, 1, 1.5]\n[[material]]\nname = \"concrete\"\nyoungs_modulus = 5e7\n"
               "friction = 0.6\nrolling_friction = " +
               std::to_string(rolling) +
               "\n[[unit]]\nname = \"cube\"\nshape = \"cube\"\nsize = 0.2\nspheres = 8\n"
               "[[wall]]\nname = \"floor\"\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nsize = "
               "2\n"
               "[[body]]\nunit = \"cube\"\nposition = [0, 0, 0.115]\n";
    };
    ASSERT_EQ(run(scene(0.0)), 0) << err_;
    EXPECT_NE(err_.find("rocks without end"), std::string::npos) << err_;
    const Rest rocking = rest_after(out() / "bodies.h5", 0.5);
    ASSERT_EQ(run(scene(0.05)), 0) << err_;
    EXPECT_EQ(err_.find("rocks without end"), std::string::npos) << err_;
    const Rest resting = rest_after(out() / "bodies.h5", 0.5);
    std::printf(
        "[ rest     ] 8-sphere cube on a plane, 0.5-1.5 s: no rolling friction %.3g mm, tilt %.2f-%.2f deg; "
        "rolling friction 0.05 %.3g mm, tilt %.2f-%.2f deg\n",
        1e3 * rocking.wander, rocking.tilt_min, rocking.tilt_max, 1e3 * resting.wander, resting.tilt_min,
        resting.tilt_max);
    EXPECT_GT(rocking.wander, 1e-3);
    EXPECT_LT(resting.wander, 1e-4);
    EXPECT_LT(resting.tilt_max - resting.tilt_min, 0.05);
}

TEST_F(Run, LiggghtsTakesWallsReachingPastTheDomain) {
    // A plane wall is a square of `size`; LIGGGHTS aborts on mesh elements
    // outside its box ("All 2 mesh elements have been lost"), so the adapter
    // hands it only the part inside the domain. A 10 m floor under a 2 m
    // domain: the cube (a = 0.2 m, from 1.5 cm) lands and rests on it, its
    // centre as high above the floor as its clump's lowest sphere reaches
    // below the centre (the optimised spheres protrude past the faces),
    // within 1 mm (the contact overlap, ~0.5 mm).
    const std::string text =
        "name = \"floor\"\n[run]\nduration = 0.3\noutput_interval = 0.01\n"
        "domain_min = [-1, -1, -0.5]\ndomain_max = [1, 1, 1.5]\n[[material]]\nname = \"concrete\"\n"
        "rolling_friction = 0.05\n[[unit]]\nname = \"cube\"\nshape = \"cube\"\nsize = 0.2\n"
        "spheres = 8\n[[wall]]\nname = \"floor\"\ntype = \"plane\"\npoint = [0, 0, 0]\n"
        "normal = [0, 0, 1]\nsize = 10\n[[body]]\nunit = \"cube\"\nposition = [0, 0, 0.115]\n";
    ASSERT_EQ(run(text), 0) << err_;
    std::ifstream in(out() / "summary.json");
    ASSERT_TRUE(in);
    const armour::BodiesFile rec = armour::read_bodies_file((out() / "bodies.h5").string());
    ASSERT_GT(rec.steps(), 0u);
    double reach = 0.0; // m, lowest sphere point below the centre, as placed
    std::ifstream spheres(out() / "units" / "cube" / "clump.spheres");
    for (std::string line; std::getline(spheres, line);) {
        if (line.empty() || line[0] == '#')
            continue;
        std::istringstream row(line);
        double x = 0, y = 0, z = 0, r = 0;
        row >> x >> y >> z >> r;
        reach = std::max(reach, r - z);
    }
    EXPECT_GT(reach, 0.1);
    EXPECT_NEAR(rec.position.back().back().z(), reach, 1e-3);
}

TEST_F(Run, RestGapTellsTheFacesAClumpRocksOn) {
    // The greedy 30-sphere cube (a = 0.2 m) rests flat on some faces and not
    // on others: its rest gap (clump_evaluator.h) is 0 on -z, under the
    // ~0.5 mm its contacts absorb (resting_overlap), and 3.1 mm on +x. (The
    // optimised 27-sphere cube this test used, 0.40 mm and 3.5 mm, now has
    // corner spheres, clump_support.h, and rests flat on every face.)
    // Placed on each face without rolling friction, it must rest on the one
    // and rock on the other, and the run warns (it could land on +x).
    // Bounds as in FewSphereCubeRestsOnAFaceOnlyWithRollingFriction
    // (measured: 0.037 mm on -z, 1.5 mm on +x).
    const auto scene = [](const std::string &orientation) {
        return "name = \"rest\"\n[run]\nduration = 1.5\noutput_interval = 0.01\ndomain_min = [-1, -1, -0.5]\n"
               "domain_max = [1, 1, 1.5]\n[[material]]\nname = \"concrete\"\nyoungs_modulus = 5e7\n"
               "friction = 0.6\n[[unit]]\nname = \"cube\"\nshape = \"cube\"\nsize = 0.2\nspheres = 30\n"
               "method = \"greedy\"\n"
               "[[wall]]\nname = \"floor\"\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nsize = "
               "2\n"
               "[[body]]\nunit = \"cube\"\nposition = [0, 0, 0.115]\norientation = " +
               orientation + "\n";
    };
    // [w, x, y, z]: as placed (-z down), and turned 90 degrees about y (+x down).
    ASSERT_EQ(run(scene("[1, 0, 0, 0]")), 0) << err_;
    EXPECT_NE(err_.find("rocks without end"), std::string::npos) << err_;
    const Rest on_minus_z = rest_after(out() / "bodies.h5", 0.5);
    ASSERT_EQ(run(scene("[0.70710678118654752, 0, 0.70710678118654752, 0]")), 0) << err_;
    const Rest on_plus_x = rest_after(out() / "bodies.h5", 0.5);

    const armour::Scene parsed = armour::load_scene((dir_ / "scene.toml").string());
    const armour::SceneSetup setup = armour::build_scene(parsed, cache_, false);
    const armour::UnitTemplate &unit = setup.units[0];
    double gap_minus_z = -1.0, gap_plus_x = -1.0;
    for (const armour::FaceRest &face :
         armour::rest_gaps(unit.mesh, Eigen::Vector3d::Zero(), unit.clump, setup.unit_Dn[0])) {
        if (face.normal.isApprox(-Eigen::Vector3d::UnitZ(), 1e-9))
            gap_minus_z = face.gap;
        if (face.normal.isApprox(Eigen::Vector3d::UnitX(), 1e-9))
            gap_plus_x = face.gap;
    }
    const double overlap = armour::resting_overlap(unit, setup.settings.materials[unit.material], 9.81);
    std::printf("[ rest     ] greedy 30-sphere cube: -z face gap %.3f mm, wander %.3g mm; +x face gap %.3f "
                "mm, wander "
                "%.3g mm; contact overlap %.3f mm\n",
                1e3 * gap_minus_z, 1e3 * on_minus_z.wander, 1e3 * gap_plus_x, 1e3 * on_plus_x.wander,
                1e3 * overlap);
    EXPECT_LT(gap_minus_z, overlap);
    EXPECT_GT(gap_plus_x, overlap);
    EXPECT_LT(on_minus_z.wander, 1e-4);
    EXPECT_GT(on_plus_x.wander, 1e-3);
}

// A command's clump cache is its --cache when given, else the default
// ($ARMOUR_CACHE first): `armour run` and `armour report` ask the same function.
TEST(ClumpCache, IsTheCommandsCacheFlagElseTheDefault) {
    const char *before = std::getenv("ARMOUR_CACHE");
    const std::string kept = before ? before : "";
    ::setenv("ARMOUR_CACHE", "/tmp/armour-cache-of-this-test", 1);
    EXPECT_EQ(armour::default_cache_dir(), "/tmp/armour-cache-of-this-test");
    EXPECT_EQ(armour::cache_dir_or_default(""), "/tmp/armour-cache-of-this-test");
    EXPECT_EQ(armour::cache_dir_or_default("given/cache"), "given/cache");
    armour::RunRequest request;
    EXPECT_EQ(request.cache_dir(), "/tmp/armour-cache-of-this-test");
    request.cache = "given/cache";
    EXPECT_EQ(request.cache_dir(), "given/cache");
    if (before)
        ::setenv("ARMOUR_CACHE", kept.c_str(), 1);
    else
        ::unsetenv("ARMOUR_CACHE");
}

TEST_F(Run, KeepsTheUsersFiles) {
    const std::string scene = (dir_ / "scene.toml").string();
    std::ofstream(scene) << scene_text("[0, 0, 0.3]");
    output_rule::check(
        dir_, "armour run",
        [&](const std::string &out, int variant) {
            return output_rule::armour({"run", scene, "--out", out, "--cache", cache_, "--set",
                                        variant == 0 ? "run.duration=0.02" : "run.duration=0.03"});
        },
        [](const nlohmann::json &s) { return s["simulated_seconds"].get<double>() > 0.025 ? 1 : 0; });
}

// `--dry-run` makes the run's checks and writes nothing: a scene that runs
// exits 0 with its plan (the steps the run then takes) and no folder; one
// that cannot gives the run's own error line, still writing nothing.
TEST_F(Run, DryRunChecksAsTheRunDoesAndWritesNothing) {
    ::testing::internal::CaptureStdout();
    const int code = run(scene_text("[0, 0, 0.3]"), {"--dry-run"});
    const std::string plan = ::testing::internal::GetCapturedStdout();
    ASSERT_EQ(code, 0) << err_;
    EXPECT_FALSE(fs::exists(out())) << plan;
    const std::size_t at = plan.find(" steps)");
    ASSERT_NE(at, std::string::npos) << plan;
    const long planned = std::stol(plan.substr(plan.rfind('(', at) + 1));
    ASSERT_EQ(run(scene_text("[0, 0, 0.3]")), 0) << err_;
    std::ifstream in(out() / "summary.json");
    EXPECT_NEAR(static_cast<double>(planned), nlohmann::json::parse(in)["steps"].get<double>(), 1.0) << plan;
    fs::remove_all(out());

    struct Case {
        std::string scene;
        std::vector<std::string> options;
    };
    const std::vector<Case> refused = {
        {scene_text("[0, 0, 0.3]", "[[body]]\nunit = \"cube\"\nposition = [0.05, 0, 0.3]\n"), {}},
        {scene_text("[0, 0, 0.05]"), {}},                           // cuts into the floor
        {scene_text("[0, 0, 0.3]", "", "time_step = 0.005\n"), {}}, // past the stability limit
        {scene_text("[0, 0, 0.3]"), {"--set", "run.durration=1"}},  // no such key
        {scene_text("[0, 0, 0.3]"), {"--np", "2"}},                 // no [fluid]
        {scene_text("[0, 0, 0.3]"), {"--resume"}},                  // nothing to resume
        {scene_text("[0, 0, 0.3]", "[[body]]\nunit = \"dolos\"\nposition = [0.5, 0, 0.3]\n"), {}},
    };
    for (const Case &c : refused) {
        std::vector<std::string> dry = c.options;
        dry.push_back("--dry-run");
        EXPECT_EQ(run(c.scene, dry), 2) << err_;
        const std::string dry_error = error_line();
        EXPECT_FALSE(fs::exists(out())) << dry_error;
        EXPECT_EQ(run(c.scene, c.options), 2) << err_;
        EXPECT_EQ(dry_error, error_line());
        EXPECT_FALSE(dry_error.empty());
        fs::remove_all(out());
    }
    // A folder the run refuses: the same line, the user's file untouched.
    fs::create_directories(out());
    std::ofstream(out() / "notes.txt") << "a user's notes\n";
    EXPECT_EQ(run(scene_text("[0, 0, 0.3]"), {"--dry-run"}), 2);
    const std::string dry_error = error_line();
    EXPECT_EQ(output_rule::names(out()), std::set<std::string>{"notes.txt"});
    EXPECT_EQ(run(scene_text("[0, 0, 0.3]")), 2);
    EXPECT_EQ(dry_error, error_line());
    EXPECT_NE(dry_error.find("holds 'notes.txt'"), std::string::npos) << dry_error;
}

// A dry run of a resume reads the run's folder and changes nothing in it;
// one the resume would refuse (a key a resume may not change) gives its line.
TEST_F(Run, DryRunOfAResumeChangesNothingInTheRunsFolder) {
    const std::string scene = scene_text("[0, 0, 0.3]", "", "checkpoint_interval = 0.02\n");
    ASSERT_EQ(run(scene), 0) << err_;
    const auto listing = [&] {
        std::map<std::string, std::string> files;
        for (const auto &e : fs::recursive_directory_iterator(out()))
            files[e.path().string()] =
                e.is_regular_file() ? std::to_string(e.file_size()) + " " +
                                          std::to_string(e.last_write_time().time_since_epoch().count())
                                    : "";
        return files;
    };
    const auto before = listing();
    ::testing::internal::CaptureStdout();
    const int code = run(scene, {"--resume", "--set", "run.duration=0.1", "--dry-run"});
    const std::string plan = ::testing::internal::GetCapturedStdout();
    EXPECT_EQ(code, 0) << err_;
    EXPECT_NE(plan.find("resumes at 0.04"), std::string::npos) << plan; // the last of 0.02, 0.04
    EXPECT_EQ(listing(), before);
    EXPECT_EQ(run(scene,
                  {"--resume", "--set", "run.duration=0.1", "--set", "material.0.friction=0.9", "--dry-run"}),
              2);
    const std::string dry_error = error_line();
    EXPECT_NE(dry_error.find("a resume may change only"), std::string::npos) << err_;
    EXPECT_EQ(listing(), before);
    EXPECT_EQ(run(scene, {"--resume", "--set", "run.duration=0.1", "--set", "material.0.friction=0.9"}), 2);
    EXPECT_EQ(dry_error, error_line());
}

// `armour report` reads coupled runs only (tests/test_stability.cpp reports
// one); anything else is one error line, and nothing is written anywhere.
TEST_F(Run, ReportRefusesWhatIsNotACoupledRunAndWritesNothing) {
    ASSERT_EQ(run(scene_text("[0, 0, 0.3]")), 0) << err_;
    std::map<std::string, std::uintmax_t> before;
    for (const auto &e : fs::recursive_directory_iterator(dir_))
        before[e.path().string()] = e.is_regular_file() ? e.file_size() : 0;
    const fs::path report = dir_ / "report";
    const auto refused = [&](const std::string &folder, const std::string &why, const fs::path &into = {}) {
        const output_rule::Outcome o =
            output_rule::armour({"report", folder, "--out", into.empty() ? report.string() : into.string()});
        err_ = o.err;
        EXPECT_EQ(o.code, 2) << err_;
        EXPECT_NE(error_line().find(why), std::string::npos) << err_;
        EXPECT_EQ(err_.find('\n'), err_.size() - 1) << err_; // one line
    };
    refused(out().string(), "no [fluid] table"); // a DEM run
    refused(out().string(), "is inside the run's folder", out() / "r");
    refused((dir_ / "none").string(), "no such folder");
    refused(dir_.string(), "not an `armour run` folder");
    fs::remove(out() / "scene.resolved.toml");
    before.erase((out() / "scene.resolved.toml").string());
    refused(out().string(), "scene.resolved.toml: missing");
    EXPECT_FALSE(fs::exists(report));
    std::map<std::string, std::uintmax_t> after;
    for (const auto &e : fs::recursive_directory_iterator(dir_))
        after[e.path().string()] = e.is_regular_file() ? e.file_size() : 0;
    EXPECT_EQ(after, before);
}

// A scene with [fluid] meets the same rule before anything needs interFoam,
// with and without the settle run in the DEM.
TEST_F(Run, CoupledRunKeepsTheUsersFiles) {
    const std::string dry = (dir_ / "scene.toml").string(), scene = (dir_ / "coupled.toml").string();
    std::ofstream(dry) << scene_text("[0, 0, 0.3]");
    std::ofstream(scene) << scene_text("[0, 0, 0.3]")
                         << "[fluid]\ncase = \"tank\"\nwater_level = 0.7\ncell_size = 0.05\n";
    const std::string text = "a user's notes\n";
    const fs::path work = dir_ / "work";
    fs::create_directories(work);
    std::ofstream(work / "notes.txt") << text;
    for (const char *settle : {"fluid.settle_time=0", "fluid.settle_time=0.1"}) {
        const auto coupled = [&](const std::string &out) {
            return output_rule::armour({"run", scene, "--out", out, "--cache", cache_, "--set", settle});
        };
        output_rule::expect_refused(output_rule::inside(work, [&] { return coupled("."); }), work,
                                    {"notes.txt"}, "notes.txt", text);
        output_rule::expect_refused(coupled(work.string()), work, {"notes.txt"}, "notes.txt", text);
        // An earlier result of `armour run` (dry) with a user's file added.
        const fs::path earlier = dir_ / "earlier";
        fs::remove_all(earlier);
        ASSERT_EQ(output_rule::armour({"run", dry, "--out", earlier.string(), "--cache", cache_}).code, 0);
        std::ofstream(earlier / "later.txt") << text;
        const auto before = output_rule::names(earlier);
        output_rule::expect_refused(coupled(earlier.string()), earlier, before, "later.txt", text);
    }
}

// ParaView's own Xdmf3 reader opens every step of a dry result, each unit
// posed as bodies.h5 records it (tests/paraview_poses.h): a cube spinning as
// it falls, so both position and orientation change from step to step.
TEST_F(Run, ParaViewOpensEveryStepWithTheRecordedPoses) {
    if (!have_pvpython())
        GTEST_SKIP() << "pvpython not found (Debian: python3-paraview)";
    ASSERT_EQ(run(scene_text("[0, 0, 0.3]", "angular_velocity = [3, 1, 2]\n")), 0) << err_;
    expect_paraview_shows_the_poses(out());
}

// The exact reference on the shipped scene (docs/bullet.md): Bullet hulls
// slide within 0.5 deg of atan(mu) and topple within 1 deg of 45 deg at the
// scene's 5 deg/s (measured: 16.73-16.75, 26.59-26.62 and 45.25-45.4 deg over
// six landings).
TEST_F(Run, ExactHullsSlideAndToppleAtTheAnalyticAnglesInTheTiltScene) {
    const armour::EngineStyle *hulls = hull_engine();
    if (!hulls)
        GTEST_SKIP() << "no exact-hull engine in this build";
    const std::string scene = shipped_scene("tilt_cube.toml");
    for (const char *mu : {"0.3", "0.5", "1.2"}) {
        fs::remove_all(out());
        ASSERT_EQ(run(scene, {"--set", "run.engine=\"" + hulls->name + "\"", "--set",
                              std::string("material.0.friction=") + mu}),
                  0)
            << err_;
        const nlohmann::json s = summary();
        if (std::string(mu) == "1.2") {
            ASSERT_TRUE(s["topple_angle_deg"].is_number()) << s.dump();
            EXPECT_NEAR(s["topple_angle_deg"].get<double>(), 45.0, 1.0);
        } else {
            ASSERT_TRUE(s["slide_angle_deg"].is_number()) << s.dump();
            EXPECT_TRUE(s["topple_angle_deg"].is_null()) << "mu " << mu;
            EXPECT_NEAR(s["slide_angle_deg"].get<double>(), s["slide_angle_analytic_deg"].get<double>(), 0.5)
                << "mu " << mu;
        }
    }
}

TEST_F(Run, CubeOnACubeTipsOverItsNeighboursEdge) {
    // The shipped cube-on-a-cube tilt with a quarter of the free cube over its
    // held neighbour's downhill edge (x = 10 mm of a 40 mm cube): an exact cube
    // tips there at atan((a/2 - x) / (a/2)) = 26.57 deg, before it would slide
    // at atan(0.6) = 30.96 deg. The hulls must (their edges rounded by 0.2 mm:
    // 26.1 deg; the analysis reads the tilt a sample or two after the onset).
    // The scene's 118-sphere clump tips over the same edge well before that
    // (docs/validation/stability.md, "A cube on a cube": 18.5 deg), the way
    // units resting on top of a layer leave. This asserts that early tip, not
    // its figure: if a change to the clump makes it fail, measure the docs'
    // figures again.
    const std::string scene = shipped_scene("tilt_cube_pair.toml");
    const double exact = std::atan(0.5) * 57.29577951308232;
    const armour::EngineStyle *hulls = hull_engine();
    if (hulls) {
        ASSERT_EQ(run(scene, {"--set", "body.0.position=[0.01, 0.0, 0.065]", "--engine", hulls->name}), 0)
            << err_;
        const nlohmann::json s = summary();
        ASSERT_TRUE(s["topple_angle_deg"].is_number()) << s.dump();
        EXPECT_NEAR(s["topple_angle_deg"].get<double>(), exact, 1.0) << s.dump();
        EXPECT_EQ(s["left_by"], "toppled") << s.dump();
        EXPECT_NEAR(s["leave_angle_deg"].get<double>(), exact, 1.0) << s.dump();
        fs::remove_all(out());
    }
    ASSERT_EQ(run(scene, {"--set", "body.0.position=[0.01, 0.0, 0.065]"}), 0) << err_;
    const nlohmann::json s = summary();
    EXPECT_EQ(s["spheres_per_unit"]["cube"], 118) << s.dump();
    ASSERT_TRUE(s["topple_angle_deg"].is_number()) << s.dump();
    EXPECT_LT(s["topple_angle_deg"].get<double>(), exact - 4.0) << s.dump();
}

TEST_F(Run, EdgeSpheresSeatACubeOverItsNeighboursEdgeWhereTheScenesClumpCannot) {
    // 30 % of the free cube over its held neighbour's downhill edge (x = 12
    // mm): an exact cube rests there and tips at atan((a/2 - x) / (a/2)) =
    // 21.8 deg. The scene's 118-sphere clump cannot seat it at all (it
    // pivots 3-5 mm short of the edge, on the last high sphere cap, so the
    // cube topples off as it lands), whatever the sphere count. The
    // builder's edge spheres (unit.edge_spheres) stand the neighbour's face
    // as high at its edge as at its corners: the scene's body of 110
    // spheres with 7 along every edge seats it and lets it go within 1.5 deg
    // of the exact cube (measured 21.8 deg; 22.2-23.0 deg for 1, 3 or 7 of
    // the 118's, docs/validation/stability.md, "Edge spheres"). Past 35 %
    // over the edge they still fail there: the bench's rows, not this test.
    // Their cost is asserted too: squarely on its neighbour (x = 0) the
    // cube's edge spheres fall between its neighbour's, and it slides late
    // (measured 41.3 deg where an exact cube slides at 31.0): if a change
    // cures that, measure the docs' figures again.
    const std::string scene = shipped_scene("tilt_cube_pair.toml");
    const double exact = std::atan(0.4) * 57.29577951308232;
    ASSERT_EQ(run(scene, {"--set", "body.0.position=[0.012, 0.0, 0.065]"}), 0) << err_;
    nlohmann::json s = summary();
    EXPECT_EQ(s["spheres_per_unit"]["cube"], 118) << s.dump();
    EXPECT_EQ(s["left_before_resting"], true) << s.dump();
    fs::remove_all(out());
    ASSERT_EQ(run(scene, {"--set", "body.0.position=[0.012, 0.0, 0.065]", "--set", "unit.0.spheres=202",
                          "--set", "unit.0.edge_spheres=7"}),
              0)
        << err_;
    s = summary();
    EXPECT_EQ(s["spheres_per_unit"]["cube"], 202) << s.dump();
    EXPECT_EQ(s["left_before_resting"], false) << s.dump();
    EXPECT_EQ(s["left_by"], "toppled") << s.dump();
    EXPECT_NEAR(s["leave_angle_deg"].get<double>(), exact, 1.5) << s.dump();
    fs::remove_all(out());
    ASSERT_EQ(run(scene, {"--set", "unit.0.spheres=202", "--set", "unit.0.edge_spheres=7"}), 0) << err_;
    s = summary();
    EXPECT_EQ(s["left_by"], "slid") << s.dump();
    EXPECT_GT(s["leave_angle_deg"].get<double>(), std::atan(0.6) * 57.29577951308232 + 4.0) << s.dump();
    // Asked for with too few spheres for them, the scene is refused by name.
    fs::remove_all(out());
    EXPECT_EQ(run(scene, {"--set", "unit.0.spheres=60", "--set", "unit.0.edge_spheres=7"}), 2);
    EXPECT_NE(err_.find("unit.0.edge_spheres"), std::string::npos) << err_;
    EXPECT_FALSE(fs::exists(out() / "summary.json"));
}

TEST_F(Run, ACubeThatCannotRestOnItsNeighbourLeavesBeforeItRestsAndSaysSo) {
    // The free cube's centre 5 mm past its neighbour's edge: an exact cube
    // has no seat there and topples off as it lands, before it ever comes
    // to rest. The tilt analysis must say so and read no slide or topple
    // angle on whatever caught it (the floor), for either unit model.
    const std::string scene = shipped_scene("tilt_cube_pair.toml");
    std::vector<std::vector<std::string>> models = {{}};
    if (const armour::EngineStyle *hulls = hull_engine())
        models.push_back({"--engine", hulls->name});
    for (std::vector<std::string> extra : models) {
        fs::remove_all(out());
        extra.insert(extra.end(), {"--set", "body.0.position=[0.025, 0.0, 0.065]"});
        ASSERT_EQ(run(scene, extra), 0) << err_;
        const nlohmann::json s = summary();
        EXPECT_EQ(s["left_before_resting"], true) << s.dump();
        EXPECT_EQ(s["left_by"], "toppled") << s.dump();
        EXPECT_LT(s["leave_angle_deg"].get<double>(), 1.0) << s.dump();
        EXPECT_TRUE(s["slide_angle_deg"].is_null()) << s.dump();
        EXPECT_TRUE(s["topple_angle_deg"].is_null()) << s.dump();
        EXPECT_NE(err_.find("never came to rest on its seat"), std::string::npos) << err_;
    }
}

TEST_F(Run, ExactHullsHoldTheirOwnSettledLayerDry) {
    // Seed 2's layer of 99 cubes, settled by the hulls on the stability
    // scene's 1:1.5 face (porosity 0.356, inside the Rock Manual's band),
    // held without water for 10 s: a laboratory's layer stands. With Bullet's
    // default of one friction direction per contact point it slumped down the
    // face (49 units a quarter unit or more); with two directions and 20
    // solver iterations it crept (11), with 50 none moved (docs/bullet.md).
    // 3 of 99 leaves room for a unit resting loose on top, none for a slump.
    const armour::EngineStyle *hulls = hull_engine();
    if (!hulls)
        GTEST_SKIP() << "no exact-hull engine in this build";
    // The layer without the fluid's tables, as users make it (studies/dry_scene.py).
    const fs::path source(ARMOUR_SOURCE_DIR), dry_file = dir_ / "dry.toml";
    const std::string make_dry =
        "/usr/bin/python3 " + (source / "studies/dry_scene.py").string() + " " +
        (source / "docs/results/severe_sea_one_layer_at_rest/layers/seed-2.toml").string() + " " +
        dry_file.string();
    ASSERT_EQ(std::system(make_dry.c_str()), 0) << make_dry;
    std::ifstream in(dry_file);
    const std::string dry((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::string line;
    ASSERT_NE(dry.find("[[body]]"), std::string::npos);
    ASSERT_EQ(run(dry, {"--engine", hulls->name, "--set", "run.duration=10"}), 0) << err_;
    // damage.csv: a comment line, the header, one row per unit.
    std::ifstream csv(out() / "damage.csv");
    const auto fields = [](const std::string &row) {
        std::vector<std::string> parts;
        std::stringstream stream(row);
        for (std::string field; std::getline(stream, field, ',');)
            parts.push_back(field);
        return parts;
    };
    std::getline(csv, line);
    std::getline(csv, line);
    const std::vector<std::string> header = fields(line);
    const auto column = std::find(header.begin(), header.end(), "final_displacement_over_Dn");
    ASSERT_NE(column, header.end()) << line;
    const std::size_t moved_column = static_cast<std::size_t>(column - header.begin());
    int units = 0, moved = 0;
    while (std::getline(csv, line)) {
        ++units;
        moved += std::stod(fields(line).at(moved_column)) >= 0.25 ? 1 : 0;
    }
    EXPECT_EQ(units, 99);
    EXPECT_LE(moved, 3) << "units moved a quarter unit or more in 10 s, held dry";
}
