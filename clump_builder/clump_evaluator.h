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
    double surface_rms = 0.0;      // both directions pooled, fraction of Dn
    double surface_max = 0.0;      // symmetric Hausdorff distance / Dn
    double rest_gap = 0.0;         // RestSummary::gap / Dn: 0 = rests flat, inf = stands on no face
    int rest_faces = 0;            // faces the exact unit rests on
    int tipping_faces = 0;         // of those, faces the clump tips off
    double topple_error_deg = 0.0; // largest |topple angle clump - exact|, degrees (clump_support.h)
    double build_seconds = 0.0;    // s, filled by the caller that timed the build
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

// How flat a clump rests. A clump stands on its spheres, not on the exact
// faces: lowered onto the plane of a face it touches first with the sphere
// that reaches furthest, and it stands still only on spheres whose touching
// points surround its centre of mass. For each face of the exact shape's
// convex hull that the unit can rest on (its centre of mass above the face),
// the spheres are ordered by the gap between their lowest point and the
// plane; the face's rest gap (m) is the height spread among the lowest
// spheres needed before their touching points surround the centre of mass
// with a margin of 1 % of Dn; infinite when no set of spheres does (a single
// sphere rolls). A clump whose gap on a face exceeds the contact overlap
// under its weight stands there on two spheres and rocks about the line
// through them (docs/clump_builder.md). `centre_of_mass` in the mesh frame.
struct FaceRest {
    Eigen::Vector3d normal; // outward unit normal of the face, mesh frame
    double support;         // m, the centre of mass's distance inside the face's edges
    double gap;             // m
};
std::vector<FaceRest> rest_gaps(const TriangleMesh &mesh, const Eigen::Vector3d &centre_of_mass,
                                const Clump &clump, double Dn);
// A gap above this fraction of Dn is not rocking: closing it tilts the clump
// by ~10 degrees or more, so it tips off that face onto another.
constexpr double kTippingGap = 0.1;
struct RestSummary {
    double gap = 0.0;      // m, the largest gap over the faces the clump stands on (inf: none)
    int faces = 0;         // faces the exact unit rests on
    int tipping_faces = 0; // of those, faces the clump tips off (gap > kTippingGap Dn)
};
RestSummary rest_summary(const TriangleMesh &mesh, const Eigen::Vector3d &centre_of_mass, const Clump &clump,
                         double Dn);

// Tolerance mode: the fewest spheres whose clump meets all three tolerances.
// The defaults are the `armour clump` defaults (docs/clump_builder.md).
struct ClumpTolerances {
    double volume = 0.01;      // |V_clump - V| / V
    double surface_rms = 0.02; // surface RMS / Dn
    double topple_deg = 1.0;   // largest |topple angle error|, degrees
};
bool meets(const ClumpQuality &quality, const ClumpTolerances &tolerances);
// The tolerances allowed, one rule for `armour clump`, `armour demo` and
// fewest_spheres: volume and surface fractions in (0, 1), topple in (0, 90)
// degrees (a topple angle itself lies in [0, 90)). Throws InputError naming
// --tol-volume, --tol-surface or --tol-topple, the options that set them.
void check_tolerances(const ClumpTolerances &tolerances);
struct ToleranceSearch {
    Clump clump; // the chosen clump (or the best tried)
    ClumpQuality quality;
    bool met = false; // false if max_spheres cannot meet them
    std::vector<ClumpQuality> tried;
};
// `progress` is called after each sphere count tried (for long searches).
ToleranceSearch fewest_spheres(const Shape &shape, ClumpMethod method, const ClumpTolerances &tolerances,
                               int max_spheres, std::uint64_t seed = 1,
                               const std::function<void(const ClumpQuality &)> &progress = {});

} // namespace armour
