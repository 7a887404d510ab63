// Scene files: every key read with its unit and default, every bad input
// rejected with one line naming file, line and key, --set overrides checked
// like the file, and the resolved scene reloading to the same Scene.
#include "engine_registry.h"
#include "input_error.h"
#include "scene.h"
#include "scene_keys.h"
#include "scratch_folder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace fs = std::filesystem;
using armour::InputError;
using armour::load_scene;
using armour::Scene;

namespace {

// Every key of every section, with values that differ from the defaults.
const char *kFull = R"(# a complete scene
name = "full"

[run]
engine = "bullet"
duration = 2.5
output_interval = 0.05
time_step = 1e-5
force_time_step = true
gravity = [0, 0, -9]
domain_min = [-2, -3, -1]
domain_max = [4, 3, 5]

[contact]
model = "hooke"
characteristic_velocity = 2

[analysis]
kind = "tilt"
tilt_rate = 5
tilt_max = 45.5

[[material]]
name = "concrete"
youngs_modulus = 1e8
poisson_ratio = 0.2
restitution = 0.4
friction = 0.7
rolling_friction = 0.05

[[material]]
name = "steel"
youngs_modulus = 2e8

[[material_pair]]
a = "concrete"
b = "steel"
friction = 0.3

[[unit]]
name = "cube"
shape = "cube"
size = 0.2
chamfer = 0.01
density = 2300
spheres = 20
tol_volume = 0.05
tol_surface = 0.04
method = "greedy"
material = "concrete"

[[unit]]
name = "dolos"
shape = "dolos"
height = 0.3
waist = 0.4
material = "steel"

[[unit]]
name = "mesh"
shape = "stl"
stl = "meshes/unit.stl"
material = "concrete"

[[wall]]
name = "floor"
type = "plane"
point = [0, 0, 0.5]
normal = [0, 0, 2]
size = 4
material = "steel"

[[wall]]
name = "slope"
type = "slope"
toe_x = 1
floor_z = -0.5
cot = 2
height = 1.5
width = 1.2
toe_height = 0.1
material = "concrete"

[[wall]]
type = "box"
min = [-1, -1, 0]
max = [1, 1, 2]
material = "concrete"

[[wall]]
name = "scan"
type = "stl"
file = "meshes/unit.stl"
material = "steel"

[[body]]
unit = "cube"
position = [0.1, 0.2, 0.3]
orientation = [0, 0, 0, 2]
velocity = [1, 0, -1]
angular_velocity = [0, 3, 0]
fixed_translation = [true, false, true]
fixed_rotation = [false, true, false]

[[drop]]
unit = "dolos"
count = 7
min = [-1, -1, 1]
max = [1, 1, 2]
seed = 42

[[pattern]]
unit = "cube"
wall = "slope"
rows = 3
columns = 4
spacing = 0.25
gap = 0.002
placement = "random"
seed = 9
)";

// Only what is required; everything else defaults.
const char *kMinimal = R"(name = "minimal"

[[material]]
name = "m"

[[unit]]
name = "u"
shape = "cube"
size = 0.2

[[body]]
unit = "u"
position = [0, 0, 1]
)";

// `text` with its first `from` replaced by `to`.
std::string replaced(std::string text, const std::string &from, const std::string &to) {
    const auto at = text.find(from);
    if (at != std::string::npos)
        text.replace(at, from.size(), to);
    return text;
}

class SceneFile : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = armour_test::fresh_test_folder("scene");
        fs::create_directories(dir_ / "meshes");
        std::ofstream(dir_ / "meshes" / "unit.stl") << "solid x\nendsolid x\n";
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string write(const std::string &text, const std::string &name = "scene.toml") {
        const fs::path p = dir_ / name;
        std::ofstream(p) << text;
        return p.string();
    }

    // The one-line message load_scene throws, or "" if it accepted the scene.
    static std::string error_of(const std::string &path, const std::vector<std::string> &overrides = {}) {
        try {
            load_scene(path, overrides);
        } catch (const InputError &e) {
            return e.what();
        }
        return "";
    }

    // A minimal scene with `line` replacing the line that starts with `prefix`
    // (or appended when `prefix` is empty); returns the file and the 1-based
    // line the change landed on.
    std::pair<std::string, int> minimal_with(const std::string &prefix, const std::string &line) {
        std::vector<std::string> lines;
        std::string l;
        std::istringstream in(kMinimal);
        while (std::getline(in, l))
            lines.push_back(l);
        int at = 0;
        if (prefix.empty()) {
            lines.push_back(line);
            at = static_cast<int>(lines.size());
        } else {
            for (std::size_t i = 0; i < lines.size(); ++i)
                if (lines[i].rfind(prefix, 0) == 0) {
                    lines[i] = line;
                    at = static_cast<int>(i) + 1;
                    break;
                }
        }
        EXPECT_GT(at, 0) << "no line starts with " << prefix;
        std::string text;
        for (const auto &x : lines)
            text += x + "\n";
        return {write(text), at};
    }

    // The error is one line: FILE:LINE: key 'KEY': ...
    void expect_error(const std::string &path, int line, const std::string &key,
                      const std::string &reason = "", const std::vector<std::string> &overrides = {}) {
        const std::string e = error_of(path, overrides);
        ASSERT_FALSE(e.empty()) << "accepted";
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
        const std::string head = path + ":" + std::to_string(line) + ": key '" + key + "': ";
        EXPECT_EQ(e.rfind(head, 0), 0u) << e << "\nexpected to start with: " << head;
        EXPECT_NE(e.find(reason), std::string::npos) << e << "\nexpected to contain: " << reason;
    }

    fs::path dir_;
};

// Every key of the table compares equal (the table names every field).
template <class S>
void expect_same_keys(const S &a, const S &b, const std::vector<armour::Key<S>> &keys,
                      const std::string &where) {
    for (const auto &k : keys)
        std::visit([&](auto S::*field) { EXPECT_EQ(a.*field, b.*field) << where << k.name; }, k.field);
}

template <class S>
void expect_same_entries(const std::vector<S> &a, const std::vector<S> &b,
                         const std::vector<armour::Key<S>> &keys, const std::string &section) {
    ASSERT_EQ(a.size(), b.size()) << section;
    for (std::size_t i = 0; i < a.size(); ++i)
        expect_same_keys(a[i], b[i], keys, section + "." + std::to_string(i) + ".");
}

void expect_same(const Scene &a, const Scene &b) {
    for (const auto *keys :
         {&armour::root_keys(), &armour::run_keys(), &armour::contact_keys(), &armour::analysis_keys()})
        expect_same_keys(a, b, *keys, "");
    expect_same_entries(a.materials, b.materials, armour::material_keys(), "material");
    expect_same_entries(a.material_pairs, b.material_pairs, armour::material_pair_keys(), "material_pair");
    expect_same_entries(a.units, b.units, armour::unit_keys(), "unit");
    expect_same_entries(a.walls, b.walls, armour::wall_keys(), "wall");
    expect_same_entries(a.bodies, b.bodies, armour::body_keys(), "body");
    expect_same_entries(a.drops, b.drops, armour::drop_keys(), "drop");
    expect_same_entries(a.patterns, b.patterns, armour::pattern_keys(), "pattern");
    ASSERT_EQ(a.fluid.has_value(), b.fluid.has_value());
    if (a.fluid) {
        expect_same_keys(*a.fluid, *b.fluid, armour::fluid_keys(), "fluid.");
        EXPECT_EQ(a.fluid->has_water_box, b.fluid->has_water_box);
    }
}

// Every [fluid] key, with values that differ from the defaults.
const char *kFluid = R"(
[analysis]
kind = "buoyancy"

[fluid]
case = "buoyancy_cube"
water_level = 0.8
cells = [12, 10, 8]
penalty = 2e5
mask = "spheres"
smoothing_cells = 1.5
added_mass = 0.5
np = 2
fluid_density = 1025
air_density = 1.2
viscosity = 1.2e-6
air_viscosity = 1.5e-5
max_courant = 0.4
max_time_step = 0.002
write_interval = 0.5
)";

} // namespace

TEST_F(SceneFile, FullSceneReadsEveryKey) {
    const std::string path = write(kFull);
    const Scene s = load_scene(path);
    EXPECT_EQ(s.file, path);
    EXPECT_EQ(s.name, "full");
    EXPECT_EQ(s.engine, "bullet");
    EXPECT_DOUBLE_EQ(s.duration, 2.5);
    EXPECT_DOUBLE_EQ(s.output_interval, 0.05);
    EXPECT_DOUBLE_EQ(s.time_step, 1e-5);
    EXPECT_TRUE(s.force_time_step);
    EXPECT_EQ(s.gravity, Eigen::Vector3d(0, 0, -9));
    EXPECT_EQ(s.domain_min, Eigen::Vector3d(-2, -3, -1));
    EXPECT_EQ(s.domain_max, Eigen::Vector3d(4, 3, 5));
    EXPECT_EQ(s.contact_model, "hooke");
    EXPECT_DOUBLE_EQ(s.characteristic_velocity, 2.0);
    EXPECT_EQ(s.analysis, "tilt");
    EXPECT_DOUBLE_EQ(s.tilt_rate, 5.0);
    EXPECT_DOUBLE_EQ(s.tilt_max, 45.5);

    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_EQ(s.materials[0].name, "concrete");
    EXPECT_DOUBLE_EQ(s.materials[0].youngs_modulus, 1e8);
    EXPECT_DOUBLE_EQ(s.materials[0].poisson_ratio, 0.2);
    EXPECT_DOUBLE_EQ(s.materials[0].restitution, 0.4);
    EXPECT_DOUBLE_EQ(s.materials[0].friction, 0.7);
    EXPECT_DOUBLE_EQ(s.materials[0].rolling_friction, 0.05);
    EXPECT_DOUBLE_EQ(s.materials[1].youngs_modulus, 2e8);
    ASSERT_EQ(s.material_pairs.size(), 1u);
    EXPECT_EQ(s.material_pairs[0].a, "concrete");
    EXPECT_EQ(s.material_pairs[0].b, "steel");
    EXPECT_FALSE(s.material_pairs[0].restitution.has_value());
    ASSERT_TRUE(s.material_pairs[0].friction.has_value());
    EXPECT_DOUBLE_EQ(*s.material_pairs[0].friction, 0.3);
    EXPECT_FALSE(s.material_pairs[0].rolling_friction.has_value());

    ASSERT_EQ(s.units.size(), 3u);
    const auto &cube = s.units[0];
    EXPECT_EQ(cube.shape, "cube");
    EXPECT_DOUBLE_EQ(cube.size, 0.2);
    EXPECT_DOUBLE_EQ(cube.chamfer, 0.01);
    EXPECT_DOUBLE_EQ(cube.density, 2300);
    EXPECT_EQ(cube.spheres, 20);
    EXPECT_DOUBLE_EQ(cube.tol_volume, 0.05);
    EXPECT_DOUBLE_EQ(cube.tol_surface, 0.04);
    EXPECT_EQ(cube.method, "greedy");
    EXPECT_EQ(cube.material, "concrete");
    EXPECT_EQ(s.units[1].shape, "dolos");
    EXPECT_DOUBLE_EQ(s.units[1].height, 0.3);
    EXPECT_DOUBLE_EQ(s.units[1].waist, 0.4);
    EXPECT_EQ(s.units[1].material, "steel");
    EXPECT_EQ(s.units[1].spheres, 0); // no `spheres`: tolerance mode
    // STL paths are relative to the scene file, stored absolute.
    EXPECT_TRUE(fs::path(s.units[2].stl).is_absolute()) << s.units[2].stl;
    EXPECT_TRUE(fs::equivalent(s.units[2].stl, dir_ / "meshes" / "unit.stl"));

    ASSERT_EQ(s.walls.size(), 4u);
    EXPECT_EQ(s.walls[0].name, "floor");
    EXPECT_EQ(s.walls[0].point, Eigen::Vector3d(0, 0, 0.5));
    EXPECT_EQ(s.walls[0].normal, Eigen::Vector3d(0, 0, 1)); // normalised
    EXPECT_DOUBLE_EQ(s.walls[0].size, 4);
    EXPECT_EQ(s.walls[0].material, "steel");
    const auto &slope = s.walls[1];
    EXPECT_EQ(slope.type, "slope");
    EXPECT_DOUBLE_EQ(slope.toe_x, 1);
    EXPECT_DOUBLE_EQ(slope.floor_z, -0.5);
    EXPECT_DOUBLE_EQ(slope.cot, 2);
    EXPECT_DOUBLE_EQ(slope.height, 1.5);
    EXPECT_DOUBLE_EQ(slope.width, 1.2);
    EXPECT_DOUBLE_EQ(slope.toe_height, 0.1);
    EXPECT_EQ(s.walls[2].type, "box");
    EXPECT_EQ(s.walls[2].name, "box_2"); // unnamed walls get type_index
    EXPECT_EQ(s.walls[2].min, Eigen::Vector3d(-1, -1, 0));
    EXPECT_EQ(s.walls[2].max, Eigen::Vector3d(1, 1, 2));
    EXPECT_TRUE(fs::equivalent(s.walls[3].file, dir_ / "meshes" / "unit.stl"));

    ASSERT_EQ(s.bodies.size(), 1u);
    const auto &b = s.bodies[0];
    EXPECT_EQ(b.unit, "cube");
    EXPECT_EQ(b.position, Eigen::Vector3d(0.1, 0.2, 0.3));
    EXPECT_EQ(b.orientation, Eigen::Vector4d(0, 0, 0, 1)); // normalised
    EXPECT_EQ(b.velocity, Eigen::Vector3d(1, 0, -1));
    EXPECT_EQ(b.angular_velocity, Eigen::Vector3d(0, 3, 0));
    EXPECT_EQ(b.fixed_translation, (std::array<bool, 3>{{true, false, true}}));
    EXPECT_EQ(b.fixed_rotation, (std::array<bool, 3>{{false, true, false}}));

    ASSERT_EQ(s.drops.size(), 1u);
    EXPECT_EQ(s.drops[0].unit, "dolos");
    EXPECT_EQ(s.drops[0].count, 7);
    EXPECT_EQ(s.drops[0].min, Eigen::Vector3d(-1, -1, 1));
    EXPECT_EQ(s.drops[0].max, Eigen::Vector3d(1, 1, 2));
    EXPECT_EQ(s.drops[0].seed, 42u);

    ASSERT_EQ(s.patterns.size(), 1u);
    EXPECT_EQ(s.patterns[0].wall, "slope");
    EXPECT_EQ(s.patterns[0].rows, 3);
    EXPECT_EQ(s.patterns[0].columns, 4);
    EXPECT_DOUBLE_EQ(s.patterns[0].spacing, 0.25);
    EXPECT_DOUBLE_EQ(s.patterns[0].gap, 0.002);
    EXPECT_EQ(s.patterns[0].placement, "random");
    EXPECT_EQ(s.patterns[0].seed, 9u);
}

TEST_F(SceneFile, DefaultsFillWhatIsAbsent) {
    const Scene s = load_scene(write(kMinimal));
    EXPECT_EQ(s.engine, "liggghts");
    EXPECT_DOUBLE_EQ(s.duration, 1.0);
    EXPECT_DOUBLE_EQ(s.output_interval, 0.01);
    EXPECT_DOUBLE_EQ(s.time_step, 0.0);
    EXPECT_FALSE(s.force_time_step);
    EXPECT_EQ(s.gravity, Eigen::Vector3d(0, 0, -9.81));
    EXPECT_EQ(s.domain_min, Eigen::Vector3d(-5, -5, -1));
    EXPECT_EQ(s.domain_max, Eigen::Vector3d(5, 5, 5));
    EXPECT_EQ(s.contact_model, "hertz");
    EXPECT_DOUBLE_EQ(s.characteristic_velocity, 1.0);
    EXPECT_EQ(s.analysis, "none");
    EXPECT_DOUBLE_EQ(s.tilt_max, 60.0);
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_DOUBLE_EQ(s.materials[0].youngs_modulus, 5e7);
    EXPECT_DOUBLE_EQ(s.materials[0].poisson_ratio, 0.25);
    EXPECT_DOUBLE_EQ(s.materials[0].restitution, 0.5);
    EXPECT_DOUBLE_EQ(s.materials[0].friction, 0.6);
    EXPECT_DOUBLE_EQ(s.materials[0].rolling_friction, 0.0);
    ASSERT_EQ(s.units.size(), 1u);
    const auto &u = s.units[0];
    EXPECT_DOUBLE_EQ(u.chamfer, 0.0);
    EXPECT_DOUBLE_EQ(u.density, 2400.0);
    EXPECT_EQ(u.spheres, 0);
    EXPECT_DOUBLE_EQ(u.tol_volume, 0.01);
    EXPECT_DOUBLE_EQ(u.tol_surface, 0.02);
    EXPECT_EQ(u.method, "optimised");
    EXPECT_EQ(u.material, "m"); // the only material
    ASSERT_EQ(s.bodies.size(), 1u);
    EXPECT_EQ(s.bodies[0].orientation, Eigen::Vector4d(1, 0, 0, 0));
    EXPECT_EQ(s.bodies[0].velocity, Eigen::Vector3d::Zero());
    EXPECT_EQ(s.bodies[0].fixed_rotation, (std::array<bool, 3>{{false, false, false}}));
    EXPECT_TRUE(s.walls.empty());
    EXPECT_TRUE(s.drops.empty());
}

TEST_F(SceneFile, IntegerAcceptedWhereFloatExpected) {
    const auto [path, line] = minimal_with("size", "size = 1");
    EXPECT_DOUBLE_EQ(load_scene(path).units[0].size, 1.0);
}

TEST_F(SceneFile, OverridesScalarNestedIndexedAndCreated) {
    const std::string path = write(kFull);
    const Scene s = load_scene(path, {"run.duration=0.5",          // nested scalar
                                      "name = \"renamed\"",        // root string, spaces around '='
                                      "unit.0.spheres=30",         // array of tables by index
                                      "unit.1.spheres=12",         // created: a known key absent in the file
                                      "run.gravity=[0, 0, -1.62]", // array value
                                      "run.gravity.0=0.5",         // one entry of an array
                                      "wall.1.cot=3",              // integer where a float is expected
                                      "material_pair.0.restitution=0.9"});
    EXPECT_DOUBLE_EQ(s.duration, 0.5);
    EXPECT_EQ(s.name, "renamed");
    EXPECT_EQ(s.units[0].spheres, 30);
    EXPECT_EQ(s.units[1].spheres, 12);
    EXPECT_EQ(s.gravity, Eigen::Vector3d(0.5, 0, -1.62));
    EXPECT_DOUBLE_EQ(s.walls[1].cot, 3.0);
    ASSERT_TRUE(s.material_pairs[0].restitution.has_value());
    EXPECT_DOUBLE_EQ(*s.material_pairs[0].restitution, 0.9);
    // Untouched values survive.
    EXPECT_DOUBLE_EQ(s.output_interval, 0.05);
}

TEST_F(SceneFile, OverrideCreatesAbsentSection) {
    const Scene s = load_scene(write(kMinimal), {"analysis.kind=\"bounce\"", "contact.model=\"hooke\""});
    EXPECT_EQ(s.analysis, "bounce");
    EXPECT_EQ(s.contact_model, "hooke");
}

TEST_F(SceneFile, OverriddenValuesAreCheckedAndBlameSet) {
    const std::string path = write(kFull);
    const std::string e = error_of(path, {"run.duration=-1"});
    EXPECT_EQ(e.rfind("--set: key 'run.duration': must be > 0 s (got -1)", 0), 0u) << e;
    const std::string t = error_of(path, {"unit.0.size=\"big\""});
    EXPECT_EQ(t.rfind("--set: key 'unit.0.size': must be a number", 0), 0u) << t;
}

TEST_F(SceneFile, MalformedOverridesAreRejected) {
    const std::string path = write(kFull);
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"run.duration", "expected KEY=VALUE"},
        {"run.duration=", "empty value"},
        {"=1", "empty key"},
        {"run..duration=1", "empty segment"},
        {"run.duration=hello", "key 'run.duration' takes a number, and hello is not one"},
        {"name=\"unterminated", "key 'name' takes a string"}, // a quote begins a TOML string
        {"run.durration=1", "did you mean 'duration'"},       // unknown key cannot be created
        {"unit.5.size=1", "index 5 out of range"},
        {"unit.size=1", "is an array"},
        {"nothere.x=1", "does not exist"},
        {"run.duration.x=1", "not a table"},
        {"run.duration=1\nname=\"x\"", "single TOML value"},
    };
    for (const auto &[set, reason] : cases) {
        const std::string e = error_of(path, {set});
        EXPECT_EQ(e.rfind("--set '" + set + "': ", 0), 0u) << set << " -> " << e;
        EXPECT_NE(e.find(reason), std::string::npos) << set << " -> " << e;
    }
}

// A string key takes a bare word as well as its TOML string: the text after
// the first '=', its ends trimmed, whatever it looks like (a number, a date,
// more '='), in single tables, arrays of tables and at the top level alike.
TEST_F(SceneFile, StringKeyTakesABareWord) {
    const Scene s = load_scene(write(kFull), {"name=bare",                  // top level
                                              "contact.model=hertz",        // a choice in a single table
                                              "unit.0.method=optimised",    // an array of tables
                                              "unit.2.stl=meshes/unit.stl", // a path: resolved as in the file
                                              "wall.0.name = 2 ",           // a number's text, trimmed
                                              "wall.3.name=a=b c"});        // '=' and spaces kept
    EXPECT_EQ(s.name, "bare");
    EXPECT_EQ(s.contact_model, "hertz");
    EXPECT_EQ(s.units[0].method, "optimised");
    EXPECT_TRUE(fs::equivalent(s.units[2].stl, dir_ / "meshes" / "unit.stl")) << s.units[2].stl;
    EXPECT_EQ(s.walls[0].name, "2");
    EXPECT_EQ(s.walls[3].name, "a=b c");
    // A date is text too; the quoted forms read as TOML strings, escapes included.
    EXPECT_EQ(load_scene(write(kFull), {"name=1979-05-27"}).name, "1979-05-27");
    EXPECT_EQ(load_scene(write(kFull), {"name=\"a\\tb\""}).name, "a\tb");
    EXPECT_EQ(load_scene(write(kFull), {"name='c:\\x'"}).name, "c:\\x");
}

// The shipped wave flume's own comment: --set waves.type=irregular.
TEST_F(SceneFile, WaveFlumeTakesItsCommentsOverride) {
    const std::string flume = (fs::path(ARMOUR_SOURCE_DIR) / "scenes" / "wave_flume.toml").string();
    for (const char *set : {"waves.type=irregular", "waves.type=\"irregular\"", "waves.type='irregular'"}) {
        const Scene s = load_scene(flume, {set});
        ASSERT_TRUE(s.waves.has_value());
        EXPECT_EQ(s.waves->type, "irregular") << set;
    }
}

// A bare word is text for string keys only: a number, boolean or array key
// refuses it in one line naming --set, the key and the type it takes; a
// string key refuses an array, and a choice key a word it does not know.
TEST_F(SceneFile, BareWordForAnotherTypeIsRefused) {
    const std::string path = write(kFull);
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"run.duration=abc",
         "--set 'run.duration=abc': key 'run.duration' takes a number, and abc is not one"},
        {"unit.0.spheres=many", "--set 'unit.0.spheres=many': key 'unit.0.spheres' takes an integer"},
        {"run.force_time_step=yes",
         "--set 'run.force_time_step=yes': key 'run.force_time_step' takes true or false"},
        {"run.gravity=0,0,-9", "--set 'run.gravity=0,0,-9': key 'run.gravity' takes an array [x, y, z]"},
        {"body.0.fixed_rotation=x",
         "--set 'body.0.fixed_rotation=x': key 'body.0.fixed_rotation' takes an array "
         "of 3 booleans"},
        {"name=[1, 2]", "--set: key 'name': must be a string (got an array)"},
        {"contact.model=hook",
         "--set: key 'contact.model': must be one of \"hertz\", \"hooke\" (got \"hook\""},
        {"run.durration=fast",
         "--set 'run.durration=fast': unknown key 'run.durration' (did you mean 'duration'?)"},
    };
    for (const auto &[set, head] : cases) {
        const std::string e = error_of(path, {set});
        EXPECT_EQ(e.rfind(head, 0), 0u) << set << " -> " << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
}

TEST_F(SceneFile, UnknownKeyNamesLineAndSuggests) {
    const auto [path, line] = minimal_with("size", "sise = 0.2");
    expect_error(path, line, "unit.0.sise", "unknown key (did you mean 'size'?)");
    const auto [p2, l2] = minimal_with("", "[runn]");
    expect_error(p2, l2, "runn", "did you mean 'run'?");
}

TEST_F(SceneFile, KeyOfAnotherShapeIsRejected) {
    const auto [path, line] = minimal_with("size", "height = 0.2");
    expect_error(path, line, "unit.0.height", "not used by shape \"cube\"");
}

TEST_F(SceneFile, MissingRequiredKeys) {
    // At the enclosing table's header line.
    const auto [p1, l1] = minimal_with("size", "");
    expect_error(p1, 6, "unit.0.size", "missing required key");
    const auto [p2, l2] = minimal_with("name = \"minimal\"", "");
    expect_error(p2, 1, "name", "missing required key");
    const auto [p3, l3] = minimal_with("", "[[wall]]\ntype = \"plane\"\nnormal = [0, 0, 1]");
    expect_error(p3, l3, "wall.0.point", "missing required key");
    const std::string p4 = write("name = \"x\"\n[[unit]]\nname = \"u\"\nshape = \"cube\"\nsize = 1\n");
    expect_error(p4, 1, "material", "at least one [[material]]");
}

TEST_F(SceneFile, WrongTypes) {
    const auto [p1, l1] = minimal_with("size", "size = \"0.2\"");
    expect_error(p1, l1, "unit.0.size", "must be a number in m (got string \"0.2\")");
    const auto [p3, l3] = minimal_with("size", "size = 0.2\nspheres = 20.0");
    expect_error(p3, l3 + 1, "unit.0.spheres", "must be an integer (got float 20)");
    const auto [p4, l4] = minimal_with("position", "position = [0, 0]");
    expect_error(p4, l4, "body.0.position", "array of 3 numbers");
    const auto [p5, l5] = minimal_with("position", "position = [0, \"a\", 1]");
    expect_error(p5, l5, "body.0.position", "entry 1 is string");
    const auto [p6, l6] = minimal_with("", "fixed_rotation = [1, 0, 0]");
    expect_error(p6, l6, "body.0.fixed_rotation", "3 booleans");
    const std::string p7 = write("name = \"x\"\nunit = 3\n[[material]]\nname = \"m\"\n");
    expect_error(p7, 2, "unit", "must be an array of tables, written [[unit]]");
}

TEST_F(SceneFile, OutOfRangeValues) {
    const auto [p1, l1] = minimal_with("size", "size = -1");
    expect_error(p1, l1, "unit.0.size", "must be > 0 m (got -1)");
    const auto [p2, l2] = minimal_with("", "orientation = [0, 0, 0, 0]");
    expect_error(p2, l2, "body.0.orientation", "non-zero quaternion");
    const auto [p3, l3] = minimal_with("position", "position = [0, 0, 9]");
    expect_error(p3, l3, "body.0.position", "inside run.domain");
    const std::string p4 = write(std::string(kMinimal) + "[run]\nduration = 1\noutput_interval = 2\n");
    expect_error(p4, 16, "run.output_interval", "must be <= run.duration");
    const std::string p5 =
        write(std::string(kMinimal) + "[analysis]\nkind = \"tilt\"\ntilt_rate = 1\ntilt_max = 95\n");
    expect_error(p5, 17, "analysis.tilt_max", "(0, 90]");
    const std::string p6 = write(std::string(kMinimal) + "[analysis]\nkind = \"tilt\"\n");
    expect_error(p6, 14, "analysis.tilt_rate", "missing required key for kind \"tilt\"");
    const std::string p7 = write(std::string(kMinimal) + "[run]\ndomain_max = [5, 5, -2]\n");
    expect_error(p7, 15, "run.domain_max", "must exceed run.domain_min");
    const auto [p8, l8] = minimal_with("name = \"m\"", "name = \"m\"\npoisson_ratio = 0.5");
    expect_error(p8, l8 + 1, "material.0.poisson_ratio", "(-1, 0.5)");
    const auto [p10, l10] = minimal_with("shape", "shape = \"dolo\"");
    expect_error(p10, l10, "unit.0.shape", "did you mean \"dolos\"?");
    const auto [p9, l9] = minimal_with("shape", "shape = \"sphere\"");
    expect_error(p9, l9, "unit.0.shape", "must be one of \"cube\", \"dolos\", \"stl\" (got \"sphere\")");
}

// A hinge off the centre of mass: the free_body engine only, and only with
// held translations for the pivot to keep.
TEST_F(SceneFile, PivotNeedsFreeBodyAndHeldTranslation) {
    const std::string hinge = "fixed_translation = [true, false, true]\npivot = [0, 0, 0.9]";
    const std::string free_body = "[run]\nengine = \"free_body\"\n";
    const std::string ok = write(std::string(kMinimal) + hinge + "\n" + free_body);
    const Scene s = load_scene(ok);
    ASSERT_TRUE(s.bodies[0].pivot.has_value());
    EXPECT_EQ(*s.bodies[0].pivot, Eigen::Vector3d(0, 0, 0.9));
    const std::string resolved = write(resolved_scene_toml(s));
    EXPECT_EQ(load_scene(resolved).bodies[0].pivot, s.bodies[0].pivot);

    const std::string liggghts = write(std::string(kMinimal) + hinge + "\n");
    expect_error(liggghts, 15, "body.0.pivot", "needs run.engine = \"free_body\" (got \"liggghts\")");
    const std::string loose = write(std::string(kMinimal) + "pivot = [0, 0, 0.9]\n" + free_body);
    expect_error(loose, 14, "body.0.pivot", "holds nothing without fixed_translation");
}

TEST_F(SceneFile, UnknownReferences) {
    const auto [p1, l1] = minimal_with("unit = \"u\"", "unit = \"v\"");
    expect_error(p1, l1, "body.0.unit", "no [[unit]] named \"v\" (known: \"u\")");
    const auto [p2, l2] = minimal_with("size", "size = 0.2\nmaterial = \"rock\"");
    expect_error(p2, l2 + 1, "unit.0.material", "no [[material]] named \"rock\"");
    const std::string full(kFull);
    const int last_line = static_cast<int>(std::count(full.begin(), full.end(), '\n'));
    const std::string p3 = write(full + "\n[[pattern]]\nunit = \"cube\"\nwall = \"floor\"\n");
    expect_error(p3, last_line + 4, "pattern.1.wall",
                 "is of type \"plane\"; a pattern needs a \"slope\" wall");
    // A placement the pattern does not know, from the file and from --set;
    // a negative seed.
    const std::string::size_type at = full.find("placement = \"random\"");
    ASSERT_NE(at, std::string::npos);
    const std::string p5 = write(std::string(full).replace(at, 20, "placement = \"hexagonal\""));
    expect_error(p5, static_cast<int>(std::count(full.begin(), full.begin() + at, '\n')) + 1,
                 "pattern.0.placement",
                 "must be one of \"grid\", \"random\", \"seated\" (got \"hexagonal\")");
    const std::string path = write(full);
    const std::string typo = error_of(path, {"pattern.0.placement=\"randon\""});
    EXPECT_EQ(typo.rfind("--set: key 'pattern.0.placement': must be one of", 0), 0u) << typo;
    const std::string seed = error_of(path, {"pattern.0.seed=-1"});
    EXPECT_EQ(seed.rfind("--set: key 'pattern.0.seed': ", 0), 0u) << seed;
    const std::string p4 =
        write(full + "\n[[drop]]\nunit = \"tetrapod\"\ncount = 1\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n");
    expect_error(p4, last_line + 3, "drop.1.unit", "no [[unit]] named \"tetrapod\"");
}

TEST_F(SceneFile, DuplicateUnitName) {
    const std::string p =
        write(std::string(kMinimal) + "\n[[unit]]\nname = \"u\"\nshape = \"cube\"\nsize = 1\n");
    expect_error(p, 16, "unit.1.name", "duplicate unit name \"u\"");
}

TEST_F(SceneFile, MaterialRequiredWhenSeveralExist) {
    const auto [p, l] = minimal_with("name = \"m\"", "name = \"m\"\n[[material]]\nname = \"n\"");
    expect_error(p, 8, "unit.0.material", "name one of \"m\", \"n\"");
}

TEST_F(SceneFile, MalformedToml) {
    const std::string p = write("name = \"x\"\n\n[run]\nduration = \n");
    const std::string e = error_of(p);
    EXPECT_EQ(e.rfind(p + ":4: invalid TOML: ", 0), 0u) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

TEST_F(SceneFile, UnreadableFile) {
    const std::string missing = (dir_ / "nope.toml").string();
    EXPECT_EQ(error_of(missing).rfind(missing + ": cannot read: ", 0), 0u) << error_of(missing);
    EXPECT_EQ(error_of(dir_.string()), dir_.string() + ": cannot read: is a directory");
}

TEST_F(SceneFile, ResolvedSceneRoundTrips) {
    for (const char *text : {kFull, kMinimal}) {
        const Scene a =
            load_scene(write(text), {"unit.0.chamfer=0.0123456789012345", "run.gravity=[0.1, 0.2, -9.3]"});
        const std::string resolved = armour::resolved_scene_toml(a);
        // Another folder: absolute STL paths must still resolve.
        fs::create_directories(dir_ / "elsewhere");
        const Scene b = load_scene(write(resolved, "elsewhere/resolved.toml"));
        expect_same(a, b);
        // Identical apart from the first line, which names the file it came from.
        const std::string again = armour::resolved_scene_toml(b);
        EXPECT_EQ(again.substr(again.find('\n')), resolved.substr(resolved.find('\n')));
    }
}

// The shipped examples load and say what their comments say.
TEST(ExampleScenes, CoupledScenesLoadAsDescribed) {
    const fs::path dir = fs::path(ARMOUR_SOURCE_DIR) / "scenes";
    const Scene b = load_scene((dir / "buoyancy_cube.toml").string());
    ASSERT_TRUE(b.fluid.has_value());
    EXPECT_EQ(b.analysis, "buoyancy");
    // Fully submerged: the top face below the water level.
    EXPECT_LT(b.bodies[0].position.z() + 0.5 * b.units[0].size, b.fluid->water_level);
    const Scene f = load_scene((dir / "floating_cube.toml").string());
    EXPECT_EQ(f.analysis, "float");
    EXPECT_DOUBLE_EQ(f.units[0].density, 500.0);
    // Released with its bottom face on the surface.
    EXPECT_NEAR(f.bodies[0].position.z() - 0.5 * f.units[0].size, f.fluid->water_level, 1e-12);
    const Scene s = load_scene((dir / "still_water_cube.toml").string());
    EXPECT_EQ(s.analysis, "still");
    EXPECT_DOUBLE_EQ(s.units[0].density, 2400.0);
    EXPECT_NEAR(s.bodies[0].position.z() - 0.5 * s.units[0].size, s.walls[0].point.z(), 1e-12);
    // The tutorial's hinge: the bottom-face centre slides along y.
    const Scene box = load_scene((dir / "floating_box.toml").string());
    ASSERT_TRUE(box.bodies[0].pivot.has_value());
    EXPECT_EQ(*box.bodies[0].pivot, Eigen::Vector3d(0.5, 0.45, 0.1));
    EXPECT_EQ(box.bodies[0].fixed_translation, (std::array<bool, 3>{{true, false, true}}));
    EXPECT_EQ(box.bodies[0].fixed_rotation, (std::array<bool, 3>{{true, false, true}}));
}

// The reference cases (docs/openfoam.md): they take minutes to run, so only
// their loading and layout are checked here (the dam break also runs, made
// short, in test_coupled).
TEST(ExampleScenes, ReferenceCasesLoadAsDescribed) {
    const fs::path dir = fs::path(ARMOUR_SOURCE_DIR) / "scenes";
    const Scene d = load_scene((dir / "dambreak_two_cubes.toml").string());
    EXPECT_EQ(d.analysis, "dambreak");
    ASSERT_TRUE(d.fluid.has_value());
    EXPECT_TRUE(d.fluid->has_water_box);
    EXPECT_DOUBLE_EQ(d.fluid->water_level, d.domain_min.z()); // dry bed outside the column
    ASSERT_EQ(d.bodies.size(), 2u);
    EXPECT_LT(d.bodies[0].position.x(), d.bodies[1].position.x()); // first, then second in the flow
    EXPECT_LT(d.units[0].density, d.fluid->fluid_density);         // light cubes
    EXPECT_GT(d.bodies[0].position.x() - 0.5 * d.units[0].size, d.fluid->water_box_max.x());

    const Scene p = load_scene((dir / "solitary_cubes_platform.toml").string());
    EXPECT_EQ(p.analysis, "platform");
    EXPECT_EQ(p.fluid->case_name, "solitary_platform");
    EXPECT_GT(p.fluid->wave_height, 0.0);
    EXPECT_LT(p.fluid->wave_height, 0.5 * (p.fluid->water_level - p.domain_min.z()));
    EXPECT_EQ(p.bodies.size(), 3u);
    bool platform = false;
    for (const auto &w : p.walls)
        platform = platform || w.name == "platform";
    EXPECT_TRUE(platform); // the fluid template cuts this wall out of the mesh

    const Scene s = load_scene((dir / "armour_slope_waves.toml").string());
    EXPECT_EQ(s.analysis, "slope_waves");
    EXPECT_EQ(s.fluid->case_name, "slope_waves");
    ASSERT_EQ(s.patterns.size(), 1u);
    const int units = s.patterns[0].rows * s.patterns[0].columns;
    EXPECT_GE(units, 20);
    EXPECT_LE(units, 30);
    ASSERT_EQ(s.walls[0].type, "slope");
    EXPECT_DOUBLE_EQ(s.walls[0].cot, 1.5);
    EXPECT_DOUBLE_EQ(s.walls[0].floor_z, s.domain_min.z()); // the fluid bed starts on the floor
    EXPECT_DOUBLE_EQ(s.walls[0].toe_height, 0.0);
    for (const char *c : {"dambreak", "solitary_platform", "slope_waves"})
        EXPECT_TRUE(fs::is_regular_file(dir.parent_path() / "foam_cases" / c / "system" / "blockMeshDict"))
            << c;
}

TEST(ExampleScenes, LoadAsDescribed) {
    const fs::path dir = fs::path(ARMOUR_SOURCE_DIR) / "scenes";
    const Scene drop = load_scene((dir / "drop_bounce.toml").string());
    EXPECT_EQ(drop.analysis, "bounce");
    ASSERT_EQ(drop.bodies.size(), 1u);
    ASSERT_EQ(drop.units.size(), 1u);
    // 0.5 m of free fall below the cube's bottom face.
    EXPECT_NEAR(drop.bodies[0].position.z() - 0.5 * drop.units[0].size, 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(drop.materials[0].restitution, 0.5);

    const Scene tilt = load_scene((dir / "tilt_cube.toml").string());
    EXPECT_EQ(tilt.analysis, "tilt");
    EXPECT_DOUBLE_EQ(tilt.duration, tilt.tilt_max / tilt.tilt_rate);
    EXPECT_DOUBLE_EQ(tilt.materials[0].friction, 0.5);

    for (const auto &[file, unit, count] :
         {std::tuple<const char *, const char *, int>{"slope_cubes.toml", "cube", 30},
          {"slope_dolosse.toml", "dolos", 20}}) {
        const Scene s = load_scene((dir / file).string());
        EXPECT_EQ(s.analysis, "slope") << file;
        ASSERT_EQ(s.drops.size(), 1u) << file;
        EXPECT_EQ(s.drops[0].count, count) << file;
        EXPECT_EQ(s.units[0].shape, unit) << file;
        const auto slope = std::find_if(s.walls.begin(), s.walls.end(),
                                        [](const armour::SceneWall &w) { return w.type == "slope"; });
        ASSERT_NE(slope, s.walls.end()) << file;
        EXPECT_DOUBLE_EQ(slope->cot, 1.5);
        EXPECT_DOUBLE_EQ(slope->toe_height, 0.1);
    }
}

TEST_F(SceneFile, FluidTableReadsEveryKey) {
    const Scene s = load_scene(write(std::string(kMinimal) + kFluid));
    ASSERT_TRUE(s.fluid.has_value());
    const auto &f = *s.fluid;
    EXPECT_EQ(s.analysis, "buoyancy");
    EXPECT_EQ(f.case_name, "buoyancy_cube");
    EXPECT_DOUBLE_EQ(f.water_level, 0.8);
    EXPECT_EQ(f.cells, (std::array<int, 3>{{12, 10, 8}}));
    EXPECT_EQ(f.cell_size, 0.0);
    EXPECT_DOUBLE_EQ(f.penalty, 2e5);
    EXPECT_EQ(f.mask, "spheres");
    EXPECT_DOUBLE_EQ(f.smoothing_cells, 1.5);
    EXPECT_DOUBLE_EQ(f.added_mass, 0.5);
    EXPECT_EQ(f.np, 2);
    EXPECT_DOUBLE_EQ(f.fluid_density, 1025);
    EXPECT_DOUBLE_EQ(f.air_density, 1.2);
    EXPECT_DOUBLE_EQ(f.viscosity, 1.2e-6);
    EXPECT_DOUBLE_EQ(f.air_viscosity, 1.5e-5);
    EXPECT_DOUBLE_EQ(f.max_courant, 0.4);
    EXPECT_DOUBLE_EQ(f.max_interface_courant, 0.4); // follows max_courant
    EXPECT_DOUBLE_EQ(f.write_interval, 0.5);
    EXPECT_FALSE(load_scene(write(kMinimal)).fluid.has_value());
}

TEST_F(SceneFile, CoupledScenesDefaultToExactHulls) {
    // Without run.engine a dry scene runs clumps, a coupled one exact hulls
    // (where Bullet is built); a given engine is kept.
    const std::string fluid = "[fluid]\nwater_level = 1\ncell_size = 0.5\n";
    EXPECT_EQ(load_scene(write(kMinimal)).engine, "liggghts");
    if (const armour::EngineStyle *exact = armour::find_engine_style([](const armour::EngineCapabilities &c) {
            return c.contacts != armour::ContactKind::none && c.shape == armour::ShapeModel::convex_hulls;
        })) {
        EXPECT_EQ(load_scene(write(std::string(kMinimal) + fluid)).engine, exact->name);
    }
    EXPECT_EQ(load_scene(write(std::string(kMinimal) + "[run]\nengine = \"liggghts\"\n" + fluid)).engine,
              "liggghts");
}

TEST_F(SceneFile, FluidDefaultsAndCellSize) {
    // Domain 10 x 10 x 6 m (the [run] defaults) at 0.5 m cells.
    const Scene s = load_scene(write(std::string(kMinimal) + "[fluid]\nwater_level = 1\ncell_size = 0.5\n"));
    ASSERT_TRUE(s.fluid.has_value());
    const auto &f = *s.fluid;
    EXPECT_EQ(f.case_name, "tank");
    EXPECT_EQ(f.cells, (std::array<int, 3>{{20, 20, 12}}));
    EXPECT_DOUBLE_EQ(f.cell_size, 0.5);
    EXPECT_DOUBLE_EQ(f.penalty, 1e5);
    EXPECT_EQ(f.mask, "exact");
    EXPECT_DOUBLE_EQ(f.smoothing_cells, 1.0);
    EXPECT_DOUBLE_EQ(f.added_mass, 0.0);
    EXPECT_EQ(f.np, 1);
    EXPECT_DOUBLE_EQ(f.fluid_density, 1000.0);
    EXPECT_DOUBLE_EQ(f.air_density, 1.0);
    EXPECT_DOUBLE_EQ(f.viscosity, 1e-6);
    EXPECT_DOUBLE_EQ(f.air_viscosity, 1.48e-5);
    EXPECT_DOUBLE_EQ(f.max_courant, 0.5);
    EXPECT_DOUBLE_EQ(f.max_interface_courant, 0.5);
    EXPECT_DOUBLE_EQ(f.max_time_step, 0.005);
    EXPECT_DOUBLE_EQ(f.write_interval, s.duration);
    const Scene air =
        load_scene(write(std::string(kMinimal) + "[fluid]\nwater_level = 1\ncell_size = 0.5\n"
                                                 "max_courant = 1\nmax_interface_courant = 0.5\n"));
    EXPECT_DOUBLE_EQ(air.fluid->max_courant, 1.0);
    EXPECT_DOUBLE_EQ(air.fluid->max_interface_courant, 0.5);
    // The step floor: a 1 km/s flow through the smallest cell at the smaller
    // Courant limit (0.5 x 0.5 m / 1000 m/s), at most max_time_step / 100.
    EXPECT_DOUBLE_EQ(f.min_time_step, 0.005 / 100.0); // 0.5 x 0.5 m / 1000 m/s = 2.5e-4 s, capped
    EXPECT_DOUBLE_EQ(air.fluid->min_time_step, 0.005 / 100.0);
    const Scene fine = load_scene(
        write(std::string(kMinimal) + "[fluid]\nwater_level = 1\ncell_size = 0.01\nmax_courant = 0.8\n"));
    EXPECT_DOUBLE_EQ(fine.fluid->min_time_step, 0.8 * 0.01 / 1000.0);
    EXPECT_FALSE(f.pressure_tolerance.has_value()); // the template's
    EXPECT_FALSE(f.pressure_relative_tolerance.has_value());
    EXPECT_FALSE(f.momentum_predictor.has_value());
    // Given, the solver settings survive the resolved scene (what the plugin and a resume read).
    const Scene set = load_scene(write(
        std::string(kMinimal) + "[fluid]\nwater_level = 1\ncell_size = 0.5\nmomentum_predictor = false\n"
                                "pressure_tolerance = 2e-6\n"));
    const Scene again = load_scene(write(armour::resolved_scene_toml(set)));
    ASSERT_TRUE(again.fluid->momentum_predictor.has_value());
    EXPECT_FALSE(*again.fluid->momentum_predictor);
    EXPECT_DOUBLE_EQ(again.fluid->pressure_tolerance.value_or(0.0), 2e-6);
    EXPECT_FALSE(again.fluid->pressure_relative_tolerance.has_value());
}

// A write interval the scene left to follow run.duration still follows it in
// a scene written from it (a settle's scene.settled.toml, rerun for longer,
// must not write fields at the short settle run's interval); a given one stays.
TEST_F(SceneFile, WriteIntervalLeftToItsDefaultFollowsTheDurationOfAWrittenScene) {
    const std::string fluid = "[run]\nduration = 2\n[fluid]\nwater_level = 1\ncell_size = 0.5\n";
    const auto longer = [](const std::string &text) {
        return std::regex_replace(text, std::regex("\n(duration *= *)[^\n]*"), "\n$018");
    };
    const Scene followed = load_scene(write(std::string(kMinimal) + fluid));
    EXPECT_DOUBLE_EQ(followed.fluid->write_interval, 2.0);
    const Scene rerun = load_scene(write(longer(armour::resolved_scene_toml(followed))));
    EXPECT_DOUBLE_EQ(rerun.duration, 8.0);
    EXPECT_DOUBLE_EQ(rerun.fluid->write_interval, 8.0);
    const Scene given = load_scene(write(std::string(kMinimal) + fluid + "write_interval = 2\n"));
    const Scene kept = load_scene(write(longer(armour::resolved_scene_toml(given))));
    EXPECT_DOUBLE_EQ(kept.duration, 8.0);
    EXPECT_DOUBLE_EQ(kept.fluid->write_interval, 2.0);
}

// The same for the Courant limit at the free surface (follows max_courant)
// and the smallest step (follows the limits and the cells): a settled scene
// rerun with a lower max_courant and finer cells takes both anew; given, they
// stay.
TEST_F(SceneFile, CourantAndMinimumStepLeftToTheirDefaultsFollowTheLimitsOfAWrittenScene) {
    const std::string fluid = "[fluid]\nwater_level = 1\ncell_size = 0.05\nmax_courant = 0.8\n";
    const auto finer = [](const std::string &text) {
        const std::string slower =
            std::regex_replace(text, std::regex("\n(max_courant *= *)[^\n]*"), "\n$010.2");
        return std::regex_replace(slower, std::regex("\n(cell_size *= *)[^\n]*"), "\n$010.025");
    };
    const Scene followed = load_scene(write(std::string(kMinimal) + fluid));
    EXPECT_DOUBLE_EQ(followed.fluid->max_interface_courant, 0.8);
    const Scene rerun = load_scene(write(finer(armour::resolved_scene_toml(followed))));
    EXPECT_DOUBLE_EQ(rerun.fluid->max_courant, 0.2);
    EXPECT_DOUBLE_EQ(rerun.fluid->max_interface_courant, 0.2);
    // 0.2 x 0.025 m / 1000 m/s, against 0.8 x 0.05 m / 1000 m/s before (both
    // below max_time_step / 100 = 5e-5 s).
    EXPECT_NEAR(followed.fluid->min_time_step, 0.8 * 0.05 / 1000.0, 1e-12);
    EXPECT_NEAR(rerun.fluid->min_time_step, 0.2 * 0.025 / 1000.0, 1e-12);
    const Scene given = load_scene(
        write(std::string(kMinimal) + fluid + "max_interface_courant = 0.1\nmin_time_step = 1e-5\n"));
    const Scene kept = load_scene(write(finer(armour::resolved_scene_toml(given))));
    EXPECT_DOUBLE_EQ(kept.fluid->max_courant, 0.2);
    EXPECT_DOUBLE_EQ(kept.fluid->max_interface_courant, 0.1);
    EXPECT_DOUBLE_EQ(kept.fluid->min_time_step, 1e-5);
}

TEST_F(SceneFile, FluidErrorsNameLineAndKey) {
    const std::string base = std::string(kMinimal) + "[fluid]\n"; // [fluid] on line 14
    const auto at = [&](const std::string &lines) { return write(base + lines); };
    expect_error(at("cells = [4, 4, 4]\n"), 14, "fluid.water_level", "missing required key");
    expect_error(at("water_level = 9\ncells = [4, 4, 4]\n"), 15, "fluid.water_level", "must lie inside");
    expect_error(at("water_level = 1\n"), 14, "fluid.cells", "give cells = [nx, ny, nz] or cell_size");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\ncell_size = 0.1\n"), 17, "fluid.cell_size",
                 "not both");
    expect_error(at("water_level = 1\ncells = [4, 0, 4]\n"), 16, "fluid.cells", "entry 1 is integer 0");
    expect_error(at("water_level = 1\ncells = [4, 4]\n"), 16, "fluid.cells", "got 2 entries");
    expect_error(at("water_level = 1\ncell_size = 20\n"), 16, "fluid.cell_size", "smallest extent");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\nmax_courant = 1.5\n"), 17, "fluid.max_courant",
                 "(0, 1]");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\nmax_interface_courant = 0.6\n"), 17,
                 "fluid.max_interface_courant", "(0, max_courant = 0.5]");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\nmin_time_step = 0.005\n"), 17, "fluid.min_time_step",
                 "(0, max_time_step = 0.005) s");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\nmomentum_predictor = 1\n"), 17,
                 "fluid.momentum_predictor", "");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\npressure_tolerance = 0\n"), 17,
                 "fluid.pressure_tolerance", "(0, 1)");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\npressure_relative_tolerance = 1\n"), 17,
                 "fluid.pressure_relative_tolerance", "(0, 1)");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\npenalty = 0\n"), 17, "fluid.penalty", "> 0");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\nmask = \"clump\"\n"), 17, "fluid.mask",
                 "\"exact\", \"spheres\"");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\nnp = 0\n"), 17, "fluid.np", "integer in [1,");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\nair_density = 2000\n"), 17, "fluid.air_density",
                 "fluid_density");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\nwrite_interval = 2\n"), 17, "fluid.write_interval",
                 "run.duration");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\nmax_time_step = 0.5\n"), 17, "fluid.max_time_step",
                 "run.output_interval");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\ncase = \"../x\"\n"), 17, "fluid.case",
                 "template folder");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\nwaterlevel = 1\n"), 17, "fluid.waterlevel",
                 "did you mean 'water_level'?");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\nsettle_time = -1\n"), 17, "fluid.settle_time",
                 ">= 0 s");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\nsettle_time = 1\nsettle_friction = -0.1\n"), 18,
                 "fluid.settle_friction", ">= 0");
    expect_error(at("water_level = 1\ncells = [4, 4, 4]\nsettle_time = 1\nsettle_density = 0\n"), 18,
                 "fluid.settle_density", "> 0 kg/m^3");
    // Fluid analyses need the fluid.
    const std::string p = write(std::string(kMinimal) + "[analysis]\nkind = \"float\"\n");
    expect_error(p, 15, "analysis.kind", "needs a [fluid] table");
}

TEST_F(SceneFile, FluidRoundTripsAndOverrides) {
    for (const std::string &fluid :
         {std::string(kFluid), std::string("[fluid]\nwater_level = 0.3\ncell_size = 0.07\n"),
          std::string(
              "[fluid]\nwater_level = 0.3\ncell_size = 0.07\nsettle_time = 0.5\nsettle_friction = 0.1\n"
              "settle_density = 2050\n")}) {
        const Scene a = load_scene(write(std::string(kMinimal) + fluid), {"fluid.penalty=3.25e5"});
        EXPECT_DOUBLE_EQ(a.fluid->penalty, 3.25e5);
        const std::string resolved = armour::resolved_scene_toml(a);
        const Scene b = load_scene(write(resolved, "resolved.toml"));
        expect_same(a, b);
    }
    EXPECT_EQ(load_scene(write(kMinimal), {"fluid.water_level=1", "fluid.cells=[2, 2, 2]"}).fluid->cells[0],
              2);
    EXPECT_EQ(load_scene(write(kMinimal), {"run.engine=\"free_body\""}).engine, "free_body");
}

// ---------------------------------------------------------------- the key table

namespace {

const fs::path kSourceDir = fs::path(ARMOUR_SOURCE_DIR);

std::string file_text(const fs::path &p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

// docs/scenes.md's key reference is the table's: regenerate it with
// `build/scene/scene_keys --update docs/scenes.md` when this fails.
TEST(SceneKeyTable, DocsReferenceIsTheTable) {
    const std::string doc = file_text(kSourceDir / "docs" / "scenes.md");
    ASSERT_FALSE(doc.empty());
    EXPECT_EQ(armour::with_generated_key_reference(doc), doc)
        << "docs/scenes.md differs from the key table: run scene_keys --update docs/scenes.md";
    for (const auto &section : armour::scene_sections()) {
        const std::string name = *section.name ? section.name : "top";
        EXPECT_NE(doc.find("<!-- scene-keys " + name + " -->"), std::string::npos) << name << ": no block";
        for (const auto &k : section.keys()) // every key has its row
            EXPECT_NE(doc.find("| `" + k.name + "` | " + k.type + " |"), std::string::npos) << k.dotted;
    }
}

// A key in the table that the reader ignored would accept any value: give
// each a value of the wrong type (a table) and expect it refused under its name.
TEST_F(SceneFile, EveryTableKeyIsRead) {
    const std::vector<std::string> bases = {
        write(std::string(kFull) +
                  "\n[fluid]\nwater_level = 0.5\ncells = [4, 4, 4]\n"
                  "water_box_min = [-1, -1, -1]\nwater_box_max = [0, 0, 0]\n"
                  "refine_min = [0, -3, -1]\nrefine_max = [4, 3, 5]\ncoarse_cell_size = [2, 0, 0]\n",
              "cells.toml"),
        write(std::string(kFull) + "\n[fluid]\nwater_level = 0.5\ncell_size = 0.5\n", "cell_size.toml"),
        write(std::string(kFull) +
                  "\n[fluid]\nwater_level = 0.5\ncell_size = 0.5\n[waves]\ntype = \"regular\"\n"
                  "height = 0.1\nperiod = 1.6\n[[porous]]\nname = \"core\"\nmin = [0, 0, -1]\n"
                  "max = [1, 1, 0]\nstone_size = 0.02\n[[porous]]\nname = \"underlayer\"\n"
                  "type = \"slope_layer\"\nwall = \"slope\"\nthickness = 0.1\nstone_size = 0.02\n"
                  "[[refine]]\nname = \"front\"\nmin = [0, 0, -1]\nmax = [1, 1, 0]\n[[refine]]\n"
                  "name = \"armour\"\ntype = \"slope_band\"\nwall = \"slope\"\nabove = 0.1\n",
              "waves.toml"),

        // A test series: irregular waves and the damage analysis.
        write(replaced(kFull, "kind = \"tilt\"\ntilt_rate = 5\ntilt_max = 45.5", "kind = \"damage\"") +
                  "\n[fluid]\nwater_level = 0.5\ncell_size = 0.5\n[waves]\ntype = \"irregular\"\nHs = 0.1\n"
                  "Tp = 1.6\ngauge_x = -1.5\n[[series]]\nHs = 0.1\nTp = 1.6\n",
              "series.toml")};
    for (const auto &base : bases)
        ASSERT_EQ(error_of(base), "") << base;
    // kFull's entries by shape and wall type.
    const std::map<std::string, int> variant_index = {{"cube", 0},  {"dolos", 1}, {"stl", 2},
                                                      {"plane", 0}, {"slope", 1}, {"box", 2}};
    int keys = 0;
    for (const auto &section : armour::scene_sections())
        for (const auto &k : section.keys()) {
            std::string path = k.name;
            if (section.kind == armour::SectionKind::Table)
                path = k.section + "." + k.name;
            if (section.kind == armour::SectionKind::ArrayOfTables) {
                const bool regions = k.section == "porous" || k.section == "refine";
                int index = k.when.empty() || regions ? 0 : variant_index.at(k.when);
                if (k.section == "wall" && k.when == "stl")
                    index = 3;
                if (k.section == "porous" && k.when == "slope_layer") // the second is a slope_layer
                    index = 1;
                if (k.section == "refine" && k.when == "slope_band") // the second is a slope_band
                    index = 1;
                path = k.section + "." + std::to_string(index) + "." + k.name;
            }
            bool refused = false;
            std::string errors;
            for (const auto &base : bases) {
                const std::string e = error_of(base, {path + "={}"});
                refused = refused || (e.rfind("--set: key '" + path + "': ", 0) == 0 &&
                                      e.find("(got a table)") != std::string::npos);
                errors += "\n  " + e;
            }
            EXPECT_TRUE(refused) << path << " was not read:" << errors;
            ++keys;
        }
    EXPECT_GT(keys, 80);
}

TEST(SceneKeyTable, KeysAreUniqueAndDocumented) {
    for (const auto &section : armour::scene_sections()) {
        std::set<std::pair<std::string, std::string>> seen;
        for (const auto &k : section.keys()) {
            EXPECT_TRUE(seen.insert({k.name, k.when}).second) << k.dotted << " declared twice";
            EXPECT_FALSE(k.doc.empty()) << k.dotted;
            EXPECT_FALSE(k.type.empty()) << k.dotted;
        }
    }
    // The defaults live in the scene structs; the table reports them.
    const auto run = armour::find_section("run")->keys();
    const auto gravity =
        std::find_if(run.begin(), run.end(), [](const auto &k) { return k.name == "gravity"; });
    ASSERT_NE(gravity, run.end());
    EXPECT_EQ(gravity->default_text, "[0, 0, -9.81]");
    EXPECT_EQ(gravity->unit, "m/s^2");
}

// The issue's example: a misspelt key is refused naming file, line and key.
TEST_F(SceneFile, MisspeltKeyNamesFileLineAndKey) {
    const std::string p = write(std::string(kMinimal) + "\n[run]\nduration = 2\nduraton = 3\n");
    expect_error(p, 17, "run.duraton", "unknown key (did you mean 'duration'?)");
    const std::string e = error_of(p);
    EXPECT_EQ(e, p + ":17: key 'run.duraton': unknown key (did you mean 'duration'?)");
}

// Every shipped example loads, and its resolved scene reloads to the same scene.
TEST_F(SceneFile, EveryShippedSceneParses) {
    int scenes = 0;
    for (const auto &entry : fs::directory_iterator(kSourceDir / "scenes")) {
        if (entry.path().extension() != ".toml")
            continue;
        ++scenes;
        SCOPED_TRACE(entry.path().filename().string());
        Scene a;
        ASSERT_NO_THROW(a = load_scene(entry.path().string()));
        const Scene b = load_scene(write(armour::resolved_scene_toml(a), "resolved.toml"));
        expect_same(a, b);
    }
    EXPECT_GE(scenes, 13);
}

// [waves]: a wave the chosen theory does not describe, one that breaks at
// the inlet, an odd number of components and gauges outside the flume are
// refused, each naming its key (docs/waves.md).
TEST_F(SceneFile, WavesOutsideTheirLimitsAreRefusedNamingTheKey) {
    // kFull: domain x -2 .. 4 m, z from -1 m; water_level 0.5 m: depth h = 1.5 m.
    const std::string fluid = std::string(kFull) + "\n[fluid]\nwater_level = 0.5\ncell_size = 0.5\n";
    const std::string regular = fluid + "[waves]\ntype = \"regular\"\nheight = 0.1\nperiod = 1.6\n";
    const std::string p = write(regular);
    ASSERT_EQ(error_of(p), "");
    EXPECT_EQ(load_scene(p).waves->theory, "StokesV"); // H / L0 = 0.025
    EXPECT_NE(error_of(p, {"waves.height=1.2"}).find("key 'waves.height': H / h = 0.8 > 0.78"),
              std::string::npos)
        << error_of(p, {"waves.height=1.2"});
    EXPECT_NE(error_of(p, {"waves.height=0.6", "waves.period=1.2"}).find("key 'waves.height': H = 0.6 m > "),
              std::string::npos);
    // T = 12 s in 1.5 m: L = 45 m, Ursell 60 with H = 0.1 m.
    const std::string ursell =
        error_of(p, {"waves.period=12", "waves.theory=\"StokesII\"", "run.domain_max=[90, 3, 5]"});
    EXPECT_NE(ursell.find("key 'waves.theory': Ursell number"), std::string::npos) << ursell;
    EXPECT_EQ(error_of(p, {"waves.period=12", "run.domain_max=[90, 3, 5]"}), ""); // auto: cnoidal
    const std::string irregular =
        error_of(p, {"waves.type=\"irregular\"", "waves.Hs=0.1", "waves.Tp=1.6", "waves.components=41"});
    EXPECT_NE(irregular.find("key 'waves.components': must be even (got 41)"), std::string::npos)
        << irregular;
    EXPECT_NE(error_of(p, {"waves.type=\"irregular\"", "waves.Hs=0.7", "waves.Tp=1.6"})
                  .find("key 'waves.Hs': 1.8 Hs"),
              std::string::npos);
    EXPECT_NE(
        error_of(p, {"waves.type=\"irregular\"", "waves.Hs=0.1", "waves.Tp=1.6", "waves.components=202"})
            .find("key 'waves.components': must be in [4, 200]"),
        std::string::npos);
    EXPECT_NE(error_of(p, {"waves.gauge_x=3.5"}).find("key 'waves.gauge_x': the gauge array"),
              std::string::npos);
    EXPECT_NE(error_of(p, {"waves.gauge_x=-2"}).find("key 'waves.gauge_x': the gauge array"),
              std::string::npos);
    // Extra gauges: anywhere inside the flume, a few, numbers; kept in the resolved scene.
    const Scene extra = load_scene(p, {"waves.extra_gauges=[1.5, 2.25]"});
    EXPECT_EQ(extra.waves->extra_gauges, (std::vector<double>{1.5, 2.25}));
    EXPECT_EQ(load_scene(write(armour::resolved_scene_toml(extra), "extra.toml")).waves->extra_gauges,
              extra.waves->extra_gauges);
    EXPECT_TRUE(load_scene(p).waves->extra_gauges.empty());
    for (const char *bad : {"[-2.5]", "[4]"}) // the flume: x -2 .. 4 m
        EXPECT_NE(error_of(p, {std::string("waves.extra_gauges=") + bad})
                      .find("key 'waves.extra_gauges': each gauge must lie inside the flume"),
                  std::string::npos)
            << bad;
    EXPECT_NE(error_of(p, {"waves.extra_gauges=[1, \"2\"]"})
                  .find("key 'waves.extra_gauges': must be an array of numbers in m (entry 1 is string"),
              std::string::npos);
    EXPECT_NE(error_of(p, {"waves.extra_gauges=[1, 1, 1, 1, 1, 1, 1, 1, 1]"})
                  .find("key 'waves.extra_gauges': at most 8 gauges (got 9)"),
              std::string::npos);
    EXPECT_NE(error_of(p, {"waves.extra_gauges=abc"})
                  .find("key 'waves.extra_gauges' takes an array of numbers, and abc is not one"),
              std::string::npos)
        << error_of(p, {"waves.extra_gauges=abc"});
    // Each theory's own limit, named: cnoidal in deep water, StokesII where
    // v1912's wavelength iteration has not converged, stream function (no
    // solver for Fenton's coefficients), an irregular train too long for it.
    const std::string cnoidal = error_of(p, {"waves.theory=\"cnoidal\""});
    EXPECT_NE(cnoidal.find("key 'waves.theory': cnoidal theory needs shallow water"), std::string::npos)
        << cnoidal;
    const std::string slow = error_of(p, {"waves.period=30", "waves.height=0.001",
                                          "waves.theory=\"StokesII\"", "run.domain_max=[900, 3, 5]"});
    EXPECT_NE(slow.find("key 'waves.theory': kh = 0.0"), std::string::npos) << slow;
    EXPECT_NE(error_of(p, {"waves.theory=\"streamFunction\""})
                  .find("key 'waves.theory': theory \"streamFunction\""),
              std::string::npos);
    const std::string long_tp = error_of(p, {"waves.type=\"irregular\"", "waves.Hs=0.1", "waves.Tp=20"});
    EXPECT_NE(long_tp.find("key 'waves.Tp': the longest component"), std::string::npos) << long_tp;
    EXPECT_NE(error_of(p, {"waves.type=\"irregular\""}).find("key 'waves.Hs': missing required key"),
              std::string::npos);
    // [waves] needs a coupled run.
    const std::string dry =
        write(std::string(kFull) + "\n[waves]\ntype = \"regular\"\nheight = 0.1\nperiod = 1.6\n", "dry.toml");
    EXPECT_NE(error_of(dry).find("key 'waves.type': [waves] makes waves in a coupled run"), std::string::npos)
        << error_of(dry);
}

// The graded mesh's z band must hold the largest wave's crest and trough,
// except at the domain's top or floor (no coarse cells beyond). On the
// shipped stability scene (band 0.18 .. 0.62 m, the domain's top; still
// water 0.40 m): Hs 0.12 m reaches 0.184 m, Hs 0.15 m 0.13 m. The scene is
// refused when it is read, so a sweep's plan refuses such a case too.
TEST_F(SceneFile, SurfaceBandOfAGradedMeshHoldsTheLargestWave) {
    const std::string scene = (kSourceDir / "scenes" / "stability_cubes.toml").string();
    ASSERT_EQ(error_of(scene), "");
    const std::string high = error_of(scene, {"waves.Hs=0.15"});
    EXPECT_NE(high.find("key 'fluid.refine_min': the refined box's z range 0.18 .. 0.62 m must hold the free "
                        "surface 0.4 m +- the wave height 0.27 m (1.8 Hs)"),
              std::string::npos)
        << high;
    // The crest 0.67 m stands above the domain's top: the band reaches it.
    EXPECT_EQ(error_of(scene, {"waves.Hs=0.15", "fluid.refine_min=[1.15, -0.124, 0.13]"}), "");
    const std::string low_top = error_of(scene, {"fluid.refine_max=[2.0, 0.124, 0.6]"});
    EXPECT_NE(low_top.find("key 'fluid.refine_max': the refined box's z range 0.18 .. 0.6 m must hold"),
              std::string::npos)
        << low_top;
    // Not graded in z: the band may be anything.
    EXPECT_EQ(error_of(scene, {"waves.Hs=0.15", "fluid.coarse_cell_size=[0.05, 0.0, 0.0]"}), "");
}
