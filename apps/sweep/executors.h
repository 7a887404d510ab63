// The two ways a sweep runs its cases; both start each case as
// `armour sweep --run-case DIR/cases/<id>` (case_runner.h).
//
// Description
//     local: a pool of `jobs` case processes on this machine; returns when
//     every case has finished. slurm: one sbatch script with a job array
//     (DIR/slurm/array.sbatch, task i runs line i+1 of DIR/slurm/cases.txt),
//     submitted with sbatch and followed with squeue; the final state of each
//     task comes from sacct where accounting is on, else from scontrol.
//     Both rewrite results.csv, summary.json and report.md as cases finish and
//     print the progress line with an ETA from the cases finished so far.
//
// Usage
//     run_local(ctx, to_run, jobs);
//     check_slurm_reachable();                   // before anything is written
//     std::string job = submit_slurm(ctx, to_run, false);
//     follow_slurm(ctx, job);
#pragma once

#include "sweep_table.h"

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace armour {

struct SweepContext {
    std::filesystem::path out;
    SweepPlan plan;
    std::string armour_exe;   // absolute path of the armour executable
    std::string executor;     // "local" | "slurm"
    bool settle_only = false; // each case runs its settle alone (armour run --settle-only)
};

// The MPI ranks a case runs on: [run] np, one for a settle alone.
inline int ranks_per_case(const SweepContext &ctx) {
    return ctx.settle_only ? 1 : std::max(1, ctx.plan.spec.np);
}

// Reads the cases' folders, writes the tables and returns them.
SweepTable refresh_tables(const SweepContext &ctx, const std::set<std::string> &skipped);

// DIR/report.md and DIR/figures/ from DIR/summary.json (apps/sweep/sweep_report.py):
// rewritten as each case ends and when the sweep ends. A warning, not an error,
// where python3 or matplotlib is missing: the tables are complete without them.
void write_report(const std::filesystem::path &out);

void run_local(const SweepContext &ctx, const std::vector<std::size_t> &to_run, int jobs,
               const std::set<std::string> &skipped);

// Throws InputError "--executor: slurm: ..." when no controller answers.
void check_slurm_reachable();
// The sbatch script for the cases `to_run` (indices into plan.cases).
std::string slurm_script(const SweepContext &ctx, std::size_t tasks);
// Writes DIR/slurm/{cases.txt,array.sbatch,job.json}, submits, returns the job id.
std::string submit_slurm(const SweepContext &ctx, const std::vector<std::size_t> &to_run);
// The job id of DIR/slurm/job.json while Slurm lists it (or cannot answer); "" once it has ended.
std::string slurm_job_in_queue(const std::filesystem::path &out);
// Follows the job until Slurm no longer lists it, then records each task's end.
void follow_slurm(const SweepContext &ctx, const std::set<std::string> &skipped);

// Seconds an ETA estimate expects: mean wall time of the cases of this
// invocation that ran whole (not resumed from a checkpoint) x cases left /
// parallel workers; -1 before any such case finishes.
double estimate_eta(const std::vector<CaseRecord> &finished, int left, int parallel);

} // namespace armour
