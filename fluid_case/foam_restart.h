// Restarting an interFoam case of a coupled run from a checkpoint (docs/checkpoints.md).
//
// Description
//     A checkpoint of a coupled run holds the fluid's time folder as
//     OpenFOAM wrote it (the plugin asks for a one-shot write, see
//     coupling/openfoam/armourCheckpoint.H); the case then writes binary at
//     full precision, and names its time folders with 17 digits (OpenFOAM
//     restarts at the time the folder's name reads as), so the restart reads
//     back the fields and the clock to the bit.
//     restore_case puts that folder back, removes the later time folders the
//     killed run wrote (ours: the case folder is the run's), and makes
//     interFoam start from it without projecting the checkpoint's flux phi
//     again (system/fvSolution pcorr: no iteration; phi is the live run's);
//     the plugin finds the checkpoint of the start time and restores the
//     engine, the coupler and the record.
//
// Usage
//     write_fields_exactly(case_dir);                    // a new case with checkpoints
//     const RestoredCase restored = restore_case(case_dir, checkpoint, scene.duration); // a resumed one
//     if (restored.ranks != np) { /* reconstructPar, */ set_ranks(case_dir, np); /* decomposePar */ }
#pragma once

#include "checkpoints.h"

#include <filesystem>
#include <map>
#include <string>

namespace armour {

void write_fields_exactly(const std::filesystem::path &case_dir);

// The ranks a coupled run's checkpoint holds its fields split over (1: not split).
int checkpoint_ranks(const Checkpoint &checkpoint);

struct RestoredCase {
    int ranks = 1;         // the ranks its fields are split over (processor<N>/), 1 when not split
    std::string time_name; // the checkpoint's time folder, as the case names it
};
RestoredCase restore_case(const std::filesystem::path &case_dir, const Checkpoint &checkpoint,
                          double end_time);

// A resume on another number of ranks splits the fields anew (decomposePar
// after reconstructPar): system/decomposeParDict for `ranks` along x.
void set_ranks(const std::filesystem::path &case_dir, int ranks);

// `text` with every @TOKEN@ of `tokens` replaced by its value, token by
// token in the map's order (a value put in is not searched for its own token).
std::string filled(std::string text, const std::map<std::string, std::string> &tokens);

// A resume runs with this armour's plugin and wave library and writes into
// the folder it is given, not the run's first: the build that started a
// long run may be gone (removed, moved, an installed copy) and the run's
// folder may have been moved or copied. Every entry of the case template's
// system/ and constant/ files whose value holds one of `tokens`
// (@ARMOUR_PLUGIN@, @OUTPUT@, ...) is set anew in the case, the tokens filled.
void refill_paths(const std::filesystem::path &case_dir, const std::filesystem::path &template_dir,
                  const std::map<std::string, std::string> &tokens);

// The fluid controls a resume may change (controlDict maxCo, maxAlphaCo:
// fluid.max_courant, max_interface_courant; writeInterval: fluid.write_interval, s).
void set_resumable_controls(const std::filesystem::path &case_dir, double every_cell, double free_surface,
                            double write_interval);

} // namespace armour
