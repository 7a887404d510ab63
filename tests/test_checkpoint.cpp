// Checkpoints and `armour run --resume` (docs/checkpoints.md): a run killed
// with SIGKILL at a random point after its first checkpoint, then resumed,
// ends as the same run uninterrupted: the same record times (no record lost
// or doubled), the same final poses (bit for bit, within the brief's 1e-3
// Dn), the same summary but for wall times. And a resume refuses what it
// cannot continue.
#include "bodies_file.h"
#include "checkpoints.h"
#include "cli.h"

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
#include <random>
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
        const auto started = std::chrono::steady_clock::now();
        const pid_t pid = start(args(file, killed, false));
        while (!checkpointed()) {
            ASSERT_LT(seconds_since(started), 30.0 + 10.0 * wall) << "no first checkpoint";
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
        std::this_thread::sleep_for(std::chrono::duration<double>(delay));
        ::kill(pid, SIGKILL);
        if (WIFSIGNALED(wait(pid)))
            break;
        delay *= 0.5;
    }
    EXPECT_FALSE(fs::exists(killed / "summary.json"));
    // The --out lock is free only once every process holding its descriptor
    // has ended: MPI's singleton start (LIGGGHTS) forks a helper that inherits
    // it and outlives the killed run for a moment; a resume started then is
    // refused as "in use".
    const auto unlocked = [&] {
        const int fd = ::open((killed / ".armour-lock").c_str(), O_RDWR);
        if (fd < 0)
            return true;
        const bool free = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
        ::close(fd);
        return free;
    };
    for (const auto since_kill = std::chrono::steady_clock::now(); !unlocked();) {
        ASSERT_LT(seconds_since(since_kill), 30.0) << "the killed run's lock is still held";
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
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
