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
//     interFoam start from it; the plugin finds the checkpoint of the start
//     time and restores the engine, the coupler and the record.
//
// Usage
//     write_fields_exactly(case_dir);                    // a new case with checkpoints
//     restore_case(case_dir, checkpoint, scene.duration); // a resumed one
#pragma once

#include "checkpoints.h"

#include <filesystem>

namespace armour {

void write_fields_exactly(const std::filesystem::path &case_dir);

void restore_case(const std::filesystem::path &case_dir, const Checkpoint &checkpoint, double end_time);

} // namespace armour
