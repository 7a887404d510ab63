// The local executor: a pool of case processes on this machine.
#include "executors.h"

#include "input_error.h"
#include "output_folder.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numeric>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace armour {

namespace fs = std::filesystem;

double estimate_eta(const std::vector<CaseRecord> &finished, int left, int parallel) {
    std::vector<double> walls;
    for (const CaseRecord &r : finished)
        if (r.resumed_from == 0.0) // a resumed case ran only its end
            walls.push_back(r.wall_seconds);
    if (walls.empty())
        return -1.0;
    const double mean = std::accumulate(walls.begin(), walls.end(), 0.0) / static_cast<double>(walls.size());
    return mean * static_cast<double>(left) / static_cast<double>(std::max(1, parallel));
}

void write_report(const fs::path &out) {
    const std::string command = std::string("/usr/bin/python3 '") + ARMOUR_SOURCE_DIR +
                                "/apps/sweep/sweep_report.py' '" + out.string() + "' >&2";
    std::fflush(nullptr);
    if (std::system(command.c_str()) != 0)
        std::fprintf(stderr,
                     "armour: warning: %s: the report's charts could not be drawn (python3 + "
                     "matplotlib); results.csv and summary.json are complete\n",
                     (out / "report.md").c_str());
}

SweepTable refresh_tables(const SweepContext &ctx, const std::set<std::string> &skipped) {
    SweepTable table = read_sweep_table(ctx.out, ctx.plan);
    table.skipped = skipped;
    write_sweep_tables(ctx.out, ctx.plan, table, ctx.executor);
    return table;
}

namespace {

volatile std::sig_atomic_t stop_requested = 0;
extern "C" void on_stop_request(int) {
    stop_requested = 1;
}

pid_t start_case(const SweepContext &ctx, const fs::path &dir) {
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        // A sweep killed (even with kill -9) takes its running cases with it.
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        std::string exe = ctx.armour_exe, sweep = "sweep", flag = "--run-case", path = dir.string();
        char *argv[] = {exe.data(), sweep.data(), flag.data(), path.data(), nullptr};
        inherit_output_locks(); // the folder stays locked while it may write into it
        ::execv(exe.c_str(), argv);
        ::_exit(127);
    }
    return pid;
}

} // namespace

void run_local(const SweepContext &ctx, const std::vector<std::size_t> &to_run, int jobs,
               const std::set<std::string> &skipped) {
    std::map<pid_t, std::size_t> running; // process -> case index
    std::vector<CaseRecord> finished;
    std::size_t next = 0;
    int elsewhere = 0;
    auto last_print = std::chrono::steady_clock::now() - std::chrono::seconds(10);
    const bool terminal = ::isatty(STDERR_FILENO) != 0;
    std::string last_line;
    bool changed = true;
    bool report_due = false; // a case ended since report.md was written
    // Ctrl-C or SIGTERM: no new cases; the running ones are stopped, put
    // back to pending by their runners, and the tables written whole.
    stop_requested = 0;
    std::signal(SIGINT, on_stop_request);
    std::signal(SIGTERM, on_stop_request);
    bool stopping = false;
    while ((next < to_run.size() && !stopping) || !running.empty()) {
        if (stop_requested && !stopping) {
            stopping = true;
            for (const auto &[pid, index] : running)
                ::kill(pid, SIGTERM);
            std::fprintf(stderr, "\nsweep: stopping: %zu running case(s) are stopped and left pending\n",
                         running.size());
        }
        while (!stopping && next < to_run.size() && static_cast<int>(running.size()) < jobs) {
            const std::size_t index = to_run[next++];
            const pid_t pid = start_case(ctx, case_dir(ctx.out, ctx.plan.cases[index]));
            if (pid < 0)
                throw InputError("--jobs: cannot start a case process (fork failed)");
            running[pid] = index;
            changed = true;
        }
        int status = 0;
        const pid_t done = ::waitpid(-1, &status, WNOHANG);
        if (done > 0 && running.count(done)) {
            const SweepCase &c = ctx.plan.cases[running[done]];
            running.erase(done);
            changed = true;
            const CaseRecord r = read_case_record(case_dir(ctx.out, c));
            if (WIFEXITED(status) && WEXITSTATUS(status) == kCaseLocked) {
                ++elsewhere;
                std::fprintf(stderr, "sweep: case %s is running in another sweep, left to it\n",
                             c.id.c_str());
            } else if (r.status == "done") {
                finished.push_back(r);
            } else if (r.status == "failed") {
                std::fprintf(stderr, "%ssweep: case %s failed (%s); log %s:\n%s", terminal ? "\n" : "",
                             c.id.c_str(), r.reason.c_str(), (case_dir(ctx.out, c) / "log.txt").c_str(),
                             log_tail(case_dir(ctx.out, c), 5).c_str());
            }
            report_due = r.status == "done" || r.status == "failed";
        }
        const auto now = std::chrono::steady_clock::now();
        if (changed || now - last_print > std::chrono::seconds(terminal ? 1 : 30)) {
            const SweepTable table = refresh_tables(ctx, skipped);
            // A case that ended has its row in report.md and its point on the
            // charts before the next starts: a study of days is read as it goes.
            if (report_due)
                write_report(ctx.out);
            report_due = false;
            const int left = static_cast<int>(to_run.size() - next) + static_cast<int>(running.size());
            const std::string line = progress_line(table, estimate_eta(finished, left, jobs));
            if (terminal)
                std::fprintf(stderr, "\r%-78s", line.c_str());
            else if (line != last_line)
                std::fprintf(stderr, "%s\n", line.c_str());
            last_line = line;
            last_print = now;
            changed = false;
        }
        if (done <= 0)
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    if (terminal)
        std::fputc('\n', stderr);
    if (elsewhere > 0)
        std::fprintf(stderr, "sweep: %d case(s) were running in another sweep of this folder\n", elsewhere);
}

} // namespace armour
