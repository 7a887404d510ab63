#include "damage_analysis.h"

#include "analysis.h"
#include "jonswap.h"
#include "rock_manual_layer.h"
#include "slope_profile.h"
#include "standard_conditions.h"
#include "wave_theory.h"

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace armour {

namespace {

using nlohmann::json;

constexpr double kPi = 3.14159265358979323846;
// A unit's way out is read over its last move: from its last record under a fifth of the displaced
// threshold to its pass of it. A cube rolled over an edge turns 90 deg while its centre moves 1 Dn;
// a unit that turned at least half of that per Dn it moved rolled out (docs/analysis.md).
constexpr double kMoveStart = 0.2;       // of the displaced threshold
constexpr double kRolledDegPerDn = 45.0; // deg turned per Dn moved

json nullable(const std::optional<double> &v) {
    return v ? json(*v) : json(nullptr);
}

// Writes `text` to `path` through a temporary file and a rename.
void write_file(const std::string &path, const std::string &text) {
    const std::string temporary = path + ".tmp";
    {
        std::ofstream out(temporary);
        out << text;
        if (!out)
            throw InputError(path + ": cannot write");
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0)
        throw InputError(path + ": cannot write");
}

// Van der Meer's (1988) cube tests: a 1:1.5 slope, N up to 7500, s_om
// 0.005-0.07. The limits a run lies outside, as text.
std::vector<std::string> van_der_meer_range(double cot, std::optional<double> waves,
                                            std::optional<double> s_om) {
    std::vector<std::string> outside;
    char text[64];
    if (std::abs(cot - 1.5) > 0.05) {
        std::snprintf(text, sizeof text, "slope 1:%.3g (tested on 1:1.5 only)", cot);
        outside.emplace_back(text);
    }
    if (waves && *waves > 7500.0) {
        std::snprintf(text, sizeof text, "N %.0f > 7500", *waves);
        outside.emplace_back(text);
    }
    if (s_om && (*s_om < 0.005 || *s_om > 0.07)) {
        std::snprintf(text, sizeof text, "s_om %.3g outside 0.005-0.07", *s_om);
        outside.emplace_back(text);
    }
    return outside;
}

double density_of(const Scene &scene, const std::string &unit) {
    for (const SceneUnit &u : scene.units)
        if (u.name == unit)
            return u.density;
    return scene.units.empty() ? 0.0 : scene.units[0].density;
}

// N_od counts strips of one Dn and Ns takes one Δ: the figures mean nothing
// for a layer of mixed units, so such a scene is refused, not averaged.
std::string damage_refusal(const Scene &scene, const SceneSetup &setup) {
    if (setup.bodies.empty())
        return "needs a body";
    const auto first = static_cast<std::size_t>(setup.bodies[0].unit);
    const double Dn = setup.unit_Dn[first], rho = density_of(scene, setup.units[first].name);
    for (const BodyInit &b : setup.bodies) {
        const auto u = static_cast<std::size_t>(b.unit);
        const double other_rho = density_of(scene, setup.units[u].name);
        if (std::abs(setup.unit_Dn[u] - Dn) <= 1e-6 * Dn && other_rho == rho)
            continue;
        const auto figures = [&](std::size_t unit, double rho_unit) {
            char text[64];
            std::snprintf(text, sizeof text, " (Dn %.4g m, %.4g kg/m^3)", setup.unit_Dn[unit], rho_unit);
            return "'" + setup.units[unit].name + "'" + text;
        };
        return "\"damage\" counts units of one size and density (N_od in strips of Dn, Ns with one delta): "
               "units " +
               figures(first, rho) + " and " + figures(u, other_rho) + " differ";
    }
    return "";
}

class DamageAnalysis : public Analysis {
  public:
    explicit DamageAnalysis(const AnalysisContext &c)
        : scene_(c.scene), setup_(c.setup), out_dir_(c.out_dir),
          measured_waves_(c.incident_waves ? *c.incident_waves : json::object()), claim_(c.claim),
          settle_(c.scene, c.setup) {
        const std::optional<SlopeFrame> frame = slope_frame(c.scene);
        if (!frame)
            throw InputError(c.scene.file + ": key 'analysis.kind': kind \"damage\" counts units on a slope: "
                                            "the scene needs a [[wall]] of type \"slope\"");
        frame_ = *frame;
        // A coupled run starts from settled poses; a dry run settles first.
        wait_for_settle_ = !c.scene.fluid.has_value();
    }

    void sample(double t, const std::vector<BodyState> &states) override {
        last_ = states;
        end_ = t;
        if (units_.empty() || (wait_for_settle_ && !settled_)) {
            settle_.sample(t, states);
            settled_ = settle_.settled();
            if (units_.empty() || settled_)
                start(t, states);
        }
        int displaced = 0;
        double largest = 0.0;
        for (std::size_t i = 0; i < states.size(); ++i) {
            const Pose &pose = states[i].pose;
            units_[i].sample(t, pose);
            const bool out = units_[i].displacement() >= scene_.displaced_threshold;
            if (units_[i].displacement() < kMoveStart * scene_.displaced_threshold)
                move_start_[i] = pose;
            if (!out) {
                left_at_[i] = std::nan(""); // back within the threshold: not gone (yet)
            } else if (std::isnan(left_at_[i])) {
                left_at_[i] = t;
                const double moved = (pose.position - move_start_[i].position).norm() / units_[i].Dn();
                turn_per_Dn_[i] =
                    moved > 0.0 ? rotation_between_deg(move_start_[i].orientation, pose.orientation) / moved
                                : std::nan("");
            }
            displaced += out ? 1 : 0;
            largest = std::max(largest, units_[i].displacement());
        }
        history_ += num(t) + "," + std::to_string(displaced) + "," +
                    num(n_od(displaced, layer_width_, Dn())) + "," + num(largest) + "\n";
    }

    std::string write(json &summary) const override {
        const double Dn = this->Dn();
        json settled_layer = nullptr; // the layer the waves met, as a profiler measures it
        const std::optional<double> S = eroded_area_over_Dn2(settled_layer, summary);
        std::optional<double> thickness; // m, the settled layer's
        if (!settled_layer.is_null())
            thickness = settled_layer["layer_thickness"].get<double>();
        Counts counts;
        const std::string rows = unit_rows(counts, thickness);
        if (!settled_layer.is_null())
            settled_layer["units_on_top"] = counts.on_top;
        const double N_od = n_od(counts.displaced, layer_width_, Dn);
        // The waves the run measured at its gauges (a wave train), else its targets.
        const WaveConditions w =
            wave_conditions(measured_waves_, scene_, acting_seconds(scene_, frame_.origin.x(), start_, end_));
        const Prediction p = predict(w, N_od);
        const std::vector<std::string> outside = van_der_meer_range(frame_.cot, w.waves, w.s_om);
        summary["units"] = units_.size();
        summary["units_displaced"] = counts.displaced;
        summary["units_displaced_at_foot"] = counts.displaced_at_foot;
        summary["units_displaced_on_top"] = thickness ? json(counts.displaced_on_top) : json(nullptr);
        summary["units_displaced_rolled"] = counts.displaced_rolled;
        summary["N_od"] = N_od;
        summary["rocking_units"] = counts.rocking;
        summary["Ns"] = nullable(p.Ns);
        summary["s_om"] = nullable(w.s_om);
        if (!summary.contains("waves") || !summary["waves"].is_object())
            summary["waves"] = nullable(w.waves); // else the incident-wave analysis's object
        summary["damage_S"] = nullable(S);
        summary["Ns_van_der_meer"] = nullable(p.vdm_ns);
        summary["N_od_van_der_meer"] = nullable(p.vdm_n_od);
        summary["units_displaced_van_der_meer"] = nullable(p.vdm_units);
        summary["Ns_hudson_breaking"] = hudson_ns(6.5, frame_.cot);
        summary["Ns_hudson_nonbreaking"] = hudson_ns(7.5, frame_.cot);
        summary["damage"] = {{"Hs", nullable(w.Hs)},
                             {"wave_source", w.source},
                             {"waves", nullable(w.waves)},
                             {"delta", p.delta},
                             {"Dn", Dn},
                             {"slope_width", frame_.width},
                             {"layer_width", layer_width_},
                             {"van_der_meer_outside", outside},
                             {"displaced_threshold", scene_.displaced_threshold},
                             {"rocking_threshold_deg", scene_.rocking_threshold_deg},
                             {"reference_time", start_},
                             {"settled", wait_for_settle_ ? json(settled_) : json(nullptr)},
                             {"settled_layer", settled_layer},
                             {"files", {"damage.csv", "damage_history.csv", "damage.png"}},
                             {"si_units",
                              {{"Hs", "m"},
                               {"Dn", "m"},
                               {"slope_width", "m"},
                               {"layer_width", "m"},
                               {"reference_time", "s"},
                               {"layer_thickness", "m"}}}};
        write_file(path("damage.csv"), rows);
        write_file(path("damage_history.csv"), "# units displaced (>= displaced_threshold Dn) against time\n"
                                               "time_s,units_displaced,N_od,max_displacement_over_Dn\n" +
                                                   history_);
        std::string line =
            std::to_string(counts.displaced) + " of " + std::to_string(units_.size()) + " units displaced";
        std::string where;
        if (counts.displaced_at_foot > 0)
            where = std::to_string(counts.displaced_at_foot) + " at the foot";
        if (counts.displaced_on_top > 0)
            where += (where.empty() ? "" : ", ") + std::to_string(counts.displaced_on_top) +
                     " from on top of the layer";
        if (counts.displaced_rolled > 0)
            where += (where.empty() ? "" : "; ") + std::to_string(counts.displaced_rolled) + " rolled out";
        if (!where.empty())
            line += " (" + where + ")";
        line += ", N_od " + num(N_od) + ", " + std::to_string(counts.rocking) + " rocking";
        if (!outside.empty() && p.vdm_ns) {
            line += "; outside Van der Meer's tested range:";
            for (const std::string &o : outside)
                line += " " + o + (&o == &outside.back() ? "" : ",");
        }
        line += coarse_record_warning(summary);
        const std::string command = std::string("/usr/bin/python3 '") + ARMOUR_SOURCE_DIR +
                                    "/analysis/damage_chart.py' '" + path("damage.csv") + "' '" +
                                    path("damage_history.csv") + "' '" + path("damage.png") +
                                    "' > /dev/null 2>&1";
        if (std::system(command.c_str()) != 0)
            line += "; no damage.png: analysis/damage_chart.py failed (needs python3-matplotlib)";
        return line;
    }

  private:
    struct Counts {
        int displaced = 0, displaced_at_foot = 0, rocking = 0; // units
        int on_top = 0, displaced_on_top = 0;                  // units
        int displaced_rolled = 0;                              // units
    };

    // damage.csv's rows: each unit from its settled pose; counts the displaced and the rocking.
    // left_at_s, for a displaced unit: the record from which it has stayed displaced (when it left).
    // on_top: the unit's settled centre rests on the layer `thickness` m thick (SlopeFrame::rests_on_layer).
    // turn_per_Dn_deg, for a displaced unit: how far it turned per Dn it moved over its last move
    // (kMoveStart).
    std::string unit_rows(Counts &counts, std::optional<double> thickness) const {
        std::string rows =
            "# damage per unit from its settled pose (SI; displacements in Dn)\n"
            "body,unit,s_m,y_m,n_m,at_foot,on_top,max_displacement_over_Dn,final_displacement_over_Dn,"
            "max_rotation_deg,rocking_events,displaced,left_at_s,turn_per_Dn_deg\n";
        for (std::size_t i = 0; i < units_.size(); ++i) {
            const UnitDamageTracker &u = units_[i];
            const bool is_displaced = u.displacement() >= scene_.displaced_threshold;
            const bool foot = frame_.seaward_of_foot(u.reference().position);
            const Eigen::Vector3d at = frame_.local(u.reference().position);
            const bool on_top = thickness && frame_.rests_on_layer(u.reference().position, *thickness);
            counts.displaced += is_displaced ? 1 : 0;
            counts.displaced_at_foot += is_displaced && foot ? 1 : 0;
            counts.on_top += on_top ? 1 : 0;
            counts.displaced_on_top += is_displaced && on_top ? 1 : 0;
            counts.rocking += u.rocking_events() > 0 ? 1 : 0;
            counts.displaced_rolled += is_displaced && turn_per_Dn_[i] >= kRolledDegPerDn ? 1 : 0;
            rows += std::to_string(i) + "," + setup_.units[unit(i)].name + "," + num(at.x()) + "," +
                    num(at.y()) + "," + num(at.z()) + "," + (foot ? "1" : "0") + "," + (on_top ? "1" : "0") +
                    "," + num(u.max_displacement()) + "," + num(u.displacement()) + "," +
                    num(u.max_rotation_deg()) + "," + std::to_string(u.rocking_events()) + "," +
                    (is_displaced ? "1," + num(left_at_[i]) + "," + nullable_cell(turn_per_Dn_[i]) : "0,,") +
                    "\n";
        }
        return rows;
    }

    // S from the profiles at the reference and at the end, over the layer the
    // reference covered; `settled_layer` gets that layer's figures (none
    // without units on the face).
    std::optional<double> eroded_area_over_Dn2(json &settled_layer, json &summary) const {
        if (region_.bodies.empty())
            return std::nullopt;
        std::vector<BodyState> reference(units_.size());
        for (std::size_t i = 0; i < units_.size(); ++i)
            reference[i].pose = units_[i].reference();
        const ArmourProfile before = armour_profile(frame_, setup_, reference, region_);
        const double S = eroded_area(before, armour_profile(frame_, setup_, last_, region_)) / (Dn() * Dn());
        const LayerFigures f = layer_figures(setup_, region_, before, scene_.layers);
        const LayerVerdict verdict = rock_manual_verdict(scene_, setup_, f);
        settled_layer = layer_record(f, verdict);
        settled_layer["units_at_foot"] = std::count_if(units_.begin(), units_.end(), [&](const auto &u) {
            return frame_.seaward_of_foot(u.reference().position);
        });
        warn_if_outside_rock_manual(verdict, summary);
        return S;
    }

    // Van der Meer's figures at the run's waves: the Ns his formula gives for
    // the damage seen, and the damage it gives at the run's Ns.
    struct Prediction {
        double delta = 0.0; // -, rho_s / rho_w - 1
        std::optional<double> Ns, vdm_ns, vdm_n_od, vdm_units;
    };
    Prediction predict(const WaveConditions &w, double N_od) const {
        const double rho_s = unit_density();
        const double rho_w = scene_.fluid ? scene_.fluid->fluid_density : kFreshWaterDensity;
        Prediction p;
        p.delta = rho_s / rho_w - 1.0;
        if (w.Hs)
            p.Ns = stability_number(*w.Hs, rho_s, rho_w, Dn());
        if (w.s_om && w.waves && *w.waves > 0.0) {
            p.vdm_ns = van_der_meer_cubes_ns(N_od, *w.waves, *w.s_om);
            if (p.Ns) {
                p.vdm_n_od = van_der_meer_cubes_n_od(*p.Ns, *w.waves, *w.s_om);
                p.vdm_units = *p.vdm_n_od * layer_width_ / Dn();
            }
        }
        return p;
    }

    // Records too far apart to tell a rest from a rocking unit caught at one
    // phase: warned in the summary, and the summary line's part (else empty).
    std::string coarse_record_warning(json &summary) const {
        const double gap = units_.empty() ? 0.0 : units_.front().largest_record_gap(); // all alike
        const double rest = rest_time(scene_);
        if (gap <= rest / UnitDamageTracker::kRestSamples)
            return "";
        const std::string coarse = "records up to " + num(gap) +
                                   " s apart, over a quarter of the rest time " + num(rest) +
                                   " s: no unit finds a new seat, rocking is counted from the settled pose "
                                   "(a finer run.output_interval)";
        summary["warnings"].push_back("damage: " + coarse);
        return "; " + coarse;
    }

    static std::string num(double v) {
        char text[32];
        std::snprintf(text, sizeof text, "%.6g", v);
        return text;
    }
    static std::string nullable_cell(double v) { return std::isnan(v) ? "" : num(v); } // empty: not known
    std::size_t unit(std::size_t body) const { return static_cast<std::size_t>(setup_.bodies[body].unit); }
    double Dn() const { return setup_.unit_Dn[unit(0)]; }
    double unit_density() const { return density_of(scene_, setup_.units[unit(0)].name); }
    std::string path(const std::string &name) const { return claim_ ? claim_(name) : out_dir_ + "/" + name; }

    // The layer against the Rock Manual's band (rock_manual_layer.h). A
    // coupled run warned before its waves (check_coupled_scene); a dry run
    // forms its layer as it runs, so it warns here.
    void warn_if_outside_rock_manual(const LayerVerdict &v, json &summary) const {
        if (v.outside && !scene_.fluid) {
            const std::string warning = rock_manual_warning(v);
            summary["warnings"].push_back("damage: " + warning);
            std::fprintf(stderr, "armour: warning: %s\n", warning.c_str());
        }
    }

    void start(double t, const std::vector<BodyState> &states) {
        units_.clear();
        for (std::size_t i = 0; i < states.size(); ++i)
            units_.emplace_back(states[i].pose, setup_.unit_Dn[unit(i)], scene_.rocking_threshold_deg,
                                rest_time(scene_));
        left_at_.assign(states.size(), std::nan(""));
        turn_per_Dn_.assign(states.size(), std::nan(""));
        move_start_.clear();
        for (const BodyState &b : states)
            move_start_.push_back(b.pose);
        history_.clear();
        start_ = t;
        region_ = layer_region(frame_, setup_, states);
        layer_width_ = layer_width(frame_, region_);
    }

    const Scene &scene_;
    const SceneSetup &setup_;
    std::string out_dir_;
    json measured_waves_; // the gauges' figures (AnalysisContext::incident_waves); empty: none
    std::function<std::string(const std::string &)> claim_;
    SlopeFrame frame_;
    SettleWatch settle_;
    bool wait_for_settle_ = true, settled_ = false;
    std::vector<UnitDamageTracker> units_;
    std::vector<double> left_at_;     // s: since when each unit has stayed displaced (NaN: it is not)
    std::vector<Pose> move_start_;    // each unit's last pose under kMoveStart of the threshold
    std::vector<double> turn_per_Dn_; // deg per Dn over the move that displaced it (NaN: none yet)
    std::vector<BodyState> last_;
    std::string history_;
    double start_ = 0.0, end_ = 0.0;
    LayerRegion region_;       // the face the layer covers at the reference
    double layer_width_ = 0.0; // m, across the slope at the reference
};

} // namespace

// Its units' centres and half a Dn beyond, out to a side wall where no unit
// fits between (a gap under one Dn), so a layer laid wall to wall spans the
// wall; the wall's width when no unit is on the face.
double layer_width(const SlopeFrame &frame, const LayerRegion &region) {
    if (region.bodies.empty())
        return frame.width;
    const double half = 0.5 * frame.width;
    const double lo = region.y_lo + half < region.Dn ? -half : region.y_lo;
    const double hi = half - region.y_hi < region.Dn ? half : region.y_hi;
    // A layer is at least one strip wide (a wall narrower than a Dn: the wall).
    return std::min(frame.width, std::max(region.Dn, hi - lo));
}

UnitDamageTracker::UnitDamageTracker(const Pose &reference, double Dn, double rocking_threshold_deg,
                                     double rest_time)
    : reference_(reference), seat_(reference), still_at_(reference), Dn_(Dn),
      threshold_(rocking_threshold_deg), rest_time_(rest_time) {}

void UnitDamageTracker::sample(double t, const Pose &pose) {
    // A record coarser than a quarter of the rest time cannot tell a rest from
    // a rocking unit caught at one phase of its swing: it never rests.
    const double gap = std::isnan(last_t_) ? 0.0 : t - last_t_;
    const bool coarse = gap > rest_time_ / kRestSamples;
    largest_gap_ = std::max(largest_gap_, gap);
    last_t_ = t;
    displacement_ = (pose.position - reference_.position).norm() / Dn_;
    max_displacement_ = std::max(max_displacement_, displacement_);
    max_rotation_ = std::max(max_rotation_, rotation_between_deg(reference_.orientation, pose.orientation));
    // A unit that rests somewhere new has a new seat: it rocks about that one.
    if (std::isnan(still_since_) || coarse ||
        rotation_between_deg(still_at_.orientation, pose.orientation) > 0.1 * threshold_ ||
        (pose.position - still_at_.position).norm() > 0.02 * Dn_) {
        still_at_ = pose;
        still_since_ = t;
        still_samples_ = 1;
    } else if (++still_samples_ >= kRestSamples && t - still_since_ >= rest_time_) {
        seat_ = still_at_;
        turned_ = false;
    }
    const double turned = rotation_between_deg(seat_.orientation, pose.orientation);
    if (!turned_ && turned > threshold_)
        turned_ = true;
    else if (turned_ && turned < 0.5 * threshold_) {
        turned_ = false;
        ++rocking_events_;
    }
}

double rest_time(const Scene &scene) {
    const bool train = scene.waves && scene.waves->type != "solitary";
    return std::max(2.0, train ? scene.waves->target_period() : scene.wave_period);
}

std::optional<double> wave_front_arrival(const Scene &scene, double toe_x) {
    if (!scene.fluid || !scene.waves || scene.waves->type == "solitary")
        return std::nullopt;
    const double cg =
        group_velocity(scene.waves->target_period(), scene.still_water_depth(), scene.gravity.norm());
    return std::max(0.0, toe_x - scene.domain_min.x()) / cg;
}

double acting_seconds(const Scene &scene, double toe_x, double start, double end) {
    return std::max(0.0, end - std::max(start, wave_front_arrival(scene, toe_x).value_or(start)));
}

double rotation_between_deg(const Eigen::Quaterniond &a, const Eigen::Quaterniond &b) {
    return 2.0 * std::acos(std::min(1.0, std::abs(a.normalized().dot(b.normalized())))) * 180.0 / kPi;
}

double n_od(int displaced, double layer_width, double Dn) {
    return displaced / (layer_width / Dn);
}

double stability_number(double Hs, double unit_density, double water_density, double Dn) {
    return Hs / ((unit_density / water_density - 1.0) * Dn);
}

double van_der_meer_cubes_ns(double N_od, double waves, double s_om) {
    return (6.7 * std::pow(N_od, 0.4) / std::pow(waves, 0.3) + 1.0) * std::pow(s_om, -0.1);
}

double van_der_meer_cubes_n_od(double Ns, double waves, double s_om) {
    const double excess = Ns * std::pow(s_om, 0.1) - 1.0;
    return excess <= 0.0 ? 0.0 : std::pow(excess * std::pow(waves, 0.3) / 6.7, 2.5);
}

double hudson_ns(double K_D, double cot) {
    return std::cbrt(K_D * cot);
}

WaveConditions wave_conditions(const json &measured, const Scene &scene, double duration) {
    WaveConditions w;
    const auto number = [](const json &o, const char *key) -> std::optional<double> {
        if (o.is_object() && o.contains(key) && o[key].is_number())
            return o[key].get<double>();
        return std::nullopt;
    };
    if (const std::optional<double> Hs = number(measured, "incident_height")) {
        w.Hs = Hs;
        w.s_om = number(measured, "s_om");
        w.waves = number(measured, "waves");
        w.source = "measured";
        return w;
    }
    const double g = scene.gravity.norm();
    const SceneWaves *train = scene.waves && scene.waves->type != "solitary" ? &*scene.waves : nullptr;
    if (scene.wave_height <= 0.0 && train) {
        const bool regular = train->type == "regular";
        const double tm = regular ? train->period : target_tm02(jonswap_components(train->jonswap_sea()));
        w.Hs = regular ? train->height : train->hs;
        w.s_om = 2.0 * kPi * *w.Hs / (g * tm * tm);
        w.waves = duration / tm;
        w.source = "target";
        return w;
    }
    const double H = scene.wave_height > 0.0 ? scene.wave_height
                     : scene.fluid           ? scene.fluid->wave_height
                                             : 0.0;
    if (H <= 0.0) {
        w.source = "none";
        return w;
    }
    w.Hs = H;
    w.source = "scene";
    if (scene.wave_period > 0.0) {
        w.s_om = 2.0 * kPi * H / (g * scene.wave_period * scene.wave_period);
        w.waves = duration / scene.wave_period;
    }
    return w;
}

AnalysisStyle damage_analysis_style() {
    return {
        "damage",
        "units on a slope from their settled poses: displaced (N_od), rocking, S, Ns against Van der Meer "
        "and Hudson",
        {"units_displaced", "N_od", "rocking_units", "damage_S"},
        {{"units_displaced", "units_displaced_van_der_meer"}, {"N_od", "N_od_van_der_meer"}},
        false,
        [](const AnalysisContext &c) { return std::make_unique<DamageAnalysis>(c); },
        damage_refusal};
}

} // namespace armour
