#include "scene_keys.h"

#include "engine_registry.h"
#include "input_error.h"
#include "shapes.h"

#include <cmath>
#include <type_traits>

namespace armour {

namespace {

using V3 = Eigen::Vector3d;
// The engines of this build, as the registry lists them.
std::vector<std::string> engine_names() {
    std::vector<std::string> names;
    for (const EngineStyle &style : engine_styles())
        names.push_back(style.name);
    return names;
}
const std::vector<std::string> kAnalyses = {"none",     "tilt",        "slope",  "bounce",
                                            "buoyancy", "float",       "still",  "dambreak",
                                            "platform", "slope_waves", "damage", "pull"};

} // namespace

// ---------------------------------------------------------------- the table

const std::vector<Key<Scene>> &root_keys() {
    static const std::vector<Key<Scene>> keys = {
        key("name", &Scene::name, "", "names the run").required(),
    };
    return keys;
}

const std::vector<Key<Scene>> &run_keys() {
    static const std::vector<Key<Scene>> keys = {
        key("engine", &Scene::engine, "",
            "rigid-body engine; free_body has no contacts (gravity and the fluid load only); coupled "
            "scenes default to exact hulls, which changed the platform case's outcome (comparison.md)")
            .one_of(engine_names())
            .defaults("`\"liggghts\"`; `\"bullet\"` with `[fluid]`"),
        key("duration", &Scene::duration, "s", "simulated time").in(Range::above(0)),
        key("output_interval", &Scene::output_interval, "s", "time between saved frames; <= duration")
            .in(Range::above(0)),
        key("time_step", &Scene::time_step, "s",
            "engine step; <= output_interval; 0 = the engine's own: LIGGGHTS from the contact "
            "stiffness, Bullet min(1 ms, sqrt(Dn / g) / 256) for the smallest unit")
            .in(Range::at_least(0)),
        key("force_time_step", &Scene::force_time_step, "", "true: use time_step even above the stable step"),
        key("gravity", &Scene::gravity, "m/s^2", "gravitational acceleration"),
        key("domain_min", &Scene::domain_min, "m",
            "a corner of the simulated region (with [fluid]: the fluid mesh box)"),
        key("domain_max", &Scene::domain_max, "m", "the opposite corner; each component > domain_min's"),
        key("checkpoint_interval", &Scene::checkpoint_interval, "s",
            "simulated time between checkpoints in OUT/checkpoints (`armour run --resume` continues from the "
            "last); 0 = none; docs/checkpoints.md")
            .in(Range::at_least(0)),
    };
    return keys;
}

const std::vector<Key<Scene>> &contact_keys() {
    static const std::vector<Key<Scene>> keys = {
        key("model", &Scene::contact_model, "", "hertz: stiffness grows with overlap; hooke: linear spring")
            .one_of({"hertz", "hooke"}),
        key("characteristic_velocity", &Scene::characteristic_velocity, "m/s",
            "typical impact speed, sets the Hooke stiffness")
            .in(Range::above(0)),
    };
    return keys;
}

const std::vector<Key<Scene>> &analysis_keys() {
    static const std::vector<Key<Scene>> keys = {
        key("kind", &Scene::analysis, "",
            "what the summary reports; buoyancy, float, still, dambreak, platform and slope_waves need "
            "[fluid] (below)")
            .one_of(kAnalyses),
        key("tilt_rate", &Scene::tilt_rate, "deg/s",
            "tilt: gravity turns about +y at this rate; required and > 0 for tilt")
            .in(Range::at_least(0)),
        key("tilt_max", &Scene::tilt_max, "deg", "tilt: tilting stops here").in(Range::open_closed(0, 90)),
        key("pull_rate", &Scene::pull_rate, "1/s",
            "pull: the outward pull on each pulled unit grows by this many of its weights (m g) per "
            "second; required and > 0 for pull")
            .in(Range::at_least(0)),
        key("pull_max", &Scene::pull_max, "", "pull: the pull stops growing at this many unit weights")
            .in(Range::above(0)),
        key("pull_angle", &Scene::pull_angle, "deg",
            "pull: the pull's direction, turned from the slope face's outward normal toward down the face")
            .in(Range::closed(0, 90)),
        key("pull_round", &Scene::pull_round, "",
            "pull: which set of outer-layer units is pulled (each set's units >= 3 Dn apart; rounds 0, 1, "
            "... together pull every outer unit once)")
            .in(Range::at_least(0)),
        key("layers", &Scene::layers, "", "slope: the layer is meant to be this many units thick (n of k_t)")
            .in(Range::at_least(1)),
        key("settle_speed", &Scene::settle_speed, "m/s",
            "slope, damage: the pile has settled once every unit's centre is slower than this, with "
            "settle_energy, for settle_span")
            .in(Range::above(0)),
        key("settle_energy", &Scene::settle_energy, "",
            "slope, damage: and the units' kinetic energy is below this times sum(m g Dn)")
            .in(Range::above(0)),
        key("settle_span", &Scene::settle_span, "s",
            "slope, damage: both held this long; slope then stops the run, else reports settled = false")
            .in(Range::above(0)),
        key("displaced_threshold", &Scene::displaced_threshold, "",
            "damage (and platform, slope_waves): a unit is displaced when it ends at least this many Dn "
            "from its settled (first recorded) position (1 Dn is physical-model practice)")
            .in(Range::above(0)),
        key("rocking_threshold_deg", &Scene::rocking_threshold_deg, "deg",
            "damage: a rocking event turns a unit past this from its seat (its settled pose, or where "
            "it last came to rest) and back below half of it (a choice: no published threshold)")
            .in(Range::open(0, 180)),
        key("wave_height", &Scene::wave_height, "m",
            "damage: Hs of Ns when the run measures no incident wave; 0 = the [waves] train's target, "
            "else fluid.wave_height")
            .in(Range::at_least(0)),
        key("wave_period", &Scene::wave_period, "s",
            "damage: Tm of s_om = 2 pi Hs/(g Tm^2) and of N = (seconds of waves at the toe)/Tm with "
            "wave_height; 0 = none")
            .in(Range::at_least(0)),
    };
    return keys;
}

const std::vector<Key<SceneFluid>> &fluid_keys() {
    using F = SceneFluid;
    static const std::vector<Key<F>> keys = {
        key("case", &F::case_name, "", "case template folder in foam_cases/"),
        key("water_level", &F::water_level, "m",
            "z of the still-water surface, strictly inside run.domain_min.z .. run.domain_max.z; with a "
            "water column it may be left out (no water outside the column)")
            .custom("required (without a water column)"),
        key("water_box_min", &F::water_box_min, "m",
            "a water column (dam break) filled at the start besides the water below water_level; both "
            "or neither; used by the dambreak template")
            .custom("none")
            .written_if([](const F &f) { return f.has_water_box; }),
        key("water_box_max", &F::water_box_max, "m", "the column's opposite corner; > water_box_min")
            .custom("none")
            .written_if([](const F &f) { return f.has_water_box; }),
        key("wave_height", &F::wave_height, "m",
            "solitary wave H of a wave template's inlet (solitary_platform, slope_waves: required > 0); "
            "< the depth water_level - run.domain_min.z")
            .in(Range::at_least(0)),
        key("cells", &F::cells, "", "blockMesh cells along x, y, z, each >= 1; give this or cell_size")
            .in(Range::at_least(1))
            .custom("–")
            .written_if([](const F &f) { return f.cell_size == 0; }),
        key("cell_size", &F::cell_size, "m",
            "cells = round(extent / cell_size) per axis; <= the domain's smallest extent")
            .in(Range::above(0))
            .custom("–")
            .written_if([](const F &f) { return f.cell_size > 0; }),
        key("refine_min", &F::refine_min, "m",
            "graded mesh (fluid.case \"wave_flume\"; docs/openfoam.md): along each axis, cells keep the size "
            "`cells` gives between refine_min and refine_max and grow outside (coarse_cell_size); both or "
            "neither, inside the run domain, >= one fine cell across; every unit starts inside (to half a "
            "fine cell), and a graded z range holds water_level +- the wave height (short of the domain's "
            "top or floor)")
            .custom("none: uniform"),
        key("refine_max", &F::refine_max, "m", "the refined box's opposite corner; > refine_min")
            .custom("none"),
        key("coarse_cell_size", &F::coarse_cell_size, "m",
            "graded mesh: the size cells grow to outside refine_min..refine_max, by at most 10 % per cell, "
            "along x, y, z; each in [0, the domain's extent], one above the fine cell; a size <= the fine "
            "cell keeps that axis uniform")
            .custom("none")
            .written_if([](const F &f) { return f.refine_min.has_value(); }),
        key("mesh", &F::mesh, "",
            "graded: one blockMesh block (graded by refine_min/max), [[refine]] unused (the reference); "
            "refined: that block with cells 2^L times larger in x and y (L the deepest [[refine]] level), "
            "split back to `cells` by refineMesh in the [[refine]] regions; x and y only, so the free "
            "surface never crosses a face between cells of different heights (such faces drove 1 m/s air "
            "jets in still water: openfoam.md); fluid.case \"wave_flume\"; every unit starts in the "
            "deepest regions")
            .one_of({"graded", "refined"})
            .defaults("`\"refined\"` with [[refine]] regions, else `\"graded\"`"),
        key("penalty", &F::penalty, "1/s",
            "K of the penalisation -rho K chi (U - U_body); implicit, any K is stable")
            .in(Range::above(0)),
        key("mask", &F::mask, "", "solid fraction from the exact shape or from the clump's spheres")
            .one_of({"exact", "spheres"}),
        key("solid_fraction", &F::solid_fraction, "",
            "chi per cell: the cell's volume fraction inside the unit (exact), or the former cosine ramp "
            "sampled at the cell centre (ramp; depends on where the unit sits in the grid, coupling.md)")
            .one_of({"exact", "ramp"}),
        key("smoothing_cells", &F::smoothing_cells, "cells",
            "width of the solid-fraction ramp (solid_fraction = \"ramp\")")
            .in(Range::open_closed(0, 4)),
        key("added_mass", &F::added_mass, "", "C_a of the added-mass correction (light units, coupling.md)")
            .in(Range::at_least(0)),
        key("np", &F::np, "", "MPI ranks of interFoam (--np overrides); each rank runs the engine")
            .in(Range::at_least(1)),
        key("fluid_density", &F::fluid_density, "kg/m^3", "water").in(Range::above(0)),
        key("air_density", &F::air_density, "kg/m^3", "air; < fluid_density").in(Range::above(0)),
        key("viscosity", &F::viscosity, "m^2/s", "water, kinematic").in(Range::above(0)),
        key("air_viscosity", &F::air_viscosity, "m^2/s", "air, kinematic").in(Range::above(0)),
        key("max_courant", &F::max_courant, "", "interFoam's maxCo, every cell's Courant number")
            .in(Range::open_closed(0, 1)),
        key("max_interface_courant", &F::max_interface_courant, "",
            "interFoam's maxAlphaCo, the free surface's cells; <= max_courant")
            .in(Range::open_closed(0, 1))
            .defaults("`fluid.max_courant`")
            .written_if([](const F &f) { return f.max_interface_courant_given; }),
        key("max_time_step", &F::max_time_step, "s", "largest fluid step; <= run.output_interval")
            .in(Range::above(0))
            .defaults("min(0.005, `run.output_interval`)"),
        key("min_time_step", &F::min_time_step, "s",
            "a fluid step below this stops the run with one error line: the flow diverged or the pressure "
            "solve stalled (the solver would go on at ever smaller steps); < max_time_step")
            .in(Range::above(0))
            .defaults("min(the smaller Courant limit x the smallest cell / 1000 m/s, `max_time_step` / 100)")
            .written_if([](const F &f) { return f.min_time_step_given; }),
        key("write_interval", &F::write_interval, "s",
            "time between OpenFOAM field writes in OUT/case; <= run.duration")
            .in(Range::above(0))
            .defaults("`run.duration`")
            .written_if([](const F &f) { return f.write_interval_given; }),
        key("pressure_tolerance", &F::pressure_tolerance, "",
            "p_rgh's solve stops at this normalised residual, in every corrector (docs/openfoam.md: "
            "looser is cheaper, and stalled a turbulent flume at 1e-6)")
            .in(Range::open(0, 1))
            .defaults("the template's (1e-7 wave templates, 1e-8 tank ones)"),
        key("pressure_relative_tolerance", &F::pressure_relative_tolerance, "",
            "p_rgh's solve also stops at this fraction of its initial residual, in the correctors before "
            "the last")
            .in(Range::open(0, 1))
            .defaults("the template's (0.01; 0.05 solitary_flume)"),
        key("momentum_predictor", &F::momentum_predictor, "",
            "PIMPLE solves the momentum equation before the pressure correctors (false: the correctors "
            "alone; docs/openfoam.md)")
            .defaults("the template's (true; false in solitary_flume)"),
        key("frozen", &F::frozen, "",
            "benchmark reference: units held, mask imposed once, no loads, no engine advance"),
        key("mirror_interior", &F::mirror_interior, "",
            "cells wholly inside a unit piercing the free surface take the outside water's phase at "
            "their height each step (floating units; docs/coupling.md)"),
        key("settle_time", &F::settle_time, "s",
            "settle the units in the DEM under the still water this long before coupling (below)")
            .in(Range::at_least(0)),
        key("settle_friction", &F::settle_friction, "",
            "Coulomb friction between units (and walls of their material) in the settle only (below)")
            .in(Range::at_least(0))
            .defaults("the materials' own"),
        key("settle_engine", &F::settle_engine, "",
            "the engine of the settle: bullet (exact hulls, each cube grown to hold its clump) settles the "
            "layer that run.engine liggghts (clumps) runs and its settled scene runs with --engine bullet: "
            "both engines meet the waves on one layer; liggghts for a bullet run: the hulls slump (below)")
            .one_of(engine_names())
            .defaults("`run.engine`")
            .written_if([](const F &f) { return !f.settle_engine.empty(); }),
        key("settled_by", &F::settled_by, "",
            "the engine that settled the bodies, written by a settle into its scene.settled.toml: run with "
            "exact hulls (bullet) after clumps (liggghts), a warning (the hulls slump off a clump-settled "
            "layer)")
            .one_of(engine_names())
            .defaults("not settled by armour")
            .written_if([](const F &f) { return !f.settled_by.empty(); }),
        key("turbulence", &F::turbulence, "",
            "laminar, or OpenFOAM's RAS kOmegaSST with wall functions (over-damps waves in propagation: "
            "turbulence.md)")
            .one_of({"laminar", "kOmegaSST"}),
        key("turbulence_intensity", &F::turbulence_intensity, "",
            "kOmegaSST's initial and inflow k = 1.5 (I sqrt(g depth))^2")
            .in(Range::open_closed(0, 1)),
        key("turbulence_length", &F::turbulence_length, "m",
            "kOmegaSST's initial and inflow omega = sqrt(k) / (0.09^0.25 l)")
            .in(Range::above(0)),
    };
    return keys;
}

const std::vector<Key<SceneMaterial>> &material_keys() {
    using M = SceneMaterial;
    static const std::vector<Key<M>> keys = {
        key("name", &M::name, "", "unique among materials").required(),
        key("youngs_modulus", &M::youngs_modulus, "Pa", "Young's modulus (DEM-softened, below)")
            .in(Range::above(0)),
        key("poisson_ratio", &M::poisson_ratio, "", "Poisson's ratio").in(Range::open(-1, 0.5)),
        key("restitution", &M::restitution, "", "rebound speed / impact speed").in(Range::open_closed(0, 1)),
        key("friction", &M::friction, "", "Coulomb sliding coefficient").in(Range::at_least(0)),
        key("rolling_friction", &M::rolling_friction, "",
            "~0.05 lets LIGGGHTS clumps that do not rest flat on every face rest instead of rocking "
            "(a warning says so; dem.md)")
            .in(Range::at_least(0)),
    };
    return keys;
}

const std::vector<Key<SceneMaterialPair>> &material_pair_keys() {
    using P = SceneMaterialPair;
    static const std::vector<Key<P>> keys = {
        key("a", &P::a, "", "a [[material]]").required(),
        key("b", &P::b, "", "another (or the same) [[material]]; each unordered pair at most once")
            .required(),
        key("restitution", &P::restitution, "", "rebound speed / impact speed")
            .in(Range::open_closed(0, 1))
            .defaults("from the materials"),
        key("friction", &P::friction, "", "Coulomb sliding coefficient")
            .in(Range::at_least(0))
            .defaults("from the materials"),
        key("rolling_friction", &P::rolling_friction, "", "rolling resistance coefficient")
            .in(Range::at_least(0))
            .defaults("from the materials"),
    };
    return keys;
}

const std::vector<Key<SceneUnit>> &unit_keys() {
    using U = SceneUnit;
    static const std::vector<Key<U>> keys = {
        key("name", &U::name, "", "unique among units").required(),
        key("shape", &U::shape, "", "the exact shape the clump approximates")
            .one_of({"cube", "dolos", "stl"})
            .required(),
        key("size", &U::size, "m", "cube edge")
            .in(Range::above(0))
            .required(" for shape \"cube\" (edge length, m)")
            .only_for("cube"),
        key("chamfer", &U::chamfer, "m", "edge chamfer; < size/2").in(Range::at_least(0)).only_for("cube"),
        key("height", &U::height, "m", "overall height H (dolos.md)")
            .in(Range::above(0))
            .required(" for shape \"dolos\" (overall height, m)")
            .only_for("dolos"),
        key("waist", &U::waist, "", "shank across-flats / height")
            .in(Range::closed(kDolosWaistMin, kDolosWaistMax))
            .only_for("dolos"),
        key("stl", &U::stl, "", "closed STL mesh in metres, relative to the scene file's folder; must exist")
            .file()
            .required()
            .only_for("stl"),
        key("density", &U::density, "kg/m^3", "unit density").in(Range::above(0)),
        key("spheres", &U::spheres, "",
            "exactly this many spheres; absent: the fewest spheres meeting both tolerances and a 1 deg "
            "topple error")
            .in(Range::at_least(1))
            .defaults("absent")
            .written_if([](const U &u) { return u.spheres > 0; }),
        key("tol_volume", &U::tol_volume, "", "tolerance mode: allowed relative volume error")
            .in(Range::open(0, 1)),
        key("tol_surface", &U::tol_surface, "", "tolerance mode: allowed surface RMS distance / Dn")
            .in(Range::open(0, 1)),
        key("method", &U::method, "", "clump method (clump_builder.md)").one_of({"greedy", "optimised"}),
        key("material", &U::material, "", "a [[material]]; required when there are several")
            .custom("the only material"),
    };
    return keys;
}

const std::vector<Key<SceneWall>> &wall_keys() {
    using W = SceneWall;
    static const std::vector<Key<W>> keys = {
        key("name", &W::name, "", "unique among walls; needed only for a [[pattern]] to name it")
            .defaults("`TYPE_INDEX` (e.g. `plane_0`)"),
        key("type", &W::type, "", "the kind of wall").one_of({"plane", "slope", "box", "stl"}).required(),
        key("material", &W::material, "", "a [[material]]; required when there are several")
            .custom("the only material"),
        key("point", &W::point, "m", "the patch's centre").required(" for type \"plane\"").only_for("plane"),
        key("normal", &W::normal, "", "not all 0, normalised on load; points to the units' side")
            .required(" for type \"plane\"")
            .only_for("plane"),
        key("size", &W::size, "m", "edge of the square patch").in(Range::above(0)).only_for("plane"),
        key("toe_x", &W::toe_x, "m", "x of the toe").only_for("slope"),
        key("floor_z", &W::floor_z, "m", "z of the floor").only_for("slope"),
        key("cot", &W::cot, "", "horizontal per vertical (1.5 for a 1:1.5 slope)")
            .in(Range::above(0))
            .required(" for type \"slope\"")
            .only_for("slope"),
        key("height", &W::height, "m", "toe to crest")
            .in(Range::above(0))
            .required(" for type \"slope\"")
            .only_for("slope"),
        key("width", &W::width, "m", "extent along y")
            .in(Range::above(0))
            .required(" for type \"slope\"")
            .only_for("slope"),
        key("toe_height", &W::toe_height, "m", "vertical step at the toe (0 = none); < height")
            .in(Range::at_least(0))
            .only_for("slope"),
        key("min", &W::min, "m", "lower corner").required(" for type \"box\"").only_for("box"),
        key("max", &W::max, "m", "upper corner; > min").required(" for type \"box\"").only_for("box"),
        key("file", &W::file, "", "STL in metres, either winding, relative to the scene's folder; must exist")
            .file()
            .required()
            .only_for("stl"),
    };
    return keys;
}

const std::vector<Key<SceneBody>> &body_keys() {
    using B = SceneBody;
    static const std::vector<Key<B>> keys = {
        key("unit", &B::unit, "", "a [[unit]]").required(),
        key("position", &B::position, "m", "centre of mass; inside the run domain").required(),
        key("orientation", &B::orientation, "", "quaternion, not all 0; normalised on load"),
        key("velocity", &B::velocity, "m/s", "initial velocity"),
        key("angular_velocity", &B::angular_velocity, "rad/s", "initial angular velocity"),
        key("fixed_translation", &B::fixed_translation, "", "hold the x, y, z position"),
        key("fixed_rotation", &B::fixed_rotation, "", "hold the rotation about x, y, z"),
        key("pivot", &B::pivot, "m",
            "world point, at the initial pose, whose held coordinates fixed_translation keeps (a hinge; "
            "OpenFOAM's centreOfRotation); needs run.engine = \"free_body\" and a held translation")
            .defaults("centre of mass"),
    };
    return keys;
}

const std::vector<Key<SceneDrop>> &drop_keys() {
    using D = SceneDrop;
    static const std::vector<Key<D>> keys = {
        key("unit", &D::unit, "", "a [[unit]]").required(),
        key("count", &D::count, "", "how many units").in(Range::at_least(1)).required(),
        key("min", &D::min, "m", "lower corner of the region of centres; inside the run domain").required(),
        key("max", &D::max, "m", "upper corner; > min; inside the run domain").required(),
        key("seed", &D::seed, "", "the same seed gives the same poses").in(Range::at_least(0)),
    };
    return keys;
}

const std::vector<Key<ScenePattern>> &pattern_keys() {
    using P = ScenePattern;
    static const std::vector<Key<P>> keys = {
        key("unit", &P::unit, "", "a [[unit]]").required(),
        key("wall", &P::wall, "", "a [[wall]] of type \"slope\"").required(),
        key("rows", &P::rows, "", "units up the slope").in(Range::at_least(1)),
        key("columns", &P::columns, "", "units along y").in(Range::at_least(1)),
        key("spacing", &P::spacing, "m",
            "between centres; 0 = 1.05 x the unit's size up and across the slope, as the engine collides "
            "it (clump spheres or exact shape)")
            .in(Range::at_least(0)),
        key("gap", &P::gap, "m", "between each unit and the slope surface (and between layers)")
            .in(Range::at_least(0)),
        key("packing_density", &P::packing_density, "",
            "units per Dn^2 of slope over all layers (Rock Manual: double-layer cubes 1.17); > 0 sets "
            "spacing = Dn sqrt(layers / packing_density); 0 = use spacing")
            .in(Range::at_least(0)),
        key("layers", &P::layers, "",
            "layers stacked on the slope; every other one half a spacing up it, with columns - 1 units in "
            "the gaps across")
            .in(Range::at_least(1)),
        key("placement", &P::placement, "",
            "grid: every unit faces the slope; random: layer by layer, in a random order, each unit is "
            "turned uniformly at random, moved up to half the free space between grid neighbours "
            "(spacing - its size) along and across the slope, and set where it clears by gap the slope, "
            "its walls and every unit placed before it (the least lifted of 8 such poses); the pile is "
            "loose until a settle (docs/stability.md)")
            .one_of({"grid", "random"}),
        key("seed", &P::seed, "", "placement \"random\": the same seed gives the same poses")
            .in(Range::at_least(0)),
    };
    return keys;
}

const std::vector<Key<SceneWaves>> &wave_keys() {
    using W = SceneWaves;
    // A solitary wave is the template's: the common keys are not its.
    constexpr auto not_solitary = [](const W &w) { return w.type != "solitary"; };
    static const std::vector<Key<W>> keys = {
        key("type", &W::type, "", "the wave train; regular and irregular need fluid.case \"wave_flume\"")
            .one_of({"solitary", "regular", "irregular"})
            .required(),
        key("height", &W::height, "m",
            "H; the inlet refuses breaking waves (H / h > 0.78, or H > 0.142 L tanh(kh))")
            .in(Range::above(0))
            .required(" for type \"regular\" (wave height, m)")
            .only_for("regular"),
        key("period", &W::period, "s", "T")
            .in(Range::above(0))
            .required(" for type \"regular\" (s)")
            .only_for("regular"),
        key("theory", &W::theory, "",
            "OpenFOAM's model; auto: cnoidal above Ursell 26.3 in shallow water (kh < pi/4), else StokesV "
            "for H / L0 > 0.02, else StokesII; each refuses waves outside its validity (docs/waves.md)")
            .one_of({"auto", "StokesII", "StokesV", "cnoidal", "streamFunction"})
            .only_for("regular"),
        key("Hs", &W::hs, "m",
            "significant height Hm0 = 4 sqrt(m0); refused when 1.8 Hs (the largest of ~1000 waves) would "
            "break at the inlet")
            .in(Range::above(0))
            .required(" for type \"irregular\" (Hm0, m)")
            .only_for("irregular"),
        key("Tp", &W::tp, "s", "peak period")
            .in(Range::above(0))
            .required(" for type \"irregular\" (s)")
            .only_for("irregular"),
        key("spectrum", &W::spectrum, "", "spectral shape").one_of({"jonswap"}).only_for("irregular"),
        key("gamma", &W::gamma, "", "JONSWAP peak enhancement; 1 = Pierson-Moskowitz")
            .in(Range::closed(1, 10))
            .only_for("irregular"),
        key("seed", &W::seed, "", "random phases: the same seed gives the same train")
            .in(Range::at_least(0))
            .only_for("irregular"),
        key("components", &W::components, "",
            "even; frequencies 0.5 Tp^-1 .. ~2.5 Tp^-1 in steps of 2 / (components Tp): the train repeats "
            "every components Tp / 2 s")
            .in(Range::closed(4, 200))
            .only_for("irregular"),
        key("ramp_time", &W::ramp_time, "s", "the inlet's amplitude ramps up from 0 over this time")
            .in(Range::above(0))
            .defaults("2 `period` (2 `Tp`)")
            .written_if(not_solitary),
        key("active_absorption", &W::active_absorption, "",
            "the inlet corrects its velocity so waves coming back leave (shallow-water correction)")
            .written_if(not_solitary),
        key("outlet", &W::outlet, "",
            "absorbing: the long-wave condition tuned to the celerity at T (Tp), u = c eta / h "
            "(armourShallowWaterAbsorption); shallow_water: OpenFOAM's shallowWaterAbsorption, u = "
            "sqrt(g / h) eta; wall: a reflecting end wall (reflection of each in docs/waves.md)")
            .one_of({"absorbing", "shallow_water", "wall"})
            .written_if(not_solitary),
        key("gauge_x", &W::gauge_x, "m",
            "x of the first of three gauges (spaced L/10 and L/4 after it, Mansard and Funke); the "
            "array must lie inside the flume")
            .defaults("one wavelength L (at T or Tp) from the inlet")
            .written_if(not_solitary),
    };
    return keys;
}

const std::vector<Key<SceneSeriesStep>> &series_keys() {
    using S = SceneSeriesStep;
    static const std::vector<Key<S>> keys = {
        key("Hs", &S::hs, "m",
            "the step's Hm0 at the wave maker; refused, as waves.Hs is, when 1.8 Hs would break at the "
            "inlet")
            .in(Range::above(0))
            .required(" (Hm0 at the wave maker, m)"),
        key("Tp", &S::tp, "s",
            "the step's peak period; refused, as waves.Tp is, where the stock wave model fails, and "
            "when the gauge array at L(Tp) leaves the flume")
            .in(Range::above(0))
            .required(" (peak period, s)"),
        key("gamma", &S::gamma, "", "JONSWAP peak enhancement")
            .in(Range::closed(1, 10))
            .defaults("`waves.gamma`"),
        key("seed", &S::seed, "", "random phases of the step's train")
            .in(Range::at_least(0))
            .defaults("`waves.seed`"),
        key("waves", &S::waves, "",
            "the step's length as a number of waves: duration = the front's travel from the maker to the "
            "first slope wall's toe (group velocity at Tp) + waves x the train's Tm0,2 (from its "
            "components); give this or duration")
            .in(Range::above(0))
            .defaults("–")
            .written_if([](const S &s) { return s.waves > 0.0; }),
        key("duration", &S::duration, "s", "the step's simulated time; >= run.output_interval")
            .in(Range::above(0))
            .defaults("`run.duration`")
            .written_if([](const S &s) { return s.waves <= 0.0; }),
        key("ramp_time", &S::ramp_time, "s", "the maker's amplitude ramps up from 0 over this time")
            .in(Range::above(0))
            .defaults("`waves.ramp_time` when given, else 2 `Tp`"),
    };
    return keys;
}

const std::vector<Key<ScenePorous>> &porous_keys() {
    using P = ScenePorous;
    static const std::vector<Key<P>> keys = {
        key("name", &P::name, "", "names the region (the cellZone porous_NAME); unique").required(),
        key("type", &P::type, "", "the region's shape").one_of({"box", "slope_layer"}),
        key("min", &P::min, "m", "a corner of the permeable box, inside run.domain_min .. domain_max")
            .required(" for type \"box\"")
            .only_for("box"),
        key("max", &P::max, "m", "the opposite corner; > min").required(" for type \"box\"").only_for("box"),
        key("wall", &P::wall, "", "a [[wall]] of type \"slope\": the layer lies under its face and crest")
            .required(" for type \"slope_layer\"")
            .only_for("slope_layer"),
        key("depth", &P::depth, "m",
            "the layer's top: its distance below the slope's face and crest, along their normals")
            .in(Range::at_least(0))
            .only_for("slope_layer"),
        key("thickness", &P::thickness, "m", "the layer's thickness along the normals (an underlayer)")
            .in(Range::above(0))
            .defaults("everything below `depth` down to the floor (a core)")
            .only_for("slope_layer"),
        key("stone_size", &P::stone_size, "m", "Dn50 of the rock").in(Range::above(0)).required(),
        key("porosity", &P::porosity, "", "n, the void fraction").in(Range::open(0, 1)),
        key("alpha", &P::alpha, "",
            "van Gent's laminar coefficient: Darcy d = alpha (1 - n)^2 / (n^3 Dn50^2) (porous.md)")
            .in(Range::above(0)),
        key("beta", &P::beta, "",
            "van Gent's turbulent coefficient: Forchheimer f = 2 beta (1 - n) / (n^3 Dn50)")
            .in(Range::above(0)),
    };
    return keys;
}

const std::vector<Key<SceneRefine>> &refine_keys() {
    using R = SceneRefine;
    static const std::vector<Key<R>> keys = {
        key("name", &R::name, "", "names the region; unique").required(),
        key("type", &R::type, "", "the region's shape").one_of({"box", "slope_band"}),
        key("min", &R::min, "m", "a corner of the box, inside run.domain_min .. domain_max")
            .required(" for type \"box\"")
            .only_for("box"),
        key("max", &R::max, "m", "the opposite corner; > min").required(" for type \"box\"").only_for("box"),
        key("wall", &R::wall, "", "a [[wall]] of type \"slope\": the band follows its face and crest")
            .required(" for type \"slope_band\"")
            .only_for("slope_band"),
        key("below", &R::below, "m",
            "the band reaches this far under the face and crest, along their normals (into the "
            "underlayer; the core beyond keeps the base cells)")
            .in(Range::at_least(0))
            .only_for("slope_band"),
        key("above", &R::above, "m",
            "and this far over them (the armour layer, the flow about it and the run-up)")
            .in(Range::above(0))
            .required(" for type \"slope_band\"")
            .only_for("slope_band"),
        key("level", &R::level, "",
            "halvings of the base cells in x and y: the deepest level's regions get fluid.cells; a region "
            "of a lower level gets one layer of its cells around each deeper one")
            .in(Range::closed(1, 3)),
    };
    return keys;
}

bool Range::bounded() const {
    return std::isfinite(lo) || std::isfinite(hi);
}

bool Range::contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
}

std::string Range::text() const {
    if (std::isfinite(lo) && std::isfinite(hi))
        return "in " + std::string(lo_open ? "(" : "[") + number_text(lo) + ", " + number_text(hi) +
               (hi_open ? ")" : "]");
    if (std::isfinite(lo))
        return (lo_open ? "> " : ">= ") + number_text(lo);
    if (std::isfinite(hi))
        return (hi_open ? "< " : "<= ") + number_text(hi);
    return "";
}

namespace {

// 5e+07 -> 5e7, 1e-06 -> 1e-6: the way the examples write them.
std::string doc_number(double v) {
    std::string s = number_text(v);
    const auto e = s.find('e');
    if (e == std::string::npos)
        return s;
    std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
    const bool negative = exponent[0] == '-';
    exponent.erase(0, exponent.find_first_not_of("+-0"));
    return mantissa + "e" + (negative ? "-" : "") + exponent;
}

std::string doc_vector(const Eigen::Ref<const Eigen::VectorXd> &v) {
    std::string s = "[";
    for (Eigen::Index i = 0; i < v.size(); ++i)
        s += (i ? ", " : "") + doc_number(v[i]);
    return s + "]";
}

template <class S> KeyInfo describe(const char *section, const Key<S> &k) {
    KeyInfo info;
    info.section = section;
    info.name = k.name;
    info.dotted = info.section.empty() ? info.name : info.section + "." + info.name;
    info.unit = k.unit;
    info.doc = k.doc;
    info.when = k.when;
    const S defaults{};
    std::string value;
    std::visit(overloaded{
                   [&](std::string S::*f) {
                       info.type = k.path ? "path" : "string";
                       value = (defaults.*f).empty() ? "" : "`" + toml_string(defaults.*f) + "`";
                   },
                   [&](double S::*f) {
                       info.type = "number";
                       value = doc_number(defaults.*f);
                   },
                   [&](int S::*f) {
                       info.type = "integer";
                       value = std::to_string(defaults.*f);
                   },
                   [&](std::uint64_t S::*f) {
                       info.type = "integer";
                       value = std::to_string(defaults.*f);
                   },
                   [&](bool S::*f) {
                       info.type = "boolean";
                       value = defaults.*f ? "true" : "false";
                   },
                   [&](Eigen::Vector3d S::*f) {
                       info.type = "[x, y, z]";
                       value = doc_vector(defaults.*f);
                   },
                   [&](Eigen::Vector4d S::*f) {
                       info.type = "[w, x, y, z]";
                       value = doc_vector(defaults.*f);
                   },
                   [&](std::array<bool, 3> S::*f) {
                       info.type = "3 booleans";
                       const auto &b = defaults.*f;
                       value = std::string("[") + (b[0] ? "true" : "false") + ", " +
                               (b[1] ? "true" : "false") + ", " + (b[2] ? "true" : "false") + "]";
                   },
                   [&](std::array<int, 3> S::*) { info.type = "3 integers"; },
                   [&](std::optional<double> S::*) { info.type = "number"; },
                   [&](std::optional<Eigen::Vector3d> S::*) { info.type = "[x, y, z]"; },
                   [&](std::optional<bool> S::*) { info.type = "boolean"; },
               },
               k.field);
    if (*k.default_doc)
        value = k.default_doc;
    else if (k.need == Need::Required)
        value = *k.when ? "required for " + std::string(k.when) : "required";
    info.default_text = value;
    if (!k.choices.empty()) {
        for (const auto &c : k.choices)
            info.allowed += (info.allowed.empty() ? "" : ", ") + std::string("`") + toml_string(c) + "`";
    } else {
        info.allowed = k.range.text();
    }
    return info;
}

template <class S> std::vector<KeyInfo> describe_all(const char *section, const std::vector<Key<S>> &keys) {
    std::vector<KeyInfo> out;
    for (const auto &k : keys)
        out.push_back(describe(section, k));
    return out;
}

} // namespace

const std::vector<SceneSection> &scene_sections() {
    static const std::vector<SceneSection> sections = {
        {"", SectionKind::Root, "", {}, [] { return describe_all("", root_keys()); }},
        {"run", SectionKind::Table, "", {}, [] { return describe_all("run", run_keys()); }},
        {"contact", SectionKind::Table, "", {}, [] { return describe_all("contact", contact_keys()); }},
        {"analysis", SectionKind::Table, "", {}, [] { return describe_all("analysis", analysis_keys()); }},
        {"fluid", SectionKind::Table, "", {}, [] { return describe_all("fluid", fluid_keys()); }},
        {"material",
         SectionKind::ArrayOfTables,
         "",
         {},
         [] { return describe_all("material", material_keys()); }},
        {"material_pair",
         SectionKind::ArrayOfTables,
         "",
         {},
         [] { return describe_all("material_pair", material_pair_keys()); }},
        {"unit",
         SectionKind::ArrayOfTables,
         "shape",
         {{"cube", "a cube, optionally chamfered"},
          {"dolos", "a dolos (dolos.md)"},
          {"stl", "any closed triangle mesh"}},
         [] { return describe_all("unit", unit_keys()); }},
        {"wall",
         SectionKind::ArrayOfTables,
         "type",
         {{"plane", "a square patch"},
          {"slope", "a 1:`cot` slope rising in +x, with its floor"},
          {"box", "a floor and four side walls, open at the top"},
          {"stl", "a triangle mesh"}},
         [] { return describe_all("wall", wall_keys()); }},
        {"body", SectionKind::ArrayOfTables, "", {}, [] { return describe_all("body", body_keys()); }},
        {"drop", SectionKind::ArrayOfTables, "", {}, [] { return describe_all("drop", drop_keys()); }},
        {"pattern",
         SectionKind::ArrayOfTables,
         "",
         {},
         [] { return describe_all("pattern", pattern_keys()); }},
        {"waves",
         SectionKind::Table,
         "type",
         {{"solitary", "the template's solitary wave of `fluid.wave_height`, as without [waves]"},
          {"regular", "a regular wave train, OpenFOAM's stock wave models (the irregular keys may stay in "
                      "the file, checked and unused, and the other way round)"},
          {"irregular", "a JONSWAP train through OpenFOAM's irregularMultiDirectional model"}},
         [] { return describe_all("waves", wave_keys()); }},
        {"series", SectionKind::ArrayOfTables, "", {}, [] { return describe_all("series", series_keys()); }},
        {"porous",
         SectionKind::ArrayOfTables,
         "type",
         {{"box", "the cells whose centre lies in a box"},
          {"slope_layer",
           "the cells under a slope wall's face and crest whose centre lies between `depth` and "
           "`depth + thickness` below them (porous.md)"}},
         [] { return describe_all("porous", porous_keys()); }},
        {"refine",
         SectionKind::ArrayOfTables,
         "type",
         {{"box", "the cells whose centre lies in a box"},
          {"slope_band",
           "the cells whose centre lies between `below` under and `above` over a slope wall's face and "
           "crest, and no lower than `below` under its floor"}},
         [] { return describe_all("refine", refine_keys()); }},
    };
    return sections;
}

const SceneSection *find_section(const std::string &name) {
    for (const auto &s : scene_sections())
        if (name == s.name)
            return &s;
    return nullptr;
}

std::vector<std::string> key_names(const SceneSection &section) {
    std::vector<std::string> names;
    for (const auto &k : section.keys())
        names.push_back(k.name);
    return names;
}

// ---------------------------------------------------------------- Markdown

namespace {

std::string doc_unit(const std::string &unit) {
    if (unit.empty())
        return "–";
    std::string s = unit;
    for (const auto &[from, to] : {std::pair<std::string, std::string>{"^2", "²"}, {"^3", "³"}})
        for (auto at = s.find(from); at != std::string::npos; at = s.find(from))
            s.replace(at, from.size(), to);
    return s;
}

std::string table_of(const std::vector<KeyInfo> &keys) {
    std::string out = "| key | type | unit | default | allowed | meaning |\n|---|---|---|---|---|---|\n";
    for (const auto &k : keys)
        out += "| `" + k.name + "` | " + k.type + " | " + doc_unit(k.unit) + " | " +
               (k.default_text.empty() ? "–" : k.default_text) + " | " +
               (k.allowed.empty() ? "any" : k.allowed) + " | " + k.doc + " |\n";
    return out;
}

const std::string kBegin = "<!-- scene-keys ";
const std::string kEnd = "<!-- end scene-keys -->";

} // namespace

std::string scene_keys_markdown(const std::string &name) {
    const SceneSection *section = find_section(name);
    if (!section)
        throw InputError("scene-keys: '" + name + "': no such section");
    const std::vector<KeyInfo> keys = section->keys();
    if (!*section->selector)
        return table_of(keys);
    std::vector<KeyInfo> common;
    for (const auto &k : keys)
        if (k.when.empty())
            common.push_back(k);
    std::string out = table_of(common);
    for (const auto &[variant, doc] : section->variants) {
        std::vector<KeyInfo> own;
        for (const auto &k : keys)
            if (k.when == variant)
                own.push_back(k);
        out += "\n`" + std::string(section->selector) + " = \"" + variant + "\"`: " + doc + ".\n\n" +
               table_of(own);
    }
    return out;
}

// Blocks read "<!-- scene-keys SECTION -->\n...\n<!-- end scene-keys -->"
// (SECTION "top" for the top level).
std::string with_generated_key_reference(const std::string &document) {
    std::string out;
    std::size_t at = 0;
    for (;;) {
        const auto begin = document.find(kBegin, at);
        if (begin == std::string::npos)
            break;
        const auto close = document.find("-->", begin);
        const auto end = document.find(kEnd, begin);
        if (close == std::string::npos || end == std::string::npos)
            throw InputError("scene-keys: unterminated block marker at offset " + std::to_string(begin));
        std::string name = document.substr(begin + kBegin.size(), close - begin - kBegin.size());
        name.erase(name.find_last_not_of(' ') + 1);
        out += document.substr(at, close + 3 - at) + "\n" + scene_keys_markdown(name == "top" ? "" : name);
        at = end;
    }
    return out + document.substr(at);
}

} // namespace armour
