// A scene file: the single source of truth for one `armour run`.
//
// Description
//     TOML (toml++), SI units. Every key is declared once in the key table
//     (scene_keys.h: unit, range, doc; the member initialisers below are the
//     defaults), from which docs/scenes.md's key reference is generated; the
//     examples live in scenes/. load_scene() checks every key and
//     value before anything runs: an unknown key, a missing key or a bad value
//     throws InputError "FILE:LINE: key 'a.b': reason". Overrides given as
//     --set key=value (dotted path, TOML value syntax, a string key's value
//     also bare: waves.type=irregular; arrays of tables by index, e.g.
//     unit.0.spheres=20) are applied before the checks, so they are checked
//     the same way, and the resolved scene can be written back.
//
// Usage
//     Scene scene = load_scene("scenes/drop_bounce.toml", {"run.duration=0.5"});
//     std::string resolved = resolved_scene_toml(scene); // OUT/scene.resolved.toml
#pragma once

#include "jonswap.h"
#include "shapes.h"
#include "standard_conditions.h"

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace armour {

struct SceneUnit {
    std::string name;
    std::string shape;                 // "cube" | "dolos" | "stl"
    double size = 0.0;                 // cube edge, m
    double chamfer = 0.0;              // m
    double height = 0.0;               // dolos H, m
    double waist = kDolosWaistDefault; // dolos waist ratio
    std::string stl;                   // path, resolved relative to the scene file
    double density = 2400.0;           // kg/m^3
    int spheres = 0;                   // > 0: fixed count; 0: tolerance mode
    int edge_spheres = 0;              // support spheres along each resting face's edges, of `spheres`
    double tol_volume = 0.01;
    double tol_surface = 0.02;
    std::string method = "optimised";
    std::string material; // name of a [[material]]
};

struct SceneMaterial {
    std::string name;
    double youngs_modulus = 5e7; // Pa
    double poisson_ratio = 0.25;
    double restitution = 0.5;
    double friction = 0.6;
    double rolling_friction = 0.0;
};

struct SceneMaterialPair {
    std::string a, b;
    std::optional<double> restitution, friction, rolling_friction;
    // Whether this is the (unordered) pair of materials x and y.
    bool joins(const std::string &x, const std::string &y) const {
        return (a == x && b == y) || (a == y && b == x);
    }
};

// type "plane": point, normal, size (edge of the square patch, m)
// type "slope": a 1:cot slope rising in +x: toe at x = toe_x on the floor z = floor_z,
//               cot (horizontal per vertical, e.g. 1.5), height (m), width along y (m),
//               toe_height (m, a vertical step at the toe, 0 = none), floor included
// type "box":   min, max (m): floor and four side walls, open top
// type "stl":   file (resolved relative to the scene file)
struct SceneWall {
    std::string name;
    std::string type;
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    double size = 10.0;
    double toe_x = 0.0, floor_z = 0.0, cot = 1.5, height = 1.0, width = 2.0, toe_height = 0.0;
    Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero();
    std::string file;
    std::string material;
};

// One explicitly placed body.
struct SceneBody {
    std::string unit;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();         // m, centre of mass
    Eigen::Vector4d orientation = Eigen::Vector4d(1, 0, 0, 0);  // quaternion w, x, y, z (normalised on load)
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();         // m/s
    Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero(); // rad/s
    std::array<bool, 3> fixed_translation{{false, false, false}};
    std::array<bool, 3> fixed_rotation{{false, false, false}};
    std::optional<Eigen::Vector3d> pivot; // m, world: the point fixed_translation holds (free_body only)
};

// Random drop: `count` units at random non-overlapping poses in a region,
// released at rest, then the run settles them.
struct SceneDrop {
    std::string unit;
    int count = 0;
    Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero(); // m
    std::uint64_t seed = 1;
};

// Pattern on a slope wall: rows along the slope, columns along y, each unit
// `gap` (m) above the slope surface; "grid" units face the slope, "random"
// ones are turned and moved at random in their grid slots (scene_setup.cpp).
struct ScenePattern {
    std::string unit;
    std::string wall; // name of a "slope" wall
    int rows = 1, columns = 1;
    double spacing = 0.0;         // m between centres (0 = 1.05 x the size of the shape the engine collides)
    double gap = 0.01;            // m
    double packing_density = 0.0; // units per Dn^2 of slope, all layers (> 0: sets spacing)
    int layers = 1;               // stacked; every other one shifted half a spacing (scene_keys.cpp)
    std::string placement = "grid"; // grid | random | seated
    std::uint64_t seed = 1;         // random and seated placement: the same seed gives the same poses
    // random and seated: true sets no unit's centre seaward of the slope's
    // foot (toe_x); unset (as every layer kept before it) or false lets it.
    // Unset is not written, so a scene without it keeps its text and hash.
    std::optional<bool> clear_of_toe;
    // The first row placed (0: from the toe). A settle in stages
    // (fluid.settle_stages) places a pattern a few rows at a time, each
    // stage's rows clear of the units settled before them ([[body]]).
    int first_row = 0;
};

// A coupled fluid run (interFoam through the armourCoupling plugin): the
// mesh box is run.domain_min/max, water below water_level at the start.
struct SceneFluid {
    std::string case_name = "tank";      // template folder in foam_cases/ (key `case`)
    double water_level = 0.0;            // m, z of the still-water surface
    std::array<int, 3> cells{{0, 0, 0}}; // blockMesh cells along x, y, z (from cell_size when given)
    double cell_size = 0.0;              // m; 0 = `cells` was given
    // A graded mesh (the wave_flume template, fluid_case/flume_mesh.h): along each
    // axis cells keep the size `cells` gives inside refine_min..refine_max
    // and grow outside it, by at most 10 % per cell, to coarse_cell_size.
    std::optional<Eigen::Vector3d> refine_min, refine_max;      // m; absent = uniform
    Eigen::Vector3d coarse_cell_size = Eigen::Vector3d::Zero(); // m along x, y, z; <= fine: not graded
    double penalty = 1e5;                                       // K [1/s] of -rho K chi (U - U_body)
    std::string mask = "exact";                                 // exact | spheres
    std::string solid_fraction = "exact";      // exact | ramp (the former sampled cosine ramp)
    double smoothing_cells = 1.0;              // width of the chi ramp [cells] (solid_fraction = "ramp")
    double added_mass = 0.0;                   // C_a [-]
    int np = 1;                                // MPI ranks of interFoam
    double fluid_density = kFreshWaterDensity; // kg/m^3, water
    double air_density = 1.0;                  // kg/m^3
    double viscosity = 1e-6;                   // m^2/s, water, kinematic
    double air_viscosity = 1.48e-5;            // m^2/s, air, kinematic
    double max_courant = 0.5;                  // interFoam maxCo: every cell
    double max_interface_courant = 0.5;        // interFoam maxAlphaCo (the parser's default: max_courant)
    double max_time_step = 0.005;              // s, largest fluid step (at most run.output_interval)
    // s: a fluid step below this stops the run with an error (a diverged flow
    // or a stalled pressure solve shrinks the step without end). The parser's
    // default: the step of a 1 km/s flow through the smallest cell at the
    // smaller Courant limit, at most max_time_step / 100.
    double min_time_step = 0.0;
    double write_interval = 0.0; // s between field writes (the parser's default: run.duration)
    // The scene gave these keys, whose defaults follow other keys
    // (write_interval: run.duration; max_interface_courant: max_courant;
    // min_time_step: the Courant limits, max_time_step and the cells). One not
    // given is not written out, so a scene written from this one (a settle's
    // scene.settled.toml) still follows its own duration, limits and cells.
    bool write_interval_given = false, max_interface_courant_given = false, min_time_step_given = false;
    // p_rgh's solve (OpenFOAM's normalised residuals): stop at this absolute
    // residual, and in the correctors before the last at this fraction of the
    // initial one. Unset: the template's (docs/openfoam.md).
    std::optional<double> pressure_tolerance, pressure_relative_tolerance;
    // PIMPLE's momentumPredictor: solve the momentum equation before the
    // pressure correctors. Unset: the template's (docs/openfoam.md).
    std::optional<bool> momentum_predictor;
    // Optional water column (dam break): water in this box at the start, besides
    // the water below water_level (which may then be left at domain_min.z: dry).
    bool has_water_box = false;
    Eigen::Vector3d water_box_min = Eigen::Vector3d::Zero(), water_box_max = Eigen::Vector3d::Zero(); // m
    double wave_height = 0.0; // m, solitary wave H of a wave template's inlet (0 = none)
    // Benchmark reference: units held where they start, mask imposed once, no
    // load integration and no engine advance (bench/run_coupled_bench.sh).
    bool frozen = false;
    // Cells wholly inside a unit that pierces the free surface take the
    // outside water's phase at their height (docs/coupling.md, the interior).
    bool mirror_interior = false;
    // s: settle the units in the DEM, under the still water's buoyancy, this
    // long before coupling (0 = start coupling from the placed poses). The
    // coupled run starts from the settled poses, written to
    // OUT/settle/scene.settled.toml.
    double settle_time = 0.0;
    // Coulomb friction between units during the settle only (unset: the
    // materials' own). A placer seats each unit by hand or crane; a pile
    // dropped at once locks loose at concrete's 0.6 (docs/stability.md).
    std::optional<double> settle_friction;
    // kg/m^3: every unit's density during the settle only (unset: the units'
    // own). A laboratory places one layer whatever the concrete; a DEM pile
    // settles into a different layer at each density (the seat's overlaps and
    // the chaos of the drop), so a sweep over density that holds the layer
    // settles every case at one density (docs/scenes.md, "Settling before
    // coupling").
    std::optional<double> settle_density;
    // The settle builds the [[pattern]]'s layer in this many stages from the
    // toe up, as a placer builds it: each stage places the next rows clear
    // of the units settled so far and settles them all (settle_time / stages;
    // the last stage settle_time). 1 = the whole pile at once.
    int settle_stages = 1;
    // The engine of the settle ("" = run.engine): clumps settle a layer that
    // exact hulls then meet the waves in, so both engines start from one layer.
    std::string settle_engine;
    // The engine that settled the bodies ("" = not settled by armour): a
    // settle writes it into RUN/settle/scene.settled.toml, so a run of that
    // scene with another unit model is warned that it inherits a layer its
    // units did not settle into.
    std::string settled_by;
    // How much that settle grew each cube to hold its clump (1 = not grown),
    // written beside settled_by: exact hulls run from these poses start up to
    // that growth apart and drop into the gaps before any wave (measured:
    // docs/validation/stability.md), so a run of them is warned.
    double settled_growth = 1.0;
    // Turbulence closure (docs/turbulence.md): laminar, or OpenFOAM's RAS
    // kOmegaSST with k and omega at the start from an intensity of the
    // shallow-water celerity sqrt(g depth) and a length scale.
    std::string turbulence = "laminar";
    double turbulence_intensity = 1e-4; // I [-]: k = 1.5 (I sqrt(g depth))^2
    double turbulence_length = 0.01;    // m, l: omega = sqrt(k) / (Cmu^0.25 l)
    // graded: one blockMesh block of `cells` (graded by refine_min/max), the
    // [[refine]] regions unused; refined: that block with cells 2^L times
    // larger in x and y, split back to `cells` in the [[refine]] regions of
    // level L (fluid_case/mesh_refinement.h). The parser's default: refined when the
    // scene has [[refine]] regions.
    std::string mesh = "graded";

    // m along x, y, z: the cell inside refine_min .. refine_max (everywhere on a uniform mesh),
    // and in the finest [[refine]] regions of a refined mesh.
    Eigen::Vector3d fine_cell(const Eigen::Vector3d &domain_extent) const {
        return domain_extent.cwiseQuotient(Eigen::Vector3d(cells[0], cells[1], cells[2]));
    }
};

// [[porous]]: a permeable region (rock underlayer, core) as a Darcy-Forchheimer
// medium, coefficients from van Gent (1995) (docs/porous.md): a box, or a
// layer under a slope wall's face and crest between two distances below it.
struct ScenePorous {
    std::string name;
    std::string type = "box";                                                     // box | slope_layer
    Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero(); // m, box
    std::string wall;                // slope_layer: a [[wall]] of type "slope"
    double depth = 0.0;              // m, slope_layer: its top below the slope's surface
    std::optional<double> thickness; // m, slope_layer: absent = everything below depth (a core)
    double stone_size = 0.0;         // m, Dn50
    double porosity = 0.4;           // n [-]
    double alpha = 1000.0;           // van Gent's laminar coefficient [-]
    double beta = 1.1;               // van Gent's turbulent coefficient [-]
};

// [[refine]]: a region of a refined wave-flume mesh (fluid.mesh "refined",
// fluid_case/mesh_refinement.h) whose cells are halved in x and y `level` times
// from the base cells: a box, or a band about a slope wall's face and crest
// from `below` under them to `above` over them (along their normals).
struct SceneRefine {
    std::string name;
    std::string type = "box";                                                     // box | slope_band
    Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero(); // m, box
    std::string wall;   // slope_band: a [[wall]] of type "slope"
    double below = 0.0; // m, slope_band: under the face and crest
    double above = 0.0; // m, slope_band: over them
    int level = 1;      // halvings in x and y
};

// [waves]: the wave train at the inlet of a wave template (docs/waves.md).
// solitary: the template's solitary wave of fluid.wave_height, as without
// [waves]; regular and irregular: OpenFOAM's stock wave models
// (foam_cases/wave_flume), with an array of three gauges for the
// incident/reflected analysis.
struct SceneWaves {
    std::string type = "regular"; // solitary | regular | irregular
    double height = 0.0;          // m, regular H
    double period = 0.0;          // s, regular T
    std::string theory = "auto";  // auto | StokesII | StokesV | cnoidal | streamFunction (resolved on load)
    double hs = 0.0;              // m, irregular Hm0 (key Hs)
    double tp = 0.0;              // s, irregular peak period (key Tp)
    std::string spectrum = "jonswap";
    double gamma = 3.3;               // JONSWAP peak enhancement (1 = Pierson-Moskowitz)
    std::uint64_t seed = 1;           // phases
    int components = 40;              // even; the train repeats every components Tp / 2
    double ramp_time = 0.0;           // s (the reader's default: 2 periods)
    bool active_absorption = true;    // inlet absorbs waves coming back
    std::string outlet = "absorbing"; // absorbing | shallow_water | wall
    std::optional<double> gauge_x;    // m, first gauge of the array (default: one wavelength from the inlet)
    std::vector<double> extra_gauges; // m, x of more gauges (the total waves there, not separated)

    // The train's own period (s) and height (m): T and H regular, Tp and Hs irregular.
    double target_period() const { return type == "regular" ? period : tp; }
    double target_height() const { return type == "regular" ? height : hs; }
    // The irregular train's sea state (waves/jonswap.h builds its components).
    JonswapSea jonswap_sea() const { return {hs, tp, gamma, components, seed}; }
};

// [[series]]: one sea state of a test series (docs/stability.md, "Test
// series"): the [waves] train (type "irregular") with this height, period,
// peak enhancement and seed, for `duration` s or `waves` of its Tm0,2 after
// its front reaches the slope's toe, started from still water with the units
// where the step before left them.
struct SceneSeriesStep {
    double hs = 0.0;        // m, Hm0 at the maker (key Hs)
    double tp = 0.0;        // s, peak period (key Tp)
    double gamma = 3.3;     // JONSWAP peak enhancement (the reader's default: waves.gamma)
    std::uint64_t seed = 1; // phases (the reader's default: waves.seed)
    double waves = 0.0;     // -, the step's length in waves (0: not given)
    double duration = 0.0;  // s, the step's length (the reader's default: run.duration, or from `waves`)
    double ramp_time = 0.0; // s (the reader's default: waves.ramp_time when given, else 2 Tp)
};

struct Scene {
    std::string file; // path as given
    std::string name;
    // [run]
    std::string engine = "liggghts"; // liggghts | bullet | free_body
    double duration = 1.0;           // s
    double output_interval = 0.01;   // s
    double time_step = 0.0;          // s; 0 = automatic
    bool force_time_step = false;
    int contact_iterations = 0; // rigid-contact engines' solver iterations per step; 0 = the engine's own
    Eigen::Vector3d gravity = Eigen::Vector3d(0, 0, -kStandardGravity);                              // m/s^2
    Eigen::Vector3d domain_min = Eigen::Vector3d(-5, -5, -1), domain_max = Eigen::Vector3d(5, 5, 5); // m
    double checkpoint_interval = 0.0; // s of simulated time between checkpoints; 0 = none
    // [contact]
    std::string contact_model = "hertz";  // hertz | hooke
    double characteristic_velocity = 1.0; // m/s
    // [analysis]: what the summary reports
    std::string analysis = "none"; // none | tilt | slope | bounce | buoyancy | float | still | dambreak |
                                   // platform | slope_waves | damage | pull
    double tilt_rate = 0.0;        // deg/s, tilt: gravity turns about +y at this rate
    double tilt_max = 60.0;        // deg, tilt: stop here
    // pull (pull_analysis.cpp): a dry pull-out test of the layer's units
    double pull_rate = 0.0;  // unit weights per second: the pull grows at this rate
    double pull_max = 3.0;   // unit weights: the pull stops growing here
    double pull_angle = 0.0; // deg from the face's outward normal toward down the face
    int pull_round = 0;      // which set of outer-layer units, >= 3 Dn apart, is pulled
    // slope and damage: the settle criterion (slope_profile.h) and the layer
    int layers = 2;              // n of k_t = t / (n Dn)
    double settle_speed = 0.01;  // m/s, every unit's centre slower
    double settle_energy = 1e-4; // -, kinetic energy of all units / sum(m g Dn)
    double settle_span = 0.2;    // s, both held this long
    // damage (damage_analysis.h)
    double displaced_threshold = 1.0;   // Dn: displaced at a final displacement >= this
    double rocking_threshold_deg = 5.0; // deg: a rocking event turns past this and back below half
    double wave_height = 0.0;           // m, Hs of Ns when the run measures no incident wave (0 = none)
    double wave_period = 0.0;           // s, Tm of s_om and N when the run measures none (0 = none)
    std::vector<SceneMaterial> materials;
    std::vector<SceneMaterialPair> material_pairs;
    std::vector<SceneUnit> units;
    std::vector<SceneWall> walls;
    std::vector<SceneBody> bodies;
    std::vector<SceneDrop> drops;
    std::vector<ScenePattern> patterns;
    std::optional<SceneFluid> fluid;     // [fluid]: a coupled interFoam run
    std::optional<SceneWaves> waves;     // [waves]: needs [fluid]
    std::vector<ScenePorous> porous;     // [[porous]]: needs [fluid]
    std::vector<SceneSeriesStep> series; // [[series]]: needs [waves] type "irregular"
    std::vector<SceneRefine> refine;     // [[refine]]: needs [fluid]

    // m: fluid.water_level above the flume's floor run.domain_min.z (a scene with [fluid]).
    double still_water_depth() const { return fluid->water_level - domain_min.z(); }
};

// `overrides` are "dotted.key=toml_value" strings (from --set; a string key's
// value may also be bare text, docs/scenes.md).
Scene load_scene(const std::string &path, const std::vector<std::string> &overrides = {});

// The scene after overrides and defaults, as TOML (echoed into every output folder).
std::string resolved_scene_toml(const Scene &scene);

} // namespace armour
