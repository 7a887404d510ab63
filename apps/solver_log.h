// What an OpenFOAM solver's log (OUT/case/log.interFoam) tells a run.
//
// Description
//     Read from the text interFoam writes: its first FOAM FATAL message (a
//     failed tool's one line), the time of the step being solved (progress),
//     the number of steps, its CPU clock per step and the largest Courant
//     numbers it reported, every cell's and the free surface's (0.01 < alpha
//     < 0.99). Times in s.
//
// Usage
//     const std::string log = read_text_file(case_dir / "log.interFoam");
//     const SolverLogFigures figures = solver_log_figures(log);
#pragma once

#include <optional>
#include <string>

namespace armour {

// The first FOAM FATAL message of a log, as one line ("" when none).
std::string fatal_line(const std::string &log);

// Last "Time = t" of a solver log (the step being solved), 0 when none.
double last_solver_time(const std::string &log);

struct SolverLogFigures {
    int steps = 0;                              // "Time = " lines
    std::optional<double> cpu_seconds_per_step; // ExecutionTime from the first step's end to the last
    double courant_max = 0.0;                   // "Courant Number ... max:"
    double interface_courant_max = 0.0;         // "Interface Courant Number ... max:"
};
SolverLogFigures solver_log_figures(const std::string &log);

} // namespace armour
