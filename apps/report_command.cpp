#include "report_command.h"

#include "analysis.h"
#include "bodies_file.h"
#include "mesh.h"
#include "scene.h"
#include "scene_keys.h"
#include "scene_setup.h"
#include "wave_case.h"

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

namespace armour {

namespace fs = std::filesystem;
using nlohmann::json;

std::string analyse_coupled_record(const Scene &scene, const SceneSetup &setup, const BodiesFile &record,
                                   const fs::path &run_dir, const fs::path &case_dir, OutputFolder &folder,
                                   json &summary, double until) {
    // The analysis samples the record as a dry run's analysis samples the engine.
    const std::unique_ptr<Analysis> analysis =
        make_analysis({scene, setup, run_dir.string(), case_dir.string(),
                       [&](const std::string &name) { return folder.claim(name).string(); }});
    std::vector<BodyState> states(record.bodies());
    for (std::size_t s = 0; s < record.steps() && record.time[s] <= until; ++s) {
        record.states_at(s, states);
        analysis->sample(record.time[s], states);
    }
    if (makes_wave_train(scene)) // first: the damage analysis reads the incident Hm0, s_om and N
        add_wave_summary(scene, case_dir, folder, summary, until);
    return analysis->write(summary);
}

int run_report(const ReportRequest &r) {
    const fs::path run = fs::absolute(r.run).lexically_normal();
    if (!fs::is_directory(run))
        throw InputError(r.run + ": no such folder");
    {
        std::ifstream marker(run / ".armour-output");
        std::string owner;
        if (!marker || !std::getline(marker, owner) || owner != "armour run")
            throw InputError(r.run +
                             ": not an `armour run` folder (no .armour-output naming \"armour run\")");
    }
    const fs::path scene_file = run / "scene.resolved.toml", bodies_file = run / "bodies.h5";
    for (const fs::path &p : {scene_file, bodies_file})
        if (!fs::is_regular_file(p))
            throw InputError(p.string() + ": missing: the run stopped before it started recording");
    const Scene scene = load_scene(scene_file.string());
    if (!scene.fluid)
        throw InputError(scene_file.string() +
                         ": no [fluid] table: a DEM run's analysis samples its engine as it runs and is in "
                         "its summary.json when it ends; `armour report` reads coupled runs");
    const BodiesFile record = read_bodies_file(bodies_file.string());
    if (record.steps() == 0)
        throw InputError(bodies_file.string() + ": no step recorded yet");
    if (r.until < record.time.front())
        throw InputError("--until: " + number_text(r.until) + " s is before the run's first record (" +
                         number_text(record.time.front()) + " s)");
    OutputFolder folder(r.out, "armour report", OutputFolder::Mode::staged); // refused before any work
    const SceneSetup setup = build_scene(scene, r.cache.empty() ? default_cache_dir() : r.cache, false);
    if (record.bodies() != setup.bodies.size())
        throw InputError(bodies_file.string() + ": " + std::to_string(record.bodies()) +
                         " bodies, its scene " + scene_file.string() + " " +
                         std::to_string(setup.bodies.size()));
    folder.open();

    std::size_t steps = 0;
    while (steps < record.steps() && record.time[steps] <= r.until)
        ++steps;
    const double last = record.time[steps - 1];
    json summary = {{"command", "report"},
                    {"run", run.string()},
                    {"scene", scene.name},
                    {"coupled", true},
                    {"units", static_cast<int>(setup.bodies.size())},
                    {"records", steps},
                    {"simulated_seconds", last},
                    {"until", std::isfinite(r.until) ? json(r.until) : json(nullptr)},
                    // An ended run has its own summary.json; a stopped or running one none.
                    {"run_ended", fs::is_regular_file(run / "summary.json")},
                    {"warnings", json::array()},
                    {"si_units", {{"simulated_seconds", "s"}, {"until", "s"}, {"lengths", "m"}}}};
    const std::string result =
        analyse_coupled_record(scene, setup, record, run, run / "case", folder, summary, r.until);
    write_text_file(folder.claim("summary.json"), summary.dump(2) + "\n");
    folder.commit();
    std::printf("%s: %d units, record to t = %.6g s%s%s -> %s\n", scene.name.c_str(),
                static_cast<int>(setup.bodies.size()), last, result.empty() ? "" : ", ", result.c_str(),
                folder.target().c_str());
    return 0;
}

} // namespace armour
