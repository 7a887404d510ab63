// `armour sweep SWEEP.toml --out DIR [--set KEY=VALUE]... [--executor local|slurm] [--jobs N]
//  [--dry-run] [--retry-failed] [--no-wait] [--kept KEPT] [--cases ID,...] [--seeds S,...] [--np N]
//  [--settle-only]` and
//  `armour sweep --collect DIR`.
//
// Description
//     Runs every case of a sweep file (sweep_file.h, docs/sweeps.md) as its own
//     `armour run`, in DIR/cases/<id>/, locally or as one Slurm job array;
//     keeps DIR/results.csv and DIR/summary.json current as cases finish and
//     ends with DIR/report.md (charts by sweep_report.py). Every case's scene
//     is checked before anything runs. Running the same command again resumes:
//     finished cases with the same scene hash are skipped, failed ones are run
//     again only with --retry-failed; with --kept, the finished cases that a
//     folder of studies/keep_results.py holds (same scene) are copied in and
//     skipped. --cases runs only the named cases now (the others stay as they
//     are, for a later sweep into the same DIR): a long study taken a few
//     cases a sitting, in the order its user needs them. --set overrides a
//     scene key for every case after the sweep file's [set] (a shorter
//     run.duration for a trial); --np sets the MPI ranks of every case in place
//     of the file's [run] np (a case resumed with other ranks than it ran
//     with goes on from its checkpoint; the scene hash, and so what counts as
//     done, does not depend on the ranks). --settle-only runs each case's settle alone
//     (`armour run --settle-only`: the layer its waves would meet, about a
//     minute a case): many seeds' layers judged before hours of waves; its
//     DIR holds settles only (a sweep with waves into it is refused).
//
// Usage
//     SweepRequest r;  r.sweep_file = "studies/tilt_friction.toml";  r.out = "tilt-sweep";
//     return run_sweep(r);   // 0 when every case (of --cases, when given) is done
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace armour {

struct SweepRequest {
    std::string sweep_file;
    std::string out;
    std::vector<std::string> overrides; // --set KEY=VALUE: every case, after the file's [set]
    std::string executor = "local";     // local | slurm
    int jobs = 0;                       // local: parallel cases (--jobs, >= 1); 0 = not given: cores / np
    bool dry_run = false;
    bool retry_failed = false;
    bool no_wait = false;            // slurm: submit and return
    std::string kept;                // DIR of studies/keep_results.py: its done cases count as done here
    std::vector<std::string> cases;  // --cases: only these case ids run now; empty: every case
    std::vector<std::int64_t> seeds; // --seeds: in place of the sweep file's seeds; empty: the file's
    int np = 0;                      // --np: MPI ranks per case in place of [run] np; 0 = not given
    std::string collect;             // DIR: gather a sweep submitted earlier
    std::string run_case;            // internal: run one case folder (what each executor starts)
    bool settle_only = false;        // --settle-only: each case `armour run --settle-only`
};

// Adds the `sweep` subcommand to `app`, filling `request`.
CLI::App *add_sweep_command(CLI::App &app, SweepRequest &request);

int run_sweep(const SweepRequest &request);

} // namespace armour
