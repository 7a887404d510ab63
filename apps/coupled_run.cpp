#include "coupled_run.h"

#include "analysis.h"
#include "bodies_file.h"
#include "body_recorder.h"
#include "checkpoints.h"
#include "fluid_models.h"
#include "flume_mesh.h"
#include "foam_case.h"
#include "foam_restart.h"
#include "mesh_refinement.h"
#include "output_folder.h"
#include "report_command.h"
#include "rigid_body_engine.h"
#include "rock_manual_layer.h"
#include "run_parts.h"
#include "scene_keys.h"
#include "solver_log.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <tuple>

namespace armour {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The plugin's count of coupling steps (one per fluid step), carried across resumes.
int coupling_steps(const fs::path &out) {
    std::ifstream in(out / "coupling_times.json");
    const json times = json::parse(in, nullptr, false);
    return times.is_object() ? times.value("coupling_steps", 0) : 0;
}

// OUT's entries before the case: what the plugin writes, the resolved scene
// (returned: the case reads it) and each unit's clump and shape.
fs::path write_run_inputs(const Scene &scene, const SceneSetup &setup, OutputFolder &folder) {
    for (const char *name : {"bodies.h5", "bodies.xdmf", "fluid.csv", "coupling_times.json"})
        folder.claim(name); // the plugin writes these (a new plugin file is listed here too)
    return write_scene_and_units(folder, scene, setup);
}

// The case in OUT/case: a new one from the template, or the run's own set
// back to `resume`.
fs::path prepare_case(const RunRequest &r, const Scene &scene, const SceneSetup &setup, OutputFolder &folder,
                      const fs::path &resolved, const Checkpoint *resume) {
    const fs::path out = folder.target();
    const fs::path case_dir = folder.claim("case");
    if (scene.checkpoint_interval > 0.0)
        folder.claim("checkpoints"); // the plugin writes them
    const std::map<std::string, std::string> paths =
        case_paths(resolved, fs::absolute(r.cache_dir()).string(), out);
    if (resume) {
        resume_case(scene, *resume, paths, case_dir);
        return case_dir;
    }
    write_case(scene, setup, paths, case_dir);
    mesh_case(scene, case_dir);
    const int np = scene.fluid->np;
    // The meshed count: on a refined mesh the block's cells are not the case's.
    std::fprintf(stderr, "run: %s: %ld cells (%s), %d rank%s, engine %s -> %s\n", scene.name.c_str(),
                 mesh_cells(case_dir), mesh_layout(scene).c_str(), np, np > 1 ? "s" : "",
                 scene.engine.c_str(), case_dir.c_str());
    return case_dir;
}

// summary["fluid"]: the case and mesh as run, the cells across each unit,
// the fluid step's limits and the coupling's settings; `steps` fluid steps.
json fluid_figures(const Scene &scene, const SceneSetup &setup, const fs::path &case_dir, int steps) {
    const SceneFluid &f = *scene.fluid;
    const Eigen::Vector3d h = fine_cell_size(scene);
    const FlumeMesh mesh = flume_mesh(scene);
    const long meshed_cells = mesh_cells(case_dir); // the owner file's note, read once
    json across = json::object();
    for (std::size_t k = 0; k < setup.units.size(); ++k)
        across[setup.units[k].name] = setup.unit_Dn[k] / h.maxCoeff();
    return {{"case", f.case_name},
            {"mesh", f.mesh},
            {"refine_levels", refine_levels(scene)},
            {"cells", {mesh.axes[0].cells, mesh.axes[1].cells, mesh.axes[2].cells}},
            {"cells_total", meshed_cells > 0 ? meshed_cells : mesh.cells()},
            {"cell_size", {h.x(), h.y(), h.z()}},
            {"largest_cell_size",
             {mesh.axes[0].largest_cell(), mesh.axes[1].largest_cell(), mesh.axes[2].largest_cell()}},
            {"cells_across_unit", across},
            {"np", f.np},
            {"steps", steps},
            {"max_time_step", f.max_time_step},
            {"min_time_step", f.min_time_step},
            {"max_courant", f.max_courant},
            {"max_interface_courant", f.max_interface_courant},
            {"water_level", f.water_level},
            {"fluid_density", f.fluid_density},
            {"penalty", f.penalty},
            {"mask", f.mask},
            {"solid_fraction", f.solid_fraction},
            {"added_mass", f.added_mass}};
}

// Cost and limits as run: interFoam's wall time per step, the largest
// Courant numbers it printed (the step adapts to max_courant from the
// previous step's flux, so it may overshoot; more than 10 % is reported).
void add_solver_figures(const Scene &scene, const SolverLogFigures &solver_log, double solver_seconds,
                        json &summary) {
    const SceneFluid &f = *scene.fluid;
    summary["fluid"]["solver_seconds"] = solver_seconds;
    summary["fluid"]["seconds_per_step"] = solver_seconds / std::max(solver_log.steps, 1);
    // interFoam's own CPU clock per step: the bench compares this.
    summary["fluid"]["cpu_seconds_per_step"] =
        solver_log.cpu_seconds_per_step ? json(*solver_log.cpu_seconds_per_step) : json(nullptr);
    summary["fluid"]["frozen"] = f.frozen;
    summary["fluid"]["courant_max_seen"] = solver_log.courant_max;
    summary["fluid"]["interface_courant_max_seen"] = solver_log.interface_courant_max;
    for (const auto &[seen, limit, over, key] :
         {std::tuple(solver_log.courant_max, f.max_courant, solver_log.courant_over, "max_courant"),
          std::tuple(solver_log.interface_courant_max, f.max_interface_courant,
                     solver_log.interface_courant_over, "max_interface_courant")})
        if (over.steps > 0) {
            const std::string w =
                "fluid Courant number reached " + figure_text(seen) + " > fluid." + key + " " +
                number_text(limit) + " (+10 %) in " + std::to_string(over.steps) + " of " +
                std::to_string(solver_log.steps) + " steps: " +
                (2 * over.after_capped_steps >= over.steps
                     ? "steps of fluid.max_time_step met a sudden flow; lower max_time_step"
                     : "interFoam sets each step from the one before and lags a flow that speeds up; "
                       "lower fluid." +
                           std::string(key) + " for a firm bound");
            summary["warnings"].push_back(w);
            std::fprintf(stderr, "armour: warning: %s\n", w.c_str());
        }
}

// The DEM's wall seconds up to the checkpoint a run resumes from (the
// plugin's coupling state there: next record, steps, load, DEM and mask
// seconds); 0 for a run from the start. Read before the solver runs: a
// resumed run may replace that checkpoint with later ones.
double dem_seconds_before(const Checkpoint *resume) {
    if (!resume)
        return 0.0;
    return read_coupling_state(resume->dir).dem_seconds;
}

// The plugin's timings (coupling_times.json: engine advance = DEM) and clocks
// at the end. Its seconds are the whole run's, earlier parts included; the
// solver's clock is this part's (a resume starts a new log), so the DEM's
// share is taken over this part alone: its DEM seconds less those before.
void add_coupling_times(const fs::path &file, double solver_seconds, double dem_before, json &summary) {
    std::ifstream times_file(file);
    const json times = times_file ? json::parse(times_file, nullptr, false) : json();
    if (times.is_object()) {
        for (const char *key : {"dem_seconds", "load_seconds", "mask_seconds"})
            summary[key] = times.value(key, 0.0);
        summary["dem_share_of_solver"] =
            (times.value("dem_seconds", 0.0) - dem_before) / std::max(solver_seconds, 1e-300);
        summary["coupling_seconds"] = times.value("dem_seconds", 0.0) + times.value("load_seconds", 0.0) +
                                      times.value("mask_seconds", 0.0);
        // s, at the end: the engine keeps the fluid's clock to half an engine step.
        for (const char *key : {"fluid_time", "engine_time"})
            summary[key] = times.contains(key) ? times[key] : json(nullptr);
    }
}

} // namespace

std::vector<std::string> check_coupled_scene(const Scene &scene, const SceneSetup &setup, int np) {
    std::vector<std::string> warnings = check_fluid_case(scene, setup, np);
    check_analysis_fits(scene, setup);
    // Before a settle the pile is not the layer.
    if (scene.analysis == "damage" && scene.fluid->settle_time <= 0.0) {
        std::vector<BodyState> start(setup.bodies.size());
        for (std::size_t i = 0; i < start.size(); ++i)
            start[i].pose = setup.bodies[i].pose;
        if (const std::string w = settled_layer_warning(scene, setup, start); !w.empty())
            warnings.push_back(w);
    }
    return warnings;
}

int run_coupled(const RunRequest &r, const Scene &scene_in, const SceneSetup &setup, OutputFolder &folder,
                const Checkpoint *resume) {
    const auto start = std::chrono::steady_clock::now();
    // The run's wall time, earlier parts included: the plugin writes it into
    // each checkpoint as the seconds since this origin (s since the epoch).
    const double earlier_wall = resume ? resume->wall_seconds : 0.0;
    const std::chrono::duration<double> since_epoch = std::chrono::system_clock::now().time_since_epoch();
    ::setenv("ARMOUR_WALL_ORIGIN", number_text(since_epoch.count() - earlier_wall).c_str(), 1);
    Scene scene = scene_in;
    SceneFluid &f = *scene.fluid;
    if (r.np > 0)
        f.np = r.np; // the resolved scene records what ran
    else if (resume)
        f.np = checkpoint_ranks(*resume); // a resume goes on with the run's ranks unless told
    std::vector<std::string> warnings = check_coupled_scene(scene, setup, f.np);
    for (const auto &w : warnings)
        std::fprintf(stderr, "armour: warning: %s\n", w.c_str());
    if (const std::string w = resume ? other_arithmetic_warning(*resume) : ""; !w.empty())
        warnings.push_back(w); // printed by checked_resume

    folder.open(); // an earlier result of this command is replaced
    const fs::path out = folder.target();
    const fs::path resolved = write_run_inputs(scene, setup, folder);
    const fs::path case_dir = prepare_case(r, scene, setup, folder, resolved, resume);
    const double dem_before = dem_seconds_before(resume);
    const auto solver_start = std::chrono::steady_clock::now();
    run_interfoam(scene, case_dir, resume);
    const double solver_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - solver_start).count();
    const double wall_seconds =
        earlier_wall + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    const BodiesFile rec =
        setup.bodies.empty() ? BodiesFile{} : read_bodies_file((out / "bodies.h5").string());
    if (!setup.bodies.empty() && (rec.time.empty() || rec.bodies() != setup.bodies.size()))
        throw InputError(out.string() + "/bodies.h5: the plugin recorded no steps");
    const SolverLogFigures solver_log =
        solver_log_figures(read_text_file(case_dir / "log.interFoam"),
                           {f.max_courant, f.max_interface_courant, f.max_time_step});

    json spheres = json::object();
    for (std::size_t k = 0; k < setup.units.size(); ++k)
        spheres[setup.units[k].name] = setup.unit_spheres[k];
    const double simulated = rec.time.empty() ? scene.duration : rec.time.back();
    json summary = {
        {"command", "run"},
        {"coupled", true},
        {"scene", scene.name},
        {"engine", rec.attribute("engine").empty() ? scene.engine : rec.attribute("engine")},
        {"spheres_per_unit", spheres},
        {"units", static_cast<int>(setup.bodies.size())},
        {"dt", std::atof(rec.attribute("dt").c_str())},
        {"simulated_seconds", simulated},
        {"wall_seconds", wall_seconds},
        {"arithmetic", arithmetic_fingerprint()}, // two runs with other fingerprints part (checkpoints.h)
        {"wall_seconds_per_simulated_second",
         simulated > 0.0 ? json(wall_seconds / simulated) : json(nullptr)},
        {"records", rec.time.size()},
        {"warnings", warnings},
        // A resumed run's coupling steps go on from its checkpoint; its log starts there.
        {"fluid", fluid_figures(scene, setup, case_dir, resume ? coupling_steps(out) : solver_log.steps)},
        {"files",
         {{"bodies", "bodies.h5"},
          {"paraview", "bodies.xdmf"},
          {"scene", "scene.resolved.toml"},
          {"case", "case"},
          {"solver_log", "case/log.interFoam"}}},
        {"si_units", {{"dt", "s"}, {"wall_seconds", "s"}, {"lengths", "m"}, {"forces", "N"}}}};

    const std::string result = analyse_coupled_record(scene, setup, rec, out, case_dir, folder, summary);
    add_solver_figures(scene, solver_log, solver_seconds, summary);
    add_coupling_times(out / "coupling_times.json", solver_seconds, dem_before, summary);
    add_fluid_models_summary(scene, summary);
    write_text_file(folder.claim("summary.json"), summary.dump(2) + "\n");
    std::printf("%s: %d units, %.4g s coupled in %.1f s wall%s%s -> %s\n", scene.name.c_str(),
                static_cast<int>(setup.bodies.size()), simulated, wall_seconds, result.empty() ? "" : ", ",
                result.c_str(), out.c_str());
    return 0;
}

} // namespace armour