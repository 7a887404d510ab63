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

namespace {

// Lattice points of spacing h over the shape's box, shifted at random by
// less than a cell; each interior point with the largest sphere that fits
// inside the shape there.
struct Lattice {
    Eigen::Vector3d origin;
    double h = 0.0;
    int nx = 0, ny = 0, nz = 0;
    std::vector<double> radius; // per point; < 0 outside the shape
    std::vector<long> interior; // the points inside

    long index(int i, int j, int k) const { return (static_cast<long>(i) * ny + j) * nz + k; }
    Eigen::Vector3i point_of(long cell) const {
        const int k = static_cast<int>(cell % nz);
        const int j = static_cast<int>((cell / nz) % ny);
        const int i = static_cast<int>(cell / (static_cast<long>(nz) * ny));
        return Eigen::Vector3i(i, j, k);
    }
    Eigen::Vector3d position(long cell) const { return origin + h * point_of(cell).cast<double>(); }

    // Calls visit(cell) for every interior point within the sphere at `cell`.
    template <class Visit> void for_each_in_ball(long cell, Visit &&visit) const {
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
    }
};

Lattice interior_lattice(const Shape &shape, const ShapeQuery &query, std::uint64_t seed,
                         int lattice_points) {
    Lattice l;
    l.h = std::cbrt(shape.props.volume / lattice_points);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> shift(0.0, l.h);
    l.origin =
        query.lower() + Eigen::Vector3d(shift(rng), shift(rng), shift(rng)) - Eigen::Vector3d::Constant(l.h);
    const Eigen::Vector3d extent = query.upper() - l.origin;
    l.nx = static_cast<int>(std::ceil(extent.x() / l.h)) + 1;
    l.ny = static_cast<int>(std::ceil(extent.y() / l.h)) + 1;
    l.nz = static_cast<int>(std::ceil(extent.z() / l.h)) + 1;
    l.radius.assign(static_cast<std::size_t>(l.nx) * l.ny * l.nz, -1.0);
    for (int i = 0; i < l.nx; ++i)
        for (int j = 0; j < l.ny; ++j)
            for (int k = 0; k < l.nz; ++k) {
                const Eigen::Vector3d p = l.origin + l.h * Eigen::Vector3d(i, j, k);
                if (query.inside(p)) {
                    l.radius[l.index(i, j, k)] = query.distance(p);
                    l.interior.push_back(l.index(i, j, k));
                }
            }
    return l;
}

} // namespace

Clump greedy_inscribed(const Shape &shape, const ShapeQuery &query, int spheres, std::uint64_t seed,
                       int lattice_points) {
    const Lattice lattice = interior_lattice(shape, query, seed, lattice_points);
    if (static_cast<int>(lattice.interior.size()) < spheres)
        throw InputError("--spheres: " + std::to_string(spheres) + " spheres exceed the " +
                         std::to_string(lattice.interior.size()) +
                         " candidate centres of the greedy lattice");

    struct Entry {
        double gain;
        long cell;
        bool operator<(const Entry &o) const { return gain < o.gain || (gain == o.gain && cell > o.cell); }
    };
    std::priority_queue<Entry> heap;
    for (long cell : lattice.interior) {
        // Lattice points in a ball of radius r number at most the volume of the
        // ball grown by half a cell diagonal: a valid first upper bound.
        const double grown = lattice.radius[cell] / lattice.h + 0.8660254037844386;
        heap.push({4.18879020478639 * grown * grown * grown, cell});
    }

    Clump clump;
    std::vector<char> covered(lattice.radius.size(), 0), chosen(lattice.radius.size(), 0);
    while (static_cast<int>(clump.size()) < spheres && !heap.empty()) {
        Entry top = heap.top();
        heap.pop();
        if (chosen[top.cell])
            continue;
        double gain = 0.0;
        lattice.for_each_in_ball(top.cell, [&](long c) { gain += covered[c] ? 0.0 : 1.0; });
        if (!heap.empty() && gain < heap.top().gain) {
            heap.push({gain, top.cell});
            continue;
        }
        chosen[top.cell] = 1;
        lattice.for_each_in_ball(top.cell, [&](long c) { covered[c] = 1; });
        clump.push_back({lattice.position(top.cell), lattice.radius[top.cell]});
    }
    return clump;
}

} // namespace armour::detail
