// What an OpenFOAM solver's log (OUT/case/log.interFoam) tells a run.
//
// Description
//     Read from the text interFoam writes: its first FOAM FATAL message (a
//     failed tool's one line), the time of the step being solved (progress),
//     the number of steps, its CPU clock per step and the largest Courant
//     numbers it reported, every cell's and the free surface's (0.01 < alpha
//     < 0.99), the steps that passed the run's Courant limits, and the
//     smallest step of a part of the log (the step floor). Times in s.
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

// The smallest "deltaT = dt" of whole lines of a solver log, and the
// "Time = t" after it (the time that step reached; 0 if not in `lines`), s.
// time_step 0: no step in `lines`.
struct SolverStep {
    double time_step = 0.0;
    double time = 0.0;
};
SolverStep smallest_time_step(const std::string &lines);

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

// The progress lines of a solver from `start` to `end` (s of simulated time;
// a resume starts at its checkpoint): the wall time left is the rest of the
// run at the pace of this part (its elapsed wall time over the simulated
// time it made), so the earlier parts of a resumed run do not count as
// made in this one. A line (to a log, not a terminal) is due at every
// tenth of this part and at least every `every_wall` s.
class SolverProgress {
  public:
    SolverProgress(double start, double end, double every_wall = 600.0);
    // Wall s left at the pace so far; nullopt before the solver moved.
    std::optional<double> seconds_left(double t, double elapsed) const;
    // The line to write at solver time t after `elapsed` wall s, "" when none is due.
    std::string line(double t, double elapsed);

  private:
    double start_, end_, every_wall_;
    double next_fraction_ = 0.1, last_line_wall_ = 0.0;
};

} // namespace armour
