#include "solver_log.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <regex>
#include <sstream>
#include <string_view>
#include <vector>

namespace armour {

namespace {

// The number after `prefix` on a log line that starts with it ("deltaT = 0.001").
std::optional<double> number_after(const std::string &line, std::string_view prefix) {
    if (line.rfind(prefix, 0) != 0)
        return std::nullopt;
    return std::atof(line.c_str() + prefix.size());
}

} // namespace

std::string fatal_line(const std::string &log) {
    const auto at = log.find("FOAM FATAL");
    if (at == std::string::npos)
        return "";
    std::istringstream in(log.substr(at));
    std::string line, out;
    for (int n = 0; n < 8 && std::getline(in, line);) {
        line = std::regex_replace(line, std::regex("\\s+"), " ");
        if (line.empty() || line == " ")
            continue;
        out += (out.empty() ? "" : " ") + line;
        ++n;
    }
    return std::regex_replace(out, std::regex("\\s+"), " ");
}

double last_solver_time(const std::string &log) {
    const auto at = log.rfind("\nTime = ");
    return at == std::string::npos ? 0.0 : std::atof(log.c_str() + at + 8);
}

SolverStep smallest_time_step(const std::string &lines) {
    SolverStep smallest;
    bool reached = true; // the smallest step's "Time =" line was read
    std::istringstream in(lines);
    for (std::string line; std::getline(in, line);) {
        if (const auto dt = number_after(line, "deltaT = ")) {
            if (*dt > 0.0 && (smallest.time_step == 0.0 || *dt < smallest.time_step)) {
                smallest = {*dt, 0.0};
                reached = false;
            }
        } else if (const auto t = number_after(line, "Time = "); t && !reached) {
            smallest.time = *t;
            reached = true;
        }
    }
    return smallest;
}

SolverProgress::SolverProgress(double start, double end, double every_wall)
    : start_(start), end_(end), every_wall_(every_wall) {}

std::optional<double> SolverProgress::seconds_left(double t, double elapsed) const {
    if (t <= start_ || elapsed <= 0.0)
        return std::nullopt;
    return std::max(0.0, end_ - t) * elapsed / (t - start_);
}

std::string SolverProgress::line(double t, double elapsed) {
    const double part = end_ > start_ ? std::clamp((t - start_) / (end_ - start_), 0.0, 1.0) : 1.0;
    if (part < next_fraction_ && elapsed - last_line_wall_ < every_wall_)
        return "";
    while (next_fraction_ <= part)
        next_fraction_ += 0.1;
    last_line_wall_ = elapsed;
    const std::optional<double> left = seconds_left(t, elapsed);
    const std::string eta = left ? "ETA " + std::to_string(std::lround(*left)) + " s" : "ETA unknown";
    char text[160];
    std::snprintf(text, sizeof text, "run: t = %.3f / %.3f s (%3.0f %%), %.0f s wall, %s\n", t, end_,
                  100.0 * std::min(1.0, t / end_), elapsed, eta.c_str());
    return text;
}

SolverLogFigures solver_log_figures(const std::string &log, const SolverLimits &limits) {
    SolverLogFigures figures;
    // interFoam's own CPU clock after each step (the master rank's, the
    // plugin's work included): from the first step's end to the last it
    // leaves out start-up (libraries, mesh, engine set-up), and CPU time is
    // what a shared machine's noise disturbs least.
    std::vector<double> cpu;
    double last_step = 0.0; // "deltaT = ": the step a following Courant line measures
    std::istringstream lines(log);
    for (std::string line; std::getline(lines, line);) {
        if (number_after(line, "Time = ")) {
            ++figures.steps;
            continue;
        }
        if (const auto clock = number_after(line, "ExecutionTime = ")) {
            cpu.push_back(*clock);
            continue;
        }
        if (const auto dt = number_after(line, "deltaT = ")) {
            last_step = *dt;
            continue;
        }
        const auto at = line.find("Courant Number mean:");
        const auto mx = line.find("max:", at == std::string::npos ? 0 : at);
        if (at == std::string::npos || mx == std::string::npos)
            continue;
        const bool every_cell = at == 0; // else "Interface Courant Number ..."
        const double co = std::atof(line.c_str() + mx + 4);
        double &worst = every_cell ? figures.courant_max : figures.interface_courant_max;
        worst = std::max(worst, co);
        const double limit = every_cell ? limits.max_courant : limits.max_interface_courant;
        if (limit > 0.0 && co > 1.1 * limit) {
            CourantOvershoot &over = every_cell ? figures.courant_over : figures.interface_courant_over;
            ++over.steps;
            // The log prints deltaT to the case's precision (6 digits unless the run checkpoints).
            if (limits.max_time_step > 0.0 && last_step >= limits.max_time_step * (1 - 1e-5))
                ++over.after_capped_steps;
        }
    }
    if (cpu.size() >= 2)
        figures.cpu_seconds_per_step = (cpu.back() - cpu.front()) / static_cast<double>(cpu.size() - 1);
    return figures;
}

} // namespace armour
