#include "case_runner.h"

#include "checkpoints.h"
#include "input_error.h"
#include "output_folder.h"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <ctime>
#include <deque>
#include <fcntl.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace armour {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

volatile std::sig_atomic_t stop_signal = 0;
extern "C" void on_stop(int sig) {
    stop_signal = sig;
}

double now_seconds() {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// The lock is held as long as the descriptor is open in this process; the
// kernel releases it when the process dies, however it dies.
int take_lock(const fs::path &case_dir) {
    const int fd = ::open((case_dir / "lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
        return -1;
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
        ::close(fd);
        return -1;
    }
    return fd;
}

// A case's lock for one attempt: released on every way out of run_case, a
// throw included (an unreadable plan, a record it cannot write), not only at
// the process' end.
class CaseLock {
  public:
    explicit CaseLock(const fs::path &case_dir) : fd_(take_lock(case_dir)) {}
    ~CaseLock() {
        if (fd_ >= 0)
            ::close(fd_);
    }
    CaseLock(const CaseLock &) = delete;
    CaseLock &operator=(const CaseLock &) = delete;
    bool held() const { return fd_ >= 0; }

  private:
    int fd_;
};

// Whether a series stopped in `run` goes on from its steps, and from where
// (`from`, s of the series' simulated time): its steps done (their own
// simulated time) and the last checkpoint of the first step not done. Not
// before its settle has ended (no run/series: the run starts again). A series
// checkpoints in its steps' folders (run/series/<k>/), not in run/ itself.
bool series_resume_point(const fs::path &run, double &from) {
    from = 0.0;
    if (!fs::is_directory(run / "series"))
        return false;
    for (int k = 1;; ++k) {
        const fs::path step = run / "series" / std::to_string(k);
        std::ifstream in(step / "summary.json");
        const json summary = in ? json::parse(in, nullptr, false) : json();
        if (summary.is_object() && summary.contains("simulated_seconds") &&
            summary["simulated_seconds"].is_number()) {
            from += summary["simulated_seconds"].get<double>();
            continue;
        }
        if (const std::optional<Checkpoint> c = last_checkpoint(step))
            from += c->time;
        return true;
    }
}

std::string host_name() {
    char name[256] = {};
    ::gethostname(name, sizeof name - 1);
    return name;
}

} // namespace

CaseRecord read_case_record(const fs::path &case_dir) {
    CaseRecord r;
    r.id = case_dir.filename().string();
    std::ifstream in(case_dir / "case.json");
    if (!in)
        return r;
    try {
        const json j = json::parse(in);
        r.scene_hash = j.value("scene_hash", "");
        r.resume_hash = j.value("resume_hash", "");
        r.duration = j.value("duration", 0.0);
        r.status = j.value("status", "pending");
        r.attempts = j.value("attempts", 0);
        r.wall_seconds = j.value("wall_seconds", 0.0);
        r.resumed_from = j.value("resumed_from", 0.0);
        r.reason = j.value("reason", "");
        r.started = j.value("started", 0.0);
        r.finished = j.value("finished", 0.0);
        r.host = j.value("host", "");
        r.slurm_job = j.value("slurm_job", "");
        r.slurm_state = j.value("slurm_state", "");
    } catch (const json::exception &) {
        r.status = "pending"; // a record cut short is a case to run again
    }
    return r;
}

void write_case_record(const fs::path &case_dir, const CaseRecord &r) {
    const json j = {{"case", r.id},
                    {"scene_hash", r.scene_hash},
                    {"resume_hash", r.resume_hash},
                    {"duration", r.duration},
                    {"status", r.status},
                    {"attempts", r.attempts},
                    {"wall_seconds", r.wall_seconds},
                    {"resumed_from", r.resumed_from},
                    {"reason", r.reason},
                    {"started", r.started},
                    {"finished", r.finished},
                    {"host", r.host},
                    {"slurm_job", r.slurm_job},
                    {"slurm_state", r.slurm_state},
                    {"si_units",
                     {{"wall_seconds", "s"},
                      {"resumed_from", "s"},
                      {"duration", "s"},
                      {"started", "s since 1970-01-01 UTC"}}}};
    write_text_file(case_dir / "case.json", j.dump(2) + "\n");
}

bool case_is_locked(const fs::path &case_dir) {
    if (!fs::exists(case_dir / "lock"))
        return false;
    const int fd = take_lock(case_dir);
    if (fd < 0)
        return true;
    ::close(fd);
    return false;
}

std::string log_tail(const fs::path &case_dir, int lines) {
    return log_tail_of(case_dir / "log.txt", lines);
}

std::string log_tail_of(const fs::path &file, int lines) {
    std::ifstream in(file);
    std::deque<std::string> last;
    for (std::string line; std::getline(in, line);) {
        last.push_back(line);
        if (static_cast<int>(last.size()) > lines)
            last.pop_front();
    }
    std::string out;
    for (const auto &l : last)
        out += "    " + l + "\n";
    return out;
}

namespace {

// How an attempt starts: from its run's last checkpoint, from its series'
// steps, or again from the start.
struct Start {
    std::optional<Checkpoint> checkpoint;
    bool series = false;
    double series_from = 0.0; // s: the series' simulated time its steps reached
};

// A case stopped before it ended (killed, timed out, a Slurm time limit)
// goes on from its run's last checkpoint when its scene is the same or
// differs only in keys a resume may change; a finished one only to run
// longer (more waves without running the first again). A checkpoint at or
// past the new end: from the start. A stopped series goes on from its
// steps (those done are kept, the settle with them).
Start how_to_start(const fs::path &case_dir, const CaseRecord &r, const json &plan) {
    const double duration = plan.value("duration", 0.0);
    const bool same =
        r.scene_hash == plan.value("scene_hash", "") || r.scene_hash == plan.value("earlier_scene_hash", "-");
    const bool resumable = !r.resume_hash.empty() && r.resume_hash == plan.value("resume_hash", "") &&
                           (r.status != "done" || r.duration < duration);
    const bool goes_on = r.attempts > 0 && (same || resumable);
    Start start;
    start.checkpoint = goes_on ? last_checkpoint(case_dir / "run") : std::nullopt;
    if (start.checkpoint && duration > 0.0 && start.checkpoint->time >= duration)
        start.checkpoint.reset();
    start.series = goes_on && r.status != "done" && series_resume_point(case_dir / "run", start.series_from);
    return start;
}

// The record of an attempt that starts now, written before the run starts.
void record_attempt(const fs::path &case_dir, CaseRecord &r, const json &plan, const Start &start) {
    r.scene_hash = plan.value("scene_hash", "");
    r.resume_hash = plan.value("resume_hash", "");
    r.duration = plan.value("duration", 0.0);
    r.status = "running";
    r.attempts += 1;
    r.resumed_from = start.checkpoint ? start.checkpoint->time : start.series_from;
    r.reason.clear();
    r.slurm_state.clear();
    r.started = now_seconds();
    r.finished = 0.0;
    r.host = host_name();
    if (const char *job = std::getenv("SLURM_ARRAY_JOB_ID"))
        r.slurm_job = std::string(job) + "_" +
                      (std::getenv("SLURM_ARRAY_TASK_ID") ? std::getenv("SLURM_ARRAY_TASK_ID") : "");
    write_case_record(case_dir, r);
    std::ofstream header(case_dir / "log.txt", std::ios::app);
    std::string resumed;
    if (start.checkpoint)
        resumed = ", resumed from its checkpoint at t = " + checkpoint_name(start.checkpoint->time) + " s";
    else if (start.series)
        resumed =
            ", its series resumed at t = " + checkpoint_name(start.series_from) + " s (the steps done kept)";
    header << "=== armour sweep: attempt " << r.attempts << " on " << r.host << resumed << " ===\n";
}

// `args` as a child in its own process group, its output appended to `log`;
// it dies with this process. Returns its pid (< 0: fork failed).
pid_t start_child(std::vector<std::string> args, const fs::path &log) {
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::setpgid(0, 0);
        ::prctl(PR_SET_PDEATHSIG, SIGKILL); // the runner killed, the run dies too
        const int out = ::open(log.c_str(), O_WRONLY | O_APPEND | O_CREAT, 0644);
        const int null = ::open("/dev/null", O_RDONLY);
        if (out < 0 || null < 0)
            ::_exit(126);
        ::dup2(null, 0);
        ::dup2(out, 1);
        ::dup2(out, 2);
        std::vector<char *> argv;
        argv.reserve(args.size() + 1);
        for (auto &a : args)
            argv.push_back(a.data());
        argv.push_back(nullptr);
        inherit_output_locks(); // the folder stays locked while it may write into it
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    if (pid > 0)
        ::setpgid(pid, pid);
    return pid;
}

// Waits for the child; a stop signal to this process, or `timeout` (s, 0:
// none) passed, sends its process group SIGTERM, and SIGKILL 5 s later.
// Returns its wait status; `timed_out` says whether the timeout stopped it.
int wait_child(pid_t pid, double timeout, bool &timed_out) {
    const auto start = std::chrono::steady_clock::now();
    int status = 0;
    double killed_at = -1.0;
    timed_out = false;
    for (;;) {
        const pid_t done = ::waitpid(pid, &status, WNOHANG);
        if (done == pid || (done < 0 && errno != EINTR))
            break;
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (killed_at < 0.0 && (stop_signal != 0 || (timeout > 0.0 && elapsed > timeout))) {
            timed_out = stop_signal == 0;
            ::kill(-pid, SIGTERM);
            killed_at = elapsed;
        } else if (killed_at >= 0.0 && elapsed > killed_at + 5.0) {
            ::kill(-pid, SIGKILL);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return status;
}

// The attempt's outcome and its reason, from how the run ended; returns
// whether the run succeeded (a stopped case is put back to pending even then).
bool record_outcome(CaseRecord &r, pid_t pid, int status, bool timed_out, double timeout, bool wrote_summary,
                    const std::string &armour_exe) {
    const bool ok = pid > 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0 && wrote_summary;
    r.status = ok ? "done" : "failed";
    if (pid < 0)
        r.reason = "cannot start a process (fork failed)";
    else if (timed_out) {
        std::ostringstream text;
        text << "timeout after " << timeout << " s (run.timeout)";
        r.reason = text.str();
    } else if (stop_signal != 0) {
        r.reason = "stopped by signal " + std::to_string(stop_signal);
        // Interrupted by hand: the case is not broken, the next sweep runs it
        // again. Under Slurm a signal means a time limit or scancel: failed.
        if (!std::getenv("SLURM_JOB_ID"))
            r.status = "pending";
    } else if (WIFSIGNALED(status))
        r.reason = "killed by signal " + std::to_string(WTERMSIG(status));
    else if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
        r.reason = "cannot start " + armour_exe;
    else if (WIFEXITED(status) && WEXITSTATUS(status) != 0)
        r.reason = "exit status " + std::to_string(WEXITSTATUS(status));
    else if (!ok)
        r.reason = "the run wrote no summary.json";
    return ok;
}

} // namespace

int run_case(const fs::path &case_dir, const std::string &armour_exe) {
    const CaseLock lock(case_dir);
    if (!lock.held())
        return kCaseLocked;
    CaseRecord r = read_case_record(case_dir);
    std::ifstream plan_in(case_dir / "plan.json");
    const json plan = json::parse(plan_in, nullptr, false);
    if (plan.is_discarded())
        throw InputError((case_dir / "plan.json").string() + ": cannot read the case's plan");
    const Start start = how_to_start(case_dir, r, plan);
    record_attempt(case_dir, r, plan, start);
    std::vector<std::string> args = {armour_exe, "run", (case_dir / "scene.toml").string(), "--out",
                                     (case_dir / "run").string()};
    if (plan.value("settle_only", false)) {
        // A settle alone: one rank, nothing to resume; its OutputFolder replaces what an earlier
        // attempt left in run/ (armour's own folder).
        args.emplace_back("--settle-only");
    } else {
        if (const int np = plan.value("np", 0); np > 0) {
            args.push_back("--np");
            args.push_back(std::to_string(np));
        }
        // Without a checkpoint (or a series' steps) of the same scene the run starts again, replacing
        // whatever an earlier attempt left in run/.
        args.emplace_back(start.checkpoint || start.series ? "--resume" : "--restart");
    }
    std::signal(SIGTERM, on_stop);
    std::signal(SIGINT, on_stop);
    std::signal(SIGHUP, on_stop);
    const auto began = std::chrono::steady_clock::now();
    const pid_t pid = start_child(args, case_dir / "log.txt");
    const double timeout = plan.value("timeout", 0.0);
    bool timed_out = false;
    const int status = pid > 0 ? wait_child(pid, timeout, timed_out) : 0;
    r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    r.finished = now_seconds();
    const bool ok = record_outcome(r, pid, status, timed_out, timeout,
                                   fs::is_regular_file(case_dir / "run" / "summary.json"), armour_exe);
    write_case_record(case_dir, r);
    return ok ? 0 : 1;
}

} // namespace armour
