#include "materials.h"

#include <algorithm>
#include <cmath>

namespace armour {

void check_materials(const EngineSettings &settings) {
    if (settings.materials.empty())
        throw InputError("material: at least one material is needed");
    for (const Material &m : settings.materials) {
        auto bad = [&](const std::string &key, const std::string &rule) {
            throw InputError("material '" + m.name + "': " + key + " " + rule);
        };
        if (!(m.youngs_modulus > 0.0) || !std::isfinite(m.youngs_modulus))
            bad("youngs_modulus", "must be > 0 Pa");
        if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5))
            bad("poisson_ratio", "must be in (-1, 0.5)");
        if (!(m.restitution > 0.0 && m.restitution <= 1.0))
            bad("restitution", "must be in (0, 1]");
        if (!(m.friction >= 0.0) || !std::isfinite(m.friction))
            bad("friction", "must be >= 0");
        if (!(m.rolling_friction >= 0.0) || !std::isfinite(m.rolling_friction))
            bad("rolling_friction", "must be >= 0");
    }
    for (const MaterialPair &p : settings.pairs) {
        const std::string what = "material pair '" + p.a + "'/'" + p.b + "'";
        auto known = [&](const std::string &name) {
            return std::any_of(settings.materials.begin(), settings.materials.end(),
                               [&](const Material &m) { return m.name == name; });
        };
        if (!known(p.a) || !known(p.b))
            throw InputError(what + ": unknown material name");
        if (p.restitution >= 0.0 && !(p.restitution > 0.0 && p.restitution <= 1.0))
            throw InputError(what + ": restitution must be in (0, 1]");
        if (!std::isfinite(p.friction) || !std::isfinite(p.rolling_friction) || !std::isfinite(p.restitution))
            throw InputError(what + ": values must be finite");
    }
}

double pair_value(const EngineSettings &settings, int a, int b, double Material::*field,
                  double MaterialPair::*override_field) {
    const Material &ma = settings.materials.at(a), &mb = settings.materials.at(b);
    for (const MaterialPair &p : settings.pairs)
        if (p.*override_field >= 0.0 &&
            ((p.a == ma.name && p.b == mb.name) || (p.a == mb.name && p.b == ma.name)))
            return p.*override_field;
    return std::min(ma.*field, mb.*field);
}

} // namespace armour
