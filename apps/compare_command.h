// `armour compare SCENE --spheres 5,10,20 --out DIR`: clumps against exact shapes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace armour {

struct CompareRequest {
    std::string scene;
    std::string out;
    std::vector<int> spheres{5, 10, 20, 50, 100};
    std::vector<std::uint64_t> seeds; // empty: {1, 2, 3} when the scene drops units at random, else {1}
    std::vector<double> dt_factors{0.5, 1.0, 2.0,
                                   4.0, 8.0, 16.0}; // x the stability limit; empty = no dt sweep
    int dt_sweep_spheres = 0;                       // 0: the --spheres count nearest 20
    std::string tolerance;              // --tolerance "key=value,...": advice tolerances (figure's own unit)
    double blow_up_gain = 0.1;          // energy gain (E_max - E_0) / sum(m g Dn) above which a run failed
    std::vector<std::string> overrides; // --set, applied to every run
    std::string cache;
    bool dry_run = false; // check and list the runs; run nothing, write nothing
};

int run_compare(const CompareRequest &request);

} // namespace armour
