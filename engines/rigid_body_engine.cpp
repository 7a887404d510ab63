// The engine clock, shared by every engine (see rigid_body_engine.h).
#include "rigid_body_engine.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace armour {

void RigidBodyEngine::advance(double span) {
    if (!(span >= 0.0) || !std::isfinite(span))
        throw std::invalid_argument(name() + " engine: advance(span) needs a finite span >= 0 s, got " +
                                    std::to_string(span));
    advance_to(requested_ + span);
}

void RigidBodyEngine::advance_to(double t) {
    if (!std::isfinite(t) || t < requested_)
        throw std::invalid_argument(name() + " engine: advance_to(" + std::to_string(t) +
                                    " s) is behind the requested clock (" + std::to_string(requested_) +
                                    " s)");
    requested_ = t;
    const double dt = time_step();
    const long n = std::lround((requested_ - time()) / dt);
    if (n <= 0)
        return;
    steps_ += n;
    try {
        run_steps(n);
    } catch (...) {
        steps_ -= n;
        throw;
    }
}

double RigidBodyEngine::time() const {
    return steps_ == 0 ? 0.0 : static_cast<double>(steps_) * time_step();
}

void RigidBodyEngine::save_state(const std::string &dir) const {
    write_state_values(dir + "/clock", {static_cast<double>(steps_), requested_});
    write_state(dir);
}

void RigidBodyEngine::load_state(const std::string &dir) {
    if (steps_ != 0)
        throw std::logic_error(name() + " engine: load_state after the first advance");
    const std::vector<double> clock = read_state_values(dir + "/clock");
    if (clock.size() != 2 || !(clock[0] >= 0.0) || !(clock[1] >= 0.0))
        throw InputError(dir + "/clock: not an engine clock (steps, requested time)");
    read_state(dir);
    steps_ = static_cast<long>(clock[0]);
    requested_ = clock[1];
}

void RigidBodyEngine::write_state(const std::string &) const {
    throw InputError("run.engine: the " + name() + " engine cannot save its state (no restart capability)");
}

void RigidBodyEngine::read_state(const std::string &) {
    throw InputError("run.engine: the " + name() + " engine cannot restore a state (no restart capability)");
}

void write_state_values(const std::string &path, const std::vector<double> &values) {
    std::ofstream out(path, std::ios::trunc);
    char text[40];
    for (double v : values) {
        std::snprintf(text, sizeof text, "%a\n", v);
        out << text;
    }
    if (!out.flush())
        throw InputError(path + ": cannot write the engine state");
}

std::vector<double> read_state_values(const std::string &path) {
    std::ifstream in(path);
    if (!in)
        throw InputError(path + ": cannot read the engine state");
    std::vector<double> values;
    for (std::string line; std::getline(in, line);) {
        char *end = nullptr;
        values.push_back(std::strtod(line.c_str(), &end));
        if (end == line.c_str() || *end != '\0')
            throw InputError(path + ": line " + std::to_string(values.size()) + " is not a number");
    }
    return values;
}

} // namespace armour
