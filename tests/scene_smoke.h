// How the smoke shortens each shipped scene (test_scene_smoke) and the one
// tiny case of each shipped study (test_sweep): --set overrides of the
// scene as shipped, keyed by its file name in scenes/.
//
// The shortening (~3 min for all scenes on the shared 2-core machine):
// - dry scenes run until their analysis has its figure (the first rebound,
//   the slide, the pile on the face);
// - coupled scenes run 0.05 s, 8-13 interFoam steps (0.1 s, 5 steps, for the
//   flume at its 0.02 s step): the case is meshed, the bodies masked, loads
//   and poses exchanged and the analysis fed, which is what the smoke checks;
// - a settle (fluid.settle_time) runs as shipped where it costs seconds
//   (armour_slope_waves 1 s, bench_tank_cubes 3 s); stability_cubes' 2.5 s
//   settle of 99 clumps costs ~4-10 min here, so it settles 0.1 s (the settle
//   still runs and hands its poses to the coupled run; test_stability runs
//   the whole settle). Its layer is laid as a grid: each unit starts in its
//   slot 2 mm off its seat, so at any instant of a short settle the pile is
//   inside the domain and apart. The random layer falls from above the
//   domain: cut at 0.05-0.2 s (measured: 47- and 118-sphere clumps) it was
//   handed over with units above the domain or overlapping at most instants,
//   so the smoke would pass or fail by where the fall was when it stopped.
//   The grid is laid in one piece (fluid.settle_stages = 1): the scene's
//   stages are for random placement.
#pragma once

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace armour_test {

struct Smoke {
    std::vector<std::string> sets; // --set KEY=VALUE, as the shell would pass them
    // Headline figures the analysis leaves null in this run, and why.
    std::vector<std::string> null_figures = {};
    std::string why_null = "";
};

// Keyed by the scene's file name. Every row shortens run.duration.
inline const std::map<std::string, Smoke> kSmoke = {
    {"armour_slope_waves.toml", {{"run.duration=0.05"}}}, // settle 1 s as shipped
    {"bench_tank_cubes.toml", {{"run.duration=0.05"}}},   // settle 3 s as shipped
    {"buoyancy_cube.toml", {{"run.duration=0.05"}}},
    {"dambreak_two_cubes.toml", {{"run.duration=0.05"}}},
    {"drop_bounce.toml", {{"run.duration=0.6"}}}, // lands at 0.32 s, its first rebound over by 0.4 s
    {"floating_box.toml", {{"run.duration=0.05"}}},
    {"floating_cube.toml", {{"run.duration=0.05"}}},
    {"released_cube.toml", {{"run.duration=0.05"}}},
    {"slope_cubes.toml", {{"run.duration=0.6"}}},   // the first units land on the face at ~0.3 s
    {"slope_dolosse.toml", {{"run.duration=0.6"}}}, // the same
    {"solitary_cubes_platform.toml", {{"run.duration=0.05"}}},
    {"stability_cubes.toml", // a grid's layer settles in one piece (stages are for random placement)
     {{"run.duration=0.05", "fluid.settle_time=0.1", "pattern.0.placement=grid", "fluid.settle_stages=1"}}},
    {"still_water_cube.toml", {{"run.duration=0.05"}}},
    {"tilt_cube.toml",
     {{"run.duration=6"}, // slides at atan(0.5) = 26.6 deg, 5.3 s at 5 deg/s
      {"topple_angle_deg"},
      "a cube at friction 0.5 slides (26.6 deg) long before it could topple (45 deg)"}},
    {"tilt_cube_pair.toml", {{"run.duration=6.0"}}}, // slides at 27.4 deg (5.5 s), tips off its neighbour
                                                     // at 28.5 deg; ends at 6.05 s
    {"wave_flume.toml", {{"run.duration=0.1"}}},
    {"wave_load_cube.toml", {{"run.duration=0.05"}}},
};

// --set options as the shell reads them.
inline std::string shell_sets(const Smoke &smoke) {
    std::string sets;
    for (const auto &s : smoke.sets)
        sets += "--set '" + s + "' ";
    return sets;
}

// The smoke's own duration: the last run.duration it sets.
inline double smoke_duration(const Smoke &smoke) {
    double duration = NAN;
    for (const auto &s : smoke.sets)
        if (s.rfind("run.duration=", 0) == 0)
            duration = std::stod(s.substr(s.find('=') + 1));
    return duration;
}

} // namespace armour_test
