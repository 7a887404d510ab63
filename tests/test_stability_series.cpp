// A test series ([[series]], docs/stability.md "Test series") and the
// settled layer's check against the Rock Manual, through `armour run` on the
// shipped stability scene made CI-sized as test_stability.cpp makes it (5
// rows, 45 cubes, 4 cm mesh): two steps of 2 s. Needs Debian's openfoam.
// ~4-5 min on the shared 2-core machine in all.
#include "bodies_file.h"
#include "process_wait.h"
#include "series_damage.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <sys/file.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr double kDn = 0.04; // m, the scene's cube

const std::vector<std::string> kSmall = {"pattern.0.rows=5", "fluid.settle_stages=5", "fluid.cells=[50,6,16]",
                                         "fluid.penalty=200"};

// Two steps of rising waves, 2 s each (ramped over half a period: the
// waves reach the toe at ~1 s), the second with its own period and seed.
const char *kSteps = R"(
[[series]]
Hs = 0.10
Tp = 1.8
ramp_time = 0.9
duration = 2.0

[[series]]
Hs = 0.12
Tp = 1.6
seed = 2
ramp_time = 0.8
duration = 2.0
)";

std::string read_text(const fs::path &file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

json read_json(const fs::path &file) {
    std::ifstream in(file);
    return json::parse(in, nullptr, false);
}

// A fresh folder of this test process, holding the series scene: the
// shipped stability scene with kSteps appended.
fs::path series_dir(const std::string &name) {
    const fs::path dir =
        fs::temp_directory_path() / ("armour_series_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "series.toml")
        << read_text(fs::path(ARMOUR_SOURCE_DIR) / "scenes" / "stability_cubes.toml") << kSteps;
    return dir;
}

// `armour run SCENE --out OUT --set ...` plus `flags`, in a child leading
// its own process group (interFoam runs below it), output to `log`.
pid_t start(const fs::path &scene, const fs::path &out, const std::vector<std::string> &sets,
            const std::vector<std::string> &flags, const fs::path &log) {
    std::vector<std::string> a = {ARMOUR_EXE, "run", scene.string(), "--out", out.string()};
    for (const std::string &s : sets)
        a.insert(a.end(), {"--set", s});
    a.insert(a.end(), flags.begin(), flags.end());
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::setpgid(0, 0);
        const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
        ::dup2(fd, 1);
        ::dup2(fd, 2);
        std::vector<char *> argv;
        for (auto &s : a)
            argv.push_back(s.data());
        argv.push_back(nullptr);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    ::setpgid(pid, pid);
    return pid;
}

using armour_test::wait_for;

int run(const fs::path &scene, const fs::path &out, const std::vector<std::string> &sets,
        const std::vector<std::string> &flags, const fs::path &log) {
    return wait_for(start(scene, out, sets, flags, log));
}

// Whether a complete checkpoint lies in OUT/checkpoints.
bool has_checkpoint(const fs::path &out) {
    std::error_code ec;
    for (const auto &e : fs::directory_iterator(out / "checkpoints", ec))
        if (e.path().filename().string().rfind(".partial-", 0) != 0 &&
            fs::exists(e.path() / "checkpoint.json"))
            return true;
    return false;
}

using armour_test::wait_unlocked;

// Units at least one Dn from where they were at the series' start (the
// first record of step 1) at the end of each step, from the steps' records.
std::vector<int> displaced_at_step_ends(const fs::path &out, std::size_t steps) {
    std::vector<int> displaced;
    const armour::BodiesFile first = armour::read_bodies_file((out / "series" / "1" / "bodies.h5").string());
    for (std::size_t k = 1; k <= steps; ++k) {
        const armour::BodiesFile rec =
            armour::read_bodies_file((out / "series" / std::to_string(k) / "bodies.h5").string());
        int n = 0;
        for (std::size_t b = 0; b < rec.bodies(); ++b)
            n += (rec.position.back()[b] - first.position.front()[b]).norm() >= kDn ? 1 : 0;
        displaced.push_back(n);
    }
    return displaced;
}

bool finite_or_null(const json &v) {
    return v.is_null() || (v.is_number() && std::isfinite(v.get<double>()));
}

// The series as a clumps-against-hulls study runs it: settled once by clump
// engine (fluid.settle_engine = liggghts), run with exact hulls (bullet),
// killed by SIGKILL part way through its second step (after a checkpoint)
// and continued with --resume. Each step starts where the one before left
// the layer (step 1: the settle's poses, handed to the hulls as they are);
// the summary's series holds both steps, the cumulative N_od counts from the
// settled layer and never falls, and Van der Meer's cumulative prediction is
// the equivalent-number-of-waves sequence of the steps' own figures.
TEST(StabilitySeries, KilledInItsSecondStepItResumesAndEachStepStartsWhereTheLastEnded) {
    const fs::path dir = series_dir("resume"), scene = dir / "series.toml", out = dir / "out";
    std::vector<std::string> sets = kSmall;
    sets.insert(sets.end(), {"fluid.settle_engine=liggghts", "run.checkpoint_interval=0.5"});
    const std::vector<std::string> engine = {"--engine", "bullet"};

    const pid_t pid = start(scene, out, sets, engine, dir / "killed.log");
    const auto t0 = std::chrono::steady_clock::now();
    while (!has_checkpoint(out / "series" / "2") &&
           std::chrono::steady_clock::now() - t0 < std::chrono::minutes(8) &&
           ::waitpid(pid, nullptr, WNOHANG) == 0)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ::kill(-pid, SIGKILL);
    ASSERT_EQ(wait_for(pid), 128 + SIGKILL) << read_text(dir / "killed.log");
    ASSERT_TRUE(wait_unlocked(out) && wait_unlocked(out / "series" / "2"));
    ASSERT_TRUE(fs::is_regular_file(out / "series" / "1" / "summary.json")) << read_text(dir / "killed.log");
    ASSERT_FALSE(fs::exists(out / "series" / "2" / "summary.json"));
    ASSERT_FALSE(fs::exists(out / "summary.json"));
    const std::string step1 = read_text(out / "series" / "1" / "summary.json");
    // Clumps' layer handed to hulls: said, not silent (the hulls slump off it).
    EXPECT_NE(read_text(dir / "killed.log").find("the hulls slump off a clump-settled layer"),
              std::string::npos)
        << read_text(dir / "killed.log");

    ASSERT_EQ(run(scene, out, sets, {"--engine", "bullet", "--resume"}, dir / "resumed.log"), 0)
        << read_text(dir / "resumed.log");
    const std::string log = read_text(dir / "resumed.log");
    EXPECT_NE(log.find("series step 1 of 2: done"), std::string::npos) << log;
    EXPECT_NE(log.find("series step 2 of 2: Hs 0.12 m, Tp 1.6 s, gamma 3.3, seed 2, 2 s (resumed at t = "),
              std::string::npos)
        << log;
    EXPECT_EQ(log.find("settling"), std::string::npos) << log;          // settled once
    EXPECT_EQ(read_text(out / "series" / "1" / "summary.json"), step1); // a finished step is never rerun

    // The settle's engine and the run's.
    EXPECT_EQ(read_json(out / "settle" / "summary.json")["engine"], "liggghts");
    // The settled scene says who settled it, so running it with hulls later
    // (its own run.engine here, or --engine bullet) is warned too; with the
    // clumps that settled it, not.
    const fs::path settled = out / "settle" / "scene.settled.toml";
    EXPECT_NE(read_text(settled).find("settled_by = \"liggghts\""), std::string::npos);
    ASSERT_EQ(run(settled, dir / "handed", {}, {"--engine", "bullet", "--dry-run"}, dir / "handed.log"), 0)
        << read_text(dir / "handed.log");
    EXPECT_NE(read_text(dir / "handed.log").find("fluid.settled_by liggghts settled sphere clumps"),
              std::string::npos)
        << read_text(dir / "handed.log");
    ASSERT_EQ(run(settled, dir / "same", {}, {"--engine", "liggghts", "--dry-run"}, dir / "same.log"), 0)
        << read_text(dir / "same.log");
    EXPECT_EQ(read_text(dir / "same.log").find("slump"), std::string::npos) << read_text(dir / "same.log");
    const json s = read_json(out / "summary.json");
    ASSERT_TRUE(s.is_object()) << log;
    EXPECT_EQ(s["engine"], "bullet");

    // Each step starts from the poses the one before ended at (step 1: the
    // settled poses), to the text's rounding.
    const armour::BodiesFile one = armour::read_bodies_file((out / "series" / "1" / "bodies.h5").string());
    const armour::BodiesFile two = armour::read_bodies_file((out / "series" / "2" / "bodies.h5").string());
    ASSERT_EQ(one.bodies(), 45u);
    ASSERT_EQ(two.bodies(), 45u);
    double gap = 0.0, turn = 0.0;
    for (std::size_t b = 0; b < 45; ++b) {
        gap = std::max(gap, (two.position.front()[b] - one.position.back()[b]).norm());
        turn = std::max(turn, 1.0 - std::abs(two.orientation.front()[b].dot(one.orientation.back()[b])));
    }
    EXPECT_LT(gap, 1e-9);
    EXPECT_LT(turn, 1e-12);
    EXPECT_GT(two.time.back(), 2.0 - 0.05 - 1e-9);

    // The series: both steps, with their figures (finite where defined).
    ASSERT_TRUE(s["series"].is_array());
    ASSERT_EQ(s["series"].size(), 2u);
    const char *keys[] = {
        "target_height", "target_period",      "incident_height",   "waves",    "Ns",
        "N_od",          "N_od_total",         "N_od_van_der_meer", "damage_S", "damage_S_total",
        "rocking_units", "rocking_units_total"};
    for (const json &step : s["series"])
        for (const char *key : keys)
            EXPECT_TRUE(step.contains(key) && finite_or_null(step[key])) << key << ": " << step.dump();
    const json &a = s["series"][0], &b = s["series"][1];
    EXPECT_EQ(a["target_height"], 0.10);
    EXPECT_EQ(b["target_period"], 1.6);
    for (const char *key : {"waves", "Ns", "N_od", "N_od_total", "N_od_van_der_meer"})
        EXPECT_TRUE(a[key].is_number() && b[key].is_number()) << key;

    // Cumulative N_od: from the series' start, never falling, the count of
    // units one Dn from their settled place over the layer's Dn strips.
    const std::vector<int> displaced = displaced_at_step_ends(out, 2);
    const double strips = s["damage"]["layer_width"].get<double>() / kDn;
    EXPECT_NEAR(a["N_od_total"].get<double>(), displaced[0] / strips, 1e-12);
    EXPECT_NEAR(b["N_od_total"].get<double>(), displaced[1] / strips, 1e-12);
    EXPECT_GE(b["N_od_total"].get<double>(), a["N_od_total"].get<double>());
    EXPECT_EQ(a["N_od_total"], a["N_od"]); // step 1 starts at the series' start
    EXPECT_EQ(s["N_od"], b["N_od_total"]); // the whole series: the top-level keys
    EXPECT_EQ(s["units_displaced"].get<int>(), displaced[1]);
    EXPECT_EQ(s["damage_S"], b["damage_S_total"]);
    EXPECT_EQ(s["rocking_units"], b["rocking_units_total"]);
    EXPECT_NEAR(s["waves"]["waves"].get<double>(), a["waves"].get<double>() + b["waves"].get<double>(), 1e-9);
    EXPECT_EQ(s["Ns"], b["Ns"]);

    // Van der Meer's cumulative prediction from the steps' own Ns, s_om and N.
    const auto predicted = armour::van_der_meer_cubes_sequence(
        {{a["Ns"].get<double>(), a["s_om"].get<double>(), a["waves"].get<double>()},
         {b["Ns"].get<double>(), b["s_om"].get<double>(), b["waves"].get<double>()}});
    EXPECT_NEAR(a["N_od_van_der_meer"].get<double>(), *predicted[0].N_od, 1e-12);
    EXPECT_NEAR(b["N_od_van_der_meer"].get<double>(), *predicted[1].N_od, 1e-12);
    EXPECT_EQ(s["N_od_van_der_meer"], b["N_od_van_der_meer"]);

    // The clump-settled layer is the Rock Manual's: not flagged, no warning.
    EXPECT_EQ(s["damage"]["settled_layer"]["outside_rock_manual"], false) << s["damage"].dump();
    EXPECT_EQ(read_text(dir / "killed.log").find("outside the Rock Manual"), std::string::npos);
    std::printf("series: N_od %s / %s (total %s / %s), Van der Meer %s / %s, layer %s\n",
                a["N_od"].dump().c_str(), b["N_od"].dump().c_str(), a["N_od_total"].dump().c_str(),
                b["N_od_total"].dump().c_str(), a["N_od_van_der_meer"].dump().c_str(),
                b["N_od_van_der_meer"].dump().c_str(), s["damage"]["settled_layer"].dump().c_str());
    if (!HasFailure())
        fs::remove_all(dir);
}

// A step the wave maker cannot make is refused before anything runs, in
// one line naming the step's key, by the run and by its --dry-run.
TEST(StabilitySeries, AStepTheMakerCannotMakeIsRefusedNamingItsKey) {
    const fs::path dir = series_dir("refused"), scene = dir / "series.toml";
    for (const auto &[set, key, why] :
         {std::tuple<std::string, std::string, std::string>{
              "series.1.Hs=0.2", "key 'series.1.Hs': step 2: ", "breaks at the inlet"},
          {"series.0.Tp=5", "key 'series.0.Tp': step 1: ", "kh ="}})
        for (const std::string flag : {"", "--dry-run"}) {
            std::vector<std::string> sets = kSmall;
            sets.push_back(set);
            const fs::path out = dir / "out", log = dir / "refused.log";
            fs::remove(log);
            EXPECT_EQ(
                run(scene, out, sets, flag.empty() ? std::vector<std::string>{} : std::vector{flag}, log), 2);
            const std::string text = read_text(log);
            EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
            EXPECT_EQ(text.rfind("armour: error: ", 0), 0u) << text;
            EXPECT_NE(text.find(key), std::string::npos) << text;
            EXPECT_NE(text.find(why), std::string::npos) << text;
            EXPECT_FALSE(fs::exists(out));
        }
    if (!HasFailure())
        fs::remove_all(dir);
}

// The scene's layer settled by exact hulls packs flat and dense (measured at
// the converged step: porosity 0.30-0.32, below the 0.35 under which random
// cubes cannot be built; a 5-row layer stays at 0.37, inside): the run warns
// once, before its waves, and flags it in summary.json.
TEST(StabilitySeries, AHullSettledLayerIsReportedOutsideTheRockManual) {
    const fs::path dir = series_dir("hull_layer"), out = dir / "out";
    // All 11 rows; the graded mesh, whose fine box holds the hull or two that
    // slide off the toe onto the berm, in front of the scene's band.
    std::vector<std::string> sets = {"fluid.cells=[50,6,16]", "fluid.penalty=200", "fluid.mesh=graded"};
    sets.insert(sets.end(), {"waves.Hs=0.001", "run.duration=0.2"});
    ASSERT_EQ(run(fs::path(ARMOUR_SOURCE_DIR) / "scenes" / "stability_cubes.toml", out, sets,
                  {"--engine", "bullet"}, dir / "run.log"),
              0)
        << read_text(dir / "run.log");
    const std::string log = read_text(dir / "run.log");
    const json layer = read_json(out / "summary.json")["damage"]["settled_layer"];
    std::printf("hull-settled layer: %s\n", layer.dump().c_str());
    ASSERT_TRUE(layer.is_object());
    EXPECT_LT(layer["porosity"].get<double>(), 0.35);
    EXPECT_EQ(layer["outside_rock_manual"], true);
    EXPECT_NE(layer["outside_reason"].get<std::string>().find("porosity"), std::string::npos);
    const std::string warning = "armour: warning: the layer the waves meet is outside the Rock Manual";
    std::size_t lines = 0;
    for (auto at = log.find(warning); at != std::string::npos; at = log.find(warning, at + 1))
        ++lines;
    EXPECT_EQ(lines, 1u) << log;
    if (!HasFailure())
        fs::remove_all(dir);
}

} // namespace
