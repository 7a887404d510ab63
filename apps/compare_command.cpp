// Runs one scene with sphere clumps of several sizes and with exact convex
// hulls, measures each against the exact run (and an analytic value where
// one exists) next to its cost, sweeps the time step past the stability
// limit for both engines, and writes summary.json, charts and a report.
#include "compare_command.h"

#include "analysis.h"
#include "compare_stats.h"
#include "engine_registry.h"
#include "output_folder.h"
#include "run_command.h"
#include "scene.h"
#include "scene_keys.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <utility>

namespace armour {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct Run {
    Run(std::string label_, std::string engine_, int spheres_, std::uint64_t seed_, double dt_factor_ = 0.0)
        : label(std::move(label_)), engine(std::move(engine_)), spheres(spheres_), seed(seed_),
          dt_factor(dt_factor_) {}
    std::string label, engine;
    int spheres; // 0 for exact hulls
    std::uint64_t seed;
    double dt_factor; // 0: the default step
    json summary;     // null if the run failed
    std::string failure;
    bool blew_up = false; // ran to the end, but gained energy beyond --blow-up-gain
    bool ok() const { return summary.is_object() && !blew_up; }
};

Run execute(const CompareRequest &r, const fs::path &runs, Run run, std::vector<std::string> overrides) {
    overrides.insert(overrides.begin(), r.overrides.begin(), r.overrides.end());
    std::fprintf(stderr, "compare: %s\n", run.label.c_str());
    try {
        const fs::path dir = runs / run.label;
        run_scene({r.scene, dir.string(), overrides, r.cache});
        std::ifstream in(dir / "summary.json");
        run.summary = json::parse(in);
    } catch (const InputError &e) {
        // A run that fails (e.g. a unit leaves the domain at an unstable step)
        // is a result of the comparison, not an error of it.
        run.failure = e.what();
        std::fprintf(stderr, "compare: %s failed: %s\n", run.label.c_str(), e.what());
    }
    return run;
}

double number_or_nan(const json &summary, const std::string &key) {
    return summary.is_object() && summary.contains(key) && summary[key].is_number()
               ? summary[key].get<double>()
               : std::nan("");
}

template <typename T> std::string joined(const std::vector<T> &values) {
    std::string text;
    for (const T &v : values)
        text += (text.empty() ? "" : ",") + number_text(static_cast<double>(v));
    return text;
}

// `armour compare --dry-run`: what the real command checks before its first
// run (the scene, the options, --out), then the runs it would make.
int print_compare_plan(const CompareRequest &r, const Scene &scene, const std::vector<std::uint64_t> &seeds,
                       const std::vector<std::string> &engines) {
    const std::filesystem::path out = OutputFolder::check_writable(r.out, "armour compare");
    const std::size_t per_seed = r.spheres.size() + (engines.size() > 1 ? 1 : 0);
    std::printf("%s: dry run, nothing written; checked: the scene, the options and --out %s\n",
                r.scene.c_str(), out.c_str());
    std::printf("  %zu runs of %s s (simulated): seeds %s x (clumps of %s spheres on %s%s)\n",
                seeds.size() * per_seed, number_text(scene.duration).c_str(), joined(seeds).c_str(),
                joined(r.spheres).c_str(), engines.front().c_str(),
                engines.size() > 1 ? (", exact hulls on " + engines[1]).c_str() : "");
    if (analysis_style(scene.analysis).turns_gravity || r.dt_factors.empty())
        std::printf("  no time-step sweep (%s)\n",
                    r.dt_factors.empty() ? "--dt-factors is empty" : "the analysis turns gravity");
    else
        std::printf("  time-step sweep: %zu factors (%s x the stability limit) x %zu engines\n",
                    r.dt_factors.size(), joined(r.dt_factors).c_str(), engines.size());
    return 0;
}

// The options checked before any run; returns the --tolerance figures.
std::map<std::string, double> checked_options(const CompareRequest &r, const Scene &scene) {
    if (r.spheres.empty())
        throw InputError("--spheres: give at least one sphere count, e.g. 5,10,20");
    for (int n : r.spheres)
        if (n < 2)
            throw InputError("--spheres: every count must be >= 2 (LIGGGHTS multisphere), got " +
                             std::to_string(n));
    if (r.dt_sweep_spheres != 0 && r.dt_sweep_spheres < 2)
        throw InputError(
            "--dt-sweep-spheres: must be >= 2 (LIGGGHTS multisphere), or 0 for the --spheres count "
            "nearest 20 (got " +
            std::to_string(r.dt_sweep_spheres) + ")");
    for (double f : r.dt_factors)
        if (!(f > 0.0))
            throw InputError("--dt-factors: every factor must be > 0");
    if (!(r.blow_up_gain > 0.0) || !std::isfinite(r.blow_up_gain))
        throw InputError("--blow-up-gain: must be a positive number (energy / sum(m g Dn))");
    const std::map<std::string, double> tolerances = parse_tolerances(r.tolerance);
    const std::vector<std::string> &headline = analysis_style(scene.analysis).headline_keys;
    std::string known;
    for (const auto &k : headline)
        known += (known.empty() ? "" : ", ") + k;
    for (const auto &[key, value] : tolerances)
        if (std::find(headline.begin(), headline.end(), key) == headline.end())
            throw InputError("--tolerance: " + key + ": not a headline figure of analysis '" +
                             scene.analysis + "' (" + (known.empty() ? "none" : known) + ")");
    return tolerances;
}

// The two sides: sphere clumps, and exact hulls where this build has them
// (the clump engine first).
std::vector<std::string> compared_engines() {
    const EngineStyle *clumps = find_engine_style([](const EngineCapabilities &c) {
        return c.contacts != ContactKind::none && c.shape == ShapeModel::sphere_clumps;
    });
    const EngineStyle *hulls = find_engine_style([](const EngineCapabilities &c) {
        return c.contacts != ContactKind::none && c.shape == ShapeModel::convex_hulls;
    });
    if (!clumps)
        throw InputError("armour compare: this build has no sphere-clump contact engine");
    std::vector<std::string> engines = {clumps->name};
    if (hulls)
        engines.push_back(hulls->name);
    return engines;
}

// The runs of one comparison and the scene keys each sets.
struct Comparison {
    const CompareRequest &request;
    const Scene &scene;
    std::vector<std::uint64_t> seeds;
    std::vector<std::string> engines; // the clump engine, then the exact one if any
    fs::path runs;                    // each run's folder is runs/<label>

    const std::string &clump_engine() const { return engines.front(); }
    std::string exact_engine() const { return engines.size() > 1 ? engines[1] : ""; }

    std::vector<std::string> overrides(std::uint64_t seed, int spheres, const std::string &engine) const {
        std::vector<std::string> o;
        for (std::size_t j = 0; j < scene.drops.size(); ++j)
            o.push_back("drop." + std::to_string(j) + ".seed=" + std::to_string(seed));
        if (spheres > 0)
            for (std::size_t k = 0; k < scene.units.size(); ++k)
                o.push_back("unit." + std::to_string(k) + ".spheres=" + std::to_string(spheres));
        o.push_back("run.engine=\"" + engine + "\"");
        return o;
    }
};

// Every seed: the exact hulls, then each clump size.
std::vector<Run> run_models(const Comparison &c) {
    std::vector<Run> results;
    for (std::uint64_t seed : c.seeds) {
        if (!c.exact_engine().empty())
            results.push_back(execute(c.request, c.runs,
                                      Run("exact_seed" + std::to_string(seed), c.exact_engine(), 0, seed),
                                      c.overrides(seed, 0, c.exact_engine())));
        for (int n : c.request.spheres)
            results.push_back(execute(
                c.request, c.runs,
                Run("clump" + std::to_string(n) + "_seed" + std::to_string(seed), c.clump_engine(), n, seed),
                c.overrides(seed, n, c.clump_engine())));
    }
    return results;
}

// Time step past the limit, for both engines (first seed, one clump size).
// Its measure is the energy gain, which needs fixed gravity: a tilt scene
// turns gravity, so it gets no sweep (the report says so). Each factor
// multiplies the limit of the very body the sweep runs (the clump of
// --dt-sweep-spheres, run at its default step first if --spheres lacks it).
std::vector<Run> run_dt_sweep(const Comparison &c, const std::vector<Run> &results) {
    std::vector<Run> sweep;
    if (analysis_style(c.scene.analysis).turns_gravity)
        return sweep;
    const CompareRequest &r = c.request;
    const std::uint64_t seed = c.seeds.front();
    int sweep_spheres = r.dt_sweep_spheres;
    if (sweep_spheres <= 0)
        for (int n : r.spheres)
            if (sweep_spheres <= 0 || std::abs(n - 20) < std::abs(sweep_spheres - 20))
                sweep_spheres = n;
    for (const std::string &engine : c.engines) {
        const int spheres = engine == c.clump_engine() ? sweep_spheres : 0;
        double limit = 0.0;
        for (const Run &run : results)
            if (run.engine == engine && run.spheres == spheres && run.seed == seed && run.summary.is_object())
                limit = run.summary["dt_limit"].get<double>();
        if (limit <= 0.0 && !r.dt_factors.empty()) {
            Run probe("dt_" + engine + "_default", engine, spheres, seed);
            sweep.push_back(execute(r, c.runs, probe, c.overrides(seed, spheres, engine)));
            if (sweep.back().summary.is_object())
                limit = sweep.back().summary["dt_limit"].get<double>();
        }
        if (limit <= 0.0)
            continue;
        for (double f : r.dt_factors) {
            auto o = c.overrides(seed, spheres, engine);
            char step[64];
            std::snprintf(step, sizeof step, "run.time_step=%.17g", f * limit);
            char interval[64];
            std::snprintf(interval, sizeof interval, "run.output_interval=%.17g",
                          std::max(c.scene.output_interval, f * limit));
            o.insert(o.end(), {step, interval, "run.force_time_step=true"});
            char label[64];
            std::snprintf(label, sizeof label, "dt_%s_x%g", engine.c_str(), f);
            sweep.push_back(execute(r, c.runs, Run(label, engine, spheres, seed, f), o));
        }
    }
    return sweep;
}

// (E_max - E_0) / sum(m g Dn) of a run's summary; NaN where it has no energies.
double energy_gain(const json &s) {
    const double scale = number_or_nan(s, "energy_scale");
    return (number_or_nan(s, "energy_max") - number_or_nan(s, "energy_initial")) /
           (scale > 0.0 ? scale : std::nan(""));
}

// A run that gains energy beyond the threshold blew up: a failure, kept out
// of the statistics. Only where gravity is fixed (else the energy balance
// means nothing).
void mark_blow_ups(std::vector<Run> &runs, double blow_up_gain) {
    for (Run &run : runs)
        if (run.summary.is_object() && energy_gain(run.summary) > blow_up_gain) {
            char why[160];
            std::snprintf(why, sizeof why, "blow-up: energy gain %.3g x sum(m g Dn) > %.3g (--blow-up-gain)",
                          energy_gain(run.summary), blow_up_gain);
            run.failure = why;
            run.blew_up = true;
        }
}

// Each headline figure's mean over the exact runs that succeeded (null where none has it).
json exact_means(const std::vector<Run> &results, const std::vector<std::string> &keys,
                 const std::string &exact_engine) {
    json mean = json::object();
    for (const auto &key : keys) {
        double sum = 0.0;
        int n = 0;
        for (const Run &run : results)
            if (run.engine == exact_engine && run.ok() && std::isfinite(number_or_nan(run.summary, key))) {
                sum += number_or_nan(run.summary, key);
                ++n;
            }
        mean[key] = n > 0 ? json(sum / n) : json(nullptr);
    }
    return mean;
}

// One run's entry in summary.json: its cost, its figures and their errors
// against the exact runs' mean and against the analysis' analytic values.
json run_entry(const Run &run, const AnalysisStyle &analysis, const json &exact_mean) {
    json e = {{"label", run.label},
              {"engine", run.engine},
              {"spheres", run.spheres},
              {"seed", run.seed},
              {"status", run.ok() ? "ok" : "failed"}};
    if (!run.ok())
        e["failure"] = run.failure;
    if (run.blew_up)
        e["blow_up"] = true;
    if (run.dt_factor > 0.0)
        e["dt_factor_requested"] = run.dt_factor;
    if (!run.summary.is_object())
        return e;
    const json &s = run.summary;
    for (const char *k :
         {"wall_seconds", "wall_seconds_per_simulated_second", "seconds_per_unit_step", "dt", "dt_limit",
          "steps", "energy_initial", "energy_max", "energy_final", "energy_scale"})
        e[k] = s.value(k, json(nullptr));
    const double gain = energy_gain(s);
    e["energy_gain"] = std::isfinite(gain) ? json(gain) : json(nullptr);
    // The step as a multiple of this run's own limit (what the charts show).
    const double dt = number_or_nan(s, "dt"), dt_limit = number_or_nan(s, "dt_limit");
    if (dt > 0.0 && dt_limit > 0.0)
        e["dt_factor"] = dt / dt_limit;
    json figures = json::object(), vs_exact = json::object(), vs_analytic = json::object();
    for (const auto &key : analysis.headline_keys) {
        const double v = number_or_nan(s, key);
        figures[key] = std::isfinite(v) ? json(v) : json(nullptr);
        const double x = exact_mean[key].is_number() ? exact_mean[key].get<double>() : std::nan("");
        vs_exact[key] = std::isfinite(v) && std::isfinite(x) ? json(v - x) : json(nullptr);
    }
    for (const auto &[key, analytic_key] : analysis.analytic_keys)
        if (s.contains(analytic_key) && s[analytic_key].is_number()) { // null: no prediction
            const double v = number_or_nan(s, key);
            vs_analytic[key] = std::isfinite(v) ? json(v - s[analytic_key].get<double>()) : json(nullptr);
        }
    e["figures"] = figures;
    e["error_vs_exact"] = vs_exact;
    e["error_vs_analytic"] = vs_analytic;
    return e;
}

} // namespace

int run_compare(const CompareRequest &r) {
    const Scene scene = load_scene(r.scene, r.overrides); // checks everything before any run
    const std::map<std::string, double> tolerances = checked_options(r, scene);
    std::vector<std::uint64_t> seeds = r.seeds;
    if (seeds.empty())
        seeds = scene.drops.empty() ? std::vector<std::uint64_t>{1} : std::vector<std::uint64_t>{1, 2, 3};
    const std::vector<std::string> engines = compared_engines();
    if (r.dry_run)
        return print_compare_plan(r, scene, seeds, engines);

    OutputFolder out(r.out, "armour compare", OutputFolder::Mode::staged);
    out.open();
    const Comparison c{r, scene, seeds, engines, out.claim("runs")};
    fs::create_directories(c.runs);
    std::vector<Run> results = run_models(c);
    std::vector<Run> sweep = run_dt_sweep(c, results);
    const AnalysisStyle &analysis = analysis_style(scene.analysis);
    if (!analysis.turns_gravity) {
        mark_blow_ups(results, r.blow_up_gain);
        mark_blow_ups(sweep, r.blow_up_gain);
    }

    // Errors against the exact runs (mean over seeds) and against analytic values.
    const std::vector<std::string> &keys = analysis.headline_keys;
    const std::string exact_engine = c.exact_engine();
    const json exact_mean = exact_means(results, keys, exact_engine);
    json entries = json::array(), sweep_entries = json::array();
    for (const Run &run : results)
        entries.push_back(run_entry(run, analysis, exact_mean));
    for (const Run &run : sweep)
        sweep_entries.push_back(run_entry(run, analysis, exact_mean));
    const json groups = compare_groups(entries, keys, exact_engine);
    const json advice = compare_advice(groups, keys, tolerances, exact_engine);
    const json summary = {
        {"command", "compare"},
        {"scene", scene.name},
        {"analysis", scene.analysis},
        {"headline_keys", keys},
        {"exact_engine", exact_engine.empty() ? json(nullptr) : json(exact_engine)},
        {"exact_mean", exact_mean},
        {"seeds", seeds},
        {"runs", entries},
        {"dt_sweep", sweep_entries},
        {"groups", groups},
        {"advice", advice},
        {"blow_up_gain", r.blow_up_gain},
        {"units",
         {{"wall_seconds", "s"},
          {"seconds_per_unit_step", "s"},
          {"dt", "s"},
          {"energy", "J"},
          {"energy_gain", "(E_max - E_0) / sum(m g Dn), -"},
          {"cost", "wall seconds per simulated second"},
          {"ci95", "half-width of the 95 % interval of the mean (Student t)"},
          {"errors", "in the figure's own unit (deg, -), signed: run minus exact mean / minus analytic"}}}};
    write_text_file(out.claim("summary.json"), summary.dump(2) + "\n");
    const std::string plot = std::string("/usr/bin/python3 '") + ARMOUR_SOURCE_DIR +
                             "/comparison/compare_report.py' '" + out.dir().string() + "'";
    if (std::system(plot.c_str()) != 0)
        throw InputError("compare: the report script failed (needs python3-matplotlib): " + plot);
    out.commit();
    std::printf("compare: %zu runs, %zu dt-sweep runs -> %s (summary.json, pareto.png, report.md)\n",
                results.size(), sweep.size(), out.target().c_str());
    return 0;
}

} // namespace armour
