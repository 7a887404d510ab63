// A coupled run killed and resumed (docs/checkpoints.md): the dam break on
// two light cubes, made CI-short (2 cells across a cube, 0.6 s, a checkpoint
// every 0.02 s), killed with SIGKILL (its whole process group: armour and
// interFoam, as a batch system ends a job) at a seeded random moment after a
// checkpoint, resumed with --resume, and compared with the same run
// uninterrupted. A resume continues the same flow: every record (time, pose)
// is the uninterrupted run's to the bit, before the surge reaches the cubes
// and during it. (It was not, until the restart kept the checkpoint's flux
// instead of projecting it again and both runs went on from a mask computed
// anew at the checkpoint: 0.07-0.6 Dn apart at the end; the surge's impact on
// the cubes amplifies any difference, 3e-6 Dn at the end from the projection
// alone. So the only tolerance this chaotic flow allows is none.)
#include "bodies_file.h"
#include "checkpoints.h"
#include "cli.h"
#include "output_folder.h"
#include "process_wait.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
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

constexpr double kDn = 0.08; // m, the cubes' edge

// `armour run` in a child process leading its own process group (interFoam
// runs below it); returns the exit status (128 + signal when killed).
pid_t start(const std::vector<std::string> &a) {
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::setpgid(0, 0);
        std::vector<const char *> argv;
        for (const auto &s : a)
            argv.push_back(s.c_str());
        const int code = armour::armour_main(static_cast<int>(argv.size()), argv.data());
        std::fflush(nullptr);
        ::_exit(code);
    }
    ::setpgid(pid, pid);
    return pid;
}

using armour_test::wait_for;
using armour_test::wait_until;

double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A fresh folder of this test process in the temp directory.
fs::path test_dir(const std::string &name) {
    const fs::path dir = fs::temp_directory_path() / ("armour_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// `armour run scenes/SCENE --out OUT --set SET ...` followed by `flags`.
std::vector<std::string> run_args(const std::string &scene, const fs::path &out,
                                  const std::vector<std::string> &sets,
                                  const std::vector<std::string> &flags = {}) {
    std::vector<std::string> a = {"armour", "run", (fs::path(ARMOUR_SOURCE_DIR) / "scenes" / scene).string(),
                                  "--out", out.string()};
    for (const std::string &set : sets) {
        a.emplace_back("--set");
        a.push_back(set);
    }
    a.insert(a.end(), flags.begin(), flags.end());
    return a;
}

json summary_of(const fs::path &out) {
    std::ifstream in(out / "summary.json");
    return json::parse(in);
}

std::string read_text(const fs::path &file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

using armour_test::wait_unlocked;

// Waits until no process runs in OUT/case: mpirun's ranks are not in
// armour's process group and do not hold OUT's lock; after a SIGKILL of that
// group they end on their own a moment later (the plugin ties each rank to
// mpirun), and until then a command into OUT is refused.
bool wait_solver_gone(const fs::path &out) {
    const fs::path case_dir = fs::weakly_canonical(out / "case");
    const auto t0 = std::chrono::steady_clock::now();
    while (since(t0) < 30.0) {
        bool running = false;
        std::error_code ec;
        for (const auto &e : fs::directory_iterator("/proc", ec)) {
            std::error_code gone;
            running = running || fs::read_symlink(e.path() / "cwd", gone) == case_dir;
        }
        if (!running)
            return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
}

// The time (s) of the latest complete checkpoint in OUT/checkpoints, -1 when none.
double latest_checkpoint(const fs::path &out) {
    double latest = -1.0;
    std::error_code ec;
    for (const auto &e : fs::directory_iterator(out / "checkpoints", ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind(".partial-", 0) != 0 && fs::exists(e.path() / "checkpoint.json"))
            latest = std::max(latest, std::stod(name));
    }
    return latest;
}

// When the surge reaches the cubes in the uninterrupted run: the first record
// where the fluid pushes a cube sideways with more than 1 % of its weight.
// Before it the cubes rest in air, and the fluid's difference after a resume
// has not reached them.
double surge_arrival(const armour::BodiesFile &run, double weight) {
    for (std::size_t s = 0; s < run.steps(); ++s)
        for (std::size_t k = 0; k < run.bodies(); ++k)
            if (run.external_force[s][k].head<2>().norm() > 0.01 * weight)
                return run.time[s];
    return run.time.back();
}

struct Resumed {
    double checkpoint = 0.0; // s, the simulated time the resume started from
    double time_shift = 0.0; // s, largest difference of a record's time
    double pose = 0.0;       // m, largest difference of a pose over every record (turns as 0.5 Dn x angle)
    double final_pose = 0.0; // m, the same at the last record
};

// How far apart two poses of body k at step s are (m; a turn counts as 0.5
// Dn x angle, the angle exactly 0 for equal orientations).
double pose_difference(const armour::BodiesFile &a, const armour::BodiesFile &b, std::size_t s,
                       std::size_t k) {
    const double turn = a.orientation[s][k].angularDistance(b.orientation[s][k]);
    return std::max((b.position[s][k] - a.position[s][k]).norm(), 0.5 * kDn * turn);
}

// Compares a resumed run's record with the uninterrupted one: whole (same
// count, strictly increasing) and the same headline figures; returns how far
// apart the records are.
Resumed compare_records(const fs::path &reference, const fs::path &resumed, double checkpoint) {
    const armour::BodiesFile a = armour::read_bodies_file((reference / "bodies.h5").string());
    const armour::BodiesFile b = armour::read_bodies_file((resumed / "bodies.h5").string());
    Resumed r;
    r.checkpoint = checkpoint;
    EXPECT_EQ(b.time.size(), a.time.size()) << "records lost or doubled";
    if (b.time.size() != a.time.size())
        return r;
    for (std::size_t s = 1; s < b.time.size(); ++s)
        EXPECT_GT(b.time[s], b.time[s - 1]) << "step " << s;
    const std::size_t last = a.time.size() - 1;
    for (std::size_t s = 0; s < a.time.size(); ++s) {
        r.time_shift = std::max(r.time_shift, std::abs(b.time[s] - a.time[s]));
        for (std::size_t k = 0; k < a.bodies(); ++k)
            r.pose = std::max(r.pose, pose_difference(a, b, s, k));
    }
    for (std::size_t k = 0; k < a.bodies(); ++k)
        r.final_pose = std::max(r.final_pose, pose_difference(a, b, last, k));
    const json x = summary_of(reference), y = summary_of(resumed);
    EXPECT_EQ(y["records"], x["records"]);
    EXPECT_EQ(y["simulated_seconds"], x["simulated_seconds"]);
    EXPECT_EQ(y["records"], a.time.size());
    return r;
}

// The same flow: every record's time and every pose to the bit (measured so
// at every resume point tried; a lost piece of state shows as a difference
// the surge amplifies, docs/checkpoints.md).
void expect_same_flow(const Resumed &r) {
    EXPECT_EQ(r.time_shift, 0.0) << "resumed at " << r.checkpoint << " s";
    EXPECT_EQ(r.pose, 0.0) << "resumed at " << r.checkpoint << " s (" << r.pose / kDn << " Dn)";
}

} // namespace

TEST(CoupledResume, KilledDamBreakResumedEndsAsTheUninterruptedOne) {
    const fs::path dir = test_dir("coupled_resume");
    const auto args = [&](const fs::path &out, bool resume) {
        return run_args("dambreak_two_cubes.toml", out,
                        {"fluid.cell_size=0.04", "run.duration=0.6", "run.checkpoint_interval=0.02"},
                        resume ? std::vector<std::string>{"--resume"} : std::vector<std::string>{});
    };

    const fs::path reference = dir / "reference";
    const auto t0 = std::chrono::steady_clock::now();
    ASSERT_EQ(wait_for(start(args(reference, false))), 0);
    const double wall = since(t0);
    const armour::BodiesFile run = armour::read_bodies_file((reference / "bodies.h5").string());
    const double cube_weight = 900.0 * kDn * kDn * kDn * 9.81; // N
    const double arrival = surge_arrival(run, cube_weight);
    std::printf(
        "[ resume   ] dam break: the surge reaches the cubes at %.3g s (uninterrupted run: %.1f s wall)\n",
        arrival, wall);
    ASSERT_GT(arrival, 0.06) << "the cubes are hit before three checkpoints";
    ASSERT_LT(arrival, 0.4) << "the surge does not reach the cubes";

    // Kills a run once its latest checkpoint lies in [from, to) s, a random
    // wall delay after that checkpoint appeared; returns the checkpoint the
    // resume starts from, or -1 when every try ended outside the window.
    const auto kill_between = [&](const fs::path &out, double from, double to, std::mt19937 &random) {
        // Wall seconds per 0.02 s of simulated time, on average over the run.
        const double gap = wall * 0.02 / 0.6;
        double delay = std::uniform_real_distribution<double>(0.0, 1.0)(random) * gap;
        for (int attempt = 0; attempt < 4; ++attempt, delay *= 0.5) {
            fs::remove_all(out);
            const pid_t pid = start(args(out, false));
            bool killed = false;
            if (wait_until(pid, [&] { return latest_checkpoint(out) >= from; })) {
                std::this_thread::sleep_for(std::chrono::duration<double>(delay));
                ::kill(-pid, SIGKILL);
                killed = wait_for(pid) == 128 + SIGKILL;
            }
            EXPECT_TRUE(wait_unlocked(out)) << "interFoam outlived the kill by 30 s";
            const double checkpoint = latest_checkpoint(out);
            if (killed && checkpoint >= from && checkpoint < to)
                return checkpoint;
        }
        return -1.0;
    };

    // Before the surge: the resume starts at a random checkpoint from the
    // first to the last before the arrival, for each seed (the cubes rest
    // in air; their fractions are kept from step to step).
    for (const unsigned seed : {1u, 2u}) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        std::mt19937 random(seed);
        const double first = std::uniform_real_distribution<double>(0.02, arrival - 0.04)(random);
        const fs::path killed = dir / ("before_surge_" + std::to_string(seed));
        const double checkpoint = kill_between(killed, first, arrival - 0.01, random);
        ASSERT_GE(checkpoint, 0.0) << "no kill between a checkpoint and the surge's arrival";
        EXPECT_FALSE(fs::exists(killed / "summary.json"));
        ASSERT_EQ(wait_for(start(args(killed, true))), 0);
        const Resumed r = compare_records(reference, killed, checkpoint);
        std::printf("[ resume   ] before the surge: resumed at %.3g s; record times differ by up to %.3g s; "
                    "poses by %.3g Dn, final poses by %.3g Dn\n",
                    r.checkpoint, r.time_shift, r.pose / kDn, r.final_pose / kDn);
        expect_same_flow(r);
    }

    // During the surge (the first cube moves; the impact amplifies any difference).
    {
        std::mt19937 random(3u);
        const fs::path killed = dir / "in_surge";
        const double checkpoint = kill_between(killed, arrival + 0.02, arrival + 0.2, random);
        ASSERT_GE(checkpoint, 0.0) << "no kill during the surge";
        // The run's folder moved, and the build that started it is gone (its
        // plugin named in the case's controlDict): the resume writes into
        // the folder it is given, with this armour's plugin.
        const fs::path moved = dir / "in_surge_moved";
        fs::rename(killed, moved);
        const fs::path control = moved / "case" / "system" / "controlDict";
        std::string text = armour::read_text_file(control);
        const auto plugin = text.find("libarmourFoamCoupling.so");
        ASSERT_NE(plugin, std::string::npos);
        text.insert(plugin, "removed-build/");
        armour::write_text_file(control, text);
        ASSERT_EQ(wait_for(start(args(moved, true))), 0);
        EXPECT_FALSE(fs::exists(killed)) << "the resume wrote into the run's old folder";
        EXPECT_EQ(armour::read_text_file(control).find("removed-build/"), std::string::npos);
        const Resumed r = compare_records(reference, moved, checkpoint);
        std::printf("[ resume   ] during the surge: resumed at %.3g s; record times differ by up to %.3g s; "
                    "poses by %.3g Dn, final poses by %.3g Dn\n",
                    r.checkpoint, r.time_shift, r.pose / kDn, r.final_pose / kDn);
        expect_same_flow(r);
    }
    if (!::testing::Test::HasFailure())
        fs::remove_all(dir);
}

namespace {

// The dam break (5 s at 2 cells per cube, a checkpoint every 0.02 s) started
// with FLAGS and killed with SIGKILL after its first checkpoint, to armour's
// pid alone or to its whole process group: interFoam, which carries the run
// in its plugin, must end with it instead of going on to the end in the
// background.
void expect_solver_ends_with_armour(const std::string &name, const std::vector<std::string> &flags,
                                    bool whole_group) {
    const fs::path dir = test_dir(name), out = dir / "run";
    const pid_t pid =
        start(run_args("dambreak_two_cubes.toml", out,
                       {"fluid.cell_size=0.04", "run.duration=5", "run.checkpoint_interval=0.02"}, flags));
    ASSERT_TRUE(wait_until(pid, [&] { return latest_checkpoint(out) >= 0.0; }))
        << "the run ended before its first checkpoint";
    ::kill(whole_group ? -pid : pid, SIGKILL);
    const double at_kill = latest_checkpoint(out);
    ASSERT_GE(at_kill, 0.0) << "the solver never reached its first checkpoint";
    EXPECT_EQ(wait_for(pid), 128 + SIGKILL);
    EXPECT_TRUE(wait_unlocked(out)) << "interFoam went on for 30 s after armour was killed";
    EXPECT_TRUE(wait_solver_gone(out)) << "the solver's ranks went on for 30 s after armour was killed";
    // The checkpoint being written at the kill may still be finished; no
    // later one. (Left to MPI, orphaned ranks noticed mpirun's end ~1 s
    // later, after ~5 more checkpoints here.)
    EXPECT_LE(latest_checkpoint(out), at_kill + 0.03) << "the solver went on after armour was killed";
    EXPECT_FALSE(fs::exists(out / "summary.json"));
    if (!::testing::Test::HasFailure())
        fs::remove_all(dir);
}

} // namespace

// `armour run` killed alone (SIGKILL to its pid, not its group: a user's
// `kill -9`, a crash).
TEST(CoupledResume, ArmourKilledAloneTakesItsSolverWithIt) {
    expect_solver_ends_with_armour("killed_alone", {}, false);
}

// A parallel run's group killed (armour and mpirun, as `kill -9 -PGID`
// does): mpirun cannot pass a SIGKILL on, and its ranks are not in the group.
TEST(CoupledResume, ParallelRanksEndWhenTheirGroupIsKilled) {
    expect_solver_ends_with_armour("ranks_killed", {"--np", "2"}, true);
}

// A parallel run (--np 2: the fields in processor<N>/) checkpoints and
// resumes on any number of ranks. Killed (its group) after its second
// checkpoint; resumed plainly: on its own 2 ranks; killed again, resumed on
// 1 rank (the fields reconstructed) with another Courant limit; killed
// again, resumed on 2 (split anew) to the end: every record on the output
// grid, and the wall time of all parts.
TEST(CoupledResume, ParallelRunResumesOnAnyNumberOfRanks) {
    const fs::path dir = test_dir("parallel_resume"), out = dir / "run";
    const auto args = [&](const std::vector<std::string> &flags) {
        return run_args("dambreak_two_cubes.toml", out,
                        {"fluid.cell_size=0.04", "run.duration=0.6", "run.checkpoint_interval=0.1"}, flags);
    };
    // Starts a part, kills its group once a checkpoint at `after` s or later
    // is complete; returns that checkpoint's time.
    const auto part_killed_after = [&](const std::vector<std::string> &flags, double after) {
        const pid_t pid = start(args(flags));
        if (wait_until(pid, [&] { return latest_checkpoint(out) >= after; })) {
            ::kill(-pid, SIGKILL);
            wait_for(pid);
        }
        EXPECT_TRUE(wait_unlocked(out));
        EXPECT_TRUE(wait_solver_gone(out)) << "interFoam's ranks outlived the kill by 30 s";
        return latest_checkpoint(out);
    };
    const auto split_over = [&](double checkpoint) {
        const fs::path fluid = out / "checkpoints" / armour::checkpoint_name(checkpoint) / "fluid";
        int ranks = 0;
        for (const auto &e : fs::directory_iterator(fluid))
            ranks += e.path().filename().string().rfind("processor", 0) == 0 ? 1 : 0;
        return ranks;
    };
    const auto wall_at = [&](double checkpoint) {
        std::ifstream in(out / "checkpoints" / armour::checkpoint_name(checkpoint) / "checkpoint.json");
        return json::parse(in).value("wall_seconds", 0.0);
    };

    const auto t0 = std::chrono::steady_clock::now();
    const double first = part_killed_after({"--np", "2"}, 0.15);
    const double first_part = since(t0);
    ASSERT_GE(first, 0.15) << "no second checkpoint";
    ASSERT_LT(first, 0.25) << "the run went past the kill";
    EXPECT_EQ(split_over(first), 2);
    const double first_wall = wall_at(first); // a checkpoint goes two checkpoints later
    const double second = part_killed_after({"--resume"}, first + 0.05);
    ASSERT_GT(second, first);
    ASSERT_LT(second, 0.35);
    EXPECT_EQ(split_over(second), 2) << "a plain --resume goes on with the run's ranks";
    const double second_wall = wall_at(second);
    const double third = part_killed_after(
        {"--np", "1", "--resume", "--set", "fluid.max_courant=0.8", "--set", "fluid.write_interval=0.02"},
        second + 0.05);
    ASSERT_GT(third, second);
    ASSERT_LT(third, 0.45);
    EXPECT_EQ(split_over(third), 0) << "the serial part's checkpoint holds the whole fields";
    const double third_wall = wall_at(third);
    std::ifstream control_file(out / "case" / "system" / "controlDict");
    std::stringstream control;
    control << control_file.rdbuf();
    EXPECT_NE(control.str().find("\nmaxCo 0.8;"), std::string::npos)
        << "a resume may change the Courant limit";
    // ... and the fluid's write interval (0.6 s, the duration, before): the
    // serial part wrote the fields in the case every 0.02 s between its
    // checkpoints (0.1 s apart; a checkpoint's own write is at its time).
    EXPECT_NE(control.str().find("\nwriteInterval 0.02;"), std::string::npos) << control.str();
    int written = 0;
    for (const auto &e : fs::directory_iterator(out / "case")) {
        const auto t = armour::time_of_name(e.path().filename().string());
        written += t && *t > second + 1e-9 && *t < third - 1e-9 ? 1 : 0;
    }
    EXPECT_GE(written, 2) << "fields written between the checkpoints at " << second << " and " << third
                          << " s";
    const auto t1 = std::chrono::steady_clock::now();
    ASSERT_EQ(wait_for(start(args({"--np", "2", "--resume"}))), 0);
    const double last_part = since(t1);
    const json summary = summary_of(out);
    EXPECT_EQ(summary["records"], 61); // 0 .. 0.6 s every 0.01 s
    EXPECT_EQ(summary["fluid"]["np"], 2);
    EXPECT_NEAR(summary["simulated_seconds"].get<double>(), 0.6, 0.005);
    const armour::BodiesFile run = armour::read_bodies_file((out / "bodies.h5").string());
    ASSERT_EQ(run.time.size(), 61u);
    for (std::size_t s = 1; s < run.time.size(); ++s)
        EXPECT_NEAR(run.time[s] - run.time[s - 1], 0.01, 0.005) << s;
    // Wall time adds up over the parts: each checkpoint carries the parts'
    // up to it, the summary that of the last checkpoint plus the last part's.
    EXPECT_GT(first_wall, 0.0);
    EXPECT_LT(first_wall, first_part);
    EXPECT_GT(second_wall, first_wall);
    EXPECT_GT(third_wall, second_wall);
    EXPECT_GT(summary["wall_seconds"].get<double>(), third_wall);
    EXPECT_LT(summary["wall_seconds"].get<double>(), third_wall + last_part);
    if (!::testing::Test::HasFailure())
        fs::remove_all(dir);
}

// The stability scene as a long run uses it (a DEM settle first, then
// irregular waves; CI-sized: 45 cubes, 4 cm cells, 12 s, a checkpoint every
// 3 s) killed after its second checkpoint and resumed with the same command,
// twice (the second resume killed again soon after it started, so a gauge
// part starting at the checkpoint is written twice): the settle is not run
// again, a changed placement is refused, and the wave analysis reads the
// gauges whole across the parts, as the uninterrupted run does.
TEST(CoupledResume, SettledWaveRunResumesWithTheSameCommand) {
    const fs::path dir = test_dir("settled_resume");
    const auto args = [&](const fs::path &out, const std::vector<std::string> &flags) {
        return run_args("stability_cubes.toml", out,
                        {"pattern.0.rows=5", "fluid.settle_stages=5", "fluid.cells=[50,6,16]",
                         "fluid.penalty=200", "run.duration=12", "run.checkpoint_interval=3"},
                        flags);
    };
    const fs::path reference = dir / "reference", killed = dir / "killed";
    ASSERT_EQ(wait_for(start(args(reference, {}))), 0);
    // Kills a run of `killed` once `ready` holds.
    const auto kill_when = [&](const std::vector<std::string> &extra, const std::function<bool()> &ready) {
        const pid_t pid = start(args(killed, extra));
        if (wait_until(pid, ready)) {
            ::kill(-pid, SIGKILL);
            wait_for(pid);
        }
        EXPECT_TRUE(wait_unlocked(killed));
    };
    kill_when({}, [&] { return latest_checkpoint(killed) >= 6.0; });
    const double checkpoint = latest_checkpoint(killed);
    ASSERT_GE(checkpoint, 6.0);
    ASSERT_LT(checkpoint, 11.0) << "the run ended before the kill";
    EXPECT_EQ(wait_for(start(args(killed, {"--set", "pattern.0.seed=2", "--resume"}))), 2);
    EXPECT_DOUBLE_EQ(latest_checkpoint(killed), checkpoint);
    // The resume's own gauge part (postProcessing/gauges/<checkpoint>/) with
    // some rows in it.
    const auto resumed_gauges = [&] {
        std::error_code ec;
        for (const auto &e : fs::directory_iterator(killed / "case" / "postProcessing" / "gauges", ec))
            if (e.path().filename() != "0" && fs::exists(e.path() / "surfaceElevation.dat") &&
                fs::file_size(e.path() / "surfaceElevation.dat") > 2000)
                return true;
        return false;
    };
    kill_when({"--resume"}, resumed_gauges);
    ASSERT_TRUE(resumed_gauges());
    // A run recorded before settled scenes named their settle's engine
    // (fluid.settled_by) resumes too: that key is a record, not the scene.
    const fs::path ran = killed / "scene.resolved.toml";
    std::string recorded = read_text(ran);
    const std::size_t at = recorded.find("settled_by = \"liggghts\"\n");
    ASSERT_NE(at, std::string::npos) << recorded;
    recorded.erase(at, recorded.find('\n', at) + 1 - at);
    std::ofstream(ran) << recorded;
    ASSERT_EQ(wait_for(start(args(killed, {"--resume"}))), 0);

    const json a = summary_of(reference), b = summary_of(killed);
    EXPECT_EQ(b["records"], a["records"]);
    EXPECT_EQ(b["units"], a["units"]);
    EXPECT_EQ(b["units_displaced"], a["units_displaced"]);
    EXPECT_EQ(b["settle"]["scene"], "settle/scene.settled.toml");
    const json &wa = a["waves"], &wb = b["waves"];
    ASSERT_TRUE(wa.contains("incident_height") && wb.contains("incident_height")) << wa.dump() << wb.dump();
    EXPECT_EQ(wb["waves"], wa["waves"]);
    EXPECT_EQ(wb["window"], wa["window"]);
    // Not bit for bit (docs/checkpoints.md): measured 3e-5 relative.
    EXPECT_NEAR(wb["incident_height"].get<double>() / wa["incident_height"].get<double>(), 1.0, 0.005);
    EXPECT_NEAR(wb["incident_period"].get<double>() / wa["incident_period"].get<double>(), 1.0, 0.01);
    EXPECT_NEAR(wb["reflection_coefficient"].get<double>(), wa["reflection_coefficient"].get<double>(), 0.01);
    EXPECT_NEAR(b["damage_S"].get<double>(), a["damage_S"].get<double>(), 0.01);
    // The DEM advances inside the solver's steps, so its share of the solver's
    // time is at most 1; the resumed part's solver clock starts at the
    // checkpoint, while the plugin's DEM seconds carry the earlier parts.
    EXPECT_GT(b["dem_share_of_solver"].get<double>(), 0.0);
    EXPECT_LE(b["dem_share_of_solver"].get<double>(), 1.0);
    if (!::testing::Test::HasFailure())
        fs::remove_all(dir);
}

// A sweep stopped while a coupled case runs (SIGTERM: the case goes back to
// pending) runs that case again from its run's last checkpoint: the second
// attempt resumes (its log says so, the killed part's solver log is kept)
// and the case ends with every record.
TEST(CoupledResume, StoppedSweepResumesItsCaseFromTheCheckpoint) {
    const fs::path dir = test_dir("sweep_resume");
    const fs::path file = dir / "sweep.toml", out = dir / "out";
    std::ofstream(file) << "scene = \"" << ARMOUR_SOURCE_DIR << "/scenes/dambreak_two_cubes.toml\"\n"
                        << "[set]\n\"fluid.cell_size\" = 0.04\n\"run.duration\" = 0.6\n"
                        << "\"run.checkpoint_interval\" = 0.05\n[vary]\n\"fluid.max_courant\" = [0.5]\n";
    const auto sweep = [&] {
        return armour_test::start_quietly(
            {ARMOUR_EXE, "sweep", file.string(), "--out", out.string(), "--jobs", "1"});
    };
    const fs::path run = out / "cases" / "max_courant-0.5" / "run";
    const pid_t first = sweep();
    ASSERT_TRUE(wait_until(first, [&] { return latest_checkpoint(run) >= 0.2; })) << "the sweep ended first";
    ::kill(first, SIGTERM);
    EXPECT_EQ(wait_for(first), 1); // stopped: a case did not finish
    const double checkpoint = latest_checkpoint(run);
    ASSERT_GE(checkpoint, 0.2);
    ASSERT_LT(checkpoint, 0.55) << "the case ended before the sweep was stopped";
    ASSERT_FALSE(fs::exists(run / "summary.json"));
    ASSERT_EQ(wait_for(sweep()), 0);
    std::ifstream log_in(run.parent_path() / "log.txt");
    const std::string log((std::istreambuf_iterator<char>(log_in)), std::istreambuf_iterator<char>());
    EXPECT_NE(log.find("attempt 2 on"), std::string::npos) << log;
    EXPECT_NE(log.find("resumed from its checkpoint at t = " + armour::checkpoint_name(checkpoint) + " s"),
              std::string::npos)
        << log;
    EXPECT_TRUE(fs::exists(run / "case" / "log.interFoam.1")) << "the killed part's solver log";
    EXPECT_EQ(summary_of(run)["records"], 61); // 0 .. 0.6 s every 0.01 s
    // The record says the attempt ran only the end (the sweep's ETA leaves it out).
    std::ifstream record(run.parent_path() / "case.json");
    EXPECT_NEAR(json::parse(record).value("resumed_from", -1.0), checkpoint, 1e-9);
    if (!::testing::Test::HasFailure())
        fs::remove_all(dir);
}
