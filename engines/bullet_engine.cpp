// Bullet adapter: the only translation unit that includes Bullet (double precision).
#include "bullet_engine.h"

#include "materials.h"

#include "time_step.h"

// Bullet's headers come in as SYSTEM (PkgConfig::BULLET), so they raise no warnings.
#include <btBulletDynamicsCommon.h>

#ifndef BT_USE_DOUBLE_PRECISION
#error "armour_bullet must be built against bullet-float64 (BT_USE_DOUBLE_PRECISION)"
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace armour {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string num(double v) {
    std::ostringstream s;
    s.precision(10);
    s << v;
    return s.str();
}

btVector3 bt(const Eigen::Vector3d &v) {
    return btVector3(v.x(), v.y(), v.z());
}
Eigen::Vector3d eig(const btVector3 &v) {
    return Eigen::Vector3d(v.x(), v.y(), v.z());
}
btQuaternion bt(const Eigen::Quaterniond &q) {
    return btQuaternion(q.x(), q.y(), q.z(), q.w());
}
Eigen::Quaterniond eig(const btQuaternion &q) {
    return Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z());
}

// Pair values (row-major, materials x materials), the rule of the LIGGGHTS
// adapter: a pair override, else the smaller of the two materials' values.
struct PairTable {
    int n = 0;
    std::vector<double> friction, restitution, rolling;
};

// A wall triangle as the contact fix needs it (World::snap_wall_contacts):
// unit normal, vertices, and per edge (v0v1, v1v2, v2v0) the in-plane unit
// vector pointing inward and whether the edge is open (a boundary or a
// crease, not shared with a coplanar neighbour).
struct WallFace {
    Eigen::Vector3d normal, v[3], inward[3];
    bool open[3];
};

// Hung on every Bullet collision object (user pointer).
struct ObjectInfo {
    const PairTable *table = nullptr;
    int material = 0;
    double radius = 0.0;                          // m, volume-equivalent sphere radius; 0 for walls
    const std::vector<WallFace> *faces = nullptr; // walls only
};

std::vector<WallFace> wall_faces(const TriangleMesh &surface) {
    std::vector<WallFace> faces;
    for (const auto &t : surface.triangles) {
        WallFace f;
        for (std::size_t k = 0; k < 3; ++k)
            f.v[k] = surface.vertices[static_cast<std::size_t>(t[k])];
        f.normal = (f.v[1] - f.v[0]).cross(f.v[2] - f.v[0]).normalized();
        for (int k = 0; k < 3; ++k) {
            f.inward[k] = f.normal.cross(f.v[(k + 1) % 3] - f.v[k]).normalized();
            if (f.inward[k].dot(f.v[(k + 2) % 3] - f.v[k]) < 0.0)
                f.inward[k] = -f.inward[k];
            f.open[k] = true;
        }
        faces.push_back(f);
    }
    // Edges by their (sorted) vertex pair: an edge two coplanar faces share is not open.
    std::map<std::pair<int, int>, std::vector<std::pair<std::size_t, int>>> edges;
    for (std::size_t i = 0; i < faces.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            const auto &t = surface.triangles[i];
            const int a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
            edges[{std::min(a, b), std::max(a, b)}].push_back({i, k});
        }
    for (const auto &[edge, sides] : edges)
        for (const auto &[i, k] : sides)
            for (const auto &[j, l] : sides)
                if (i != j && std::abs(faces[i].normal.dot(faces[j].normal)) > 1.0 - 1e-12)
                    faces[i].open[k] = false;
    return faces;
}

// Replaces Bullet's combine rule (product of the two objects' values) for
// every contact point Bullet adds or replaces. Bullet's rolling friction
// coefficient is a length (angular impulse limit / normal impulse): it is
// mu_r x R*, R* = R1 R2 / (R1 + R2) between bodies, R of the body at a wall.
bool contact_added(btManifoldPoint &cp, const btCollisionObjectWrapper *w0, int, int,
                   const btCollisionObjectWrapper *w1, int, int) {
    const auto *a = static_cast<const ObjectInfo *>(w0->getCollisionObject()->getUserPointer());
    const auto *b = static_cast<const ObjectInfo *>(w1->getCollisionObject()->getUserPointer());
    if (!a || !b || !a->table)
        return false;
    const PairTable &t = *a->table;
    const std::size_t k = static_cast<std::size_t>(a->material * t.n + b->material);
    cp.m_combinedFriction = t.friction[k];
    cp.m_combinedRestitution = t.restitution[k];
    cp.m_combinedSpinningFriction = 0.0;
    double r = std::max(a->radius, b->radius);
    if (a->radius > 0.0 && b->radius > 0.0)
        r = a->radius * b->radius / (a->radius + b->radius);
    cp.m_combinedRollingFriction = t.rolling[k] * r;
    return true;
}

// Bullet's contacts are speculative: a contact point found at a gap g acts
// with the target normal velocity e v_in - g / dt, so a body that closes the
// gap within this step rebounds with up to v_in less than e v_in (measured:
// rebound height 0.05 to 1 x e^2 depending on where the last step before the
// impact ends). Counting such points as touching (g = 0) restores the
// rebound e v_in; the bounce then starts up to one step early, at a height
// below v_in dt, which loses no energy. Points farther away keep Bullet's
// speculative rule, so nothing penetrates, and no penetration has to be
// pushed out (pushing out at the rebound speed would add m g depth per bounce).
class World final : public btDiscreteDynamicsWorld {
  public:
    using btDiscreteDynamicsWorld::btDiscreteDynamicsWorld;

  protected:
    void solveConstraints(btContactSolverInfo &info) override {
        snap_wall_contacts();
        const double dt = info.m_timeStep;
        for (int i = 0; i < m_dispatcher1->getNumManifolds(); ++i) {
            btPersistentManifold *m = m_dispatcher1->getManifoldByIndexInternal(i);
            const btRigidBody *a = btRigidBody::upcast(m->getBody0());
            const btRigidBody *b = btRigidBody::upcast(m->getBody1());
            for (int j = 0; j < m->getNumContacts(); ++j) {
                btManifoldPoint &p = m->getContactPoint(j);
                if (p.m_distance1 <= 0.0)
                    continue;
                // Relative velocity at the point, with what gravity and the
                // applied loads add during this step.
                btVector3 v(0, 0, 0);
                if (a)
                    v += a->getVelocityInLocalPoint(p.getPositionWorldOnA() - a->getCenterOfMassPosition()) +
                         a->getTotalForce() * a->getInvMass() * dt;
                if (b)
                    v -= b->getVelocityInLocalPoint(p.getPositionWorldOnB() - b->getCenterOfMassPosition()) +
                         b->getTotalForce() * b->getInvMass() * dt;
                const double approach = -p.m_normalWorldOnB.dot(v); // > 0: closing
                if (p.m_distance1 < approach * dt)
                    p.m_distance1 = 0.0;
            }
        }
        btDiscreteDynamicsWorld::solveConstraints(info);
    }

    // Bullet's multipoint contact generation (setConvexConvexMultipointIterations)
    // turns the smaller body by gContactBreakingThreshold / its radius (0.02 m
    // of arc: 6.7 deg for a 0.2 m cube), runs GJK on the turned pose and keeps
    // that pose's normal and wall point. Such a point persists in the manifold
    // while the unit rests: its normal tilted by up to that angle pushes the
    // unit downhill (a cube crept 2 mm and "slid" at 25.0 deg for atan 0.5 =
    // 26.57 deg), and its wall point, up to 0.35 mm above the wall, props the
    // unit up askew. A point that lies inside a wall face (no open edge
    // within reach) has the face's normal for certain: snap its normal and its
    // wall point onto the face before every solve.
    void snap_wall_contacts() {
        for (int i = 0; i < m_dispatcher1->getNumManifolds(); ++i) {
            btPersistentManifold *m = m_dispatcher1->getManifoldByIndexInternal(i);
            const auto *info0 = static_cast<const ObjectInfo *>(m->getBody0()->getUserPointer());
            const auto *info1 = static_cast<const ObjectInfo *>(m->getBody1()->getUserPointer());
            const bool wall_is_b = info1 && info1->faces;
            const ObjectInfo *wall = wall_is_b ? info1 : info0;
            if (!wall || !wall->faces)
                continue;
            const btTransform &wall_pose = (wall_is_b ? m->getBody1() : m->getBody0())->getWorldTransform();
            for (int j = 0; j < m->getNumContacts(); ++j) {
                btManifoldPoint &p = m->getContactPoint(j);
                const int index = wall_is_b ? p.m_index1 : p.m_index0; // the wall's triangle
                if (index < 0 || index >= static_cast<int>(wall->faces->size()))
                    continue;
                const WallFace &f = (*wall->faces)[static_cast<std::size_t>(index)];
                const Eigen::Vector3d x = eig(wall_is_b ? p.getPositionWorldOnB() : p.getPositionWorldOnA());
                bool inside = true;
                for (int k = 0; k < 3; ++k)
                    inside = inside && (!f.open[k] || f.inward[k].dot(x - f.v[k]) > 0.0);
                if (!inside)
                    continue;
                const btVector3 on_face = bt(x - f.normal * f.normal.dot(x - f.v[0]));
                if (wall_is_b) {
                    p.m_positionWorldOnB = on_face;
                    p.m_localPointB = wall_pose.invXform(on_face);
                } else {
                    p.m_positionWorldOnA = on_face;
                    p.m_localPointA = wall_pose.invXform(on_face);
                }
                // Normal on B, pointing from B to A.
                const Eigen::Vector3d n = f.normal.dot(eig(p.m_normalWorldOnB)) < 0.0 ? -f.normal : f.normal;
                p.m_normalWorldOnB = bt(n);
                p.m_distance1 = (p.getPositionWorldOnA() - p.getPositionWorldOnB()).dot(p.m_normalWorldOnB);
            }
        }
    }
};

class BulletEngine final : public RigidBodyEngine {
  public:
    BulletEngine(const EngineSettings &settings, const BulletOptions &options)
        : settings_(settings), options_(options), scene_gravity_(settings.gravity.norm()) {
        check_materials(settings_);
        if (!(settings_.domain_max.array() > settings_.domain_min.array()).all())
            throw InputError("run.domain: domain_max must exceed domain_min in x, y and z");
        if (!settings_.gravity.allFinite())
            throw InputError("run.gravity: must be finite");
        if (!(options_.collision_margin >= 0.0) || !std::isfinite(options_.collision_margin))
            throw InputError("bullet.collision_margin: must be >= 0 m (0 = automatic)");
        if (settings_.contact_iterations < 0)
            throw InputError("run.contact_iterations: must be >= 0 (0 = the adapter's " +
                             std::to_string(options_.solver_iterations) + ")");
        if (settings_.contact_iterations > 0)
            options_.solver_iterations = settings_.contact_iterations;
        if (options_.solver_iterations < 1)
            throw InputError("bullet.solver_iterations: must be >= 1");
        build_pair_table();

        config_ = std::make_unique<btDefaultCollisionConfiguration>();
        // Several contact points from the first touch (perturbed GJK), rather
        // than one new point per step.
        config_->setConvexConvexMultipointIterations(3, 3);
        dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
        broadphase_ = std::make_unique<btDbvtBroadphase>();
        solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
        world_ = std::make_unique<World>(dispatcher_.get(), broadphase_.get(), solver_.get(), config_.get());
        world_->setGravity(bt(settings_.gravity));
        btContactSolverInfo &info = world_->getSolverInfo();
        info.m_numIterations = options_.solver_iterations;
        // Penetration is always removed by split impulses (position only), so
        // that resolving overlap never adds kinetic energy.
        info.m_splitImpulse = 1;
        info.m_splitImpulsePenetrationThreshold = std::numeric_limits<double>::max();
        // Coulomb friction resists sliding in every direction of the contact
        // plane. Bullet's default resists it along one direction per point
        // only (the sliding velocity before the solve): in a layer, where the
        // other contacts' impulses turn that velocity during the iterations,
        // the units creep down the face. Held dry 5 s, a hull-settled layer
        // of 99 cubes moved 30 a quarter unit with one direction, 1 with two
        // (and none in 15 s with the 50 iterations; docs/bullet.md).
        info.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
        gContactAddedCallback = contact_added;
    }

    ~BulletEngine() override {
        for (auto &b : bodies_)
            world_->removeRigidBody(b->rb.get());
        for (auto &w : walls_)
            world_->removeRigidBody(w->rb.get());
    }

    std::string name() const override { return "bullet"; }

    int add_template(const UnitTemplate &unit) override {
        const std::string what = "unit '" + unit.name + "'";
        if (unit.material < 0 || unit.material >= static_cast<int>(settings_.materials.size()))
            throw InputError(what + ": unknown material index");
        if (!(unit.props.mass > 0.0) || !(unit.props.principal_moments.array() > 0.0).all())
            throw InputError(what + ": mass and principal moments of inertia must be > 0");
        if (unit.convex_parts.empty() && unit.mesh.vertices.empty())
            throw InputError(what + ": Bullet needs the exact shape (convex_parts or mesh)");
        auto u = std::make_unique<Unit>();
        u->name = unit.name;
        u->material = unit.material;
        u->mass = unit.props.mass;
        u->moments = unit.props.principal_moments;
        u->centroid = unit.props.centroid;
        u->radius = std::cbrt(3.0 * unit.props.volume / (4.0 * kPi));
        u->nominal_diameter = std::cbrt(unit.props.volume);
        Eigen::Matrix3d axes = unit.props.principal_axes;
        if (axes.determinant() < 0.0)
            axes.col(2) = -axes.col(2);
        u->principal_to_unit = Eigen::Quaterniond(axes).normalized();
        u->margin = options_.collision_margin > 0.0
                        ? options_.collision_margin
                        : std::min(0.04, kBulletMarginFraction * std::cbrt(unit.props.volume));
        // Without convex parts the convex hull of the exact mesh stands in:
        // exact for convex units, a filled-in shape for concave ones.
        std::vector<const TriangleMesh *> parts;
        for (const auto &p : unit.convex_parts)
            parts.push_back(&p);
        if (parts.empty()) {
            parts.push_back(&unit.mesh);
            u->hull_of_mesh = true;
        }
        u->compound = std::make_unique<btCompoundShape>(true, static_cast<int>(parts.size()));
        const Eigen::Matrix3d to_principal = u->principal_to_unit.toRotationMatrix().transpose();
        for (std::size_t k = 0; k < parts.size(); ++k) {
            const std::string part =
                what + (u->hull_of_mesh ? " hull of mesh" : " part " + std::to_string(k));
            for (const auto &v : parts[k]->vertices)
                u->extent.push_back(v);
            const auto core = shrunk_hull(parts[k]->vertices, u->margin, part);
            auto hull = std::make_unique<btConvexHullShape>();
            for (const auto &v : core)
                hull->addPoint(bt(to_principal * (v - u->centroid)), false);
            hull->setMargin(u->margin);
            hull->recalcLocalAabb();
            btTransform identity;
            identity.setIdentity();
            u->compound->addChildShape(identity, hull.get());
            u->hulls.push_back(std::move(hull));
        }
        units_.push_back(std::move(u));
        UnitTemplate dem; // what compute_time_step reads
        dem.name = unit.name;
        dem.clump = unit.clump;
        dem.props = unit.props;
        dem.material = unit.material;
        dem_templates_.push_back(std::move(dem));
        return static_cast<int>(units_.size()) - 1;
    }

    int add_body(const BodyInit &init) override {
        const int index = static_cast<int>(bodies_.size());
        if (init.unit < 0 || init.unit >= static_cast<int>(units_.size()))
            throw InputError("body " + std::to_string(index) + ": unknown unit template");
        if (!init.pose.position.allFinite() || !init.pose.orientation.coeffs().allFinite() ||
            init.pose.orientation.norm() < 1e-12 || !init.velocity.allFinite() ||
            !init.angular_velocity.allFinite())
            throw InputError("body " + std::to_string(index) + ": pose and velocities must be finite");
        if (init.pivot)
            throw InputError("body " + std::to_string(index) +
                             ": the bullet engine holds locked axes at the centre of mass; a pivot "
                             "needs the free_body engine");
        const Unit &u = *units_[init.unit];
        const Eigen::Quaterniond q = init.pose.orientation.normalized();
        for (const auto &v : u.extent) {
            const Eigen::Vector3d x = init.pose.position + q * (v - u.centroid);
            if ((x.array() < settings_.domain_min.array()).any() ||
                (x.array() > settings_.domain_max.array()).any())
                throw InputError("body " + std::to_string(index) + " (unit '" + u.name +
                                 "') reaches outside the domain at (" + num(x.x()) + ", " + num(x.y()) +
                                 ", " + num(x.z()) + ") m");
        }
        auto b = std::make_unique<Body>();
        b->unit = init.unit;
        b->info = {&table_, u.material, u.radius};
        btRigidBody::btRigidBodyConstructionInfo ci(u.mass, nullptr, u.compound.get(), bt(u.moments));
        const Material &m = settings_.materials[static_cast<std::size_t>(u.material)];
        ci.m_friction = m.friction;
        ci.m_restitution = m.restitution;
        ci.m_rollingFriction = 0.0; // the callback sets the pair value
        ci.m_linearDamping = 0.0;
        ci.m_angularDamping = 0.0;
        ci.m_startWorldTransform =
            btTransform(bt((q * u.principal_to_unit).normalized()), bt(init.pose.position));
        b->rb = std::make_unique<btRigidBody>(ci);
        btRigidBody &rb = *b->rb;
        rb.setUserPointer(&b->info);
        rb.setCollisionFlags(rb.getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
        rb.setActivationState(DISABLE_DEACTIVATION);
        rb.setFlags(rb.getFlags() | BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
        Eigen::Vector3d linear, angular, velocity = init.velocity, omega = init.angular_velocity;
        for (int a = 0; a < 3; ++a) {
            linear[a] = init.fixed_translation[static_cast<std::size_t>(a)] ? 0.0 : 1.0;
            angular[a] = init.fixed_rotation[static_cast<std::size_t>(a)] ? 0.0 : 1.0;
        }
        rb.setLinearFactor(bt(linear));
        rb.setAngularFactor(bt(angular));
        rb.setLinearVelocity(bt(velocity.cwiseProduct(linear)));
        rb.setAngularVelocity(bt(omega.cwiseProduct(angular)));
        world_->addRigidBody(&rb);
        added_.push_back(&rb);
        bodies_.push_back(std::move(b));
        return index;
    }

    void add_wall(const Wall &wall) override {
        const std::string what = "wall '" + wall.name + "'";
        if (wall.surface.triangles.empty())
            throw InputError(what + ": no triangles");
        if (wall.material < 0 || wall.material >= static_cast<int>(settings_.materials.size()))
            throw InputError(what + ": unknown material index");
        auto w = std::make_unique<WallObject>();
        w->mesh = std::make_unique<btTriangleMesh>(true, false);
        const int nv = static_cast<int>(wall.surface.vertices.size());
        for (const auto &t : wall.surface.triangles) {
            for (int i : t)
                if (i < 0 || i >= nv)
                    throw InputError(what + ": triangle vertex index " + std::to_string(i) + " out of range");
            w->mesh->addTriangle(bt(wall.surface.vertices[static_cast<std::size_t>(t[0])]),
                                 bt(wall.surface.vertices[static_cast<std::size_t>(t[1])]),
                                 bt(wall.surface.vertices[static_cast<std::size_t>(t[2])]), false);
        }
        w->shape = std::make_unique<btBvhTriangleMeshShape>(w->mesh.get(), true, true);
        w->shape->setMargin(0.0);
        w->faces = wall_faces(wall.surface);
        w->info = {&table_, wall.material, 0.0, &w->faces};
        btRigidBody::btRigidBodyConstructionInfo ci(0.0, nullptr, w->shape.get());
        const Material &m = settings_.materials[static_cast<std::size_t>(wall.material)];
        ci.m_friction = m.friction;
        ci.m_restitution = m.restitution;
        w->rb = std::make_unique<btRigidBody>(ci);
        w->rb->setUserPointer(&w->info);
        w->rb->setCollisionFlags(w->rb->getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT |
                                 btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
        world_->addRigidBody(w->rb.get());
        added_.push_back(w->rb.get());
        walls_.push_back(std::move(w));
        wall_materials_.push_back(wall.material);
    }

    void set_external_load(int body, const Eigen::Vector3d &force, const Eigen::Vector3d &torque) override {
        Body &b = checked(body);
        if (!force.allFinite() || !torque.allFinite())
            throw InputError("body " + std::to_string(body) + ": external load must be finite");
        b.force = force;
        b.torque = torque;
    }

    void set_gravity(const Eigen::Vector3d &gravity) override {
        if (!gravity.allFinite())
            throw InputError("run.gravity: must be finite");
        settings_.gravity = gravity;
        world_->setGravity(bt(gravity)); // every dynamic body's gravity too
    }

    void run_steps(long n) override {
        if (!frozen_) {
            report_ = make_report();
            frozen_ = true;
        }
        const double dt = report_.used;
        for (long i = 0; i < n; ++i) {
            // Bullet clears applied forces after every stepSimulation call.
            for (auto &b : bodies_) {
                b->rb->applyCentralForce(bt(b->force));
                b->rb->applyTorque(bt(b->torque));
            }
            world_->stepSimulation(dt, 0, dt); // maxSubSteps = 0: exactly one step of dt
        }
        collect_contact_forces(dt);
        for (std::size_t i = 0; i < bodies_.size(); ++i) {
            const Eigen::Vector3d x = eig(bodies_[i]->rb->getCenterOfMassPosition());
            if ((x.array() < settings_.domain_min.array()).any() ||
                (x.array() > settings_.domain_max.array()).any() || !x.allFinite())
                throw InputError("body " + std::to_string(i) + " left the domain at t = " + num(time()) +
                                 " s; enlarge run.domain_min/domain_max (results so far are kept)");
        }
    }

    int body_count() const override { return static_cast<int>(bodies_.size()); }

    BodyState state(int body) const override {
        const Body &b = checked(body);
        const Unit &u = *units_[b.unit];
        const btRigidBody &rb = *b.rb;
        BodyState s;
        s.pose.position = eig(rb.getCenterOfMassPosition());
        const Eigen::Quaterniond principal_to_world = eig(rb.getOrientation());
        s.pose.orientation = (principal_to_world * u.principal_to_unit.conjugate()).normalized();
        s.velocity = eig(rb.getLinearVelocity());
        s.angular_velocity = eig(rb.getAngularVelocity());
        s.contact_force = b.contact;
        s.external_force = b.force;
        s.external_torque = b.torque;
        return s;
    }

    double time_step() const override { return report().used; }
    TimeStepReport time_step_report() const override { return report(); }

    BulletBodyInfo info(int body) const {
        const Body &b = checked(body);
        BulletBodyInfo i;
        i.mass = 1.0 / b.rb->getInvMass();
        i.local_inertia = eig(b.rb->getLocalInertia());
        i.center_of_mass = eig(b.rb->getCenterOfMassPosition());
        i.principal_to_world = eig(b.rb->getOrientation());
        i.margin = units_[b.unit]->margin;
        i.hulls = units_[b.unit]->compound->getNumChildShapes();
        return i;
    }

    Eigen::Vector3d support(int body, const Eigen::Vector3d &direction) const {
        const Body &b = checked(body);
        const btTransform &T = b.rb->getCenterOfMassTransform();
        const btVector3 local = T.getBasis().transpose() * bt(direction);
        btVector3 best(0, 0, 0);
        double best_dot = -HUGE_VAL;
        for (const auto &hull : units_[b.unit]->hulls) {
            const btVector3 p = hull->localGetSupportingVertex(local);
            if (p.dot(local) > best_dot) {
                best_dot = p.dot(local);
                best = p;
            }
        }
        return eig(T * best);
    }

  protected:
    // Per body: Bullet's transform (basis and origin, as Bullet holds them),
    // velocities, the held load and the last contact force; then gravity.
    // Bullet's contact manifolds (their cached impulses warm-start the
    // solver), its broadphase tree and pair order are not saved; instead the
    // saving engine drops them too (restart_point), so both continue alike.
    void write_state(const std::string &dir) const override {
        std::vector<double> v;
        for (const auto &b : bodies_) {
            const btTransform &T = b->rb->getCenterOfMassTransform();
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c)
                    v.push_back(T.getBasis()[r][c]);
            for (const btVector3 &x :
                 {T.getOrigin(), b->rb->getLinearVelocity(), b->rb->getAngularVelocity()})
                v.insert(v.end(), {x.x(), x.y(), x.z()});
            for (const Eigen::Vector3d *x : {&b->force, &b->torque, &b->contact})
                v.insert(v.end(), x->data(), x->data() + 3);
        }
        v.insert(v.end(), settings_.gravity.data(), settings_.gravity.data() + 3);
        write_state_values(dir + "/bullet", v);
        const_cast<BulletEngine *>(this)->restart_point();
    }

    void read_state(const std::string &dir) override {
        const std::vector<double> v = read_state_values(dir + "/bullet");
        if (v.size() != 27 * bodies_.size() + 3)
            throw InputError(dir + "/bullet: holds " + std::to_string(v.size()) + " values, not the " +
                             std::to_string(27 * bodies_.size() + 3) + " of " +
                             std::to_string(bodies_.size()) + " bodies (another scene?)");
        const double *x = v.data();
        for (auto &b : bodies_) {
            btMatrix3x3 basis;
            for (int r = 0; r < 3; ++r)
                basis[r] = btVector3(x[3 * r], x[3 * r + 1], x[3 * r + 2]);
            x += 9;
            const btVector3 origin(x[0], x[1], x[2]), linear(x[3], x[4], x[5]), angular(x[6], x[7], x[8]);
            x += 9;
            // Velocities first: setCenterOfMassTransform copies them into
            // the interpolation state, as the end of a step does.
            b->rb->setLinearVelocity(linear);
            b->rb->setAngularVelocity(angular);
            b->rb->setCenterOfMassTransform(btTransform(basis, origin));
            for (Eigen::Vector3d *y : {&b->force, &b->torque, &b->contact}) {
                *y = Eigen::Vector3d(x[0], x[1], x[2]);
                x += 3;
            }
        }
        set_gravity(Eigen::Vector3d(x[0], x[1], x[2]));
        report_ = make_report();
        frozen_ = true;
        restart_point();
    }

    // One start for the engine that saved a state and the one that read it:
    // every object leaves the world and comes back, in the order it was
    // added, into a new broadphase; the contact manifolds (and the impulses
    // that warm-start the solver) go with the old pairs. Both then take the
    // same steps, bit for bit; the saving run pays a cold start of its
    // contacts at each checkpoint.
    void restart_point() {
        for (auto it = added_.rbegin(); it != added_.rend(); ++it)
            world_->removeRigidBody(*it);
        auto fresh = std::make_unique<btDbvtBroadphase>();
        world_->setBroadphase(fresh.get());
        broadphase_ = std::move(fresh);
        solver_->reset();
        for (btRigidBody *rb : added_)
            world_->addRigidBody(rb);
    }

  private:
    struct Unit {
        std::string name;
        int material = 0;
        double mass = 0.0, radius = 0.0, margin = 0.0, nominal_diameter = 0.0;
        Eigen::Vector3d moments, centroid;
        Eigen::Quaterniond principal_to_unit;
        std::vector<Eigen::Vector3d> extent; // every part vertex, unit frame
        bool hull_of_mesh = false;
        std::vector<std::unique_ptr<btConvexHullShape>> hulls;
        std::unique_ptr<btCompoundShape> compound;
    };
    struct Body {
        int unit = 0;
        ObjectInfo info;
        std::unique_ptr<btRigidBody> rb;
        Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
        Eigen::Vector3d contact = Eigen::Vector3d::Zero();
    };
    struct WallObject {
        ObjectInfo info;
        std::vector<WallFace> faces;
        std::unique_ptr<btTriangleMesh> mesh;
        std::unique_ptr<btBvhTriangleMeshShape> shape;
        std::unique_ptr<btRigidBody> rb;
    };

    void build_pair_table() {
        table_.n = static_cast<int>(settings_.materials.size());
        for (int a = 0; a < table_.n; ++a)
            for (int b = 0; b < table_.n; ++b) {
                table_.friction.push_back(
                    pair_value(settings_, a, b, &Material::friction, &MaterialPair::friction));
                table_.restitution.push_back(
                    pair_value(settings_, a, b, &Material::restitution, &MaterialPair::restitution));
                table_.rolling.push_back(pair_value(settings_, a, b, &Material::rolling_friction,
                                                    &MaterialPair::rolling_friction));
            }
    }

    const Body &checked(int body) const {
        if (body < 0 || body >= static_cast<int>(bodies_.size()))
            throw InputError("body " + std::to_string(body) + ": no such body (" +
                             std::to_string(bodies_.size()) + " bodies)");
        return *bodies_[static_cast<std::size_t>(body)];
    }
    Body &checked(int body) {
        return const_cast<Body &>(static_cast<const BulletEngine *>(this)->checked(body));
    }

    // Until the first advance() the report follows the settings and templates;
    // then the step is fixed.
    TimeStepReport report() const { return frozen_ ? report_ : make_report(); }

    TimeStepReport make_report() const {
        TimeStepReport r;
        std::ostringstream rule;
        rule << "Bullet: sequential-impulse solver, rigid contacts (no contact spring), so no "
                "spring-dashpot limit applies; limit = 1/60 s (Bullet's own step; above it contacts tunnel "
                "and resting contacts jitter); default = min("
             << kBulletDefaultStep << " s, sqrt(Dn / g) / " << kBulletStepsPerUnitTime
             << " for the smallest Dn: resting layers creep at coarser steps) = " << default_step() << " s; "
             << options_.solver_iterations << " solver iterations; contact stiffness: rigid (Bullet's own)";
        bool spheres = false;
        for (const auto &u : dem_templates_)
            spheres = spheres || !u.clump.empty();
        if (spheres) {
            EngineSettings dem = settings_;
            dem.time_step = 0.0;
            const TimeStepReport d = compute_time_step(dem, dem_templates_, wall_materials_);
            r.rayleigh = d.rayleigh;
            r.contact_duration = d.contact_duration;
            rule << "; for comparison the sphere-clump DEM of the same materials: " << d.rule << " = "
                 << d.limit << " s";
        }
        for (const auto &u : units_)
            if (u->hull_of_mesh)
                rule << "; unit '" << u->name << "': convex hull of its mesh (no convex_parts)";
        r.rule = rule.str();
        r.limit = kBulletMaxStep;
        if (settings_.time_step <= 0.0) {
            r.used = default_step();
        } else {
            r.used = settings_.time_step;
            if (settings_.time_step > r.limit) {
                if (!settings_.force_time_step) {
                    std::ostringstream msg;
                    msg << "run.time_step: " << settings_.time_step << " s exceeds Bullet's limit " << r.limit
                        << " s (impulse solver; above it contacts tunnel); use a smaller step or set "
                        << "run.force_time_step = true for a stability study";
                    throw InputError(msg.str());
                }
                r.forced = true;
            }
        }
        return r;
    }

    // A unit's own time sqrt(Dn / g) over kBulletStepsPerUnitTime, for the
    // smallest unit, at most kBulletDefaultStep: a resting layer of 4 cm cubes
    // crept 7 mm in 5 s at 1 ms and 1.3 mm at 0.25 ms (docs/validation/stability.md).
    // The scene's gravity, not a later set_gravity: a restored engine must
    // take the step of the one that saved it.
    double default_step() const {
        double step = kBulletDefaultStep;
        if (scene_gravity_ > 0.0)
            for (const auto &u : units_)
                step =
                    std::min(step, std::sqrt(u->nominal_diameter / scene_gravity_) / kBulletStepsPerUnitTime);
        return step;
    }

    void collect_contact_forces(double dt) {
        for (auto &b : bodies_)
            b->contact.setZero();
        const int manifolds = dispatcher_->getNumManifolds();
        for (int i = 0; i < manifolds; ++i) {
            const btPersistentManifold *m = dispatcher_->getManifoldByIndexInternal(i);
            btVector3 impulse(0, 0, 0); // on body 0; body 1 gets the opposite
            for (int j = 0; j < m->getNumContacts(); ++j) {
                const btManifoldPoint &p = m->getContactPoint(j);
                if (p.getDistance() > m->getContactProcessingThreshold())
                    continue; // not solved this step: its impulses are stale
                impulse += p.m_normalWorldOnB * p.getAppliedImpulse() +
                           p.m_lateralFrictionDir1 * p.m_appliedImpulseLateral1 +
                           p.m_lateralFrictionDir2 * p.m_appliedImpulseLateral2;
            }
            const Eigen::Vector3d f = eig(impulse) / dt;
            add_contact(m->getBody0(), f);
            add_contact(m->getBody1(), -f);
        }
    }

    void add_contact(const btCollisionObject *object, const Eigen::Vector3d &force) {
        for (auto &b : bodies_)
            if (b->rb.get() == object) {
                b->contact += force;
                return;
            }
    }

    // Members that Bullet's world refers to come first: the world is destroyed first.
    EngineSettings settings_;
    BulletOptions options_;
    PairTable table_;
    std::vector<std::unique_ptr<Unit>> units_;
    std::vector<UnitTemplate> dem_templates_;
    std::vector<std::unique_ptr<Body>> bodies_;
    std::vector<std::unique_ptr<WallObject>> walls_;
    std::vector<int> wall_materials_;
    std::vector<btRigidBody *> added_; // walls and bodies in the order they entered the world
    std::unique_ptr<btDefaultCollisionConfiguration> config_;
    std::unique_ptr<btCollisionDispatcher> dispatcher_;
    std::unique_ptr<btDbvtBroadphase> broadphase_;
    std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
    std::unique_ptr<World> world_;
    TimeStepReport report_;
    bool frozen_ = false;
    const double scene_gravity_; // m/s^2, |run.gravity| at construction (the default step's g)
};

const BulletEngine &as_bullet(const RigidBodyEngine &engine) {
    const auto *b = dynamic_cast<const BulletEngine *>(&engine);
    if (!b)
        throw std::invalid_argument("not a Bullet engine: " + engine.name());
    return *b;
}

} // namespace

EngineStyle bullet_engine_style() {
    EngineCapabilities c;
    c.contacts = ContactKind::rigid_impulse;
    c.shape = ShapeModel::convex_hulls;
    c.replica_per_rank = true; // deterministic: replicas fed the same loads stay one run
    c.restart = true;
    return {"bullet", "Bullet 3.24 (double): exact convex hulls, rigid-contact impulses", c,
            [](const EngineSettings &s) { return make_bullet_engine(s); }};
}

std::unique_ptr<RigidBodyEngine> make_bullet_engine(const EngineSettings &settings) {
    return std::make_unique<BulletEngine>(settings, BulletOptions{});
}

std::unique_ptr<RigidBodyEngine> make_bullet_engine(const EngineSettings &settings,
                                                    const BulletOptions &options) {
    return std::make_unique<BulletEngine>(settings, options);
}

BulletBodyInfo bullet_body_info(const RigidBodyEngine &engine, int body) {
    return as_bullet(engine).info(body);
}

Eigen::Vector3d bullet_support_point(const RigidBodyEngine &engine, int body,
                                     const Eigen::Vector3d &direction) {
    return as_bullet(engine).support(body, direction);
}

} // namespace armour
