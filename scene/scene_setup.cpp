#include "scene_setup.h"

#include "clump_evaluator.h"
#include "collider.h"
#include "engine_registry.h"
#include "materials.h"
#include "random_pattern.h"
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
    key << "armour-clump-v2|" << shape.description << "|density=" << u.density << "|method=" << u.method
        << "|spheres=" << u.spheres << "|tol=" << u.tol_volume << "," << u.tol_surface << "|seed=1";
    if (u.edge_spheres > 0) // only when set, so that existing caches keep their names
        key << "|edges=" << u.edge_spheres;
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
        const std::string edges =
            u.edge_spheres > 0 ? ", " + std::to_string(u.edge_spheres) + " per edge" : "";
        if (progress)
            std::fprintf(stderr, "unit %s: building a %d-sphere clump (%s%s)\n", u.name.c_str(), u.spheres,
                         u.method.c_str(), edges.c_str());
        clump = build_clump(shape, method, u.spheres, 1, u.edge_spheres);
    } else {
        if (progress)
            std::fprintf(stderr, "unit %s: fewest spheres for volume %g, surface %g Dn\n", u.name.c_str(),
                         u.tol_volume, u.tol_surface);
        // The topple tolerance is the `armour clump` default (clump_evaluator.h).
        ToleranceSearch search = fewest_spheres(shape, method, {u.tol_volume, u.tol_surface}, 200);
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

Eigen::Quaterniond random_orientation(std::mt19937_64 &rng) {
    std::normal_distribution<double> gauss(0.0, 1.0);
    Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
    q.normalize();
    return q;
}

double largest_Dn(const SceneSetup &setup) {
    double largest = 0.0;
    for (const double Dn : setup.unit_Dn)
        largest = std::max(largest, Dn);
    return largest;
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

std::string cache_dir_or_default(const std::string &given) {
    return given.empty() ? default_cache_dir() : given;
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
    // Side walls keep the units on the slope's width: above the profile
    // only, so that inside the slope's solid no side wall is nearer than its
    // face (a point cut into the face beside a side wall would read as in
    // front of that wall). Every face's normal points to the units' side, as
    // Wall requires.
    for (std::size_t k = 0; k + 1 < profile.size(); ++k) {
        const Eigen::Vector2d &a = profile[k], &b = profile[k + 1];
        if (b.x() <= a.x())
            continue; // the toe step's vertical face: no width
        add_quad(m, {a.x(), y0, a.y()}, {a.x(), y0, hi.z()}, {b.x(), y0, hi.z()}, {b.x(), y0, b.y()});
        add_quad(m, {a.x(), y1, a.y()}, {b.x(), y1, b.y()}, {b.x(), y1, hi.z()}, {a.x(), y1, hi.z()});
    }
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

double settle_headroom(const Scene &scene, const SceneSetup &setup) {
    return scene.fluid && scene.fluid->settle_time > 0.0 ? kSettleHeadroom * largest_Dn(setup) : 0.0;
}

namespace {

EngineSettings engine_settings(const Scene &scene) {
    EngineSettings s;
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
    s.contact_iterations = scene.contact_iterations;
    return s;
}

void add_units(const Scene &scene, const std::string &cache_dir, bool progress, SceneSetup &setup) {
    for (std::size_t k = 0; k < scene.units.size(); ++k) {
        const SceneUnit &u = scene.units[k];
        const Shape shape = unit_shape(u);
        UnitTemplate t;
        t.name = u.name;
        t.mesh = shape.mesh;
        t.props = shape.props;
        t.material = material_index(scene, u.material, "unit." + std::to_string(k) + ".material");
        // Checked here, where the shape is known, before any clump is built.
        if (const int needed = u.edge_spheres > 0 ? fewest_spheres_with_edges(shape, u.edge_spheres) : 0;
            u.spheres < needed)
            throw InputError(scene.file + ": key 'unit." + std::to_string(k) +
                             ".edge_spheres': " + std::to_string(u.edge_spheres) + " per edge need unit." +
                             std::to_string(k) + ".spheres >= " + std::to_string(needed) +
                             " (the corner and edge spheres, and 8 for the body; got " +
                             std::to_string(u.spheres) + ")");
        t.clump = cached_clump(u, shape, cache_dir, progress);
        t.convex_parts = shape.convex_parts;
        setup.unit_Dn.push_back(shape.Dn());
        setup.unit_spheres.push_back(static_cast<int>(t.clump.size()));
        setup.units.push_back(std::move(t));
    }
}

std::vector<Wall> make_walls(const Scene &scene, const Eigen::Vector3d &placement_max) {
    std::vector<Wall> walls;
    for (std::size_t k = 0; k < scene.walls.size(); ++k) {
        const SceneWall &w = scene.walls[k];
        Wall wall;
        wall.name = w.name.empty() ? "wall" + std::to_string(k) : w.name;
        wall.material = material_index(scene, w.material, "wall." + std::to_string(k) + ".material");
        if (w.type == "plane")
            wall.surface = plane_wall(w.point, w.normal, w.size);
        else if (w.type == "slope")
            wall.surface = slope_wall(w, scene.domain_min, placement_max);
        else if (w.type == "box")
            wall.surface = box_wall(w.min, w.max);
        else {
            wall.surface = read_stl(w.file);
            wall.oriented = false;
            wall.wound = consistently_wound(wall.surface);
        }
        walls.push_back(std::move(wall));
    }
    return walls;
}

BodyInit body_init(const SceneBody &b, int unit) {
    BodyInit init;
    init.unit = unit;
    init.pose.position = b.position;
    init.pose.orientation =
        Eigen::Quaterniond(b.orientation[0], b.orientation[1], b.orientation[2], b.orientation[3])
            .normalized();
    init.velocity = b.velocity;
    init.angular_velocity = b.angular_velocity;
    init.fixed_translation = b.fixed_translation;
    init.fixed_rotation = b.fixed_rotation;
    init.pivot = b.pivot;
    return init;
}

// What placing units and checking their poses needs beside the templates:
// the shape each unit collides in the scene's engine and how far it reaches.
struct Placement {
    std::vector<Collider> colliders;
    std::vector<double> reach;     // m: no part of a unit farther from its centre, clump or exact shape
    Eigen::Vector3d domain_min;    // m
    Eigen::Vector3d placement_max; // m: the domain's top raised by the settle's headroom

    // m: the radius within which a unit's collided shape lies (drops keep units this far apart).
    double collided_radius(int unit) const {
        const auto k = static_cast<std::size_t>(unit);
        return colliders[k].spheres ? colliders[k].reach : reach[k];
    }
};

Placement make_placement(const Scene &scene, const SceneSetup &setup) {
    Placement place;
    const ShapeModel model = engine_style(scene.engine).capabilities.shape;
    for (std::size_t k = 0; k < setup.units.size(); ++k) {
        place.colliders.push_back(make_collider(setup.units[k], model, setup.unit_Dn[k]));
        place.reach.push_back(bounding_radius(setup.units[k].clump));
        for (const Eigen::Vector3d &v : setup.units[k].mesh.vertices)
            place.reach.back() = std::max(place.reach.back(), v.norm());
    }
    place.domain_min = scene.domain_min;
    // A loose pile (random placement) stands higher than the layer it
    // settles into, and the settle is DEM alone.
    place.placement_max = scene.domain_max + Eigen::Vector3d(0.0, 0.0, settle_headroom(scene, setup));
    return place;
}

int unit_index(const SceneSetup &setup, const std::string &name) {
    const auto named = [&](const UnitTemplate &u) { return u.name == name; };
    return static_cast<int>(std::find_if(setup.units.begin(), setup.units.end(), named) -
                            setup.units.begin());
}

void drop_units(const Scene &scene, std::size_t k, const Placement &place, SceneSetup &setup) {
    const SceneDrop &d = scene.drops[k];
    const int unit = unit_index(setup, d.unit);
    const Collider &collider = place.colliders[static_cast<std::size_t>(unit)];
    const double R = place.collided_radius(unit);
    // Units clear of each other by their collided shapes, not by the
    // spheres that enclose them: a cube turned at random is kept ~2 Dn
    // apart by those (a 20-sphere clump's corner spheres stand 0.197 m
    // from a 0.2 m cube's centre), and slope_cubes' region, which a pile
    // at the Rock Manual's porosity 0.47 fills with ~60, took 22 of its
    // 30. They all fall at g from rest: a gap of 2 % of Dn stays open
    // until they land.
    const double gap = 0.02 * setup.unit_Dn[static_cast<std::size_t>(unit)];
    const auto touches = [&](const BodyInit &a, const BodyInit &b) {
        return (a.pose.position - b.pose.position).norm() < R + place.collided_radius(b.unit) + gap &&
               closer_than(a, setup.units[unit], collider, b, setup.units[b.unit], place.colliders[b.unit],
                           gap);
    };
    std::mt19937_64 rng(d.seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    int placed = 0;
    for (long tries = 0; placed < d.count && tries < 2000L * d.count; ++tries) {
        BodyInit init;
        init.unit = unit;
        init.pose.position =
            d.min + (d.max - d.min).cwiseProduct(Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng)));
        init.pose.orientation = random_orientation(rng);
        bool free = ((init.pose.position.array() - R) > place.domain_min.array()).all() &&
                    ((init.pose.position.array() + R) < place.placement_max.array()).all();
        for (const auto &other : setup.bodies)
            free = free && !touches(init, other);
        if (!free || body_wall_penetration(init, setup.units[unit], collider, setup.walls).first > 0.0)
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

// The units in the scene before a random pattern's (a settle's stage: the
// rows settled before it, as [[body]]): the pattern's units clear them by
// `gap`, as the engine collides them, and rise no higher than their top.
UnitsBefore units_before(const SceneSetup &setup, const Placement &place, const PatternGrid &grid, double gap,
                         int unit) {
    UnitsBefore before;
    const std::vector<BodyInit> others = setup.bodies; // a copy: the pattern appends to setup.bodies
    if (others.empty())
        return before;
    for (const BodyInit &o : others)
        before.top =
            std::max(before.top, (o.pose.position - grid.origin).dot(grid.normal) + place.reach[o.unit]);
    const UnitTemplate &u = setup.units[static_cast<std::size_t>(unit)];
    const Collider &c = place.colliders[static_cast<std::size_t>(unit)];
    const double reach = place.reach[static_cast<std::size_t>(unit)];
    before.clear = [others, &setup, &place, &u, &c, reach, gap](const BodyInit &b) {
        for (const BodyInit &o : others) {
            const auto k = static_cast<std::size_t>(o.unit);
            if ((b.pose.position - o.pose.position).norm() < reach + place.reach[k] + gap &&
                closer_than(b, u, c, o, setup.units[k], place.colliders[k], gap))
                return false;
        }
        return true;
    };
    return before;
}

void pattern_units(const Scene &scene, std::size_t k, const Placement &place, SceneSetup &setup) {
    const ScenePattern &p = scene.patterns[k];
    const int unit = unit_index(setup, p.unit);
    const Collider &collider = place.colliders[static_cast<std::size_t>(unit)];
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
    // The unit frame turned onto the slope: x up it, y across, z out of
    // it. Extents of the shape the engine collides, which for a clump may
    // protrude beyond the exact shape.
    double low = 0.0, high = 0.0, half = 0.0;
    const auto extend = [&](const Eigen::Vector3d &c, double radius) {
        low = std::max(low, radius - c.z());
        high = std::max(high, radius + c.z());
        half = std::max(half, std::max(std::abs(c.x()), std::abs(c.y())) + radius);
    };
    if (collider.spheres)
        for (const auto &sph : setup.units[unit].clump)
            extend(sph.center, sph.radius);
    else
        for (const auto &point : collider.points)
            extend(point, 0.0);
    const std::string key = "pattern." + std::to_string(k) + ".";
    const double Dn = setup.unit_Dn[unit];
    double spacing = p.spacing > 0.0 ? p.spacing : 1.05 * 2.0 * half;
    if (p.packing_density > 0.0) {
        spacing = Dn * std::sqrt(p.layers / p.packing_density);
        if (spacing < 2.0 * half)
            throw InputError(scene.file + ": key '" + key + "packing_density': " + num(p.packing_density) +
                             " units per Dn^2 in " + std::to_string(p.layers) + " layer(s) needs centres " +
                             num(spacing) + " m apart, less than the unit's size " + num(2.0 * half) +
                             " m: a regular pattern would overlap (at most " +
                             num(p.layers * Dn * Dn / (4.0 * half * half)) + "); add layers");
    }
    const auto pose = [&](double up, double across, double out) {
        BodyInit init;
        init.unit = unit;
        init.pose.position =
            Eigen::Vector3d(slope->toe_x, across, slope->floor_z) + up * along + out * normal;
        init.pose.orientation = turn;
        return init;
    };
    // The first row half a spacing from the toe, moved up the slope
    // until it clears a toe step (and any wall) by the shape the engine collides.
    double first = 0.5 * spacing;
    for (; first < 0.5 * spacing + 3.0 * Dn; first += 0.02 * Dn)
        if (body_wall_penetration(pose(first, 0.0, low + p.gap), setup.units[unit], collider, setup.walls)
                .first <= 0.0)
            break;
    if (p.placement == "random" || p.placement == "seated") {
        PatternGrid grid;
        grid.slope = slope;
        grid.origin = Eigen::Vector3d(slope->toe_x, 0.0, slope->floor_z);
        grid.along = along;
        grid.normal = normal;
        grid.turn = turn;
        grid.first = first;
        grid.spacing = spacing;
        grid.size = 2.0 * half;
        grid.domain_min = place.domain_min;
        grid.domain_max = place.placement_max;
        const UnitsBefore before = units_before(setup, place, grid, p.gap, unit);
        for (const BodyInit &b : random_pattern(p, grid, unit, setup.units[unit], collider, place.reach[unit],
                                                Dn, setup.walls, before, scene.file + ": key '" + key))
            setup.bodies.push_back(b);
        return;
    }
    // Every other layer sits half a spacing up the slope, its columns in
    // the gaps of the one below (one column fewer: within the same width).
    for (int layer = 0; layer < p.layers; ++layer) {
        const bool shifted = layer % 2 == 1 && p.columns > 1;
        const int columns = shifted ? p.columns - 1 : p.columns;
        const double n = low + p.gap + layer * (low + high + p.gap);
        for (int row = p.first_row; row < p.rows; ++row)
            for (int col = 0; col < columns; ++col)
                setup.bodies.push_back(pose(first + (row + (layer % 2) * 0.5) * spacing,
                                            (col - 0.5 * (columns - 1)) * spacing, n));
    }
}

// The engines' domain about the scene's. A unit resting on a wall laid on
// the domain's face (a side wall at domain_min.y) reaches through that face:
// by its contact overlap, and under a layer's load a clump's smallest spheres
// pass the soft wall. Cubes placed at random in scenes/stability_cubes.toml
// put their exact corners 1.8-3.2 mm through its side walls (as deep as into
// the slope) and their clumps' 0.4 mm corner spheres, which stand 1.5 mm out
// of the cube on each axis, 4.5-4.7 mm (0.12 Dn). Units may start up to
// 0.25 Dn beyond the faces (poses from a settled run, fluid.settle_time,
// checked in check_initial_poses); the engines' own domain reaches 0.5 Dn
// beyond them, as LIGGGHTS drops a sphere outside its box with its whole unit.
void set_engine_domain(const Placement &place, double largest, EngineSettings &s) {
    s.domain_min = place.domain_min - Eigen::Vector3d::Constant(0.5 * largest);
    s.domain_max = place.placement_max + Eigen::Vector3d::Constant(0.5 * largest);
}

void check_inside_domain(const Scene &scene, const Placement &place, const SceneSetup &setup) {
    const double largest = largest_Dn(setup);
    const Eigen::Vector3d start_min = place.domain_min - Eigen::Vector3d::Constant(0.25 * largest),
                          start_max = place.placement_max + Eigen::Vector3d::Constant(0.25 * largest);
    for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
        const BodyInit &b = setup.bodies[i];
        for (const auto &sph : setup.units[b.unit].clump) {
            const Eigen::Vector3d c = b.pose.position + b.pose.orientation * sph.center;
            if (((c.array() - sph.radius) < start_min.array()).any() ||
                ((c.array() + sph.radius) > start_max.array()).any()) {
                throw InputError(scene.file + ": body " + std::to_string(i) + " (unit '" +
                                 setup.units[b.unit].name + "') reaches outside run.domain_min/domain_max");
            }
        }
    }
}

// How deep a unit may start in a wall or a neighbour: a resting contact, not a mistake.
struct RestingDepth {
    const Scene &scene;
    const SceneSetup &setup;
    std::vector<double> beyond_clump; // m: how far each exact collider stands out of its clump

    // A resting contact overlaps a little: a Hertz contact under a unit's own
    // weight by ~0.2 % of the sphere radius (E = 5e7 Pa, 0.06 m concrete
    // cube), under a settled pile of 0.1 m cubes up to 1.5 %. Poses taken from
    // a settled run (fluid.settle_time) carry such overlaps; up to 5 % of the
    // smaller radius is a contact, not a mistake (at 5 % the softened Hertz
    // contact pushes back with ~10 unit weights: a start that is not wrong).
    // Against the domain's faces the 0.25 Dn of check_inside_domain counts.
    // A clump's smallest spheres (a cube's corners: 0.01 a) sink deeper than
    // 5 % of their radius under a settled layer's load (0.05-0.19 mm on
    // 0.4 mm corners, scenes/stability_cubes.toml): there the contact is the
    // Hertz overlap under those same ~10 unit weights.
    // Against a wall: a sphere of this radius on a plane.
    double sphere(double radius, int unit) const { return contact(radius, radius, unit); }
    // Between two spheres (unit's the smaller): Hertz's effective radius
    // ra rb / (ra + rb) is half a plane's between equal spheres, so under the
    // same force they press 2^(1/3) = 1.26 x deeper into each other than into
    // a wall (a layer settled in stages pressed a 4.0 and a 4.3 mm sphere
    // 0.35 mm into each other: 9.1 unit weights, where a plane's figure
    // allowed 0.30 mm).
    double pair(double ra, double rb, int unit) const {
        return contact(std::min(ra, rb), ra * rb / (ra + rb), unit);
    }

    // An exact shape rests with next to no overlap (Bullet keeps its contact
    // within its collision margin): 1 % of Dn is a contact there. Poses a
    // clump engine settled (fluid.settle_engine, or a settled scene run with
    // another engine) put the exact shape as deep into a wall or a neighbour
    // as it stands out of its clump (measured: a 47-sphere cube's faces 0.03
    // Dn into the slope): that depth is the clump's shape error, not a
    // placement mistake, and the exact-shape engine pushes it out in its
    // first steps.
    double exact(int unit) const {
        const auto k = static_cast<std::size_t>(unit);
        return std::max(0.01 * setup.unit_Dn[k], beyond_clump[k]);
    }

  private:
    double contact(double smaller, double effective_radius, int unit) const {
        const UnitTemplate &u = setup.units[static_cast<std::size_t>(unit)];
        return std::max(0.05 * smaller,
                        sphere_overlap(effective_radius,
                                       setup.settings.materials[static_cast<std::size_t>(u.material)],
                                       10.0 * u.props.mass * scene.gravity.norm()));
    }
};

// Exact shapes' settled poses handed to clumps as they are: the clumps'
// spheres stand out of the shapes, into the neighbours and the slope. Handed
// to exact shapes again, a unit that deep was pressed into a wall the engine
// collides as triangles, which hold no inside.
std::string settled_hulls_remedy(const Scene &scene) {
    if (!scene.fluid || scene.fluid->settled_by.empty() ||
        engine_style(scene.fluid->settled_by).capabilities.shape != ShapeModel::convex_hulls)
        return "";
    // Inscribed clumps lie inside the shapes: a cut is the shape's own.
    const bool inscribed = std::all_of(scene.units.begin(), scene.units.end(),
                                       [](const SceneUnit &u) { return u.method == "inscribed"; });
    if (engine_style(scene.engine).capabilities.shape != ShapeModel::sphere_clumps || inscribed)
        return " (fluid.settled_by " + scene.fluid->settled_by +
               " left it so: a pressed unit can sink into a wall's triangle mesh; settle anew, e.g. with "
               "another pattern seed)";
    return " (fluid.settled_by " + scene.fluid->settled_by +
           " settled exact shapes, which the clumps stand out of: settle for the clumps with run.engine " +
           scene.engine + " and fluid.settle_engine " + scene.fluid->settled_by +
           ", which grows the cubes to hold them, or give the unit method \"inscribed\", whose spheres lie "
           "inside the exact shape)";
}

void check_wall_contacts(const Scene &scene, const Placement &place, const SceneSetup &setup,
                         const RestingDepth &resting, const std::string &remedy) {
    for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
        const BodyInit &b = setup.bodies[i];
        const Collider &c = place.colliders[static_cast<std::size_t>(b.unit)];
        const auto [depth, wall] = body_wall_penetration(b, setup.units[b.unit], c, setup.walls);
        double smallest = HUGE_VAL;
        for (const auto &sph : setup.units[b.unit].clump)
            smallest = std::min(smallest, sph.radius);
        if (depth > (c.spheres ? resting.sphere(smallest, b.unit) : resting.exact(b.unit)))
            throw InputError(scene.file + ": body " + std::to_string(i) + " (unit '" +
                             setup.units[b.unit].name + "') cuts into wall '" + setup.walls[wall].name +
                             "' by " + num(depth) + " m at its initial pose " +
                             (c.spheres ? "(the clump's spheres may protrude beyond the exact shape)"
                                        : "(its exact shape, which the engine collides)") +
                             "; move it away from the wall" + remedy);
    }
}

bool bodies_overlap(const BodyInit &a, const BodyInit &b, const Placement &place, const SceneSetup &setup,
                    const RestingDepth &resting) {
    if ((a.pose.position - b.pose.position).norm() >= place.reach[a.unit] + place.reach[b.unit])
        return false;
    const Collider &xa = place.colliders[static_cast<std::size_t>(a.unit)],
                   &xb = place.colliders[static_cast<std::size_t>(b.unit)];
    if (!xa.spheres) {
        // Exact shapes: a surface point of either inside the other
        // (by as much as both stand out of their clumps).
        const double tolerance = std::max(std::min(resting.exact(a.unit), resting.exact(b.unit)),
                                          resting.beyond_clump[static_cast<std::size_t>(a.unit)] +
                                              resting.beyond_clump[static_cast<std::size_t>(b.unit)]);
        return !none_deeper_than(a, xa, b, xb, tolerance) || !none_deeper_than(b, xb, a, xa, tolerance);
    }
    for (const auto &sa : setup.units[a.unit].clump)
        for (const auto &sb : setup.units[b.unit].clump) {
            const double allowed =
                resting.pair(sa.radius, sb.radius, sa.radius < sb.radius ? a.unit : b.unit);
            if (((a.pose.position + a.pose.orientation * sa.center) -
                 (b.pose.position + b.pose.orientation * sb.center))
                    .norm() < sa.radius + sb.radius - allowed)
                return true;
        }
    return false;
}

// Bodies inside the domain, clear of the walls and no two overlapping, each
// by more than a resting contact.
void check_initial_poses(const Scene &scene, const Placement &place, const SceneSetup &setup) {
    check_inside_domain(scene, place, setup);
    RestingDepth resting{scene, setup, std::vector<double>(setup.units.size(), 0.0)};
    for (std::size_t k = 0; k < setup.units.size(); ++k)
        if (!place.colliders[k].spheres)
            resting.beyond_clump[k] = depth_outside_clump(setup.units[k].clump, place.colliders[k].points);
    const std::string remedy = settled_hulls_remedy(scene);
    check_wall_contacts(scene, place, setup, resting, remedy);
    std::string pairs;
    int found = 0;
    for (std::size_t i = 0; i < setup.bodies.size() && found < 5; ++i)
        for (std::size_t j = i + 1; j < setup.bodies.size() && found < 5; ++j)
            if (bodies_overlap(setup.bodies[i], setup.bodies[j], place, setup, resting)) {
                pairs += (pairs.empty() ? "" : ", ") + std::to_string(i) + "-" + std::to_string(j);
                ++found;
            }
    if (found > 0)
        throw InputError(scene.file + ": initial placement: bodies overlap (pairs " + pairs +
                         "); move them apart" + remedy);
}

} // namespace

SceneSetup build_scene(const Scene &scene, const std::string &cache_dir, bool progress) {
    SceneSetup setup;
    setup.settings = engine_settings(scene);
    add_units(scene, cache_dir, progress, setup);
    const Placement place = make_placement(scene, setup);
    setup.walls = make_walls(scene, place.placement_max);
    for (const auto &b : scene.bodies)
        setup.bodies.push_back(body_init(b, unit_index(setup, b.unit)));
    for (std::size_t k = 0; k < scene.drops.size(); ++k)
        drop_units(scene, k, place, setup);
    for (std::size_t k = 0; k < scene.patterns.size(); ++k)
        pattern_units(scene, k, place, setup);
    set_engine_domain(place, largest_Dn(setup), setup.settings);
    check_initial_poses(scene, place, setup);
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
        // The smallest sphere under half the unit's weight (a unit tipping
        // onto two corner spheres) must not sink by a good part of its
        // radius: the 2 mm corner spheres of a 0.2 m cube at E = 5e7 Pa sink
        // 2.3 mm and pass through a tilting plate (docs/clump_builder.md).
        double smallest = HUGE_VAL;
        for (const Sphere &s : unit.clump)
            smallest = std::min(smallest, s.radius);
        const double sink =
            sphere_overlap(smallest, st.materials[m], 0.5 * unit.props.mass * scene.gravity.norm());
        if (sink > 0.5 * smallest) {
            char figures[200];
            std::snprintf(figures, sizeof figures, "r = %.2f mm sink %.2f mm", 1e3 * smallest, 1e3 * sink);
            warnings.push_back(
                "unit '" + unit.name + "': its smallest spheres (" + figures +
                " under half its weight, more than half their radius) may pass through "
                "walls as it tips; raise youngs_modulus of its material (scenes/tilt_cube.toml "
                "uses 5e8 Pa)");
        }
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

double sphere_overlap(double radius, const Material &material, double force) {
    // Hertz, sphere on a plane of the same material: F = 4/3 E* sqrt(R) d^(3/2)
    // (between two spheres, R is their effective radius ra rb / (ra + rb)).
    const double e_star =
        material.youngs_modulus / (2.0 * (1.0 - material.poisson_ratio * material.poisson_ratio));
    return std::pow(3.0 * force / (4.0 * e_star * std::sqrt(radius)), 2.0 / 3.0);
}

double resting_overlap(const UnitTemplate &unit, const Material &material, double gravity) {
    std::vector<double> radii;
    for (const Sphere &s : unit.clump)
        radii.push_back(s.radius);
    std::nth_element(radii.begin(), radii.begin() + static_cast<long>(radii.size() / 2), radii.end());
    return sphere_overlap(radii[radii.size() / 2], material, 0.5 * unit.props.mass * gravity);
}

} // namespace armour
