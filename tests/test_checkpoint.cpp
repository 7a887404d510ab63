// Checkpoints and `armour run --resume` (docs/checkpoints.md): a run killed
// with SIGKILL at a random point after its first checkpoint, then resumed,
// ends as the same run uninterrupted: the same record times (no record lost
// or doubled), the same final poses (bit for bit, within the brief's 1e-3
// Dn), the same summary but for wall times. And a resume refuses what it
// cannot continue.
#include "bodies_file.h"
#include "checkpoints.h"
#include "cli.h"
#include "output_folder_rule.h"
#include "rigid_body_engine.h"

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
#include <optional>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <sys/file.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr double kEdge = 0.2; // m, the cubes' edge (= Dn)

// Four cubes dropped onto a floor, tumbling into each other: contacts
// between bodies and with the floor are live at every checkpoint.
std::string drop_scene(const std::string &engine, double duration) {
    std::string text = "name = \"drop4\"\n"
                       "[run]\nengine = \"" +
                       engine + "\"\nduration = " + std::to_string(duration) +
                       "\noutput_interval = 0.01\ncheckpoint_interval = 0.1\n"
                       "domain_min = [-1, -1, -0.5]\ndomain_max = [1, 1, 1.5]\n"
                       "[contact]\ncharacteristic_velocity = 2.0\n"
                       "[[material]]\nname = \"concrete\"\nyoungs_modulus = 5e7\nfriction = 0.5\n"
                       "[[unit]]\nname = \"cube\"\nshape = \"cube\"\nsize = 0.2\nspheres = 8\n"
                       "[[wall]]\nname = \"floor\"\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\n"
                       "size = 2\n";
    const char *bodies[] = {"[0, 0, 0.15]", "[0.05, 0.02, 0.45]", "[0.26, -0.03, 0.2]", "[-0.02, 0.3, 0.3]"};
    const char *turns[] = {"[1, 0, 0, 0]", "[0.96, 0.2, 0.1, 0.17]", "[0.9, 0, 0.43, 0]",
                           "[0.97, 0.17, 0, 0.17]"};
    for (int i = 0; i < 4; ++i)
        text += std::string("[[body]]\nunit = \"cube\"\nposition = ") + bodies[i] +
                "\norientation = " + turns[i] + "\nvelocity = [0.3, 0, 0]\n";
    return text;
}

class Resume : public ::testing::TestWithParam<std::string> {
  protected:
    void SetUp() override {
        std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
        std::replace(name.begin(), name.end(), '/', '_');
        dir_ = fs::temp_directory_path() / ("armour_checkpoint_" + name + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        cache_ = (dir_ / "cache").string();
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path scene(const std::string &text, const std::string &name = "scene.toml") {
        const fs::path file = dir_ / name;
        std::ofstream(file) << text;
        return file;
    }

    std::vector<std::string> args(const fs::path &scene_file, const fs::path &out, bool resume) const {
        std::vector<std::string> a = {"armour",  "run", scene_file.string(), "--out", out.string(),
                                      "--cache", cache_};
        if (resume)
            a.push_back("--resume");
        return a;
    }

    // `armour run` in a child process (an engine may own the process: MPI,
    // LIGGGHTS' exit on error); returns its pid.
    static pid_t start(const std::vector<std::string> &a) {
        std::fflush(nullptr);
        const pid_t pid = ::fork();
        if (pid == 0) {
            std::vector<const char *> argv;
            for (const auto &s : a)
                argv.push_back(s.c_str());
            const int code = armour::armour_main(static_cast<int>(argv.size()), argv.data());
            std::fflush(nullptr);
            ::_exit(code);
        }
        return pid;
    }
    static int wait(pid_t pid) {
        int status = 0;
        while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
        return status;
    }
    static int run(const std::vector<std::string> &a) {
        const int status = wait(start(a));
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    // `armour ...` in this process (a free_body run: no engine owns it), its stderr into `err`.
    static int run_here(std::vector<std::string> a, std::string &err) {
        a.erase(a.begin()); // "armour": output_rule::armour puts it first
        const output_rule::Outcome o = output_rule::armour(a);
        err = o.err;
        return o.code;
    }

    fs::path dir_;
    std::string cache_;
};

json summary_of(const fs::path &out) {
    std::ifstream in(out / "summary.json");
    return json::parse(in);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace

TEST_P(Resume, KilledRunResumedEndsAsTheUninterruptedOne) {
    const fs::path file = scene(drop_scene(GetParam(), 2.0));
    const fs::path reference = dir_ / "reference", killed = dir_ / "killed";

    const auto t0 = std::chrono::steady_clock::now();
    ASSERT_EQ(run(args(file, reference, false)), 0);
    const double wall = seconds_since(t0);

    // Killed at a random moment after its first checkpoint (0.1 s of 2 s);
    // a run that ends first (a quiet machine) is started again and killed sooner.
    std::mt19937 random(std::random_device{}());
    double delay = std::uniform_real_distribution<double>(0.0, 0.4)(random) * wall;
    const auto checkpointed = [&] {
        std::error_code ec;
        for (const auto &e : fs::directory_iterator(killed / "checkpoints", ec))
            if (fs::exists(e.path() / "checkpoint.json"))
                return true;
        return false;
    };
    for (int attempt = 0;; ++attempt) {
        ASSERT_LT(attempt, 6) << "every run ended before it was killed";
        fs::remove_all(killed);
        const pid_t pid = start(args(file, killed, false));
        // Until the first checkpoint, however slow the machine; a run that
        // ended first failed.
        int status = 0;
        pid_t ended = 0;
        while (!checkpointed() && (ended = ::waitpid(pid, &status, WNOHANG)) == 0)
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        ASSERT_EQ(ended, 0) << "the run ended before its first checkpoint";
        std::this_thread::sleep_for(std::chrono::duration<double>(delay));
        ::kill(pid, SIGKILL);
        if (WIFSIGNALED(wait(pid)))
            break;
        delay *= 0.5;
    }
    EXPECT_FALSE(fs::exists(killed / "summary.json"));
    // The --out lock is free once the killed run is reaped: no other process
    // holds its descriptor (MPI's start-up helper, which LIGGGHTS' MPI_Init
    // starts, held it for a moment, and a resume started then was refused as
    // "in use"; output_folder.h).
    {
        const int fd = ::open((killed / ".armour-lock").c_str(), O_RDWR);
        EXPECT_TRUE(fd < 0 || ::flock(fd, LOCK_EX | LOCK_NB) == 0) << "the killed run's lock is still held";
        if (fd >= 0)
            ::close(fd);
    }

    // At most two checkpoints, each whole (partial ones carry a '.' name).
    int kept = 0;
    for (const auto &e : fs::directory_iterator(killed / "checkpoints"))
        if (e.path().filename().string().front() != '.') {
            ++kept;
            EXPECT_TRUE(fs::exists(e.path() / "checkpoint.json")) << e.path();
        }
    EXPECT_GE(kept, 1);
    EXPECT_LE(kept, 2);

    ASSERT_EQ(run(args(file, killed, true)), 0);

    const armour::BodiesFile a = armour::read_bodies_file((reference / "bodies.h5").string());
    const armour::BodiesFile b = armour::read_bodies_file((killed / "bodies.h5").string());
    ASSERT_EQ(b.time.size(), a.time.size()) << "records lost or doubled";
    const double step = summary_of(reference)["dt"].get<double>(); // records fall on whole engine steps
    for (std::size_t s = 0; s < b.time.size(); ++s) {
        EXPECT_DOUBLE_EQ(b.time[s], a.time[s]) << "step " << s;
        if (s > 0) {
            EXPECT_NEAR(b.time[s] - b.time[s - 1], 0.01, step) << "step " << s;
        }
    }
    double largest = 0.0;
    const std::size_t last = a.time.size() - 1;
    for (std::size_t k = 0; k < a.bodies(); ++k) {
        largest = std::max(largest, (b.position[last][k] - a.position[last][k]).norm());
        const double turn =
            2.0 * std::acos(std::min(1.0, std::abs(b.orientation[last][k].dot(a.orientation[last][k]))));
        largest = std::max(largest, 0.5 * kEdge * turn); // how far a corner moves
    }
    // The brief's bound is 1e-3 Dn; every engine continues bit for bit
    // (docs/checkpoints.md), so the resumed run must match exactly.
    EXPECT_LT(largest, 1e-3 * kEdge);
    EXPECT_EQ(largest, 0.0);
    std::printf("[ resume   ] %s: killed %.3f s after the first checkpoint; final poses differ by %.3g m "
                "(%.3g Dn)\n",
                GetParam().c_str(), delay, largest, largest / kEdge);

    json x = summary_of(reference), y = summary_of(killed);
    for (json *j : {&x, &y})
        for (const char *key : {"wall_seconds", "wall_seconds_per_simulated_second", "seconds_per_unit_step"})
            j->erase(key);
    EXPECT_EQ(x, y) << x.dump(1) << "\n" << y.dump(1);
}

TEST_P(Resume, RefusesAChangedSceneAndAFolderWithoutCheckpoint) {
    if (GetParam() != "free_body")
        GTEST_SKIP() << "engine-independent";
    const fs::path file = scene(drop_scene(GetParam(), 0.3));
    const fs::path out = dir_ / "out";
    ASSERT_EQ(run(args(file, out, false)), 0);
    // A longer duration is allowed ...
    const fs::path longer = scene(drop_scene(GetParam(), 0.5), "longer.toml");
    // ... a changed body is not.
    std::string changed_text = drop_scene(GetParam(), 0.3);
    changed_text.replace(changed_text.find("[0, 0, 0.15]"), 12, "[0, 0, 0.16]");
    const fs::path changed = scene(changed_text, "changed.toml");

    ::testing::internal::CaptureStderr();
    std::vector<std::string> a = args(changed, out, true);
    std::vector<const char *> argv;
    for (const auto &s : a)
        argv.push_back(s.c_str());
    EXPECT_NE(armour::armour_main(static_cast<int>(argv.size()), argv.data()), 0);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find("armour: error: " + changed.string() + ": differs from the scene that ran in"),
              std::string::npos)
        << err;
    EXPECT_NE(err.find("0.16"), std::string::npos) << err;
    EXPECT_TRUE(fs::exists(out / "summary.json")) << "a refused resume touched the result";

    ASSERT_EQ(run(args(longer, out, true)), 0);
    const armour::BodiesFile rec = armour::read_bodies_file((out / "bodies.h5").string());
    EXPECT_EQ(rec.time.size(), 51u);
    EXPECT_NEAR(rec.time.back(), 0.5, 1e-9);

    const fs::path fresh = dir_ / "fresh";
    std::string none = drop_scene(GetParam(), 0.05);
    none.replace(none.find("checkpoint_interval = 0.1"), 25, "checkpoint_interval = 0.0");
    const fs::path none_file = scene(none, "none.toml");
    ASSERT_EQ(run(args(none_file, fresh, false)), 0);
    ::testing::internal::CaptureStderr();
    a = args(none_file, fresh, true);
    argv.clear();
    for (const auto &s : a)
        argv.push_back(s.c_str());
    EXPECT_NE(armour::armour_main(static_cast<int>(argv.size()), argv.data()), 0);
    const std::string none_err = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(none_err.find("armour: error: --resume: " + fresh.string() + " holds no complete checkpoint"),
              std::string::npos)
        << none_err;
}

// A run stopped before its end (killed: checkpoints, no summary.json) is
// hours or days of waves: the same command without --resume would replace
// it, so it is refused until the user says --resume or --restart.
TEST_F(Resume, AStoppedRunIsReplacedOnlyWhenAskedTo) { // engine-independent: one engine
    const fs::path file = scene(drop_scene("free_body", 0.3));
    const fs::path out = dir_ / "out";
    ASSERT_EQ(run(args(file, out, false)), 0);
    fs::remove(out / "summary.json"); // as a killed run leaves it: its checkpoints at 0.1 and 0.2 s
    ASSERT_TRUE(armour::last_checkpoint(out).has_value());
    const auto main_with = [&](const std::vector<std::string> &extra, std::string &err) {
        std::vector<std::string> a = args(file, out, false);
        a.insert(a.end(), extra.begin(), extra.end());
        return run_here(a, err);
    };
    std::string err;
    for (const std::vector<std::string> &extra : {std::vector<std::string>{}, {"--dry-run"}}) {
        EXPECT_EQ(main_with(extra, err), 2) << err;
        EXPECT_NE(err.find("armour: error: --out " + out.string() +
                           ": holds a run that stopped at its checkpoint t = 0.2 s (no summary.json): "
                           "--resume continues it, --restart starts again"),
                  std::string::npos)
            << err;
        EXPECT_NEAR(armour::last_checkpoint(out)->time, 0.2, 1e-12) << "a refused run touched the folder";
        EXPECT_TRUE(fs::exists(out / "bodies.h5"));
    }
    EXPECT_EQ(main_with({"--resume", "--restart"}, err), 2) << err;
    EXPECT_NE(err.find("armour: error: --resume and --restart: choose one"), std::string::npos) << err;

    ASSERT_EQ(run([&] {
                  std::vector<std::string> a = args(file, out, false);
                  a.push_back("--restart");
                  return a;
              }()),
              0);
    EXPECT_TRUE(fs::exists(out / "summary.json"));
    // A finished run is replaced by the same command as before, unasked.
    ASSERT_EQ(run(args(file, out, false)), 0);
}

// A resume on a machine whose C library maths rounds otherwise (another
// processor: FMA or not; another glibc) goes on as another realisation of
// the run, not the run itself (docs/validation/robustness.md): it is said,
// once on stderr and in summary.json's warnings of a coupled run, never
// silently. Here the checkpoint's fingerprint is rewritten as another
// machine's would read.
TEST_F(Resume, AResumeWhereTheMathsRoundsOtherwiseIsWarnedOf) { // engine-independent: one engine
    const fs::path file = scene(drop_scene("free_body", 0.3));
    const fs::path out = dir_ / "out";
    ASSERT_EQ(run(args(file, out, false)), 0);
    const std::string here = armour::arithmetic_fingerprint();
    EXPECT_EQ(here.size(), 16u) << here;
    EXPECT_EQ(armour::arithmetic_fingerprint(), here) << "the fingerprint of one process changed";
    EXPECT_EQ(summary_of(out).value("arithmetic", ""), here);
    const auto resume_with = [&](const std::string &theirs, std::string &err) {
        fs::remove(out / "summary.json"); // as a killed run leaves it: its checkpoints at 0.1 and 0.2 s
        const std::optional<armour::Checkpoint> last = armour::last_checkpoint(out);
        if (!last)
            return -1;
        EXPECT_EQ(last->arithmetic, here) << "a checkpoint carries its writer's fingerprint";
        json j = json::parse(std::ifstream(last->dir / "checkpoint.json"));
        j["arithmetic"] = theirs;
        std::ofstream(last->dir / "checkpoint.json") << j.dump(2) << "\n";
        return run_here(args(file, out, true), err);
    };
    std::string err;
    ASSERT_EQ(resume_with(here, err), 0) << err;
    EXPECT_EQ(err.find("rounds otherwise"), std::string::npos) << "the same maths warned of: " << err;

    const std::string theirs = here == "0123456789abcdef" ? "fedcba9876543210" : "0123456789abcdef";
    ASSERT_EQ(resume_with(theirs, err), 0) << err;
    const std::string checkpoint = armour::last_checkpoint(out)->dir.string();
    EXPECT_NE(err.find("armour: warning: --resume: " + checkpoint +
                       " was written where the C library's maths rounds otherwise (another processor or C "
                       "library: checkpoint.json arithmetic " +
                       theirs + ", here " + here + "): the run goes on as another realisation of its case"),
              std::string::npos)
        << err;
    EXPECT_TRUE(fs::exists(out / "summary.json")) << "the warned resume did not finish";
}

// The fingerprint tells the C library's FMA code from its plain x86-64
// code, the difference that parts one command's runs on two machines
// (bench/run_cpu_paths.sh): the armour binary with FMA hidden from glibc
// (GLIBC_TUNABLES, glibc >= 2.33) writes another into summary.json.
TEST_F(Resume, TheFingerprintTellsTheMathsWithoutFma) {
#if defined(__x86_64__)
    // glibc takes its FMA code where the processor has both FMA and AVX2.
    if (!__builtin_cpu_supports("fma") || !__builtin_cpu_supports("avx2"))
        GTEST_SKIP() << "this processor lacks FMA or AVX2: the C library runs its plain code already";
    const fs::path file = scene(drop_scene("free_body", 0.05));
    const std::string command = "GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA " + std::string(ARMOUR_EXE) +
                                " run " + file.string() + " --out " + (dir_ / "no_fma").string() +
                                " --cache " + cache_ + " > " + (dir_ / "no_fma.log").string() + " 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    const std::string theirs = summary_of(dir_ / "no_fma").value("arithmetic", "");
    EXPECT_EQ(theirs.size(), 16u) << theirs;
    EXPECT_NE(theirs, armour::arithmetic_fingerprint())
        << "the maths without FMA gave this process's fingerprint";
#else
    GTEST_SKIP() << "FMA code in glibc's libm is picked on x86-64";
#endif
}

// Checkpoints fall at multiples of the interval and never at the last step,
// so an interval not below the duration writes none: the run says so at its
// start, and a run just longer than one interval writes one and says nothing.
TEST_P(Resume, AnIntervalNotBelowTheDurationIsWarnedOf) {
    const fs::path equal = scene(drop_scene(GetParam(), 0.1), "equal.toml");
    ::testing::internal::CaptureStderr();
    const int equal_code = run(args(equal, dir_ / "equal", false));
    const std::string equal_err = ::testing::internal::GetCapturedStderr();
    ASSERT_EQ(equal_code, 0) << equal_err;
    EXPECT_NE(equal_err.find("armour: warning: run.checkpoint_interval = 0.1 s is not below run.duration = "
                             "0.1 s: no checkpoint is written"),
              std::string::npos)
        << equal_err;
    EXPECT_FALSE(armour::last_checkpoint(dir_ / "equal").has_value());

    const fs::path longer = scene(drop_scene(GetParam(), 0.15), "longer.toml");
    ::testing::internal::CaptureStderr();
    const int longer_code = run(args(longer, dir_ / "longer", false));
    const std::string longer_err = ::testing::internal::GetCapturedStderr();
    ASSERT_EQ(longer_code, 0) << longer_err;
    EXPECT_EQ(longer_err.find("checkpoint_interval"), std::string::npos) << longer_err;
    EXPECT_TRUE(armour::last_checkpoint(dir_ / "longer").has_value());
}

INSTANTIATE_TEST_SUITE_P(Engines, Resume, ::testing::Values("free_body", "bullet", "liggghts"),
                         [](const ::testing::TestParamInfo<std::string> &p) { return p.param; });

// Time folders and postProcessing/ parts are found by their names: a name is
// a time only when all of it is one number (not "uniform", "processor0", a
// name with a suffix, one out of range).
TEST(CheckpointNames, FolderNamesReadAsTheirTime) {
    EXPECT_EQ(armour::time_of_name("30.0037782764934633"), 30.0037782764934633);
    EXPECT_EQ(armour::time_of_name("0"), 0.0);
    EXPECT_EQ(armour::time_of_name(armour::checkpoint_name(0.1)), 0.1);
    for (const char *other : {"", "uniform", "processor0", "0.5x", "0.5 ", "1e999"})
        EXPECT_FALSE(armour::time_of_name(other).has_value()) << '"' << other << '"';
}

// The coupling state the plugin writes and `armour run` reads back: every
// value as written (a resume goes on counting steps and seconds from them),
// and a file of another layout refused naming it rather than read wrongly.
TEST(CouplingState, ReadsBackAsWrittenAndRefusesAnotherLayout) {
    const fs::path dir = fs::temp_directory_path() / ("armour_coupling_state_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const armour::CouplingState written{12.35, 4478, 61.25, 1186.5, 5.125};
    armour::write_coupling_state(dir, written);
    const armour::CouplingState read = armour::read_coupling_state(dir);
    EXPECT_EQ(read.next_record, written.next_record);
    EXPECT_EQ(read.steps, written.steps);
    EXPECT_EQ(read.load_seconds, written.load_seconds);
    EXPECT_EQ(read.dem_seconds, written.dem_seconds);
    EXPECT_EQ(read.mask_seconds, written.mask_seconds);

    armour::write_state_values((dir / "coupling").string(), {1.0, 2.0, 3.0, 4.0});
    try {
        armour::read_coupling_state(dir);
        ADD_FAILURE() << "a state of 4 values was read as a coupling state";
    } catch (const std::exception &e) {
        EXPECT_NE(std::string(e.what()).find((dir / "coupling").string()), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

namespace {

// The checkpoints under OUT/checkpoints that a reader takes (names without a
// leading '.'), each checked whole: its checkpoint.json and its engine state.
std::set<std::string> checkpoint_names(const fs::path &out) {
    std::set<std::string> names;
    std::error_code ec;
    for (const auto &e : fs::directory_iterator(out / "checkpoints", ec)) {
        const std::string name = e.path().filename().string();
        if (name.front() == '.')
            continue;
        EXPECT_TRUE(fs::is_regular_file(e.path() / "checkpoint.json")) << name << " is not whole";
        EXPECT_TRUE(fs::is_regular_file(e.path() / "engine" / "state")) << name << " is not whole";
        names.insert(name);
    }
    return names;
}

// A checkpoint at t whose engine state is a file of its own.
void write_checkpoint(armour::Checkpoints &writer, double t) {
    armour::Checkpoint at;
    at.time = t;
    at.records = std::lround(t * 100);
    writer.write(at, [](const fs::path &dir) { std::ofstream(dir / "engine" / "state") << "state\n"; });
}

struct Killed {};

// Checkpoints at `before` exist (and, with `later`, a copy of the latest
// under that later time, as a killed run could leave); a writer resumed from
// the latest of `before` (none: a fresh run) commits one at t, killed after
// its k-th filesystem step, for every k. At every step and after each kill:
// at most two whole checkpoints, one at least once one existed, none older
// than the resume point as the latest; a writer resumed from what the kill
// left ends with the latest two. Returns the steps of a whole commit.
std::vector<std::string> kill_at_every_step(const fs::path &dir, const std::vector<double> &before,
                                            double later, double t, const std::set<std::string> &after) {
    std::vector<std::string> steps;
    for (std::size_t kill_at = 0;; ++kill_at) {
        SCOPED_TRACE("killed after step " + std::to_string(kill_at));
        const fs::path out = dir / ("kill_" + std::to_string(kill_at));
        fs::remove_all(out);
        double resumed_from = 0.0;
        for (const double b : before) {
            armour::Checkpoints earlier(out, 0.1, resumed_from);
            write_checkpoint(earlier, b);
            resumed_from = b;
        }
        if (later > 0.0) {
            const fs::path copy = out / "checkpoints" / armour::checkpoint_name(later);
            fs::copy(out / "checkpoints" / armour::checkpoint_name(resumed_from), copy,
                     fs::copy_options::recursive);
            std::ofstream(copy / "checkpoint.json") << json{{"time", later}, {"records", 99}}.dump() << "\n";
        }
        armour::Checkpoints writer(out, 0.1, resumed_from);
        steps.clear();
        writer.set_step_hook([&](const std::string &what) {
            steps.push_back(what);
            const std::set<std::string> now = checkpoint_names(out);
            EXPECT_LE(now.size(), 2u) << "at '" << what << "'";
            if (!before.empty() || what == "in place") {
                EXPECT_GE(now.size(), 1u) << "at '" << what << "'";
            }
            if (steps.size() == kill_at + 1)
                throw Killed{};
        });
        try {
            write_checkpoint(writer, t);
        } catch (const Killed &) {
            const std::optional<armour::Checkpoint> last = armour::last_checkpoint(out);
            if (!before.empty()) {
                EXPECT_TRUE(last.has_value());
                EXPECT_GE(last ? last->time : -1.0, resumed_from);
            }
            armour::Checkpoints again(out, 0.1, last ? last->time : 0.0);
            const double next = last ? last->time + 0.1 : t;
            write_checkpoint(again, next);
            std::set<std::string> expected = {armour::checkpoint_name(next)};
            if (last)
                expected.insert(armour::checkpoint_name(last->time));
            EXPECT_EQ(checkpoint_names(out), expected);
            continue;
        }
        EXPECT_EQ(checkpoint_names(out), after);
        std::set<std::string> all;
        for (const auto &e : fs::directory_iterator(out / "checkpoints"))
            all.insert(e.path().filename().string());
        EXPECT_EQ(all, after) << "a partial or set-aside folder stayed";
        return steps;
    }
}

} // namespace

// Rotation, step by step (results/checkpoints.h): the flake was a
// kill between the rename of a third checkpoint into place and the removal
// of the oldest. Every step of a commit is a possible kill point here.
TEST(CheckpointRotation, AKillAtAnyStepLeavesAtMostTwoWholeCheckpoints) {
    const fs::path dir = fs::temp_directory_path() / ("armour_rotation_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    {
        SCOPED_TRACE("third checkpoint");
        const std::vector<std::string> steps = kill_at_every_step(dir, {0.1, 0.2}, 0.0, 0.3, {"0.2", "0.3"});
        EXPECT_EQ(steps, (std::vector<std::string>{"written", "set aside 0.1", "removed 0.1", "in place"}));
    }
    {
        SCOPED_TRACE("first checkpoint");
        const std::vector<std::string> steps = kill_at_every_step(dir, {}, 0.0, 0.1, {"0.1"});
        EXPECT_EQ(steps, (std::vector<std::string>{"written", "in place"}));
    }
    {
        SCOPED_TRACE("a later one a killed run left");
        const std::vector<std::string> steps = kill_at_every_step(dir, {0.2}, 0.3, 0.25, {"0.2", "0.25"});
        EXPECT_EQ(steps, (std::vector<std::string>{"written", "set aside 0.3", "removed 0.3", "in place"}));
    }
    // A folder half removed under a set-aside name is never taken as a
    // checkpoint, and the next checkpoint removes it.
    const fs::path out = dir / "half";
    armour::Checkpoints writer(out, 0.1);
    write_checkpoint(writer, 0.1);
    const fs::path half = out / "checkpoints" / ".partial-drop-1-0";
    fs::create_directories(half);
    std::ofstream(half / "checkpoint.json") << "{\"time\": 9, \"records\": 900}\n";
    ASSERT_TRUE(armour::last_checkpoint(out).has_value());
    EXPECT_EQ(armour::last_checkpoint(out)->time, 0.1);
    write_checkpoint(writer, 0.2);
    EXPECT_FALSE(fs::exists(half));
    EXPECT_EQ(checkpoint_names(out), (std::set<std::string>{"0.1", "0.2"}));
    if (!::testing::Test::HasFailure())
        fs::remove_all(dir);
}

// The interFoam plugin asks for a checkpoint two steps before it is whole
// (Checkpoints::due_ahead): one per interval, at the first step at or after
// each multiple, and none whose two further steps would not end before the
// run does. Steps of 0.01 s over 0.1 s intervals; no folder is written.
std::vector<double> started_times(double end) {
    armour::Checkpoints timing(fs::path("/nonexistent"), 0.1);
    std::vector<double> started;
    for (int k = 0; k * 0.01 < end; ++k) {
        const double t = k * 0.01;
        if (timing.due_ahead(t, 0.01, end, 2)) {
            started.push_back(t);
            timing.started(t);
        }
    }
    return started;
}

TEST(CheckpointTiming, AWriterThatCommitsLaterStartsOncePerIntervalAndNotAtTheEnd) {
    const std::vector<double> whole = started_times(0.5);
    ASSERT_EQ(whole.size(), 4u); // 0.1 .. 0.4: at 0.5 the run ends
    for (std::size_t i = 0; i < whole.size(); ++i)
        EXPECT_NEAR(whole[i], 0.1 * static_cast<double>(i + 1), 1e-12);
    // At 0.4 the two steps (and half a step to spare) end at 0.425 > 0.42.
    EXPECT_EQ(started_times(0.42).size(), 3u);
    EXPECT_EQ(started_times(0.43).size(), 4u);
}
