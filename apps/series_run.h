// `armour run` of a scene with [[series]]: a test series, sea states run one
// after another on one layer (docs/stability.md, "Test series").
//
// Description
//     A laboratory stills the flume between the sea states of a test series
//     and does not rebuild the layer. So each step is its own coupled run
//     (run_coupled, an `armour run` result in OUT/series/<k>/, k = 1..) of
//     the scene with [waves] given the step's Hs, Tp, gamma, seed and ramp,
//     run.duration its length, from still water, with the units at rest
//     where the step before left them (step 1: where the settle left them,
//     OUT/settle, settled once). Everything is checked before anything runs:
//     every step's waves and case (check_coupled_scene), refused naming the
//     step's key.
//
//     OUT/summary.json keeps the top-level damage keys of a run, for the
//     whole series (measured from the series' start, the settled layer, to
//     the end of the last step; Ns and s_om the last step's, `waves` every
//     step's N; N_od_van_der_meer the cumulative prediction), and adds
//     `series`: per step its target, incident height, N, Ns, s_om, its own
//     damage (N_od, damage_S, rocking_units: from its own start) and the
//     cumulative damage (N_od_total, damage_S_total, rocking_units_total) with
//     Van der Meer's cumulative prediction (N_od_van_der_meer, by his
//     equivalent number of waves: series_damage.h). damage.csv,
//     damage_history.csv and damage.png are the whole series'.
//
//     --resume: a step with its summary.json is never run again; the step in
//     progress goes on from its last checkpoint (started again when it has
//     none); the steps after it run. The settle is not run again.
//
// Usage
//     if (!scene.series.empty()) return run_series(request, scene);
#pragma once

#include "run_command.h"
#include "scene.h"

namespace armour {

// Returns the exit status; throws InputError (nothing written when thrown
// before the first step starts). `request.dry_run`: the checks and the plan.
int run_series(const RunRequest &request, const Scene &scene);

// The scene of step `k` (0-based) of a series scene `start` (its units at
// their start: placed, or settled): [waves] with the step's train,
// run.duration its length, no [[series]]; `bodies`, when given, replace
// its units (at rest).
Scene series_step_scene(const Scene &start, std::size_t k, const std::vector<SceneBody> *bodies = nullptr);

} // namespace armour
