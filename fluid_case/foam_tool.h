// Runs an OpenFOAM tool in a case folder, its output to log.<tool>, watched.
//
// Description
//     The tool runs as a child (killed with armour, mpirun passing the signal
//     to its ranks); its log gives a progress line (a bar on a terminal, a
//     line every tenth of the run otherwise) and, for a solver, every step it
//     took: a step below the floor (fluid.min_time_step) stops it at once. A
//     diverged flow or a pressure solve that no longer converges does not end
//     interFoam: it goes on at ever smaller steps (1e-25 s was seen) and the
//     run would never end. A tool that fails, or logs FOAM FATAL (mpirun may
//     exit 0 after one), or falls below the floor is one InputError line.
//
// Usage
//     run_tool("blockMesh", {"blockMesh"}, case_dir, duration, false);
//     run_tool("interFoam", {"interFoam"}, case_dir, duration, true, resume_time,
//              {scene.fluid->min_time_step, scene.file});
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace armour {

// A solver's step below min_time_step stops the run (0: not watched).
struct StepFloor {
    double min_time_step = 0.0; // s
    std::string scene_file;     // named in the error
};

// Runs `args` in `case_dir`; progress from start_time (a resume's checkpoint)
// to end_time (s of simulated time). Throws InputError on failure.
void run_tool(const std::string &name, const std::vector<std::string> &args,
              const std::filesystem::path &case_dir, double end_time, bool show_progress,
              double start_time = 0.0, const StepFloor &floor = {});

} // namespace armour
