// `armour clump` and `armour demo`: what the command line asked for, and running it.
#pragma once

#include <cstdint>
#include <string>

namespace armour {

struct ClumpRequest {
    std::string shape;         // "cube" or "dolos"; empty with --stl
    std::string stl;           // path of a closed STL (m)
    double size = 0.0;         // cube edge, m
    double chamfer = 0.0;      // cube edge chamfer, m
    double height = 0.0;       // dolos height, m
    double waist = 0.33;       // dolos waist ratio, -
    bool waist_given = false;  // --waist given (a cube refuses it)
    double density = 2400.0;   // kg/m^3
    bool fixed_count = false;  // --spheres given; else tolerance mode
    int spheres = 0;           // with fixed_count
    int edge_spheres = 0;      // support spheres per resting-face edge, of `spheres`
    double tol_volume = 0.01;  // |V_clump - V| / V
    double tol_surface = 0.02; // surface RMS / Dn
    double tol_topple = 1.0;   // topple angle error, degrees
    int max_spheres = 200;
    std::string method = "optimised";
    std::uint64_t seed = 1;
    std::string out;
};

struct DemoRequest {
    std::string out = "armour-demo";
    double tol_volume = 0.01;
    double tol_surface = 0.02;
    double tol_topple = 1.0; // degrees
};

// Both return the process exit status (see cli.h) and throw InputError on bad input.
int run_clump(const ClumpRequest &request);
int run_demo(const DemoRequest &request);

} // namespace armour
