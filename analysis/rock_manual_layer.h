// The settled layer against the packing and porosity a random double layer
// of cubes is built to (docs/stability.md, "The settled layer").
//
// Description
//     The Rock Manual (CIRIA/CUR/CETMEF 2007, §3.5) gives a randomly placed
//     double layer of cubes k_t 1.10, porosity 0.47 and packing density
//     φ = n k_t (1 − p) = 1.17 units per Dn². A layer below 35 % porosity
//     cannot be built with cranes and is more stable than a buildable one
//     (Medina, Molines & Gómez-Martín 2014, Ocean Eng. 88:289-297), so a
//     settle that packs it that densely measures a layer no laboratory
//     tests. The band: porosity 0.35 to 0.55 (the lower end Medina et al.'s;
//     the upper one our choice, as far above the Rock Manual's 0.47 as a
//     loose pile settles: a layer looser than that holds less than the
//     formula's), packing 1.17 ± 15 % (the band the project's own settled
//     layers are tested in). Only cubes in a double layer
//     (analysis.layers = 2) have a band; other layers are not judged.
//
// Usage
//     const LayerVerdict v = rock_manual_verdict(scene, setup, figures);
//     if (v.judged && v.outside) warn(v.reason);
//     summary["settled_layer"] = settled_layer_record(scene, setup, states);
#pragma once

#include "rigid_body_engine.h"
#include "scene.h"
#include "scene_setup.h"
#include "slope_profile.h"

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace armour {

struct RockManualBand {
    double porosity_min = 0.35, porosity_max = 0.55;             // -
    double packing_min = 0.85 * 1.17, packing_max = 1.15 * 1.17; // units per Dn²
};

struct LayerVerdict {
    bool judged = false;  // a band applies (cubes in a double layer)
    bool outside = false; // the layer lies outside it
    std::string reason;   // what lies outside, with the figures ("" inside)
    RockManualBand band;
};

LayerVerdict rock_manual_verdict(const Scene &scene, const SceneSetup &setup, const LayerFigures &layer);
// The one-line warning for a layer outside the band ("" inside, or not judged).
std::string rock_manual_warning(const LayerVerdict &verdict);

// The layer of the bodies at `states` on the scene's first slope wall,
// measured as the damage analysis measures the layer the waves meet, and
// held against the band: rock_manual_warning.
std::string settled_layer_warning(const Scene &scene, const SceneSetup &setup,
                                  const std::vector<BodyState> &states);

// A layer's figures and verdict as summary.json records them (its
// "settled_layer"): units_on_slope, packing_density (units per Dn^2),
// porosity, layer_thickness (m), layer_coefficient, outside_rock_manual
// (null when not judged), outside_reason and rock_manual_band.
nlohmann::json layer_record(const LayerFigures &layer, const LayerVerdict &verdict);
// The record of the layer the bodies at `states` form on the scene's first
// slope wall (as the damage analysis measures the layer the waves meet),
// with the units in all, those whose centres lie seaward of the face's foot
// (units_at_foot) and those on the face whose centres lie farther out of it
// than the layer is thick (units_on_top: resting on the double layer, not in
// it); null without a slope wall or units on its face.
nlohmann::json settled_layer_record(const Scene &scene, const SceneSetup &setup,
                                    const std::vector<BodyState> &states);

} // namespace armour
