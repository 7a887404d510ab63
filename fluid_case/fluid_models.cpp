#include "fluid_models.h"

#include "output_folder.h"
#include "scene_keys.h"

#include <cmath>
#include <string>

namespace armour {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string header(const std::string &cls, const std::string &object) {
    return "FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       " + cls +
           ";\n    object      " + object +
           ";\n}\n// Written by armour run from the scene (fluid_case/fluid_models.cpp).\n\n";
}

// A turbulence field: `wall_type` on every patch of type wall (the patch
// group "wall" takes precedence over the wildcard), `open_type` elsewhere.
std::string turbulence_field(const std::string &name, const std::string &dimensions, double value,
                             const std::string &wall_type, const std::string &open_type) {
    const std::string v = "uniform " + number_text(value);
    return header("volScalarField", name) + "dimensions      " + dimensions + ";\ninternalField   " + v +
           ";\n\nboundaryField\n{\n    #includeEtc \"caseDicts/setConstraintTypes\"\n\n    \".*\"\n    {\n"
           "        type            " +
           open_type + ";\n" + (open_type == "inletOutlet" ? "        inletValue      " + v + ";\n" : "") +
           "        value           " + v + ";\n    }\n    wall\n    {\n        type            " +
           wall_type + ";\n        value           " + v + ";\n    }\n}\n";
}

void append(const fs::path &path, const std::string &text) {
    write_text_file(path, read_text_file(path) +
                              "\n// Appended by armour run (fluid_case/fluid_models.cpp).\n" + text);
}

void write_turbulence(const Scene &scene, const fs::path &case_dir) {
    const TurbulenceStart s = turbulence_start(scene);
    write_text_file(case_dir / "constant" / "turbulenceProperties",
                    header("dictionary", "turbulenceProperties") +
                        "simulationType  RAS;\n\nRAS\n{\n    RASModel        " + scene.fluid->turbulence +
                        ";\n    turbulence      on;\n    printCoeffs     on;\n}\n");
    const fs::path zero = case_dir / "0";
    write_text_file(zero / "k.orig",
                    turbulence_field("k", "[0 2 -2 0 0 0 0]", s.k, "kqRWallFunction", "inletOutlet"));
    write_text_file(zero / "omega.orig", turbulence_field("omega", "[0 0 -1 0 0 0 0]", s.omega,
                                                          "omegaWallFunction", "inletOutlet"));
    write_text_file(zero / "nut.orig",
                    turbulence_field("nut", "[0 2 -1 0 0 0 0]", 0.0, "nutkWallFunction", "calculated"));
    // Upwind k and omega: bounded, and their diffusion dwarfs the scheme's.
    append(case_dir / "system" / "fvSchemes",
           "divSchemes\n{\n    div(phi,k)      Gauss upwind;\n    div(phi,omega)  Gauss upwind;\n}\n\n"
           "wallDist\n{\n    method          meshWave;\n}\n");
    append(
        case_dir / "system" / "fvSolution",
        "solvers\n{\n    \"(k|omega).*\"\n    {\n        solver          smoothSolver;\n"
        "        smoother        symGaussSeidel;\n        tolerance       1e-8;\n        relTol          0;\n"
        "    }\n}\n");
}

std::string foam_point(double x, double y, double z) {
    return "(" + number_text(x) + " " + number_text(y) + " " + number_text(z) + ")";
}

// One topoSet action on the cellSet `set`.
std::string set_action(const std::string &set, const std::string &action, const std::string &source) {
    return "    { name " + set + "; type cellSet; action " + action + "; " + source + " }\n";
}

// The cells of a slope_layer region: under the slope's face (its plane, from
// the toe rising at 1:cot) and its crest (z = floor + height), above the
// floor, whose centre's distance below the nearer of the two (the distance
// to the surface inside the convex body) lies in [depth, depth + thickness).
// `far` is beyond the mesh: it stands for an unbounded side.
std::string slope_layer_actions(const ScenePorous &p, const SceneWall &w, const std::string &set,
                                double far) {
    const double sin_t = 1.0 / std::sqrt(1.0 + w.cot * w.cot), cos_t = w.cot * sin_t;
    const double crest_z = w.floor_z + w.height, d0 = p.depth, d1 = p.thickness ? d0 + *p.thickness : far;
    // Between distances a and b below the face plane: a box along the face
    // (i up it, j across, k into the body: right-handed), from far below the
    // toe to far above the crest.
    auto under_face = [&](double a, double b) {
        const double x = w.toe_x - far * cos_t + a * sin_t, z = w.floor_z - far * sin_t - a * cos_t;
        return "source rotatedBoxToCell; origin " + foam_point(x, far, z) + "; i " +
               foam_point(2 * far * cos_t, 0, 2 * far * sin_t) + "; j " + foam_point(0, -2 * far, 0) +
               "; k " + foam_point((b - a) * sin_t, 0, -(b - a) * cos_t) + ";";
    };
    auto under_crest = [&](double a, double b) {
        return "source boxToCell; box " + foam_point(-far, -far, crest_z - b) + " " +
               foam_point(far, far, crest_z - a) + ";";
    };
    const std::string above_floor =
        "source boxToCell; box " + foam_point(-far, -far, w.floor_z) + " " + foam_point(far, far, far) + ";";
    std::string actions = set_action(set, "new", under_face(d0, d1)) +
                          set_action(set, "subset", under_crest(d0, far)) +
                          set_action(set, "subset", above_floor);
    if (p.thickness) { // and the band under the crest, where the face is further
        const std::string crest = set + "_crest";
        actions +=
            set_action(crest, "new", under_crest(d0, d1)) + set_action(crest, "subset", under_face(d0, far)) +
            set_action(crest, "subset", above_floor) +
            set_action(set, "add", "source cellToCell; set " + crest + ";") + set_action(crest, "remove", "");
    }
    return actions;
}

// The zones and sources of the [[porous]] regions. A template that cuts
// cells out of the mesh (system/topoSetDict makes the cellSet "fluid" that
// subsetMesh keeps) keeps the porous cells too: this dictionary runs
// between the two, and subsetMesh keeps the zones.
void write_porosity(const Scene &scene, const fs::path &case_dir) {
    const SceneFluid &f = *scene.fluid;
    const bool cuts_cells = fs::is_regular_file(case_dir / "system" / "topoSetDict");
    const double far = 10.0 * (1.0 + (scene.domain_max - scene.domain_min).norm());
    std::string actions, options;
    for (const ScenePorous &p : scene.porous) {
        const std::string zone = "porous_" + p.name;
        const DarcyForchheimer c = darcy_forchheimer(p, f.viscosity, scene.gravity.norm());
        const std::string d = number_text(c.d), fc = number_text(c.f);
        if (p.type == "slope_layer") {
            for (const SceneWall &w : scene.walls)
                if (w.name == p.wall)
                    actions += slope_layer_actions(p, w, zone, far);
        } else {
            actions += set_action(zone, "new",
                                  "source boxToCell; box " + foam_point(p.min.x(), p.min.y(), p.min.z()) +
                                      " " + foam_point(p.max.x(), p.max.y(), p.max.z()) + ";");
        }
        actions += "    { name " + zone + "; type cellZoneSet; action new; source setToCellZone; set " +
                   zone + "; }\n";
        if (cuts_cells)
            actions += set_action("fluid", "add", "source cellToCell; set " + zone + ";");
        options +=
            "// van Gent (1995): Dn50 " + number_text(p.stone_size) + " m, n " + number_text(p.porosity) +
            ", alpha " + number_text(p.alpha) + ", beta " + number_text(p.beta) +
            ": a = " + number_text(c.a) + " s/m, b = " + number_text(c.b) + " s^2/m^2\n" + zone +
            "\n{\n    type            explicitPorositySource;\n    active          yes;\n\n"
            "    explicitPorositySourceCoeffs\n    {\n        selectionMode   cellZone;\n"
            "        cellZone        " +
            zone +
            ";\n        type            DarcyForchheimer;\n\n        DarcyForchheimerCoeffs\n"
            "        {\n            d   [0 -2 0 0 0 0 0] (" +
            d + " " + d + " " + d + ");\n            f   [0 -1 0 0 0 0 0] (" + fc + " " + fc + " " + fc +
            ");\n            coordinateSystem\n            {\n                type    cartesian;\n"
            "                origin  (0 0 0);\n                e1      (1 0 0);\n"
            "                e2      (0 1 0);\n            }\n        }\n    }\n}\n\n";
    }
    write_text_file(case_dir / "system" / "topoSetDict.porous",
                    header("dictionary", "topoSetDict") + "actions\n(\n" + actions + ");\n");
    const fs::path fv_options = case_dir / "constant" / "fvOptions";
    if (fs::is_regular_file(fv_options))
        append(fv_options, options);
    else
        write_text_file(fv_options, header("dictionary", "fvOptions") + options);
}

} // namespace

DarcyForchheimer darcy_forchheimer(const ScenePorous &p, double viscosity, double gravity) {
    const double n = p.porosity, D = p.stone_size, n3 = n * n * n;
    DarcyForchheimer c;
    // d and f straight from the rock (the case needs no g, nor nu); a and b,
    // the hydraulic gradient's, through them.
    c.d = p.alpha * (1.0 - n) * (1.0 - n) / (n3 * D * D);
    c.f = 2.0 * p.beta * (1.0 - n) / (n3 * D);
    c.a = c.d * viscosity / gravity;
    c.b = c.f / (2.0 * gravity);
    return c;
}

TurbulenceStart turbulence_start(const Scene &scene) {
    const SceneFluid &f = *scene.fluid;
    // The reference speed: the shallow-water celerity at the still-water depth
    // (the mesh's height for a dry start, a dam break's column).
    double depth = scene.still_water_depth();
    if (depth <= 0.0)
        depth = scene.domain_max.z() - scene.domain_min.z();
    const double speed = std::sqrt(scene.gravity.norm() * depth);
    const double c_mu = 0.09;
    TurbulenceStart s;
    s.k = 1.5 * std::pow(f.turbulence_intensity * speed, 2);
    s.omega = std::sqrt(s.k) / (std::pow(c_mu, 0.25) * f.turbulence_length);
    s.nut = s.k / s.omega;
    return s;
}

// p_rghFinal copied p_rgh ($p_rgh) when the template was read, so it takes
// the absolute tolerance again; its relTol stays the template's 0.
void write_pressure_solve(const SceneFluid &f, const fs::path &case_dir) {
    std::string p_rgh, final;
    if (f.pressure_tolerance) {
        p_rgh += "        tolerance       " + number_text(*f.pressure_tolerance) + ";\n";
        final = p_rgh;
    }
    if (f.pressure_relative_tolerance)
        p_rgh += "        relTol          " + number_text(*f.pressure_relative_tolerance) + ";\n";
    append(case_dir / "system" / "fvSolution",
           "solvers\n{\n    p_rgh\n    {\n" + p_rgh + "    }\n" +
               (final.empty() ? "" : "    p_rghFinal\n    {\n" + final + "    }\n") + "}\n");
}

void write_fluid_models(const Scene &scene, const fs::path &case_dir) {
    if (scene.fluid->pressure_tolerance || scene.fluid->pressure_relative_tolerance)
        write_pressure_solve(*scene.fluid, case_dir);
    if (const std::optional<bool> &predictor = scene.fluid->momentum_predictor)
        append(case_dir / "system" / "fvSolution",
               std::string("PIMPLE\n{\n    momentumPredictor ") + (*predictor ? "yes" : "no") + ";\n}\n");
    if (scene.fluid->turbulence != "laminar")
        write_turbulence(scene, case_dir);
    if (needs_porous_zones(scene))
        write_porosity(scene, case_dir);
}

bool needs_porous_zones(const Scene &scene) {
    return !scene.porous.empty();
}

void add_fluid_models_summary(const Scene &scene, json &summary) {
    const SceneFluid &f = *scene.fluid;
    json turbulence = {{"model", f.turbulence}};
    if (f.turbulence != "laminar") {
        const TurbulenceStart s = turbulence_start(scene);
        turbulence["k0"] = s.k;
        turbulence["omega0"] = s.omega;
        turbulence["nut0"] = s.nut;
        turbulence["nut0_over_nu"] = s.nut / f.viscosity;
    }
    summary["fluid"]["turbulence"] = turbulence;
    // null: the template's own (its system/fvSolution).
    summary["fluid"]["pressure_tolerance"] =
        f.pressure_tolerance ? json(*f.pressure_tolerance) : json(nullptr);
    summary["fluid"]["pressure_relative_tolerance"] =
        f.pressure_relative_tolerance ? json(*f.pressure_relative_tolerance) : json(nullptr);
    summary["fluid"]["momentum_predictor"] =
        f.momentum_predictor ? json(*f.momentum_predictor) : json(nullptr);
    if (scene.porous.empty())
        return;
    json regions = json::array();
    for (const ScenePorous &p : scene.porous) {
        const DarcyForchheimer c = darcy_forchheimer(p, f.viscosity, scene.gravity.norm());
        regions.push_back({{"name", p.name},
                           {"zone", "porous_" + p.name},
                           {"stone_size", p.stone_size},
                           {"porosity", p.porosity},
                           {"a", c.a},
                           {"b", c.b},
                           {"d", c.d},
                           {"f", c.f}});
    }
    summary["fluid"]["porous"] = regions;
}

} // namespace armour
