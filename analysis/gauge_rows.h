// The wave gauges' record of a coupled run, whole across its resumes.
//
// Description
//     The armourWaveGauges function object writes
//     postProcessing/gauges/<start time>/surfaceElevation.dat: one row per
//     fluid step, time (s) then the surface's z (m) at each gauge. A resumed
//     run starts a new folder at its checkpoint's time, and the killed run's
//     file holds rows past it that the resume computes again; those are
//     dropped, so the rows run once through the whole run in time order.
//
// Usage
//     for (const std::vector<double> &row : armour::gauge_rows(case_dir))
//         use(row[0], row[1]); // t (s), z at the first gauge (m)
#pragma once

#include <filesystem>
#include <vector>

namespace armour {

std::vector<std::vector<double>> gauge_rows(const std::filesystem::path &case_dir);

} // namespace armour
