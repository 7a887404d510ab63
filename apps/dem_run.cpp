// The DEM run of a scene without [fluid]: engine set-up, time loop with
// progress, recording, energy balance, analysis.
#include "dem_run.h"
#include "run_parts.h"

#include "analysis.h"
#include "bodies_file.h"
#include "body_recorder.h"
#include "checkpoints.h"
#include "clump_io.h"
#include "engine_registry.h"
#include "mesh.h"
#include "scene_text.h"
#include "stl_io.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
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

// Mechanical energy of all bodies (kinetic + potential in the scene's
// gravity), at output times: stability studies compare its maximum with its
// initial value (a stable, dissipative run never gains energy).
class EnergyBalance {
  public:
    EnergyBalance(const Scene &scene, const SceneSetup &setup) : scene_(scene), setup_(setup) {
        for (const auto &b : setup.bodies)
            scale_ += setup.units[b.unit].props.mass * scene.gravity.norm() * setup.unit_Dn[b.unit];
    }
    void account(const std::vector<BodyState> &states) {
        double energy = 0.0;
        for (std::size_t i = 0; i < states.size(); ++i) {
            const MassProperties &p = setup_.units[setup_.bodies[i].unit].props;
            const Eigen::Matrix3d R = states[i].pose.orientation.toRotationMatrix();
            const Eigen::Vector3d &w = states[i].angular_velocity;
            energy += 0.5 * p.mass * states[i].velocity.squaredNorm() +
                      0.5 * w.dot(R * p.inertia * R.transpose() * w) -
                      p.mass * scene_.gravity.dot(states[i].pose.position);
        }
        if (!initial_)
            initial_ = energy;
        max_ = std::max(max_, energy);
        final_ = energy;
    }
    void write(json &summary) const {
        summary["energy_initial"] = initial_.value_or(0.0);
        summary["energy_max"] = max_;
        summary["energy_final"] = final_;
        summary["energy_scale"] = scale_;
    }

  private:
    const Scene &scene_;
    const SceneSetup &setup_;
    std::optional<double> initial_;
    double scale_ = 0.0; // J, sum of m |g| Dn: the energy of lifting every unit by its size
    double max_ = -HUGE_VAL, final_ = 0.0;
};

// OUT/summary.json of a DEM run, before its energy balance and analysis add theirs.
json dem_summary(const Scene &scene, const SceneSetup &setup, const RigidBodyEngine &engine,
                 const TimeStepReport &dt, double wall_seconds) {
    json spheres = json::object();
    for (std::size_t k = 0; k < setup.units.size(); ++k)
        spheres[setup.units[k].name] = setup.unit_spheres[k];
    json summary = {
        {"command", "run"},
        {"scene", scene.name},
        {"engine", engine.name()},
        {"spheres_per_unit", spheres},
        {"units", static_cast<int>(setup.bodies.size())},
        {"dt", dt.used},
        {"dt_limit", dt.limit},
        {"dt_forced", dt.forced},
        {"dt_rule", dt.rule},
        {"rayleigh_time", dt.rayleigh},
        {"contact_duration", dt.contact_duration},
        {"steps", engine.steps()},
        {"simulated_seconds", engine.time()},
        {"wall_seconds", wall_seconds},
        {"arithmetic", arithmetic_fingerprint()}, // two runs with other fingerprints part (checkpoints.h)
        // A run shorter than one step simulates nothing: no cost per second or per step to report.
        {"wall_seconds_per_simulated_second",
         engine.steps() > 0 ? json(wall_seconds / engine.time()) : json(nullptr)},
        {"seconds_per_unit_step", engine.steps() > 0 && !setup.bodies.empty()
                                      ? json(wall_seconds / (static_cast<double>(engine.steps()) *
                                                             static_cast<double>(setup.bodies.size())))
                                      : json(nullptr)},
        {"files", {{"bodies", "bodies.h5"}, {"paraview", "bodies.xdmf"}, {"scene", "scene.resolved.toml"}}},
        {"si_units",
         {{"dt", "s"}, {"wall_seconds", "s"}, {"angles", "deg"}, {"lengths", "m"}, {"energy", "J"}}}};
    return summary;
}

} // namespace

fs::path write_scene_and_units(OutputFolder &folder, const Scene &scene, const SceneSetup &setup) {
    std::error_code ec;
    fs::create_directories(folder.claim("units"), ec);
    if (ec)
        throw InputError("--out: cannot create " + folder.target().string() + ": " + ec.message());
    const fs::path resolved = folder.claim("scene.resolved.toml");
    write_text_file(resolved, resolved_scene_toml(scene));
    for (const auto &u : setup.units) {
        const fs::path dir = folder.target() / "units" / u.name;
        fs::create_directories(dir);
        write_sphere_file(u.clump, (dir / "clump.spheres").string(), u.name);
        write_stl(u.mesh, (dir / "shape.stl").string(), true, u.name);
    }
    return resolved;
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

namespace {

// The trajectory file of a DEM run: new, or (resume) reopened after the
// checkpoint's records, whose states land in `earlier`.
std::unique_ptr<BodyRecorder> open_recorder(OutputFolder &folder, const Scene &scene, const SceneSetup &setup,
                                            const RigidBodyEngine &engine, double dt,
                                            const Checkpoint *resume, BodiesFile &earlier) {
    std::vector<RecorderUnit> recorder_units;
    for (const auto &u : setup.units)
        recorder_units.push_back({u.name, u.mesh});
    std::vector<int> body_unit;
    for (const auto &b : setup.bodies)
        body_unit.push_back(b.unit);
    const fs::path h5 = folder.claim("bodies.h5"), xdmf = folder.claim("bodies.xdmf");
    if (!resume)
        return std::make_unique<BodyRecorder>(
            h5.string(), xdmf.string(), recorder_units, body_unit,
            std::vector<std::pair<std::string, std::string>>{
                {"scene", scene.name}, {"engine", engine.name()}, {"dt", std::to_string(dt)}},
            scene.checkpoint_interval <= 0.0);
    earlier = read_bodies_file(h5.string());
    if (static_cast<long>(earlier.steps()) < resume->records || earlier.bodies() != setup.bodies.size())
        throw InputError(h5.string() + ": holds " + std::to_string(earlier.steps()) + " steps of " +
                         std::to_string(earlier.bodies()) + " bodies, not the " +
                         std::to_string(resume->records) + " steps of " +
                         std::to_string(setup.bodies.size()) + " bodies its checkpoint " +
                         resume->dir.string() + " recorded");
    return BodyRecorder::reopen(h5.string(), xdmf.string(), recorder_units, body_unit, resume->records);
}

// Advances the engine to `target` (s) in spans no longer than the
// analysis' (tilt turns gravity) and the still water's buoyancy update's:
// both act between engine advances.
void advance_to_record(RigidBodyEngine &engine, Analysis &analysis, const SceneSetup &setup,
                       const Scene &scene, const StillWater *water, double dt, double target) {
    do {
        double span = analysis.before_advance(engine.time(), engine);
        if (water) {
            for (int i = 0; i < engine.body_count(); ++i)
                set_buoyancy(engine, i, setup.units[setup.bodies[i].unit], engine.state(i), *water,
                             scene.gravity);
            span = std::min(span, water->update_interval);
        }
        engine.advance_to(std::min(engine.time() + std::max(span, dt), target));
    } while (engine.time() < target - 0.5 * dt);
}

} // namespace

// The DEM run of a scene without [fluid], dry or (`water`, a settle run)
// under still water's buoyancy, into `folder`; `final_states` (optional)
// receives every body's state at the end. `resume`: continue the run in
// `folder` (resumed already) from this checkpoint.
int run_dem(OutputFolder &folder, const Scene &scene, SceneSetup &setup, std::vector<BodyState> *final_states,
            const StillWater *water, const Checkpoint *resume) {
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
    write_scene_and_units(folder, scene, setup);
    // Start the engine before opening the trajectory file: MPI's start-up may
    // fork a helper that would inherit (and keep locked) any file open then.
    engine->state(0);
    // A resumed run replays the records up to its checkpoint into the
    // energy balance and the analysis, then appends after them.
    BodiesFile earlier;
    const std::unique_ptr<BodyRecorder> recorder =
        open_recorder(folder, scene, setup, *engine, dt.used, resume, earlier);
    Checkpoints checkpoints(out, scene.checkpoint_interval, resume ? resume->time : 0.0);
    if (scene.checkpoint_interval > 0.0)
        folder.claim("checkpoints");

    std::vector<BodyState> states(setup.bodies.size());
    EnergyBalance energy(scene, setup);
    auto record = [&] {
        for (int i = 0; i < engine->body_count(); ++i)
            states[i] = engine->state(i);
        energy.account(states);
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
            energy.account(states);
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
        advance_to_record(*engine, *analysis, setup, scene, water, dt.used, target);
        record();
        analysis->sample(engine->time(), states);
        if (analysis->finished()) {
            std::fprintf(stderr, "run: %s test decided at t = %.3f s, stopping\n", scene.analysis.c_str(),
                         engine->time());
            break;
        }
        // Not at the last record: the run is whole then (summary.json).
        if (k < outputs && checkpoints.due(engine->time()))
            checkpoints.write({engine->time(), recorder->steps(), progress.seconds(), {}, {}},
                              [&](const fs::path &dir) { engine->save_state((dir / "engine").string()); });
        progress.update(engine->time());
    }
    recorder->close();
    const double wall_seconds = progress.seconds();

    json summary = dem_summary(scene, setup, *engine, dt, wall_seconds);
    energy.write(summary);
    if (const std::string line = analysis->write(summary); !line.empty())
        std::fprintf(stderr, "run: %s: %s\n", scene.analysis.c_str(), line.c_str());
    write_text_file(folder.claim("summary.json"), summary.dump(2) + "\n");
    std::printf("%s: %d units, %ld steps of %.3g s, %.1f s wall -> %s\n", scene.name.c_str(),
                static_cast<int>(setup.bodies.size()), engine->steps(), dt.used, wall_seconds, out.c_str());
    if (final_states)
        *final_states = states;
    return 0;
}

} // namespace armour
