// The analyses of dry (DEM-only) runs: none, tilt, bounce, slope.
#include "analysis.h"

#include "materials.h"
#include "slope_profile.h"

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
// Besides, the angle at which the unit leaves its seat, whichever way: the
// last still sample before it first stands 0.1 Dn from its seat or has
// turned 10 degrees from it. Its seat is where it first comes to rest (two
// still samples in a row); before that (a unit placed above the plane drops
// straight onto it) only a move of 0.1 Dn across the plane, a fall deeper
// than Dn or a turn counts. A unit on another unit may creep a few tenths of
// a millimetre long before it goes, which the slide angle reads as its
// slide. A unit placed where it cannot rest leaves before it ever comes to
// rest (left_before_resting): the slide and topple angles, read from the
// rest at 1 degree on, would then be read on whatever caught it, so neither
// is reported.
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
        watch_seat(theta, s);
        if (leave_ && !reference_) { // gone before the reference: nothing to read the angles from
            finished_ = true;
            return;
        }
        if (!reference_) {
            // The reference is the unit at rest on the plane: a unit placed
            // above it lands and rocks for a while, and that motion is not sliding.
            if (theta >= 1.0 && still(s)) {
                reference_ = s.pose;
                last_still_slide_ = last_still_turn_ = theta;
            }
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
        summary["leave_angle_deg"] = nullable(leave_);
        summary["left_by"] = leave_ ? json(left_by_) : json(nullptr);
        summary["left_before_resting"] = leave_ && !seat_;
        summary["came_to_rest"] = seat_.has_value();
        char line[192];
        if (leave_ && !seat_)
            std::snprintf(
                line, sizeof line,
                "the unit never came to rest on its seat: it %s off at %.2f deg, still moving from its "
                "landing; no slide or topple angle",
                left_by_.c_str(), *leave_);
        else if (leave_ && !reference_)
            std::snprintf(
                line, sizeof line,
                "the unit %s off its seat at %.2f deg, before the 1 deg from which the slide and topple "
                "are read: neither is reported",
                left_by_.c_str(), *leave_);
        else if (leave_)
            std::snprintf(line, sizeof line, "the unit %s off its seat at %.2f deg", left_by_.c_str(),
                          *leave_);
        else if (!seat_)
            std::snprintf(line, sizeof line, "the unit never came to rest, and never left, up to %.1f deg",
                          max_);
        else
            std::snprintf(line, sizeof line, "the unit stayed on its seat up to %.1f deg", max_);
        return line;
    }

  private:
    double angle(double t) const { return std::min(rate_ * t, max_); } // deg
    // At rest: slower than 5 mm/s and turning slower than 0.05 rad/s (above).
    static bool still(const BodyState &s) {
        return s.velocity.norm() < 5e-3 && s.angular_velocity.norm() < 5e-2;
    }

    // The first sample is where the unit was placed; its seat, where it
    // first rests after that. Before it rests the unit drops straight down
    // as it lands, so only moves across the plane, a fall deeper than Dn and
    // turns count.
    void watch_seat(double theta, const BodyState &s) {
        if (!placed_) {
            placed_ = s.pose;
            return;
        }
        if (leave_)
            return;
        const Pose &from = seat_ ? *seat_ : *placed_;
        const Eigen::Vector3d moved = s.pose.position - from.position;
        const double turned = rotation_deg(s.pose.orientation, from.orientation);
        const bool fell = !seat_ && -moved.z() > Dn_,
                   shifted = seat_ ? moved.norm() > 0.1 * Dn_ : std::hypot(moved.x(), moved.y()) > 0.1 * Dn_;
        if (turned > 10.0 || fell || shifted) {
            leave_ = seat_ ? last_still_seat_ : theta;
            left_by_ = turned > 10.0 ? "toppled" : fell ? "fell" : "slid";
        } else if (still(s)) {
            // Two still samples in a row: one may be the top of a bounce or the turn of a rock.
            if (!seat_ && ++still_samples_ >= 2)
                seat_ = s.pose;
            if (seat_)
                last_still_seat_ = theta;
        } else {
            still_samples_ = 0;
        }
    }

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
    std::optional<Pose> placed_, seat_;
    double last_still_seat_ = 0.0;
    int still_samples_ = 0; // in a row, before the seat
    std::optional<double> leave_;
    std::string left_by_;
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

// Armour layer on the first slope wall, by the Rock Manual's conventions
// (slope_profile.h): thickness from a profiler's envelope, packing density,
// porosity and layer coefficient of the units on the face, at the last
// sample. The run stops once the pile has settled (the scene's settle
// criterion); a pile that never did is reported with settled = false.
class SlopeAnalysis : public Analysis {
  public:
    explicit SlopeAnalysis(const AnalysisContext &c)
        : scene_(c.scene), setup_(c.setup), frame_(slope_frame(c.scene)), settle_(c.scene, c.setup) {}

    void sample(double t, const std::vector<BodyState> &states) override {
        last_ = states;
        settle_.sample(t, states);
    }

    bool finished() const override { return settle_.settled(); }

    std::string write(json &summary) const override {
        summary["settled"] = settle_.settled();
        summary["settled_at"] = nullable(settle_.settled_at());
        summary["settle_max_speed"] = settle_.max_speed();
        summary["settle_kinetic_energy_ratio"] = settle_.kinetic_energy_ratio();
        const json nothing = nullptr;
        for (const char *k : {"packing_density", "porosity", "layer_thickness", "layer_coefficient"})
            summary[k] = nothing;
        if (!frame_)
            return "no slope wall: no layer figures";
        const LayerRegion region = layer_region(*frame_, setup_, last_);
        summary["units_on_slope"] = region.bodies.size();
        summary["units_total"] = last_.size();
        summary["slope_angle_deg"] = std::atan2(1.0, frame_->cot) * 180.0 / kPi;
        if (region.bodies.empty())
            return "no units on the slope";
        const LayerFigures f =
            layer_figures(setup_, region, armour_profile(*frame_, setup_, last_, region), scene_.layers);
        summary["packing_density"] = f.packing_density;
        summary["porosity"] = f.porosity;
        summary["layer_thickness"] = f.thickness;
        summary["layer_coefficient"] = f.layer_coefficient;
        summary["layer_area"] = f.area;
        summary["layers"] = scene_.layers;
        return settle_.settled()
                   ? ""
                   : "the pile did not settle (analysis.settle_speed/settle_energy/settle_span): "
                     "its figures are the last sample's";
    }

  private:
    const Scene &scene_;
    const SceneSetup &setup_;
    std::optional<SlopeFrame> frame_;
    SettleWatch settle_;
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
            "gravity turns about +y; the angles at which the first unit slides, topples and leaves its seat",
            {"slide_angle_deg", "topple_angle_deg", "leave_angle_deg"},
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
            "the layer on the first slope wall once settled: packing density, porosity, thickness, k_t",
            {"packing_density", "porosity", "layer_thickness", "layer_coefficient"},
            {},
            false,
            [](const AnalysisContext &c) { return std::make_unique<SlopeAnalysis>(c); }};
}

} // namespace armour
