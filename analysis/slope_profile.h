// The armour layer on a slope as a profiler measures it.
//
// Description
//     Slope coordinates of the scene's first slope wall: s up the face from
//     its toe (m), y across the flume (m), n out of the face (m). The layer's
//     upper envelope is sampled as a flume profiler samples it: a ball foot of
//     diameter 0.5 Dn lowered along -n onto the units' exact shapes at every
//     point of a grid, the envelope being the ball's lowest point where it
//     stops (n = 0 where it reaches the underlayer). A ball of about half a
//     unit is the usual laboratory foot (stability.md): it bridges the narrow
//     gaps between units as a real layer's surface does, but drops into holes
//     a unit could fall into. The grid is cell-centred with a spacing of at
//     most 0.1 Dn (the mean converges well below that; measured: 0.1 and
//     0.05 Dn differ by < 0.2 % of t on the slope_cubes pile).
//
//     The layer's figures follow the Rock Manual (CIRIA/CUR/CETMEF 2007,
//     §3.5): over the covered area A, thickness t = the envelope's mean,
//     packing density φ = N Dn²/A, porosity p = 1 − N V/(A t) and the layer
//     thickness coefficient k_t = t/(n Dn) for a layer meant to be n units
//     thick.
//
// Usage
//     const std::optional<SlopeFrame> frame = slope_frame(scene);
//     const LayerRegion region = layer_region(*frame, setup, states);
//     const ArmourProfile profile = armour_profile(*frame, setup, states, region);
//     const LayerFigures f = layer_figures(setup, states, *frame, region, profile, 2);
#pragma once

#include "scene.h"
#include "scene_setup.h"

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace armour {

struct SlopeFrame {
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();          // the toe of the face, y = 0 (m)
    Eigen::Vector3d along, across, normal;                     // unit vectors
    double length = 0.0;                                       // m, toe to crest along the face
    double width = 0.0;                                        // m, across (y)
    double cot = 1.5;                                          // -
    Eigen::Vector3d local(const Eigen::Vector3d &world) const; // (s, y, n)
    // Whether a point lies seaward of the face's foot (over the toe or the
    // bed in front of it, not over the face): a laboratory that counts the
    // units on the face alone leaves out those whose centres lie there.
    bool seaward_of_foot(const Eigen::Vector3d &world) const;
    // Whether a unit's centre at `world` rests on a double layer `thickness`
    // m thick rather than in it: over the face (not seaward of its foot) and
    // farther out of it than the layer is thick.
    bool rests_on_layer(const Eigen::Vector3d &world, double thickness) const;
};

// The scene's first "slope" wall; nullopt when it has none.
std::optional<SlopeFrame> slope_frame(const Scene &scene);

// The rectangle of the face the layer covers (slope coordinates, m) and the
// bodies on it: centres between the toe (less one Dn) and the crest, in front
// of the face (n > -Dn); the rectangle spans their centres and half the
// largest Dn beyond, within the face.
struct LayerRegion {
    double s_lo = 0.0, s_hi = 0.0, y_lo = 0.0, y_hi = 0.0;
    std::vector<int> bodies; // indices on the slope
    double Dn = 0.0;         // m, the largest unit's among them
    double area() const { return (s_hi - s_lo) * (y_hi - y_lo); }
};
LayerRegion layer_region(const SlopeFrame &frame, const SceneSetup &setup,
                         const std::vector<BodyState> &states);

struct ArmourProfile {
    double s_lo = 0.0, y_lo = 0.0, ds = 0.0, dy = 0.0; // grid point (i, j) at s_lo + (i + 1/2) ds, ...
    int ns = 0, ny = 0;
    std::vector<double> elevation; // m above the face, [i * ny + j]
    double at(int i, int j) const { return elevation[static_cast<std::size_t>(i * ny + j)]; }
    double mean() const;
};

// The envelope over `region` of every body's exact shape (a body anywhere may
// reach over it), ball diameter 0.5 region.Dn, grid spacing <= 0.1 region.Dn.
ArmourProfile armour_profile(const SlopeFrame &frame, const SceneSetup &setup,
                             const std::vector<BodyState> &states, const LayerRegion &region);

// m: the highest n at which a ball of radius `r` whose centre moves along the
// normal through (s, y) touches triangle (a, b, c) (slope coordinates);
// -inf when it never does. Exposed for tests.
double ball_contact_height(double s, double y, double r, const Eigen::Vector3d &a, const Eigen::Vector3d &b,
                           const Eigen::Vector3d &c);

struct LayerFigures {
    int units = 0;                  // on the slope
    double area = 0.0;              // m², A
    double thickness = 0.0;         // m, t
    double packing_density = 0.0;   // -, N Dn²/A
    double porosity = 0.0;          // -, 1 - N V/(A t)
    double layer_coefficient = 0.0; // -, t/(n Dn)
};
LayerFigures layer_figures(const SceneSetup &setup, const LayerRegion &region, const ArmourProfile &profile,
                           int layers);

// The settle criterion: the pile has settled once, for `span` seconds of
// samples, every unit's centre moved slower than `speed` (m/s) and the
// kinetic energy of all units (translation and rotation) stayed below
// `energy` times sum(m g Dn) (the energy of lifting every unit by its size).
class SettleWatch {
  public:
    SettleWatch(const Scene &scene, const SceneSetup &setup);
    void sample(double t, const std::vector<BodyState> &states);
    bool settled() const { return settled_at_.has_value(); }
    std::optional<double> settled_at() const { return settled_at_; } // s: the end of the quiet span
    double max_speed() const { return speed_; }                      // m/s, at the last sample
    double kinetic_energy_ratio() const { return energy_; }          // -, at the last sample

  private:
    const SceneSetup &setup_;
    double speed_limit_, energy_limit_, span_, scale_ = 0.0;
    std::optional<double> quiet_since_, settled_at_;
    double speed_ = 0.0, energy_ = 0.0;
};

// m²: the area between two profiles over the same grid where `after` lies
// below `before` (eroded), each profile first averaged across y (as a flume's
// profile lines are averaged: a unit that shifts across the slope erodes
// nothing). Until 2026-11-26 each line's eroded area was averaged instead,
// which counts such a shift as erosion.
double eroded_area(const ArmourProfile &before, const ArmourProfile &after);

} // namespace armour
