// `armour run SCENE --out DIR [--set key=value ...] [--np N] [--resume]`.
#pragma once

#include <string>
#include <vector>

namespace armour {

struct RunRequest {
    std::string scene;
    std::string out;
    std::vector<std::string> overrides; // --set key=value
    std::string cache;                  // clump cache folder; empty = default
    int np = 0;                         // MPI ranks of a coupled run; 0 = the scene's fluid.np
    bool resume = false;                // continue DIR from its last checkpoint (docs/checkpoints.md)
};

// Returns the exit status (0 on success); throws InputError before anything
// is written when the scene cannot run.
int run_scene(const RunRequest &request);

} // namespace armour
