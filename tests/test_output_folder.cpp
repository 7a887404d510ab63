// One command at a time in an output folder (docs/outputs.md): the lock on
// --out, and what a killed command leaves (its staging folder, its lock file)
// going with the next command into the folder, never anything of the user's.
#include "input_error.h"
#include "output_folder.h"
#include "output_folder_rule.h"
#include "scratch_folder.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

extern char **environ;

namespace fs = std::filesystem;
using armour::OutputFolder;

namespace {

class OutputLock : public ::testing::Test {
  protected:
    void SetUp() override { dir_ = armour_test::fresh_test_folder("lock"); }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
};

// The message of the InputError `make` throws ("" if none).
template <class Make> std::string refusal(Make make) {
    try {
        make();
    } catch (const armour::InputError &e) {
        return e.what();
    }
    return "";
}

// `armour args...` as a process of its own, stderr into `err`.
pid_t spawn_armour(std::vector<std::string> args, const fs::path &err) {
    args.insert(args.begin(), ARMOUR_BINARY);
    std::vector<char *> argv;
    for (std::string &a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    pid_t pid = -1;
    const int failed = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    return failed ? -1 : pid;
}

int exit_status(pid_t pid) {
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// A child that holds `out` (as a command at work does) until killed.
pid_t holder(const fs::path &out, OutputFolder::Mode mode) {
    int ready[2];
    if (::pipe(ready) != 0)
        return -1;
    const pid_t pid = ::fork();
    if (pid == 0) {
        OutputFolder folder(out, "armour clump", mode);
        folder.open();
        armour::write_text_file(folder.claim("clump.spheres"), "half\n");
        const char ok = 1;
        if (::write(ready[1], &ok, 1) != 1)
            ::_exit(1);
        for (;;)
            ::pause();
    }
    char ok = 0;
    ::close(ready[1]);
    const bool started = ::read(ready[0], &ok, 1) == 1;
    ::close(ready[0]);
    return started ? pid : -1;
}

} // namespace

TEST_F(OutputLock, ASecondCommandIsRefusedNamingTheHolder) {
    const fs::path out = dir_ / "result";
    OutputFolder first(out, "armour run", OutputFolder::Mode::streaming);
    const std::string why = refusal([&] { OutputFolder(out, "armour run", OutputFolder::Mode::streaming); });
    EXPECT_EQ(why, "--out " + out.string() + ": in use by another armour command (pid " +
                       std::to_string(::getpid()) + "); wait for it to end or choose another folder");
    // Another command's folder is refused for the lock as well, untouched.
    EXPECT_NE(refusal([&] { OutputFolder(out, "armour clump", OutputFolder::Mode::staged); }).find("in use"),
              std::string::npos);
    EXPECT_EQ(output_rule::names(out), std::set<std::string>{".armour-lock"});
}

TEST_F(OutputLock, AFailedCommandRemovesTheFolderItCreated) {
    const fs::path out = dir_ / "new" / "deeper" / "result";
    {
        OutputFolder folder(out, "armour clump", OutputFolder::Mode::staged);
        folder.open();
        EXPECT_TRUE(fs::is_directory(out));
        armour::write_text_file(folder.claim("summary.json"), "{}\n");
    } // fails before commit()
    EXPECT_EQ(output_rule::names(dir_), std::set<std::string>{});
    {
        OutputFolder folder(out, "armour run", OutputFolder::Mode::streaming);
    } // fails before open(), e.g. on the scene
    EXPECT_FALSE(fs::exists(dir_ / "new"));
    // An existing empty folder stays (it may be the shell's `--out .`).
    fs::create_directories(out);
    { OutputFolder folder(out, "armour clump", OutputFolder::Mode::staged); }
    EXPECT_TRUE(fs::is_directory(out));
    EXPECT_EQ(output_rule::names(out), std::set<std::string>{});
}

TEST_F(OutputLock, AKilledHolderLetsGoAndItsLeftoversAreRemoved) {
    for (const auto mode : {OutputFolder::Mode::staged, OutputFolder::Mode::streaming}) {
        const bool staged = mode == OutputFolder::Mode::staged;
        SCOPED_TRACE(staged ? "staged" : "streaming");
        const fs::path out = dir_ / (staged ? "staged" : "streaming");
        const pid_t pid = holder(out, mode);
        ASSERT_GT(pid, 0);
        const std::string why = refusal([&] { OutputFolder(out, "armour clump", mode); });
        EXPECT_NE(why.find("(pid " + std::to_string(pid) + ")"), std::string::npos) << why;
        const std::string partial = ".armour-partial-" + std::to_string(pid);
        EXPECT_EQ(fs::exists(out / partial), staged);

        ::kill(pid, SIGKILL); // no destructor, no cleanup: what a killed command leaves
        EXPECT_EQ(exit_status(pid), 128 + SIGKILL);
        EXPECT_TRUE(fs::exists(out / ".armour-lock"));
        {
            OutputFolder next(out, "armour clump", mode);
            next.open();
            EXPECT_FALSE(fs::exists(out / partial));
            armour::write_text_file(next.claim("summary.json"), "{}\n");
            next.commit();
        }
        EXPECT_EQ(output_rule::names(out), (std::set<std::string>{".armour-output", "summary.json"}));
    }
}

TEST_F(OutputLock, AnOldSiblingStagingFolderIsNamedNeverRemoved) {
    // Earlier versions staged a new DIR in DIR.partial-PID: it may be a
    // killed run's, or a user's folder that happens to be named so.
    const pid_t gone = ::fork();
    if (gone == 0)
        ::_exit(0);
    ASSERT_EQ(exit_status(gone), 0);
    const fs::path out = dir_ / "result", old = dir_ / ("result.partial-" + std::to_string(gone));
    fs::create_directories(old);
    std::ofstream(old / "summary.json") << "{}\n";
    ::testing::internal::CaptureStderr();
    { OutputFolder folder(out, "armour run", OutputFolder::Mode::streaming); }
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(
        err.rfind("armour: warning: " + old.string() + " looks like what a killed earlier armour left", 0),
        0u)
        << err;
    EXPECT_EQ(output_rule::read(old / "summary.json"), "{}\n");
}

// The real thing: two `armour demo` processes into one --out. The second is
// refused at once, while the first works on, and the first completes. The
// first is held still (SIGSTOP) while the second tries, so a slow start of
// the second cannot let the first end before it.
TEST_F(OutputLock, TwoCommandsIntoOneFolder) {
    const fs::path out = dir_ / "demo";
    const pid_t first = spawn_armour({"demo", "--out", out.string()}, dir_ / "first.err");
    ASSERT_GT(first, 0);
    // The first holds the folder once its pid is in the lock file.
    int status = 0;
    pid_t ended = 0;
    while (output_rule::read(out / ".armour-lock") != std::to_string(first) + "\n" &&
           (ended = ::waitpid(first, &status, WNOHANG)) == 0)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_EQ(ended, 0) << output_rule::read(dir_ / "first.err");
    ::kill(first, SIGSTOP);
    const pid_t second = spawn_armour({"demo", "--out", out.string()}, dir_ / "second.err");
    ASSERT_GT(second, 0);
    EXPECT_EQ(exit_status(second), 2);
    EXPECT_EQ(::waitpid(first, &status, WNOHANG), 0) << "the first ended before the second was refused";
    ::kill(first, SIGCONT);
    EXPECT_EQ(output_rule::read(dir_ / "second.err"),
              "armour: error: --out " + out.string() + ": in use by another armour command (pid " +
                  std::to_string(first) + "); wait for it to end or choose another folder\n");
    EXPECT_EQ(exit_status(first), 0) << output_rule::read(dir_ / "first.err");
    EXPECT_TRUE(fs::is_regular_file(out / "summary.json"));
    EXPECT_EQ(output_rule::names(out),
              (std::set<std::string>{".armour-output", "cube", "dolos", "summary.json"}));
}

// A coupled run with a wrong WM_PROJECT_DIR, or without OpenFOAM's tools, is
// refused before anything is written: one line naming the variable, no new
// folder, an earlier result untouched.
TEST_F(OutputLock, AWrongOpenFoamIsRefusedBeforeAnythingIsWritten) {
    const std::string scene = (fs::path(ARMOUR_SOURCE_DIR) / "scenes" / "buoyancy_cube.toml").string();
    const std::string cache = (dir_ / "cache").string();
    const fs::path earlier = dir_ / "earlier";
    fs::create_directories(earlier);
    std::ofstream(earlier / ".armour-output") << "armour run\nsummary.json\n";
    std::ofstream(earlier / "summary.json") << "{}\n";
    struct Case {
        const char *variable, *value, *settle, *says;
    };
    const char *path = std::getenv("PATH");
    const std::string saved_path = path ? path : "";
    for (const Case &c :
         {Case{"WM_PROJECT_DIR", "/no/such/openfoam", "0",
               "armour: error: WM_PROJECT_DIR: /no/such/openfoam: not an OpenFOAM installation"},
          Case{"WM_PROJECT_DIR", "/tmp", "0.05", "armour: error: WM_PROJECT_DIR: /tmp: not an"},
          Case{"PATH", "/no/such/bin", "0", "armour: error: blockMesh not found on PATH"}}) {
        SCOPED_TRACE(std::string(c.variable) + "=" + c.value + ", settle " + c.settle);
        ::setenv(c.variable, c.value, 1);
        for (const fs::path &out : {dir_ / "new", earlier}) {
            const output_rule::Outcome o =
                output_rule::armour({"run", scene, "--out", out.string(), "--cache", cache, "--set",
                                     std::string("fluid.settle_time=") + c.settle});
            EXPECT_EQ(o.code, 2) << o.err;
            const std::size_t at = o.err.find(c.says);
            EXPECT_NE(at, std::string::npos) << o.err;
            EXPECT_EQ(o.err.find('\n', at), o.err.size() - 1) << o.err; // one line, the last
        }
        EXPECT_FALSE(fs::exists(dir_ / "new"));
        EXPECT_EQ(output_rule::names(earlier), (std::set<std::string>{".armour-output", "summary.json"}));
        EXPECT_EQ(output_rule::read(earlier / "summary.json"), "{}\n");
        if (std::string(c.variable) == "PATH")
            ::setenv("PATH", saved_path.c_str(), 1);
        else
            ::unsetenv(c.variable);
    }
}

// The case: `armour compare` killed with -9 mid-way. It leaves only
// hidden names of ours inside --out (no sibling DIR.partial-PID), and the
// next compare into the folder completes and leaves nothing of it behind.
TEST_F(OutputLock, AKilledCompareIsCleanedUpByTheNext) {
    const auto scene = [](const char *duration) {
        return std::string("name = \"tiny\"\n[run]\nduration = ") + duration +
               "\noutput_interval = 0.005\ndomain_min = [-1, -1, -0.5]\n"
               "domain_max = [1, 1, 1.5]\n[analysis]\nkind = \"bounce\"\n[[material]]\nname = \"concrete\"\n"
               "[[unit]]\nname = \"cube\"\nshape = \"cube\"\nsize = 0.2\nspheres = 8\n"
               "[[wall]]\nname = \"floor\"\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nsize = "
               "2\n"
               "[[body]]\nunit = \"cube\"\nposition = [0, 0, 0.4]\n";
    };
    const fs::path out = dir_ / "out", slow = dir_ / "slow.toml", quick = dir_ / "quick.toml";
    std::ofstream(slow) << scene("30.0");
    std::ofstream(quick) << scene("0.05");
    const std::string cache = (dir_ / "cache").string();
    const pid_t killed = spawn_armour({"compare", slow.string(), "--spheres", "4", "--dt-factors", "1",
                                       "--out", out.string(), "--cache", cache},
                                      dir_ / "killed.err");
    ASSERT_GT(killed, 0);
    const fs::path partial = out / (".armour-partial-" + std::to_string(killed));
    int status = 0;
    pid_t ended = 0;
    while (!fs::exists(partial / "runs") && (ended = ::waitpid(killed, &status, WNOHANG)) == 0)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_EQ(ended, 0) << output_rule::read(dir_ / "killed.err");
    std::this_thread::sleep_for(std::chrono::milliseconds(500)); // well inside its 30 s runs
    ::kill(killed, SIGKILL);
    ASSERT_EQ(exit_status(killed), 128 + SIGKILL);
    EXPECT_EQ(output_rule::names(out),
              (std::set<std::string>{".armour-lock", ".armour-partial-" + std::to_string(killed)}));

    const output_rule::Outcome next =
        output_rule::armour({"compare", quick.string(), "--spheres", "4", "--dt-factors", "1", "--out",
                             out.string(), "--cache", cache});
    ASSERT_EQ(next.code, 0) << next.err;
    for (const std::string &name : output_rule::names(out))
        EXPECT_EQ(name.find(".armour-partial-"), std::string::npos) << name;
    EXPECT_FALSE(fs::exists(out / ".armour-lock"));
    EXPECT_TRUE(fs::is_regular_file(out / "summary.json"));
    for (const std::string &name : output_rule::names(dir_))
        EXPECT_EQ(name.find("out.partial-"), std::string::npos) << name;
}

// A run reads its solver's log as it grows (a long run's log.interFoam
// grows by ~100 MB in 20 min; every step is checked against the step floor):
// each whole line comes back once, in order, and a line still being written
// waits for its end.
TEST(ReadNewLines, GivesEachWholeLineOfAGrowingLogOnce) {
    const fs::path path =
        fs::temp_directory_path() / ("armour_growing_" + std::to_string(::getpid()) + ".log");
    std::uintmax_t offset = 0;
    EXPECT_EQ(armour::read_new_lines(path, offset), ""); // not there yet
    EXPECT_EQ(offset, 0u);
    std::ofstream out(path, std::ios::binary);
    out << "deltaT = 0.005\nTime = 0.005\n\ndeltaT = 0.0" << std::flush;
    EXPECT_EQ(armour::read_new_lines(path, offset), "deltaT = 0.005\nTime = 0.005\n\n");
    EXPECT_EQ(armour::read_new_lines(path, offset), ""); // "deltaT = 0.0" is not a whole line
    out << "01\nTime = 0.006\n" << std::flush;
    EXPECT_EQ(armour::read_new_lines(path, offset), "deltaT = 0.001\nTime = 0.006\n");
    EXPECT_EQ(offset, fs::file_size(path));
    EXPECT_EQ(armour::read_new_lines(path, offset), "");
    fs::remove(path);
}
