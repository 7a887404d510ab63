#include "random_pattern.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace armour {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Uniform on [0, 1) from the generator's own bits: the standard
// distributions' algorithms differ between libraries, and a pattern's seed
// should give the same poses with any of them.
double uniform01(std::mt19937_64 &rng) {
    return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// Uniform on SO(3) (Shoemake, "Uniform random rotations", Graphics Gems III, 1992).
Eigen::Quaterniond uniform_rotation(std::mt19937_64 &rng) {
    const double u = uniform01(rng), a = 2.0 * kPi * uniform01(rng), b = 2.0 * kPi * uniform01(rng);
    const double r = std::sqrt(1.0 - u), t = std::sqrt(u);
    return Eigen::Quaterniond(t * std::cos(b), r * std::sin(a), r * std::cos(a), t * std::sin(b));
}

// One sphere of the collided shape, in the unit frame: a clump's, or a point
// of the exact shape's surface as a sphere of radius 0.
using Part = std::pair<Eigen::Vector3d, double>;

// m, of a shape turned by q from its centre: below and above it (out of the
// face), and across the slope to either side.
struct Extents {
    double below = 0.0, above = 0.0, left = 0.0, right = 0.0;
};

Extents turned_extents(const std::vector<Part> &parts, const Eigen::Quaterniond &q) {
    Extents e;
    for (const auto &[c, radius] : parts) {
        const Eigen::Vector3d t = q * c;
        e.below = std::max(e.below, radius - t.z());
        e.above = std::max(e.above, radius + t.z());
        e.left = std::max(e.left, radius - t.y());
        e.right = std::max(e.right, radius + t.y());
    }
    return e;
}

struct Slot {
    int layer, row, col, columns;
};

// The pattern's slots in the grid's order (layer, row, column), its rows
// from first_row up; a layer of odd index has a column fewer, staggered.
std::vector<Slot> grid_slots(const ScenePattern &p) {
    std::vector<Slot> slots;
    for (int layer = 0; layer < p.layers; ++layer) {
        const int columns = layer % 2 == 1 && p.columns > 1 ? p.columns - 1 : p.columns;
        for (int row = p.first_row; row < p.rows; ++row)
            for (int col = 0; col < columns; ++col)
                slots.push_back({layer, row, col, columns});
    }
    return slots;
}

// The slots' order: each run of slots that `together` keeps together (in
// the grid's order, a layer's slots or a row's are adjacent) in a random
// order, Fisher-Yates within [from, to). In the grid's order each unit would
// lean the same way on the one placed before it.
template <class Together>
std::vector<std::size_t> shuffled_within(const std::vector<Slot> &slots, std::mt19937_64 &rng,
                                         Together together) {
    std::vector<std::size_t> order(slots.size());
    for (std::size_t i = 0; i < order.size(); ++i)
        order[i] = i;
    for (std::size_t from = 0; from < order.size();) {
        std::size_t to = from;
        while (to < order.size() && together(slots[to], slots[from]))
            ++to;
        for (std::size_t i = to - from; i > 1; --i)
            std::swap(order[from + i - 1],
                      order[from + std::min(i - 1, static_cast<std::size_t>(uniform01(rng) *
                                                                            static_cast<double>(i)))]);
        from = to;
    }
    return order;
}

// Placement "random": layer by layer, each layer's slots in a random order.
// Placement "seated": layer by layer and row by row from the toe up, each
// row's slots in a random order, so that a unit slid down the face from its
// slot meets the rows below it already in place.
std::vector<std::size_t> placing_order(const std::vector<Slot> &slots, bool seated, std::mt19937_64 &rng) {
    if (seated)
        return shuffled_within(
            slots, rng, [](const Slot &a, const Slot &b) { return a.layer == b.layer && a.row == b.row; });
    return shuffled_within(slots, rng, [](const Slot &a, const Slot &b) { return a.layer == b.layer; });
}

// Sets the units of one pattern slot by slot, each where it clears the face
// and the units placed before it. The random draws come in a fixed order (the
// slots' shuffle, then per draw a rotation and the two offsets): a seed gives
// the same layer on every machine and in every version that keeps the order.
class RandomPlacer {
  public:
    RandomPlacer(const ScenePattern &p, const PatternGrid &grid, int unit, const UnitTemplate &unit_template,
                 const Collider &collider, double reach, double Dn, const std::vector<Wall> &walls,
                 const UnitsBefore &before)
        : p_(p), grid_(grid), slope_(*grid.slope), unit_(unit), template_(unit_template), collider_(collider),
          reach_(reach), Dn_(Dn), walls_(walls), before_(before), rng_(p.seed),
          seated_(p.placement == "seated"), clear_of_toe_(p.clear_of_toe.value_or(false)),
          play_(0.5 * std::max(0.0, grid.spacing - grid.size)),
          step_top_(slope_.floor_z + slope_.toe_height) {
        if (collider.spheres)
            for (const auto &sphere : unit_template.clump)
                parts_.emplace_back(sphere.center, sphere.radius);
        else
            for (const auto &point : collider.points)
                parts_.emplace_back(point, 0.0);
    }

    std::vector<BodyInit> place_all(const std::string &key) {
        const std::vector<Slot> slots = grid_slots(p_);
        const std::vector<std::size_t> order = placing_order(slots, seated_, rng_);
        std::vector<BodyInit> bodies(slots.size()); // in the grid's order (layer, row, column)
        for (const std::size_t k : order) {
            const Slot &slot = slots[k];
            double top = 0.0;
            if (!place(slot, bodies[k], top)) {
                const std::string where = key + "placement': \"" + p_.placement + "\": the unit of layer " +
                                          std::to_string(slot.layer + 1) + ", row " +
                                          std::to_string(slot.row + 1) + ", column " +
                                          std::to_string(slot.col + 1);
                throw InputError(
                    where + ": each of " + std::to_string(kDraws) +
                    " random poses cuts a wall or leaves run.domain_min/domain_max" +
                    (clear_of_toe_ ? " or sets its centre seaward of the toe (clear_of_toe)" : "") +
                    "; raise spacing, or use fewer rows, columns or layers");
            }
            placed_.push_back(&bodies[k]);
            top_.push_back(top);
        }
        return bodies;
    }

  private:
    // Each slot takes, of kChoices poses that cut no wall and stay in the
    // domain, the first that rests on the face or else the least lifted
    // one: a placer sets a unit where it fits. The grid's slots are too
    // dense for turned units to lie side by side (a cube turned at random is
    // 1.5 Dn across on average, the stability scene's slots 1.24 Dn apart):
    // many rest on their neighbours, and the pile stands loose and thick
    // until the settle (stability_cubes, 5 rows: lifts up to ~5 Dn). The
    // choice tilts the units a little more than uniform draws
    // (test_placement: mean tilt from the slope 37 deg against 32).
    static constexpr int kDraws = 1000, kChoices = 8;

    // The slot's pose (`best`) and its highest point above the face (`top`,
    // m); false when no draw gave a pose.
    bool place(const Slot &slot, BodyInit &best, double &top) {
        int choices = 0;
        double least = HUGE_VAL; // m: the least lift of a draw
        for (int draw = 0; draw < kDraws && choices < kChoices && least > 0.0; ++draw) {
            const Eigen::Quaterniond q = uniform_rotation(rng_); // in the slope's frame
            const double ds = play_ * (2.0 * uniform01(rng_) - 1.0),
                         dy = play_ * (2.0 * uniform01(rng_) - 1.0);
            const Extents e = turned_extents(parts_, q);
            if (e.left + e.right + 2.0 * p_.gap > slope_.width)
                continue;
            // Within the side walls, by gap: an outer slot leaves a turned
            // unit less room than its neighbours do, so it moves inwards.
            const double y =
                std::clamp((slot.col - 0.5 * (slot.columns - 1)) * grid_.spacing + dy,
                           -0.5 * slope_.width + e.left + p_.gap, 0.5 * slope_.width - e.right - p_.gap);
            const double s = grid_.first + (slot.row + (slot.layer % 2) * 0.5) * grid_.spacing + ds;
            BodyInit b;
            double n = set_on_face(q, s, y, e.below, b);
            if (!fits(b))
                continue;
            if (seated_)
                n = slide_down(q, s, y, e.below, b, n);
            if (clear_of_toe_ && b.pose.position.x() < slope_.toe_x) // still, after set_on_face's shifts
                continue;
            ++choices;
            if (n - e.below - p_.gap < least) {
                least = n - e.below - p_.gap;
                best = b;
                top = n + e.above;
            }
        }
        return choices > 0;
    }

    bool fits(const BodyInit &b) const {
        return inside_domain(b) && body_wall_penetration(b, template_, collider_, walls_).first <= 0.0;
    }

    // Placement "seated": the pose `b` (at s up the face, height n out of
    // it) slid down the face a tenth of Dn at a time, each time set where it
    // clears the face and the units placed so far, for as long as its centre
    // goes lower: it stops in the first trough, where a unit let down the
    // face would come to rest (at most kMaxSlide Dn from its slot). What the
    // settle would do to the loose pile is done here unit by unit, on the
    // rows below already in place. Returns the height out of the face (m).
    static constexpr double kMaxSlide = 5.0;

    double slide_down(const Eigen::Quaterniond &q, double s, double y, double below, BodyInit &b,
                      double n) const {
        for (int step = 1; step <= static_cast<int>(10.0 * kMaxSlide); ++step) {
            BodyInit lower;
            const double m = set_on_face(q, s - 0.1 * step * Dn_, y, below, lower);
            if (lower.pose.position.z() >= b.pose.position.z() - 1e-6 * Dn_ || !fits(lower))
                break;
            b = lower;
            n = m;
        }
        return n;
    }

    BodyInit pose(const Eigen::Quaterniond &q, double up, double across, double out) const {
        BodyInit b;
        b.unit = unit_;
        b.pose.position =
            grid_.origin + up * grid_.along + across * Eigen::Vector3d::UnitY() + out * grid_.normal;
        b.pose.orientation = grid_.turn * q;
        return b;
    }

    bool clear(const BodyInit &b) const {
        if (before_.clear && !before_.clear(b))
            return false;
        for (const BodyInit *other : placed_)
            if ((b.pose.position - other->pose.position).norm() < 2.0 * reach_ + p_.gap &&
                closer_than(b, *other, template_, collider_, p_.gap))
                return false;
        return true;
    }

    // The pose `b` turned by q at s up the face and y across, lifted clear
    // (lift) and moved up the slope off the toe step's face; returns its
    // height out of the face (m). What of the unit lies below the step's top
    // moves landward of its face by gap (with clear_of_toe, its centre
    // landward of the foot), at most 4 times (16 with clear_of_toe: each
    // shift up lifts the unit onto the units below, seaward again).
    double set_on_face(const Eigen::Quaterniond &q, double s, double y, double below, BodyInit &b) const {
        double n = 0.0;
        for (int shift = 0; shift < (clear_of_toe_ ? 16 : 4); ++shift) {
            n = lift(q, s, y, below, b);
            double short_of = 0.0; // m in x
            for (const auto &[c, radius] : parts_) {
                const Eigen::Vector3d w = b.pose.position + b.pose.orientation * c;
                if (slope_.toe_height > 0.0 && w.z() - radius < step_top_ + p_.gap)
                    short_of = std::max(short_of, slope_.toe_x + radius + p_.gap - w.x());
            }
            // clear_of_toe: a unit lifted out of the lowest rows would stand
            // seaward over the toe (the face's normal leans seaward); a
            // placer sets it higher up the face instead.
            if (clear_of_toe_)
                short_of = std::max(short_of, slope_.toe_x - b.pose.position.x());
            if (short_of <= 0.0)
                break;
            s += short_of / grid_.along.x() + 0.001 * Dn_;
        }
        return n;
    }

    // The lowest height at which the pose clears the face and every unit
    // placed so far by gap (to 0.005 Dn): at `ceiling` it lies above them
    // all. Not lowered from above: a unit resting on two others would shield
    // the slots beside it, and the next units would stack on it. Returns the
    // height (m) and leaves `b` at it.
    double lift(const Eigen::Quaterniond &q, double s, double y, double below, BodyInit &b) const {
        const auto at = [&](double height) {
            b = pose(q, s, y, height);
            return clear(b);
        };
        double ceiling = std::max(below, before_.top + below) + p_.gap;
        for (const double t : top_)
            ceiling = std::max(ceiling, t + p_.gap + below);
        double n = below + p_.gap;
        if (at(n))
            return n;
        double blocked = n;
        while (n < ceiling && !at(n)) {
            blocked = n;
            n += 0.05 * Dn_;
        }
        n = std::min(n, ceiling);
        while (n - blocked > 0.005 * Dn_) {
            const double mid = 0.5 * (blocked + n);
            (at(mid) ? n : blocked) = mid;
        }
        at(n);
        return n;
    }

    // Inside the domain as the engine collides it, and as build_scene checks
    // it: by the clump, which may protrude beyond the exact shape.
    bool inside_domain(const BodyInit &b) const {
        const auto in = [&](const Eigen::Vector3d &c, double radius) {
            const Eigen::Vector3d w = b.pose.position + b.pose.orientation * c;
            return ((w.array() - radius) >= grid_.domain_min.array()).all() &&
                   ((w.array() + radius) <= grid_.domain_max.array()).all();
        };
        bool inside = true;
        for (const auto &[c, radius] : parts_)
            inside = inside && in(c, radius);
        for (const auto &sphere : template_.clump)
            inside = inside && in(sphere.center, sphere.radius);
        return inside;
    }

    const ScenePattern &p_;
    const PatternGrid &grid_;
    const SceneWall &slope_;
    const int unit_;
    const UnitTemplate &template_;
    const Collider &collider_;
    const double reach_, Dn_;
    const std::vector<Wall> &walls_;
    const UnitsBefore &before_;
    std::mt19937_64 rng_;
    const bool seated_;       // placement "seated": toe up, each unit slid down into its trough
    const bool clear_of_toe_; // no centre seaward of the face's foot
    const double play_;       // m: how far a unit may move off its slot's centre, along and across
    const double step_top_;   // m, z: the toe step's top
    std::vector<Part> parts_;
    std::vector<const BodyInit *> placed_;
    std::vector<double> top_; // m: each placed unit's highest point above the face
};

} // namespace

std::vector<BodyInit> random_pattern(const ScenePattern &p, const PatternGrid &grid, int unit,
                                     const UnitTemplate &unit_template, const Collider &collider,
                                     double reach, double Dn, const std::vector<Wall> &walls,
                                     const UnitsBefore &before, const std::string &key) {
    return RandomPlacer(p, grid, unit, unit_template, collider, reach, Dn, walls, before).place_all(key);
}

} // namespace armour
