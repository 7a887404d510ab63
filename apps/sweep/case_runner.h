// One case of a sweep, run in its own process: DIR/cases/<id>/.
//
// Description
//     The case folder holds the resolved case scene (scene.toml), the plan
//     (plan.json: values, scene hash, np, timeout), the sweep's record of it (case.json: status, attempts,
//     scene hash, wall time, why it failed), the run's log (log.txt, every attempt appended), a lock file and
//     run/, the `armour run` output folder (summary.json, bodies.h5, ...).
//     run_case() takes the case's lock (flock: a second sweep on the same
//     folder skips a case that is running), counts the attempt, starts
//     `armour run scene.toml --out run` as a child in its own process group,
//     waits (killing the group at the sweep's per-case timeout or when this
//     process is told to stop) and records the outcome. Both executors start
//     it as `armour sweep --run-case DIR/cases/<id>`, so a crash or an MPI
//     abort in the run never takes the sweep down, and a sweep killed even
//     with kill -9 loses only the cases that were running: their children die
//     with it (PR_SET_PDEATHSIG) and their lock is free again.
//
// Usage
//     CaseRecord r = read_case_record(dir);       // status "pending" when never started
//     bool busy = case_is_locked(dir);
//     int status = run_case(dir, "/path/to/armour"); // 0 done, 1 failed, 75 locked
#pragma once

#include <filesystem>
#include <string>

namespace armour {

struct CaseRecord {
    std::string id;
    std::string scene_hash;
    std::string resume_hash;        // of the keys a resume may not change (SweepCase::resume_hash)
    double duration = 0.0;          // s, the run.duration of the last attempt
    std::string status = "pending"; // pending | running | done | failed
    int attempts = 0;               // times the case was started
    double wall_seconds = 0.0;      // s, of the last attempt
    double resumed_from = 0.0;      // s of simulated time the last attempt resumed from (0: from the start)
    std::string reason;             // why the last attempt failed, e.g. "exit status 2", "timeout after 60 s"
    double started = 0.0, finished = 0.0; // s since the epoch
    std::string host;
    std::string slurm_job;   // "JOBID_TASK" when a Slurm array task ran it
    std::string slurm_state; // Slurm's state for a task that did not finish normally
};

inline constexpr int kCaseLocked = 75; // run_case: another process holds the case

CaseRecord read_case_record(const std::filesystem::path &case_dir);
void write_case_record(const std::filesystem::path &case_dir, const CaseRecord &record);

// True while some process holds the case's lock (the case is running).
bool case_is_locked(const std::filesystem::path &case_dir);

// Runs the case planned in case_dir/plan.json (scene_hash, np, timeout).
int run_case(const std::filesystem::path &case_dir, const std::string &armour_exe);

// The last `lines` lines of the case's log.
std::string log_tail(const std::filesystem::path &case_dir, int lines);
// The same of any text file, each line indented.
std::string log_tail_of(const std::filesystem::path &file, int lines);

} // namespace armour
