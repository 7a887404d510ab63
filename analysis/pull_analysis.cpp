// Pull: a dry pull-out test of the units of an armour layer.
//
// Description
//     Measures what holds a unit in its layer, apart from the waves: a set of
//     the layer's outer units is pulled out of the face by a force that grows
//     steadily from zero, each unit by its own weight times the same factor,
//     and each unit's resistance is the pull it held last. The fluid loads a
//     coupled run puts on the same units (bodies.h5, in their submerged
//     weights) can then be set beside it: a unit whose peak load stays below
//     its resistance cannot leave.
//
//     The pulled units: the outer layer (centre more than 1 Dn out of the
//     face), taken in rounds of units at least 3 Dn apart, so that no two
//     pulled units touch or lean on the same neighbour from both sides; round
//     k takes, in order up the face, every outer unit that no earlier round
//     took and that stands 3 Dn from those round k has taken. The set is
//     chosen from the layer as the run starts, which should be at rest (a
//     settled scene).
//
//     The seat: nothing is pulled for the first wait = 5 (Dn / |g|)^1/2 of
//     the largest unit (0.32 s for 4 cm cubes), so that a layer settled
//     under buoyancy takes its full dry weight first. Each unit is seated at
//     its first still sample (centre slower than 5 mm/s, turning slower than
//     0.05 rad/s) from then on; one that moves 0.25 Dn before it is seated,
//     or is not still by twice the wait, was unseated by the start itself:
//     it is not pulled, and is counted apart (pull_unseated), not as a
//     resistance of 0.
//
//     The pull on each seated unit: F = min(pull_rate (t - t_seat), pull_max)
//     m |g|, at its centre of mass, along the face's outward normal turned by
//     pull_angle toward down the face; it is let go (zero) once the unit has
//     moved 0.5 Dn. Its resistance is the pull that acted on it up to the
//     last sample at which it was still before its centre first moved 0.25 Dn
//     from its seat (the pull is set at every sample, so this is the applied
//     pull when records are no further apart than 0.01 / pull_rate s): soft contacts
//     creep at 0.1-1 mm/s while they hold, and a unit that has let go moves
//     at 5 mm/s within (2 v / (pull_rate g))^1/2 = 0.06 s of letting go at
//     pull_rate 0.25/s, a pull 0.016 weights past the onset. A unit that
//     re-seats and holds again is still again: its resistance is the pull at
//     which it finally left. One that never moves 0.25 Dn held pull_max.
//
//     A lone unit resting face-down on a flat bed of units parallel to the
//     face (an outer unit on the layer below, with nothing else holding it)
//     starts to move at
//         lift:  F cos(beta) = W cos(alpha)
//         slide: F sin(beta) + W sin(alpha) = mu (W cos(alpha) - F cos(beta))
//     (alpha the slope's angle, beta = pull_angle, mu the friction between
//     units, W = m |g|): the slide comes first for any beta in [0, 90] deg,
//     and is 0 where the unit slides unaided (mu < tan alpha: the stability
//     scene's 1:1.5 face at mu 0.6). The lift is that of a unit held against
//     sliding (by the units below it, the toe) but not clamped: what a unit
//     in a layer holds above it is its neighbours' clamping and wedging.
//     A unit in a layer held by its neighbours and the toe needs more; how
//     much more is what the test measures. Forces in a dry run are in dry
//     weights: frictional holding scales with the weight, so the same ratio
//     holds for submerged weights under still water.
//
// Usage
//     [analysis]
//     kind = "pull"
//     pull_rate = 0.25   # unit weights per second
//     pull_max = 3.0     # unit weights
//     pull_angle = 0.0   # deg: straight out of the face
//     pull_round = 0     # the first set of units
//
//     on a dry scene with a slope wall and a settled layer (run.duration at
//     least twice the wait, pull_max / pull_rate and a second); bench/run_pull_test.sh makes the dry scene
//     from a settled one and runs every round.
#include "analysis.h"

#include "materials.h"
#include "scene_keys.h"
#include "slope_profile.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

namespace armour {
namespace {

using nlohmann::json;

constexpr double kPi = 3.14159265358979323846;
constexpr double kOuterLayer = 1.0;                     // Dn: centre out of the face beyond this
constexpr double kSpacing = 3.0;                        // Dn between the units of one round
constexpr double kMoved = 0.25;                         // Dn: the unit has left its seat
constexpr double kLetGo = 0.5;                          // Dn: the pull stops
constexpr double kStillSpeed = 5e-3, kStillTurn = 5e-2; // m/s, rad/s
constexpr double kSeatWait = 5.0;                       // (Dn / |g|)^1/2 of the largest unit

double seat_wait(const SceneSetup &setup, double g) { // s
    const double Dn =
        setup.unit_Dn.empty() ? 0.0 : *std::max_element(setup.unit_Dn.begin(), setup.unit_Dn.end());
    return kSeatWait * std::sqrt(Dn / g);
}

struct PulledUnit {
    int body = 0;
    Eigen::Vector3d start, local; // m: world centre (at the seat once seated), and (s, y, n) on the face
    double Dn = 0.0, weight = 0.0;
    double seat_time = 0.0;               // s: its pull starts here
    double last_still = 0.0, acted = 0.0; // weights: at the last still sample; up to the last sample
    std::optional<double> moved_at;       // weights, the pull when it had moved kMoved Dn
    std::optional<double> resistance;     // weights, the pull it held last
    bool seated = false, unseated = false, let_go = false;
};

// The rounds of outer-layer units as the Description says; round `k`.
std::vector<int> pull_round(const SlopeFrame &frame, const SceneSetup &setup,
                            const std::vector<BodyState> &states, int k) {
    std::vector<std::pair<double, int>> outer; // (s, body)
    for (const int i : layer_region(frame, setup, states).bodies) {
        const BodyInit &b = setup.bodies[static_cast<std::size_t>(i)];
        const double Dn = setup.unit_Dn[static_cast<std::size_t>(b.unit)];
        const Eigen::Vector3d c = frame.local(states[static_cast<std::size_t>(i)].pose.position);
        const auto any = [](const std::array<bool, 3> &a) { return a[0] || a[1] || a[2]; };
        const bool held = any(b.fixed_translation) || any(b.fixed_rotation);
        if (!held && c.z() > kOuterLayer * Dn)
            outer.emplace_back(c.x(), i);
    }
    std::sort(outer.begin(), outer.end());
    std::vector<bool> taken(outer.size(), false);
    std::vector<int> round;
    for (int r = 0; r <= k; ++r) {
        round.clear();
        for (std::size_t a = 0; a < outer.size(); ++a) {
            if (taken[a])
                continue;
            const int i = outer[a].second;
            const Eigen::Vector3d &p = states[static_cast<std::size_t>(i)].pose.position;
            const double Dn =
                setup.unit_Dn[static_cast<std::size_t>(setup.bodies[static_cast<std::size_t>(i)].unit)];
            const bool apart = std::all_of(round.begin(), round.end(), [&](int j) {
                return (states[static_cast<std::size_t>(j)].pose.position - p).norm() >= kSpacing * Dn;
            });
            if (apart) {
                round.push_back(i);
                taken[a] = true;
            }
        }
    }
    return round;
}

class PullAnalysis : public Analysis {
  public:
    explicit PullAnalysis(const AnalysisContext &c)
        : setup_(c.setup), frame_(*slope_frame(c.scene)), rate_(c.scene.pull_rate), max_(c.scene.pull_max),
          round_(c.scene.pull_round), g_(c.scene.gravity.norm()), wait_(seat_wait(c.setup, g_)),
          csv_(c.claim ? c.claim("pull.csv") : "") {
        const double beta = c.scene.pull_angle * kPi / 180.0;
        direction_ = std::cos(beta) * frame_.normal - std::sin(beta) * frame_.along;
        // A lone outer unit rests on units of the layer below it: the units' friction.
        const int material = setup_.units.empty() ? 0 : setup_.units[0].material;
        mu_ = pair_value(setup_.settings, material, material, &Material::friction, &MaterialPair::friction);
        const double alpha = std::atan2(1.0, frame_.cot);
        // Pulled along the face (beta = 90 deg) a unit never lifts off.
        lift_ =
            std::cos(beta) > 1e-9 ? std::optional<double>(std::cos(alpha) / std::cos(beta)) : std::nullopt;
        slide_ = std::max(0.0, (mu_ * std::cos(alpha) - std::sin(alpha)) /
                                   (std::sin(beta) + mu_ * std::cos(beta)));
    }

    double before_advance(double t, RigidBodyEngine &engine) override {
        for (const PulledUnit &u : units_) {
            const double f = u.seated && !u.let_go ? pull(u, t) * u.weight : 0.0;
            engine.set_external_load(u.body, f * direction_, Eigen::Vector3d::Zero());
        }
        return 0.01 / rate_; // the pull grows by at most 0.01 weights between updates
    }

    void sample(double t, const std::vector<BodyState> &states) override {
        if (!chosen_) {
            // The layer as the run starts (replayed on a resume: the same set).
            for (const int i : pull_round(frame_, setup_, states, round_)) {
                PulledUnit u;
                u.body = i;
                u.start = states[static_cast<std::size_t>(i)].pose.position;
                u.local = frame_.local(u.start);
                const int unit = setup_.bodies[static_cast<std::size_t>(i)].unit;
                u.Dn = setup_.unit_Dn[static_cast<std::size_t>(unit)];
                u.weight = setup_.units[static_cast<std::size_t>(unit)].props.mass * g_;
                units_.push_back(u);
            }
            chosen_ = true;
        }
        for (PulledUnit &u : units_) {
            if (u.unseated)
                continue;
            const BodyState &s = states[static_cast<std::size_t>(u.body)];
            const bool still = s.velocity.norm() < kStillSpeed && s.angular_velocity.norm() < kStillTurn;
            if (!u.seated) {
                u.unseated =
                    (s.pose.position - u.start).norm() / u.Dn >= kMoved || (t >= 2.0 * wait_ && !still);
                u.seated = !u.unseated && t >= wait_ && still;
                if (u.seated) {
                    u.start = s.pose.position;
                    u.seat_time = t;
                }
                continue;
            }
            const double p = pull(u, previous_); // what acted since the last sample (set there)
            u.acted = p;
            const double moved = (s.pose.position - u.start).norm() / u.Dn;
            if (!u.moved_at) {
                if (still)
                    u.last_still = p;
                if (moved >= kMoved) {
                    u.moved_at = p;
                    u.resistance = u.last_still;
                }
            }
            u.let_go = u.let_go || moved >= kLetGo;
        }
        previous_ = t;
        // Every unit let go or unseated, or every seated one held the full pull for a second.
        finished_ = std::all_of(units_.begin(), units_.end(), [&](const PulledUnit &u) {
            return u.let_go || u.unseated || (u.seated && t >= u.seat_time + max_ / rate_ + 1.0);
        });
    }

    bool finished() const override { return finished_; }

    std::string write(json &summary) const override {
        std::vector<double> held; // weights; a unit that never left counts as the pull it reached
        int stayed = 0, unseated = 0;
        std::ostringstream csv;
        csv << "# pull test (analysis kind pull): forces in the unit's own weight m|g| (-), positions on the "
               "slope face in the unit's Dn (-): s up the face from its toe, y across, n out of the face\n"
               "body,s_over_Dn,y_over_Dn,n_over_Dn,resistance_weights,moved_at_weights,stayed,unseated\n";
        for (const PulledUnit &u : units_) {
            const bool stays = u.seated && !u.moved_at;
            if (u.seated)
                held.push_back(u.resistance.value_or(u.acted));
            stayed += stays ? 1 : 0;
            unseated += u.seated ? 0 : 1;
            csv << u.body << ',' << u.local.x() / u.Dn << ',' << u.local.y() / u.Dn << ','
                << u.local.z() / u.Dn << ',' << (u.resistance ? std::to_string(*u.resistance) : "") << ','
                << (u.moved_at ? std::to_string(*u.moved_at) : "") << ',' << (stays ? 1 : 0) << ','
                << (u.seated ? 0 : 1) << '\n';
        }
        std::sort(held.begin(), held.end());
        const auto quantile = [&](double q) {
            return held.empty()
                       ? json(nullptr)
                       : json(held[static_cast<std::size_t>(q * static_cast<double>(held.size() - 1) + 0.5)]);
        };
        summary["pull_units"] = units_.size();
        summary["pull_stayed"] = stayed;
        summary["pull_unseated"] = unseated;
        summary["pull_wait"] = wait_;
        summary["pull_resistance_median"] = quantile(0.5);
        summary["pull_resistance_quartiles"] = {quantile(0.25), quantile(0.75)};
        summary["pull_lone_unit_lift"] = lift_ ? json(*lift_) : json(nullptr);
        summary["pull_lone_unit_slide"] = slide_;
        summary["pull_friction"] = mu_;
        if (!csv_.empty()) {
            std::ofstream(csv_) << csv.str();
            summary["files"]["pull"] = "pull.csv";
        }
        std::ostringstream line;
        line << "pull: " << units_.size() << " units, resistance median " << quantile(0.5).dump()
             << " weights (" << stayed << " held " << max_ << ", " << unseated
             << " unseated by the start); a lone unit slides at " << slide_
             << ", held against sliding lifts at " << (lift_ ? json(*lift_).dump() : std::string("never"));
        return line.str();
    }

  private:
    double pull(const PulledUnit &u, double t) const { // weights
        return std::clamp(rate_ * (t - u.seat_time), 0.0, max_);
    }

    const SceneSetup &setup_;
    SlopeFrame frame_;
    double rate_, max_;
    int round_;
    double g_, wait_;       // m/s^2, s
    double previous_ = 0.0; // s: the last sample, where the pull acting since was set
    std::string csv_;
    Eigen::Vector3d direction_;
    std::optional<double> lift_;
    double slide_ = 0.0, mu_ = 0.0;
    std::vector<PulledUnit> units_;
    bool chosen_ = false, finished_ = false;
};

} // namespace

AnalysisStyle pull_analysis_style() {
    return {"pull",
            "dry pull-out test: outer units of the slope's layer pulled out of the face; the pull each held",
            {"pull_resistance_median", "pull_stayed"},
            {},
            false,
            [](const AnalysisContext &c) { return std::make_unique<PullAnalysis>(c); },
            [](const Scene &scene, const SceneSetup &setup) {
                if (!slope_frame(scene))
                    return std::string("pull needs a wall of type \"slope\"");
                // The last unit seated (by twice the wait) must reach pull_max and hold it a second.
                const double wait = seat_wait(setup, scene.gravity.norm());
                const double needed = 2.0 * wait + scene.pull_max / scene.pull_rate + 1.0;
                if (needed > scene.duration)
                    return "pull needs run.duration >= " + figure_text(needed) + " s: twice the seat wait (" +
                           figure_text(wait) + " s), pull_max / pull_rate and a second at pull_max";
                return std::string();
            }};
}

} // namespace armour
