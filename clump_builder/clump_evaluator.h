// Independent measure of how well a clump represents its exact shape.
//
// Description
//     Dense sampling that shares nothing with the optimiser's objective:
//     union volume and inertia by exact chord integration, surface deviation
//     from tens of thousands of points on both surfaces (exact -> clump and
//     clump -> exact). All lengths are reported as fractions of Dn = V^(1/3);
//     volume and inertia errors are relative (signed for volume).
#pragma once

#include "clump.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace armour {

struct SurfaceDeviation {
    double mean = 0.0; // fraction of Dn
    double rms = 0.0;  // fraction of Dn
    double max = 0.0;  // fraction of Dn
};

struct ClumpQuality {
    int spheres = 0;
    double Dn = 0.0;              // m
    double volume_exact = 0.0;    // m^3
    double volume_clump = 0.0;    // m^3
    double volume_error = 0.0;    // (V_clump - V_exact) / V_exact
    double centroid_offset = 0.0; // |c_clump - c_exact| / Dn
    double inertia_error = 0.0;   // max over exact principal axes |dI| / I_exact
    SurfaceDeviation exact_to_clump;
    SurfaceDeviation clump_to_exact;
    double surface_rms = 0.0;   // both directions pooled, fraction of Dn
    double surface_max = 0.0;   // symmetric Hausdorff distance / Dn
    double build_seconds = 0.0; // s, filled by the caller that timed the build
};

struct EvaluatorSettings {
    int surface_samples = 40000; // points on each surface
    int integration_lines = 400; // chord grid is lines x lines
    std::uint64_t seed = 12345;  // different from any builder seed
};

// Distance (m) from each point to the boundary of the union of spheres: exact
// outside the union and at exposed radial projections, otherwise bounded by
// `boundary_samples` points spread over the union's boundary.
std::vector<double> distances_to_clump_surface(const Clump &clump, const std::vector<Eigen::Vector3d> &points,
                                               int boundary_samples = 40000, std::uint64_t seed = 12345);

ClumpQuality evaluate_clump(const Shape &shape, const Clump &clump, const EvaluatorSettings &settings = {});

// Tolerance mode: the fewest spheres whose clump meets both tolerances.
struct ToleranceSearch {
    Clump clump; // the chosen clump (or the best tried)
    ClumpQuality quality;
    bool met = false; // false if max_spheres cannot meet them
    std::vector<ClumpQuality> tried;
};
// `progress` is called after each sphere count tried (for long searches).
ToleranceSearch fewest_spheres(const Shape &shape, ClumpMethod method, double tol_volume,
                               double tol_surface_rms, int max_spheres, std::uint64_t seed = 1,
                               const std::function<void(const ClumpQuality &)> &progress = {});

} // namespace armour
