// Damage to an armour layer, counted as coastal engineers count it.
//
// Description
//     The `damage` analysis kind (any scene with units on a slope wall, dry or
//     coupled). Every unit is watched from its settled pose: the first record
//     of a coupled run (which starts from settled poses), or in a dry run the
//     poses at which the pile first met the settle criterion
//     (slope_profile.h; the first record when it never did). Per unit: the
//     largest and final displacement of its centre (in Dn), the largest
//     rotation (deg) and the rocking events: turns from the unit's seat (its
//     settled pose, or where it last came to rest) past
//     analysis.rocking_threshold_deg that come back below half of it (a
//     choice: no published threshold exists, stability.md). Headline figures
//     (docs/analysis.md): units displaced (final displacement >=
//     analysis.displaced_threshold Dn, 1 Dn as in physical-model practice),
//     N_od = displaced / (layer width / Dn), rocking units, Ns = Hs/(Δ Dn) with
//     Δ = ρs/ρw − 1, s_om, the number of waves, the damage S = eroded area /
//     Dn² between the before and after profiles (slope_profile.h), and where
//     the run sits against Van der Meer (1988, double-layer cubes) and
//     Hudson (K_D 6.5 and 7.5).
//
//     The wave figures come from WaveConditions: measured ones when the run
//     has a wave train's gauges (incident_waves.h: incident_height, s_om,
//     waves), else analysis.wave_height (analysis.wave_period for s_om
//     and N), else the [waves] train's target, else fluid.wave_height; a
//     figure with no source is null. `damage.waves` is the N the figures
//     used, whatever its source.
//
// Usage
//     UnitDamageTracker unit(reference_pose, Dn, 5.0, rest_time(scene));
//     unit.sample(t, pose);                         // every recorded step
//     double ns = van_der_meer_cubes_ns(0.5, 1000, 0.03); // 2.33
//     double n_od = van_der_meer_cubes_n_od(2.33, 1000, 0.03); // 0.5
#pragma once

#include "rigid_body_engine.h"
#include "scene.h"
#include "slope_profile.h"

#include <nlohmann/json_fwd.hpp>

#include <cmath>
#include <optional>
#include <string>

namespace armour {

// One unit's motion from its reference pose. Displacement and rotation are
// measured from the reference; rocking from the unit's seat: the reference,
// or where it last rested (stayed within a tenth of the threshold and 0.02 Dn
// of one pose for rest_time, over at least kRestSamples records no more than
// rest_time / kRestSamples apart: a coarser record never rests). A rocking
// event is a turn from the seat past the threshold that comes back below half
// of it; a unit that comes to rest tilted has moved to a new seat, not rocked.
class UnitDamageTracker {
  public:
    static constexpr int kRestSamples = 4;
    UnitDamageTracker(const Pose &reference, double Dn, double rocking_threshold_deg, double rest_time);
    void sample(double t, const Pose &pose);                      // t in s, increasing
    double displacement() const { return displacement_; }         // Dn, now
    double max_displacement() const { return max_displacement_; } // Dn
    double max_rotation_deg() const { return max_rotation_; }
    double Dn() const { return Dn_; } // m
    int rocking_events() const { return rocking_events_; }
    double largest_record_gap() const { return largest_gap_; } // s, between samples
    const Pose &reference() const { return reference_; }

  private:
    Pose reference_, seat_, still_at_;
    double Dn_, threshold_, rest_time_;
    double still_since_ = std::nan(""); // s, set by the first sample
    double last_t_ = std::nan("");      // s, the previous sample
    double largest_gap_ = 0.0;          // s
    int still_samples_ = 0;
    double displacement_ = 0.0, max_displacement_ = 0.0, max_rotation_ = 0.0;
    bool turned_ = false;
    int rocking_events_ = 0;
};

// s: how long a unit stays put to have a new seat: a wave period (the scene's
// [waves] T or Tp, else analysis.wave_period), so a unit rocking once a wave
// never rests at the far end of its swing; at least 2 s.
double rest_time(const Scene &scene);

// deg: the angle of the rotation taking orientation a to b.
double rotation_between_deg(const Eigen::Quaterniond &a, const Eigen::Quaterniond &b);

// N_od: units displaced per strip of width Dn across the layer (layer_width m).
double n_od(int displaced, double layer_width, double Dn);
// m: the width of N_od's strips across the slope for the layer on `region`.
double layer_width(const SlopeFrame &frame, const LayerRegion &region);
// Ns = Hs / (Δ Dn), Δ = ρs/ρw − 1.
double stability_number(double Hs, double unit_density, double water_density, double Dn);
// Van der Meer (1988), double-layer cubes: Ns = (6.7 N_od^0.4 / N^0.3 + 1.0) s_om^−0.1.
double van_der_meer_cubes_ns(double N_od, double waves, double s_om);
// The same curve solved for N_od: the damage it predicts at Ns (0 below its
// floor Ns = s_om^-0.1).
double van_der_meer_cubes_n_od(double Ns, double waves, double s_om);
// Hudson: H/(Δ Dn) = (K_D cot α)^(1/3).
double hudson_ns(double K_D, double cot);

// The waves a damage figure is held against (SI; unset = unknown).
struct WaveConditions {
    std::optional<double> Hs;    // m, the incident Hm0 (H of a regular or solitary wave)
    std::optional<double> s_om;  // -, 2 pi Hs / (g Tm^2)
    std::optional<double> waves; // -, N
    std::string source;          // "measured" | "scene" | "target" | "none"
};

// From the incident-wave analysis' figures (incident_waves.h) when they hold
// a measured incident_height ("measured"), else
// analysis.wave_height and wave_period ("scene"), else the [waves] train's
// target at the maker ("target": H and T, or Hs and the Tm0,2 of its
// JONSWAP components), else fluid.wave_height ("scene"); `duration` s of
// waves at the structure give N (acting_seconds).
WaveConditions wave_conditions(const nlohmann::json &measured, const Scene &scene, double duration);

// s: how long the waves have acted on a structure whose toe is at toe_x (m)
// over a record from `start` to `end` (s): from the front's arrival at the
// toe (the wave maker's train at the group velocity of T or Tp over the
// still-water depth), or from `start` when there is no [waves] train.
double acting_seconds(const Scene &scene, double toe_x, double start, double end);

// s: when the front of the scene's [waves] train reaches a toe at toe_x (m),
// as acting_seconds counts it; none without a train (or for a solitary wave).
std::optional<double> wave_front_arrival(const Scene &scene, double toe_x);

} // namespace armour
