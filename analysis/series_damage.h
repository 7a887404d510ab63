// Damage over a test series: sea states run one after another on one layer
// (docs/stability.md, "Test series").
//
// Description
//     Van der Meer's cumulative prediction for a sequence of sea states (Van
//     der Meer 1988, "Rock slopes and gravel beaches under wave attack", PhD
//     thesis, Delft University of Technology; CIRIA/CUR/CETMEF 2007, The Rock
//     Manual §5.2.2.2, for S), applied to N_od with his cube formula: the
//     damage reached after step k-1 is the damage that step k's sea state
//     (its Ns and s_om) makes in some number of waves, N_eq; the prediction
//     after step k is the formula at step k's Ns and s_om for N_eq + N_k
//     waves. A step below the formula's floor (Ns s_om^0.1 <= 1) adds no
//     damage; damage never shrinks (a lower step's N_eq is larger). A step
//     whose Ns, s_om or N is unknown leaves the prediction unknown from
//     there on.
//
//     CumulativeDamage watches the whole series' record (every step's
//     records one after another, the first being the series' start: the
//     settled layer) and gives, at any record, the damage against the
//     series' start as the damage analysis counts it (damage_analysis.h):
//     units displaced by at least analysis.displaced_threshold Dn, N_od,
//     units that rocked at least once, S.
//
// Usage
//     const std::vector<SequencePrediction> p = van_der_meer_cubes_sequence({{2.0, 0.03, 500}, ...});
//     CumulativeDamage d(scene, setup);
//     d.sample(t, states);                  // every record of every step, in order
//     const CumulativeFigures now = d.figures();
#pragma once

#include "damage_analysis.h"
#include "scene.h"
#include "scene_setup.h"
#include "slope_profile.h"

#include <optional>
#include <vector>

namespace armour {

struct SeaStateFigures {
    std::optional<double> Ns;    // -, Hs/(Δ Dn)
    std::optional<double> s_om;  // -
    std::optional<double> waves; // -, N of the step
};

struct SequencePrediction {
    std::optional<double> N_od; // -, cumulative after the step
    std::optional<double>
        equivalent_waves; // -, N_eq: waves at the step's sea state that make the damage before it
};

std::vector<SequencePrediction> van_der_meer_cubes_sequence(const std::vector<SeaStateFigures> &steps);

struct CumulativeFigures {
    int displaced = 0;       // units
    double N_od = 0.0;       // -
    int rocking_units = 0;   // units that rocked at least once
    std::optional<double> S; // -, eroded area / Dn² (none when no unit is on the slope)
};

class CumulativeDamage {
  public:
    CumulativeDamage(const Scene &scene, const SceneSetup &setup);
    // t in s, increasing; the first call is the reference (the series' start).
    void sample(double t, const std::vector<BodyState> &states);
    CumulativeFigures figures() const;

  private:
    const Scene &scene_;
    const SceneSetup &setup_;
    std::optional<SlopeFrame> frame_;
    std::vector<UnitDamageTracker> units_;
    std::vector<BodyState> last_;
    LayerRegion region_;
    std::optional<ArmourProfile> before_;
    double layer_width_ = 0.0;
};

} // namespace armour
