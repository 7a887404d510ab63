// `armour report RUN --out DIR [--until T] [--from T0]`: a coupled run's figures as its record stands.
//
// Description
//     A stability test on the scene's own mesh runs for days (docs/stability.md:
//     ~135 wall s per wave), and a run writes its summary only when it ends. The
//     report reads an `armour run` folder of a scene with [fluid] as it is on
//     disk (ended, stopped after a checkpoint, killed, or still running: the
//     record is read without a lock and ends at its last whole step) and runs
//     what the run runs at its end on the record up to its last step, or up to
//     `until`: the scene's analysis (damage: damage.csv, damage_history.csv,
//     damage.png, N_od against Van der Meer at the waves so far) and, for
//     regular or irregular waves, the incident-wave figures from the gauges.
//     DIR gets summary.json (the run's keys for those figures, plus what was
//     read: `simulated_seconds`, `records`, `until`, `run_ended`) and the
//     analysis' files, staged: it appears whole or not at all. The run's
//     folder is only read.
//
//     `from` takes the units' poses at the first record at or after T0 as the
//     damage's reference instead of the run's first record: the layer as it
//     lies when the waves come, as a laboratory profiles it before a test
//     (units that re-seat or fall in the still water before any wave are
//     then not counted). T0 is refused past the moment the wave train's front
//     reaches the toe, so the waves counted for Van der Meer's prediction are
//     the waves the reference met.
//
//     A report of an ended run without `until` repeats the run's own figures
//     (tests/test_stability.cpp). A DEM run (no [fluid]) is refused: its
//     analysis samples the engine as it runs, not the record.
//
// Usage
//     armour report runs/stability --out runs/stability-report              # as the record stands
//     armour report runs/stability --out runs/report-100s --until 100        # the figures at t = 100 s
//     armour report runs/stability --out runs/report-from --from 0.8         # from the layer at 0.8 s
#pragma once

#include "output_folder.h"

#include <nlohmann/json_fwd.hpp>

#include <cmath>
#include <filesystem>
#include <string>

namespace armour {

struct Scene;
struct SceneSetup;
struct BodiesFile;

struct ReportRequest {
    std::string run;         // an `armour run` folder
    std::string out;         // the report's folder
    std::string cache;       // clump cache folder; empty = default
    double until = HUGE_VAL; // s: the record up to this time
    double from = -HUGE_VAL; // s: the damage's reference, the first record at or after this time
};

// Returns the exit status; throws InputError, naming the folder or file and
// the reason, before anything is written.
int run_report(const ReportRequest &request);

// What a coupled run computes from its record after the solver, shared by
// `armour run` and `armour report`: the wave figures from the gauges in
// `case_dir` (wave trains: analysis/incident_waves.h), then the scene's
// analysis sampling `record` from `from` up to `until` (s), into `summary`; files
// through `folder`. `run_dir` holds
// the plugin's fluid.csv. Returns the analysis' one-line result.
std::string analyse_coupled_record(const Scene &scene, const SceneSetup &setup, const BodiesFile &record,
                                   const std::filesystem::path &run_dir,
                                   const std::filesystem::path &case_dir, OutputFolder &folder,
                                   nlohmann::json &summary, double until = HUGE_VAL, double from = -HUGE_VAL);

} // namespace armour
