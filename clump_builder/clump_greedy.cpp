// Baseline clump: greedy maximal inscribed spheres.
//
// Candidate centres are interior lattice points, each with the largest sphere
// that fits inside the shape there. Spheres are chosen one at a time to cover
// the most still-uncovered lattice points (lazy greedy: coverage gains only
// shrink, so a stale gain is an upper bound). Spheres never protrude, which is
// why this method always under-fills the shape.
#include "clump_methods.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <random>

namespace armour::detail {

Clump greedy_inscribed(const Shape &shape, const ShapeQuery &query, int spheres, std::uint64_t seed,
                       int lattice_points) {
    const double h = std::cbrt(shape.props.volume / lattice_points);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> shift(0.0, h);
    const Eigen::Vector3d origin =
        query.lower() + Eigen::Vector3d(shift(rng), shift(rng), shift(rng)) - Eigen::Vector3d::Constant(h);
    const Eigen::Vector3d extent = query.upper() - origin;
    const int nx = static_cast<int>(std::ceil(extent.x() / h)) + 1;
    const int ny = static_cast<int>(std::ceil(extent.y() / h)) + 1;
    const int nz = static_cast<int>(std::ceil(extent.z() / h)) + 1;
    auto index = [&](int i, int j, int k) { return (static_cast<long>(i) * ny + j) * nz + k; };

    // radius[cell] < 0 marks lattice points outside the shape.
    std::vector<double> radius(static_cast<std::size_t>(nx) * ny * nz, -1.0);
    std::vector<long> interior;
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j)
            for (int k = 0; k < nz; ++k) {
                const Eigen::Vector3d p = origin + h * Eigen::Vector3d(i, j, k);
                if (query.inside(p)) {
                    radius[index(i, j, k)] = query.distance(p);
                    interior.push_back(index(i, j, k));
                }
            }
    if (static_cast<int>(interior.size()) < spheres)
        throw InputError("--spheres: " + std::to_string(spheres) + " spheres exceed the " +
                         std::to_string(interior.size()) + " candidate centres of the greedy lattice");

    std::vector<char> covered(radius.size(), 0);
    auto point_of = [&](long cell) {
        const int k = static_cast<int>(cell % nz);
        const int j = static_cast<int>((cell / nz) % ny);
        const int i = static_cast<int>(cell / (static_cast<long>(nz) * ny));
        return Eigen::Vector3i(i, j, k);
    };
    // Calls visit(cell) for every interior lattice point within the candidate's sphere.
    auto for_each_in_ball = [&](long cell, auto &&visit) {
        const Eigen::Vector3i c = point_of(cell);
        const double r = radius[cell] / h;
        const int reach = static_cast<int>(std::floor(r));
        for (int di = -reach; di <= reach; ++di) {
            const int i = c.x() + di;
            if (i < 0 || i >= nx)
                continue;
            for (int dj = -reach; dj <= reach; ++dj) {
                const int j = c.y() + dj;
                if (j < 0 || j >= ny)
                    continue;
                const double rest = r * r - di * di - dj * dj;
                if (rest < 0.0)
                    continue;
                const int kreach = static_cast<int>(std::floor(std::sqrt(rest)));
                for (int k = std::max(0, c.z() - kreach); k <= std::min(nz - 1, c.z() + kreach); ++k)
                    if (radius[index(i, j, k)] >= 0.0)
                        visit(index(i, j, k));
            }
        }
    };

    struct Entry {
        double gain;
        long cell;
        bool operator<(const Entry &o) const { return gain < o.gain || (gain == o.gain && cell > o.cell); }
    };
    std::priority_queue<Entry> heap;
    for (long cell : interior) {
        // Lattice points in a ball of radius r number at most the volume of the
        // ball grown by half a cell diagonal: a valid first upper bound.
        const double grown = radius[cell] / h + 0.8660254037844386;
        heap.push({4.18879020478639 * grown * grown * grown, cell});
    }

    Clump clump;
    std::vector<char> chosen(radius.size(), 0);
    while (static_cast<int>(clump.size()) < spheres && !heap.empty()) {
        Entry top = heap.top();
        heap.pop();
        if (chosen[top.cell])
            continue;
        double gain = 0.0;
        for_each_in_ball(top.cell, [&](long c) { gain += covered[c] ? 0.0 : 1.0; });
        if (!heap.empty() && gain < heap.top().gain) {
            heap.push({gain, top.cell});
            continue;
        }
        chosen[top.cell] = 1;
        for_each_in_ball(top.cell, [&](long c) { covered[c] = 1; });
        const Eigen::Vector3i c = point_of(top.cell);
        clump.push_back({origin + h * c.cast<double>(), radius[top.cell]});
    }
    return clump;
}

} // namespace armour::detail
