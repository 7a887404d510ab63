#include "engine_registry.h"

#include "free_body_engine.h"
#include "liggghts_engine.h"
#ifdef ARMOUR_HAVE_BULLET
#include "bullet_engine.h"
#endif

#include <algorithm>

namespace armour {

const std::vector<EngineStyle> &engine_styles() {
    // To add an engine: write its adapter with a *_engine_style() and add it here.
    static const std::vector<EngineStyle> styles = {
        liggghts_engine_style(),
#ifdef ARMOUR_HAVE_BULLET
        bullet_engine_style(),
#endif
        free_body_engine_style(),
    };
    return styles;
}

std::vector<std::string> engine_style_names() {
    std::vector<std::string> names;
    for (const EngineStyle &style : engine_styles())
        names.push_back(style.name);
    return names;
}

const EngineStyle &engine_style(const std::string &name) {
    const auto &styles = engine_styles();
    const auto it =
        std::find_if(styles.begin(), styles.end(), [&](const EngineStyle &s) { return s.name == name; });
    if (it != styles.end())
        return *it;
    std::string known;
    for (const std::string &n : engine_style_names())
        known += (known.empty() ? "" : ", ") + n;
    throw InputError("run.engine: '" + name + "' is not available in this build (available: " + known + ")");
}

const EngineStyle *find_engine_style(const std::function<bool(const EngineCapabilities &)> &wanted) {
    for (const auto &s : engine_styles())
        if (wanted(s.capabilities))
            return &s;
    return nullptr;
}

std::unique_ptr<RigidBodyEngine> make_engine(const std::string &name, const EngineSettings &settings) {
    return engine_style(name).make(settings);
}

namespace {

std::string text(ContactKind k) {
    switch (k) {
    case ContactKind::spring_dashpot:
        return "spring_dashpot";
    case ContactKind::rigid_impulse:
        return "rigid_impulse";
    case ContactKind::none:
        break;
    }
    return "none";
}

std::string text(ShapeModel s) {
    switch (s) {
    case ShapeModel::sphere_clumps:
        return "sphere_clumps";
    case ShapeModel::convex_hulls:
        return "convex_hulls";
    case ShapeModel::none:
        break;
    }
    return "none";
}

} // namespace

std::string describe_engine_styles() {
    std::string out;
    for (const auto &s : engine_styles()) {
        const EngineCapabilities &c = s.capabilities;
        std::string laws;
        for (ContactModel m : c.contact_models)
            laws += std::string(laws.empty() ? " (" : ", ") + (m == ContactModel::hooke ? "hooke" : "hertz");
        if (!laws.empty())
            laws += ")";
        out += s.name + ": contacts=" + text(c.contacts) + laws + " shape=" + text(c.shape) +
               " parallel=" + (c.replica_per_rank ? "replica_per_rank" : "no") +
               " pivot=" + (c.pivot ? "yes" : "no") + " restart=" + (c.restart ? "yes" : "no") + " -- " +
               s.summary + "\n";
    }
    return out;
}

} // namespace armour
