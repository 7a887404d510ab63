// The analyses of coupled runs (scenes with [fluid]): buoyancy, float,
// still, dambreak, platform, slope_waves. The solver runs in interFoam; the
// driver then samples the plugin's bodies.h5 step by step.
#include "analysis.h"
#include "gauge_rows.h"
#include "scene_keys.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

namespace armour {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Keeps every sampled step: these figures are taken over the whole record.
class History : public Analysis {
  public:
    explicit History(const AnalysisContext &c)
        : scene_(c.scene), setup_(c.setup), out_dir_(c.out_dir), case_dir_(c.case_dir), until_(c.until) {
        if (!c.scene.fluid)
            throw InputError(c.scene.file + ": analysis.kind: '" + c.scene.analysis +
                             "' needs a [fluid] table");
    }
    void sample(double t, const std::vector<BodyState> &states) override {
        time_.push_back(t);
        states_.push_back(states);
    }

  protected:
    const Eigen::Vector3d &position(std::size_t step, std::size_t body) const {
        return states_[step][body].pose.position;
    }
    double Dn(std::size_t body) const {
        return setup_.unit_Dn[static_cast<std::size_t>(setup_.bodies[body].unit)];
    }
    // As the damage analysis counts it: analysis.displaced_threshold Dn or more.
    bool displaced(double final_displacement, std::size_t body) const {
        return final_displacement >= scene_.displaced_threshold * Dn(body);
    }
    const SceneFluid &fluid() const { return *scene_.fluid; }

    const Scene &scene_;
    const SceneSetup &setup_;
    const fs::path out_dir_, case_dir_;
    const double until_;                         // s, the gauges' rows read
    std::vector<double> time_;                   // s
    std::vector<std::vector<BodyState>> states_; // [step][body]
};

// Buoyancy: the fluid's vertical load on a fixed, submerged first unit
// against Archimedes, rho_w g V.
class BuoyancyAnalysis : public History {
  public:
    using History::History;
    std::string write(json &summary) const override {
        const Eigen::Vector3d up = -scene_.gravity.normalized();
        const double volume = setup_.units[static_cast<std::size_t>(setup_.bodies[0].unit)].props.volume;
        const double expected = fluid().fluid_density * scene_.gravity.norm() * volume;
        const Eigen::Vector3d force = states_.back()[0].external_force;
        const double fz = force.dot(up);
        summary["buoyancy_force"] = fz;
        summary["buoyancy_expected"] = expected;
        summary["buoyancy_error"] = std::abs(fz - expected) / expected;
        summary["buoyancy_lateral"] = (force - fz * up).norm();
        char text[96];
        std::snprintf(text, sizeof text, "buoyancy %.5g N vs rho g V = %.5g N", fz, expected);
        return text;
    }
};

// Float: the draft of a floating cube against rho_u / rho_w a.
class FloatAnalysis : public History {
  public:
    using History::History;
    std::string write(json &summary) const override {
        // The free surface rises as the cube sinks into the small tank, and
        // falls by what seeps into the cube's ramp cells. With the waterline
        // on the cube's sides (A_b = a^2, upright), the water outside the
        // cube's mask, W_out = A (h - z0) - A_b (h - z_b), gives the level;
        // the plugin measures W_out (fluid.csv). Without it: the cube's
        // interior keeps the water it started with (W_in), so
        // W_out = A (h0 - z0) - W_in.
        const SceneFluid &f = fluid();
        const Eigen::Vector3d &lo = scene_.domain_min, &hi = scene_.domain_max;
        const Eigen::Vector3d up = -scene_.gravity.normalized();
        const auto unit0 = static_cast<std::size_t>(setup_.bodies[0].unit);
        const double a = scene_.units[unit0].size;
        const double rho_u = scene_.units[unit0].density;
        const double tank = (hi.x() - lo.x()) * (hi.y() - lo.y()), area = a * a;
        const auto bottom = [&](std::size_t step) {
            double low = HUGE_VAL;
            for (const auto &v : setup_.units[unit0].mesh.vertices)
                low = std::min(low, (position(step, 0) + states_[step][0].pose.orientation * v).dot(up));
            return low;
        };
        const double h0 = f.water_level, zb0 = bottom(0);
        const double inside = area * std::clamp(h0 - zb0, 0.0, a);
        const std::size_t n = time_.size();
        const double simulated = time_.back();
        const double z0 = lo.dot(up);
        std::map<double, double> outside_water; // time -> W_out, from the plugin
        {
            std::ifstream csv(out_dir_ / "fluid.csv");
            std::string line;
            std::getline(csv, line);
            for (double t, w, wo; std::getline(csv, line);)
                if (std::sscanf(line.c_str(), "%lf,%lf,%lf", &t, &w, &wo) == 3)
                    outside_water[t] = wo;
        }
        std::vector<double> zb(n), drafts(n);
        int measured = 0;
        for (std::size_t s = 0; s < n; ++s) {
            zb[s] = bottom(s);
            double w_out = tank * (h0 - z0) - inside;
            const auto it = outside_water.lower_bound(time_[s] - 1e-9);
            if (it != outside_water.end() &&
                std::abs(it->first - time_[s]) <= 1e-9 * std::max(1.0, it->first)) {
                w_out = it->second;
                ++measured;
            }
            drafts[s] = (w_out + tank * z0 - area * zb[s]) / (tank - area) - zb[s];
        }
        summary["water_level_from"] = measured > 0 ? "fluid.csv: water volume outside the units, measured"
                                                   : "volume balance: the cube keeps its initial contents";
        // Heave is lightly damped (radiated waves reflect in a small tank),
        // so the equilibrium is taken as the mean over whole heave periods:
        // from the first to the last crest of the bottom height in the second
        // half of the run; without two crests, the last value.
        std::vector<std::size_t> crests;
        for (std::size_t s = 1; s + 1 < n; ++s)
            if (time_[s] >= 0.5 * simulated && zb[s] > zb[s - 1] && zb[s] >= zb[s + 1])
                crests.push_back(s);
        double draft = drafts.back();
        if (crests.size() >= 2) {
            double sum = 0.0;
            for (std::size_t s = crests.front(); s < crests.back(); ++s)
                sum += drafts[s];
            draft = sum / static_cast<double>(crests.back() - crests.front());
            summary["draft_averaged_from"] = time_[crests.front()];
            summary["draft_averaged_to"] = time_[crests.back()];
            summary["heave_periods_averaged"] = crests.size() - 1;
            // The free-decay period, each crest placed by the parabola
            // through its three samples (the record is 0.01 s apart).
            const auto crest_time = [&](std::size_t s) {
                const double curvature = zb[s - 1] - 2 * zb[s] + zb[s + 1];
                const double shift = curvature != 0 ? 0.5 * (zb[s - 1] - zb[s + 1]) / curvature : 0.0;
                return time_[s] + shift * 0.5 * (time_[s + 1] - time_[s - 1]);
            };
            summary["heave_period"] = (crest_time(crests.back()) - crest_time(crests.front())) /
                                      static_cast<double>(crests.size() - 1);
        }
        const double expected = rho_u / f.fluid_density * a;
        double zmin = HUGE_VAL, zmax = -HUGE_VAL;
        for (std::size_t s = 0; s < n; ++s)
            if (time_[s] >= 0.8 * simulated) {
                zmin = std::min(zmin, zb[s]);
                zmax = std::max(zmax, zb[s]);
            }
        summary["draft"] = draft;
        summary["draft_expected"] = expected;
        summary["draft_error"] = std::abs(draft - expected) / expected;
        summary["draft_final"] = drafts.back();
        summary["water_level_final"] = drafts.back() + zb.back();
        summary["heave_amplitude_last_fifth"] = 0.5 * (zmax - zmin);
        char text[96];
        std::snprintf(text, sizeof text, "draft %.5g m vs %.5g m", draft, expected);
        return text;
    }
};

// Still: units resting in still water must not drift.
class StillAnalysis : public History {
  public:
    using History::History;
    std::string write(json &summary) const override {
        double worst = 0.0, ratio = 0.0;
        for (std::size_t s = 0; s < time_.size(); ++s)
            for (std::size_t b = 0; b < setup_.bodies.size(); ++b) {
                const double d = (position(s, b) - position(0, b)).norm();
                worst = std::max(worst, d);
                ratio = std::max(ratio, d / Dn(b));
            }
        summary["max_displacement"] = worst;
        summary["max_displacement_over_Dn"] = ratio;
        char text[96];
        std::snprintf(text, sizeof text, "max displacement %.3g m (%.3g %% of Dn)", worst, 100 * ratio);
        return text;
    }
};

// Units in a flow: per unit over the record, displacement from the start
// (largest and last), speed, streamwise (+x) fluid load; a unit whose centre
// leaves the mesh box is counted. Each kind adds its own figures (flow()).
class UnitMotionAnalysis : public History {
  public:
    using History::History;
    std::string write(json &summary) const override {
        const Eigen::Vector3d &lo = scene_.domain_min, &hi = scene_.domain_max;
        const std::size_t n = time_.size(), bodies = setup_.bodies.size();
        json units = json::array();
        Motion m{std::vector<double>(bodies, -HUGE_VAL), std::vector<double>(bodies, 0.0),
                 std::vector<double>(bodies, 0.0)};
        int left = 0;
        for (std::size_t b = 0; b < bodies; ++b) {
            double top_speed = 0.0, first_move = -1.0;
            bool outside = false;
            for (std::size_t s = 0; s < n; ++s) {
                const Eigen::Vector3d d = position(s, b) - position(0, b);
                m.max_disp[b] = std::max(m.max_disp[b], d.norm());
                top_speed = std::max(top_speed, states_[s][b].velocity.norm());
                m.peak_fx[b] = std::max(m.peak_fx[b], states_[s][b].external_force.x());
                if (first_move < 0.0 && d.x() > 0.05 * Dn(b)) // downstream, not the settling drop
                    first_move = time_[s];
                outside = outside || ((position(s, b).array() < lo.array()).any() ||
                                      (position(s, b).array() > hi.array()).any());
            }
            const Eigen::Vector3d last = position(n - 1, b) - position(0, b);
            m.final_disp[b] = last.norm();
            left += outside ? 1 : 0;
            const Eigen::Vector3d &start = position(0, b);
            units.push_back({{"body", b},
                             {"initial_position", {start.x(), start.y(), start.z()}},
                             {"max_displacement", m.max_disp[b]},
                             {"final_displacement", m.final_disp[b]},
                             {"final_displacement_x", last.x()},
                             {"max_speed", top_speed},
                             {"peak_force_x", m.peak_fx[b]},
                             {"first_move_time", first_move >= 0.0 ? json(first_move) : json(nullptr)},
                             {"moved", m.max_disp[b] > 0.1 * Dn(b)},
                             {"displaced", displaced(m.final_disp[b], b)},
                             {"Dn", Dn(b)},
                             {"left_domain", outside}});
        }
        summary["per_unit"] = units;
        summary["units_left_domain"] = left;
        summary["max_displacement"] = *std::max_element(m.max_disp.begin(), m.max_disp.end());
        return flow(summary, m);
    }

  protected:
    struct Motion {
        std::vector<double> peak_fx, max_disp, final_disp; // per body: N, m, m
    };
    virtual std::string flow(json &summary, const Motion &m) const = 0;
};

// Dam break: the first and the second unit in the flow (by initial x; the
// water column is upstream, at smaller x) and the difference of their peak loads.
class DamBreakAnalysis : public UnitMotionAnalysis {
  public:
    using UnitMotionAnalysis::UnitMotionAnalysis;

  private:
    std::string flow(json &summary, const Motion &m) const override {
        std::vector<std::size_t> order(setup_.bodies.size());
        for (std::size_t b = 0; b < order.size(); ++b)
            order[b] = b;
        std::sort(order.begin(), order.end(),
                  [&](std::size_t i, std::size_t j) { return position(0, i).x() < position(0, j).x(); });
        summary["first_body"] = order[0];
        summary["second_body"] = order[1];
        summary["force_difference"] = m.peak_fx[order[0]] - m.peak_fx[order[1]];
        char text[160];
        std::snprintf(text, sizeof text,
                      "peak F_x %.3g N (first) vs %.3g N (second), max displacement %.3g / %.3g m",
                      m.peak_fx[order[0]], m.peak_fx[order[1]], m.max_disp[order[0]], m.max_disp[order[1]]);
        return text;
    }
};

// Surface height at the first gauge of an armourWaveGauges function object
// (gauge_rows.h): (time, z) rows up to `until` (s).
std::vector<std::pair<double, double>> gauge_series(const fs::path &case_dir, double until) {
    std::vector<std::pair<double, double>> rows;
    for (const std::vector<double> &row : gauge_rows(case_dir))
        if (row.size() >= 2 && row[0] <= until)
            rows.emplace_back(row[0], row[1]);
    return rows;
}

// Waves on units (a platform or an armour slope): the wave at the first
// gauge, crest above the still level and when it first exceeded 5 % of the
// inlet's wave height, what moved before it arrived, and how many units moved
// and were displaced.
class WaveAnalysis : public UnitMotionAnalysis {
  public:
    using UnitMotionAnalysis::UnitMotionAnalysis;

  private:
    std::string flow(json &summary, const Motion &m) const override {
        const SceneFluid &f = fluid();
        const std::size_t n = time_.size(), bodies = setup_.bodies.size();
        const auto gauge = gauge_series(case_dir_, until_);
        double crest = -HUGE_VAL, arrival = -1.0;
        for (const auto &[t, z] : gauge) {
            crest = std::max(crest, z - f.water_level);
            if (arrival < 0.0 && f.wave_height > 0.0 && z - f.water_level > 0.05 * f.wave_height)
                arrival = t;
        }
        summary["wave_height_inlet"] = f.wave_height;
        summary["wave_height_gauge"] = gauge.empty() ? json(nullptr) : json(crest);
        summary["wave_arrival_gauge"] = arrival >= 0.0 ? json(arrival) : json(nullptr);
        // What moved before the wave reached the gauge (settling of the
        // placed units in the still water).
        double before = 0.0;
        for (std::size_t s = 0; s < n && arrival >= 0.0 && time_[s] <= arrival; ++s)
            for (std::size_t b = 0; b < bodies; ++b)
                before = std::max(before, (position(s, b) - position(0, b)).norm());
        summary["max_displacement_before_wave"] = before;
        int moved = 0, displaced_units = 0;
        for (std::size_t b = 0; b < bodies; ++b) {
            moved += m.max_disp[b] > 0.1 * Dn(b) ? 1 : 0;
            displaced_units += displaced(m.final_disp[b], b) ? 1 : 0;
        }
        summary["units_moved"] = moved;               // largest displacement > 0.1 Dn
        summary["units_displaced"] = displaced_units; // final displacement >= displaced_threshold Dn
        char text[160];
        std::snprintf(text, sizeof text, "wave %.3g m at the gauge, %d of %zu units moved, %d displaced",
                      gauge.empty() ? 0.0 : crest, moved, bodies, displaced_units);
        return text;
    }
};

template <class T> std::function<std::unique_ptr<Analysis>(const AnalysisContext &)> factory() {
    return [](const AnalysisContext &c) { return std::make_unique<T>(c); };
}

std::string needs_a_body(const Scene &, const SceneSetup &setup) {
    return setup.bodies.empty() ? "needs a body" : "";
}

std::string needs_one_lighter_cube(const Scene &scene, const SceneSetup &setup) {
    const SceneUnit *u = nullptr;
    for (const auto &unit : scene.units)
        if (!scene.bodies.empty() && unit.name == scene.bodies[0].unit)
            u = &unit;
    if (!u || u->shape != "cube" || setup.bodies.size() != 1)
        return "\"float\" needs exactly one [[body]] of a cube unit";
    if (scene.fluid && u->density >= scene.fluid->fluid_density)
        return "\"float\": the cube's density " + number_text(u->density) +
               " kg/m^3 is not below fluid.fluid_density; it sinks";
    return "";
}

std::string needs_two_bodies(const Scene &, const SceneSetup &setup) {
    if (setup.bodies.size() >= 2)
        return "";
    return "\"dambreak\" compares two units: it needs at least two bodies (has " +
           std::to_string(setup.bodies.size()) + ")";
}

} // namespace

AnalysisStyle buoyancy_analysis_style() {
    return {"buoyancy",
            "a fixed submerged unit: the fluid's vertical load against rho_w g V",
            {"buoyancy_force", "buoyancy_error"},
            {{"buoyancy_force", "buoyancy_expected"}},
            false,
            factory<BuoyancyAnalysis>(),
            needs_a_body};
}

AnalysisStyle float_analysis_style() {
    return {"float",
            "a floating cube: its draft against rho_u / rho_w a",
            {"draft", "draft_error"},
            {{"draft", "draft_expected"}},
            false,
            factory<FloatAnalysis>(),
            needs_one_lighter_cube};
}

AnalysisStyle still_analysis_style() {
    return {"still",
            "units at rest in still water: the largest drift",
            {"max_displacement_over_Dn"},
            {},
            false,
            factory<StillAnalysis>(),
            needs_a_body};
}

AnalysisStyle dambreak_analysis_style() {
    return {"dambreak",
            "units hit by a dam break: peak loads and displacements, first against second",
            {"force_difference", "max_displacement"},
            {},
            false,
            factory<DamBreakAnalysis>(),
            needs_two_bodies};
}

AnalysisStyle platform_analysis_style() {
    return {"platform",
            "units on a platform under a wave: the wave at the gauge, units moved and displaced",
            {"units_moved", "units_displaced"},
            {},
            false,
            factory<WaveAnalysis>(),
            needs_a_body};
}

AnalysisStyle slope_waves_analysis_style() {
    return {"slope_waves",
            "an armour slope under waves: the wave at the gauge, units moved and displaced",
            {"units_moved", "units_displaced"},
            {},
            false,
            factory<WaveAnalysis>(),
            needs_a_body};
}

} // namespace armour
