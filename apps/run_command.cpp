// `armour run`: the checks of a run and a resume, the dry-run plan, and the
// choice of a DEM run, a settle and a coupled run.
#include "run_command.h"

#include "analysis.h"
#include "checkpoints.h"
#include "coupled_run.h"
#include "dem_run.h"
#include "engine_registry.h"
#include "flume_mesh.h"
#include "foam_restart.h"
#include "output_folder.h"
#include "run_parts.h"
#include "scene_keys.h"
#include "scene_setup.h"
#include "scene_text.h"
#include "series_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

namespace armour {

namespace fs = std::filesystem;
using nlohmann::json;

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
    if (s.fluid) { // records of who settled the layer, and how (runs before them lack them)
        s.fluid->settled_by.clear();
        s.fluid->settled_growth = 1.0;
    }
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
    if (const std::string w = other_arithmetic_warning(*last); !w.empty())
        std::fprintf(stderr, "armour: warning: %s\n", w.c_str());
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
    // The stages are not in the settle's scene (it has no [fluid]).
    const int stages = settle_report(dir, setup).value("settle_stages", 1);
    if (stages != scene.fluid->settle_stages)
        throw InputError("--resume: " + r.scene + ": key 'fluid.settle_stages': " +
                         std::to_string(scene.fluid->settle_stages) + ", where " + dir.string() +
                         " settled in " + std::to_string(stages) + "; run it again without --resume");
    return settled_scene(scene, load_scene((dir / "scene.settled.toml").string()).bodies,
                         settle_growth(scene, settle_scene(scene, setup)));
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
    const SceneSetup settled_setup = build_scene(settled, r.cache_dir(), false);
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
    check_engine_keys(scene);
}

void check_engine_keys(const Scene &scene) {
    if (scene.contact_iterations == 0)
        return;
    std::vector<std::string> engines = {scene.engine};
    if (scene.fluid && scene.fluid->settle_time > 0.0 && !scene.fluid->settle_engine.empty())
        engines.push_back(scene.fluid->settle_engine);
    for (const std::string &engine : engines)
        if (engine_style(engine).capabilities.contacts != ContactKind::rigid_impulse)
            throw InputError(scene.file + ": key 'run.contact_iterations': the " + engine +
                             " engine has no iterative contact solve (a key of engines with rigid contacts, "
                             "bullet; a settled scene keeps its settle's: --set run.contact_iterations=0 "
                             "clears it)");
}

void warn_if_settle_keys_unused(const Scene &scene) {
    if (!scene.fluid || scene.fluid->settle_time > 0.0)
        return;
    if (scene.fluid->settle_friction)
        std::fprintf(stderr, "armour: warning: fluid.settle_friction is unused: there is no settle "
                             "(fluid.settle_time = 0)\n");
    if (scene.fluid->settle_density)
        std::fprintf(stderr, "armour: warning: fluid.settle_density is unused: there is no settle "
                             "(fluid.settle_time = 0)\n");
    if (!scene.fluid->settle_engine.empty())
        std::fprintf(stderr, "armour: warning: fluid.settle_engine is unused: there is no settle "
                             "(fluid.settle_time = 0)\n");
}

void warn_if_hulls_inherit_a_layer(const Scene &scene) {
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
                     "before any wave (the stability scene's layer held dry 5 s: 35 of 99 units displaced at "
                     "friction 0.6, 17 at 0.9; docs/validation/stability.md), "
                     "so their damage is not the waves' alone; one layer for both: a run.engine liggghts "
                     "run with fluid.settle_engine bullet, then its settled scene with --engine bullet\n",
                     settles_here ? "fluid.settle_engine" : "fluid.settled_by", settled_by.c_str(),
                     scene.engine.c_str());
    // A settled scene whose settle grew the cubes to hold the clumps (this
    // run's own settle grows them only for clumps, which fill the growth).
    if (!settles_here && scene.fluid->settled_growth > 1.0 && run == ShapeModel::convex_hulls)
        std::fprintf(
            stderr,
            "armour: warning: fluid.settled_growth %.4g: the settle grew each cube %.4g x to hold its "
            "clump, and run.engine %s runs the exact cubes from those poses: they start up to that "
            "growth apart and drop into the gaps before any wave (the stability scene's severe sea: "
            "32-43 of 99 hulls moved more than 0.2 Dn in the first second, where from a layer the hulls "
            "settled at their own size none did; docs/validation/stability.md), so their damage is "
            "not the waves' alone\n",
            scene.fluid->settled_growth, scene.fluid->settled_growth, scene.engine.c_str());
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
    check_engine_keys(scene);
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
        const int np = r.np > 0 ? r.np : f.np;
        std::printf("coupled with interFoam: template '%s', %s, %d rank%s, fluid steps <= %s s",
                    f.case_name.c_str(), mesh_layout(scene).c_str(), np, np > 1 ? "s" : "",
                    number_text(f.max_time_step).c_str());
        const std::string stages =
            f.settle_stages > 1 ? ", in " + std::to_string(f.settle_stages) + " stages from the toe up" : "";
        if (f.settle_time > 0.0 && !resume_time)
            std::printf("; a dry settle of %s s first%s", number_text(f.settle_time).c_str(), stages.c_str());
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
    const RunCheck check = check_run(scene, r.cache_dir(), np);
    if (r.resume && settles)
        resume = checked_settled_resume(r, scene, check.setup, out).second;
    if (!r.resume)
        warn_if_no_checkpoint(scene);
    warn_if_settle_keys_unused(scene);
    warn_if_hulls_inherit_a_layer(scene);
    for (const std::string &w : check.warnings)
        std::fprintf(stderr, "armour: warning: %s\n", w.c_str());
    print_plan(r, scene, check, out, resume ? std::optional<double>(resume->time) : std::optional<double>());
    return 0;
}

// The latest checkpoint of a run in `out` that stopped before its end (no
// summary.json): a single run's, or any step's of a series.
std::optional<Checkpoint> stopped_run(const fs::path &out) {
    if (!fs::is_directory(out) || fs::exists(out / "summary.json"))
        return std::nullopt;
    std::optional<Checkpoint> latest = last_checkpoint(out);
    std::error_code ec;
    if (fs::is_directory(out / "series", ec))
        for (const auto &step : fs::directory_iterator(out / "series", ec))
            if (const auto last = last_checkpoint(step.path());
                last && (!latest || last->time > latest->time))
                latest = last;
    return latest;
}

// The same command without --resume would replace a stopped run, hours or
// days of waves: the user says which they mean.
void refuse_replacing_stopped_run(const RunRequest &r) {
    if (r.resume && r.restart)
        throw InputError("--resume and --restart: choose one (continue the run in --out, or start it again)");
    if (r.resume || r.restart)
        return;
    if (const auto stopped = stopped_run(fs::path(r.out)))
        throw InputError("--out " + r.out + ": holds a run that stopped at its checkpoint t = " +
                         checkpoint_name(stopped->time) +
                         " s (no summary.json): --resume continues it, --restart starts again (its "
                         "checkpoints are replaced)");
}

} // namespace

std::string RunRequest::cache_dir() const {
    return cache_dir_or_default(cache);
}

std::string resume_key_text(const Scene &scene) {
    return resumable_form(scene, true);
}

std::vector<std::string> check_scene_runs(const Scene &scene, const std::string &cache_dir, int np) {
    return check_run(scene, cache_dir, np).warnings;
}

int run_scene(const RunRequest &r) {
    const Scene scene = load_scene(r.scene, r.overrides);
    refuse_replacing_stopped_run(r);
    if (r.settle_only)
        return settle_only(r, scene);
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
    SceneSetup setup = build_scene(scene, r.cache_dir(), true);
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
    warn_if_settle_keys_unused(scene);
    warn_if_hulls_inherit_a_layer(scene);
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
