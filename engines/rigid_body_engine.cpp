// The engine clock, shared by every engine (see rigid_body_engine.h).
#include "rigid_body_engine.h"

#include <cmath>
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

} // namespace armour
