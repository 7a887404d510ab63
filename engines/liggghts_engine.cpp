// LIGGGHTS adapter: the only translation unit that includes LIGGGHTS.
#include "liggghts_engine.h"

#include "materials.h"
#include "stl_io.h"
#include "time_step.h"

#include <mpi.h>

#include <fix_multisphere.h>
#include <lammps.h>
#include <library.h>
#include <modify.h>
#include <multisphere.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace armour {

namespace {

namespace fs = std::filesystem;
using LAMMPS_NS::Multisphere;

// LIGGGHTS' neighbour skin, as a fraction of the largest sphere radius of
// any unit (the bins are sized by that radius already).
constexpr double kSkinOfLargestRadius = 0.2;

std::string num(double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}

// LIGGGHTS ends the process on its own errors (exit or MPI_Abort). If that
// happens, this prints the ERROR line from its log as the one error line.
// In an MPI job every rank's replica meets the same error and prints it with
// its own log's path; an MPI_Abort (LIGGGHTS' Error::one) ends the whole job
// without running this.
std::string g_log_path;
void report_liggghts_exit() {
    if (g_log_path.empty())
        return;
    std::ifstream log(g_log_path);
    std::string line, error;
    while (std::getline(log, line))
        if (line.rfind("ERROR", 0) == 0)
            error = line;
    if (!error.empty())
        std::fprintf(stderr, "armour: error: LIGGGHTS: %s (log: %s)\n", error.c_str(), g_log_path.c_str());
}

class LiggghtsEngine final : public RigidBodyEngine {
  public:
    explicit LiggghtsEngine(const EngineSettings &settings) : settings_(settings) {
        check_materials(settings_);
        if (settings_.contact_iterations != 0)
            throw InputError(
                "run.contact_iterations: the liggghts engine's contacts are springs and dashpots, "
                "solved without iterations (a key of engines with rigid contacts: bullet)");
        if (!(settings_.domain_max.array() > settings_.domain_min.array()).all())
            throw InputError("run.domain: domain_max must exceed domain_min in x, y and z");
        base_dir_ = settings_.work_dir.empty() ? fs::temp_directory_path() / "armour-liggghts"
                                               : fs::path(settings_.work_dir);
        work_dir_ = base_dir_;
    }

    ~LiggghtsEngine() override {
        if (lmp_)
            lammps_close(lmp_);
        g_log_path.clear();
    }

    std::string name() const override { return "liggghts"; }

    int add_template(const UnitTemplate &unit) override {
        require_setup_phase("add_template");
        if (unit.clump.size() < 2)
            throw InputError("unit '" + unit.name + "': LIGGGHTS multisphere needs at least 2 spheres (got " +
                             std::to_string(unit.clump.size()) + ")");
        if (unit.material < 0 || unit.material >= static_cast<int>(settings_.materials.size()))
            throw InputError("unit '" + unit.name + "': unknown material index");
        if (!(unit.props.mass > 0.0))
            throw InputError("unit '" + unit.name + "': mass must be > 0");
        units_.push_back(unit);
        return static_cast<int>(units_.size()) - 1;
    }

    int add_body(const BodyInit &body) override {
        require_setup_phase("add_body");
        if (body.unit < 0 || body.unit >= static_cast<int>(units_.size()))
            throw InputError("body " + std::to_string(bodies_.size()) + ": unknown unit template");
        if (body.pivot)
            throw InputError("body " + std::to_string(bodies_.size()) +
                             ": the liggghts engine holds locked axes at the centre of mass; a pivot "
                             "needs the free_body engine");
        Body b;
        b.init = body;
        b.init.pose.orientation.normalize();
        bodies_.push_back(b);
        return static_cast<int>(bodies_.size()) - 1;
    }

    void add_wall(const Wall &wall) override {
        require_setup_phase("add_wall");
        if (wall.surface.triangles.empty())
            throw InputError("wall '" + wall.name + "': no triangles");
        if (wall.material < 0 || wall.material >= static_cast<int>(settings_.materials.size()))
            throw InputError("wall '" + wall.name + "': unknown material index");
        walls_.push_back(wall);
    }

    void set_external_load(int body, const Eigen::Vector3d &force, const Eigen::Vector3d &torque) override {
        bodies_.at(body).force = force;
        bodies_.at(body).torque = torque;
    }

    void set_gravity(const Eigen::Vector3d &gravity) override { settings_.gravity = gravity; }

    void run_steps(long n) override {
        if (!lmp_)
            start();
        write_external_loads();
        command("run " + std::to_string(n) + " pre no post no");
        read_states();
    }

    int body_count() const override { return static_cast<int>(bodies_.size()); }

    BodyState state(int body) const override {
        if (!lmp_)
            const_cast<LiggghtsEngine *>(this)->start();
        return bodies_.at(body).state;
    }

    double time_step() const override { return report().used; }

    TimeStepReport time_step_report() const override { return report(); }

  protected:
    // LIGGGHTS' own restart file (atoms, multisphere bodies, contact
    // histories of pairs and walls) and the adapter's part: each body's
    // tag and held load, each unit's principal frame, gravity.
    void write_state(const std::string &dir) const override {
        auto &self = *const_cast<LiggghtsEngine *>(this);
        if (!lmp_)
            self.start();
        // A restarted LIGGGHTS builds its neighbour lists at the saved
        // positions, so the order in which it sums contact forces differs
        // from a run whose lists were built earlier; the saving run builds
        // them again here too (a set-up, no step), and both continue alike.
        self.write_external_loads();
        self.command("run 0 post no");
        self.command("write_restart " + dir + "/liggghts.restart");
        std::vector<double> v;
        for (const Body &b : bodies_) {
            v.push_back(b.tag);
            v.insert(v.end(), b.force.data(), b.force.data() + 3);
            v.insert(v.end(), b.torque.data(), b.torque.data() + 3);
        }
        for (const Eigen::Quaterniond &q : principal_to_unit_)
            v.insert(v.end(), {q.w(), q.x(), q.y(), q.z()});
        v.insert(v.end(), settings_.gravity.data(), settings_.gravity.data() + 3);
        write_state_values(dir + "/liggghts", v);
    }

    void read_state(const std::string &dir) override {
        if (lmp_) { // started by a state() query only (no step): start again from the restart file
            lammps_close(lmp_);
            lmp_ = nullptr;
            transcript_.str("");
        }
        const std::vector<double> v = read_state_values(dir + "/liggghts");
        if (v.size() != 7 * bodies_.size() + 4 * units_.size() + 3)
            throw InputError(dir + "/liggghts: holds " + std::to_string(v.size()) + " values, not those of " +
                             std::to_string(bodies_.size()) + " bodies and " + std::to_string(units_.size()) +
                             " units (another scene?)");
        const double *x = v.data();
        for (Body &b : bodies_) {
            b.tag = static_cast<int>(x[0]);
            b.force = Eigen::Vector3d(x[1], x[2], x[3]);
            b.torque = Eigen::Vector3d(x[4], x[5], x[6]);
            x += 7;
        }
        principal_to_unit_.clear();
        for (std::size_t k = 0; k < units_.size(); ++k, x += 4)
            principal_to_unit_.emplace_back(x[0], x[1], x[2], x[3]);
        settings_.gravity = Eigen::Vector3d(x[0], x[1], x[2]);
        const std::string file = dir + "/liggghts.restart";
        if (!fs::is_regular_file(file))
            throw InputError(file + ": missing (an incomplete checkpoint?)");
        start(fs::absolute(file).string());
        if (multisphere().n_body() != static_cast<int>(bodies_.size()))
            throw InputError(file + ": holds " + std::to_string(multisphere().n_body()) +
                             " bodies, the scene " + std::to_string(bodies_.size()));
    }

  private:
    struct Body {
        BodyInit init;
        BodyState state;
        Eigen::Vector3d force = Eigen::Vector3d::Zero();
        Eigen::Vector3d torque = Eigen::Vector3d::Zero();
        int tag = -1;
    };

    void require_setup_phase(const char *what) const {
        if (lmp_)
            throw std::logic_error(std::string("LiggghtsEngine::") + what + " after the first advance()");
    }

    const TimeStepReport &report() const {
        if (!report_ready_) {
            std::vector<int> wall_materials;
            for (const auto &w : walls_)
                wall_materials.push_back(w.material);
            report_ = compute_time_step(settings_, units_, wall_materials);
            report_ready_ = true;
        }
        return report_;
    }

    void command(const std::string &line) {
        transcript_ << line << '\n';
        lammps_command(lmp_, const_cast<char *>(line.c_str()));
    }

    void set(const std::string &name, const std::string &value) {
        command("variable " + name + " string \"" + value + "\"");
    }

    // lammps_file, not the `include` command: an include issued through
    // lammps_command is only queued and never read.
    void include(const char *file) {
        std::string path = std::string(ARMOUR_LIGGGHTS_INPUTS) + "/" + file;
        transcript_ << "include " << path << '\n';
        lammps_file(lmp_, path.data());
    }

    // Per material pair, as LIGGGHTS' peratomtypepair matrices (row-major).
    std::string pair_matrix(double Material::*field, double MaterialPair::*override_field) const {
        std::ostringstream s;
        s.precision(17);
        const int n = static_cast<int>(settings_.materials.size());
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b)
                s << pair_value(settings_, a, b, field, override_field) << ' ';
        return s.str();
    }

    void check_placement() const {
        for (std::size_t i = 0; i < bodies_.size(); ++i) {
            const Body &b = bodies_[i];
            const UnitTemplate &u = units_[b.init.unit];
            for (const auto &s : u.clump) {
                const Eigen::Vector3d c = b.init.pose.position + b.init.pose.orientation * s.center;
                if (((c.array() - s.radius) < settings_.domain_min.array()).any() ||
                    ((c.array() + s.radius) > settings_.domain_max.array()).any())
                    throw InputError("body " + std::to_string(i) + " (unit '" + u.name +
                                     "') reaches outside the domain at (" + num(c.x()) + ", " + num(c.y()) +
                                     ", " + num(c.z()) + ") m");
            }
        }
    }

    // `restart`: a LIGGGHTS restart file of this scene (read_state), whose
    // atoms and bodies replace the insertion of the bodies.
    void start(const std::string &restart = "") {
        if (bodies_.empty())
            throw InputError("scene: no bodies to simulate");
        report();
        check_placement();
        open_liggghts();
        const double largest = set_domain_and_contact();
        if (restart.empty()) {
            include("domain.in");
        } else {
            set("restart_file", restart);
            include("restart.in");
        }
        include("contact.in");
        add_walls();
        add_unit_templates();
        if (!restart.empty()) {
            include("integrate.in");
            write_external_loads(); // gravity too: the set-up's body forces feed the first half-step
            command("run 0 post no");
            read_states();
            return;
        }
        insert_bodies(largest);
        include("integrate.in");
        // One step inserts the bodies; then each is put exactly where asked.
        command("run 1");
        for (std::size_t i = 0; i < bodies_.size(); ++i)
            command("unfix place" + std::to_string(i));
        place_exactly();
        command("run 0 post no");
        read_states();
        // The set-up as a plain LIGGGHTS script, for users and for bench/.
        std::ofstream(work_dir_ / "input.liggghts")
            << "# LIGGGHTS commands of this run's set-up, in order. After `run 1` the adapter set each\n"
            << "# body's exact pose, velocity and locked axes; gravity and external loads are applied\n"
            << "# per body (dragforce_cm/hdtorque_cm) before every run.\n"
            << transcript_.str();
    }

    // One serial LIGGGHTS instance of this process, in its work folder.
    void open_liggghts() {
        int initialised = 0;
        MPI_Initialized(&initialised);
        if (!initialised)
            MPI_Init(nullptr, nullptr);
        // In an MPI job (a parallel interFoam) every rank runs its own serial
        // replica and writes the same file names: rank r > 0 keeps its files
        // in work_dir/processor<r>, rank 0 in work_dir itself, where a serial
        // run puts them (the files a run keeps are rank 0's).
        int rank = 0;
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);
        work_dir_ = base_dir_;
        if (rank > 0)
            work_dir_ /= "processor" + std::to_string(rank);
        std::error_code ec;
        fs::create_directories(work_dir_, ec);
        if (ec)
            throw InputError(work_dir_.string() +
                             ": cannot create the LIGGGHTS work folder: " + ec.message());
        const fs::path log = work_dir_ / "log.liggghts";
        g_log_path = log.string();
        static bool registered = false;
        if (!registered) {
            std::atexit(report_liggghts_exit);
            registered = true;
        }
        std::string log_arg = log.string();
        const char *args[] = {"liggghts", "-screen", "/dev/null", "-log", log_arg.c_str()};
        {
            // A second LIGGGHTS instance in one process prints hundreds of
            // harmless "style collision" warnings on stderr while it starts.
            std::fflush(stderr);
            const int saved = ::dup(STDERR_FILENO);
            const int null = ::open("/dev/null", O_WRONLY);
            if (null >= 0)
                ::dup2(null, STDERR_FILENO);
            // MPI_COMM_SELF: one serial LIGGGHTS per process. On
            // MPI_COMM_WORLD the ranks of a parallel interFoam would join one
            // LIGGGHTS run split over a processor grid; the coupling wants a
            // whole replica per rank instead, fed the same summed loads, so
            // that every rank takes the same step (serial LIGGGHTS is
            // deterministic). Nothing LIGGGHTS does here talks to
            // MPI_COMM_WORLD: its one use, a timing gather in Finish::end,
            // needs modify_timing verbose, which the inputs never set.
            lammps_open(5, const_cast<char **>(args), MPI_COMM_SELF, &lmp_);
            if (saved >= 0)
                ::dup2(saved, STDERR_FILENO);
            if (null >= 0)
                ::close(null);
            if (saved >= 0)
                ::close(saved);
        }
    }

    // The box, the materials and the contact model as the input files' variables;
    // returns the largest sphere radius (m).
    double set_domain_and_contact() {
        const Eigen::Vector3d &lo = settings_.domain_min, &hi = settings_.domain_max;
        set("xlo", num(lo.x()));
        set("ylo", num(lo.y()));
        set("zlo", num(lo.z()));
        set("xhi", num(hi.x()));
        set("yhi", num(hi.y()));
        set("zhi", num(hi.z()));
        set("ntypes", std::to_string(settings_.materials.size()));
        double largest = 0.0;
        for (const auto &u : units_)
            for (const auto &s : u.clump)
                largest = std::max(largest, s.radius);
        // The neighbour lists are rebuilt whenever a sphere has moved half the
        // skin. A skin sized by the smallest sphere (a clump's 0.4 mm corner
        // spheres) rebuilt them every 3 steps in a moving pile: 10 x the cost
        // of 0.2 x the largest radius, which costs about the same at rest and
        // changes no contact (bench/run_dem_skin.sh; docs/validation/speed.md,
        // "The DEM's neighbour lists").
        set("skin", num(kSkinOfLargestRadius * largest));
        std::ostringstream youngs, poisson;
        youngs.precision(17);
        poisson.precision(17);
        bool rolling = false;
        for (const auto &m : settings_.materials) {
            youngs << m.youngs_modulus << ' ';
            poisson << m.poisson_ratio << ' ';
            rolling = rolling || m.rolling_friction > 0.0;
        }
        for (const auto &p : settings_.pairs)
            rolling = rolling || p.rolling_friction > 0.0;
        set("youngs", youngs.str());
        set("poisson", poisson.str());
        set("restitution", pair_matrix(&Material::restitution, &MaterialPair::restitution));
        set("friction", pair_matrix(&Material::friction, &MaterialPair::friction));
        set("rolling", pair_matrix(&Material::rolling_friction, &MaterialPair::rolling_friction));
        set("characteristic_velocity", num(settings_.characteristic_velocity));
        set("model", settings_.contact == ContactModel::hooke ? "hooke" : "hertz");
        set("rolling_model", rolling ? "rolling_friction cdt" : "");
        set("dt", num(report_.used));
        return largest;
    }

    // Each wall as an STL mesh clipped to the box.
    void add_walls() {
        const Eigen::Vector3d &lo = settings_.domain_min, &hi = settings_.domain_max;
        std::string wall_ids;
        for (std::size_t w = 0; w < walls_.size(); ++w) {
            const fs::path file = work_dir_ / ("wall" + std::to_string(w) + ".stl");
            // LIGGGHTS drops (and then aborts on) mesh elements outside its
            // box: a plane wall is a big square, an STL block may reach past
            // the flume. Only the part inside the domain can be touched.
            const Eigen::Vector3d inset = Eigen::Vector3d::Constant(1e-9 * (hi - lo).norm());
            const TriangleMesh inside = clipped_to_box(walls_[w].surface, lo + inset, hi - inset);
            if (inside.triangles.empty())
                throw InputError(
                    "wall '" + walls_[w].name +
                    "': lies wholly outside run.domain_min/domain_max; move it or enlarge the domain");
            write_stl(inside, file.string(), false, walls_[w].name);
            set("wall_id", "wall" + std::to_string(w));
            set("wall_file", file.string());
            set("wall_type", std::to_string(walls_[w].material + 1));
            include("wall.in");
            wall_ids += "wall" + std::to_string(w) + " ";
        }
        if (!walls_.empty()) {
            set("n_walls", std::to_string(walls_.size()));
            set("wall_ids", wall_ids);
            include("walls.in");
        }
    }

    // Each unit as a multisphere template: its spheres, mass and inertia.
    void add_unit_templates() {
        for (std::size_t k = 0; k < units_.size(); ++k) {
            const UnitTemplate &u = units_[k];
            const fs::path file = work_dir_ / ("unit" + std::to_string(k + 1) + ".spheres");
            {
                std::ofstream out(file);
                out.precision(17);
                for (const auto &s : u.clump)
                    out << s.center.x() << ' ' << s.center.y() << ' ' << s.center.z() << ' ' << s.radius
                        << '\n';
            }
            const Eigen::Matrix3d &I = u.props.inertia;
            const double scale = I.cwiseAbs().maxCoeff();
            auto entry = [&](int i, int j) {
                return i != j && std::abs(I(i, j)) < 1e-12 * scale ? 0.0 : I(i, j);
            };
            set("unit_type", std::to_string(k + 1));
            set("atom_type", std::to_string(u.material + 1));
            set("density", num(u.props.density));
            set("nspheres", std::to_string(u.clump.size()));
            set("sphere_file", file.string());
            set("mass", num(u.props.mass));
            set("inertia", num(entry(0, 0)) + " " + num(entry(0, 1)) + " " + num(entry(0, 2)) + " " +
                               num(entry(1, 1)) + " " + num(entry(1, 2)) + " " + num(entry(2, 2)));
            include("unit_template.in");
        }
    }

    // `largest`: m, the largest sphere radius (sizes the insertion regions).
    void insert_bodies(double largest) {
        // The insertion region only needs a finite volume: place_exactly() then
        // moves each body onto its requested position.
        const double half = 1e-6 * std::max(1.0, largest);
        for (std::size_t i = 0; i < bodies_.size(); ++i) {
            const BodyInit &b = bodies_[i].init;
            const Eigen::Vector3d &p = b.pose.position;
            const Eigen::Quaterniond &q = b.pose.orientation;
            set("body", std::to_string(i));
            set("unit_type", std::to_string(b.unit + 1));
            set("bxlo", num(p.x() - half));
            set("bxhi", num(p.x() + half));
            set("bylo", num(p.y() - half));
            set("byhi", num(p.y() + half));
            set("bzlo", num(p.z() - half));
            set("bzhi", num(p.z() + half));
            set("qw", num(q.w()));
            set("qx", num(q.x()));
            set("qy", num(q.y()));
            set("qz", num(q.z()));
            set("vx", num(b.velocity.x()));
            set("vy", num(b.velocity.y()));
            set("vz", num(b.velocity.z()));
            set("wx", num(b.angular_velocity.x()));
            set("wy", num(b.angular_velocity.y()));
            set("wz", num(b.angular_velocity.z()));
            include("body.in");
        }
    }

    Multisphere &multisphere() const {
        auto *lmp = static_cast<LAMMPS_NS::LAMMPS *>(lmp_);
        const int ifix = lmp->modify->find_fix("integrate");
        return static_cast<LAMMPS_NS::FixMultisphere *>(lmp->modify->fix[ifix])->data();
    }

    LAMMPS_NS::FixMultisphere &fix_multisphere() const {
        auto *lmp = static_cast<LAMMPS_NS::LAMMPS *>(lmp_);
        return *static_cast<LAMMPS_NS::FixMultisphere *>(
            lmp->modify->fix[lmp->modify->find_fix("integrate")]);
    }

    // Principal frame -> world (quat is a 4-vector, which extract_double_vector does not serve).
    static Eigen::Quaterniond body_quaternion(Multisphere &ms, int local) {
        double q[4];
        ms.quat(q, local);
        return Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
    }

    // Matches LIGGGHTS' bodies to ours by position, records the rotation from
    // LIGGGHTS' principal frame to each unit frame, and sets the exact initial
    // state (insertion leaves a tiny offset and one step of motion).
    void place_exactly() {
        Multisphere &ms = multisphere();
        const int n = ms.n_body();
        if (n != static_cast<int>(bodies_.size()))
            throw std::runtime_error("LIGGGHTS inserted " + std::to_string(n) + " of " +
                                     std::to_string(bodies_.size()) + " bodies (see " + g_log_path + ")");
        double **xcm = ms.extract_double_vector("xcm");
        double **vcm = ms.extract_double_vector("vcm");
        double **omega = ms.extract_double_vector("omega");
        double **angmom = ms.extract_double_vector("angmom");
        double **ex = ms.extract_double_vector("ex_space");
        double **ey = ms.extract_double_vector("ey_space");
        double **ez = ms.extract_double_vector("ez_space");
        double **inertia = ms.extract_double_vector("inertia");
        std::vector<char> taken(n, 0);
        principal_to_unit_.assign(units_.size(), Eigen::Quaterniond::Identity());
        for (std::size_t i = 0; i < bodies_.size(); ++i) {
            Body &b = bodies_[i];
            int best = -1;
            double best_d = HUGE_VAL;
            for (int k = 0; k < n; ++k) {
                if (taken[k])
                    continue;
                const double d =
                    (Eigen::Vector3d(xcm[k][0], xcm[k][1], xcm[k][2]) - b.init.pose.position).norm();
                if (d < best_d) {
                    best_d = d;
                    best = k;
                }
            }
            taken[best] = 1;
            b.tag = ms.tag(best);
            // q_body (principal -> world) = q_insert (unit -> world) * q_p (principal -> unit).
            const Eigen::Quaterniond body = body_quaternion(ms, best);
            principal_to_unit_[b.init.unit] = (b.init.pose.orientation.conjugate() * body).normalized();
            const Eigen::Matrix3d R = body.toRotationMatrix();
            for (int a = 0; a < 3; ++a) {
                xcm[best][a] = b.init.pose.position[a];
                vcm[best][a] = b.init.velocity[a];
                omega[best][a] = b.init.angular_velocity[a];
                ex[best][a] = R(a, 0);
                ey[best][a] = R(a, 1);
                ez[best][a] = R(a, 2);
            }
            // Angular momentum from omega: L = R diag(I) R^T omega.
            const Eigen::Vector3d I(inertia[best][0], inertia[best][1], inertia[best][2]);
            const Eigen::Vector3d L = R * (I.asDiagonal() * (R.transpose() * b.init.angular_velocity));
            for (int a = 0; a < 3; ++a)
                angmom[best][a] = L[a];
            bool free_translation[3], free_rotation[3];
            for (int a = 0; a < 3; ++a) {
                free_translation[a] = !b.init.fixed_translation[a];
                free_rotation[a] = !b.init.fixed_rotation[a];
            }
            ms.set_fflag(best, free_translation);
            ms.set_tflag(best, free_rotation);
        }
        fix_multisphere().add_body_finalize();
    }

    // Written before every run: LIGGGHTS zeroes them on insertion and does
    // not carry them across ranks.
    void write_external_loads() {
        Multisphere &ms = multisphere();
        double **force = ms.extract_double_vector("dragforce_cm");
        double **torque = ms.extract_double_vector("hdtorque_cm");
        for (auto &b : bodies_) {
            const int k = ms.map(b.tag);
            if (k < 0)
                continue;
            const Eigen::Vector3d f = b.force + units_[b.init.unit].props.mass * settings_.gravity;
            for (int a = 0; a < 3; ++a) {
                force[k][a] = f[a];
                torque[k][a] = b.torque[a];
            }
        }
    }

    void read_states() {
        Multisphere &ms = multisphere();
        double **xcm = ms.extract_double_vector("xcm");
        double **vcm = ms.extract_double_vector("vcm");
        double **omega = ms.extract_double_vector("omega");
        double **fcm = ms.extract_double_vector("fcm");
        double **drag = ms.extract_double_vector("dragforce_cm");
        for (auto &b : bodies_) {
            const int k = ms.map(b.tag);
            if (k < 0)
                throw InputError("body " + std::to_string(&b - bodies_.data()) +
                                 " left the domain at t = " + num(time()) +
                                 " s; enlarge run.domain_min/domain_max (results so far are kept)");
            BodyState &s = b.state;
            s.pose.position = Eigen::Vector3d(xcm[k][0], xcm[k][1], xcm[k][2]);
            const Eigen::Quaterniond body = body_quaternion(ms, k);
            s.pose.orientation = (body * principal_to_unit_[b.init.unit].conjugate()).normalized();
            s.velocity = Eigen::Vector3d(vcm[k][0], vcm[k][1], vcm[k][2]);
            s.angular_velocity = Eigen::Vector3d(omega[k][0], omega[k][1], omega[k][2]);
            s.contact_force =
                Eigen::Vector3d(fcm[k][0] - drag[k][0], fcm[k][1] - drag[k][1], fcm[k][2] - drag[k][2]);
            s.external_force = b.force;
            s.external_torque = b.torque;
        }
    }

    EngineSettings settings_;
    fs::path base_dir_, work_dir_;
    std::vector<UnitTemplate> units_;
    std::vector<Body> bodies_;
    std::vector<Wall> walls_;
    std::vector<Eigen::Quaterniond> principal_to_unit_;
    mutable TimeStepReport report_;
    mutable bool report_ready_ = false;
    void *lmp_ = nullptr;
    std::ostringstream transcript_;
};

} // namespace

EngineStyle liggghts_engine_style() {
    EngineCapabilities c;
    c.contacts = ContactKind::spring_dashpot;
    c.contact_models = {ContactModel::hooke, ContactModel::hertz};
    c.shape = ShapeModel::sphere_clumps;
    c.replica_per_rank = true; // one serial LIGGGHTS on MPI_COMM_SELF per rank
    c.restart = true;          // write_restart/read_restart keep the bodies and contact histories
    return {"liggghts", "LIGGGHTS 3.8 multisphere: sphere clumps, spring-dashpot contacts", c,
            [](const EngineSettings &s) { return make_liggghts_engine(s); }};
}

std::unique_ptr<RigidBodyEngine> make_liggghts_engine(const EngineSettings &settings) {
    return std::make_unique<LiggghtsEngine>(settings);
}

} // namespace armour
