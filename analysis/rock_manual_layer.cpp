#include "rock_manual_layer.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>

namespace armour {

namespace {

std::string figure(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", v);
    return text;
}

} // namespace

LayerVerdict rock_manual_verdict(const Scene &scene, const SceneSetup &setup, const LayerFigures &layer) {
    LayerVerdict v;
    bool cubes = !setup.bodies.empty() && scene.layers == 2;
    for (const BodyInit &b : setup.bodies)
        cubes = cubes && scene.units[static_cast<std::size_t>(b.unit)].shape == "cube";
    if (!cubes || layer.units == 0)
        return v;
    v.judged = true;
    const RockManualBand &band = v.band;
    const auto add = [&](const std::string &text) { v.reason += (v.reason.empty() ? "" : "; ") + text; };
    if (layer.porosity < band.porosity_min)
        add("porosity " + figure(layer.porosity) + " < " + figure(band.porosity_min) +
            " (a random cube layer that dense cannot be built and overstates stability: Medina et al. 2014)");
    if (layer.porosity > band.porosity_max)
        add("porosity " + figure(layer.porosity) + " > " + figure(band.porosity_max) +
            " (looser than built)");
    if (layer.packing_density < band.packing_min || layer.packing_density > band.packing_max)
        add("packing " + figure(layer.packing_density) + " units/Dn^2 outside " + figure(band.packing_min) +
            " .. " + figure(band.packing_max));
    v.outside = !v.reason.empty();
    return v;
}

namespace {

// The figures of the layer the bodies at `states` form on the scene's first
// slope wall; none without a slope wall or units on its face.
std::optional<LayerFigures> layer_on_slope(const Scene &scene, const SceneSetup &setup,
                                           const std::vector<BodyState> &states) {
    const std::optional<SlopeFrame> frame = slope_frame(scene);
    if (!frame || states.empty())
        return std::nullopt;
    const LayerRegion region = layer_region(*frame, setup, states);
    if (region.bodies.empty())
        return std::nullopt;
    const ArmourProfile profile = armour_profile(*frame, setup, states, region);
    return layer_figures(setup, region, profile, scene.layers);
}

} // namespace

std::string settled_layer_warning(const Scene &scene, const SceneSetup &setup,
                                  const std::vector<BodyState> &states) {
    const std::optional<LayerFigures> layer = layer_on_slope(scene, setup, states);
    return layer ? rock_manual_warning(rock_manual_verdict(scene, setup, *layer)) : "";
}

nlohmann::json layer_record(const LayerFigures &f, const LayerVerdict &v) {
    using nlohmann::json;
    return {{"units_on_slope", f.units},
            {"packing_density", f.packing_density},
            {"porosity", f.porosity},
            {"layer_thickness", f.thickness},
            {"layer_coefficient", f.layer_coefficient},
            {"outside_rock_manual", v.judged ? json(v.outside) : json(nullptr)},
            {"outside_reason", v.outside ? json(v.reason) : json(nullptr)},
            {"rock_manual_band",
             {{"porosity", {v.band.porosity_min, v.band.porosity_max}},
              {"packing_density", {v.band.packing_min, v.band.packing_max}}}}};
}

nlohmann::json settled_layer_record(const Scene &scene, const SceneSetup &setup,
                                    const std::vector<BodyState> &states) {
    const std::optional<LayerFigures> layer = layer_on_slope(scene, setup, states);
    if (!layer)
        return nullptr;
    nlohmann::json record = layer_record(*layer, rock_manual_verdict(scene, setup, *layer));
    const SlopeFrame frame = *slope_frame(scene);
    record["units_at_foot"] = std::count_if(states.begin(), states.end(), [&](const BodyState &s) {
        return frame.seaward_of_foot(s.pose.position);
    });
    record["units_on_top"] = std::count_if(states.begin(), states.end(), [&](const BodyState &s) {
        return frame.rests_on_layer(s.pose.position, layer->thickness);
    });
    record["units"] = states.size();
    return record;
}

std::string rock_manual_warning(const LayerVerdict &v) {
    if (!v.outside)
        return "";
    return "the layer the waves meet is outside the Rock Manual's random double layer of cubes (porosity "
           "0.47, 1.17 units/Dn^2; band porosity " +
           figure(v.band.porosity_min) + " .. " + figure(v.band.porosity_max) + "): " + v.reason +
           "; its damage is not that of a layer a laboratory builds (docs/stability.md)";
}

} // namespace armour
