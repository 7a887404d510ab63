// The `armour` command line: results on good input; one error line, a
// non-zero exit and no output directory on bad input.
#include "cli.h"
#include "engine_registry.h"
#include "mesh.h"
#include "output_folder.h"
#include "output_folder_rule.h"
#include "shapes.h"
#include "stl_io.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace {

class Cli : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("armour_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    // Runs `armour args...`, returns the exit code and keeps stderr.
    int run(std::vector<std::string> args) {
        const output_rule::Outcome o = output_rule::armour(std::move(args));
        err_ = o.err;
        return o.code;
    }

    // Bad input: exit 2, exactly one line naming `what`, and nothing left in dir_.
    void expect_rejected(std::vector<std::string> args, const std::string &what) {
        const std::string out = (dir_ / "out").string();
        args.push_back("--out");
        args.push_back(out);
        EXPECT_EQ(run(args), 2) << err_;
        EXPECT_NE(err_.find(what), std::string::npos) << err_;
        // Progress lines may precede it; the error is one line, the last.
        const std::size_t at = err_.find("armour: error: ");
        ASSERT_NE(at, std::string::npos) << err_;
        EXPECT_TRUE(at == 0 || err_[at - 1] == '\n') << err_;
        EXPECT_EQ(err_.find('\n', at), err_.size() - 1) << err_;
        for (const auto &entry : fs::directory_iterator(dir_))
            EXPECT_NE(entry.path().filename().string().rfind("out", 0), 0u)
                << "left behind: " << entry.path();
    }

    fs::path dir_;
    std::string err_;
};

nlohmann::json read_json(const fs::path &path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

} // namespace

TEST_F(Cli, ClumpWritesEveryFileWithConsistentSummary) {
    const fs::path out = dir_ / "cube";
    ASSERT_EQ(run({"clump", "--shape", "cube", "--size", "0.5", "--spheres", "12", "--out", out.string()}), 0)
        << err_;
    for (const char *name : {"summary.json", "clump.spheres", "template.liggghts", "shape.stl", "clump.stl"})
        EXPECT_TRUE(fs::exists(out / name)) << name;
    const auto s = read_json(out / "summary.json");
    for (const char *key : {"spheres", "volume_error", "surface_rms", "surface_max", "inertia_error",
                            "centroid_offset", "build_seconds", "Dn", "volume_exact", "method"})
        EXPECT_TRUE(s.contains(key)) << key;
    EXPECT_EQ(s["spheres"], 12);
    EXPECT_EQ(s["method"], "optimised");
    EXPECT_NEAR(s["volume_exact"].get<double>(), 0.125, 1e-12);
    EXPECT_NEAR(s["Dn"].get<double>(), 0.5, 1e-12);
    EXPECT_NEAR(s["mass"].get<double>(), 0.125 * 2400.0, 1e-9);
    // The exact shape file is the cube itself, centred on its centroid.
    const armour::TriangleMesh shape = armour::read_stl((out / "shape.stl").string());
    EXPECT_NEAR(armour::signed_volume(shape), 0.125, 1e-6);
    int lines = 0;
    std::ifstream spheres(out / "clump.spheres");
    for (std::string line; std::getline(spheres, line);)
        lines += !line.empty() && line[0] != '#';
    EXPECT_EQ(lines, 12);
}

TEST_F(Cli, ToleranceModeRecordsTheSearch) {
    const fs::path out = dir_ / "dolos";
    ASSERT_EQ(run({"clump", "--shape", "dolos", "--height", "1.5", "--tol-volume", "0.02", "--tol-surface",
                   "0.03", "--out", out.string()}),
              0)
        << err_;
    const auto s = read_json(out / "summary.json");
    EXPECT_LE(std::abs(s["volume_error"].get<double>()), 0.02);
    EXPECT_LE(s["surface_rms"].get<double>(), 0.03);
    EXPECT_TRUE(s["tolerance"]["met"].get<bool>());
    EXPECT_GE(s["tolerance"]["tried"].size(), 2u);
    // The topple tolerance applies with its default, 1 degree.
    EXPECT_EQ(s["tolerance"]["topple_deg"].get<double>(), 1.0);
    EXPECT_LE(s["topple_error_deg"].get<double>(), 1.0);
    for (const auto &tried : s["tolerance"]["tried"])
        EXPECT_TRUE(tried["topple_error_deg"].is_number());
}

TEST_F(Cli, StlInputIsCentredAndMeasured) {
    // A cube off the origin: the unit frame puts its centroid at the origin.
    armour::TriangleMesh mesh = armour::translated(armour::make_cube_mesh(2.0), Eigen::Vector3d(5, 6, 7));
    const fs::path stl = dir_ / "block.stl";
    armour::write_stl(mesh, stl.string(), false);
    const fs::path out = dir_ / "block";
    ASSERT_EQ(run({"clump", "--stl", stl.string(), "--spheres", "5", "--out", out.string()}), 0) << err_;
    const auto s = read_json(out / "summary.json");
    EXPECT_NEAR(s["volume_exact"].get<double>(), 8.0, 1e-9);
    const armour::TriangleMesh centred = armour::read_stl((out / "shape.stl").string());
    Eigen::Vector3d lower = Eigen::Vector3d::Constant(1e9);
    for (const auto &v : centred.vertices)
        lower = lower.cwiseMin(v);
    EXPECT_NEAR((lower - Eigen::Vector3d(-1, -1, -1)).norm(), 0.0, 1e-6);
}

TEST_F(Cli, RejectsBadShapeArguments) {
    expect_rejected({"clump", "--shape", "tetrapod", "--size", "1", "--spheres", "5"}, "--shape");
    expect_rejected({"clump", "--shape", "cube", "--size", "-1", "--spheres", "5"}, "--size");
    expect_rejected({"clump", "--shape", "cube", "--size", "0", "--spheres", "5"}, "--size");
    expect_rejected({"clump", "--shape", "dolos", "--height", "0", "--spheres", "5"}, "--height");
    expect_rejected({"clump", "--shape", "dolos", "--height", "2", "--waist", "0.6", "--spheres", "5"},
                    "--waist");
    expect_rejected({"clump", "--shape", "dolos", "--height", "2", "--waist", "0.2", "--spheres", "5"},
                    "--waist");
    expect_rejected({"clump", "--shape", "cube", "--size", "1", "--spheres", "0"}, "--spheres");
    expect_rejected({"clump", "--shape", "cube", "--size", "1", "--spheres", "-3"}, "--spheres");
    expect_rejected({"clump", "--shape", "cube", "--size", "1", "--density", "0", "--spheres", "3"},
                    "--density");
    expect_rejected({"clump", "--shape", "cube", "--size", "1", "--method", "magic", "--spheres", "3"},
                    "--method");
    expect_rejected({"clump", "--spheres", "3"}, "--shape");
}

TEST_F(Cli, RejectsBadStlFiles) {
    expect_rejected({"clump", "--stl", (dir_ / "missing.stl").string(), "--spheres", "5"}, "missing.stl");
    armour::TriangleMesh open = armour::make_cube_mesh(1.0);
    open.triangles.pop_back();
    const fs::path open_stl = dir_ / "open.stl";
    armour::write_stl(open, open_stl.string());
    expect_rejected({"clump", "--stl", open_stl.string(), "--spheres", "5"}, "open.stl");
    const fs::path junk = dir_ / "junk.stl";
    std::ofstream(junk) << "solid junk\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0\n";
    expect_rejected({"clump", "--stl", junk.string(), "--spheres", "5"}, "junk.stl");
}

TEST_F(Cli, RejectsImpossibleTolerances) {
    expect_rejected({"clump", "--shape", "cube", "--size", "1", "--tol-volume", "0", "--tol-surface", "0.02"},
                    "--tol-volume");
    expect_rejected(
        {"clump", "--shape", "cube", "--size", "1", "--tol-volume", "0.01", "--tol-surface", "-0.1"},
        "--tol-surface");
    expect_rejected({"clump", "--shape", "cube", "--size", "1", "--tol-topple", "0"}, "--tol-topple");
    expect_rejected({"clump", "--shape", "cube", "--size", "1", "--tol-topple", "95"}, "--tol-topple");
    // Reachable in principle, not with 6 spheres: the search says how close it got.
    expect_rejected({"clump", "--shape", "cube", "--size", "1", "--tol-volume", "0.01", "--tol-surface",
                     "0.001", "--max-spheres", "6"},
                    "cannot be met with at most 6 spheres");
}

TEST_F(Cli, RejectsEdgeSpheresItCannotBuild) {
    // Edge spheres are a layout of a fixed count: without --spheres, with too
    // few for them (a cube's 12 edges x 7 + 8 corners + 8 body spheres =
    // 100), negative, or for the greedy clump, nothing is built.
    expect_rejected({"clump", "--shape", "cube", "--size", "1", "--edge-spheres", "3"}, "--spheres");
    expect_rejected({"clump", "--shape", "cube", "--size", "1", "--spheres", "99", "--edge-spheres", "7"},
                    "at least 100");
    expect_rejected({"clump", "--shape", "cube", "--size", "1", "--spheres", "99", "--edge-spheres", "-1"},
                    "--edge-spheres");
    expect_rejected({"clump", "--shape", "cube", "--size", "1", "--spheres", "99", "--edge-spheres", "1",
                     "--method", "greedy"},
                    "greedy");
}

TEST_F(Cli, HelpStatesUnits) {
    ::testing::internal::CaptureStdout();
    const std::vector<const char *> argv = {"armour", "clump", "--help"};
    EXPECT_EQ(armour::armour_main(3, argv.data()), 0);
    const std::string help = ::testing::internal::GetCapturedStdout();
    for (const char *needle : {"--size", "[m]", "--density", "[kg/m^3]", "--tol-surface", "of Dn"})
        EXPECT_NE(help.find(needle), std::string::npos) << needle;
}

TEST_F(Cli, ReplacesAnEarlierResultWhole) {
    const fs::path out = dir_ / "again";
    ASSERT_EQ(run({"clump", "--shape", "cube", "--size", "1", "--spheres", "4", "--out", out.string()}), 0);
    ASSERT_EQ(run({"clump", "--shape", "cube", "--size", "1", "--spheres", "6", "--out", out.string()}), 0);
    EXPECT_EQ(read_json(out / "summary.json")["spheres"], 6);
    // A failing run leaves the earlier result untouched.
    EXPECT_EQ(run({"clump", "--shape", "cube", "--size", "-1", "--spheres", "6", "--out", out.string()}), 2);
    EXPECT_EQ(read_json(out / "summary.json")["spheres"], 6);
    int entries = 0;
    for ([[maybe_unused]] const auto &entry : fs::directory_iterator(dir_))
        ++entries;
    EXPECT_EQ(entries, 1); // no staging or backup directories left
}

TEST_F(Cli, ClumpKeepsTheUsersFiles) {
    output_rule::check(
        dir_, "armour clump",
        [](const std::string &out, int variant) {
            return output_rule::armour({"clump", "--shape", "cube", "--size", "1", "--spheres",
                                        variant == 0 ? "4" : "6", "--out", out});
        },
        [](const nlohmann::json &s) { return s["spheres"] == 6 ? 1 : 0; });
}

TEST_F(Cli, ClumpRefusesTheFolderHoldingItsStl) {
    const fs::path stl = dir_ / "block.stl";
    armour::write_stl(armour::make_cube_mesh(1.0), stl.string(), false);
    const std::string before = output_rule::read(stl);
    EXPECT_EQ(run({"clump", "--stl", stl.string(), "--spheres", "4", "--out", dir_.string()}), 2) << err_;
    EXPECT_NE(err_.find("holds 'block.stl'"), std::string::npos) << err_;
    EXPECT_EQ(output_rule::names(dir_), std::set<std::string>{"block.stl"});
    EXPECT_EQ(output_rule::read(stl), before);
}

TEST_F(Cli, AnotherCommandsResultIsRefused) {
    const fs::path out = dir_ / "cube";
    ASSERT_EQ(run({"clump", "--shape", "cube", "--size", "1", "--spheres", "4", "--out", out.string()}), 0);
    const auto before = output_rule::names(out);
    EXPECT_EQ(run({"demo", "--tol-volume", "0.3", "--tol-surface", "0.3", "--out", out.string()}), 2);
    EXPECT_NE(err_.find("it is a result of 'armour clump'"), std::string::npos) << err_;
    EXPECT_EQ(output_rule::names(out), before);
}

TEST_F(Cli, DemoKeepsTheUsersFiles) {
    output_rule::check(
        dir_, "armour demo",
        [](const std::string &out, int variant) {
            return output_rule::armour({"demo", "--tol-volume", variant == 0 ? "0.3" : "0.25",
                                        "--tol-surface", "0.3", "--out", out});
        },
        [](const nlohmann::json &s) { return s["tolerance"]["volume"] == 0.25 ? 1 : 0; });
}

// The folder rule's corners, on OutputFolder itself.
TEST_F(Cli, OutputFolderReplacesWhatAKilledRunLeft) {
    // A run killed after claiming summary.json but before writing it, and a
    // staged command killed mid-way (its hidden staging folder, a marker copy).
    const fs::path out = dir_ / "killed";
    fs::create_directories(out / ".armour-partial-4242");
    std::ofstream(out / ".armour-output") << "armour run\nbodies.h5\nsummary.json\n";
    std::ofstream(out / ".armour-output.tmp") << "armour run\n";
    std::ofstream(out / "bodies.h5") << "partial";
    std::ofstream(out / ".armour-lock") << "4242\n"; // its lock went with it
    {
        armour::OutputFolder folder(out, "armour run", armour::OutputFolder::Mode::streaming);
        folder.open();
        // The lock file is ours again while the folder is held.
        EXPECT_EQ(output_rule::names(out), (std::set<std::string>{".armour-lock", ".armour-output"}));
        EXPECT_EQ(output_rule::read(out / ".armour-lock"), std::to_string(::getpid()) + "\n");
        EXPECT_EQ(output_rule::read(out / ".armour-output"), "armour run\n");
        armour::write_text_file(folder.claim("summary.json"), "{}\n");
        EXPECT_EQ(output_rule::read(out / ".armour-output"), "armour run\nsummary.json\n");
    }
    EXPECT_EQ(output_rule::names(out), (std::set<std::string>{".armour-output", "summary.json"}));
}

TEST_F(Cli, OutputFolderMarkerNeverReachesOutside) {
    const fs::path out = dir_ / "result";
    fs::create_directories(out);
    std::ofstream(dir_ / "keep.txt") << "mine";
    std::ofstream(out / ".armour-output") << "armour run\n../keep.txt\n..\n.\n/\n";
    armour::OutputFolder folder(out, "armour run", armour::OutputFolder::Mode::streaming);
    folder.open();
    EXPECT_EQ(output_rule::read(dir_ / "keep.txt"), "mine");
    EXPECT_TRUE(fs::is_directory(out));
}

TEST_F(Cli, OutputFolderLooksLikeOursIsNotOurs) {
    // Only .armour-partial-<digits> is a leftover of ours; a look-alike is the user's.
    const fs::path out = dir_ / "result";
    fs::create_directories(out);
    std::ofstream(out / ".armour-partial-notes") << "mine";
    EXPECT_THROW(armour::OutputFolder(out, "armour clump", armour::OutputFolder::Mode::staged),
                 armour::InputError);
    EXPECT_EQ(output_rule::read(out / ".armour-partial-notes"), "mine");
}

TEST_F(Cli, OutputFolderUncommittedLeavesTheEarlierResult) {
    const fs::path out = dir_ / "cube";
    ASSERT_EQ(run({"clump", "--shape", "cube", "--size", "1", "--spheres", "4", "--out", out.string()}), 0);
    const auto before = output_rule::names(out);
    const std::string summary = output_rule::read(out / "summary.json");
    {
        armour::OutputFolder folder(out, "armour clump", armour::OutputFolder::Mode::staged);
        folder.open();
        armour::write_text_file(folder.claim("summary.json"), "{}\n");
        armour::write_text_file(folder.claim("extra.txt"), "x\n");
    } // a command that fails before commit()
    EXPECT_EQ(output_rule::names(out), before);
    EXPECT_EQ(output_rule::read(out / "summary.json"), summary);
}

// `armour engines`: one line per registered style, name first, with its
// capabilities; an engine a scene cannot have is refused by name.
TEST_F(Cli, EnginesListsEveryRegisteredStyleWithItsCapabilities) {
    ::testing::internal::CaptureStdout();
    const int code = run({"engines"});
    const std::string out = ::testing::internal::GetCapturedStdout();
    ASSERT_EQ(code, 0) << err_;
    std::istringstream lines(out);
    std::string line;
    std::size_t n = 0;
    while (std::getline(lines, line)) {
        const std::string &name = armour::engine_styles().at(n).name;
        EXPECT_EQ(line.rfind(name + ": contacts=", 0), 0u) << line;
        for (const char *field : {" shape=", " parallel=", " pivot=", " restart="})
            EXPECT_NE(line.find(field), std::string::npos) << line;
        ++n;
    }
    EXPECT_EQ(n, armour::engine_styles().size());
    EXPECT_NE(out.find("free_body: contacts=none"), std::string::npos) << out;
}

// A bad command line, CLI11's own errors included, is refused like bad input:
// exit status 2, stderr exactly one line `armour: error: ` naming the option
// (or argument) and the reason, nothing written.
TEST_F(Cli, CommandLineErrorsAreOneLineAndExitTwo) {
    const std::string out = (dir_ / "out").string(), scene = (dir_ / "scene.toml").string();
    std::ofstream(scene) << "name = \"s\"\n[[material]]\nname = \"m\"\n[[unit]]\nname = \"u\"\nshape = "
                            "\"cube\"\nsize = 0.2\n[[body]]\nunit = \"u\"\nposition = [0, 0, 1]\n";
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"clump", "--shape", "cube", "--size", "1", "--spheres", "abc", "--out", out},
         "--spheres: 'abc' is not an integer"},
        {{"clump", "--shape", "cube", "--size", "1", "--spheres", "2.5", "--out", out},
         "--spheres: '2.5' is not an integer"},
        {{"clump", "--shape", "cube", "--size", "big", "--spheres", "3", "--out", out},
         "--size: 'big' is not a number"},
        {{"clump", "--shape", "cube", "--size", "inf", "--spheres", "3", "--out", out},
         "--size: 'inf' is not a finite number"},
        {{"clump", "--shape", "cube", "--size", "1", "--seed", "-1", "--out", out},
         "--seed: '-1' is not an integer >= 0"},
        {{"clump", "--shape", "cube", "--size", "1", "--bogus", "--out", out}, "--bogus: unknown option"},
        {{"clump", "--shape", "cube", "--size", "1", "--spheres", "3"}, "--out is required"},
        {{"clump", "--shape", "cube", "--size", "1", "--out"}, "--out: needs a value"},
        {{"clump", "--stl", scene, "--size", "1", "--out", out}, "--stl excludes --size"},
        {{"clump", "--shape", "cube", "--size", "1", "--waist", "0.3", "--out", out}, "--waist: applies to"},
        {{}, "a command is required, one of: clump, demo, run"},
        {{"frobnicate"}, "'frobnicate' is not a command"},
        {{"--bogus"}, "--bogus: unknown option (armour --help lists them)"},
        {{"run", scene, "extra.toml", "--out", out}, "'extra.toml': unexpected argument"},
        {{"run", scene, "--out", out, "--np", "0"}, "--np: must be >= 1 (got 0)"},
        {{"run", scene, "--out", out, "--np", "two"}, "--np: 'two' is not an integer"},
        {{"run", scene, "--out", out, "--set", "run.duration=abc"},
         "--set 'run.duration=abc': key 'run.duration' takes a number"},
        {{"report", dir_.string(), "--out", out, "--until", "0"}, "--until: must be > 0 s (got 0)"},
        {{"report", dir_.string(), "--out", out, "--until", "nan"}, "--until: 'nan' is not a finite number"},
        {{"compare", scene, "--out", out, "--spheres", "5,x"}, "--spheres: 'x' is not an integer"},
        {{"compare", scene, "--out", out, "--dt-sweep-spheres", "-3"}, "--dt-sweep-spheres: must be >= 2"},
        {{"sweep", scene, "--out", out, "--jobs", "0"}, "--jobs: must be >= 1 (got 0)"},
        {{"sweep", scene, "--out", out, "--jobs", "-2"}, "--jobs: must be >= 1 (got -2)"},
        {{"sweep", scene, "--out", out, "--executor", "slurm", "--jobs", "2"},
         "--jobs: only with --executor local"},
    };
    for (const auto &[args, what] : cases) {
        std::string command = "armour";
        for (const auto &a : args)
            command += " " + a;
        EXPECT_EQ(run(args), 2) << command << "\n" << err_;
        EXPECT_EQ(err_.rfind("armour: error: ", 0), 0u) << command << "\n" << err_;
        EXPECT_EQ(err_.find('\n'), err_.size() - 1) << command << "\n" << err_;
        EXPECT_NE(err_.find(what), std::string::npos) << command << "\n" << err_ << "expected: " << what;
        EXPECT_FALSE(fs::exists(out)) << command;
    }
}

// --help and -h print help on stdout and exit 0, for the command and each subcommand.
TEST_F(Cli, HelpExitsZero) {
    for (const std::vector<std::string> &args : {std::vector<std::string>{"--help"},
                                                 {"-h"},
                                                 {"run", "--help"},
                                                 {"sweep", "-h"},
                                                 {"compare", "--help"}}) {
        ::testing::internal::CaptureStdout();
        const int code = run(args);
        const std::string help = ::testing::internal::GetCapturedStdout();
        EXPECT_EQ(code, 0) << args.front() << "\n" << err_;
        EXPECT_TRUE(err_.empty()) << err_;
        EXPECT_NE(help.find("--help"), std::string::npos) << help;
    }
}

// The help states each option's range as its check applies it: --jobs >= 1
// and --jobs 1 accepted, one --tol-topple range for clump and demo.
TEST_F(Cli, HelpAndChecksAgree) {
    const auto help_of = [&](const std::string &command) {
        ::testing::internal::CaptureStdout();
        EXPECT_EQ(run({command, "--help"}), 0);
        return ::testing::internal::GetCapturedStdout();
    };
    EXPECT_NE(help_of("sweep").find("--jobs INT:>=1"), std::string::npos) << help_of("sweep");
    for (const std::string command : {"clump", "demo"}) {
        const std::string help = help_of(command);
        EXPECT_NE(help.find("on, in (0, 90) [deg]"), std::string::npos) << help;
        std::vector<std::string> args = {command, "--tol-topple", "90", "--out", (dir_ / "out").string()};
        if (command == "clump")
            args.insert(args.begin() + 1, {"--shape", "cube", "--size", "1"});
        EXPECT_EQ(run(args), 2) << command;
        EXPECT_EQ(err_,
                  "armour: error: --tol-topple: must be an angle in (0, 90) degrees, e.g. 1 (got 90)\n");
    }
    // --jobs 1 passes the command line: the sweep file is what is refused.
    const std::string missing = (dir_ / "missing.toml").string();
    EXPECT_EQ(run({"sweep", missing, "--out", (dir_ / "s").string(), "--jobs", "1"}), 2);
    EXPECT_EQ(err_.find("--jobs"), std::string::npos) << err_;
    EXPECT_NE(err_.find("missing.toml"), std::string::npos) << err_;
}
