// `armour run SCENE --out DIR [--set key=value ...] [--np N] [--resume] [--restart] [--dry-run]`.
#pragma once

#include <string>
#include <vector>

namespace armour {

struct Scene;

struct RunRequest {
    std::string scene;
    std::string out;
    std::vector<std::string> overrides; // --set key=value
    std::string cache;                  // clump cache folder; empty = default
    int np = 0;                         // MPI ranks of a coupled run; 0 = the scene's fluid.np
    bool resume = false;                // continue DIR from its last checkpoint (docs/checkpoints.md)
    bool restart = false;               // replace a run DIR holds that stopped before its end
    bool dry_run = false;               // every check of a run, a plan on stdout, nothing written to DIR
    bool settle_only = false;           // the settle a coupled run starts with, and its layer's figures

    // --cache, or the default folder (ARMOUR_CACHE, XDG_CACHE_HOME, ~/.cache) when it is not given.
    std::string cache_dir() const;
};

// Returns the exit status (0 on success); throws InputError before anything
// is written when the scene cannot run.
int run_scene(const RunRequest &request);

// What `armour run` checks before it writes anything, short of running: the
// placed scene (units, clumps, placement), the engine's step against its
// contact stability limit, and for a scene with [fluid] its case (template,
// mesh, waves, gauges, OpenFOAM's tools; check_coupled_scene) on `np` ranks
// (0: the scene's fluid.np). `armour sweep` checks every case with it before
// any runs. Throws InputError; returns the warnings.
std::vector<std::string> check_scene_runs(const Scene &scene, const std::string &cache_dir, int np);

// Why `--settle-only` cannot run this scene ("key 'fluid.settle_time': ..."),
// or "" when it settles its units before the waves. `armour run` and
// `armour sweep --settle-only` refuse with it.
std::string settle_only_refusal(const Scene &scene);

// The scene's keys with those a resume may change (run.duration, the
// checkpoint interval, the Courant limits, the ranks; docs/checkpoints.md)
// set to fixed values: a run of one scene goes on from a checkpoint of
// another with the same text (`armour run --resume` compares them).
std::string resume_key_text(const Scene &scene);

} // namespace armour
