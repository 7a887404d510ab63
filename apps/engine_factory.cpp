#include "engine_factory.h"

#include "free_body_engine.h"
#include "liggghts_engine.h"
#ifdef ARMOUR_HAVE_BULLET
#include "bullet_engine.h"
#endif

namespace armour {

std::vector<std::string> available_engines() {
#ifdef ARMOUR_HAVE_BULLET
    return {"liggghts", "bullet"};
#else
    return {"liggghts"};
#endif
}

std::unique_ptr<RigidBodyEngine> make_engine(const std::string &name, const EngineSettings &settings) {
    if (name == "liggghts")
        return make_liggghts_engine(settings);
    // No contacts: coupled tests of the fluid load alone, and parallel interFoam.
    if (name == "free_body")
        return make_free_body_engine(settings);
#ifdef ARMOUR_HAVE_BULLET
    if (name == "bullet")
        return make_bullet_engine(settings);
#endif
    std::string known;
    for (const auto &e : available_engines())
        known += (known.empty() ? "" : ", ") + e;
    known += ", free_body";
    throw InputError("run.engine: '" + name + "' is not available in this build (available: " + known + ")");
}

} // namespace armour
