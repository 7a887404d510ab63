// The analyses of a run, one per scene `analysis` kind, behind one registry.
//
// Description
//     An analysis watches a run and writes its headline figures into the
//     run's summary.json. The run driver never names a kind: it makes the
//     scene's analysis through the registry and asks it
//         before_advance(t, engine)  before the engine advances from t (the
//                                    tilt analysis turns gravity here); the
//                                    engine then advances at most the span
//                                    returned (s) before asking again
//         sample(t, states)          at every recorded step, t = 0 included
//                                    (a coupled run samples its bodies.h5
//                                    after the solver: the same steps)
//         finished()                 true once nothing more can be learnt: the
//                                    run stops early
//         write(summary)             adds the figures; returns a one-line
//                                    result for the console ("" for none)
//     Each kind is an AnalysisStyle (name, headline keys, factory) defined in
//     its own file and listed in analysis_registry.cpp, an explicit list as
//     engines/engine_registry.cpp keeps (a self-registering static object in
//     a static library is dropped by the linker). `armour compare` takes its
//     headline keys from the style. The scene room keeps its own list of
//     kinds (scene_keys.cpp); test_analysis checks that the two agree.
//     docs/analysis.md lists the kinds and their figures with units.
//
// Usage
//     std::unique_ptr<Analysis> a = make_analysis({scene, setup});
//     a->sample(0.0, states);
//     const double span = a->before_advance(engine.time(), engine);
//     ...
//     const std::string line = a->write(summary);
//     check_analysis_fits(scene, setup); // or analysis_refusal(scene, setup): the reason
//     for (const auto &key : analysis_style(scene.analysis).headline_keys) ...
#pragma once

#include "rigid_body_engine.h"
#include "scene.h"
#include "scene_setup.h"

#include <nlohmann/json_fwd.hpp>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace armour {

// What an analysis may read of the run it watches.
struct AnalysisContext {
    const Scene &scene;
    const SceneSetup &setup;
    std::string out_dir;  // the run's output folder (coupled runs: the plugin's fluid.csv)
    std::string case_dir; // the OpenFOAM case of a coupled run (wave gauges); "" for a dry run
    // The path of a top-level entry the analysis writes into the output
    // folder, listed as the run's own (OutputFolder::claim); unset: out_dir/name.
    std::function<std::string(const std::string &)> claim = {};
    // s: the end of what the analysis reads besides the samples (a coupled
    // run's gauges), for `armour report --until` and a record still being written.
    double until = HUGE_VAL;
    // summary["waves"] as the driver measured it once at the wave train's
    // gauges (incident_waves.h: incident height, period, s_om, waves at the
    // toe); null when the run makes no wave train.
    const nlohmann::json *incident_waves = nullptr;
};

class Analysis {
  public:
    virtual ~Analysis() = default;
    // May set loads or gravity on `engine`; returns the longest span (s) to
    // advance before the next call.
    virtual double before_advance(double /*t*/, RigidBodyEngine & /*engine*/) { return HUGE_VAL; }
    // The state of every body at a recorded step (s).
    virtual void sample(double t, const std::vector<BodyState> &states) = 0;
    virtual bool finished() const { return false; }
    // Adds the headline figures (SI, docs/analysis.md) to `summary`.
    virtual std::string write(nlohmann::json &summary) const = 0;
};

struct AnalysisStyle {
    std::string name;                       // as the scene's analysis key names it
    std::string summary;                    // one line
    std::vector<std::string> headline_keys; // summary.json keys `armour compare` tabulates
    // For each headline key that physics predicts, the summary key of the
    // predicted value (compare reports the error against it).
    std::vector<std::pair<std::string, std::string>> analytic_keys;
    bool turns_gravity = false; // gravity is not fixed: an energy balance means nothing
    std::function<std::unique_ptr<Analysis>(const AnalysisContext &)> make;
    // Why the kind cannot watch this scene's bodies ("" when it can; unset:
    // any bodies do). A run refuses the scene with it before any tool runs.
    std::function<std::string(const Scene &, const SceneSetup &)> refusal = {};
};

// Every style, in the order of the scene room's list of kinds.
const std::vector<AnalysisStyle> &analysis_styles();

// Throws InputError naming the key `analysis` and listing the kinds.
const AnalysisStyle &analysis_style(const std::string &name);

// Why scene.analysis cannot watch the scene's bodies; "" when it can.
std::string analysis_refusal(const Scene &scene, const SceneSetup &setup);
// Throws that refusal as an InputError naming the scene file and the key
// `analysis.kind`, before any tool runs.
void check_analysis_fits(const Scene &scene, const SceneSetup &setup);

// The analysis for context.scene.analysis.
std::unique_ptr<Analysis> make_analysis(const AnalysisContext &context);

// The styles defined in the analyses' own files (listed by the registry).
AnalysisStyle none_analysis_style();
AnalysisStyle tilt_analysis_style();
AnalysisStyle bounce_analysis_style();
AnalysisStyle slope_analysis_style();
AnalysisStyle buoyancy_analysis_style();
AnalysisStyle float_analysis_style();
AnalysisStyle still_analysis_style();
AnalysisStyle dambreak_analysis_style();
AnalysisStyle platform_analysis_style();
AnalysisStyle slope_waves_analysis_style();
AnalysisStyle damage_analysis_style();
AnalysisStyle pull_analysis_style();

} // namespace armour
