#include "analysis.h"

#include <algorithm>

namespace armour {

const std::vector<AnalysisStyle> &analysis_styles() {
    // To add an analysis: write its class and *_analysis_style() in its own
    // file, add it here and to kAnalyses in scene/scene_keys.cpp.
    static const std::vector<AnalysisStyle> styles = {
        none_analysis_style(),        tilt_analysis_style(),     slope_analysis_style(),
        bounce_analysis_style(),      buoyancy_analysis_style(), float_analysis_style(),
        still_analysis_style(),       dambreak_analysis_style(), platform_analysis_style(),
        slope_waves_analysis_style(), damage_analysis_style(),   pull_analysis_style(),
    };
    return styles;
}

const AnalysisStyle &analysis_style(const std::string &name) {
    const auto &styles = analysis_styles();
    const auto it =
        std::find_if(styles.begin(), styles.end(), [&](const AnalysisStyle &s) { return s.name == name; });
    if (it != styles.end())
        return *it;
    std::string known;
    for (const auto &s : styles)
        known += (known.empty() ? "" : ", ") + s.name;
    throw InputError("analysis.kind: '" + name + "' is not an analysis (known: " + known + ")");
}

std::string analysis_refusal(const Scene &scene, const SceneSetup &setup) {
    const AnalysisStyle &style = analysis_style(scene.analysis);
    return style.refusal ? style.refusal(scene, setup) : std::string();
}

void check_analysis_fits(const Scene &scene, const SceneSetup &setup) {
    if (const std::string why = analysis_refusal(scene, setup); !why.empty())
        throw InputError(scene.file + ": key 'analysis.kind': " + why);
}

std::unique_ptr<Analysis> make_analysis(const AnalysisContext &context) {
    return analysis_style(context.scene.analysis).make(context);
}

} // namespace armour
