#include "time_step.h"

#include "materials.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace armour {

namespace {

constexpr double kPi = 3.14159265358979323846;

double effective_modulus(const Material &a, const Material &b) {
    return 1.0 / ((1.0 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus +
                  (1.0 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus);
}

struct Contact {
    double omega = 0.0;    // rad/s
    double duration = 0.0; // s, half period of the undamped oscillator
    double critical = HUGE_VAL;
};

Contact contact(ContactModel model, double v, double y_eff, double r_eff, double m_eff, double e) {
    double k = 0.0;
    const double sqrt_r = std::sqrt(r_eff);
    if (model == ContactModel::hooke) {
        k = 16.0 / 15.0 * sqrt_r * y_eff * std::pow(15.0 * m_eff * v * v / (16.0 * sqrt_r * y_eff), 0.2);
    } else {
        const double overlap = std::pow(15.0 * m_eff * v * v / (16.0 * y_eff * sqrt_r), 0.4);
        k = 2.0 * y_eff * std::sqrt(r_eff * overlap);
    }
    Contact c;
    c.omega = std::sqrt(k / m_eff);
    c.duration = kPi / c.omega;
    const double log_e = std::log(std::max(e, 1e-12));
    const double zeta = -log_e / std::sqrt(kPi * kPi + log_e * log_e);
    c.critical = 2.0 / c.omega * (std::sqrt(1.0 + zeta * zeta) - zeta);
    return c;
}

} // namespace

TimeStepReport compute_time_step(const EngineSettings &settings, const std::vector<UnitTemplate> &units,
                                 const std::vector<int> &wall_materials) {
    TimeStepReport report;
    double critical = HUGE_VAL, rayleigh = HUGE_VAL, duration = HUGE_VAL;
    const double v = settings.characteristic_velocity;
    for (const auto &unit : units) {
        double r = HUGE_VAL;
        for (const auto &s : unit.clump)
            r = std::min(r, s.radius);
        if (!std::isfinite(r))
            continue;
        const double rho = unit.props.density;
        const double m = rho * 4.0 / 3.0 * kPi * r * r * r;
        const Material &mat = settings.materials.at(unit.material);
        // Equal spheres of this unit against each other.
        for (const auto &other : units) {
            const Material &mo = settings.materials.at(other.material);
            const Contact c = contact(settings.contact, v, effective_modulus(mat, mo), 0.5 * r, 0.5 * m,
                                      pair_value(settings, unit.material, other.material,
                                                 &Material::restitution, &MaterialPair::restitution));
            critical = std::min(critical, c.critical);
            duration = std::min(duration, c.duration);
        }
        for (int w : wall_materials) {
            const Contact c = contact(
                settings.contact, v, effective_modulus(mat, settings.materials.at(w)), r, m,
                pair_value(settings, unit.material, w, &Material::restitution, &MaterialPair::restitution));
            critical = std::min(critical, c.critical);
            duration = std::min(duration, c.duration);
        }
        const double shear = mat.youngs_modulus / (2.0 * (1.0 + mat.poisson_ratio));
        rayleigh =
            std::min(rayleigh, kPi * r * std::sqrt(rho / shear) / (0.1631 * mat.poisson_ratio + 0.8766));
    }
    std::ostringstream rule;
    report.contact_duration = std::isfinite(duration) ? duration : 0.0;
    report.limit = critical;
    rule << "limit = critical step of the damped contact of the smallest sphere at "
         << settings.characteristic_velocity << " m/s";
    if (settings.contact == ContactModel::hertz && std::isfinite(rayleigh)) {
        report.rayleigh = rayleigh;
        if (rayleigh < report.limit) {
            report.limit = rayleigh;
            rule.str("");
            rule << "limit = Rayleigh time of the smallest sphere (below the contact's critical step)";
        }
    }
    rule << "; default = " << kDefaultSafety << " x limit";
    report.rule = rule.str();
    if (!std::isfinite(report.limit))
        throw InputError("time step: no sphere in any unit, nothing sets a contact time scale");
    if (settings.time_step <= 0.0) {
        report.used = kDefaultSafety * report.limit;
    } else {
        report.used = settings.time_step;
        if (settings.time_step > report.limit) {
            if (!settings.force_time_step) {
                std::ostringstream msg;
                msg << "run.time_step: " << settings.time_step << " s exceeds the stability limit "
                    << report.limit << " s (" << report.rule
                    << "); use a smaller step or set run.force_time_step = true for a "
                    << "stability study";
                throw InputError(msg.str());
            }
            report.forced = true;
        }
    }
    return report;
}

} // namespace armour
