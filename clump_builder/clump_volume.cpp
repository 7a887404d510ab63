// Mass properties of a union of spheres.
//
// Along each grid line parallel to x the union is a set of intervals whose
// ends are known exactly, so the x-integrals are exact and only the (y, z)
// plane is discretised (midpoint rule). Overlaps are counted once.
#include "clump.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace armour {

namespace {

struct Moments {
    double v = 0, x = 0, y = 0, z = 0;                     // integrals of 1, x, y, z
    double xx = 0, yy = 0, zz = 0, xy = 0, xz = 0, yz = 0; // second moments
};

Moments union_moments(const Clump &clump, int lines) {
    Moments m;
    if (clump.empty())
        return m;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL);
    Eigen::Vector3d hi = -lo;
    for (const auto &s : clump) {
        lo = lo.cwiseMin(s.center - Eigen::Vector3d::Constant(s.radius));
        hi = hi.cwiseMax(s.center + Eigen::Vector3d::Constant(s.radius));
    }
    const double hy = (hi.y() - lo.y()) / lines;
    const double hz = (hi.z() - lo.z()) / lines;
    const double cell = hy * hz;

    std::vector<const Sphere *> row;
    std::vector<std::pair<double, double>> chords;
    for (int iy = 0; iy < lines; ++iy) {
        const double y = lo.y() + (iy + 0.5) * hy;
        row.clear();
        for (const auto &s : clump)
            if (std::abs(y - s.center.y()) < s.radius)
                row.push_back(&s);
        for (int iz = 0; iz < lines; ++iz) {
            const double z = lo.z() + (iz + 0.5) * hz;
            chords.clear();
            for (const Sphere *s : row) {
                const double dy = y - s->center.y();
                const double dz = z - s->center.z();
                const double h2 = s->radius * s->radius - dy * dy - dz * dz;
                if (h2 > 0.0) {
                    const double h = std::sqrt(h2);
                    chords.emplace_back(s->center.x() - h, s->center.x() + h);
                }
            }
            if (chords.empty())
                continue;
            std::sort(chords.begin(), chords.end());
            double a = chords[0].first;
            double b = chords[0].second;
            auto flush = [&](double a0, double b0) {
                const double len = b0 - a0;
                const double sx = 0.5 * (b0 * b0 - a0 * a0);
                const double sxx = (b0 * b0 * b0 - a0 * a0 * a0) / 3.0;
                m.v += len * cell;
                m.x += sx * cell;
                m.y += y * len * cell;
                m.z += z * len * cell;
                m.xx += sxx * cell;
                m.yy += y * y * len * cell;
                m.zz += z * z * len * cell;
                m.xy += y * sx * cell;
                m.xz += z * sx * cell;
                m.yz += y * z * len * cell;
            };
            for (std::size_t k = 1; k < chords.size(); ++k) {
                if (chords[k].first > b) {
                    flush(a, b);
                    a = chords[k].first;
                    b = chords[k].second;
                } else {
                    b = std::max(b, chords[k].second);
                }
            }
            flush(a, b);
        }
    }
    return m;
}

} // namespace

double clump_volume(const Clump &clump, int lines) {
    return union_moments(clump, lines).v;
}

MassProperties clump_mass_properties(const Clump &clump, double density, int lines) {
    const Moments m = union_moments(clump, lines);
    MassProperties p;
    p.density = density;
    p.volume = m.v;
    p.mass = density * m.v;
    if (m.v <= 0.0)
        return p;
    p.centroid = Eigen::Vector3d(m.x, m.y, m.z) / m.v;
    Eigen::Matrix3d second; // density-free integral of r r^T
    second << m.xx, m.xy, m.xz, m.xy, m.yy, m.yz, m.xz, m.yz, m.zz;
    second -= m.v * p.centroid * p.centroid.transpose(); // about the centroid
    p.inertia = density * (second.trace() * Eigen::Matrix3d::Identity() - second);
    set_principal(p);
    return p;
}

} // namespace armour
