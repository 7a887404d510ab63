// A sweep file: which scene, which keys vary over which values, how each case runs.
//
// Description
//     TOML, SI units (docs/sweeps.md). Keys:
//       scene = "path"                 the base scene, relative to the sweep file's folder
//       seeds = [1, 2]                 repeats; each case runs once per seed
//       seed_key = "drop.0.seed"       scene key(s) a seed sets (default: every [[drop]]'s seed)
//       [vary]  "KEY" = [values]       cartesian product over all keys (KEY as --set takes it)
//       [[case]] "KEY" = value         explicit combinations, added to the product
//       [set]   "KEY" = value          overrides applied to every case
//       [run]   np, timeout (s)        MPI ranks per case (coupled scenes), per-case wall limit
//       [slurm] partition, time, memory, cpus_per_case, max_concurrent, extra
//     Values are kept as TOML text, exactly as `armour run --set KEY=VALUE` takes them.
//     Every failure throws InputError "FILE: key 'a.b': reason".
//
// Usage
//     SweepSpec spec = read_sweep_file("studies/tilt_friction.toml");
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace armour {

// One scene key and a value as TOML text ("0.3", "\"liggghts\"").
using KeyValue = std::pair<std::string, std::string>;

struct SweepSlurm {
    std::string partition;          // "" = the cluster's default
    std::string time;               // per task, Slurm syntax ("01:00:00"); "" = the partition's
    std::string memory;             // per task, Slurm syntax ("4G"); "" = the partition's
    int cpus_per_case = 0;          // 0 = the sweep's np (or 1)
    int max_concurrent = 0;         // %M of --array; 0 = no limit
    std::vector<std::string> extra; // further "#SBATCH ..." options, e.g. "--account=coastal"
};

struct SweepSpec {
    std::string file;                                                   // the sweep file as given
    std::string scene;                                                  // absolute path of the base scene
    std::vector<std::pair<std::string, std::vector<std::string>>> vary; // [vary], in file order
    std::vector<std::vector<KeyValue>> cases;                           // [[case]]
    std::vector<KeyValue> fixed;                                        // [set]
    std::vector<std::int64_t> seeds;
    std::vector<std::string> seed_keys; // empty: every [[drop]]'s seed
    int np = 0;                         // MPI ranks per case; 0 = the scene's
    std::string np_option;              // the option that set np, for errors (--np); empty: [run] np
    double timeout = 0.0;               // s of wall time per case; 0 = none
    SweepSlurm slurm;
};

SweepSpec read_sweep_file(const std::string &path);

} // namespace armour
