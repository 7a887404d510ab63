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

} // namespace

std::vector<BodyInit> random_pattern(const ScenePattern &p, const PatternGrid &grid, int unit,
                                     const UnitTemplate &unit_template, const Collider &collider,
                                     double reach, double Dn, const std::vector<Wall> &walls,
                                     const std::string &key) {
    const SceneWall &slope = *grid.slope;
    // The collided shape as spheres (unit frame): a clump's, or the exact
    // shape's surface points as spheres of radius 0.
    std::vector<std::pair<Eigen::Vector3d, double>> parts;
    if (collider.spheres)
        for (const auto &s : unit_template.clump)
            parts.emplace_back(s.center, s.radius);
    else
        for (const auto &point : collider.points)
            parts.emplace_back(point, 0.0);
    const auto pose = [&](const Eigen::Quaterniond &q, double up, double across, double out) {
        BodyInit b;
        b.unit = unit;
        b.pose.position =
            grid.origin + up * grid.along + across * Eigen::Vector3d::UnitY() + out * grid.normal;
        b.pose.orientation = grid.turn * q;
        return b;
    };

    std::mt19937_64 rng(p.seed);
    const double play = 0.5 * std::max(0.0, grid.spacing - grid.size);
    const double step_top = slope.floor_z + slope.toe_height; // m, z
    // Layer by layer, each layer's slots in a random order (in the grid's
    // order, each unit would lean the same way on the one placed before it).
    struct Slot {
        int layer, row, col, columns;
    };
    std::vector<Slot> slots;
    for (int layer = 0; layer < p.layers; ++layer) {
        const int columns = layer % 2 == 1 && p.columns > 1 ? p.columns - 1 : p.columns;
        for (int row = 0; row < p.rows; ++row)
            for (int col = 0; col < columns; ++col)
                slots.push_back({layer, row, col, columns});
    }
    std::vector<std::size_t> order(slots.size());
    for (std::size_t i = 0; i < order.size(); ++i)
        order[i] = i;
    // Fisher-Yates within each layer (slots [from, to))
    for (std::size_t from = 0; from < order.size();) {
        std::size_t to = from;
        while (to < order.size() && slots[to].layer == slots[from].layer)
            ++to;
        for (std::size_t i = to - from; i > 1; --i)
            std::swap(order[from + i - 1],
                      order[from + std::min(i - 1, static_cast<std::size_t>(uniform01(rng) *
                                                                            static_cast<double>(i)))]);
        from = to;
    }

    std::vector<BodyInit> bodies(slots.size()); // in the grid's order (layer, row, column)
    std::vector<const BodyInit *> placed;
    std::vector<double> top; // m: each placed unit's highest point above the face
    const auto clear = [&](const BodyInit &b) {
        for (const BodyInit *other : placed)
            if ((b.pose.position - other->pose.position).norm() < 2.0 * reach + p.gap &&
                closer_than(b, *other, unit_template, collider, p.gap))
                return false;
        return true;
    };
    // Each slot takes, of kChoices poses that cut no wall and stay in the
    // domain, the first that rests on the face or else the least lifted
    // one: a placer sets a unit where it fits. The grid's slots are too
    // dense for turned units to lie side by side (a cube turned at random is
    // 1.5 Dn across on average, the stability scene's slots 1.24 Dn apart):
    // many rest on their neighbours, and the pile stands loose and thick
    // until the settle (stability_cubes, 5 rows: lifts up to ~5 Dn). The
    // choice tilts the units a little more than uniform draws
    // (test_placement: mean tilt from the slope 37 deg against 32).
    constexpr int kDraws = 1000, kChoices = 8;
    for (const std::size_t k : order) {
        const Slot &slot = slots[k];
        int choices = 0;
        double least = HUGE_VAL, best_top = 0.0; // m: the least lift of a draw, and its top
        for (int draw = 0; draw < kDraws && choices < kChoices && least > 0.0; ++draw) {
            const Eigen::Quaterniond q = uniform_rotation(rng); // in the slope's frame
            const double ds = play * (2.0 * uniform01(rng) - 1.0), dy = play * (2.0 * uniform01(rng) - 1.0);
            // m, of the turned shape from its centre: below and above it, and
            // across the slope to either side
            double below = 0.0, above = 0.0, left = 0.0, right = 0.0;
            for (const auto &[c, radius] : parts) {
                const Eigen::Vector3d t = q * c;
                below = std::max(below, radius - t.z());
                above = std::max(above, radius + t.z());
                left = std::max(left, radius - t.y());
                right = std::max(right, radius + t.y());
            }
            if (left + right + 2.0 * p.gap > slope.width)
                continue;
            // Within the side walls, by gap: an outer slot leaves a turned
            // unit less room than its neighbours do, so it moves inwards.
            const double y = std::clamp((slot.col - 0.5 * (slot.columns - 1)) * grid.spacing + dy,
                                        -0.5 * slope.width + left + p.gap, 0.5 * slope.width - right - p.gap);
            double s = grid.first + (slot.row + (slot.layer % 2) * 0.5) * grid.spacing + ds;
            BodyInit b;
            double n = 0.0;
            const auto at = [&](double height) {
                b = pose(q, s, y, height);
                return clear(b);
            };
            // The lowest height at which it clears the face and every unit
            // placed so far by gap (to 0.005 Dn): at `ceiling` it lies above
            // them all. Not lowered from above: a unit resting on two
            // others would shield the slots beside it, and the next units
            // would stack on it.
            const auto lift = [&] {
                double ceiling = below + p.gap;
                for (const double t : top)
                    ceiling = std::max(ceiling, t + p.gap + below);
                n = below + p.gap;
                if (at(n))
                    return;
                double blocked = n;
                while (n < ceiling && !at(n)) {
                    blocked = n;
                    n += 0.05 * Dn;
                }
                n = std::min(n, ceiling);
                while (n - blocked > 0.005 * Dn) {
                    const double mid = 0.5 * (blocked + n);
                    (at(mid) ? n : blocked) = mid;
                }
                at(n);
            };
            // The toe step: what of the unit lies below the step's top moves
            // landward of its face by gap, up the slope.
            for (int shift = 0; shift < 4; ++shift) {
                lift();
                double short_of = 0.0; // m in x
                for (const auto &[c, radius] : parts) {
                    const Eigen::Vector3d w = b.pose.position + b.pose.orientation * c;
                    if (slope.toe_height > 0.0 && w.z() - radius < step_top + p.gap)
                        short_of = std::max(short_of, slope.toe_x + radius + p.gap - w.x());
                }
                if (short_of <= 0.0)
                    break;
                s += short_of / grid.along.x() + 0.001 * Dn;
            }
            // Inside the domain as the engine collides it, and as build_scene
            // checks it: by the clump, which may protrude beyond the exact shape.
            bool inside = true;
            const auto in_domain = [&](const Eigen::Vector3d &c, double radius) {
                const Eigen::Vector3d w = b.pose.position + b.pose.orientation * c;
                inside = inside && ((w.array() - radius) >= grid.domain_min.array()).all() &&
                         ((w.array() + radius) <= grid.domain_max.array()).all();
            };
            for (const auto &[c, radius] : parts)
                in_domain(c, radius);
            for (const auto &sphere : unit_template.clump)
                in_domain(sphere.center, sphere.radius);
            if (!inside || body_wall_penetration(b, unit_template, collider, walls).first > 0.0)
                continue;
            ++choices;
            if (n - below - p.gap < least) {
                least = n - below - p.gap;
                bodies[k] = b;
                best_top = n + above;
            }
        }
        const std::string where = key + "placement': \"random\": the unit of layer " +
                                  std::to_string(slot.layer + 1) + ", row " + std::to_string(slot.row + 1) +
                                  ", column " + std::to_string(slot.col + 1);
        if (choices == 0)
            throw InputError(where + ": each of " + std::to_string(kDraws) +
                             " random poses cuts a wall or leaves run.domain_min/domain_max; raise spacing, "
                             "or use fewer rows, columns or layers");
        placed.push_back(&bodies[k]);
        top.push_back(best_top);
    }
    return bodies;
}

} // namespace armour
