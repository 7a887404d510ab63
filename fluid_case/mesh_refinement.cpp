#include "mesh_refinement.h"

#include "flume_mesh.h"
#include "output_folder.h"
#include "scene_keys.h"
#include "scene_setup.h"

#include <algorithm>
#include <cmath>

namespace armour {

namespace fs = std::filesystem;

namespace {

std::string header(const std::string &object) {
    return "FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       dictionary;\n"
           "    object      " +
           object +
           ";\n}\n// Written by armour run from the scene's [[refine]] regions "
           "(fluid_case/mesh_refinement.cpp).\n\n";
}

std::string point(double x, double y, double z) {
    return "(" + number_text(x) + " " + number_text(y) + " " + number_text(z) + ")";
}

std::string action(const std::string &set, const std::string &what, const std::string &source) {
    return "    { name " + set + "; type cellSet; action " + what + "; " + source + " }\n";
}

const SceneWall &wall_of(const Scene &scene, const SceneRefine &r) {
    return *std::find_if(scene.walls.begin(), scene.walls.end(),
                         [&](const SceneWall &w) { return w.name == r.wall; });
}

// The slope's face plane: its unit normal out of the body (up and seaward)
// and its height above the face plane of a point, m.
struct Face {
    double sin_t, cos_t, toe_x, floor_z, crest_z;
    explicit Face(const SceneWall &w)
        : sin_t(1.0 / std::sqrt(1.0 + w.cot * w.cot)), cos_t(w.cot * sin_t), toe_x(w.toe_x),
          floor_z(w.floor_z), crest_z(w.floor_z + w.height) {}
    double height(const Eigen::Vector3d &p) const {
        return -(p.x() - toe_x) * sin_t + (p.z() - floor_z) * cos_t;
    }
};

// The cells whose centre lies between heights a and b above the face plane:
// a box along the face (i up it, j across, k down into the body:
// right-handed, as rotatedBoxToCell needs), `far` beyond the mesh.
std::string face_slab(const Face &f, double a, double b, double far) {
    const double x = f.toe_x - far * f.cos_t - b * f.sin_t, z = f.floor_z - far * f.sin_t + b * f.cos_t;
    return "source rotatedBoxToCell; origin " + point(x, far, z) + "; i " +
           point(2 * far * f.cos_t, 0, 2 * far * f.sin_t) + "; j " + point(0, -2 * far, 0) + "; k " +
           point((b - a) * f.sin_t, 0, -(b - a) * f.cos_t) + ";";
}

std::string z_slab(double lo, double hi, double far) {
    return "source boxToCell; box " + point(-far, -far, lo) + " " + point(far, far, hi) + ";";
}

// The actions that make the cellSet `set` the cells of one region. A band
// is where the larger of the heights above the face and above the crest
// (the distance outside the slope's convex body, to its corner) lies in
// [-below, above], and no lower than `below` under the floor.
std::string region_actions(const Scene &scene, const SceneRefine &r, const std::string &set, double far) {
    if (r.type == "box")
        return action(set, "new",
                      "source boxToCell; box " + point(r.min.x(), r.min.y(), r.min.z()) + " " +
                          point(r.max.x(), r.max.y(), r.max.z()) + ";");
    const Face f(wall_of(scene, r));
    const std::string crest = set + "Crest";
    return action(set, "new", face_slab(f, -r.below, r.above, far)) +
           action(set, "subset", z_slab(-far, f.crest_z + r.above, far)) +
           action(crest, "new", z_slab(f.crest_z - r.below, f.crest_z + r.above, far)) +
           action(crest, "subset", face_slab(f, -far, r.above, far)) +
           action(set, "add", "source cellToCell; set " + crest + ";") +
           action(set, "subset", z_slab(f.floor_z - r.below, far, far)) + action(crest, "remove", "");
}

} // namespace

bool in_refine_region(const Scene &scene, const SceneRefine &r, const Eigen::Vector3d &p, double tolerance) {
    if (r.type == "box")
        return (p.array() >= r.min.array() - tolerance).all() &&
               (p.array() <= r.max.array() + tolerance).all();
    const Face f(wall_of(scene, r));
    const double outside = std::max(f.height(p), p.z() - f.crest_z);
    return outside >= -r.below - tolerance && outside <= r.above + tolerance &&
           p.z() >= f.floor_z - r.below - tolerance;
}

std::string refine_set_actions(const Scene &scene, int pass) {
    const double far = 10.0 * (1.0 + (scene.domain_max - scene.domain_min).norm());
    // An empty set to add to (topoSet reads the set of an "add").
    std::string actions = action("refine", "new", z_slab(-2 * far, -far, far));
    auto add_regions = [&](int from_level) {
        for (const SceneRefine &r : scene.refine)
            if (r.level >= from_level)
                actions += region_actions(scene, r, "refineRegion", far) +
                           action("refine", "add", "source cellToCell; set refineRegion;") +
                           action("refineRegion", "remove", "");
    };
    if (pass < refine_levels(scene)) {
        // One layer of this pass's cells around the deeper regions: every
        // cell that shares a point with them.
        add_regions(pass + 1);
        actions +=
            "    { name refinePoints; type pointSet; action new; source cellToPoint; set refine; option "
            "all; }\n" +
            action("refine", "add", "source pointToCell; set refinePoints; option any;") +
            "    { name refinePoints; type pointSet; action remove; }\n";
    }
    add_regions(pass);
    return actions;
}

void write_refine_dicts(const Scene &scene, const fs::path &case_dir) {
    for (int pass = 1; pass <= refine_levels(scene); ++pass)
        write_text_file(case_dir / "system" / ("topoSetDict.refine" + std::to_string(pass)),
                        header("topoSetDict") + "actions\n(\n" + refine_set_actions(scene, pass) + ");\n");
    // x and y (tan1, tan2) only: see the header.
    write_text_file(case_dir / "system" / "refineMeshDict",
                    header("refineMeshDict") +
                        "set             refine;\ncoordinateSystem global;\nglobalCoeffs\n{\n"
                        "    tan1        (1 0 0);\n    tan2        (0 1 0);\n}\n"
                        "directions      (tan1 tan2);\nuseHexTopology  true;\ngeometricCut    false;\n"
                        "writeMesh       false;\n");
}

void check_units_refined(const Scene &scene, const SceneSetup &setup) {
    const int levels = refine_levels(scene);
    // Placed units that settle first stand anywhere above the slope: their
    // settled poses are checked before the coupled run.
    if (levels == 0 || settle_headroom(scene, setup) > 0.0)
        return;
    const double tolerance = 0.5 * fine_cell_size(scene).maxCoeff();
    // The error's key is the first region of the deepest level, by its index; it
    // lists every region of that level, so the user sees which one to widen.
    std::string key, regions;
    for (std::size_t r = 0; r < scene.refine.size(); ++r) {
        if (scene.refine[r].level != levels)
            continue;
        const std::string region = "refine." + std::to_string(r);
        if (key.empty())
            key = region + (scene.refine[r].type == "box" ? ".max" : ".above");
        regions += (regions.empty() ? "" : ", ") + region + " '" + scene.refine[r].name + "'";
    }
    for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
        const BodyInit &b = setup.bodies[i];
        for (const auto &v : setup.units[b.unit].mesh.vertices) {
            const Eigen::Vector3d p = b.pose.position + b.pose.orientation * v;
            if (std::none_of(scene.refine.begin(), scene.refine.end(), [&](const SceneRefine &r) {
                    return r.level == levels && in_refine_region(scene, r, p, tolerance);
                }))
                throw InputError(
                    scene.file + ": key '" + key + "': body " + std::to_string(i) + " (unit '" +
                    setup.units[b.unit].name + "') starts outside every region of level " +
                    std::to_string(levels) + " (" + regions + ") with its vertex " + vector_text(p) +
                    " m: the loads need fluid.cells; widen a region, raise its level, or run the graded "
                    "mesh (fluid.mesh = \"graded\")");
        }
    }
}

} // namespace armour
