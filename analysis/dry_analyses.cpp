// The analyses of dry (DEM-only) runs: none, tilt, bounce, slope.
#include "analysis.h"

#include "materials.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <optional>

namespace armour {
namespace {

using nlohmann::json;

constexpr double kPi = 3.14159265358979323846;

double rotation_deg(const Eigen::Quaterniond &a, const Eigen::Quaterniond &b) {
    return 2.0 * std::acos(std::min(1.0, std::abs(a.dot(b)))) * 180.0 / kPi;
}

json nullable(const std::optional<double> &v) {
    return v ? json(*v) : json(nullptr);
}

class NoAnalysis : public Analysis {
  public:
    void sample(double, const std::vector<BodyState> &) override {}
    std::string write(json &) const override { return ""; }
};

// Tilt: gravity turns about +y; the angle at which the unit first slides
// (moves along x by 1 % of Dn without turning) and first topples (turns by
// 10 degrees), each taken back to the last sample at which it was still at
// rest: slower than 5 mm/s (soft contacts creep at ~0.1-1 mm/s well before
// sliding) or turning slower than 0.05 rad/s. A slide is taken back further,
// to its onset: under a tilt rising at a steady rate a Coulomb slide starts
// with v = k (theta - theta0)^2, so sqrt(v) is linear in theta and the line
// through the first two moving samples meets zero at theta0. At 5 deg/s the
// last still sample lies 0.26-0.51 deg after the onset (v reaches 5 mm/s
// 0.5 deg after it), which alone would eat a 0.5 deg tolerance. The line is
// trusted only where its slope is a Coulomb block's, sqrt(v) growing at
// sqrt(g w / (2 cos theta)) per second (w: tilt rate, rad/s), within a factor
// of 2: a soft clump that creeps into its slide (sqrt(v) growing 4 times
// slower at 20 deg/s) keeps the last still sample.
class TiltAnalysis : public Analysis {
  public:
    explicit TiltAnalysis(const AnalysisContext &c)
        : rate_(c.scene.tilt_rate), max_(c.scene.tilt_max), g_(c.scene.gravity.norm()),
          Dn_(c.setup.unit_Dn[static_cast<std::size_t>(c.setup.bodies[0].unit)]) {
        const int wall_material = c.setup.walls.empty() ? 0 : c.setup.walls[0].material;
        mu_ = pair_value(c.setup.settings,
                         c.setup.units[static_cast<std::size_t>(c.setup.bodies[0].unit)].material,
                         wall_material, &Material::friction, &MaterialPair::friction);
    }

    // Gravity turns in increments of at most 0.1 degree.
    double before_advance(double t, RigidBodyEngine &engine) override {
        const double theta = angle(t) * kPi / 180.0;
        engine.set_gravity(Eigen::Vector3d(g_ * std::sin(theta), 0.0, -g_ * std::cos(theta)));
        return 0.1 / std::max(rate_, 1e-12);
    }

    void sample(double t, const std::vector<BodyState> &states) override {
        const BodyState &s = states[0];
        const double theta = angle(t);
        if (!reference_) {
            // The reference is the unit at rest on the plane: a unit placed
            // above it lands and rocks for a while, and that motion is not sliding.
            if (theta >= 1.0 && s.velocity.norm() < 5e-3 && s.angular_velocity.norm() < 5e-2)
                reference_ = s.pose;
            return;
        }
        const double moved = s.pose.position.x() - reference_->position.x();
        const double turned = rotation_deg(s.pose.orientation, reference_->orientation);
        if (std::abs(s.velocity.x()) < 5e-3 && !slide_) {
            last_still_slide_ = theta;
            moving_.clear();
        } else if (!slide_ && moving_.size() < 2 && theta < max_) {
            moving_.push_back({theta, std::abs(s.velocity.x())});
        }
        if (s.angular_velocity.norm() < 5e-2 && !topple_)
            last_still_turn_ = theta;
        if (!slide_ && moved > 0.01 * Dn_ && turned < 5.0)
            slide_ = slide_onset();
        if (!topple_ && turned > 10.0)
            topple_ = last_still_turn_;
        // Slid a whole Dn or turned past 45 degrees: nothing more to learn.
        finished_ = (slide_ && moved > Dn_) || (topple_ && turned > 45.0);
    }

    bool finished() const override { return finished_; }

    std::string write(json &summary) const override {
        summary["mu"] = mu_;
        summary["slide_angle_deg"] = nullable(slide_);
        summary["topple_angle_deg"] = nullable(topple_);
        summary["slide_angle_analytic_deg"] = std::atan(mu_) * 180.0 / kPi;
        return "";
    }

  private:
    double angle(double t) const { return std::min(rate_ * t, max_); } // deg

    // theta0 from the first two moving samples (see above), kept between one
    // degree before the last still sample and that sample.
    double slide_onset() const {
        if (moving_.size() < 2)
            return last_still_slide_;
        const auto &[t1, v1] = moving_[0];
        const auto &[t2, v2] = moving_[1];
        const double r1 = std::sqrt(v1), r2 = std::sqrt(v2);
        if (!(r2 > r1) || !(t2 > t1))
            return last_still_slide_;
        const double w = rate_ * kPi / 180.0; // rad/s
        const double coulomb = std::sqrt(g_ * w / (2.0 * std::cos(t1 * kPi / 180.0))),
                     slope = (r2 - r1) / ((t2 - t1) / rate_); // sqrt(m/s) per s
        if (!(slope > 0.5 * coulomb && slope < 2.0 * coulomb))
            return last_still_slide_;
        const double onset = t1 - r1 * (t2 - t1) / (r2 - r1);
        return std::clamp(onset, last_still_slide_ - 1.0, last_still_slide_);
    }
    double rate_, max_, g_, Dn_, mu_ = 0.0;
    std::optional<Pose> reference_;
    double last_still_slide_ = 0.0, last_still_turn_ = 0.0;
    std::vector<std::pair<double, double>> moving_; // (deg, m/s) since the last still sample, first two
    std::optional<double> slide_, topple_;
    bool finished_ = false;
};

// Bounce: the first body's lowest sphere falls `drop` onto the first plane
// wall; the apex of its first rebound, from the moment contact ends and it
// rises until it falls again.
class BounceAnalysis : public Analysis {
  public:
    explicit BounceAnalysis(const AnalysisContext &c) {
        const BodyInit &b = c.setup.bodies[0];
        double low = HUGE_VAL;
        for (const auto &s : c.setup.units[static_cast<std::size_t>(b.unit)].clump)
            low = std::min(low, (b.pose.orientation * s.center).z() - s.radius);
        lowest_offset_ = -low;
        for (const auto &w : c.scene.walls)
            if (w.type == "plane") {
                floor_z_ = w.point.z();
                break;
            }
        drop_ = b.pose.position.z() + low - floor_z_;
    }

    void sample(double, const std::vector<BodyState> &states) override {
        const BodyState &s = states[0];
        if (done_)
            return;
        const double bottom = s.pose.position.z() - lowest_offset_ - floor_z_;
        if (s.contact_force.norm() > 0.0)
            contact_ = true;
        if (contact_ && s.contact_force.norm() == 0.0 && s.velocity.z() > 0.0)
            rising_ = true;
        if (rising_) {
            apex_ = std::max(apex_, bottom);
            if (s.velocity.z() < 0.0)
                done_ = true;
        }
    }

    std::string write(json &summary) const override {
        summary["drop_height"] = drop_;
        summary["rebound_height"] = done_ ? json(apex_) : json(nullptr);
        summary["bounce_height_ratio"] = done_ ? json(apex_ / drop_) : json(nullptr);
        summary["restitution_effective"] =
            done_ ? json(std::sqrt(std::max(0.0, apex_ / drop_))) : json(nullptr);
        return "";
    }

  private:
    double floor_z_ = 0.0, drop_ = 0.0, lowest_offset_ = 0.0;
    bool contact_ = false, rising_ = false, done_ = false;
    double apex_ = -HUGE_VAL;
};

// Armour layer on the first slope wall, from the final poses. With the units'
// centres in slope coordinates (s up the slope, y across), the covered area is
// A = (s_max - s_min + Dn) (y_max - y_min + Dn), capped at the slope's width;
// packing density = N Dn^2 / A (the coastal-engineering definition, units per
// Dn^2 of slope) and porosity = 1 - N V / (A t), with t the layer thickness:
// the highest sphere surface above the slope plane.
class SlopeAnalysis : public Analysis {
  public:
    explicit SlopeAnalysis(const AnalysisContext &c) : scene_(c.scene), setup_(c.setup) {}

    void sample(double, const std::vector<BodyState> &states) override { last_ = states; }

    std::string write(json &summary) const override {
        summary.update(figures());
        return "";
    }

  private:
    json figures() const {
        const Scene &scene = scene_;
        const SceneSetup &setup = setup_;
        const std::vector<BodyState> &states = last_;
        const SceneWall *slope = nullptr;
        for (const auto &w : scene.walls)
            if (w.type == "slope") {
                slope = &w;
                break;
            }
        if (!slope)
            return {{"units", states.size()}, {"packing_density", nullptr}, {"porosity", nullptr}};
        const double alpha = std::atan2(1.0, slope->cot);
        const Eigen::Vector3d origin(slope->toe_x, 0.0, slope->floor_z);
        const Eigen::Vector3d along(std::cos(alpha), 0.0, std::sin(alpha)),
            normal(-std::sin(alpha), 0.0, std::cos(alpha));
        double s_min = HUGE_VAL, s_max = -HUGE_VAL, y_min = HUGE_VAL, y_max = -HUGE_VAL, top = 0.0,
               volume = 0.0, Dn = 0.0;
        int n = 0;
        for (std::size_t i = 0; i < states.size(); ++i) {
            const int unit = setup.bodies[i].unit;
            const Eigen::Vector3d c = states[i].pose.position - origin;
            if (c.dot(along) < -setup.unit_Dn[unit] || c.dot(normal) < -setup.unit_Dn[unit])
                continue; // not on the slope (e.g. fell off seaward)
            ++n;
            s_min = std::min(s_min, c.dot(along));
            s_max = std::max(s_max, c.dot(along));
            y_min = std::min(y_min, c.y());
            y_max = std::max(y_max, c.y());
            volume += setup.units[unit].props.volume;
            Dn = std::max(Dn, setup.unit_Dn[unit]);
            for (const auto &sph : setup.units[unit].clump) {
                const Eigen::Vector3d p =
                    states[i].pose.position + states[i].pose.orientation * sph.center - origin;
                top = std::max(top, p.dot(normal) + sph.radius);
            }
        }
        if (n == 0)
            return {{"units", 0}, {"packing_density", nullptr}, {"porosity", nullptr}};
        const double area = (s_max - s_min + Dn) * std::min(slope->width, y_max - y_min + Dn);
        return {{"units", n},
                {"units_total", states.size()},
                {"packing_density", n * Dn * Dn / area},
                {"porosity", 1.0 - volume / (area * top)},
                {"layer_area", area},
                {"layer_thickness", top},
                {"slope_angle_deg", alpha * 180.0 / kPi}};
    }

    const Scene &scene_;
    const SceneSetup &setup_;
    std::vector<BodyState> last_;
};

} // namespace

AnalysisStyle none_analysis_style() {
    return {"none", "no figures beyond the run's own (time, energy, cost)",
            {},     {},
            false,  [](const AnalysisContext &) { return std::make_unique<NoAnalysis>(); }};
}

AnalysisStyle tilt_analysis_style() {
    return {"tilt",
            "gravity turns about +y; the angles at which the first unit slides and topples",
            {"slide_angle_deg", "topple_angle_deg"},
            {{"slide_angle_deg", "slide_angle_analytic_deg"}},
            true,
            [](const AnalysisContext &c) { return std::make_unique<TiltAnalysis>(c); }};
}

AnalysisStyle bounce_analysis_style() {
    return {"bounce",
            "the first unit dropped on the first plane wall: rebound height over drop height",
            {"bounce_height_ratio"},
            {},
            false,
            [](const AnalysisContext &c) { return std::make_unique<BounceAnalysis>(c); }};
}

AnalysisStyle slope_analysis_style() {
    return {"slope",
            "the layer on the first slope wall at the end: packing density and porosity",
            {"packing_density", "porosity"},
            {},
            false,
            [](const AnalysisContext &c) { return std::make_unique<SlopeAnalysis>(c); }};
}

} // namespace armour
