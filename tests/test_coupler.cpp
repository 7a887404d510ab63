// The coupler core and the free-body test engine against analytic solutions.
#include "added_mass_problem.h"
#include "coupler.h"
#include "free_body_engine.h"

#include <gtest/gtest.h>

#include <cfenv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

using namespace armour;

namespace {

constexpr double kG = 9.81;
constexpr double kPi = 3.14159265358979323846;

UnitTemplate unit_of(const Shape &shape) {
    UnitTemplate unit;
    unit.name = shape.kind;
    unit.mesh = shape.mesh;
    unit.props = shape.props;
    return unit;
}

// A uniform cubic mesh of spacing h covering the box [lo, hi].
CellSet uniform_cells(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi, double h) {
    CellSet cells;
    int n[3];
    for (int a = 0; a < 3; ++a)
        n[a] = static_cast<int>(std::ceil((hi[a] - lo[a]) / h));
    for (int i = 0; i < n[0]; ++i)
        for (int j = 0; j < n[1]; ++j)
            for (int k = 0; k < n[2]; ++k) {
                cells.centres.push_back(lo + h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5));
                cells.volumes.push_back(h * h * h);
            }
    return cells;
}

CellSet cells_around(const Eigen::Vector3d &centre, double radius, double h) {
    const Eigen::Vector3d r = Eigen::Vector3d::Constant(radius + 2.0 * h);
    return uniform_cells(centre - r, centre + r, h);
}

double mask_volume(const CellMask &mask, const CellSet &cells) {
    double v = 0.0;
    for (std::size_t i = 0; i < cells.volumes.size(); ++i)
        v += mask.chi[i] * cells.volumes[i];
    return v;
}

Pose tilted_pose() {
    Pose pose;
    pose.position = Eigen::Vector3d(0.13, -0.07, 0.21);
    pose.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
    return pose;
}

// One body of `unit` at `pose` in a free-body engine, masked by a coupler.
struct Scene {
    std::unique_ptr<RigidBodyEngine> engine;
    std::unique_ptr<Coupler> coupler;

    Scene(const std::vector<UnitTemplate> &units, const std::vector<BodyInit> &bodies,
          CouplerSettings settings = {}) {
        engine = make_free_body_engine(EngineSettings{});
        std::vector<int> body_unit;
        for (const UnitTemplate &u : units)
            engine->add_template(u);
        for (const BodyInit &b : bodies) {
            engine->add_body(b);
            body_unit.push_back(b.unit);
        }
        coupler = std::make_unique<Coupler>(*engine, units, body_unit, settings);
    }
};

BodyInit body_at(const Pose &pose, int unit = 0) {
    BodyInit b;
    b.unit = unit;
    b.pose = pose;
    return b;
}

// The cosine ramp over-counts every convex 90-degree edge by
// (2 + pi/2)(1/16 - 1/(2 pi^2)) w^2 per unit length (coupler.cpp): for a cube
// of edge a meshed at h = w, 12 a of edge give this relative volume excess.
double cube_edge_excess(double h_over_a) {
    return 12.0 * (2.0 + 0.5 * kPi) * (1.0 / 16.0 - 1.0 / (2.0 * kPi * kPi)) * h_over_a * h_over_a;
}

double relative(double value, double expected) {
    return std::abs(value - expected) / std::abs(expected);
}

} // namespace

// ---------------------------------------------------------------- free body

TEST(FreeBody, FallsFreelyAndFollowsForceOverMass) {
    const UnitTemplate cube = unit_of(make_cube_shape(1.0, 0.0, 2400.0));
    auto engine = make_free_body_engine(EngineSettings{});
    EXPECT_EQ(engine->name(), "free_body");
    EXPECT_DOUBLE_EQ(engine->time_step(), 1e-4);
    EXPECT_EQ(engine->time_step_report().rule, "analytic free body, no contacts");
    engine->add_template(cube);
    BodyInit falling;
    falling.pose.position = Eigen::Vector3d(0, 0, 10);
    falling.velocity = Eigen::Vector3d(1, 0, 0);
    engine->add_body(falling);
    engine->add_body(BodyInit{});
    const Eigen::Vector3d F(1200.0, -3000.0, 50000.0);
    engine->set_external_load(1, F, Eigen::Vector3d::Zero());
    engine->advance(0.05);
    engine->advance(0.05);
    const double t = engine->time();
    EXPECT_NEAR(t, 0.1, 1e-15);
    EXPECT_EQ(engine->steps(), 1000);

    const BodyState s = engine->state(0);
    EXPECT_LT(relative(s.pose.position.z(), 10.0 - 0.5 * kG * t * t), 1e-6);
    EXPECT_LT(relative(s.pose.position.x(), t), 1e-6);
    EXPECT_LT(relative(s.velocity.z(), -kG * t), 1e-6);

    const Eigen::Vector3d a = F / cube.props.mass + Eigen::Vector3d(0, 0, -kG);
    const BodyState l = engine->state(1);
    for (int k = 0; k < 3; ++k) {
        EXPECT_LT(relative(l.velocity[k], a[k] * t), 1e-6) << k;
        EXPECT_LT(relative(l.pose.position[k], 0.5 * a[k] * t * t), 1e-6) << k;
    }
    EXPECT_EQ(l.external_force, F);
}

TEST(FreeBody, TorqueOverInertiaForIsotropicCube) {
    const UnitTemplate cube = unit_of(make_cube_shape(1.0, 0.0, 2400.0));
    const double I = cube.props.inertia(0, 0); // m a^2 / 6, equal on all axes
    auto engine = make_free_body_engine(EngineSettings{});
    engine->add_template(cube);
    BodyInit b;
    b.pose = tilted_pose();
    engine->add_body(b);
    const Eigen::Vector3d T(300.0, -120.0, 80.0);
    engine->set_external_load(0, Eigen::Vector3d::Zero(), T);
    engine->advance(0.2);
    const double t = engine->time();
    const BodyState s = engine->state(0);
    for (int k = 0; k < 3; ++k)
        EXPECT_LT(relative(s.angular_velocity[k], T[k] / I * t), 1e-6) << k;
    // The spin axis stays along T, so the turned angle is |T| t^2 / (2 I).
    const Eigen::AngleAxisd turned(s.pose.orientation * b.pose.orientation.conjugate());
    EXPECT_LT(relative(turned.angle(), T.norm() * t * t / (2.0 * I)), 1e-6);
    EXPECT_LT((turned.axis() - T.normalized()).norm(), 1e-6);
}

TEST(FreeBody, TorqueFreeSpinAboutPrincipalAxisKeepsOmega) {
    const Shape dolos = make_dolos_shape(2.0, 0.33, 2400.0);
    auto engine = make_free_body_engine(EngineSettings{});
    engine->add_template(unit_of(dolos));
    const Pose pose = tilted_pose();
    const double spin = 3.0; // rad/s
    for (int axis = 0; axis < 3; ++axis) {
        BodyInit b = body_at(pose);
        b.angular_velocity = spin * (pose.orientation * dolos.props.principal_axes.col(axis));
        engine->add_body(b);
    }
    // A non-principal spin: |L| exactly, energy to the integrator's order.
    BodyInit wobble = body_at(pose);
    wobble.angular_velocity = Eigen::Vector3d(1.0, 2.0, -1.5);
    engine->add_body(wobble);
    auto energy = [&](const BodyState &s) {
        const Eigen::Matrix3d R = s.pose.orientation.toRotationMatrix();
        return 0.5 * s.angular_velocity.dot(R * dolos.props.inertia * R.transpose() * s.angular_velocity);
    };
    const double e0 = energy(engine->state(3));
    const Eigen::Vector3d w0 = engine->state(3).angular_velocity;
    const Eigen::Matrix3d R0 = pose.orientation.toRotationMatrix();
    const Eigen::Vector3d L0 = R0 * dolos.props.inertia * R0.transpose() * w0;
    engine->advance(2.0);
    for (int axis = 0; axis < 3; ++axis) {
        const BodyState s = engine->state(axis);
        EXPECT_NEAR(s.angular_velocity.norm(), spin, 1e-9 * spin) << axis;
        const Eigen::Vector3d expected_axis = pose.orientation * dolos.props.principal_axes.col(axis);
        EXPECT_LT((s.angular_velocity / spin - expected_axis).norm(), 1e-9) << axis;
    }
    const BodyState s = engine->state(3);
    const Eigen::Matrix3d R = s.pose.orientation.toRotationMatrix();
    const Eigen::Vector3d L = R * dolos.props.inertia * R.transpose() * s.angular_velocity;
    EXPECT_LT((L - L0).norm() / L0.norm(), 1e-9);
    EXPECT_LT(relative(energy(s), e0), 1e-4);
    EXPECT_GT((s.angular_velocity - w0).norm(), 0.1); // it did wobble
}

TEST(FreeBody, LockedAxesHoldAndWallsAreIgnored) {
    const UnitTemplate cube = unit_of(make_cube_shape(1.0, 0.0, 2400.0));
    EngineSettings es;
    es.time_step = 2e-4;
    auto engine = make_free_body_engine(es);
    engine->add_template(cube);
    engine->add_wall(Wall{});
    BodyInit b;
    b.velocity = Eigen::Vector3d(1, 2, 3);
    b.angular_velocity = Eigen::Vector3d(0.5, 0.5, 0.5);
    b.fixed_translation = {{false, true, true}};
    b.fixed_rotation = {{true, false, true}};
    engine->add_body(b);
    engine->set_external_load(0, Eigen::Vector3d(100, 100, 100), Eigen::Vector3d(10, 10, 10));
    engine->advance(0.1);
    EXPECT_EQ(engine->steps(), 500);
    const BodyState s = engine->state(0);
    EXPECT_EQ(s.pose.position.y(), 0.0);
    EXPECT_EQ(s.pose.position.z(), 0.0);
    EXPECT_GT(s.pose.position.x(), 0.09);
    EXPECT_EQ(s.angular_velocity.x(), 0.0);
    EXPECT_EQ(s.angular_velocity.z(), 0.0);
    const double I = cube.props.inertia(1, 1);
    EXPECT_LT(relative(s.angular_velocity.y(), 0.5 + 10.0 / I * 0.1), 1e-9);
    const Eigen::AngleAxisd turned(s.pose.orientation);
    EXPECT_LT((turned.axis().cwiseAbs() - Eigen::Vector3d::UnitY()).norm(), 1e-9);
}

// A cube hanging from a hinge at its top-face centre (line along y held in
// x and z, rotation about y only) is a compound pendulum:
// T = 2 pi sqrt(I_p / (m g d)), I_p = I_c + m d^2 (parallel axes), d = a/2.
TEST(FreeBody, HingeOffTheCentreOfMassSwingsAsACompoundPendulum) {
    const double a = 1.0;
    const UnitTemplate cube = unit_of(make_cube_shape(a, 0.0, 2400.0));
    auto engine = make_free_body_engine(EngineSettings{});
    engine->add_template(cube);
    const Eigen::Vector3d hinge(0.0, 0.0, 2.0);
    const double theta0 = 0.05; // rad: the amplitude correction theta0^2/16 is 1.6e-4
    BodyInit b;
    b.pose.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(theta0, Eigen::Vector3d::UnitY()));
    b.pose.position = hinge + b.pose.orientation * Eigen::Vector3d(0, 0, -0.5 * a);
    b.fixed_translation = {{true, false, true}};
    b.fixed_rotation = {{true, false, true}};
    b.pivot = hinge;
    engine->add_body(b);

    const double m = cube.props.mass;
    const double d = 0.5 * a;
    const double I_p = cube.props.inertia(1, 1) + m * d * d;
    const double period = 2.0 * kPi * std::sqrt(I_p / (m * kG * d)) * (1.0 + theta0 * theta0 / 16.0);
    // Period from the times the swing passes the bottom going the same way.
    std::vector<double> crossings;
    double previous = theta0;
    double max_hinge_error = 0.0;
    while (engine->time() < 3.2 * period) {
        engine->advance(1e-4);
        const BodyState s = engine->state(0);
        const Eigen::AngleAxisd turn(s.pose.orientation);
        const double theta = turn.angle() * turn.axis().y();
        if (previous > 0.0 && theta <= 0.0)
            crossings.push_back(engine->time() - 1e-4 * theta / (theta - previous));
        previous = theta;
        const Eigen::Vector3d at_hinge =
            s.pose.position + s.pose.orientation * Eigen::Vector3d(0, 0, 0.5 * a);
        max_hinge_error = std::max(
            {max_hinge_error, std::abs(at_hinge.x() - hinge.x()), std::abs(at_hinge.z() - hinge.z())});
        ASSERT_LT(std::abs(theta), 1.01 * theta0) << "the swing grew at t = " << engine->time();
    }
    ASSERT_GE(crossings.size(), 3u);
    EXPECT_LT(
        relative((crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1), period),
        2e-3);
    EXPECT_LT(max_hinge_error, 1e-12);
}

// A push at the centre of mass of a unit hinged at its bottom face: the
// moment about the hinge turns it with alpha = d F / I_p, and the push
// along the hinge line slides it with F / m, unaffected by the hinge.
TEST(FreeBody, HingeTakesPushesAboutThePivot) {
    const double a = 1.0;
    const UnitTemplate cube = unit_of(make_cube_shape(a, 0.0, 2400.0));
    auto engine = make_free_body_engine(EngineSettings{});
    engine->add_template(cube);
    engine->set_gravity(Eigen::Vector3d::Zero());
    BodyInit b;
    b.pose.position = Eigen::Vector3d(0.0, 0.0, 0.5 * a);
    b.fixed_translation = {{true, false, true}};
    b.fixed_rotation = {{true, false, true}};
    b.pivot = Eigen::Vector3d::Zero();
    engine->add_body(b);
    const Eigen::Vector3d F(100.0, 300.0, 0.0);
    engine->set_external_load(0, F, Eigen::Vector3d::Zero());
    const double t = 0.01;
    engine->advance(t);
    const BodyState s = engine->state(0);
    const double m = cube.props.mass;
    const double d = 0.5 * a;
    const double alpha = d * F.x() / (cube.props.inertia(1, 1) + m * d * d);
    EXPECT_LT(relative(s.angular_velocity.y(), alpha * t), 1e-3);
    EXPECT_LT(relative(s.velocity.y(), F.y() / m * t), 1e-9);
    EXPECT_LT(relative(s.velocity.x(), alpha * t * d), 1e-3); // the centre of mass swings about the hinge
    EXPECT_NEAR(s.angular_velocity.x(), 0.0, 1e-15);
    EXPECT_NEAR(s.angular_velocity.z(), 0.0, 1e-15);
}

// ---------------------------------------------------------------- mask

// Mask volume of a cube of edge a at a tilted pose on a mesh of spacing a/cells.
double cube_mask_error(int cells_per_edge) {
    const double a = 1.0;
    const UnitTemplate cube = unit_of(make_cube_shape(a, 0.0, 2400.0));
    CouplerSettings ramp;
    ramp.fraction = SolidFraction::sampled_ramp;
    Scene scene({cube}, {body_at(tilted_pose())}, ramp);
    const CellSet cells = cells_around(tilted_pose().position, 0.5 * std::sqrt(3.0) * a, a / cells_per_edge);
    const CellMask &mask = scene.coupler->update_mask(cells);
    return mask_volume(mask, cells) / (a * a * a) - 1.0;
}

TEST(Mask, CubeVolumeConvergesAtSecondOrder) {
    const double e10 = cube_mask_error(10), e20 = cube_mask_error(20);
    std::printf("cube mask volume error: h = a/10 %+.4f %%, h = a/20 %+.4f %%\n", 100 * e10, 100 * e20);
    EXPECT_LT(std::abs(e10), 0.01);
    EXPECT_LT(std::abs(e20), 0.003);
    EXPECT_LT(std::abs(e20), 0.5 * std::abs(e10)); // converging, not a lucky cancellation
    // And the error is the edge term, not sampling noise (corners add O(h^3)).
    EXPECT_NEAR(e10, cube_edge_excess(0.1), 0.1 * cube_edge_excess(0.1));
    EXPECT_NEAR(e20, cube_edge_excess(0.05), 0.1 * cube_edge_excess(0.05));
}

TEST(Mask, DolosVolume) {
    const Shape dolos = make_dolos_shape(2.0, 0.33, 2400.0);
    Scene scene({unit_of(dolos)}, {body_at(tilted_pose())});
    double outer = 0.0;
    for (const Eigen::Vector3d &v : dolos.mesh.vertices)
        outer = std::max(outer, v.norm());
    const CellSet cells = cells_around(tilted_pose().position, outer, dolos.Dn() / 10.0);
    const CellMask &mask = scene.coupler->update_mask(cells);
    const double error = mask_volume(mask, cells) / dolos.props.volume - 1.0;
    std::printf("dolos mask volume error at h = Dn/10: %+.4f %% (%zu cells)\n", 100 * error,
                cells.volumes.size());
    EXPECT_LT(std::abs(error), 0.02);
}

TEST(Mask, OneDeepInsideZeroFarOutsideAndRigidVelocity) {
    const double a = 1.0, h = a / 10;
    BodyInit b = body_at(tilted_pose());
    b.velocity = Eigen::Vector3d(0.3, -0.2, 0.1);
    b.angular_velocity = Eigen::Vector3d(0.4, 1.1, -0.7);
    Scene scene({unit_of(make_cube_shape(a, 0.0, 2400.0))}, {b});
    const CellSet cells = cells_around(b.pose.position, a, h);
    const CellMask &mask = scene.coupler->update_mask(cells);
    int inside = 0, outside = 0;
    for (std::size_t i = 0; i < cells.centres.size(); ++i) {
        const Eigen::Vector3d r = cells.centres[i] - b.pose.position;
        const double reach = (b.pose.orientation.conjugate() * r).cwiseAbs().maxCoeff();
        if (reach < 0.5 * a - h) {
            ++inside;
            EXPECT_EQ(mask.chi[i], 1.0);
        }
        if (reach > 0.5 * a + h) {
            ++outside;
            EXPECT_EQ(mask.chi[i], 0.0);
            EXPECT_EQ(mask.body[i], -1);
        }
        EXPECT_GE(mask.chi[i], 0.0);
        EXPECT_LE(mask.chi[i], 1.0);
        if (mask.chi[i] > 0.0) {
            EXPECT_EQ(mask.body[i], 0);
            const Eigen::Vector3d expected = b.velocity + b.angular_velocity.cross(r);
            EXPECT_LT((mask.velocity[i] - expected).norm(), 1e-12);
        }
    }
    EXPECT_GT(inside, 300);
    EXPECT_GT(outside, 3000);
}

TEST(Mask, ClumpSpheresVolumeMatchesUnionVolume) {
    // Nine overlapping spheres: a centre ball and eight corner balls.
    UnitTemplate unit = unit_of(make_cube_shape(1.0, 0.0, 2400.0));
    unit.clump = {{Eigen::Vector3d::Zero(), 0.45}};
    for (int i = 0; i < 8; ++i)
        unit.clump.push_back({0.25 * Eigen::Vector3d(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1), 0.3});
    const double union_volume = clump_volume(unit.clump, 800);
    const double Dn = std::cbrt(union_volume);
    CouplerSettings settings;
    settings.mask = MaskSource::clump_spheres;
    for (double cells_per_Dn : {10.0, 20.0}) {
        Scene scene({unit}, {body_at(tilted_pose())}, settings);
        const CellSet cells =
            cells_around(tilted_pose().position, 0.25 * std::sqrt(3.0) + 0.3, Dn / cells_per_Dn);
        const double error = mask_volume(scene.coupler->update_mask(cells), cells) / union_volume - 1.0;
        std::printf("clump mask volume error at h = Dn/%.0f: %+.4f %%\n", cells_per_Dn, 100 * error);
        EXPECT_LT(std::abs(error), 0.02);
    }
}

TEST(Mask, OverlapGoesToTheLargerFraction) {
    const double a = 1.0, h = a / 10;
    Pose left, right;
    left.position = Eigen::Vector3d(-0.45, 0, 0);
    right.position = Eigen::Vector3d(0.45, 0, 0); // overlap 0.1 m deep
    Scene scene({unit_of(make_cube_shape(a, 0.0, 2400.0))}, {body_at(left), body_at(right)});
    const CellSet cells = uniform_cells(Eigen::Vector3d(-1.2, -0.8, -0.8), Eigen::Vector3d(1.2, 0.8, 0.8), h);
    const CellMask &mask = scene.coupler->update_mask(cells);
    for (std::size_t i = 0; i < cells.centres.size(); ++i) {
        const Eigen::Vector3d &x = cells.centres[i];
        if (std::abs(x.y()) < 0.3 && std::abs(x.z()) < 0.3 && std::abs(x.x()) > 0.2 &&
            std::abs(x.x()) < 0.85) {
            EXPECT_EQ(mask.body[i], x.x() < 0 ? 0 : 1);
            EXPECT_EQ(mask.chi[i], 1.0);
        }
    }
}

// The cost of a mask is the cells each unit looks at, not cells x units:
// 100 cubes on a 10 x 10 grid, 1e5 cells. Without culling every unit would
// ask every cell a distance, 1e7 queries (a runaway: ~30 s). The time is
// bench/run_mask_bench.sh's ("many"); here the counts, which cannot vary.
TEST(Mask, EachUnitVisitsOnlyTheCellsNearIt) {
    const UnitTemplate cube = unit_of(make_cube_shape(1.0, 0.0, 2400.0));
    std::vector<BodyInit> bodies;
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) {
            Pose p = tilted_pose();
            p.position = Eigen::Vector3d(2.0 * i + 1.0, 2.0 * j + 1.0, 0.0);
            bodies.push_back(body_at(p));
        }
    CouplerSettings ramp;
    ramp.fraction = SolidFraction::sampled_ramp;
    Scene scene({cube}, bodies, ramp);
    const double h = std::cbrt(20.0 * 20.0 * 3.0 / 1e5);
    const CellSet cells = uniform_cells(Eigen::Vector3d(0, 0, -1.5), Eigen::Vector3d(20, 20, 1.5), h);
    const CellMask &mask = scene.coupler->update_mask(cells);
    const Coupler::MaskWork &work = scene.coupler->last_mask_work();
    const double error = mask_volume(mask, cells) / (100.0 * cube.props.volume) - 1.0;
    // A distance is asked only where culling cannot decide: centres within
    // the bounding sphere plus half the ramp (h/2) and outside the inscribed
    // ball less it. Counted here over every cell and unit.
    const double outer = std::sqrt(3.0) / 2, inner = 0.5;
    long shell = 0;
    for (const BodyInit &b : bodies)
        for (const Eigen::Vector3d &x : cells.centres) {
            const double r = (x - b.pose.position).norm();
            shell += r < outer + h / 2 + 1e-9 && r > inner - h / 2 - 1e-9;
        }
    const long all = static_cast<long>(cells.volumes.size()) * 100;
    std::printf("mask of %zu cells x 100 units: %ld cells visited (%.2f %% of cells x units), %ld resolved "
                "(shell: %ld), volume error %+.3f %% (h = a/%.1f)\n",
                cells.volumes.size(), work.cells_visited,
                100.0 * static_cast<double>(work.cells_visited) / static_cast<double>(all),
                work.cells_resolved, shell, 100 * error, 1.0 / h);
    // Coarse cells (h = a/4.4): the edge excess dominates, 2.6 % predicted.
    EXPECT_NEAR(error, cube_edge_excess(h), 0.005);
    EXPECT_EQ(work.bodies_recomputed, 100);
    EXPECT_LE(work.cells_resolved, shell);
    // Binned, a unit visits the bins about it, each about its reach wide:
    // a few thousand cells of 1e5 (1-2 % of cells x units at most).
    EXPECT_LT(work.cells_visited, all / 20);
}

// ---------------------------------------------------------------- loads

TEST(Loads, HydrostaticPressureGivesArchimedes) {
    const double rho = 1025.0, a = 1.0;
    Pose pose = tilted_pose();
    pose.position.z() = -3.0; // free surface at z = 0
    Scene scene({unit_of(make_cube_shape(a, 0.0, 2400.0))}, {body_at(pose)});
    const CellSet cells = cells_around(pose.position, a, a / 10);
    scene.coupler->update_mask(cells);
    // p = p0 + rho |g| (0 - z): -grad p = (0, 0, +rho |g|), from a central difference of p.
    auto p = [&](const Eigen::Vector3d &x) { return 1e5 + rho * kG * (0.0 - x.z()); };
    std::vector<Eigen::Vector3d> f;
    const double dz = 1e-3;
    for (const Eigen::Vector3d &x : cells.centres)
        f.push_back(Eigen::Vector3d(
            0, 0, -(p(x + Eigen::Vector3d(0, 0, dz)) - p(x - Eigen::Vector3d(0, 0, dz))) / (2 * dz)));
    const BodyLoads loads = scene.coupler->integrate_loads(cells, f);
    const double buoyancy = rho * kG * a * a * a;
    std::printf("Archimedes: F = (%.3g, %.3g, %.6g) N, expected %.6g N, M = %.3g N m\n", loads.force[0].x(),
                loads.force[0].y(), loads.force[0].z(), buoyancy, loads.torque[0].norm());
    EXPECT_LT(relative(loads.force[0].z(), buoyancy), 0.01);
    EXPECT_LT(loads.force[0].head<2>().norm(), 1e-9 * buoyancy);
    // The mask's centroid can sit off the body's by a fraction of the ramp
    // width: about the centre of mass a spurious moment remains ...
    EXPECT_LT(loads.torque[0].norm(), 1e-3 * buoyancy * a);
    // ... about the mask's centroid a uniform density gives none.
    BodyLoads centred = loads;
    centre_torque_on_mask(centred);
    std::printf("Archimedes: M about the mask centroid = %.3g N m\n", centred.torque[0].norm());
    EXPECT_LT(centred.torque[0].norm(), 1e-9 * buoyancy * a);
    EXPECT_EQ(centred.force[0], loads.force[0]);
}

// A floating cube (density ratio 1/2, draft a/2) heeled by theta about y,
// its centre of mass on the still-water plane, water below z = 0. The
// wall-sided formula is exact for a box while no face leaves the water or
// the air (theta < atan(1/2)): righting arm GZ = sin(theta) (GM + BM tan^2
// (theta) / 2) with BM = a / 6, BG = a / 4, so GM = -a / 12 (a cube floating
// flat is unstable; it settles on an edge), moment -rho g V GZ about y.
// Cells are all water or all air (z = 0 on a cell face), f = (0, 0, rho g)
// in water. The moment is a small difference of large terms (GM = KB + BM -
// KG), so the mask's sampling of the waterline faces, at the largest arm,
// sets its error: measured -18 %, +19 %, -16 %, -14 %, +4 % at 4.4, 6, 8,
// 10, 16 cells across (the centring changes it by 1-10 N m of 69 N m).
// Floating units are held to heave in the shipped scenes for that reason;
// at 16 cells across the moment is within 10 %.
TEST(Loads, HeelingMomentOfAFloatingCube) {
    const double a = 1.0, rho = 1000.0, h = a / 16.0;
    const double theta = 10.0 * 3.14159265358979323846 / 180.0;
    Pose pose;
    pose.position = Eigen::Vector3d(0.137, -0.061, 0.0);
    pose.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()));
    Scene scene({unit_of(make_cube_shape(a, 0.0, 500.0))}, {body_at(pose)});
    // z = 0 on a cell face: each cell is all water or all air.
    const double reach = std::ceil(1.2 * a / h) * h;
    const CellSet cells =
        uniform_cells(Eigen::Vector3d(-reach, -reach, -reach), Eigen::Vector3d(reach, reach, reach), h);
    scene.coupler->update_mask(cells);
    std::vector<Eigen::Vector3d> f;
    for (const Eigen::Vector3d &x : cells.centres)
        f.push_back(Eigen::Vector3d(0, 0, x.z() < 0.0 ? rho * kG : 0.0));
    BodyLoads loads = scene.coupler->integrate_loads(cells, f);
    const double raw = loads.torque[0].y();
    centre_torque_on_mask(loads);
    const double V = a * a * a;
    const double gz = std::sin(theta) * (-a / 12.0 + (a / 6.0) * std::tan(theta) * std::tan(theta) / 2.0);
    const double expected = -rho * kG * (V / 2.0) * gz; // about +y: heel grows (unstable)
    std::printf("heeling moment: %.4g N m about the mask centroid, %.4g N m about the centre of mass, "
                "wall-sided %.4g N m\n",
                loads.torque[0].y(), raw, expected);
    EXPECT_NEAR(loads.torque[0].y(), expected, 0.10 * std::abs(expected));
}

TEST(Loads, MomentIsAboutTheOwnersCentre) {
    const double a = 1.0, h = a / 10;
    Pose left, right;
    left.position = Eigen::Vector3d(-1.0, 0, 0.3);
    right.position = Eigen::Vector3d(1.0, 0, -0.3);
    right.orientation = tilted_pose().orientation;
    Scene scene({unit_of(make_cube_shape(a, 0.0, 2400.0))}, {body_at(left), body_at(right)});
    const CellSet cells = uniform_cells(Eigen::Vector3d(-2, -1, -1.2), Eigen::Vector3d(2, 1, 1.2), h);
    const CellMask &mask = scene.coupler->update_mask(cells);

    // Uniform f: each unit feels chi V f and (almost) no moment about its own
    // centre, although the pair's centre is far from either.
    const Eigen::Vector3d f0(300.0, -2000.0, 900.0);
    const BodyLoads uniform =
        scene.coupler->integrate_loads(cells, std::vector<Eigen::Vector3d>(cells.centres.size(), f0));
    BodyLoads centred = uniform;
    centre_torque_on_mask(centred);
    for (int k = 0; k < 2; ++k) {
        EXPECT_LT((uniform.force[k] - f0 * a * a * a).norm(), 0.01 * f0.norm());
        EXPECT_LT(uniform.torque[k].norm(), 1e-3 * f0.norm() * a) << k;
        EXPECT_LT(centred.torque[k].norm(), 1e-12 * f0.norm() * a) << k;
    }

    // A load in one owned cell off the centre: M = r x F exactly.
    std::size_t probe = 0;
    for (std::size_t i = 0; i < cells.centres.size(); ++i)
        if (mask.body[i] == 1 && mask.chi[i] == 1.0 && (cells.centres[i] - right.position).norm() > 0.3)
            probe = i;
    ASSERT_EQ(mask.body[probe], 1);
    std::vector<Eigen::Vector3d> f(cells.centres.size(), Eigen::Vector3d::Zero());
    f[probe] = f0;
    const BodyLoads point = scene.coupler->integrate_loads(cells, f);
    const Eigen::Vector3d F = cells.volumes[probe] * f0;
    EXPECT_LT((point.force[1] - F).norm(), 1e-12 * F.norm());
    EXPECT_LT((point.torque[1] - (cells.centres[probe] - right.position).cross(F)).norm(), 1e-12 * F.norm());
    EXPECT_EQ(point.force[0], Eigen::Vector3d::Zero());
    EXPECT_EQ(point.torque[0], Eigen::Vector3d::Zero());
}

// A blown-up fluid hands over inf or absurd loads. Inside interFoam floating
// point exceptions trap (FOAM_SIGFPE): the coupler must stop with its message,
// not die of SIGFPE while looking at the numbers.
TEST(Stability, BlownUpLoadStopsTheRunUnderFloatingPointTraps) {
    const UnitTemplate cube = unit_of(make_cube_shape(1.0, 0.0, 2400.0));
    Scene scene({cube}, {body_at(Pose{})});
    BodyLoads loads;
    loads.torque.assign(1, Eigen::Vector3d::Zero());
    loads.mask_volume.assign(1, 1.0);
    loads.mask_first_moment.assign(1, Eigen::Vector3d::Zero());
    feenableexcept(FE_INVALID | FE_OVERFLOW | FE_DIVBYZERO); // as OpenFOAM does
    std::vector<std::string> messages;
    for (const double bad :
         {std::numeric_limits<double>::infinity(), 1e200, std::numeric_limits<double>::quiet_NaN()}) {
        loads.force.assign(1, Eigen::Vector3d(0.0, bad, 0.0));
        try {
            scene.coupler->advance(loads, 1e-3);
        } catch (const std::runtime_error &e) {
            messages.emplace_back(e.what());
        }
    }
    fedisableexcept(FE_INVALID | FE_OVERFLOW | FE_DIVBYZERO);
    ASSERT_EQ(messages.size(), 3u);
    for (const std::string &m : messages)
        EXPECT_NE(m.find("the fluid solution has blown up"), std::string::npos) << m;
}

// ---------------------------------------------------------------- added mass

TEST(AddedMass, PlainExplicitDivergesForLightUnitsOnly) {
    AddedMassProblem p;
    p.true_added_mass_coefficient = 0.5;
    p.coupler_added_mass_coefficient = 0.0;
    p.density_ratio = 0.3;
    const AddedMassResult light = run_added_mass_problem(p);
    EXPECT_TRUE(light.diverged);
    // The coupler stops it (Coupler::check_stability) once the swings exceed
    // five times the weight, after growing by (0.5/0.3) per step.
    EXPECT_TRUE(light.stopped);
    EXPECT_GT(light.last_error, 2.0 * light.first_error); // 4.6 when stopped, 4 steps in
    EXPECT_LT(light.acceleration.size(), static_cast<std::size_t>(p.steps));
    p.density_ratio = 1.2;
    const AddedMassResult heavy = run_added_mass_problem(p);
    EXPECT_FALSE(heavy.diverged);
    EXPECT_LT(heavy.last_error, 1e-6 * std::abs(heavy.analytic)); // (0.5/1.2)^39 = 1.5e-15
    // Either side of the boundary rho_s / rho_f = C_a,true = 0.5.
    p.steps = 200;
    p.density_ratio = 0.47;
    EXPECT_TRUE(run_added_mass_problem(p).diverged);
    p.density_ratio = 0.53;
    EXPECT_FALSE(run_added_mass_problem(p).diverged);
}

TEST(AddedMass, CorrectedSchemeMatchesAnalyticAcceleration) {
    AddedMassProblem p;
    p.coupler_added_mass_coefficient = 0.5;
    for (double ratio : {0.1, 0.3, 1.2}) {
        p.density_ratio = ratio;
        const AddedMassResult r = run_added_mass_problem(p);
        std::printf("corrected, rho_s/rho_f = %.1f: a = %.6f m/s^2, analytic %.6f, max error %.2e\n", ratio,
                    r.acceleration.back(), r.analytic, r.max_relative_error);
        EXPECT_FALSE(r.diverged) << ratio;
        EXPECT_LT(r.max_relative_error, 0.01) << ratio;
        const double m = ratio * p.fluid_density, m_a = 0.5 * p.fluid_density; // per unit volume
        EXPECT_LT(relative(r.analytic, (m - p.fluid_density) * -kG / (m + m_a)), 1e-12);
    }
}

TEST(AddedMass, UnderestimatedAddedMassStabilisesWithinItsLimit) {
    // Stable when m_a,true < m + 2 m_a: at rho_s/rho_f = 0.1 with C_true = 0.5,
    // C_a = 0.25 is stable (factor -0.71), C_a = 0.1 is not (factor -2).
    AddedMassProblem p;
    p.density_ratio = 0.1;
    p.steps = 100;
    p.coupler_added_mass_coefficient = 0.25;
    const AddedMassResult under = run_added_mass_problem(p);
    EXPECT_FALSE(under.diverged);
    EXPECT_LT(relative(under.acceleration.back(), under.analytic), 1e-6);
    p.coupler_added_mass_coefficient = 0.1;
    EXPECT_TRUE(run_added_mass_problem(p).diverged);
}

TEST(AddedMass, FailureBoundaryTable) {
    // The table in docs/coupling.md.
    std::printf("rho_s/rho_f  C_a=0: diverged  error_last/error_first   C_a=0.5: max rel. error\n");
    for (double ratio : {0.1, 0.2, 0.3, 0.4, 0.45, 0.5, 0.55, 0.6, 0.8, 1.2, 2.0, 2.4}) {
        AddedMassProblem p;
        p.density_ratio = ratio;
        p.steps = 40;
        const AddedMassResult plain = run_added_mass_problem(p);
        p.coupler_added_mass_coefficient = 0.5;
        const AddedMassResult corrected = run_added_mass_problem(p);
        std::printf("%10.2f   %14s   %22.3e   %24.2e\n", ratio, plain.diverged ? "yes" : "no",
                    plain.last_error / plain.first_error, corrected.max_relative_error);
        if (ratio != 0.5) { // amplification exactly -1 there: neither grows nor decays
            EXPECT_EQ(plain.diverged, ratio < 0.5) << ratio;
        }
        EXPECT_FALSE(corrected.diverged) << ratio;
        EXPECT_LT(corrected.max_relative_error, 0.01) << ratio;
    }
}
