// The settle before a coupled run: the scene's units settled under still
// water in a forked DEM run (dem_run.h), and the scene the waves start from.
#include "dem_run.h"
#include "run_parts.h"

#include "engine_registry.h"
#include "output_folder.h"
#include "rock_manual_layer.h"
#include "scene_keys.h"
#include "scene_setup.h"
#include "scene_text.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sys/wait.h>
#include <unistd.h>

namespace armour {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

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

// The warning for a layer that still moves at the settle's end (a settle
// report's speeds); "" for a still one.
std::string unsettled_warning(const json &report) {
    const double speed = report["max_speed_at_end"].get<double>(),
                 still = report["still_speed"].get<double>();
    if (speed <= still)
        return "";
    return "after fluid.settle_time = " + number_text(report["settle_time"].get<double>()) +
           " s a unit still moves at " + figure_text(speed) + " m/s (> " + figure_text(still) +
           " m/s, 1 % of Dn per second): the layer has not settled and will readjust in the water; raise "
           "fluid.settle_time";
}

// The coupled summary says where its start came from, and whether the
// layer had come to rest (among its warnings, beside the run's others).
int with_settle_report(OutputFolder &folder, int status, json report) {
    const fs::path summary_file = folder.claim("summary.json");
    std::ifstream in(summary_file);
    if (status == 0 && in) {
        json summary = json::parse(in);
        in.close();
        if (const std::string w = unsettled_warning(report); !w.empty())
            summary["warnings"].push_back(w);
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
// flukes do not grow about its centre, and an STL unit has no size key. An
// inscribed clump (unit.method = "inscribed") needs none: the hulls settle at
// their own size and hand over to it as they lie.
void grow_units_to_hold_clumps(Scene &dry, const Scene &scene, const SceneSetup &setup) {
    if (engine_style(dry.engine).capabilities.shape != ShapeModel::convex_hulls ||
        engine_style(scene.engine).capabilities.shape != ShapeModel::sphere_clumps)
        return;
    for (std::size_t k = 0; k < dry.units.size(); ++k) {
        SceneUnit &u = dry.units[k];
        const std::optional<double> growth = growth_to_hold_clump(setup.units[k]);
        if (growth && *growth <= 1.0 + 1e-9)
            continue; // an inscribed clump: its spheres touch the faces at most (rounding aside)
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
// between units as pairs, its units at the settle's density.
Scene settle_scene(const Scene &scene, const SceneSetup &setup) {
    const SceneFluid &fluid = *scene.fluid;
    Scene dry = scene;
    dry.fluid.reset();
    dry.waves.reset(); // both need [fluid]
    dry.porous.clear();
    dry.refine.clear(); // the fluid mesh's regions, refused without [fluid]
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
    if (fluid.settle_density)
        for (SceneUnit &u : dry.units)
            u.density = *fluid.settle_density;
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

double settle_growth(const Scene &scene, const Scene &dry) {
    double growth = 1.0;
    for (std::size_t k = 0; k < scene.units.size() && k < dry.units.size(); ++k)
        if (scene.units[k].size > 0.0)
            growth = std::max(growth, dry.units[k].size / scene.units[k].size);
    return growth;
}

Scene settled_scene(const Scene &scene, std::vector<SceneBody> bodies, double growth) {
    Scene settled = scene;
    settled.fluid->settle_time = 0.0;
    settled.fluid->settle_friction.reset();
    settled.fluid->settle_density.reset();
    settled.fluid->settle_stages = 1;
    settled.fluid->settled_by =
        scene.fluid->settle_engine.empty() ? scene.engine : scene.fluid->settle_engine;
    settled.fluid->settled_growth = growth;
    settled.fluid->settle_engine.clear();
    settled.drops.clear();
    settled.patterns.clear();
    settled.bodies = std::move(bodies);
    return settled;
}

namespace {

// Says on stderr what the settle does (and how the settle's cubes differ
// from the run's), before the settle's own log lines.
void announce_settle(const Scene &scene, const Scene &dry, std::size_t units, const fs::path &dir) {
    const SceneFluid &fluid = *scene.fluid;
    std::string how;
    if (fluid.settle_friction)
        how += ", friction " + number_text(*fluid.settle_friction) + " between units";
    if (fluid.settle_density)
        how += ", units at " + number_text(*fluid.settle_density) + " kg/m^3";
    std::fprintf(stderr,
                 "run: settling %zu units in the DEM under still water (level %g m) for %g s "
                 "(fluid.settle_time)%s -> %s\n",
                 units, fluid.water_level, fluid.settle_time, how.c_str(), dir.c_str());
    for (std::size_t k = 0; k < dry.units.size(); ++k)
        if (dry.units[k].size != scene.units[k].size)
            std::fprintf(
                stderr,
                "run: the settle's %s cubes '%s' are grown %.4g x (edge %.4g m) so that the run's clumps "
                "start inside them\n",
                dry.engine.c_str(), dry.units[k].name.c_str(), dry.units[k].size / scene.units[k].size,
                dry.units[k].size);
    std::fflush(nullptr);
}

// A stage's own seed for the pattern (stage 0 keeps the pattern's): each
// stage draws afresh, and the seed stays a TOML integer (< 2^63) in the
// stage's scene.resolved.toml.
std::uint64_t stage_seed(std::uint64_t seed, int stage) {
    return stage == 0
               ? seed
               : (seed + 0x9E3779B97F4A7C15ULL * static_cast<std::uint64_t>(stage)) & 0x7FFFFFFFFFFFFFFFULL;
}

// The settle in fluid.settle_stages stages (DIR/stage-1 ...): stage k places
// the pattern's next rows (an equal share of them, from the toe up) clear of
// the units settled before, as [[body]] at rest, and settles them all; the
// last stage runs settle_time, the others settle_time / stages. Returns the
// units' states at the end; `placed` gets each unit's placed pose, in the
// same order.
std::vector<BodyState> settle_in_stages(const RunRequest &r, const Scene &dry, int stages,
                                        const StillWater &water, OutputFolder &settle_folder,
                                        std::vector<Pose> &placed) {
    const ScenePattern &pattern = dry.patterns.front();
    const int first = pattern.first_row, rows = pattern.rows - pattern.first_row;
    std::vector<SceneBody> settled;
    std::vector<BodyState> states;
    for (int k = 0; k < stages; ++k) {
        Scene stage = dry;
        stage.patterns.front().first_row = first + rows * k / stages;
        stage.patterns.front().rows = first + rows * (k + 1) / stages;
        stage.patterns.front().seed = stage_seed(pattern.seed, k);
        stage.bodies = settled;
        stage.duration = k + 1 < stages ? dry.duration / stages : dry.duration;
        stage.output_interval = std::min(dry.output_interval, stage.duration);
        std::fprintf(stderr, "run: settle stage %d of %d: rows %d-%d, %g s\n", k + 1, stages,
                     stage.patterns.front().first_row + 1, stage.patterns.front().rows, stage.duration);
        std::fflush(nullptr);
        SceneSetup setup = build_scene(stage, r.cache_dir(), false);
        for (std::size_t i = settled.size(); i < setup.bodies.size(); ++i)
            placed.push_back(setup.bodies[i].pose);
        OutputFolder folder(settle_folder.claim("stage-" + std::to_string(k + 1)), "armour run",
                            OutputFolder::Mode::streaming);
        run_dem(folder, stage, setup, &states, &water);
        settled = bodies_at_rest(stage, setup, states);
    }
    return states;
}

// A settle in stages has no DEM run of its own: its summary.json adds up its
// stages' steps and seconds, and takes the engine, its step and the step's
// limit from the last stage (every stage's units are the scene's own), the
// keys a one-piece settle's summary is read for.
void write_staged_settle_summary(OutputFolder &settle_folder, const fs::path &dir, const Scene &dry,
                                 int stages, std::size_t units) {
    double wall = 0.0, simulated = 0.0;
    long long steps = 0;
    json last;
    for (int k = 1; k <= stages; ++k) {
        std::ifstream in(dir / ("stage-" + std::to_string(k)) / "summary.json");
        const json stage = json::parse(in, nullptr, false);
        if (stage.is_discarded())
            throw std::runtime_error("settle stage " + std::to_string(k) + " wrote no summary.json");
        wall += stage.value("wall_seconds", 0.0);
        simulated += stage.value("simulated_seconds", 0.0);
        steps += stage.value("steps", 0LL);
        last = stage;
    }
    write_text_file(
        settle_folder.claim("summary.json"),
        json{
            {"command", "run"},
            {"scene", dry.name},
            {"engine", last.value("engine", json())},
            {"dt", last.value("dt", json())},
            {"dt_limit", last.value("dt_limit", json())},
            {"settle_stages", stages},
            {"units", units},
            {"steps", steps},
            {"simulated_seconds", simulated},
            {"wall_seconds", wall},
            {"stages", "stage-1 ... stage-" + std::to_string(stages) + ", each a DEM run's output"},
            {"si_units", {{"dt", "s"}, {"dt_limit", "s"}, {"simulated_seconds", "s"}, {"wall_seconds", "s"}}}}
                .dump(2) +
            "\n");
}

// The settle itself (in the forked child): the DEM run of `dry` under the
// still water into `dir` (in stages: fluid.settle_stages), then the settled
// scene (file `settled_name`) and settled.json.
void run_settle(const RunRequest &r, const Scene &scene, const Scene &dry, const SceneSetup &setup,
                const fs::path &dir, const std::string &settled_name) {
    const SceneFluid &fluid = *scene.fluid;
    OutputFolder settle_folder(dir, "armour run", OutputFolder::Mode::streaming);
    std::vector<BodyState> states;
    StillWater water;
    water.level = fluid.water_level;
    water.density = fluid.fluid_density;
    water.update_interval = std::min(fluid.max_time_step, dry.output_interval);
    std::vector<Pose> placed;
    if (fluid.settle_stages > 1) {
        settle_folder.open();
        // The whole settle's scene, as `--resume` checks it (each stage's own
        // is in its folder).
        write_text_file(settle_folder.claim("scene.resolved.toml"), resolved_scene_toml(dry));
        states = settle_in_stages(r, dry, fluid.settle_stages, water, settle_folder, placed);
        write_staged_settle_summary(settle_folder, dir, dry, fluid.settle_stages, states.size());
    } else {
        SceneSetup dry_setup = build_scene(dry, r.cache_dir(), false);
        run_dem(settle_folder, dry, dry_setup, &states, &water);
        for (const BodyInit &b : dry_setup.bodies)
            placed.push_back(b.pose);
    }
    if (states.size() != setup.bodies.size())
        throw InputError("fluid.settle_time: the settle placed " + std::to_string(states.size()) +
                         " units, the scene " + std::to_string(setup.bodies.size()));

    std::vector<SceneBody> bodies = bodies_at_rest(scene, setup, states);
    double speed = 0.0, displacement = 0.0;
    for (std::size_t i = 0; i < states.size(); ++i) {
        speed = std::max(speed, states[i].velocity.norm());
        displacement = std::max(displacement, (states[i].pose.position - placed[i].position).norm());
    }
    write_text_file(settle_folder.claim(settled_name),
                    resolved_scene_toml(settled_scene(scene, std::move(bodies), settle_growth(scene, dry))));
    write_text_file(
        settle_folder.claim("settled.json"),
        json{
            {"settle_time", fluid.settle_time},
            {"settle_friction", fluid.settle_friction ? json(*fluid.settle_friction) : json(nullptr)},
            {"settle_density", fluid.settle_density ? json(*fluid.settle_density) : json(nullptr)},
            {"settle_stages", fluid.settle_stages},
            {"water_level", water.level},
            {"water_density", water.density},
            {"max_speed_at_end", speed},
            {"max_displacement", displacement},
            {"units", states.size()},
            {"si_units",
             {{"speed", "m/s"}, {"lengths", "m"}, {"water_density", "kg/m^3"}, {"settle_density", "kg/m^3"}}}}
                .dump(2) +
            "\n");
}

} // namespace

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
    announce_settle(scene, dry, setup.bodies.size(), dir);
    const pid_t pid = ::fork();
    if (pid < 0)
        throw InputError("fluid.settle_time: cannot start the settle run (fork failed)");
    if (pid == 0) {
        int status = 1;
        try {
            run_settle(r, scene, dry, setup, dir, settled_file.filename().string());
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
    if (const std::string w = unsettled_warning(report); !w.empty())
        std::fprintf(stderr, "armour: warning: %s\n", w.c_str());
    // A settle cut short hands over a pile still falling: units above the
    // domain or overlapping. Say so in the user's own terms.
    try {
        Scene settled = load_scene(settled_file.string());
        setup = build_scene(settled, r.cache_dir(), false);
        return settled;
    } catch (const InputError &e) {
        if (speed <= still)
            throw;
        throw InputError(scene.file + ": key 'fluid.settle_time': after " + number_text(fluid.settle_time) +
                         " s a unit still moved at " + figure_text(speed) +
                         " m/s and the settled pose is refused (" + e.what() + "); raise fluid.settle_time");
    }
}

// `armour run --settle-only`: a layer is looked at in minutes before hours
// of waves are spent on it. The settle is the one a coupled run makes (its
// OUT/settle, rerunnable with the waves as `armour run
// OUT/settle/scene.settled.toml`); the fluid case is neither checked nor
// built (a coupled run checks the settled layer against its mesh when it
// starts). summary.json: the settle's report and the layer the waves would
// meet, measured as the damage analysis measures it.
std::string settle_only_refusal(const Scene &scene) {
    return scene.fluid && scene.fluid->settle_time > 0.0
               ? std::string()
               : "key 'fluid.settle_time': --settle-only needs a scene with [fluid] that settles its units "
                 "before the waves (fluid.settle_time > 0 s)";
}

int settle_only(const RunRequest &r, const Scene &scene) {
    for (const auto &[given, name] :
         {std::pair{r.resume, "--resume"}, {r.restart, "--restart"}, {r.np != 0, "--np"}})
        if (given)
            throw InputError(std::string("--settle-only: not with ") + name +
                             " (a settle is not resumed, and runs in the DEM alone on one rank)");
    if (const std::string why = settle_only_refusal(scene); !why.empty())
        throw InputError(r.scene + ": " + why);
    check_engine_keys(scene);
    const auto start = std::chrono::steady_clock::now();
    if (r.dry_run) { // the settle's checks (units, placement, settle keys, --out), nothing written
        const fs::path out = OutputFolder::check_writable(r.out, "armour run");
        const SceneSetup setup = build_scene(scene, r.cache_dir(), true);
        const Scene dry = settle_scene(scene, setup);
        warn_if_hulls_inherit_a_layer(scene);
        std::printf("plan: settle %zu units for %g s (fluid.settle_time) in %s under still water at %g m, "
                    "then stop: %s and the layer's figures in %s; no fluid case\n",
                    setup.bodies.size(), scene.fluid->settle_time, dry.engine.c_str(),
                    scene.fluid->water_level, (out / "settle" / "scene.settled.toml").c_str(),
                    (out / "summary.json").c_str());
        return 0;
    }
    OutputFolder folder(r.out, "armour run", OutputFolder::Mode::streaming); // refused before any work
    SceneSetup setup = build_scene(scene, r.cache_dir(), true);
    warn_if_hulls_inherit_a_layer(scene);
    folder.open();
    json report;
    const Scene settled = settle_before_coupling(r, folder, scene, setup, report);
    std::vector<BodyState> states(setup.bodies.size());
    for (std::size_t i = 0; i < states.size(); ++i)
        states[i].pose = setup.bodies[i].pose;
    json summary = {{"command", "run"},
                    {"settle_only", true},
                    {"scene", scene.name},
                    {"units", states.size()},
                    {"settle", report},
                    {"settled_layer", settled_layer_record(settled, setup, states)},
                    {"warnings", json::array()},
                    {"files", {{"settled_scene", "settle/scene.settled.toml"}, {"settle", "settle"}}},
                    {"si_units",
                     {{"packing_density", "units per Dn^2"},
                      {"layer_thickness", "m"},
                      {"lengths", "m"},
                      {"speed", "m/s"},
                      {"wall_seconds", "s"}}}};
    summary["settle"]["scene"] = "settle/scene.settled.toml";
    if (const std::string w = unsettled_warning(report); !w.empty())
        summary["warnings"].push_back(w);
    if (const std::string w = settled_layer_warning(settled, setup, states); !w.empty()) {
        std::fprintf(stderr, "armour: warning: %s\n", w.c_str());
        summary["warnings"].push_back(w);
    }
    const json &layer = summary["settled_layer"];
    summary["wall_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    write_text_file(folder.claim("summary.json"), summary.dump(2) + "\n");
    if (layer.is_object())
        std::printf(
            "run: settled layer: %d of %zu units on the slope (%d seaward of the face's foot, %d resting on "
            "top of the layer), packing %.3g units/Dn^2, porosity %.3g, k_t %.3g -> %s\n",
            layer["units_on_slope"].get<int>(), states.size(), layer["units_at_foot"].get<int>(),
            layer["units_on_top"].get<int>(), layer["packing_density"].get<double>(),
            layer["porosity"].get<double>(), layer["layer_coefficient"].get<double>(),
            (folder.target() / "settle" / "scene.settled.toml").c_str());
    return 0;
}

} // namespace armour
