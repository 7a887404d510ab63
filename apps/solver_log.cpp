#include "solver_log.h"

#include <algorithm>
#include <cstdlib>
#include <regex>
#include <sstream>
#include <vector>

namespace armour {

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

SolverLogFigures solver_log_figures(const std::string &log) {
    SolverLogFigures figures;
    // interFoam's own CPU clock after each step (the master rank's, the
    // plugin's work included): from the first step's end to the last it
    // leaves out start-up (libraries, mesh, engine set-up), and CPU time is
    // what a shared machine's noise disturbs least.
    std::vector<double> cpu;
    std::istringstream lines(log);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("Time = ", 0) == 0) {
            ++figures.steps;
            continue;
        }
        if (line.rfind("ExecutionTime = ", 0) == 0) {
            cpu.push_back(std::atof(line.c_str() + 16));
            continue;
        }
        const auto at = line.find("Courant Number mean:");
        const auto mx = line.find("max:", at == std::string::npos ? 0 : at);
        if (at == std::string::npos || mx == std::string::npos)
            continue;
        double &worst =
            at == 0 ? figures.courant_max : figures.interface_courant_max; // "Interface Courant..."
        worst = std::max(worst, std::atof(line.c_str() + mx + 4));
    }
    if (cpu.size() >= 2)
        figures.cpu_seconds_per_step = (cpu.back() - cpu.front()) / static_cast<double>(cpu.size() - 1);
    return figures;
}

} // namespace armour
