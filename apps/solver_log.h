// What an OpenFOAM solver's log (OUT/case/log.interFoam) tells a run.
//
// Description
//     Read from the text interFoam writes: its first FOAM FATAL message (a
//     failed tool's one line), the time of the step being solved (progress),
//     the number of steps, its CPU clock per step and the largest Courant
//     numbers it reported, every cell's and the free surface's (0.01 < alpha
//     < 0.99), and the steps that passed the run's Courant limits. Times in s.
//
// Usage
//     const std::string log = read_text_file(case_dir / "log.interFoam");
//     const SolverLogFigures figures = solver_log_figures(log, {max_courant, max_interface_courant,
//     max_time_step});
#pragma once

#include <optional>
#include <string>

namespace armour {

// The first FOAM FATAL message of a log, as one line ("" when none).
std::string fatal_line(const std::string &log);

// Last "Time = t" of a solver log (the step being solved), 0 when none.
double last_solver_time(const std::string &log);

// A Courant limit passed by more than 10 %. interFoam sets each step from
// the Courant number of the step before, so a flow that speeds up passes the
// limit for a step; after a step at max_time_step (the cap, not the Courant
// number, set it) the overshoot can be any size.
struct CourantOvershoot {
    int steps = 0;              // steps whose Courant number passed 1.1 x the limit
    int after_capped_steps = 0; // of them, those that followed a step of max_time_step
};

// The run's limits, to count the overshoots (0: not counted).
struct SolverLimits {
    double max_courant = 0.0;
    double max_interface_courant = 0.0;
    double max_time_step = 0.0; // s
};

struct SolverLogFigures {
    int steps = 0;                              // "Time = " lines
    std::optional<double> cpu_seconds_per_step; // ExecutionTime from the first step's end to the last
    double courant_max = 0.0;                   // "Courant Number ... max:"
    double interface_courant_max = 0.0;         // "Interface Courant Number ... max:"
    CourantOvershoot courant_over, interface_courant_over;
};
SolverLogFigures solver_log_figures(const std::string &log, const SolverLimits &limits = {});

} // namespace armour
