#include "foam_tool.h"

#include "input_error.h"
#include "output_folder.h"
#include "scene_keys.h"
#include "solver_log.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <sstream>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace armour {

namespace fs = std::filesystem;

namespace {

// The processes whose parent is `parent`, from /proc (zombies too).
std::vector<pid_t> children_of(pid_t parent) {
    std::vector<pid_t> children;
    std::error_code ec;
    for (const auto &entry : fs::directory_iterator("/proc", ec)) {
        const std::string name = entry.path().filename().string();
        if (name.find_first_not_of("0123456789") != std::string::npos)
            continue;
        std::ifstream in(entry.path() / "stat");
        const std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        // "pid (comm) state ppid ...": comm may hold spaces and brackets.
        const std::size_t close = stat.rfind(')');
        if (close == std::string::npos)
            continue;
        std::istringstream rest(stat.substr(close + 1));
        char state = 0;
        long ppid = 0;
        if (rest >> state >> ppid && ppid == parent)
            children.push_back(static_cast<pid_t>(std::stol(name)));
    }
    return children;
}

// Stops a tool (mpirun passes the signal to its ranks) and reaps it.
void stop_tool(pid_t pid) {
    ::kill(pid, SIGTERM);
    for (int naps = 0; naps < 1000; ++naps) { // 10 s, then for good
        if (::waitpid(pid, nullptr, WNOHANG) != 0)
            return;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
}

// Ends what a tool left behind. An mpirun that ends, or is stopped, before
// its ranks leaves them to this process, their subreaper (start_tool), so
// that `armour run` returns only once nothing of the solver works in the
// case: SIGTERM, 10 s for them all, then SIGKILL. Called once the tool is
// reaped, when this process's only children are what it left.
void end_left_behind() {
    std::vector<pid_t> left = children_of(::getpid());
    for (const pid_t p : left)
        ::kill(p, SIGTERM);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (!left.empty() && std::chrono::steady_clock::now() < deadline) {
        left.erase(std::remove_if(left.begin(), left.end(),
                                  [](pid_t p) {
                                      const pid_t done = ::waitpid(p, nullptr, WNOHANG);
                                      return done == p || (done < 0 && errno != EINTR);
                                  }),
                   left.end());
        if (!left.empty())
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    for (const pid_t p : left) {
        ::kill(p, SIGKILL);
        while (::waitpid(p, nullptr, 0) < 0 && errno == EINTR) {
        }
    }
}

// Starts `args` in case_dir, its output into `log`, tied to this process:
// interFoam is the run (the engine lives in its plugin), so killed alone,
// `armour run` must not leave it going on to the end in the background
// (mpirun passes the signal to its ranks).
pid_t start_tool(const std::string &name, const std::vector<std::string> &args, const fs::path &case_dir,
                 const fs::path &log) {
    std::vector<char *> argv;
    for (const auto &a : args)
        argv.push_back(const_cast<char *>(a.c_str()));
    argv.push_back(nullptr);
    const std::string dir = case_dir.string(), log_path = log.string();
    const pid_t armour = ::getpid();
    ::prctl(PR_SET_CHILD_SUBREAPER, 1); // the ranks an mpirun leaves fall to this process: end_left_behind
    const pid_t pid = ::fork();
    if (pid < 0)
        throw InputError(name + ": cannot start: " + std::strerror(errno));
    if (pid == 0) {
        if (::prctl(PR_SET_PDEATHSIG, SIGTERM) != 0 || ::getppid() != armour)
            ::_exit(127);
        const int fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd < 0 || ::chdir(dir.c_str()) != 0)
            ::_exit(127);
        ::dup2(fd, STDOUT_FILENO);
        ::dup2(fd, STDERR_FILENO);
        inherit_output_locks(); // the folder stays locked while it may write into it
        ::execvp(argv[0], argv.data());
        ::_exit(127);
    }
    return pid;
}

// Why a tool that ended with `status` and wrote `text` failed: its FOAM FATAL
// line, or else its last three lines (and the signal that ended it); empty
// when it did not fail. mpirun may exit 0 although a rank reported FOAM FATAL.
std::string tool_failure(int status, const std::string &text, const std::string &program) {
    const std::string fatal = fatal_line(text);
    const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (ok || !fatal.empty())
        return fatal;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
        return "could not run " + program;
    std::istringstream in(text);
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);)
        if (!l.empty())
            lines.push_back(l);
    std::string why;
    for (std::size_t i = lines.size() > 3 ? lines.size() - 3 : 0; i < lines.size(); ++i)
        why += (why.empty() ? "" : " | ") + lines[i];
    if (WIFSIGNALED(status))
        why = "killed by signal " + std::to_string(WTERMSIG(status)) + (why.empty() ? "" : ": " + why);
    if (why.empty() && WIFEXITED(status))
        why = "exit status " + std::to_string(WEXITSTATUS(status)) + ", nothing in its log";
    return why;
}

} // namespace

void run_tool(const std::string &name, const std::vector<std::string> &args, const fs::path &case_dir,
              double end_time, bool show_progress, double start_time, const StepFloor &floor) {
    const fs::path log = case_dir / ("log." + name);
    const pid_t pid = start_tool(name, args, case_dir, log);
    const bool terminal = ::isatty(STDERR_FILENO) != 0;
    // The log is read as it grows, each line once (a long run's log reaches
    // 100 MB): every step is checked against the floor, so a dip between two
    // looks counts as much as a collapse.
    std::uintmax_t log_read = 0;
    const auto check_floor = [&](const std::string &lines, double solver_time_now, bool running) {
        if (floor.min_time_step <= 0.0)
            return;
        const SolverStep step = smallest_time_step(lines);
        if (step.time_step <= 0.0 || step.time_step >= floor.min_time_step)
            return;
        if (running)
            stop_tool(pid);
        end_left_behind();
        if (show_progress && terminal)
            std::fputc('\n', stderr);
        throw InputError(floor.scene_file + ": key 'fluid.min_time_step': " + name + "'s step fell to " +
                         figure_text(step.time_step) +
                         " s at t = " + figure_text(step.time > 0.0 ? step.time : solver_time_now) +
                         " s, below " + number_text(floor.min_time_step) +
                         " s: the flow diverged or the pressure solve stopped converging (see " +
                         log.string() + ")" + (running ? "; the run was stopped there" : ""));
    };
    const auto start = std::chrono::steady_clock::now();
    SolverProgress progress(start_time, end_time);
    double solver_time = start_time; // until the solver's first "Time =" line
    int status = 0;
    long naps = 0;
    for (;;) {
        const pid_t done = ::waitpid(pid, &status, WNOHANG);
        if (done == pid)
            break;
        if (done < 0 && errno != EINTR)
            throw InputError(name + ": lost the process: " + std::strerror(errno));
        // Short naps, so that the wall time measured around a tool is good to
        // ~10 ms; the log is read for progress every 250 ms only.
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        if ((!show_progress && floor.min_time_step <= 0.0) || ++naps % 25 != 0)
            continue;
        const std::string lines = read_new_lines(log, log_read);
        const double t = solver_time = std::max(solver_time, last_solver_time("\n" + lines));
        check_floor(lines, t, true);
        if (!show_progress)
            continue;
        const double fraction = std::min(1.0, t / end_time);
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (terminal)
            std::fprintf(stderr, "\r[%-30s] t = %.3f / %.3f s  ETA %.0f s ",
                         std::string(static_cast<std::size_t>(30 * fraction), '#').c_str(), t, end_time,
                         progress.seconds_left(t, elapsed).value_or(0.0));
        else if (const std::string line = progress.line(t, elapsed); !line.empty())
            std::fputs(line.c_str(), stderr);
    }
    end_left_behind();
    check_floor(read_new_lines(log, log_read), solver_time, false);
    if (show_progress && terminal)
        std::fputc('\n', stderr);
    if (const std::string why = tool_failure(status, read_text_file(log), args[0]); !why.empty())
        throw InputError(name + " failed (see " + log.string() + "): " + why);
}

} // namespace armour
