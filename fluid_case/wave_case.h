// Regular and irregular waves of a scene's [waves] in a wave template
// (foam_cases/wave_flume): what the case needs to make them and where its
// gauges stand.
//
// Description
//     Before the case runs, wave_tokens() writes what the template needs:
//     OpenFOAM's stock generation model (StokesII, StokesV, cnoidal,
//     irregularMultiDirectional with our JONSWAP components) and absorbing
//     outlet (shallowWaterAbsorption) into constant/waveProperties, the
//     outlet's velocity condition, the three gauges of the Mansard-Funke
//     array and waves.extra_gauges at cell centres, and the side patches
//     (2D or walled). A template with a wave maker needs [waves] regular or
//     irregular, and such waves need such a template: either mismatch is an
//     InputError naming the key.
//
//     After the run, the incident-wave analysis (analysis/incident_waves.h)
//     reads the gauges at wave_gauge_positions().
//
// Usage
//     wave_tokens(scene, template_text, tokens);                   // before fill_tokens
//     context.gauge_x = wave_gauge_positions(scene);               // for the analyses
#pragma once

#include "scene.h"

#include <map>
#include <string>
#include <vector>

namespace armour {

// True when the scene makes regular or irregular waves.
bool makes_wave_train(const Scene &scene);

void wave_tokens(const Scene &scene, const std::string &template_text,
                 std::map<std::string, std::string> &tokens);

// m: x of the Mansard-Funke array (x, x + L/10, x + L/4 from waves.gauge_x),
// then of waves.extra_gauges, each at the centre of its column of cells;
// empty when the scene makes no wave train.
std::vector<double> wave_gauge_positions(const Scene &scene);

} // namespace armour
