// Analytic free-body engine (no contacts).
#include "free_body_engine.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace armour {

namespace {

constexpr double kDefaultStep = 1e-4; // s: no contact to resolve, only load changes between fluid steps

Eigen::Quaterniond rotation_of(const Eigen::Vector3d &rotation_vector) {
    const double angle = rotation_vector.norm();
    if (angle < 1e-300)
        return Eigen::Quaterniond::Identity();
    return Eigen::Quaterniond(Eigen::AngleAxisd(angle, rotation_vector / angle));
}

struct Template {
    double mass = 0.0;
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero(); // unit frame, about the centroid
};

struct Body {
    int unit = 0;
    BodyState state;
    Eigen::Vector3d momentum = Eigen::Vector3d::Zero(); // world angular momentum, kg m^2/s
    std::array<bool, 3> fixed_translation{{false, false, false}};
    std::array<bool, 3> fixed_rotation{{false, false, false}};
    bool has_pivot = false;
    Eigen::Vector3d pivot_in_unit = Eigen::Vector3d::Zero(); // m, unit frame, from the centre of mass
    Eigen::Vector3d pivot_anchor = Eigen::Vector3d::Zero();  // m, world: where the held components stay
};

class FreeBodyEngine final : public RigidBodyEngine {
  public:
    explicit FreeBodyEngine(const EngineSettings &settings) : gravity_(settings.gravity) {
        if (settings.contact_iterations != 0)
            throw InputError("run.contact_iterations: free_body has no contacts to iterate (a key of engines "
                             "with rigid contacts: bullet)");
        if (settings.time_step < 0.0 || !std::isfinite(settings.time_step))
            throw InputError("free_body engine: time_step must be >= 0 (0 = default 1e-4 s)");
        report_.used = settings.time_step > 0.0 ? settings.time_step : kDefaultStep;
        report_.limit = 0.0; // no stability limit: nothing stiff is integrated
        report_.forced = false;
        report_.rule = "analytic free body, no contacts";
    }

    std::string name() const override { return "free_body"; }

    int add_template(const UnitTemplate &unit) override {
        const MassProperties &p = unit.props;
        if (!(p.mass > 0.0) || !std::isfinite(p.mass))
            throw InputError("free_body engine: template '" + unit.name + "' needs a positive mass");
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (p.inertia + p.inertia.transpose()));
        if (!(eig.eigenvalues().minCoeff() > 0.0))
            throw InputError("free_body engine: template '" + unit.name +
                             "' needs a positive definite inertia tensor");
        templates_.push_back({p.mass, 0.5 * (p.inertia + p.inertia.transpose())});
        return static_cast<int>(templates_.size()) - 1;
    }

    int add_body(const BodyInit &init) override {
        if (init.unit < 0 || init.unit >= static_cast<int>(templates_.size()))
            throw InputError("free_body engine: body refers to unknown template " +
                             std::to_string(init.unit));
        Body b;
        b.unit = init.unit;
        b.fixed_translation = init.fixed_translation;
        b.fixed_rotation = init.fixed_rotation;
        b.state.pose = init.pose;
        b.state.pose.orientation.normalize();
        b.state.velocity = init.velocity;
        b.state.angular_velocity = init.angular_velocity;
        for (int a = 0; a < 3; ++a) {
            if (b.fixed_translation[a] && !init.pivot)
                b.state.velocity[a] = 0.0;
            if (b.fixed_rotation[a])
                b.state.angular_velocity[a] = 0.0;
        }
        if (init.pivot) { // the held translations are the pivot's: projected below
            if (!init.pivot->allFinite())
                throw InputError("free_body engine: body " + std::to_string(bodies_.size()) +
                                 ": pivot must be finite");
            b.has_pivot = true;
            b.pivot_anchor = *init.pivot;
            b.pivot_in_unit = b.state.pose.orientation.conjugate() * (*init.pivot - b.state.pose.position);
            project_onto_constraints(b, b.state.velocity, b.state.angular_velocity);
        }
        b.momentum = world_inertia(b, b.state.pose.orientation) * b.state.angular_velocity;
        bodies_.push_back(b);
        return static_cast<int>(bodies_.size()) - 1;
    }

    void add_wall(const Wall &) override {} // no contacts: walls have nothing to act on

    void set_external_load(int body, const Eigen::Vector3d &force, const Eigen::Vector3d &torque) override {
        Body &b = bodies_.at(body);
        b.state.external_force = force;
        b.state.external_torque = torque;
    }

    void set_gravity(const Eigen::Vector3d &gravity) override { gravity_ = gravity; }

    void run_steps(long n) override {
        for (long s = 0; s < n; ++s)
            for (Body &b : bodies_)
                step(b, report_.used);
    }

    int body_count() const override { return static_cast<int>(bodies_.size()); }
    BodyState state(int body) const override { return bodies_.at(body).state; }
    double time_step() const override { return report_.used; }
    TimeStepReport time_step_report() const override { return report_; }

  protected:
    // Per body: pose, velocities, held load, angular momentum; then gravity.
    // Pivots, held axes and templates come from the scene.
    void write_state(const std::string &dir) const override {
        std::vector<double> v;
        for (const Body &b : bodies_) {
            const BodyState &s = b.state;
            const Eigen::Quaterniond &q = s.pose.orientation;
            for (const Eigen::Vector3d *x : {&s.pose.position, &s.velocity, &s.angular_velocity,
                                             &s.external_force, &s.external_torque, &b.momentum})
                v.insert(v.end(), x->data(), x->data() + 3);
            v.insert(v.end(), {q.w(), q.x(), q.y(), q.z()});
        }
        v.insert(v.end(), gravity_.data(), gravity_.data() + 3);
        write_state_values(dir + "/free_body", v);
    }

    void read_state(const std::string &dir) override {
        const std::vector<double> v = read_state_values(dir + "/free_body");
        if (v.size() != 22 * bodies_.size() + 3)
            throw InputError(dir + "/free_body: holds " + std::to_string(v.size()) + " values, not the " +
                             std::to_string(22 * bodies_.size() + 3) + " of " +
                             std::to_string(bodies_.size()) + " bodies (another scene?)");
        const double *x = v.data();
        auto next = [&x] {
            const Eigen::Vector3d r(x[0], x[1], x[2]);
            x += 3;
            return r;
        };
        for (Body &b : bodies_) {
            BodyState &s = b.state;
            s.pose.position = next();
            s.velocity = next();
            s.angular_velocity = next();
            s.external_force = next();
            s.external_torque = next();
            b.momentum = next();
            s.pose.orientation = Eigen::Quaterniond(x[0], x[1], x[2], x[3]);
            x += 4;
        }
        gravity_ = next();
    }

  private:
    Eigen::Matrix3d world_inertia(const Body &b, const Eigen::Quaterniond &q) const {
        const Eigen::Matrix3d R = q.toRotationMatrix();
        return R * templates_[b.unit].inertia * R.transpose();
    }

    // The constraint torque of locked rotation axes acts only about those
    // axes, so the free components of L evolve freely and fix the free
    // components of omega through the free rows and columns of I_world.
    Eigen::Vector3d angular_velocity(const Body &b, const Eigen::Quaterniond &q,
                                     const Eigen::Vector3d &L) const {
        const Eigen::Matrix3d I = world_inertia(b, q);
        int free[3];
        int nf = 0;
        for (int a = 0; a < 3; ++a)
            if (!b.fixed_rotation[a])
                free[nf++] = a;
        Eigen::Vector3d w = Eigen::Vector3d::Zero();
        if (nf == 3) {
            w = I.ldlt().solve(L);
        } else if (nf > 0) {
            Eigen::MatrixXd A(nf, nf);
            Eigen::VectorXd rhs(nf);
            for (int i = 0; i < nf; ++i) {
                rhs[i] = L[free[i]];
                for (int j = 0; j < nf; ++j)
                    A(i, j) = I(free[i], free[j]);
            }
            const Eigen::VectorXd x = A.ldlt().solve(rhs);
            for (int i = 0; i < nf; ++i)
                w[free[i]] = x[i];
        }
        return w;
    }

    // Velocities (v, omega) projected onto the hinge constraints with the
    // body's mass metric: held components of the pivot velocity
    // v + omega x r and of omega become zero, the constraint impulse being
    // the smallest in kinetic energy (Gauss' principle).
    void project_onto_constraints(const Body &b, Eigen::Vector3d &v, Eigen::Vector3d &w) const {
        const Template &t = templates_[b.unit];
        const Eigen::Quaterniond &q = b.state.pose.orientation;
        const Eigen::Vector3d r = q * b.pivot_in_unit;
        const Eigen::Matrix3d I_inv = world_inertia(b, q).inverse();
        Eigen::Matrix<double, 6, 6> rows;
        int nc = 0;
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector3d e = Eigen::Vector3d::Unit(k);
            if (b.fixed_translation[k]) // e . (v + w x r) = e . v + (r x e) . w
                rows.row(nc++) << e.transpose(), r.cross(e).transpose();
            if (b.fixed_rotation[k])
                rows.row(nc++) << Eigen::RowVector3d::Zero(), e.transpose();
        }
        if (nc == 0)
            return;
        const Eigen::MatrixXd J = rows.topRows(nc);
        Eigen::Matrix<double, 6, 6> M_inv = Eigen::Matrix<double, 6, 6>::Zero();
        M_inv.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() / t.mass;
        M_inv.bottomRightCorner<3, 3>() = I_inv;
        Eigen::Matrix<double, 6, 1> u;
        u << v, w;
        const Eigen::MatrixXd A = J * M_inv * J.transpose();
        // Redundant rows (a locked rotation that a locked translation already
        // implies) make A singular: the pseudo-inverse through the complete
        // orthogonal decomposition takes the least impulse.
        const Eigen::VectorXd lambda = A.completeOrthogonalDecomposition().solve(J * u);
        u -= M_inv * J.transpose() * lambda;
        v = u.head<3>();
        w = u.tail<3>();
    }

    // A body held at a pivot off its centre of mass: translation and
    // rotation are coupled through the constraint, so the separate exact
    // updates of step() do not apply. Symplectic Euler for the free motion,
    // then the velocities projected onto the constraints and the held
    // components of the pivot put back on their anchor (no drift).
    void step_about_pivot(Body &b, double dt) const {
        const Template &t = templates_[b.unit];
        BodyState &s = b.state;
        const Eigen::Matrix3d I_w = world_inertia(b, s.pose.orientation);
        Eigen::Vector3d v = s.velocity + dt * (s.external_force / t.mass + gravity_);
        Eigen::Vector3d w =
            s.angular_velocity +
            dt * I_w.ldlt().solve(s.external_torque - s.angular_velocity.cross(I_w * s.angular_velocity));
        project_onto_constraints(b, v, w);
        s.velocity = v;
        s.angular_velocity = w;
        s.pose.position += dt * v;
        s.pose.orientation = (rotation_of(dt * w) * s.pose.orientation).normalized();
        const Eigen::Vector3d pivot = s.pose.position + s.pose.orientation * b.pivot_in_unit;
        for (int k = 0; k < 3; ++k)
            if (b.fixed_translation[k])
                s.pose.position[k] += b.pivot_anchor[k] - pivot[k];
        b.momentum = world_inertia(b, s.pose.orientation) * w;
    }

    void step(Body &b, double dt) const {
        if (b.has_pivot) {
            step_about_pivot(b, dt);
            return;
        }
        const Template &t = templates_[b.unit];
        BodyState &s = b.state;

        // Velocity Verlet with a load held over the step: exact for constant loads.
        Eigen::Vector3d a = s.external_force / t.mass + gravity_;
        for (int k = 0; k < 3; ++k)
            if (b.fixed_translation[k])
                a[k] = 0.0;
        s.pose.position += s.velocity * dt + 0.5 * dt * dt * a;
        s.velocity += a * dt;

        // dL/dt = T in the world frame is Euler's equations written in the
        // inertial frame: exact for a constant torque, and |L| is conserved
        // to rounding without one. The orientation uses the angular velocity
        // at mid-step (implicit midpoint, a few fixed-point sweeps), which
        // makes the quaternion update second order.
        const Eigen::Quaterniond q0 = s.pose.orientation;
        const Eigen::Vector3d L_half = b.momentum + 0.5 * dt * s.external_torque;
        const Eigen::Vector3d L_new = b.momentum + dt * s.external_torque;
        Eigen::Vector3d w_mid = s.angular_velocity;
        for (int it = 0; it < 4; ++it) {
            const Eigen::Quaterniond q_half = (rotation_of(0.5 * dt * w_mid) * q0).normalized();
            w_mid = angular_velocity(b, q_half, L_half);
        }
        s.pose.orientation = (rotation_of(dt * w_mid) * q0).normalized();
        s.angular_velocity = angular_velocity(b, s.pose.orientation, L_new);
        b.momentum = L_new;
    }

    Eigen::Vector3d gravity_;
    TimeStepReport report_;
    std::vector<Template> templates_;
    std::vector<Body> bodies_;
};

} // namespace

EngineStyle free_body_engine_style() {
    EngineCapabilities c;
    c.replica_per_rank = true;
    c.pivot = true;
    c.restart = true;
    return {"free_body", "analytic rigid bodies without contacts: fluid loads alone, hinges", c,
            [](const EngineSettings &s) { return make_free_body_engine(s); }};
}

std::unique_ptr<RigidBodyEngine> make_free_body_engine(const EngineSettings &settings) {
    return std::make_unique<FreeBodyEngine>(settings);
}

} // namespace armour
