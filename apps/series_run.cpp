#include "series_run.h"

#include "analysis.h"
#include "bodies_file.h"
#include "checkpoints.h"
#include "coupled_run.h"
#include "flume_mesh.h"
#include "output_folder.h"
#include "run_parts.h"
#include "scene_keys.h"
#include "scene_setup.h"
#include "series_damage.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

namespace armour {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

fs::path step_dir(const fs::path &out, std::size_t k) {
    return out / "series" / std::to_string(k + 1);
}

json read_json(const fs::path &file) {
    std::ifstream in(file);
    return json::parse(in, nullptr, false);
}

std::optional<double> number(const json &o, const char *key) {
    if (o.is_object() && o.contains(key) && o[key].is_number())
        return o[key].get<double>();
    return std::nullopt;
}

json nullable(const std::optional<double> &v) {
    return v ? json(*v) : json(nullptr);
}

// The units where a step left them, at rest: the last record of its
// bodies.h5, each an explicit [[body]] (held axes kept from `scene`'s own).
std::vector<SceneBody> bodies_at_end(const fs::path &dir, const Scene &scene, const SceneSetup &setup) {
    const BodiesFile rec = read_bodies_file((dir / "bodies.h5").string());
    if (rec.steps() == 0 || rec.bodies() != setup.bodies.size())
        throw InputError((dir / "bodies.h5").string() + ": holds " + std::to_string(rec.steps()) +
                         " steps of " + std::to_string(rec.bodies()) + " bodies, not the " +
                         std::to_string(setup.bodies.size()) + " units of the series");
    std::vector<BodyState> states(rec.bodies());
    rec.states_at(rec.steps() - 1, states);
    return bodies_at_rest(scene, setup, states);
}

std::string step_text(const SceneSeriesStep &s) {
    return "Hs " + number_text(s.hs) + " m, Tp " + number_text(s.tp) + " s, gamma " + number_text(s.gamma) +
           ", seed " + std::to_string(s.seed) + ", " + figure_text(s.duration) + " s" +
           (s.waves > 0.0 ? " (" + number_text(s.waves) + " waves after the front)" : "");
}

// Every step's case checked as its run will check it, before anything runs.
std::vector<std::string> check_steps(const RunRequest &r, const Scene &scene, const SceneSetup &setup) {
    const int np = r.np > 0 ? r.np : scene.fluid->np;
    std::vector<std::string> warnings;
    for (std::size_t k = 0; k < scene.series.size(); ++k)
        warnings = check_coupled_scene(series_step_scene(scene, k), setup, np);
    return warnings;
}

// Steps that checkpoint nothing (their checkpoints fall at or after their
// end) start again from their beginning on --resume: one warning.
void warn_if_steps_unresumable(const Scene &scene) {
    const double interval = scene.checkpoint_interval;
    std::string steps;
    for (std::size_t k = 0; k < scene.series.size(); ++k)
        if (interval > 0.0 && interval >= scene.series[k].duration)
            steps += (steps.empty() ? "" : ", ") + std::to_string(k + 1);
    if (!steps.empty())
        std::fprintf(
            stderr,
            "armour: warning: run.checkpoint_interval = %s s is not below the length of step(s) %s: "
            "they write no checkpoint, so a step stopped part way starts again from its beginning on "
            "--resume (finished steps are kept)\n",
            number_text(interval).c_str(), steps.c_str());
}

// Where a step of a resumed series stands.
enum class StepState { done, resumes, restarts, runs };

StepState state_of(const fs::path &dir, bool resume) {
    if (!resume || !fs::exists(dir))
        return StepState::runs;
    if (fs::is_regular_file(dir / "summary.json"))
        return StepState::done;
    return last_checkpoint(dir) ? StepState::resumes : StepState::restarts;
}

// --resume: the series that ran in `out` must be this one (but for the
// resumable keys), and its settle must have ended. Returns its start.
Scene checked_series_start(const RunRequest &r, const Scene &scene, const SceneSetup &setup,
                           const fs::path &out) {
    const fs::path ran = out / "scene.resolved.toml";
    if (!fs::is_regular_file(ran))
        throw InputError("--resume: " + ran.string() + " is missing: not a series to continue");
    refuse_if_differs(r.scene, resumable_form(scene), resumable_form(load_scene(ran.string())),
                      "ran in " + out.string());
    return scene.fluid->settle_time > 0.0 ? checked_settle(r, scene, setup, out) : scene;
}

// One step: run, resumed from its checkpoint, or (done) checked and kept.
int run_step(const RunRequest &r, const Scene &step, const SceneSetup &setup, const fs::path &dir,
             const SceneSeriesStep &values, std::size_t k, std::size_t count) {
    RunRequest request = r;
    request.out = dir.string();
    const StepState state = state_of(dir, r.resume);
    const std::string head = "run: series step " + std::to_string(k + 1) + " of " + std::to_string(count);
    if (state == StepState::done) {
        refuse_if_differs(r.scene, resumable_form(step),
                          resumable_form(load_scene((dir / "scene.resolved.toml").string())),
                          "ran in " + dir.string());
        std::fprintf(stderr, "%s: done in %s, kept\n", head.c_str(), dir.c_str());
        return 0;
    }
    OutputFolder folder(dir, "armour run", OutputFolder::Mode::streaming);
    std::optional<Checkpoint> checkpoint;
    if (state == StepState::resumes)
        checkpoint = checked_resume(request, step, dir);
    const std::string how = checkpoint ? " (resumed at t = " + number_text(checkpoint->time) + " s)"
                            : state == StepState::restarts ? " (no checkpoint: from its start)"
                                                           : "";
    std::fprintf(stderr, "%s: %s%s -> %s\n", head.c_str(), step_text(values).c_str(), how.c_str(),
                 dir.c_str());
    if (checkpoint) {
        folder.resume();
        return run_coupled(request, step, setup, folder, &*checkpoint);
    }
    return run_coupled(request, step, setup, folder);
}

// Per step its own figures (its summary.json) and the series' so far
// (`total`, against the series' start), and Van der Meer's cumulative
// prediction; returns the steps' sea states for the whole series' figures.
json step_entry(const Scene &series, std::size_t k, const json &own, const CumulativeFigures &total) {
    const SceneSeriesStep &step = series.series[k];
    const json &waves = own.contains("waves") ? own["waves"] : json();
    const json &damage = own.contains("damage") ? own["damage"] : json();
    const auto value = [&](const char *key) { return own.contains(key) ? own[key] : json(nullptr); };
    return {{"step", k + 1},
            {"folder", "series/" + std::to_string(k + 1)},
            {"target_height", step.hs},
            {"target_period", step.tp},
            {"gamma", step.gamma},
            {"seed", step.seed},
            {"duration", step.duration},
            {"incident_height", nullable(number(waves, "incident_height"))},
            {"waves", nullable(number(damage, "waves"))},
            {"Ns", value("Ns")},
            {"s_om", value("s_om")},
            {"wave_source", damage.value("wave_source", "none")},
            {"units_displaced", value("units_displaced")},
            {"N_od", value("N_od")},
            {"damage_S", value("damage_S")},
            {"rocking_units", value("rocking_units")},
            {"units_displaced_total", total.displaced},
            {"N_od_total", total.N_od},
            {"damage_S_total", nullable(total.S)},
            {"rocking_units_total", total.rocking_units},
            {"wall_seconds", value("wall_seconds")}};
}

// OUT/summary.json of the whole series, from its steps' records and summaries.
int write_series_summary(const Scene &series, const Scene &last, const SceneSetup &setup,
                         OutputFolder &folder, const json &settle) {
    const fs::path out = folder.target();
    AnalysisContext context{last, setup, out.string(), "",
                            [&](const std::string &name) { return folder.claim(name).string(); }};
    const std::unique_ptr<Analysis> analysis = make_analysis(context);
    CumulativeDamage cumulative(last, setup);
    json steps = json::array();
    std::vector<SeaStateFigures> sea_states;
    std::vector<BodyState> states(setup.bodies.size());
    double offset = 0.0, wall = 0.0, N = 0.0;
    for (std::size_t k = 0; k < series.series.size(); ++k) {
        const fs::path dir = step_dir(out, k);
        const BodiesFile rec = read_bodies_file((dir / "bodies.h5").string());
        // A step's first record is the last of the step before: sampled once.
        for (std::size_t s = k == 0 ? 0 : 1; s < rec.steps(); ++s) {
            rec.states_at(s, states);
            analysis->sample(offset + rec.time[s], states);
            cumulative.sample(offset + rec.time[s], states);
        }
        offset += rec.time.empty() ? 0.0 : rec.time.back();
        const json own = read_json(dir / "summary.json");
        steps.push_back(step_entry(series, k, own, cumulative.figures()));
        sea_states.push_back({number(own, "Ns"), number(own, "s_om"), number(own["damage"], "waves")});
        wall += number(own, "wall_seconds").value_or(0.0);
        N += number(own["damage"], "waves").value_or(0.0);
    }
    const std::vector<SequencePrediction> predicted = van_der_meer_cubes_sequence(sea_states);
    for (std::size_t k = 0; k < steps.size(); ++k) {
        steps[k]["N_od_van_der_meer"] = nullable(predicted[k].N_od);
        steps[k]["waves_equivalent"] = nullable(predicted[k].equivalent_waves);
    }
    json summary = {{"command", "run"},
                    {"coupled", true},
                    {"scene", series.name},
                    {"engine", last.engine},
                    {"units", static_cast<int>(setup.bodies.size())},
                    {"simulated_seconds", offset},
                    {"wall_seconds", wall},
                    {"warnings", json::array()},
                    {"series_steps", steps.size()}};
    // The whole series' waves, as the damage analysis reads a run's: the
    // last step's height and steepness (the sea state the layer ends under),
    // every step's waves.
    const json &last_own = read_json(step_dir(out, steps.size() - 1) / "summary.json");
    const std::optional<double> Hs = number(last_own["damage"], "Hs"), s_om = number(last_own, "s_om");
    if (Hs && s_om)
        summary["waves"] = {{"incident_height", *Hs},
                            {"s_om", *s_om},
                            {"waves", N},
                            {"source", "the last step's Hs (damage.Hs) and s_om, the waves of every step"}};
    const std::string line = analysis->write(summary);
    if (Hs && s_om) // what the series' figures used, not an incident height measured at the toe
        summary["waves"] = {{"waves", N},
                            {"height", *Hs},
                            {"s_om", *s_om},
                            {"source", "the last step's Hs (damage.Hs) and s_om, the waves of every step"}};
    // Van der Meer for the series: the cumulative prediction by the
    // equivalent number of waves, not the formula at the total N.
    const SequencePrediction &end = predicted.back();
    const double width = summary["damage"]["layer_width"].get<double>(),
                 Dn = summary["damage"]["Dn"].get<double>();
    summary["N_od_van_der_meer"] = nullable(end.N_od);
    summary["units_displaced_van_der_meer"] = end.N_od ? json(*end.N_od * width / Dn) : json(nullptr);
    summary["Ns_van_der_meer"] =
        end.equivalent_waves && s_om && sea_states.back().waves
            ? json(van_der_meer_cubes_ns(summary["N_od"].get<double>(),
                                         *end.equivalent_waves + *sea_states.back().waves, *s_om))
            : json(nullptr);
    summary["damage"]["wave_source"] = "series";
    if (!settle.is_null()) {
        if (const std::string w = unsettled_warning(settle); !w.empty())
            summary["warnings"].push_back(w);
        summary["settle"] = settle;
    }
    summary["series"] = steps;
    write_text_file(folder.claim("summary.json"), summary.dump(2) + "\n");
    std::printf("%s: series of %zu steps, %.4g s coupled in %.1f s wall, %s -> %s\n", series.name.c_str(),
                steps.size(), offset, wall, line.c_str(), out.c_str());
    return 0;
}

// `armour run --dry-run` of a series: its checks and its plan, step by step.
int dry_run_series(const RunRequest &r, const Scene &scene) {
    const fs::path out = OutputFolder::check_writable(r.out, "armour run");
    check_options(r, scene);
    const SceneSetup setup = build_scene(scene, r.cache_dir(), false);
    const std::vector<std::string> warnings = check_steps(r, scene, setup);
    const bool settles = scene.fluid->settle_time > 0.0;
    if (r.resume)
        checked_series_start(r, scene, setup, out);
    warn_if_settle_keys_unused(scene);
    warn_if_hulls_inherit_a_layer(scene);
    warn_if_steps_unresumable(scene);
    if (!settles) // the layer the waves meet is known (a settle's is not yet)
        for (const std::string &w : warnings)
            std::fprintf(stderr, "armour: warning: %s\n", w.c_str());
    std::printf("%s: dry run, nothing written; checked: the scene, its units and engine, every step's waves "
                "and fluid case, OpenFOAM's tools and --out %s\n",
                r.scene.c_str(), out.c_str());
    std::printf("  %zu units, engine %s; coupled with interFoam: %s, %d rank%s%s\n", setup.bodies.size(),
                scene.engine.c_str(), mesh_layout(scene).c_str(), r.np > 0 ? r.np : scene.fluid->np,
                (r.np > 0 ? r.np : scene.fluid->np) > 1 ? "s" : "",
                settles && !r.resume
                    ? ("; a dry settle of " + number_text(scene.fluid->settle_time) + " s first (" +
                       (scene.fluid->settle_engine.empty() ? scene.engine : scene.fluid->settle_engine) + ")")
                          .c_str()
                    : "");
    double total = 0.0;
    for (std::size_t k = 0; k < scene.series.size(); ++k) {
        const fs::path dir = step_dir(out, k);
        const char *what[] = {"done, kept", "resumes from its last checkpoint",
                              "starts again (no checkpoint)", "runs"};
        std::printf("  step %zu: %s: %s -> %s\n", k + 1, step_text(scene.series[k]).c_str(),
                    what[static_cast<int>(state_of(dir, r.resume))], dir.c_str());
        total += scene.series[k].duration;
    }
    std::printf("  %s s of simulated time in %zu steps, a record every %s s\n", number_text(total).c_str(),
                scene.series.size(), number_text(scene.output_interval).c_str());
    return 0;
}

} // namespace

int run_series(const RunRequest &r, const Scene &scene) {
    if (r.dry_run)
        return dry_run_series(r, scene);
    OutputFolder folder(r.out, "armour run", OutputFolder::Mode::streaming); // refused before any work
    check_options(r, scene);
    SceneSetup setup = build_scene(scene, r.cache_dir(), true);
    warn_if_settle_keys_unused(scene);
    warn_if_hulls_inherit_a_layer(scene);
    check_steps(r, scene, setup); // every step's case, before anything is written
    warn_if_steps_unresumable(scene);
    const fs::path out = folder.target();
    const bool settles = scene.fluid->settle_time > 0.0;
    Scene start;
    json settle;
    if (r.resume) {
        start = checked_series_start(r, scene, setup, out);
        folder.resume();
        if (settles) {
            settle = settle_report(out / "settle", setup);
            setup = build_scene(start, r.cache_dir(), false);
        }
    } else {
        folder.open(); // an earlier result of this command is replaced
        write_text_file(folder.claim("scene.resolved.toml"), resolved_scene_toml(scene));
        start = settles ? settle_before_coupling(r, folder, scene, setup, settle) : scene;
    }
    if (!settle.is_null())
        settle["scene"] = "settle/scene.settled.toml";
    std::error_code ec;
    fs::create_directories(folder.claim("series"), ec);
    if (ec)
        throw InputError("--out: cannot create " + (out / "series").string() + ": " + ec.message());
    const std::size_t count = scene.series.size();
    Scene step = series_step_scene(start, 0);
    SceneSetup step_setup = build_scene(step, r.cache_dir(), false);
    for (std::size_t k = 0;; ++k) {
        if (const int status = run_step(r, step, step_setup, step_dir(out, k), scene.series[k], k, count);
            status != 0)
            return status;
        if (k + 1 == count)
            break;
        const std::vector<SceneBody> bodies = bodies_at_end(step_dir(out, k), start, step_setup);
        step = series_step_scene(start, k + 1, &bodies);
        step_setup = build_scene(step, r.cache_dir(), false);
    }
    return write_series_summary(scene, step, step_setup, folder, settle);
}

Scene series_step_scene(const Scene &start, std::size_t k, const std::vector<SceneBody> *bodies) {
    Scene s = start;
    const SceneSeriesStep &step = start.series.at(k);
    s.series.clear();
    SceneWaves &w = *s.waves;
    w.hs = step.hs;
    w.tp = step.tp;
    w.gamma = step.gamma;
    w.seed = step.seed;
    w.ramp_time = step.ramp_time;
    s.duration = step.duration;
    s.fluid->write_interval = std::min(s.fluid->write_interval, step.duration);
    if (bodies) {
        s.bodies = *bodies;
        s.drops.clear();
        s.patterns.clear();
    }
    return s;
}

} // namespace armour
