#include "time_step.h"

#include "materials.h"

#include <Eigen/Dense>

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

// Normal stiffness (N/m) of a sphere of radius r hit by mass m at speed v.
double stiffness(ContactModel model, double v, double y_eff, double r, double m) {
    const double sqrt_r = std::sqrt(r);
    if (model == ContactModel::hooke)
        return 16.0 / 15.0 * sqrt_r * y_eff * std::pow(15.0 * m * v * v / (16.0 * sqrt_r * y_eff), 0.2);
    const double overlap = std::pow(15.0 * m * v * v / (16.0 * y_eff * sqrt_r), 0.4);
    return 2.0 * y_eff * std::sqrt(r * overlap);
}

// Peak Hertz overlap (m) of the same impact; hooke: the same scale.
double impact_overlap(double v, double y_eff, double r, double m) {
    return std::pow(15.0 * m * v * v / (16.0 * y_eff * std::sqrt(r)), 0.4);
}

// Highest natural frequency (rad/s) of the unit on the springs of the
// spheres that touch a plane at once, over kTimeStepDirections directions.
double body_contact_omega(const UnitTemplate &unit, ContactModel model, double v, double y_eff) {
    const double m = unit.props.mass;
    Eigen::Matrix<double, 6, 6> mass = Eigen::Matrix<double, 6, 6>::Zero();
    mass.topLeftCorner<3, 3>() = m * Eigen::Matrix3d::Identity();
    mass.bottomRightCorner<3, 3>() = unit.props.inertia;
    std::vector<double> k(unit.clump.size()), overlap(unit.clump.size());
    for (std::size_t j = 0; j < unit.clump.size(); ++j) {
        k[j] = stiffness(model, v, y_eff, unit.clump[j].radius, m);
        overlap[j] = impact_overlap(v, y_eff, unit.clump[j].radius, m);
    }
    double omega2 = 0.0;
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < kTimeStepDirections; ++i) {
        // Fibonacci points on the sphere: even coverage, deterministic.
        const double z = 1.0 - (2.0 * i + 1.0) / kTimeStepDirections;
        const double ring = std::sqrt(1.0 - z * z);
        const Eigen::Vector3d n(ring * std::cos(golden * i), ring * std::sin(golden * i), z);
        double reach = -HUGE_VAL;
        for (const auto &s : unit.clump)
            reach = std::max(reach, n.dot(s.center) + s.radius);
        Eigen::Matrix<double, 6, 6> K = Eigen::Matrix<double, 6, 6>::Zero();
        for (std::size_t j = 0; j < unit.clump.size(); ++j) {
            const Sphere &s = unit.clump[j];
            if (reach - (n.dot(s.center) + s.radius) > overlap[j])
                continue;
            const Eigen::Vector3d arm = s.center + s.radius * n - unit.props.centroid;
            Eigen::Matrix<double, 6, 1> J;
            J << n, arm.cross(n);
            K += k[j] * J * J.transpose();
        }
        const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> modes(
            K, mass, Eigen::EigenvaluesOnly);
        omega2 = std::max(omega2, modes.eigenvalues().maxCoeff());
    }
    return std::sqrt(omega2);
}

double critical_step(double omega, double restitution) {
    const double log_e = std::log(std::max(restitution, 1e-12));
    const double zeta = -log_e / std::sqrt(kPi * kPi + log_e * log_e);
    return 2.0 / omega * (std::sqrt(1.0 + zeta * zeta) - zeta);
}

} // namespace

TimeStepReport compute_time_step(const EngineSettings &settings, const std::vector<UnitTemplate> &units,
                                 const std::vector<int> &wall_materials) {
    TimeStepReport report;
    double critical = HUGE_VAL, rayleigh = HUGE_VAL, duration = HUGE_VAL;
    const double v = settings.characteristic_velocity;
    double omega_max = 0.0;
    for (const auto &unit : units) {
        double r = HUGE_VAL;
        for (const auto &s : unit.clump)
            r = std::min(r, s.radius);
        if (!std::isfinite(r) || !(unit.props.mass > 0.0))
            continue;
        const Material &mat = settings.materials.at(unit.material);
        auto limit_with = [&](int other_material, double omega_factor) {
            const Material &mo = settings.materials.at(other_material);
            const double omega =
                omega_factor * body_contact_omega(unit, settings.contact, v, effective_modulus(mat, mo));
            const double e = pair_value(settings, unit.material, other_material, &Material::restitution,
                                        &MaterialPair::restitution);
            critical = std::min(critical, critical_step(omega, e));
            omega_max = std::max(omega_max, omega);
        };
        // Two units on the same springs: w^2 at most doubles.
        for (const auto &other : units)
            limit_with(other.material, std::sqrt(2.0));
        for (int w : wall_materials)
            limit_with(w, 1.0);
        const double shear = mat.youngs_modulus / (2.0 * (1.0 + mat.poisson_ratio));
        rayleigh = std::min(rayleigh, kPi * r * std::sqrt(unit.props.density / shear) /
                                          (0.1631 * mat.poisson_ratio + 0.8766));
    }
    if (omega_max > 0.0)
        duration = kPi / omega_max;
    std::ostringstream rule;
    report.contact_duration = std::isfinite(duration) ? duration : 0.0;
    report.limit = critical;
    if (std::isfinite(rayleigh))
        report.rayleigh = rayleigh; // for comparison: the single-grain rule
    rule << "limit = critical step of the stiffest contact mode of a whole unit (its mass and inertia on "
            "the contact springs of the spheres that touch at once, impact at "
         << settings.characteristic_velocity << " m/s)";
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
