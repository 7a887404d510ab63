#include "series_damage.h"

#include <cmath>

namespace armour {

std::vector<SequencePrediction> van_der_meer_cubes_sequence(const std::vector<SeaStateFigures> &steps) {
    std::vector<SequencePrediction> out;
    std::optional<double> damage = 0.0; // N_od before the step; unknown once a step is
    for (const SeaStateFigures &step : steps) {
        SequencePrediction p;
        if (damage && step.Ns && step.s_om && step.waves) {
            // N_od = ((Ns s^0.1 - 1) N^0.3 / 6.7)^2.5 solved for N at the damage so far.
            const double excess = *step.Ns * std::pow(*step.s_om, 0.1) - 1.0;
            if (excess > 0.0) {
                const double n_eq =
                    *damage > 0.0 ? std::pow(6.7 * std::pow(*damage, 0.4) / excess, 1.0 / 0.3) : 0.0;
                p.equivalent_waves = n_eq;
                damage = std::max(*damage, van_der_meer_cubes_n_od(*step.Ns, n_eq + *step.waves, *step.s_om));
            } // else below the floor: no number of these waves reaches the damage, none is added
            p.N_od = damage;
        } else {
            damage.reset();
        }
        out.push_back(p);
    }
    return out;
}

CumulativeDamage::CumulativeDamage(const Scene &scene, const SceneSetup &setup)
    : scene_(scene), setup_(setup), frame_(slope_frame(scene)) {}

void CumulativeDamage::sample(double t, const std::vector<BodyState> &states) {
    last_ = states;
    if (units_.empty()) {
        for (std::size_t i = 0; i < states.size(); ++i)
            units_.emplace_back(states[i].pose,
                                setup_.unit_Dn[static_cast<std::size_t>(setup_.bodies[i].unit)],
                                scene_.rocking_threshold_deg, rest_time(scene_));
        if (frame_) {
            region_ = layer_region(*frame_, setup_, states);
            layer_width_ = layer_width(*frame_, region_);
            if (!region_.bodies.empty())
                before_ = armour_profile(*frame_, setup_, states, region_);
        }
    }
    for (std::size_t i = 0; i < states.size(); ++i)
        units_[i].sample(t, states[i].pose);
}

CumulativeFigures CumulativeDamage::figures() const {
    CumulativeFigures f;
    if (units_.empty())
        return f;
    for (const UnitDamageTracker &u : units_) {
        f.displaced += u.displacement() >= scene_.displaced_threshold ? 1 : 0;
        f.rocking_units += u.rocking_events() > 0 ? 1 : 0;
    }
    const double Dn = setup_.unit_Dn[static_cast<std::size_t>(setup_.bodies[0].unit)];
    f.N_od = n_od(f.displaced, layer_width_, Dn);
    if (before_)
        f.S = eroded_area(*before_, armour_profile(*frame_, setup_, last_, region_)) / (Dn * Dn);
    return f;
}

} // namespace armour
