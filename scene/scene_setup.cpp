#include "scene_setup.h"

#include "clump_evaluator.h"
#include "engine_registry.h"
#include "materials.h"
#include "shapes.h"
#include "stl_io.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <unistd.h>

namespace armour {

namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string num(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

int material_index(const Scene &scene, const std::string &name, const std::string &key) {
    for (std::size_t i = 0; i < scene.materials.size(); ++i)
        if (scene.materials[i].name == name)
            return static_cast<int>(i);
    throw InputError(scene.file + ": key '" + key + "': unknown material '" + name + "'");
}

Shape unit_shape(const SceneUnit &u) {
    if (u.shape == "cube")
        return make_cube_shape(u.size, u.chamfer, u.density);
    if (u.shape == "dolos")
        return make_dolos_shape(u.height, u.waist, u.density);
    return make_stl_shape(u.stl, u.density);
}

// Clumps are cached by everything that determines them, so a sweep that only
// changes materials or time step never rebuilds one.
Clump cached_clump(const SceneUnit &u, const Shape &shape, const std::string &cache_dir, bool progress) {
    std::ostringstream key;
    key.precision(17);
    key << "armour-clump-v1|" << shape.description << "|density=" << u.density << "|method=" << u.method
        << "|spheres=" << u.spheres << "|tol=" << u.tol_volume << "," << u.tol_surface << "|seed=1";
    if (u.shape == "stl") { // the file's content, not only its name, decides the clump
        std::ifstream in(u.stl, std::ios::binary);
        key << "|bytes=" << std::hash<std::string>{}(std::string(std::istreambuf_iterator<char>(in), {}));
    }
    char hex[32];
    std::snprintf(hex, sizeof hex, "%016zx", std::hash<std::string>{}(key.str()));
    const fs::path file = fs::path(cache_dir) / (std::string(hex) + ".spheres");
    {
        std::ifstream in(file);
        std::string header;
        if (in && std::getline(in, header) && header == "# " + key.str()) {
            Clump clump;
            for (Sphere s{}; in >> s.center.x() >> s.center.y() >> s.center.z() >> s.radius;)
                clump.push_back(s);
            if (!clump.empty())
                return clump;
        }
    }
    const ClumpMethod method = parse_method(u.method);
    Clump clump;
    if (u.spheres > 0) {
        if (progress)
            std::fprintf(stderr, "unit %s: building a %d-sphere clump (%s)\n", u.name.c_str(), u.spheres,
                         u.method.c_str());
        clump = build_clump(shape, method, u.spheres);
    } else {
        if (progress)
            std::fprintf(stderr, "unit %s: fewest spheres for volume %g, surface %g Dn\n", u.name.c_str(),
                         u.tol_volume, u.tol_surface);
        ToleranceSearch search = fewest_spheres(shape, method, u.tol_volume, u.tol_surface, 200);
        if (!search.met)
            throw InputError("unit '" + u.name + "': tolerances cannot be met with 200 spheres");
        clump = std::move(search.clump);
    }
    std::error_code ec;
    fs::create_directories(cache_dir, ec);
    const fs::path temporary = file.string() + ".tmp" + std::to_string(::getpid());
    {
        std::ofstream out(temporary);
        out.precision(17);
        out << "# " << key.str() << "\n";
        for (const auto &s : clump)
            out << s.center.x() << ' ' << s.center.y() << ' ' << s.center.z() << ' ' << s.radius << '\n';
    }
    fs::rename(temporary, file, ec); // a cache that cannot be written only costs time
    return clump;
}

void add_quad(TriangleMesh &m, const Eigen::Vector3d &a, const Eigen::Vector3d &b, const Eigen::Vector3d &c,
              const Eigen::Vector3d &d) {
    const int base = static_cast<int>(m.vertices.size());
    m.vertices.insert(m.vertices.end(), {a, b, c, d});
    m.triangles.push_back({base, base + 1, base + 2});
    m.triangles.push_back({base, base + 2, base + 3});
}

double bounding_radius(const Clump &clump) {
    double r = 0.0;
    for (const auto &s : clump)
        r = std::max(r, s.center.norm() + s.radius);
    return r;
}

Eigen::Quaterniond random_orientation(std::mt19937_64 &rng) {
    std::normal_distribution<double> gauss(0.0, 1.0);
    Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
    q.normalize();
    return q;
}

// Deepest cut of a posed clump into any wall (m, <= 0 when clear) and the wall's index.
std::pair<double, int> wall_penetration(const BodyInit &b, const Clump &clump,
                                        const std::vector<Wall> &walls) {
    double deepest = -HUGE_VAL;
    int which = -1;
    for (std::size_t w = 0; w < walls.size(); ++w)
        for (const auto &sph : clump) {
            const Eigen::Vector3d c = b.pose.position + b.pose.orientation * sph.center;
            for (const auto &t : walls[w].surface.triangles) {
                const auto &v = walls[w].surface.vertices;
                const double depth =
                    sph.radius - (c - closest_point_on_triangle(c, v[t[0]], v[t[1]], v[t[2]])).norm();
                if (depth > deepest) {
                    deepest = depth;
                    which = static_cast<int>(w);
                }
            }
        }
    return {deepest, which};
}

} // namespace

std::string default_cache_dir() {
    if (const char *dir = std::getenv("ARMOUR_CACHE"); dir && *dir)
        return dir;
    if (const char *xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        return std::string(xdg) + "/armour-fsi";
    if (const char *home = std::getenv("HOME"); home && *home)
        return std::string(home) + "/.cache/armour-fsi";
    return (fs::temp_directory_path() / "armour-fsi-cache").string();
}

TriangleMesh plane_wall(const Eigen::Vector3d &point, const Eigen::Vector3d &normal, double size) {
    const Eigen::Vector3d n = normal.normalized();
    const Eigen::Vector3d u = n.unitOrthogonal() * (0.5 * size);
    const Eigen::Vector3d v = n.cross(u);
    TriangleMesh m;
    add_quad(m, point - u - v, point + u - v, point + u + v, point - u + v);
    return m;
}

TriangleMesh slope_wall(const SceneWall &w, const Eigen::Vector3d &lo, const Eigen::Vector3d &hi) {
    // Profile in x-z, from the sea side (-x) landward: the toe's top, the
    // toe's landward face (holding the armour), the 1:cot slope, the crest.
    const double y0 = -0.5 * w.width, y1 = 0.5 * w.width;
    std::vector<Eigen::Vector2d> profile;
    profile.emplace_back(lo.x(), w.floor_z + w.toe_height);
    if (w.toe_height > 0.0)
        profile.emplace_back(w.toe_x, w.floor_z + w.toe_height);
    profile.emplace_back(w.toe_x, w.floor_z);
    profile.emplace_back(w.toe_x + w.cot * w.height, w.floor_z + w.height);
    profile.emplace_back(hi.x(), w.floor_z + w.height);
    TriangleMesh m;
    for (std::size_t k = 0; k + 1 < profile.size(); ++k) {
        const Eigen::Vector2d &a = profile[k], &b = profile[k + 1];
        if ((b - a).norm() <= 0.0)
            continue;
        add_quad(m, {a.x(), y0, a.y()}, {b.x(), y0, b.y()}, {b.x(), y1, b.y()}, {a.x(), y1, a.y()});
    }
    // Side walls keep the units on the slope's width. Every face's normal
    // points to the units' side, as Wall requires.
    add_quad(m, {lo.x(), y0, w.floor_z}, {lo.x(), y0, hi.z()}, {hi.x(), y0, hi.z()}, {hi.x(), y0, w.floor_z});
    add_quad(m, {lo.x(), y1, w.floor_z}, {hi.x(), y1, w.floor_z}, {hi.x(), y1, hi.z()}, {lo.x(), y1, hi.z()});
    return m;
}

TriangleMesh box_wall(const Eigen::Vector3d &a, const Eigen::Vector3d &b) {
    TriangleMesh m;
    add_quad(m, {a.x(), a.y(), a.z()}, {b.x(), a.y(), a.z()}, {b.x(), b.y(), a.z()}, {a.x(), b.y(), a.z()});
    add_quad(m, {a.x(), a.y(), a.z()}, {a.x(), b.y(), a.z()}, {a.x(), b.y(), b.z()}, {a.x(), a.y(), b.z()});
    add_quad(m, {b.x(), a.y(), a.z()}, {b.x(), a.y(), b.z()}, {b.x(), b.y(), b.z()}, {b.x(), b.y(), a.z()});
    add_quad(m, {a.x(), a.y(), a.z()}, {a.x(), a.y(), b.z()}, {b.x(), a.y(), b.z()}, {b.x(), a.y(), a.z()});
    add_quad(m, {a.x(), b.y(), a.z()}, {b.x(), b.y(), a.z()}, {b.x(), b.y(), b.z()}, {a.x(), b.y(), b.z()});
    return m;
}

SceneSetup build_scene(const Scene &scene, const std::string &cache_dir, bool progress) {
    SceneSetup setup;
    EngineSettings &s = setup.settings;
    s.contact = scene.contact_model == "hooke" ? ContactModel::hooke : ContactModel::hertz;
    s.characteristic_velocity = scene.characteristic_velocity;
    for (const auto &m : scene.materials)
        s.materials.push_back(
            {m.name, m.youngs_modulus, m.poisson_ratio, m.restitution, m.friction, m.rolling_friction});
    for (const auto &p : scene.material_pairs)
        s.pairs.push_back({p.a, p.b, p.restitution.value_or(-1.0), p.friction.value_or(-1.0),
                           p.rolling_friction.value_or(-1.0)});
    s.gravity = scene.gravity;
    s.time_step = scene.time_step;
    s.force_time_step = scene.force_time_step;

    std::vector<std::string> unit_names;
    for (std::size_t k = 0; k < scene.units.size(); ++k) {
        const SceneUnit &u = scene.units[k];
        const Shape shape = unit_shape(u);
        UnitTemplate t;
        t.name = u.name;
        t.mesh = shape.mesh;
        t.props = shape.props;
        t.material = material_index(scene, u.material, "unit." + std::to_string(k) + ".material");
        t.clump = cached_clump(u, shape, cache_dir, progress);
        t.convex_parts = shape.convex_parts;
        setup.unit_Dn.push_back(shape.Dn());
        setup.unit_spheres.push_back(static_cast<int>(t.clump.size()));
        setup.units.push_back(std::move(t));
        unit_names.push_back(u.name);
    }
    auto unit_index = [&](const std::string &name) {
        return static_cast<int>(std::find(unit_names.begin(), unit_names.end(), name) - unit_names.begin());
    };

    for (std::size_t k = 0; k < scene.walls.size(); ++k) {
        const SceneWall &w = scene.walls[k];
        Wall wall;
        wall.name = w.name.empty() ? "wall" + std::to_string(k) : w.name;
        wall.material = material_index(scene, w.material, "wall." + std::to_string(k) + ".material");
        if (w.type == "plane")
            wall.surface = plane_wall(w.point, w.normal, w.size);
        else if (w.type == "slope")
            wall.surface = slope_wall(w, scene.domain_min, scene.domain_max);
        else if (w.type == "box")
            wall.surface = box_wall(w.min, w.max);
        else
            wall.surface = read_stl(w.file);
        setup.walls.push_back(std::move(wall));
    }

    for (const auto &b : scene.bodies) {
        BodyInit init;
        init.unit = unit_index(b.unit);
        init.pose.position = b.position;
        init.pose.orientation =
            Eigen::Quaterniond(b.orientation[0], b.orientation[1], b.orientation[2], b.orientation[3])
                .normalized();
        init.velocity = b.velocity;
        init.angular_velocity = b.angular_velocity;
        init.fixed_translation = b.fixed_translation;
        init.fixed_rotation = b.fixed_rotation;
        init.pivot = b.pivot;
        setup.bodies.push_back(init);
    }

    for (std::size_t k = 0; k < scene.drops.size(); ++k) {
        const SceneDrop &d = scene.drops[k];
        const int unit = unit_index(d.unit);
        const double R = bounding_radius(setup.units[unit].clump);
        std::mt19937_64 rng(d.seed);
        std::uniform_real_distribution<double> uniform(0.0, 1.0);
        int placed = 0;
        for (long tries = 0; placed < d.count && tries < 2000L * d.count; ++tries) {
            BodyInit init;
            init.unit = unit;
            init.pose.position =
                d.min +
                (d.max - d.min).cwiseProduct(Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng)));
            init.pose.orientation = random_orientation(rng);
            bool free = ((init.pose.position.array() - R) > scene.domain_min.array()).all() &&
                        ((init.pose.position.array() + R) < scene.domain_max.array()).all();
            for (const auto &other : setup.bodies)
                free = free && (other.pose.position - init.pose.position).norm() >
                                   R + bounding_radius(setup.units[other.unit].clump);
            if (!free || wall_penetration(init, setup.units[unit].clump, setup.walls).first > 0.0)
                continue;
            setup.bodies.push_back(init);
            ++placed;
        }
        if (placed < d.count)
            throw InputError(scene.file + ": key 'drop." + std::to_string(k) + ".count': only " +
                             std::to_string(placed) + " of " + std::to_string(d.count) +
                             " units fit in the region clear of each other and of the walls; enlarge " +
                             "drop.min/max");
    }

    for (std::size_t k = 0; k < scene.patterns.size(); ++k) {
        const ScenePattern &p = scene.patterns[k];
        const int unit = unit_index(p.unit);
        const SceneWall *slope = nullptr;
        for (const auto &w : scene.walls)
            if (w.name == p.wall && w.type == "slope")
                slope = &w;
        if (!slope)
            throw InputError(scene.file + ": key 'pattern." + std::to_string(k) + ".wall': '" + p.wall +
                             "' is not a slope wall");
        const double alpha = std::atan2(1.0, slope->cot);
        const Eigen::Vector3d along(std::cos(alpha), 0.0, std::sin(alpha)),
            normal(-std::sin(alpha), 0.0, std::cos(alpha));
        const Eigen::Quaterniond turn(Eigen::AngleAxisd(-alpha, Eigen::Vector3d::UnitY()));
        // Clearance from the exact shape and from the clump, which may protrude.
        double low = 0.0, extent = 0.0;
        for (const auto &v : setup.units[unit].mesh.vertices) {
            low = std::max(low, -v.z());
            extent = std::max(extent, 2.0 * std::max(std::abs(v.x()), std::abs(v.y())));
        }
        for (const auto &sph : setup.units[unit].clump)
            low = std::max(low, sph.radius - sph.center.z());
        const double spacing = p.spacing > 0.0 ? p.spacing : 1.05 * extent;
        for (int row = 0; row < p.rows; ++row)
            for (int col = 0; col < p.columns; ++col) {
                BodyInit init;
                init.unit = unit;
                const double along_slope = (row + 0.5) * spacing;
                const double across = (col - 0.5 * (p.columns - 1)) * spacing;
                init.pose.position = Eigen::Vector3d(slope->toe_x, across, slope->floor_z) +
                                     along_slope * along + (low + p.gap) * normal;
                init.pose.orientation = turn;
                setup.bodies.push_back(init);
            }
    }

    // The engines' own domain is a little larger than the scene's: a unit
    // resting on a wall laid on the domain's face (a floor at domain_min.z)
    // reaches through that face by its contact overlap, which the engines
    // would otherwise refuse (poses from a settled run, fluid.settle_time).
    double largest = 0.0;
    for (const double Dn : setup.unit_Dn)
        largest = std::max(largest, Dn);
    s.domain_min = scene.domain_min - Eigen::Vector3d::Constant(0.02 * largest);
    s.domain_max = scene.domain_max + Eigen::Vector3d::Constant(0.02 * largest);

    // A resting contact overlaps a little: a Hertz contact under a unit's own
    // weight by ~0.2 % of the sphere radius (E = 5e7 Pa, 0.06 m concrete
    // cube), under a settled pile of 0.1 m cubes up to 1.5 %. Poses taken from
    // a settled run (fluid.settle_time) carry such overlaps; up to 5 % of the
    // smaller radius is a contact, not a mistake (at 5 % the softened Hertz
    // contact pushes back with ~10 unit weights: a start that is not wrong).
    // Against the domain's faces the engines' padded domain (above) counts.
    const auto resting = [](double radius) { return 0.05 * radius; };
    // Bodies inside the domain, and no two overlapping.
    std::vector<std::string> problems;
    for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
        const BodyInit &b = setup.bodies[i];
        for (const auto &sph : setup.units[b.unit].clump) {
            const Eigen::Vector3d c = b.pose.position + b.pose.orientation * sph.center;
            if (((c.array() - sph.radius) < s.domain_min.array()).any() ||
                ((c.array() + sph.radius) > s.domain_max.array()).any()) {
                throw InputError(scene.file + ": body " + std::to_string(i) + " (unit '" +
                                 setup.units[b.unit].name + "') reaches outside run.domain_min/domain_max");
            }
        }
    }
    for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
        const BodyInit &b = setup.bodies[i];
        const auto [depth, wall] = wall_penetration(b, setup.units[b.unit].clump, setup.walls);
        double smallest = HUGE_VAL;
        for (const auto &sph : setup.units[b.unit].clump)
            smallest = std::min(smallest, sph.radius);
        if (depth > resting(smallest))
            throw InputError(
                scene.file + ": body " + std::to_string(i) + " (unit '" + setup.units[b.unit].name +
                "') cuts into wall '" + setup.walls[wall].name + "' by " + num(depth) +
                " m at its initial pose (the clump's spheres may protrude beyond the exact shape); " +
                "move it away from the wall");
    }
    for (std::size_t i = 0; i < setup.bodies.size() && problems.size() < 5; ++i)
        for (std::size_t j = i + 1; j < setup.bodies.size() && problems.size() < 5; ++j) {
            const BodyInit &a = setup.bodies[i], &b = setup.bodies[j];
            const Clump &ca = setup.units[a.unit].clump, &cb = setup.units[b.unit].clump;
            if ((a.pose.position - b.pose.position).norm() >= bounding_radius(ca) + bounding_radius(cb))
                continue;
            bool overlap = false;
            for (const auto &sa : ca)
                for (const auto &sb : cb)
                    overlap = overlap || ((a.pose.position + a.pose.orientation * sa.center) -
                                          (b.pose.position + b.pose.orientation * sb.center))
                                                 .norm() <
                                             sa.radius + sb.radius - resting(std::min(sa.radius, sb.radius));
            if (overlap)
                problems.push_back(std::to_string(i) + "-" + std::to_string(j));
        }
    if (!problems.empty()) {
        std::string pairs;
        for (const auto &p : problems)
            pairs += (pairs.empty() ? "" : ", ") + p;
        throw InputError(scene.file + ": initial placement: bodies overlap (pairs " + pairs +
                         "); move them apart");
    }
    const bool wave_flume = scene.waves && scene.waves->type != "solitary"; // an empty flume is a scene
    if (setup.bodies.empty() && !wave_flume)
        throw InputError(scene.file + ": no bodies: add [[body]], [[drop]] or [[pattern]]");
    return setup;
}

// A clump does not rest on a face but on its spheres. Where the lowest
// spheres on a face differ in height by more than the contacts can absorb
// (the face's rest gap, clump_evaluator.h), the clump stands on two of them
// and rocks about the line through them: a rolling motion with no sliding
// at the contacts, hence nothing to damp it. The contacts absorb their
// overlap: a unit on two spheres puts half its weight on each, and a third
// sphere touches when its gap is under that Hertz overlap. Measured on a
// plane in the dry DEM (a = 0.2 m cube, E = 5e7 Pa, 0.5-1.5 s; overlap
// estimate 0.57 mm): the optimised 8-sphere cube (gap 4.4 mm) wanders
// 2-4 mm tilting 2-3 degrees; the 27-sphere cube rests on its -z face (gap
// 0.40 mm, 0.037 mm wander) and rocks on its +x face (gap 3.5 mm, 1.5 mm).
// Rolling friction 0.05 stops the rocking (8 spheres: 0.015 mm). In water
// the rocking unit stirs the flow and drifts (docs/dem.md).
std::vector<std::string> rocking_clump_warnings(const Scene &scene, const SceneSetup &setup) {
    std::vector<std::string> warnings;
    if (engine_style(scene.engine).capabilities.shape != ShapeModel::sphere_clumps)
        return warnings;
    const EngineSettings &st = setup.settings;
    for (std::size_t k = 0; k < setup.units.size(); ++k) {
        const UnitTemplate &unit = setup.units[k];
        const int m = unit.material;
        double rolling = pair_value(st, m, m, &Material::rolling_friction, &MaterialPair::rolling_friction);
        for (const Wall &w : setup.walls)
            rolling = std::min(rolling, pair_value(st, m, w.material, &Material::rolling_friction,
                                                   &MaterialPair::rolling_friction));
        if (rolling != 0.0)
            continue;
        const double gap = rest_summary(unit.mesh, Eigen::Vector3d::Zero(), unit.clump, setup.unit_Dn[k]).gap;
        const double overlap = resting_overlap(unit, st.materials[m], scene.gravity.norm());
        if (gap > overlap) {
            char figures[200];
            std::snprintf(figures, sizeof figures,
                          "rest gap %.2f mm > %.2f mm, the contact overlap under half its weight", 1e3 * gap,
                          1e3 * overlap);
            warnings.push_back(
                "unit '" + unit.name + "': its " + std::to_string(setup.unit_spheres[k]) +
                "-sphere clump stands on two spheres on some faces (" +
                (std::isfinite(gap) ? std::string(figures) : std::string("it stands flat on none of them")) +
                ") and rocks without end there; set rolling_friction = 0.05 on its material, "
                "or use a clump that rests flat (`armour clump` reports rest_gap; docs/dem.md)");
        }
    }
    return warnings;
}

double resting_overlap(const UnitTemplate &unit, const Material &material, double gravity) {
    std::vector<double> radii;
    for (const Sphere &s : unit.clump)
        radii.push_back(s.radius);
    std::nth_element(radii.begin(), radii.begin() + static_cast<long>(radii.size() / 2), radii.end());
    const double radius = radii[radii.size() / 2];
    // Hertz, sphere on a plane of the same material: F = 4/3 E* sqrt(R) d^(3/2).
    const double e_star =
        material.youngs_modulus / (2.0 * (1.0 - material.poisson_ratio * material.poisson_ratio));
    const double force = 0.5 * unit.props.mass * gravity;
    return std::pow(3.0 * force / (4.0 * e_star * std::sqrt(radius)), 2.0 / 3.0);
}

} // namespace armour
