// Optimised clump: fit the clump surface to the exact surface.
//
// The clump's surface is the zero level of f(p) = min_j (|p - c_j| - r_j).
// The objective, on the builder's own samples, is
//     mean_surface f^2 + 0.5 mean_interior max(0, f)^2 + 0.5 mean_exterior max(0, -f)^2
// i.e. exact-surface points should lie on the clump surface, interior points
// should be covered and exterior points near the shape left empty. Each sample
// depends on one sphere only (its arg-min), so the Gauss-Newton system is block
// diagonal, 4 x 4 per sphere, and one Levenberg-Marquardt step costs one pass
// over samples x spheres. Spheres that no sample depends on are moved to the
// largest uncovered hole. A final common radius offset matches the volume.
#include "clump_methods.h"
#include "clump_support.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace armour::detail {

namespace {

enum class Role : unsigned char { surface, interior, exterior };

struct Samples {
    std::vector<Eigen::Vector3d> points;
    std::vector<Role> role;
    std::vector<double> weight;
};

Samples make_samples(const Shape &shape, const ShapeQuery &query, int spheres, std::uint64_t seed) {
    const double Dn = shape.Dn();
    const int surface_count = 2000 + 40 * spheres;
    const int volume_count = 1500 + 20 * spheres;
    Samples s;
    std::vector<Eigen::Vector3d> normals;
    const auto surface = sample_surface(shape.mesh, surface_count, seed, &normals);

    std::mt19937_64 rng(seed ^ 0x9e3779b97f4a7c15ULL);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Eigen::Vector3d> interior, exterior;
    // Half of the volume samples sit in a shell of 0.15 Dn on either side of
    // the surface, where the clump's errors are; the other half fill the body.
    for (std::size_t k = 0; k < surface.size() && static_cast<int>(interior.size()) < volume_count / 2; ++k) {
        const Eigen::Vector3d p = surface[k] - normals[k] * (0.15 * Dn * unit(rng));
        if (query.inside(p))
            interior.push_back(p);
    }
    for (std::size_t k = 0; k < surface.size() && static_cast<int>(exterior.size()) < volume_count; ++k) {
        const Eigen::Vector3d p = surface[k] + normals[k] * (0.15 * Dn * unit(rng));
        if (!query.inside(p))
            exterior.push_back(p);
    }
    const Eigen::Vector3d lo = query.lower(), span = query.upper() - query.lower();
    for (int tries = 0; static_cast<int>(interior.size()) < volume_count && tries < 1000 * volume_count;
         ++tries) {
        const Eigen::Vector3d p = lo + span.cwiseProduct(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
        if (query.inside(p))
            interior.push_back(p);
    }
    auto add = [&](const std::vector<Eigen::Vector3d> &pts, Role role, double group_weight) {
        for (const auto &p : pts) {
            s.points.push_back(p);
            s.role.push_back(role);
            s.weight.push_back(group_weight / static_cast<double>(pts.size()));
        }
    };
    add(surface, Role::surface, 1.0);
    add(interior, Role::interior, 0.5);
    add(exterior, Role::exterior, 0.5);
    return s;
}

// Residual of one sample given f: what the objective squares.
double residual(Role role, double f) {
    switch (role) {
    case Role::surface:
        return f;
    case Role::interior:
        return f > 0.0 ? f : 0.0;
    case Role::exterior:
        return f < 0.0 ? f : 0.0;
    }
    return 0.0;
}

struct Fit {
    std::vector<double> f;  // min_j (|p - c_j| - r_j) per sample
    std::vector<int> owner; // its arg-min
    double loss = 0.0;
};

void evaluate(const Clump &clump, const Samples &s, Fit &fit) {
    const std::size_t n = clump.size();
    std::vector<double> cx(n), cy(n), cz(n), r(n);
    for (std::size_t j = 0; j < n; ++j) {
        cx[j] = clump[j].center.x();
        cy[j] = clump[j].center.y();
        cz[j] = clump[j].center.z();
        r[j] = clump[j].radius;
    }
    fit.f.resize(s.points.size());
    fit.owner.resize(s.points.size());
    fit.loss = 0.0;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
        const double px = s.points[i].x(), py = s.points[i].y(), pz = s.points[i].z();
        double best = std::numeric_limits<double>::infinity();
        int owner = 0;
        for (std::size_t j = 0; j < n; ++j) {
            const double dx = px - cx[j], dy = py - cy[j], dz = pz - cz[j];
            const double d = std::sqrt(dx * dx + dy * dy + dz * dz) - r[j];
            if (d < best) {
                best = d;
                owner = static_cast<int>(j);
            }
        }
        fit.f[i] = best;
        fit.owner[i] = owner;
        const double e = residual(s.role[i], best);
        fit.loss += s.weight[i] * e * e;
    }
}

// Moves spheres that no sample depends on (or that shrank below min_radius)
// to the interior sample farthest from the clump. Returns how many moved.
// The first `fixed` spheres stay.
int respawn_idle(Clump &clump, const Samples &s, const Fit &fit, double min_radius, std::size_t fixed) {
    std::vector<int> users(clump.size(), 0);
    for (std::size_t i = 0; i < s.points.size(); ++i)
        if (residual(s.role[i], fit.f[i]) != 0.0 || s.role[i] == Role::interior)
            ++users[fit.owner[i]];
    std::vector<double> gap(fit.f);
    int moved = 0;
    for (std::size_t j = fixed; j < clump.size(); ++j) {
        if (users[j] > 0 && clump[j].radius >= min_radius)
            continue;
        std::size_t worst = s.points.size();
        for (std::size_t i = 0; i < s.points.size(); ++i)
            if (s.role[i] == Role::interior && gap[i] > 0.0 &&
                (worst == s.points.size() || gap[i] > gap[worst]))
                worst = i;
        if (worst == s.points.size())
            break; // the interior is covered: nothing better to do with the sphere
        clump[j] = {s.points[worst], std::max(gap[worst], min_radius)};
        // Later respawns in this round go elsewhere.
        for (std::size_t i = 0; i < s.points.size(); ++i)
            gap[i] = std::min(gap[i], (s.points[i] - clump[j].center).norm() - clump[j].radius);
        ++moved;
    }
    return moved;
}

} // namespace

Clump optimise_clump(const Shape &shape, const ShapeQuery &query, Clump clump, std::uint64_t seed,
                     std::size_t fixed) {
    const double Dn = shape.Dn();
    // Spheres below kMinSphereRadius are moved instead.
    const double min_radius = kMinSphereRadius * Dn;
    const double max_step = 0.05 * Dn;
    const Samples samples = make_samples(shape, query, static_cast<int>(clump.size()), seed);

    Fit fit, trial_fit;
    evaluate(clump, samples, fit);
    double damping = 1e-3;
    int respawn_rounds = 0;
    double loss_at_check = fit.loss;
    for (int iteration = 0; iteration < 300; ++iteration) {
        std::vector<Eigen::Matrix4d> normal(clump.size(), Eigen::Matrix4d::Zero());
        std::vector<Eigen::Vector4d> gradient(clump.size(), Eigen::Vector4d::Zero());
        for (std::size_t i = 0; i < samples.points.size(); ++i) {
            const double e = residual(samples.role[i], fit.f[i]);
            if (e == 0.0)
                continue;
            const int j = fit.owner[i];
            Eigen::Vector3d u = samples.points[i] - clump[j].center;
            const double len = u.norm();
            u = len > 0.0 ? Eigen::Vector3d(u / len) : Eigen::Vector3d::UnitX();
            const Eigen::Vector4d J(-u.x(), -u.y(), -u.z(), -1.0); // d e / d (c, r)
            normal[j] += samples.weight[i] * J * J.transpose();
            gradient[j] += samples.weight[i] * e * J;
        }
        Clump trial = clump;
        for (std::size_t j = fixed; j < clump.size(); ++j) {
            Eigen::Matrix4d A = normal[j];
            A.diagonal() += damping * normal[j].diagonal() + Eigen::Vector4d::Constant(1e-12);
            Eigen::Vector4d step = -A.ldlt().solve(gradient[j]);
            if (!step.allFinite()) // a step of NaN times 0 would still be NaN
                step.setZero();
            const double size = step.norm();
            if (size > max_step)
                step *= max_step / size;
            trial[j].center += step.head<3>();
            trial[j].radius = std::max(trial[j].radius + step[3], 0.5 * min_radius);
        }
        evaluate(trial, samples, trial_fit);
        if (trial_fit.loss < fit.loss) {
            clump.swap(trial);
            std::swap(fit, trial_fit);
            damping = std::max(damping / 3.0, 1e-7);
        } else {
            damping *= 5.0;
        }
        if (iteration % 15 == 14) {
            if (respawn_rounds < 8) {
                Clump moved = clump;
                if (respawn_idle(moved, samples, fit, min_radius, fixed) > 0) {
                    ++respawn_rounds;
                    evaluate(moved, samples, trial_fit);
                    if (trial_fit.loss < fit.loss) {
                        clump.swap(moved);
                        std::swap(fit, trial_fit);
                        damping = 1e-3;
                        loss_at_check = std::numeric_limits<double>::infinity();
                    }
                }
            }
            if (fit.loss > (1.0 - 1e-4) * loss_at_check || damping > 1e8)
                break; // converged: under 0.01 % progress in 15 iterations
            loss_at_check = fit.loss;
        }
    }
    for (std::size_t j = fixed; j < clump.size(); ++j)
        clump[j].radius = std::max(clump[j].radius, min_radius);
    return match_volume(std::move(clump), shape.props.volume, fixed);
}

Clump match_volume(Clump clump, double volume, std::size_t fixed) {
    if (clump.size() <= fixed)
        return clump;
    double smallest = HUGE_VAL, largest = 0.0;
    for (std::size_t j = fixed; j < clump.size(); ++j) {
        const Sphere &s = clump[j];
        smallest = std::min(smallest, s.radius);
        largest = std::max(largest, s.radius);
    }
    auto volume_at = [&](double offset) {
        Clump c = clump;
        for (std::size_t j = fixed; j < c.size(); ++j)
            c[j].radius += offset;
        return clump_volume(c, 300);
    };
    // The union volume grows monotonically with the offset: bracket, then
    // regula falsi (Illinois) to 1e-5 relative.
    double lo = -0.9 * smallest, hi = 0.0;
    double vlo = volume_at(lo), vhi = volume_at(hi);
    while (vhi < volume) {
        lo = hi;
        vlo = vhi;
        hi += 0.25 * largest;
        vhi = volume_at(hi);
    }
    if (vlo > volume)
        return clump; // even 10 % radii overfill: leave it, the evaluator reports it
    int side = 0;
    double offset = hi;
    for (int it = 0; it < 60; ++it) {
        offset = (lo * (vhi - volume) - hi * (vlo - volume)) / (vhi - vlo);
        const double v = volume_at(offset);
        if (std::abs(v - volume) <= 1e-5 * volume)
            break;
        if (v < volume) {
            lo = offset;
            vlo = v;
            if (side == -1)
                vhi = volume + 0.5 * (vhi - volume);
            side = -1;
        } else {
            hi = offset;
            vhi = v;
            if (side == 1)
                vlo = volume + 0.5 * (vlo - volume);
            side = 1;
        }
    }
    for (std::size_t j = fixed; j < clump.size(); ++j)
        clump[j].radius += offset;
    return clump;
}

void hold_inside(Clump &clump, const Shape &shape, const ShapeQuery &query, std::size_t fixed) {
    // No sphere ends below the optimiser's smallest (kMinSphereRadius), which
    // would shrink the DEM's step: one whose centre lies shallower than that
    // moves towards the centroid until it lies that deep.
    const double min_radius = kMinSphereRadius * shape.Dn();
    const Eigen::Vector3d centre = shape.props.centroid;
    for (std::size_t j = fixed; j < clump.size(); ++j) {
        Sphere &s = clump[j];
        const double depth = std::min(s.radius, min_radius);
        if (-query.signed_distance(s.center) < depth) {
            double lo = 0.0, hi = 1.0; // fraction of the way to the centroid
            for (int it = 0; it < 40; ++it) {
                const double mid = 0.5 * (lo + hi);
                (-query.signed_distance(s.center + mid * (centre - s.center)) < depth ? lo : hi) = mid;
            }
            s.center += hi * (centre - s.center);
        }
        const double held = -query.signed_distance(s.center);
        if (!(held > 0.0)) // the centroid outside the shape (a ring, say): no way in along this line
            throw InputError("--method inscribed: a sphere cannot be moved inside the shape towards its "
                             "centroid, which lies outside it; use --method optimised");
        s.radius = std::min(s.radius, held);
    }
}

std::string method_name(ClumpMethod method) {
    switch (method) {
    case ClumpMethod::greedy:
        return "greedy";
    case ClumpMethod::inscribed:
        return "inscribed";
    default:
        return "optimised";
    }
}

ClumpMethod parse_method(const std::string &name) {
    if (name == "greedy")
        return ClumpMethod::greedy;
    if (name == "optimised" || name == "optimized")
        return ClumpMethod::optimised;
    if (name == "inscribed")
        return ClumpMethod::inscribed;
    throw InputError("--method: unknown clump method '" + name + "' (known: greedy, optimised, inscribed)");
}

} // namespace armour::detail

namespace armour {

std::string method_name(ClumpMethod method) {
    return detail::method_name(method);
}
ClumpMethod parse_method(const std::string &name) {
    return detail::parse_method(name);
}

namespace {
// With fewer body spheres than this the fit is worse than the greedy
// baseline's (cube, 8 corners and 2 body spheres: surface RMS 7.2 % Dn
// against 6.9 %).
constexpr std::size_t kMinBodySpheres = 8;

// The corners of every resting face and, with edge_spheres > 0, that many
// points along each of their edges. A hull edge of a concave unit (a
// dolos's, from one fluke to another) may cross open air: a sphere there
// would be a contact surface the unit does not have, so only the points on
// the unit's surface are kept.
std::vector<SupportCorner> supports_of(const std::vector<RestingFace> &faces, int edge_spheres, double Dn,
                                       const ShapeQuery &query) {
    std::vector<SupportCorner> corners = support_corners(faces, Dn);
    if (edge_spheres > 0) {
        const std::size_t corner_count = corners.size();
        add_edge_supports(corners, faces, edge_spheres, Dn);
        corners.erase(std::remove_if(corners.begin() + static_cast<std::ptrdiff_t>(corner_count),
                                     corners.end(),
                                     [&](const SupportCorner &k) {
                                         return std::abs(query.signed_distance(k.vertex)) > 1e-6 * Dn;
                                     }),
                      corners.end());
    }
    return corners;
}
} // namespace

int fewest_spheres_with_edges(const Shape &shape, int edge_spheres) {
    const double Dn = shape.Dn();
    const auto faces = resting_faces(shape.mesh, shape.props.centroid, Dn);
    return static_cast<int>(supports_of(faces, edge_spheres, Dn, ShapeQuery(shape.mesh)).size() +
                            kMinBodySpheres);
}

Clump build_clump(const Shape &shape, ClumpMethod method, int spheres, std::uint64_t seed, int edge_spheres) {
    if (spheres < 1)
        throw InputError("--spheres: the number of spheres must be >= 1 (got " + std::to_string(spheres) +
                         ")");
    if (edge_spheres < 0)
        throw InputError("--edge-spheres: must be >= 0 (got " + std::to_string(edge_spheres) + ")");
    if (edge_spheres > 0 && method == ClumpMethod::greedy)
        throw InputError("--edge-spheres: the greedy clump has no support spheres; use --method optimised or "
                         "inscribed");
    const ShapeQuery query(shape.mesh);
    if (method == ClumpMethod::greedy)
        return detail::greedy_inscribed(shape, query, spheres, seed);
    // The optimised clump stands on the corners of every resting face
    // (clump_support.h) when it has a sphere for each corner (and edge
    // sphere) and at least kMinBodySpheres for the body; the body's spheres
    // are fitted around them.
    const double Dn = shape.Dn();
    const std::vector<RestingFace> faces = resting_faces(shape.mesh, shape.props.centroid, Dn);
    std::vector<SupportCorner> corners = supports_of(faces, edge_spheres, Dn, query);
    if (static_cast<std::size_t>(spheres) < corners.size() + kMinBodySpheres) {
        // Asked for, edge spheres are never dropped silently.
        if (edge_spheres > 0)
            throw InputError("--edge-spheres: " + std::to_string(edge_spheres) + " per edge make " +
                             std::to_string(corners.size()) +
                             " support spheres with the corners, so --spheres must be at least " +
                             std::to_string(corners.size() + kMinBodySpheres) + " (got " +
                             std::to_string(spheres) + ")");
        corners.clear();
    }
    const double radius = kSupportRadius * Dn;
    Clump clump(corners.size(), Sphere{Eigen::Vector3d::Zero(), radius});
    // Inside every face to start with, so that the fit sees where they will be.
    for (std::size_t k = 0; k < corners.size(); ++k)
        clump[k].center = corners[k].vertex - radius * corners[k].bisector;
    const Clump body =
        detail::greedy_inscribed(shape, query, spheres - static_cast<int>(corners.size()), seed);
    clump.insert(clump.end(), body.begin(), body.end());
    clump = detail::optimise_clump(shape, query, std::move(clump), seed, corners.size());
    // Shrunk after the fit rather than fitted under the constraint: fitted so
    // (every step held inside) it came out no better on the scene's
    // 118-sphere cube, surface RMS 2.03 % Dn against 1.97 %.
    if (method == ClumpMethod::inscribed)
        detail::hold_inside(clump, shape, query, corners.size());
    place_support_spheres(clump, corners, faces, radius);
    return clump;
}

} // namespace armour
