// Regular and irregular waves of a scene's [waves] in a wave template
// (foam_cases/wave_flume), and the incident-wave analysis of its gauges.
//
// Description
//     Before the case runs, wave_tokens() writes what the template needs:
//     OpenFOAM's stock generation model (StokesII, StokesV, cnoidal,
//     irregularMultiDirectional with our JONSWAP components) and absorbing
//     outlet (shallowWaterAbsorption) into constant/waveProperties, the
//     outlet's velocity condition, the three gauges of the Mansard-Funke
//     array at cell centres, and the side patches (2D or walled). A template
//     with a wave maker needs [waves] regular or irregular, and such waves
//     need such a template: either mismatch is an InputError naming the key.
//
//     After the run, add_wave_summary() reads the gauges
//     (postProcessing/gauges/<start>/surfaceElevation.dat, whole across
//     resumes: gauge_rows.h), separates incident and reflected waves
//     over the analysis window (regular: the last whole periods after the
//     ramp and the front's travel to the last gauge;
//     irregular: the last repeat period of the train when the run holds
//     one), adds summary["waves"] and writes OUT/waves_spectrum.csv and
//     OUT/waves_spectrum.png (chart: analysis/wave_spectrum_chart.py).
//
// Usage
//     wave_tokens(scene, template_text, tokens);                   // before fill_tokens
//     add_wave_summary(scene, case_dir, folder, summary);          // after interFoam
#pragma once

#include "output_folder.h"
#include "scene.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

namespace armour {

// True when the scene makes regular or irregular waves.
bool makes_wave_train(const Scene &scene);

void wave_tokens(const Scene &scene, const std::string &template_text,
                 std::map<std::string, std::string> &tokens);

// The gauges' record up to `until` (s; `armour report --until`), warnings
// into summary["warnings"].
void add_wave_summary(const Scene &scene, const std::filesystem::path &case_dir, OutputFolder &folder,
                      nlohmann::json &summary, double until = HUGE_VAL);

} // namespace armour
