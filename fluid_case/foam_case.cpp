#include "foam_case.h"

#include "checkpoints.h"
#include "collider.h"
#include "engine_registry.h"
#include "fluid_models.h"
#include "flume_mesh.h"
#include "foam_restart.h"
#include "foam_tool.h"
#include "input_error.h"
#include "mesh_refinement.h"
#include "openfoam_environment.h"
#include "output_folder.h"
#include "scene_keys.h"
#include "wave_case.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <unistd.h>

namespace armour {

namespace fs = std::filesystem;

namespace {

std::string foam_vector(const Eigen::Vector3d &v) {
    return "(" + number_text(v.x()) + " " + number_text(v.y()) + " " + number_text(v.z()) + ")";
}

fs::path source_dir() {
#ifdef ARMOUR_SOURCE_DIR
    return ARMOUR_SOURCE_DIR;
#else
    return fs::current_path();
#endif
}

// The plugin: $ARMOUR_FOAM_PLUGIN (an installed copy), else the one this
// build made.
std::string plugin_path() {
    if (const char *env = std::getenv("ARMOUR_FOAM_PLUGIN"); env && *env)
        return env;
#ifdef ARMOUR_FOAM_PLUGIN
    return ARMOUR_FOAM_PLUGIN;
#else
    throw InputError("this armour was built without the OpenFOAM plugin (ARMOUR_BUILD_OPENFOAM=OFF, see "
                     "docs/openfoam.md); set ARMOUR_FOAM_PLUGIN to a libarmourFoamCoupling.so");
#endif
}

bool on_path(const std::string &tool) {
    const char *path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "/usr/bin:/bin");
    for (std::string dir; std::getline(dirs, dir, ':');)
        if (!dir.empty() && ::access((fs::path(dir) / tool).c_str(), X_OK) == 0)
            return true;
    return false;
}

std::vector<Eigen::Vector3d> posed_vertices(const SceneSetup &setup, const BodyInit &b) {
    std::vector<Eigen::Vector3d> out;
    for (const auto &v : setup.units[b.unit].mesh.vertices)
        out.push_back(b.pose.position + b.pose.orientation * v);
    return out;
}

// Fills @TOKENS@ in every file of the copied case; a token left over is a
// template the runner does not know, and would fail inside OpenFOAM.
void fill_tokens(const fs::path &case_dir, const std::map<std::string, std::string> &tokens) {
    const std::regex leftover("@[A-Z0-9_]+@");
    for (const auto &entry : fs::recursive_directory_iterator(case_dir)) {
        if (!entry.is_regular_file())
            continue;
        std::string text = read_text_file(entry.path());
        if (text.find('@') == std::string::npos)
            continue;
        text = filled(text, tokens);
        std::smatch m;
        if (std::regex_search(text, m, leftover))
            throw InputError("case template " + entry.path().string() + ": unknown token " + m.str() +
                             " (known: the tokens listed in docs/openfoam.md)");
        std::ofstream(entry.path(), std::ios::binary | std::ios::trunc) << text;
    }
}

// Every file of a case template as one text (to see which tokens it uses).
std::string template_text(const fs::path &dir) {
    std::string text;
    std::error_code ec;
    for (const auto &e : fs::recursive_directory_iterator(dir, ec))
        if (e.is_regular_file())
            text += read_text_file(e.path());
    return text;
}

int cells_along(double length, double h) {
    return std::max(1, static_cast<int>(std::lround(length / h)));
}

// Geometry tokens of the templates with an obstacle or a sloping bed, from
// the scene's walls, so the fluid mesh and the rigid bodies' walls are one
// geometry (docs/openfoam.md, "Reference cases"):
//   the first "slope" wall: @SLOPE_TOE_X@ @SLOPE_CREST_X@ @SLOPE_CREST_Z@, cells
//     @NX_SEA@ (mesh start to toe), @NX_SLOPE@, @NX_CREST@ (crest to mesh end);
//   the wall named "platform" (its bounding box): @PLATFORM_X0@ @PLATFORM_X1@
//     @PLATFORM_Z1@ (top), cells @NX_BEFORE_PLATFORM@ @NX_ON_PLATFORM@
//     @NX_AFTER_PLATFORM@ @NZ_BELOW_PLATFORM@ @NZ_ABOVE_PLATFORM@.
// A wall that does not fit the mesh box is an error only for a template
// that uses its tokens.
void geometry_tokens(const Scene &scene, const SceneSetup &setup, const std::string &used,
                     std::map<std::string, std::string> &tokens) {
    const Eigen::Vector3d &lo = scene.domain_min, &hi = scene.domain_max;
    const Eigen::Vector3d h = fine_cell_size(scene);
    const std::string where = scene.file + ": ";
    for (const auto &w : scene.walls) {
        if (w.type != "slope")
            continue;
        const double crest_x = w.toe_x + w.cot * w.height, crest_z = w.floor_z + w.height;
        if (used.find("@SLOPE_") != std::string::npos) {
            if (!(w.toe_x > lo.x() && crest_x < hi.x() && crest_z < hi.z()))
                throw InputError(where + "slope wall '" + w.name + "': fluid.case \"" +
                                 scene.fluid->case_name + "\" needs the toe (x = " + number_text(w.toe_x) +
                                 " m) and the crest (x = " + number_text(crest_x) +
                                 " m, z = " + number_text(crest_z) + " m) inside the mesh box");
            if (w.floor_z != lo.z() || w.toe_height != 0.0)
                throw InputError(where + "slope wall '" + w.name + "': fluid.case \"" +
                                 scene.fluid->case_name + "\" needs floor_z = run.domain_min.z (" +
                                 number_text(lo.z()) +
                                 " m) and toe_height = 0 (the fluid bed is the slope's profile)");
        }
        tokens["@SLOPE_TOE_X@"] = number_text(w.toe_x);
        tokens["@SLOPE_CREST_X@"] = number_text(crest_x);
        tokens["@SLOPE_CREST_Z@"] = number_text(crest_z);
        tokens["@NX_SEA@"] = std::to_string(cells_along(w.toe_x - lo.x(), h.x()));
        tokens["@NX_SLOPE@"] = std::to_string(cells_along(crest_x - w.toe_x, h.x()));
        tokens["@NX_CREST@"] = std::to_string(cells_along(hi.x() - crest_x, h.x()));
        break;
    }
    for (std::size_t k = 0; k < scene.walls.size(); ++k) {
        if (scene.walls[k].name != "platform")
            continue;
        Eigen::Vector3d a = Eigen::Vector3d::Constant(HUGE_VAL), b = -a;
        for (const auto &v : setup.walls[k].surface.vertices) {
            a = a.cwiseMin(v);
            b = b.cwiseMax(v);
        }
        if (used.find("@PLATFORM_") != std::string::npos &&
            !(a.x() > lo.x() && b.x() < hi.x() && b.z() > lo.z() && b.z() < hi.z() && a.z() <= lo.z() &&
              a.y() <= lo.y() && b.y() >= hi.y()))
            throw InputError(where + "wall 'platform': fluid.case \"" + scene.fluid->case_name +
                             "\" needs it inside the mesh box along x, its top inside along z, and it must "
                             "span the whole width (y) and reach down to the floor (bounding box " +
                             foam_vector(a) + " .. " + foam_vector(b) + " m)");
        tokens["@PLATFORM_X0@"] = number_text(a.x());
        tokens["@PLATFORM_X1@"] = number_text(b.x());
        tokens["@PLATFORM_Z1@"] = number_text(b.z());
        tokens["@NX_BEFORE_PLATFORM@"] = std::to_string(cells_along(a.x() - lo.x(), h.x()));
        tokens["@NX_ON_PLATFORM@"] = std::to_string(cells_along(b.x() - a.x(), h.x()));
        tokens["@NX_AFTER_PLATFORM@"] = std::to_string(cells_along(hi.x() - b.x(), h.x()));
        tokens["@NZ_BELOW_PLATFORM@"] = std::to_string(cells_along(b.z() - lo.z(), h.z()));
        tokens["@NZ_ABOVE_PLATFORM@"] = std::to_string(cells_along(hi.z() - b.z(), h.z()));
    }
}

// libarmourWaves.so (solitary inlet, absorbing outlet, gauges): $ARMOUR_WAVES_LIB,
// else next to the coupling plugin (coupling/openfoam/waves/ in a build tree).
std::string waves_library(const std::string &plugin) {
    if (const char *env = std::getenv("ARMOUR_WAVES_LIB"); env && *env)
        return env;
    return (fs::path(plugin).parent_path() / "waves" / "libarmourWaves.so").string();
}

// The mesh box and its cells, the water column and level (the template's tokens).
std::map<std::string, std::string> mesh_tokens(const Scene &scene) {
    const SceneFluid &f = *scene.fluid;
    const FlumeMesh mesh = flume_mesh(scene);
    const Eigen::Vector3d &lo = scene.domain_min, &hi = scene.domain_max;
    const Eigen::Vector3d pad = Eigen::Vector3d::Constant(1.0 + (hi - lo).maxCoeff());
    // Without a water column the column box is empty (below the mesh).
    const Eigen::Vector3d column_min = f.has_water_box ? f.water_box_min : Eigen::Vector3d(lo - 2.0 * pad),
                          column_max = f.has_water_box ? f.water_box_max : Eigen::Vector3d(lo - pad);
    return {
        {"@X0@", number_text(lo.x())},
        {"@Y0@", number_text(lo.y())},
        {"@Z0@", number_text(lo.z())},
        {"@X1@", number_text(hi.x())},
        {"@Y1@", number_text(hi.y())},
        {"@Z1@", number_text(hi.z())},
        {"@NX@", std::to_string(mesh.axes[0].cells)},
        {"@NY@", std::to_string(mesh.axes[1].cells)},
        {"@NZ@", std::to_string(mesh.axes[2].cells)},
        {"@GRADING@", mesh.axes[0].grading + " " + mesh.axes[1].grading + " " + mesh.axes[2].grading},
        {"@BOX_MIN@", foam_vector(lo - pad)},
        {"@WATER_MAX@", foam_vector(Eigen::Vector3d(hi.x() + pad.x(), hi.y() + pad.y(), f.water_level))},
        {"@WATER_LEVEL@", number_text(f.water_level)},
        {"@WATER_BOX_MIN@", foam_vector(column_min)},
        {"@WATER_BOX_MAX@", foam_vector(column_max)},
        {"@WATER_DEPTH@", number_text(scene.still_water_depth())},
    };
}

// Ranks, times and step limits, the fluids' properties, gravity, the solitary wave.
std::map<std::string, std::string> fluid_tokens(const Scene &scene, const SceneSetup &setup) {
    const SceneFluid &f = *scene.fluid;
    double speed = 0.0;
    for (const auto &b : setup.bodies)
        speed = std::max(speed, b.velocity.norm());
    const double first_dt =
        speed > 0.0 ? std::min(f.max_time_step, f.max_courant * fine_cell_size(scene).minCoeff() / speed)
                    : f.max_time_step;
    return {
        {"@NP@", std::to_string(f.np)},
        {"@END_TIME@", number_text(scene.duration)},
        {"@DELTA_T@", number_text(first_dt)},
        {"@MAX_DELTA_T@", number_text(f.max_time_step)},
        {"@MAX_CO@", number_text(f.max_courant)},
        {"@MAX_ALPHA_CO@", number_text(f.max_interface_courant)},
        {"@WRITE_INTERVAL@", number_text(f.write_interval)},
        {"@RHO_WATER@", number_text(f.fluid_density)},
        {"@NU_WATER@", number_text(f.viscosity)},
        {"@RHO_AIR@", number_text(f.air_density)},
        {"@NU_AIR@", number_text(f.air_viscosity)},
        {"@GRAVITY@", foam_vector(scene.gravity)},
        {"@WAVE_HEIGHT@", number_text(f.wave_height)},
    };
}

// A refined mesh (fluid.mesh "refined"): refineMesh splits the block's
// cells in the [[refine]] regions, one pass per level (mesh_refinement.h),
// before any zone is made, so the porous zones are the refined cells'.
void refine_flume_mesh(const Scene &scene, const fs::path &case_dir) {
    const int levels = refine_levels(scene);
    if (levels == 0)
        return;
    write_refine_dicts(scene, case_dir);
    for (int pass = 1; pass <= levels; ++pass) {
        const std::string k = std::to_string(pass);
        run_tool("topoSet.refine" + k, {"topoSet", "-dict", "system/topoSetDict.refine" + k}, case_dir,
                 scene.duration, false);
        run_tool("refineMesh." + k, {"refineMesh", "-overwrite"}, case_dir, scene.duration, false);
    }
    // refineMesh -overwrite leaves its cell map in 0/polyMesh: the mesh is constant/polyMesh's.
    std::error_code ec;
    fs::remove_all(case_dir / "0" / "polyMesh", ec);
}

// The template, its tokens, the walls and grading it needs, the plugin,
// OpenFOAM's tools and the ranks, before anything is written.
void check_case_template(const Scene &scene, const SceneSetup &setup, int np) {
    const SceneFluid &f = *scene.fluid;
    const std::string &file = scene.file;
    const fs::path tmpl = source_dir() / "foam_cases" / f.case_name;
    if (!fs::is_regular_file(tmpl / "system" / "controlDict")) {
        std::string known;
        std::error_code ec;
        for (const auto &e : fs::directory_iterator(source_dir() / "foam_cases", ec))
            if (fs::is_regular_file(e.path() / "system" / "controlDict"))
                known += (known.empty() ? "" : ", ") + ("\"" + e.path().filename().string() + "\"");
        throw InputError(file + ": key 'fluid.case': no case template " + tmpl.string() +
                         " (known: " + known + ")");
    }
    const std::string used = template_text(tmpl); // every file of the template, read once
    {
        // [waves], the walls and the template agree, before anything is written.
        std::map<std::string, std::string> tokens;
        wave_tokens(scene, used, tokens);
        geometry_tokens(scene, setup, used, tokens);
        if (used.find("@ARMOUR_WAVES@") != std::string::npos && f.wave_height <= 0.0 &&
            !makes_wave_train(scene))
            throw InputError(file + ": key 'fluid.wave_height': fluid.case \"" + f.case_name +
                             "\" makes a solitary wave: give its height (> 0 m)");
    }
    check_flume_grading(scene, setup, used);
    check_units_refined(scene, setup);
    const std::string plugin = plugin_path();
    if (!fs::is_regular_file(plugin))
        throw InputError("OpenFOAM plugin " + plugin + " not found: build the target armourFoamCoupling");
    if (used.find("@ARMOUR_WAVES@") != std::string::npos && !fs::is_regular_file(waves_library(plugin)))
        throw InputError("fluid.case \"" + f.case_name + "\" needs the wave library " +
                         waves_library(plugin) + ": build the target armourWaves (or set ARMOUR_WAVES_LIB)");
    const FlumeMesh mesh = flume_mesh(scene);
    for (const char *tool : {"blockMesh", "setFields", "interFoam"})
        if (!on_path(tool))
            throw InputError(std::string(tool) +
                             " not found on PATH: install Debian's openfoam (docs/openfoam.md)");
    check_openfoam_project_dir();
    if (np > 1) {
        for (const char *tool : {"decomposePar", "mpirun"})
            if (!on_path(tool))
                throw InputError(std::string(tool) + " not found on PATH: needed for --np " +
                                 std::to_string(np));
        if (mesh.axes[0].cells < 2 * np)
            throw InputError(file + ": key 'fluid.np': " + std::to_string(np) +
                             " ranks split the mesh along x, " + "which has only " +
                             std::to_string(mesh.axes[0].cells) + " cells (need >= 2 per rank)");
    }
}

// Units against the mesh box and the walls: placement errors, resting contacts.
void check_unit_placement(const Scene &scene, const SceneSetup &setup, std::vector<std::string> &warnings) {
    const std::string &file = scene.file;
    const Eigen::Vector3d h = fine_cell_size(scene);
    if (!setup.bodies.empty() && h.maxCoeff() > 2.0 * h.minCoeff())
        warnings.push_back("fluid cells are stretched (" + figure_text(h.x()) + " x " + figure_text(h.y()) +
                           " x " + figure_text(h.z()) + " m): the mask ramp follows the largest side");
    // A unit resting on a wall (or on the mesh's bottom face) reaches into it
    // by its contact overlap, or where its exact shape sticks out of its
    // clump (a settled layer): under half a cell the mask cannot tell, so
    // that is one warning for all such units; deeper is a placement error.
    const double resolvable = 0.5 * h.minCoeff();
    // Units placed for a settle may stand above the mesh (scene_setup.h).
    const Eigen::Vector3d top_room(0.0, 0.0, settle_headroom(scene, setup));
    double resting_depth = 0.0;
    int resting_units = 0;
    for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
        const BodyInit &b = setup.bodies[i];
        const std::string who = "body " + std::to_string(i) + " (unit '" + setup.units[b.unit].name + "')";
        const std::vector<Eigen::Vector3d> vertices = posed_vertices(setup, b);
        double depth = 0.0;
        for (const auto &v : vertices) {
            const double beyond =
                std::max((scene.domain_min - v).maxCoeff(), (v - scene.domain_max - top_room).maxCoeff());
            if (beyond > resolvable)
                throw InputError(file + ": " + who +
                                 " reaches outside the fluid mesh box run.domain_min .. " +
                                 "run.domain_max (vertex " + foam_vector(v) + " m)");
            depth = std::max(depth, beyond);
        }
        for (const auto &w : setup.walls) {
            // The exact shape, which the fluid sees (build_scene checked the clump).
            double into = -HUGE_VAL;
            const double front = wall_front(w, b.pose.position);
            for (const auto &v : vertices)
                into = std::max(into, depth_behind_wall(v, w, b.pose.position, front));
            if (into > resolvable)
                throw InputError(
                    file + ": " + who + " cuts into wall '" + w.name + "' by " + figure_text(into) +
                    " m at its initial pose (more than half a fluid cell); move it clear of the wall");
            depth = std::max(depth, into);
        }
        if (depth > 1e-9) {
            ++resting_units;
            resting_depth = std::max(resting_depth, depth);
        }
    }
    if (resting_units > 0)
        warnings.push_back(std::to_string(resting_units) + " unit(s) reach up to " +
                           figure_text(resting_depth) +
                           " m into a wall or through the mesh box (resting contacts; below half a fluid "
                           "cell, the mask does not resolve it)");
}

// Cells across each unit, and soft contacts against the exchange's stability.
void unit_cell_warnings(const Scene &scene, const SceneSetup &setup, std::vector<std::string> &warnings) {
    const SceneFluid &f = *scene.fluid;
    const Eigen::Vector3d h = fine_cell_size(scene);
    for (std::size_t k = 0; k < setup.units.size(); ++k) {
        const double across = setup.unit_Dn[k] / h.maxCoeff();
        if (across < 4.0) {
            char buf[160];
            std::snprintf(buf, sizeof buf,
                          "unit '%s': %.2f cells across (Dn %.4g m, cell %.4g m); below ~4 the ",
                          setup.units[k].name.c_str(), across, setup.unit_Dn[k], h.maxCoeff());
            warnings.push_back(std::string(buf) + "mask and the loads are coarse (refine fluid.cells)");
        }
        // Soft contacts vibrate: a unit resting on a wall moves into it and
        // back by micrometres at the contact frequency, and the penalty forces
        // the fluid in the cell layer between them to follow, which it cannot
        // (a squeeze film). The pressure that builds is a damping load
        // rho_f K V_layer v, applied explicitly one fluid step late: unstable
        // once rho_f K V_layer dt / m, about N = K dt (rho_f / rho_s) (h / Dn),
        // passes about one; how much fluid a unit traps against walls sets
        // the constant. Measured with LIGGGHTS: one cube on a tank floor
        // (still_water_cube, 1 s) stable at N = 4.2, stopped by
        // Coupler::check_stability at 12.5; 100 settled cubes
        // (bench_tank_cubes) stable at N = 0.42 over 0.5 s, but one cube
        // wedged against the tank wall went unstable at N = 1.67.
        // Rigid contacts (bullet) do not vibrate.
        if (engine_style(scene.engine).capabilities.contacts == ContactKind::spring_dashpot) {
            const double unit_density = setup.units[k].props.mass / setup.units[k].props.volume;
            const double n = f.penalty * f.max_time_step * (f.fluid_density / unit_density) *
                             (h.maxCoeff() / setup.unit_Dn[k]);
            if (n > 1.0) {
                char buf[512];
                std::snprintf(
                    buf, sizeof buf,
                    "unit '%s' with LIGGGHTS' soft contacts: fluid.penalty x fluid.max_time_step x "
                    "(rho_f / rho_unit) x (cell / Dn) = %.3g > 1: a unit resting against a wall may "
                    "make the exchange unstable (measured: stable at 0.42, unstable from 1.67 for a "
                    "unit wedged against a wall); the run stops if it does. Lower fluid.penalty to "
                    "%.3g 1/s or below, or use engine bullet",
                    setup.units[k].name.c_str(), n, f.penalty / n);
                warnings.push_back(buf);
            }
        }
    }
}

void first_step_warnings(const Scene &scene, const SceneSetup &setup, std::vector<std::string> &warnings) {
    const SceneFluid &f = *scene.fluid;
    const Eigen::Vector3d h = fine_cell_size(scene);
    // The body's own Courant number in its first step: interFoam only sees
    // the body's velocity once the penalty has set the fluid moving.
    for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
        const BodyInit &b = setup.bodies[i];
        double reach = 0.0;
        for (const auto &v : setup.units[b.unit].mesh.vertices)
            reach = std::max(reach, v.norm());
        const double speed = b.velocity.norm() + b.angular_velocity.norm() * reach;
        const double co = speed * f.max_time_step / h.minCoeff();
        if (co > f.max_courant)
            warnings.push_back("body " + std::to_string(i) + ": initial speed " + figure_text(speed) +
                               " m/s gives Courant " + figure_text(co) +
                               " > fluid.max_courant at fluid.max_time_step; " +
                               "the first step starts smaller");
    }
}

void engine_step_warnings(const Scene &scene, const SceneSetup &setup, std::vector<std::string> &warnings) {
    const SceneFluid &f = *scene.fluid;
    const std::string &file = scene.file;
    // The engine's own step against its contact stability limit: refused here,
    // before any tool runs, as a DEM run refuses it (run.force_time_step lets
    // it through, with a warning); an engine step above the largest fluid step
    // leaves fluid steps without an engine step.
    {
        const auto engine = make_engine(scene.engine, setup.settings);
        for (const auto &u : setup.units)
            engine->add_template(u);
        for (const auto &w : setup.walls)
            engine->add_wall(w);
        TimeStepReport dt;
        try {
            dt = engine->time_step_report();
        } catch (const InputError &e) {
            throw InputError(file + ": " + e.what());
        }
        if (dt.forced)
            warnings.push_back("run.time_step " + figure_text(dt.used) +
                               " s exceeds the engine's stability limit " + figure_text(dt.limit) +
                               " s (run.force_time_step = true): contacts may blow up");
        if (dt.used > f.max_time_step)
            warnings.push_back("engine step " + figure_text(dt.used) + " s exceeds fluid.max_time_step " +
                               number_text(f.max_time_step) +
                               " s: fluid steps shorter than it run no engine step");
    }
}

} // namespace

std::vector<std::string> check_fluid_case(const Scene &scene, const SceneSetup &setup, int np) {
    check_case_template(scene, setup, np);
    std::vector<std::string> warnings;
    check_unit_placement(scene, setup, warnings);
    unit_cell_warnings(scene, setup, warnings);
    for (const std::string &w : rocking_clump_warnings(scene, setup))
        warnings.push_back(w);
    first_step_warnings(scene, setup, warnings);
    engine_step_warnings(scene, setup, warnings);
    return warnings;
}

// The note in constant/polyMesh/owner.
long mesh_cells(const fs::path &case_dir) {
    const std::string owner = read_text_file(case_dir / "constant" / "polyMesh" / "owner");
    const auto at = owner.find("nCells:");
    return at == std::string::npos ? -1 : std::atol(owner.c_str() + at + 7);
}

std::map<std::string, std::string> case_paths(const fs::path &scene_file, const std::string &cache_dir,
                                              const fs::path &out) {
    const std::string plugin = plugin_path(); // checked by check_fluid_case
    return {
        {"@ARMOUR_PLUGIN@", plugin},
        {"@ARMOUR_WAVES@", waves_library(plugin)}, // checked by check_fluid_case where used
        {"@SCENE@", scene_file.string()},
        {"@CACHE@", cache_dir},
        {"@OUTPUT@", out.string()},
    };
}

void write_case(const Scene &scene, const SceneSetup &setup, const std::map<std::string, std::string> &paths,
                const fs::path &case_dir) {
    use_debian_openfoam();
    const SceneFluid &f = *scene.fluid;
    fs::copy(source_dir() / "foam_cases" / f.case_name, case_dir, fs::copy_options::recursive);
    if (setup.bodies.empty()) // an empty wave flume: interFoam alone, nothing to couple
        fs::remove(case_dir / "constant" / "fvOptions");
    const std::string used = template_text(case_dir);
    std::map<std::string, std::string> tokens = paths;
    tokens.merge(mesh_tokens(scene));
    tokens.merge(fluid_tokens(scene, setup));
    geometry_tokens(scene, setup, used, tokens); // checked by check_fluid_case
    wave_tokens(scene, used, tokens);
    fill_tokens(case_dir, tokens);
    write_fluid_models(scene, case_dir);
}

void mesh_case(const Scene &scene, const fs::path &case_dir) {
    use_debian_openfoam();
    run_tool("blockMesh", {"blockMesh"}, case_dir, scene.duration, false);
    refine_flume_mesh(scene, case_dir);
    // system/topoSetDict: the cellSet "fluid" (porous zones join it) that the mesh keeps (slope_waves).
    const bool blocked = fs::is_regular_file(case_dir / "system" / "topoSetDict");
    if (blocked)
        run_tool("topoSet", {"topoSet"}, case_dir, scene.duration, false);
    if (needs_porous_zones(scene))
        run_tool("topoSet.porous", {"topoSet", "-dict", "system/topoSetDict.porous"}, case_dir,
                 scene.duration, false);
    if (blocked)
        run_tool("subsetMesh", {"subsetMesh", "-overwrite", "fluid", "-patch", "walls"}, case_dir,
                 scene.duration, false);
    for (const auto &e : fs::directory_iterator(case_dir / "0"))
        if (e.path().extension() == ".orig")
            fs::copy_file(e.path(), case_dir / "0" / e.path().stem(), fs::copy_options::overwrite_existing);
    run_tool("setFields", {"setFields"}, case_dir, scene.duration, false);
    if (scene.checkpoint_interval > 0.0)
        write_fields_exactly(case_dir);
    if (scene.fluid->np > 1)
        run_tool("decomposePar", {"decomposePar", "-force"}, case_dir, scene.duration, false);
}

void resume_case(const Scene &scene, const Checkpoint &checkpoint,
                 const std::map<std::string, std::string> &paths, const fs::path &case_dir) {
    use_debian_openfoam();
    const SceneFluid &f = *scene.fluid;
    const RestoredCase restored = restore_case(case_dir, checkpoint, scene.duration);
    set_resumable_controls(case_dir, f.max_courant, f.max_interface_courant, f.write_interval);
    refill_paths(case_dir, source_dir() / "foam_cases" / f.case_name, paths);
    if (restored.ranks == f.np) // the fields split anew for this run's ranks
        return;
    if (restored.ranks > 1)
        run_tool("reconstructPar", {"reconstructPar", "-time", restored.time_name}, case_dir, scene.duration,
                 false);
    if (f.np > 1) {
        set_ranks(case_dir, f.np);
        run_tool("decomposePar", {"decomposePar", "-force", "-time", restored.time_name}, case_dir,
                 scene.duration, false);
    }
}

void run_interfoam(const Scene &scene, const fs::path &case_dir, const Checkpoint *resume) {
    use_debian_openfoam();
    const SceneFluid &f = *scene.fluid;
    const std::vector<std::string> malloc_settings = keep_solver_memory();
    const StepFloor step_floor{f.min_time_step, scene.file};
    const double start = resume ? resume->time : 0.0;
    if (f.np == 1) {
        run_tool("interFoam", {"interFoam"}, case_dir, scene.duration, true, start, step_floor);
        return;
    }
    std::vector<std::string> mpirun = {"mpirun", "--allow-run-as-root", "-np", std::to_string(f.np)};
    for (const auto &name :
         {std::string("WM_PROJECT_DIR"), std::string("LD_LIBRARY_PATH"), std::string("ARMOUR_WALL_ORIGIN")})
        mpirun.insert(mpirun.end(), {"-x", name});
    for (const auto &name : malloc_settings)
        mpirun.insert(mpirun.end(), {"-x", name});
    mpirun.insert(mpirun.end(), {"interFoam", "-parallel"});
    run_tool("interFoam", mpirun, case_dir, scene.duration, true, start, step_floor);
}

} // namespace armour
