// Runs a scene: engine set-up, time loop with progress, recording, analysis.
#include "run_command.h"

#include "analysis.h"
#include "bodies_file.h"
#include "body_recorder.h"
#include "checkpoints.h"
#include "clump_io.h"
#include "coupled_run.h"
#include "engine_registry.h"
#include "flume_mesh.h"
#include "foam_restart.h"
#include "mesh.h"
#include "output_folder.h"
#include "run_parts.h"
#include "scene_keys.h"
#include "scene_setup.h"
#include "scene_text.h"
#include "series_run.h"
#include "stl_io.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace armour {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

class Progress {
  public:
    // `earlier`: wall seconds of the run before this process (a resume).
    Progress(double duration, bool terminal, double earlier = 0.0)
        : duration_(duration), earlier_(earlier), terminal_(terminal) {}
    void update(double t) {
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        // ETA from this process's pace (a resume starts part way).
        const double fraction = std::min(1.0, t / duration_);
        const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
        if (terminal_) {
            const int filled = static_cast<int>(30 * fraction);
            std::fprintf(stderr, "\r[%-30s] t = %.3f / %.3f s  ETA %.0f s ", std::string(filled, '#').c_str(),
                         t, duration_, eta);
            if (fraction >= 1.0)
                std::fputc('\n', stderr);
        } else if (fraction >= next_report_ - 1e-12) {
            std::fprintf(stderr, "run: t = %.3f / %.3f s (%3.0f %%), ETA %.0f s\n", t, duration_,
                         100 * fraction, eta);
            next_report_ += 0.1;
        }
    }
    double seconds() const {
        return earlier_ + std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

  private:
    double duration_, earlier_;
    bool terminal_;
    double next_report_ = 0.1;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// Still water for a settle run (the coupled scene's, at rest): each unit
// carries the buoyancy of its part below the surface, so the layer settles
// under its submerged weight, as in a flume filled slowly.
struct StillWater {
    double level = 0.0;                  // m, z of the surface
    double density = kFreshWaterDensity; // kg/m^3
    double update_interval = 0.0;        // s between buoyancy updates
};

// Buoyancy on body `state` of unit `unit`: -rho g V_below at the centroid of
// the part below the surface, as a force and a torque about the centre of mass.
void set_buoyancy(RigidBodyEngine &engine, int body, const UnitTemplate &unit, const BodyState &state,
                  const StillWater &water, const Eigen::Vector3d &gravity) {
    const Eigen::Matrix3d R = state.pose.orientation.normalized().toRotationMatrix();
    const Eigen::Vector3d surface_point(state.pose.position.x(), state.pose.position.y(), water.level);
    // The unit's mesh is in its own frame, centred on its centre of mass.
    const PartBelowPlane below =
        part_below_plane(unit.mesh, R.transpose() * (surface_point - state.pose.position),
                         R.transpose() * Eigen::Vector3d::UnitZ());
    const Eigen::Vector3d force = -water.density * below.volume * gravity;
    const Eigen::Vector3d arm =
        below.volume > 0.0 ? Eigen::Vector3d(R * below.centroid) : Eigen::Vector3d::Zero();
    engine.set_external_load(body, force, arm.cross(force));
}

// The scene's engine with its units, walls and bodies, not started.
std::unique_ptr<RigidBodyEngine> scene_engine(const Scene &scene, const SceneSetup &setup,
                                              const EngineSettings &settings) {
    std::unique_ptr<RigidBodyEngine> engine = make_engine(scene.engine, settings);
    for (const auto &u : setup.units)
        engine->add_template(u);
    for (const auto &w : setup.walls)
        engine->add_wall(w);
    for (const auto &b : setup.bodies)
        engine->add_body(b);
    return engine;
}

// The DEM run of a scene without [fluid], dry or (`water`, a settle run)
// under still water's buoyancy, into `folder`; `final_states` (optional)
// receives every body's state at the end. `resume`: continue the run in
// `folder` (resumed already) from this checkpoint.
int run_dem(OutputFolder &folder, const Scene &scene, SceneSetup &setup, std::vector<BodyState> *final_states,
            const StillWater *water = nullptr, const Checkpoint *resume = nullptr) {
    const bool terminal = ::isatty(STDERR_FILENO) != 0;
    // Everything is checked before the output folder is touched.
    const fs::path out = folder.target();
    setup.settings.work_dir = (out / scene.engine).string();
    std::unique_ptr<RigidBodyEngine> engine = scene_engine(scene, setup, setup.settings);
    const TimeStepReport dt = engine->time_step_report();
    if (resume)
        engine->load_state((resume->dir / "engine").string());

    folder.open();              // an earlier result of this command is replaced (resumed: nothing)
    folder.claim(scene.engine); // the engine's own files (work_dir), if it writes any
    std::error_code ec;
    fs::create_directories(folder.claim("units"), ec);
    if (ec)
        throw InputError("--out: cannot create " + out.string() + ": " + ec.message());
    write_text_file(folder.claim("scene.resolved.toml"), resolved_scene_toml(scene));
    std::vector<RecorderUnit> recorder_units;
    for (const auto &u : setup.units) {
        const fs::path dir = out / "units" / u.name;
        fs::create_directories(dir);
        write_sphere_file(u.clump, (dir / "clump.spheres").string(), u.name);
        write_stl(u.mesh, (dir / "shape.stl").string(), true, u.name);
        recorder_units.push_back({u.name, u.mesh});
    }
    std::vector<int> body_unit;
    for (const auto &b : setup.bodies)
        body_unit.push_back(b.unit);
    // Start the engine before opening the trajectory file: MPI's start-up may
    // fork a helper that would inherit (and keep locked) any file open then.
    engine->state(0);
    const fs::path h5 = folder.claim("bodies.h5"), xdmf = folder.claim("bodies.xdmf");
    // A resumed run replays the records up to its checkpoint into the
    // energy balance and the analysis, then appends after them.
    BodiesFile earlier;
    if (resume) {
        earlier = read_bodies_file(h5.string());
        if (static_cast<long>(earlier.steps()) < resume->records || earlier.bodies() != setup.bodies.size())
            throw InputError(h5.string() + ": holds " + std::to_string(earlier.steps()) + " steps of " +
                             std::to_string(earlier.bodies()) + " bodies, not the " +
                             std::to_string(resume->records) + " steps of " +
                             std::to_string(setup.bodies.size()) + " bodies its checkpoint " +
                             resume->dir.string() + " recorded");
    }
    const std::unique_ptr<BodyRecorder> recorder =
        resume ? BodyRecorder::reopen(h5.string(), xdmf.string(), recorder_units, body_unit, resume->records)
               : std::make_unique<BodyRecorder>(
                     h5.string(), xdmf.string(), recorder_units, body_unit,
                     std::vector<std::pair<std::string, std::string>>{
                         {"scene", scene.name}, {"engine", engine->name()}, {"dt", std::to_string(dt.used)}},
                     scene.checkpoint_interval <= 0.0);
    Checkpoints checkpoints(out, scene.checkpoint_interval, resume ? resume->time : 0.0);
    if (scene.checkpoint_interval > 0.0)
        folder.claim("checkpoints");

    std::vector<BodyState> states(setup.bodies.size());
    // Mechanical energy of all bodies (kinetic + potential in the scene's
    // gravity), at output times: stability studies compare its maximum with
    // its initial value (a stable, dissipative run never gains energy).
    std::optional<double> energy_initial;
    double energy_scale = 0.0; // sum of m |g| Dn: the energy of lifting every unit by its size
    for (const auto &b : setup.bodies)
        energy_scale += setup.units[b.unit].props.mass * scene.gravity.norm() * setup.unit_Dn[b.unit];
    double energy_max = -HUGE_VAL, energy_final = 0.0;
    auto account = [&] {
        double energy = 0.0;
        for (std::size_t i = 0; i < states.size(); ++i) {
            const MassProperties &p = setup.units[setup.bodies[i].unit].props;
            const Eigen::Matrix3d R = states[i].pose.orientation.toRotationMatrix();
            const Eigen::Vector3d &w = states[i].angular_velocity;
            energy += 0.5 * p.mass * states[i].velocity.squaredNorm() +
                      0.5 * w.dot(R * p.inertia * R.transpose() * w) -
                      p.mass * scene.gravity.dot(states[i].pose.position);
        }
        if (!energy_initial)
            energy_initial = energy;
        energy_max = std::max(energy_max, energy);
        energy_final = energy;
    };
    auto record = [&] {
        for (int i = 0; i < engine->body_count(); ++i)
            states[i] = engine->state(i);
        account();
        recorder->append(engine->time(), states);
    };

    const auto claim = [&](const std::string &name) { return folder.claim(name).string(); };
    const std::unique_ptr<Analysis> analysis = make_analysis({scene, setup, out.string(), "", claim});
    Progress progress(scene.duration, terminal, resume ? resume->wall_seconds : 0.0);
    long first = 1; // the first output step to compute
    if (resume) {
        for (long step = 0; step < resume->records; ++step) {
            const auto s = static_cast<std::size_t>(step);
            earlier.states_at(s, states);
            account();
            analysis->sample(earlier.time[s], states);
        }
        first = resume->records;
        std::fprintf(stderr, "run: resuming at t = %.6g s from %s\n", resume->time, resume->dir.c_str());
    } else {
        analysis->before_advance(0.0, *engine);
        record();
        analysis->sample(engine->time(), states);
    }
    const long outputs = std::lround(std::ceil(scene.duration / scene.output_interval - 1e-9));
    for (long k = first; k <= outputs; ++k) {
        const double target = std::min(scene.duration, static_cast<double>(k) * scene.output_interval);
        do {
            // The analysis (tilt turns gravity) and the still water's buoyancy
            // both act between engine advances of at most their own span.
            double span = analysis->before_advance(engine->time(), *engine);
            if (water) {
                for (int i = 0; i < engine->body_count(); ++i)
                    set_buoyancy(*engine, i, setup.units[setup.bodies[i].unit], engine->state(i), *water,
                                 scene.gravity);
                span = std::min(span, water->update_interval);
            }
            engine->advance_to(std::min(engine->time() + std::max(span, dt.used), target));
        } while (engine->time() < target - 0.5 * dt.used);
        record();
        analysis->sample(engine->time(), states);
        if (analysis->finished()) {
            std::fprintf(stderr, "run: %s test decided at t = %.3f s, stopping\n", scene.analysis.c_str(),
                         engine->time());
            break;
        }
        // Not at the last record: the run is whole then (summary.json).
        if (k < outputs && checkpoints.due(engine->time()))
            checkpoints.write({engine->time(), recorder->steps(), progress.seconds(), {}},
                              [&](const fs::path &dir) { engine->save_state((dir / "engine").string()); });
        progress.update(engine->time());
    }
    recorder->close();
    const double wall_seconds = progress.seconds();

    json spheres = json::object();
    for (std::size_t k = 0; k < setup.units.size(); ++k)
        spheres[setup.units[k].name] = setup.unit_spheres[k];
    json summary = {
        {"command", "run"},
        {"scene", scene.name},
        {"engine", engine->name()},
        {"spheres_per_unit", spheres},
        {"units", static_cast<int>(setup.bodies.size())},
        {"dt", dt.used},
        {"dt_limit", dt.limit},
        {"dt_forced", dt.forced},
        {"dt_rule", dt.rule},
        {"rayleigh_time", dt.rayleigh},
        {"contact_duration", dt.contact_duration},
        {"steps", engine->steps()},
        {"simulated_seconds", engine->time()},
        {"wall_seconds", wall_seconds},
        {"wall_seconds_per_simulated_second", wall_seconds / std::max(engine->time(), 1e-300)},
        {"seconds_per_unit_step", wall_seconds / (static_cast<double>(std::max(1L, engine->steps())) *
                                                  static_cast<double>(setup.bodies.size()))},
        {"energy_initial", energy_initial.value_or(0.0)},
        {"energy_max", energy_max},
        {"energy_final", energy_final},
        {"energy_scale", energy_scale},
        {"files", {{"bodies", "bodies.h5"}, {"paraview", "bodies.xdmf"}, {"scene", "scene.resolved.toml"}}},
        {"si_units",
         {{"dt", "s"}, {"wall_seconds", "s"}, {"angles", "deg"}, {"lengths", "m"}, {"energy", "J"}}}};
    if (const std::string line = analysis->write(summary); !line.empty())
        std::fprintf(stderr, "run: %s: %s\n", scene.analysis.c_str(), line.c_str());
    write_text_file(folder.claim("summary.json"), summary.dump(2) + "\n");
    std::printf("%s: %d units, %ld steps of %.3g s, %.1f s wall -> %s\n", scene.name.c_str(),
                static_cast<int>(setup.bodies.size()), engine->steps(), dt.used, wall_seconds, out.c_str());
    if (final_states)
        *final_states = states;
    return 0;
}

// The settle's friction between the units (fluid.settle_friction): every
// pair of materials that units are made of gets it as a pair override;
// a wall of such a material meets the units with it too.
void set_friction_between_units(Scene &scene, double friction) {
    std::vector<std::string> names;
    for (const SceneUnit &u : scene.units)
        if (std::find(names.begin(), names.end(), u.material) == names.end())
            names.push_back(u.material);
    for (std::size_t i = 0; i < names.size(); ++i)
        for (std::size_t j = i; j < names.size(); ++j) {
            auto found =
                std::find_if(scene.material_pairs.begin(), scene.material_pairs.end(),
                             [&](const SceneMaterialPair &p) { return p.joins(names[i], names[j]); });
            if (found == scene.material_pairs.end()) {
                scene.material_pairs.push_back(
                    {names[i], names[j], std::nullopt, std::nullopt, std::nullopt});
                found = std::prev(scene.material_pairs.end());
            }
            found->friction = friction;
        }
}

} // namespace

// OUT/settle/settled.json with the speed below which the layer counts as
// still: 1 % of the smallest unit's size per second, the drift a resting
// unit may show in water (the coupled rest test). A layer still moving
// faster readjusts in the first coupled steps, and the flow (and the
// pressure solver) sees that as a real motion.
json settle_report(const fs::path &dir, const SceneSetup &setup) {
    std::ifstream in(dir / "settled.json");
    json report = json::parse(in);
    double Dn = HUGE_VAL;
    for (const double d : setup.unit_Dn)
        Dn = std::min(Dn, d);
    report["still_speed"] = 0.01 * Dn / 1.0;
    return report;
}

// The coupled summary says where its start came from.
int with_settle_report(OutputFolder &folder, int status, json report) {
    const fs::path summary_file = folder.claim("summary.json");
    std::ifstream in(summary_file);
    if (status == 0 && in) {
        json summary = json::parse(in);
        in.close();
        report["scene"] = "settle/scene.settled.toml";
        summary["settle"] = report;
        write_text_file(summary_file, summary.dump(2) + "\n");
    }
    return status;
}

// A settle in an exact-shape engine for a run in a clump engine: the clump's
// spheres stand out of the exact faces (the stability scene's 118-sphere cube
// by 1.2 mm, 0.03 Dn), so the exact shapes' settled poses would start each
// clump inside its neighbours and the slope. The settle's cubes grow (edge
// and chamfer, about their centres) until every sphere lies inside
// (growth_to_hold_clump): the clumps start in contact or apart, and the
// exact shapes of a run of the settled scene at most that growth apart,
// one layer for both unit models (docs/stability.md). Only cubes: a dolos's
// flukes do not grow about its centre, and an STL unit has no size key.
void grow_units_to_hold_clumps(Scene &dry, const Scene &scene, const SceneSetup &setup) {
    if (engine_style(dry.engine).capabilities.shape != ShapeModel::convex_hulls ||
        engine_style(scene.engine).capabilities.shape != ShapeModel::sphere_clumps)
        return;
    for (std::size_t k = 0; k < dry.units.size(); ++k) {
        SceneUnit &u = dry.units[k];
        const std::optional<double> growth = growth_to_hold_clump(setup.units[k]);
        if (u.shape != "cube" || !growth)
            throw InputError(scene.file + ": key 'fluid.settle_engine': " + dry.engine +
                             " settles exact shapes and run.engine " + scene.engine +
                             " runs sphere clumps from their poses, which needs each unit grown to hold its "
                             "clump; unit '" +
                             u.name + "' is a " + u.shape + " (only cubes grow); settle with run.engine");
        u.size *= *growth;
        u.chamfer *= *growth;
    }
}

// The settle's own scene (OUT/settle/scene.resolved.toml reruns it): the
// scene without its fluid, the pile's headroom in its domain, its friction
// between units as pairs.
Scene settle_scene(const Scene &scene, const SceneSetup &setup) {
    const SceneFluid &fluid = *scene.fluid;
    Scene dry = scene;
    dry.fluid.reset();
    dry.waves.reset(); // both need [fluid]
    dry.porous.clear();
    dry.duration = fluid.settle_time;
    dry.output_interval = std::min(scene.output_interval, fluid.settle_time);
    dry.analysis = "none";
    dry.checkpoint_interval = 0.0; // the settle run is short; the coupled run checkpoints
    dry.series.clear();            // the waves' steps, not the settle's
    if (!fluid.settle_engine.empty())
        dry.engine = fluid.settle_engine;
    grow_units_to_hold_clumps(dry, scene, setup);
    dry.domain_max.z() += settle_headroom(scene, setup);
    if (fluid.settle_friction)
        set_friction_between_units(dry, *fluid.settle_friction);
    return dry;
}

// The scene the coupled run starts from after the settle: the same scene
// with every unit an explicit [[body]] (`bodies`: at the settled poses).
std::vector<SceneBody> bodies_at_rest(const Scene &scene, const SceneSetup &setup,
                                      const std::vector<BodyState> &states) {
    std::vector<SceneBody> bodies;
    for (std::size_t i = 0; i < states.size(); ++i) {
        SceneBody b;
        if (i < scene.bodies.size())
            b = scene.bodies[i]; // explicit bodies keep their held axes
        b.unit = setup.units[static_cast<std::size_t>(setup.bodies[i].unit)].name;
        b.position = states[i].pose.position;
        const Eigen::Quaterniond q = states[i].pose.orientation.normalized();
        b.orientation = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
        b.velocity.setZero();
        b.angular_velocity.setZero();
        bodies.push_back(b);
    }
    return bodies;
}

Scene settled_scene(const Scene &scene, std::vector<SceneBody> bodies) {
    Scene settled = scene;
    settled.fluid->settle_time = 0.0;
    settled.fluid->settle_friction.reset();
    settled.fluid->settled_by =
        scene.fluid->settle_engine.empty() ? scene.engine : scene.fluid->settle_engine;
    settled.fluid->settle_engine.clear();
    settled.drops.clear();
    settled.patterns.clear();
    settled.bodies = std::move(bodies);
    return settled;
}

// Settles a coupled scene's units in the DEM for fluid.settle_time, under
// the buoyancy of the scene's still water (without it the contacts, loaded
// by the dry weight, would relax in the first coupled steps as if the water
// had appeared at once), and returns the scene the coupled run starts from:
// the same scene with every unit an explicit [[body]] at its settled pose, at
// rest. The DEM runs in a forked child: an engine that starts MPI (LIGGGHTS)
// in this process would leave it unable to launch interFoam under mpirun.
// The child writes OUT/settle (a normal `armour run` output), OUT/settle/scene.settled.toml
// (rerunnable on its own) and OUT/settle/settled.json (how still it got).
Scene settle_before_coupling(const RunRequest &r, OutputFolder &folder, const Scene &scene, SceneSetup &setup,
                             json &report) {
    const SceneFluid &fluid = *scene.fluid;
    const Scene dry = settle_scene(scene, setup); // refused here, before anything is written
    const fs::path dir = folder.claim("settle");
    const fs::path settled_file = dir / "scene.settled.toml";
    std::fprintf(stderr,
                 "run: settling %zu units in the DEM under still water (level %g m) for %g s "
                 "(fluid.settle_time)%s -> %s\n",
                 setup.bodies.size(), fluid.water_level, fluid.settle_time,
                 fluid.settle_friction
                     ? (", friction " + number_text(*fluid.settle_friction) + " between units").c_str()
                     : "",
                 dir.c_str());
    for (std::size_t k = 0; k < dry.units.size(); ++k)
        if (dry.units[k].size != scene.units[k].size)
            std::fprintf(
                stderr,
                "run: the settle's %s cubes '%s' are grown %.4g x (edge %.4g m) so that the run's clumps "
                "start inside them\n",
                dry.engine.c_str(), dry.units[k].name.c_str(), dry.units[k].size / scene.units[k].size,
                dry.units[k].size);
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid < 0)
        throw InputError("fluid.settle_time: cannot start the settle run (fork failed)");
    if (pid == 0) {
        int status = 1;
        try {
            OutputFolder settle_folder(dir, "armour run", OutputFolder::Mode::streaming);
            std::vector<BodyState> states;
            StillWater water;
            water.level = fluid.water_level;
            water.density = fluid.fluid_density;
            water.update_interval = std::min(fluid.max_time_step, dry.output_interval);
            SceneSetup dry_setup = build_scene(dry, r.cache.empty() ? default_cache_dir() : r.cache, false);
            if (dry_setup.bodies.size() != setup.bodies.size())
                throw InputError("fluid.settle_time: the settle placed " +
                                 std::to_string(dry_setup.bodies.size()) + " units, the scene " +
                                 std::to_string(setup.bodies.size()));
            run_dem(settle_folder, dry, dry_setup, &states, &water);

            std::vector<SceneBody> bodies = bodies_at_rest(scene, setup, states);
            double speed = 0.0, displacement = 0.0;
            for (std::size_t i = 0; i < states.size(); ++i) {
                speed = std::max(speed, states[i].velocity.norm());
                displacement =
                    std::max(displacement, (states[i].pose.position - setup.bodies[i].pose.position).norm());
            }
            write_text_file(settle_folder.claim(settled_file.filename().string()),
                            resolved_scene_toml(settled_scene(scene, std::move(bodies))));
            write_text_file(
                settle_folder.claim("settled.json"),
                json{
                    {"settle_time", fluid.settle_time},
                    {"settle_friction", fluid.settle_friction ? json(*fluid.settle_friction) : json(nullptr)},
                    {"water_level", water.level},
                    {"water_density", water.density},
                    {"max_speed_at_end", speed},
                    {"max_displacement", displacement},
                    {"units", states.size()},
                    {"si_units", {{"speed", "m/s"}, {"lengths", "m"}, {"water_density", "kg/m^3"}}}}
                        .dump(2) +
                    "\n");
            status = 0;
        } catch (const std::exception &e) {
            std::fprintf(stderr, "armour: settle run: %s\n", e.what());
        }
        std::fflush(nullptr);
        ::_exit(status);
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !fs::is_regular_file(settled_file))
        throw InputError(scene.file + ": key 'fluid.settle_time': the dry settle run failed (see the line " +
                         "above and " + dir.string() + ")");
    report = settle_report(dir, setup);
    const double speed = report["max_speed_at_end"].get<double>(),
                 still = report["still_speed"].get<double>();
    if (speed > still)
        std::fprintf(stderr,
                     "armour: warning: after fluid.settle_time = %g s a unit still moves at %.3g m/s (> %.3g "
                     "m/s, 1 %% of Dn per second): the layer has not settled and will readjust in the "
                     "water; raise fluid.settle_time\n",
                     fluid.settle_time, speed, still);
    // A settle cut short hands over a pile still falling: units above the
    // domain or overlapping. Say so in the user's own terms.
    try {
        Scene settled = load_scene(settled_file.string());
        setup = build_scene(settled, r.cache.empty() ? default_cache_dir() : r.cache, false);
        return settled;
    } catch (const InputError &e) {
        if (speed <= still)
            throw;
        throw InputError(scene.file + ": key 'fluid.settle_time': after " + number_text(fluid.settle_time) +
                         " s a unit still moved at " + figure_text(speed) +
                         " m/s and the settled pose is refused (" + e.what() + "); raise fluid.settle_time");
    }
}

// A run that asks for checkpoints but will write none (they fall at
// multiples of the interval, never at the last step) cannot be resumed:
// say so before hours are spent on it.
void warn_if_no_checkpoint(const Scene &scene) {
    const double interval = scene.checkpoint_interval;
    if (interval > 0.0 && interval >= scene.duration)
        std::fprintf(stderr,
                     "armour: warning: run.checkpoint_interval = %g s is not below run.duration = %g s: "
                     "no checkpoint is written (none at the last step), so this run cannot be "
                     "resumed\n",
                     interval, scene.duration);
}

// The scene as far as a resume may not change it: the keys a resume may
// change (docs/checkpoints.md) set to fixed values.
std::string resumable_form(Scene s, bool resumable_keys) {
    if (s.fluid)
        s.fluid->settled_by.clear(); // a record of who settled the layer (runs before it lack it)
    if (resumable_keys) {
        s.duration = 1.0;
        s.checkpoint_interval = 0.0;
        if (s.fluid) {
            s.fluid->write_interval = 0.0; // its default follows run.duration
            s.fluid->write_interval_given = false;
            // The ranks and the Courant limits set how the steps after the
            // checkpoint are taken, not what it holds (the fields are split
            // anew for other ranks).
            s.fluid->np = 1;
            s.fluid->max_courant = s.fluid->max_interface_courant = 1.0;
            s.fluid->max_interface_courant_given = false;
            s.fluid->min_time_step = 0.0; // a watch on the solver; its default follows the limits
            s.fluid->min_time_step_given = false;
        }
    }
    return scene_keys_text(resolved_scene_toml(s)); // comments name the file
}

void refuse_if_differs(const std::string &scene_file, const std::string &now, const std::string &before,
                       const std::string &where) {
    if (now == before)
        return;
    std::istringstream a(now), b(before);
    std::string la, lb;
    while (std::getline(a, la) && std::getline(b, lb) && la == lb) {
    }
    throw InputError(
        scene_file + ": differs from the scene that " + where + " ('" + la + "' against '" + lb +
        "'); a resume may change only run.duration, run.checkpoint_interval, "
        "fluid.write_interval, fluid.max_courant, fluid.max_interface_courant, fluid.min_time_step and "
        "--np");
}

// The checkpoint `armour run --resume` continues from, after checking that
// the scene is the one that ran in `out` but for the resumable keys.
Checkpoint checked_resume(const RunRequest &r, const Scene &scene, const fs::path &out) {
    const std::optional<Checkpoint> last = last_checkpoint(out);
    if (!last)
        throw InputError("--resume: " + out.string() +
                         " holds no complete checkpoint (run.checkpoint_interval was 0, or the run stopped "
                         "before its first)");
    const fs::path ran = out / "scene.resolved.toml";
    if (!fs::is_regular_file(ran))
        throw InputError("--resume: " + ran.string() + " is missing: not a run to continue");
    refuse_if_differs(r.scene, resumable_form(scene), resumable_form(load_scene(ran.string())),
                      "ran in " + out.string());
    if (last->time >= scene.duration)
        throw InputError("--resume: the last checkpoint (t = " + checkpoint_name(last->time) +
                         " s) is not before run.duration = " + checkpoint_name(scene.duration) + " s");
    return *last;
}

// `--resume` of a run that settled its units first: the settle is not run
// again. The scene must be the one that ran but for the resumable keys:
// the settle's (OUT/settle/scene.resolved.toml: units, placement,
// materials, walls, settle time and friction) and the coupled run's from
// the settled poses (OUT/scene.resolved.toml). Returns the settled scene and
// the checkpoint it continues from; reads `out` only.
Scene checked_settle(const RunRequest &r, const Scene &scene, const SceneSetup &setup, const fs::path &out) {
    const fs::path dir = out / "settle";
    for (const char *name : {"scene.resolved.toml", "scene.settled.toml", "settled.json"})
        if (!fs::is_regular_file(dir / name))
            throw InputError("--resume: " + (dir / name).string() +
                             " is missing: the run stopped before its settle ended; start it again without "
                             "--resume");
    refuse_if_differs(r.scene, resumable_form(settle_scene(scene, setup), false),
                      resumable_form(load_scene((dir / "scene.resolved.toml").string()), false),
                      "settled in " + dir.string());
    return settled_scene(scene, load_scene((dir / "scene.settled.toml").string()).bodies);
}

std::pair<Scene, Checkpoint> checked_settled_resume(const RunRequest &r, const Scene &scene,
                                                    const SceneSetup &setup, const fs::path &out) {
    Scene settled = checked_settle(r, scene, setup, out);
    const Checkpoint checkpoint = checked_resume(r, settled, out);
    return {std::move(settled), checkpoint};
}

namespace {

int resume_settled(const RunRequest &r, OutputFolder &folder, const Scene &scene, const SceneSetup &setup) {
    const auto [settled, checkpoint] = checked_settled_resume(r, scene, setup, folder.target());
    const SceneSetup settled_setup =
        build_scene(settled, r.cache.empty() ? default_cache_dir() : r.cache, false);
    folder.resume();
    return with_settle_report(folder, run_coupled(r, settled, settled_setup, folder, &checkpoint),
                              settle_report(folder.target() / "settle", setup));
}

} // namespace

// The options that do not fit the scene, refused before any work.
void check_options(const RunRequest &r, const Scene &scene) {
    if (!scene.fluid && r.np != 0)
        throw InputError("--np: only for scenes with a [fluid] table (MPI ranks of interFoam)");
    if (r.resume && !engine_style(scene.engine).capabilities.restart)
        throw InputError(r.scene + ": key 'run.engine': the " + scene.engine +
                         " engine cannot restore a state, so its runs cannot be resumed");
}

void warn_if_settle_friction_unused(const Scene &scene) {
    if (!scene.fluid || scene.fluid->settle_time > 0.0)
        return;
    if (scene.fluid->settle_friction)
        std::fprintf(stderr, "armour: warning: fluid.settle_friction is unused: there is no settle "
                             "(fluid.settle_time = 0)\n");
    if (!scene.fluid->settle_engine.empty())
        std::fprintf(stderr, "armour: warning: fluid.settle_engine is unused: there is no settle "
                             "(fluid.settle_time = 0)\n");
}

void warn_if_settle_hands_clumps_to_hulls(const Scene &scene) {
    if (!scene.fluid)
        return;
    // This run's settle, or the one that wrote a settled scene run now.
    const bool settles_here = scene.fluid->settle_time > 0.0 && !scene.fluid->settle_engine.empty();
    const std::string &settled_by = settles_here ? scene.fluid->settle_engine : scene.fluid->settled_by;
    if (settled_by.empty() || (!settles_here && scene.fluid->settle_time > 0.0))
        return;
    const ShapeModel settle = engine_style(settled_by).capabilities.shape,
                     run = engine_style(scene.engine).capabilities.shape;
    if (settle == ShapeModel::sphere_clumps && run == ShapeModel::convex_hulls)
        std::fprintf(stderr,
                     "armour: warning: %s %s settled sphere clumps and run.engine %s "
                     "runs exact hulls from their poses: the hulls slump off a clump-settled layer "
                     "before any wave (dry, 52 of 99 units displaced in 5 s: docs/validation/stability.md), "
                     "so their damage is not the waves' alone; one layer for both: a run.engine liggghts "
                     "run with fluid.settle_engine bullet, then its settled scene with --engine bullet\n",
                     settles_here ? "fluid.settle_engine" : "fluid.settled_by", settled_by.c_str(),
                     scene.engine.c_str());
}

namespace {

// What a run of a scene checks before it writes: its set-up, the warnings,
// and a DEM run's engine step.
struct RunCheck {
    SceneSetup setup;
    std::vector<std::string> warnings;
    TimeStepReport dt; // DEM runs only: a coupled run's engine steps with the fluid
};

RunCheck check_run(const Scene &scene, const std::string &cache_dir, int np) {
    RunCheck check;
    check.setup = build_scene(scene, cache_dir, false);
    if (scene.fluid) {
        check.warnings = check_coupled_scene(scene, check.setup, np > 0 ? np : scene.fluid->np);
        for (std::size_t k = 0; k < scene.series.size(); ++k) // a sweep's case: every step's waves
            check_coupled_scene(series_step_scene(scene, k), check.setup, np > 0 ? np : scene.fluid->np);
        return check;
    }
    check_analysis_fits(scene, check.setup);
    check.warnings = rocking_clump_warnings(scene, check.setup);
    // The engine's step, as run_dem asks it: from the materials and clumps,
    // before the engine starts (nothing is written, as in check_coupled_scene).
    check.dt = scene_engine(scene, check.setup, check.setup.settings)->time_step_report();
    if (check.dt.forced)
        check.warnings.push_back("run.time_step " + figure_text(check.dt.used) +
                                 " s exceeds the engine's stability limit (run.force_time_step = true)");
    return check;
}

// The plan of a run `armour run --dry-run` prints: units, engine, the kind
// of run, its length in simulated time and in steps or fluid cells.
void print_plan(const RunRequest &r, const Scene &scene, const RunCheck &check, const fs::path &out,
                const std::optional<double> &resume_time) {
    const SceneSetup &setup = check.setup;
    std::vector<int> count(setup.units.size(), 0);
    for (const auto &b : setup.bodies)
        ++count[static_cast<std::size_t>(b.unit)];
    std::printf("%s: dry run, nothing written; checked: the scene, its units and engine%s and --out %s\n",
                r.scene.c_str(), scene.fluid ? ", the fluid case and OpenFOAM's tools" : "", out.c_str());
    std::printf("  units:%s", setup.bodies.empty() ? " none" : "");
    const char *separator = "";
    for (std::size_t k = 0; k < setup.units.size(); ++k)
        if (count[k] > 0) {
            std::printf("%s %d x '%s' (Dn %s m, %s kg, %d spheres)", separator, count[k],
                        setup.units[k].name.c_str(), figure_text(setup.unit_Dn[k]).c_str(),
                        figure_text(setup.units[k].props.mass).c_str(), setup.unit_spheres[k]);
            separator = ",";
        }
    std::printf("\n  engine %s; ", scene.engine.c_str());
    if (scene.fluid) {
        const SceneFluid &f = *scene.fluid;
        const FlumeMesh mesh = flume_mesh(scene);
        const int np = r.np > 0 ? r.np : f.np;
        std::printf(
            "coupled with interFoam: template '%s', %d x %d x %d cells%s, %d rank%s, fluid steps <= %s s",
            f.case_name.c_str(), mesh.axes[0].cells, mesh.axes[1].cells, mesh.axes[2].cells,
            mesh.graded ? " (graded)" : "", np, np > 1 ? "s" : "", number_text(f.max_time_step).c_str());
        if (f.settle_time > 0.0 && !resume_time)
            std::printf("; a dry settle of %s s first", number_text(f.settle_time).c_str());
    } else {
        std::printf("dry (DEM): steps of %s s (limit %s s)", figure_text(check.dt.used).c_str(),
                    figure_text(check.dt.limit).c_str());
    }
    std::printf("\n  %s %s s of simulated time", resume_time ? "resumes at" : "runs",
                resume_time ? number_text(*resume_time).c_str() : number_text(scene.duration).c_str());
    if (resume_time)
        std::printf(" to %s s", number_text(scene.duration).c_str());
    if (!scene.fluid && check.dt.used > 0.0)
        std::printf(" (%.0f steps)", std::ceil((scene.duration - resume_time.value_or(0.0)) / check.dt.used));
    std::printf(", a record every %s s\n", number_text(scene.output_interval).c_str());
}

// `armour run --dry-run`: every check the run makes before its work, in
// the same order and with the same errors, then its plan; writes nothing
// into --out (the clump cache fills as a run would fill it).
int dry_run(const RunRequest &r, const Scene &scene) {
    const fs::path out = OutputFolder::check_writable(r.out, "armour run");
    check_options(r, scene);
    const bool settles = scene.fluid && scene.fluid->settle_time > 0.0;
    std::optional<Checkpoint> resume;
    if (r.resume && !settles)
        resume = checked_resume(r, scene, out);
    // A resume goes on with the run's ranks unless told (run_coupled).
    const int np = r.np > 0 || !resume || !scene.fluid ? r.np : checkpoint_ranks(*resume);
    const RunCheck check = check_run(scene, r.cache.empty() ? default_cache_dir() : r.cache, np);
    if (r.resume && settles)
        resume = checked_settled_resume(r, scene, check.setup, out).second;
    if (!r.resume)
        warn_if_no_checkpoint(scene);
    warn_if_settle_friction_unused(scene);
    warn_if_settle_hands_clumps_to_hulls(scene);
    for (const std::string &w : check.warnings)
        std::fprintf(stderr, "armour: warning: %s\n", w.c_str());
    print_plan(r, scene, check, out, resume ? std::optional<double>(resume->time) : std::optional<double>());
    return 0;
}

} // namespace

std::vector<std::string> check_scene_runs(const Scene &scene, const std::string &cache_dir, int np) {
    return check_run(scene, cache_dir, np).warnings;
}

int run_scene(const RunRequest &r) {
    const Scene scene = load_scene(r.scene, r.overrides);
    if (!scene.series.empty())
        return run_series(r, scene);
    if (r.dry_run)
        return dry_run(r, scene);
    OutputFolder folder(r.out, "armour run", OutputFolder::Mode::streaming); // refused before any work
    check_options(r, scene);
    const bool settles = scene.fluid && scene.fluid->settle_time > 0.0;
    std::optional<Checkpoint> resume;
    if (r.resume && !settles)
        resume = checked_resume(r, scene, folder.target());
    SceneSetup setup = build_scene(scene, r.cache.empty() ? default_cache_dir() : r.cache, true);
    if (!r.resume)
        warn_if_no_checkpoint(scene);
    if (!scene.fluid) {
        check_analysis_fits(scene, setup);
        for (const std::string &w : rocking_clump_warnings(scene, setup))
            std::fprintf(stderr, "armour: warning: %s\n", w.c_str());
        if (resume)
            folder.resume();
        return run_dem(folder, scene, setup, nullptr, nullptr, resume ? &*resume : nullptr);
    }
    warn_if_settle_friction_unused(scene);
    warn_if_settle_hands_clumps_to_hulls(scene);
    if (r.resume) {
        if (settles)
            return resume_settled(r, folder, scene, setup);
        folder.resume();
        return run_coupled(r, scene, setup, folder, &*resume);
    }
    if (scene.fluid->settle_time <= 0.0)
        return run_coupled(r, scene, setup, folder);

    // The placed scene is checked before anything is written; the settled
    // one again by run_coupled.
    check_coupled_scene(scene, setup, r.np > 0 ? r.np : scene.fluid->np);
    folder.open(); // an earlier result of this command is replaced
    json report;
    const Scene settled = settle_before_coupling(r, folder, scene, setup, report);
    return with_settle_report(folder, run_coupled(r, settled, setup, folder), report);
}

} // namespace armour
