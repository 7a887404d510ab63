// The incident-wave analysis of a wave train's gauges: incident and
// reflected height and period, the wave count and the spectra.
//
// Description
//     measure_incident_waves() reads the gauges' record
//     (postProcessing/gauges/<start>/surfaceElevation.dat, whole across
//     resumes: gauge_rows.h) and separates incident and reflected waves
//     (Mansard-Funke, waves/wave_separation.h) over the analysis window
//     (regular: the last whole periods after the ramp and the front's
//     travel to the last gauge; irregular: the last repeat period of the
//     train when the run holds one). It writes nothing: the damage
//     analysis calls it for the waves it holds its figures against, and a
//     coupled run's driver calls it once more and add_incident_waves() puts
//     the figures into summary["waves"] and writes OUT/waves_spectrum.csv
//     and OUT/waves_spectrum.png (chart: analysis/wave_spectrum_chart.py).
//     The gauges' x come from the case writer (fluid_case/wave_case.h,
//     AnalysisContext::gauge_x): this room never reads the case's files
//     other than the gauges' record.
//
// Usage
//     const IncidentWaves w = measure_incident_waves(scene, gauge_x, case_dir);
//     if (w.figures.contains("incident_height")) ...      // measured
//     add_incident_waves(w, claim, summary);               // summary["waves"], files
#pragma once

#include "scene.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace armour {

struct IncidentWaves {
    // summary["waves"]: the train's targets always; incident_height,
    // incident_period, s_om, reflection_coefficient, waves, ... and each
    // gauge's total Hm0, H_max, H_one_third, H_2_percent (array_gauges,
    // extra_gauges) when the record held a window to analyse (SI).
    nlohmann::json figures;
    std::vector<std::string> warnings; // "waves: ..." (a short record, a repeating train)
    std::string spectrum_csv;          // waves_spectrum.csv's text; "" when nothing was analysed
};

// The gauges at `gauge_x` (m: the case's Mansard-Funke array, then its
// waves.extra_gauges, whose total waves go into figures["extra_gauges"]) in
// `case_dir`, their record up to `until` (s; `armour report --until`).
IncidentWaves measure_incident_waves(const Scene &scene, const std::vector<double> &gauge_x,
                                     const std::filesystem::path &case_dir, double until = HUGE_VAL);

// summary["waves"] = waves.figures, its warnings into summary["warnings"]
// (and stderr), the spectrum and its chart through `claim` (the path of a
// top-level output entry).
void add_incident_waves(const IncidentWaves &waves,
                        const std::function<std::string(const std::string &)> &claim,
                        nlohmann::json &summary);

} // namespace armour
