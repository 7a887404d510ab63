#include "report_command.h"

#include "analysis.h"
#include "bodies_file.h"
#include "damage_analysis.h"
#include "incident_waves.h"
#include "input_error.h"
#include "scene.h"
#include "scene_keys.h"
#include "scene_setup.h"
#include "slope_profile.h"
#include "wave_case.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

namespace armour {

namespace fs = std::filesystem;
using nlohmann::json;

std::string analyse_coupled_record(const Scene &scene, const SceneSetup &setup, const BodiesFile &record,
                                   const fs::path &run_dir, const fs::path &case_dir, OutputFolder &folder,
                                   json &summary, double until, double from) {
    // The analysis samples the record as a dry run's analysis samples the engine.
    AnalysisContext context{scene, setup, run_dir.string(), case_dir.string(),
                            [&](const std::string &name) { return folder.claim(name).string(); }};
    context.until = until;
    // The gauges where the case put them (none without a wave train), read once.
    const std::vector<double> gauge_x = wave_gauge_positions(scene);
    const std::optional<IncidentWaves> waves =
        gauge_x.empty() ? std::nullopt
                        : std::optional(measure_incident_waves(scene, gauge_x, case_dir, until));
    if (waves)
        context.incident_waves = &waves->figures;
    const std::unique_ptr<Analysis> analysis = make_analysis(context);
    std::vector<BodyState> states(record.bodies());
    for (std::size_t s = 0; s < record.steps() && record.time[s] <= until; ++s) {
        if (record.time[s] < from)
            continue;
        record.states_at(s, states);
        analysis->sample(record.time[s], states);
    }
    if (waves)
        add_incident_waves(*waves, context.claim, summary);
    return analysis->write(summary);
}

namespace {

// The steps bodies.xdmf lists: the recorder writes it after each step is
// flushed to bodies.h5, so a step it lists is whole on disk.
std::size_t listed_steps(const fs::path &xdmf) {
    std::ifstream in(xdmf);
    std::size_t steps = 0;
    for (std::string line; std::getline(in, line);)
        steps += line.find("<Time ") != std::string::npos ? 1 : 0;
    return steps;
}

// The record as far as it is whole: a running solver's bodies.h5 may hold a
// step being appended (extended, not yet written or flushed).
BodiesFile whole_record(const fs::path &run, bool ended) {
    const fs::path h5 = run / "bodies.h5";
    for (int attempt = 1;; ++attempt) {
        try {
            BodiesFile record = read_bodies_file(h5.string());
            if (!ended)
                record.keep_steps(listed_steps(run / "bodies.xdmf"));
            return record;
        } catch (const InputError &) {
            if (ended || attempt == 3) // a running solver's append takes milliseconds
                throw;
            std::this_thread::sleep_for(std::chrono::seconds(1));
        }
    }
}

bool inside(const fs::path &path, const fs::path &folder) {
    const fs::path p = fs::weakly_canonical(path), f = fs::weakly_canonical(folder);
    const auto [end, rest] = std::mismatch(f.begin(), f.end(), p.begin(), p.end());
    return end == f.end();
}

// --from: a record to start from, before --until, and no later than the
// front of the scene's wave train reaches the slope's toe.
void check_from(const ReportRequest &r, const Scene &scene, const BodiesFile &record) {
    if (r.from == -HUGE_VAL)
        return; // not given
    if (!(r.from < r.until))
        throw InputError("--from: " + number_text(r.from) + " s is not before --until (" +
                         number_text(r.until) + " s)");
    if (r.from > record.time.back())
        throw InputError("--from: " + number_text(r.from) + " s is after the run's last record (" +
                         number_text(record.time.back()) + " s)");
    const std::optional<SlopeFrame> frame = slope_frame(scene);
    const std::optional<double> arrival = frame ? wave_front_arrival(scene, frame->origin.x()) : std::nullopt;
    if (arrival && r.from > *arrival) // else no train whose waves Van der Meer's prediction counts
        throw InputError("--from: " + number_text(r.from) +
                         " s is after the wave train's front reaches the toe (" + number_text(*arrival) +
                         " s): the damage would be held against waves its reference did not meet");
}

} // namespace

int run_report(const ReportRequest &r) {
    const fs::path run = fs::absolute(r.run).lexically_normal();
    if (!fs::is_directory(run))
        throw InputError(r.run + ": no such folder");
    if (result_of(run) != "armour run")
        throw InputError(r.run + ": not an `armour run` folder (no .armour-output naming \"armour run\")");
    if (inside(r.out, run)) // an entry its marker does not list would stop its resume
        throw InputError("--out: " + r.out + " is inside the run's folder " + run.string() +
                         ": a report goes beside the run");
    const fs::path scene_file = run / "scene.resolved.toml";
    if (!fs::is_regular_file(scene_file))
        throw InputError(scene_file.string() + ": missing: the run stopped before its coupled part started");
    const Scene scene = load_scene(scene_file.string());
    if (!scene.fluid)
        throw InputError(scene_file.string() +
                         ": no [fluid] table: a DEM run's analysis samples its engine as it runs and is in "
                         "its summary.json when it ends; `armour report` reads coupled runs");
    const SceneSetup setup = build_scene(scene, cache_dir_or_default(r.cache), false);
    if (setup.bodies.empty())
        throw InputError(scene_file.string() +
                         ": no bodies (an empty wave flume): its wave figures are in its summary.json when "
                         "it ends; `armour report` reads runs with units");
    const bool ended = fs::is_regular_file(run / "summary.json");
    if (!fs::is_regular_file(run / "bodies.h5"))
        throw InputError((run / "bodies.h5").string() +
                         ": missing: the run stopped before it started recording");
    const BodiesFile record = whole_record(run, ended);
    if (record.steps() == 0)
        throw InputError((run / "bodies.h5").string() + ": no step recorded yet");
    if (!(r.until >= record.time.front())) // NaN too
        throw InputError("--until: " + number_text(r.until) + " s is before the run's first record (" +
                         number_text(record.time.front()) + " s)");
    check_from(r, scene, record);
    if (record.bodies() != setup.bodies.size())
        throw InputError((run / "bodies.h5").string() + ": " + std::to_string(record.bodies()) +
                         " bodies, its scene " + scene_file.string() + " " +
                         std::to_string(setup.bodies.size()));
    OutputFolder folder(r.out, "armour report", OutputFolder::Mode::staged);
    folder.open();

    std::size_t steps = 0;
    while (steps < record.steps() && record.time[steps] <= r.until)
        ++steps;
    const double last = record.time[steps - 1];
    json summary = {
        {"command", "report"},
        {"run", run.string()},
        {"scene", scene.name},
        {"coupled", true},
        {"units", static_cast<int>(setup.bodies.size())},
        {"records", steps},
        {"simulated_seconds", last},
        {"until", std::isfinite(r.until) ? json(r.until) : json(nullptr)},
        {"from", std::isfinite(r.from) ? json(r.from) : json(nullptr)},
        // An ended run has its own summary.json; a stopped or running one none.
        {"run_ended", ended},
        {"warnings", json::array()},
        {"si_units", {{"simulated_seconds", "s"}, {"until", "s"}, {"from", "s"}, {"lengths", "m"}}}};
    // A running or stopped run's gauges go on past its last whole step: the
    // figures end where the record does (an ended run's, as the run took them).
    const double until = ended ? r.until : std::min(r.until, last);
    const std::string result =
        analyse_coupled_record(scene, setup, record, run, run / "case", folder, summary, until, r.from);
    write_text_file(folder.claim("summary.json"), summary.dump(2) + "\n");
    folder.commit();
    std::printf("%s: %d units, record to t = %.6g s%s%s -> %s\n", scene.name.c_str(),
                static_cast<int>(setup.bodies.size()), last, result.empty() ? "" : ", ", result.c_str(),
                folder.target().c_str());
    return 0;
}

} // namespace armour
