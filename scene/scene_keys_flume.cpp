// The scene key table's wave-flume sections: [fluid], [waves], [[series]],
// [[porous]] and [[refine]] (the rest, and what reads the table:
// scene_keys.cpp; the table's design: scene_keys.h).
#include "scene_keys.h"

#include "engine_registry.h"

namespace armour {

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
        key("settle_density", &F::settle_density, "kg/m^3",
            "every unit's density in the settle only: a sweep over unit.density that settles at one "
            "density meets the waves on one layer per seed, as a laboratory places one layer whatever the "
            "concrete (below)")
            .in(Range::above(0))
            .defaults("the units' own"),
        key("settle_stages", &F::settle_stages, "",
            "the settle builds the [[pattern]]'s layer this many stages from the toe up, as a placer "
            "builds it: each stage places the next rows clear of the units already settled and settles "
            "them all, settle_time / settle_stages each, the last settle_time (below)")
            .in(Range::at_least(1))
            .written_if([](const F &f) { return f.settle_stages != 1; }),
        key("settle_engine", &F::settle_engine, "",
            "the engine of the settle: bullet (exact hulls, each cube grown to hold its clump) settles the "
            "layer that run.engine liggghts (clumps) runs and its settled scene runs with --engine bullet: "
            "both engines meet the waves on one layer; liggghts for a bullet run: the hulls slump (below)")
            .one_of(engine_style_names())
            .defaults("`run.engine`")
            .written_if([](const F &f) { return !f.settle_engine.empty(); }),
        key("settled_by", &F::settled_by, "",
            "the engine that settled the bodies, written by a settle into its scene.settled.toml: run with "
            "exact hulls (bullet) after clumps (liggghts), a warning (the hulls slump off a clump-settled "
            "layer)")
            .one_of(engine_style_names())
            .defaults("not settled by armour")
            .written_if([](const F &f) { return !f.settled_by.empty(); }),
        key("settled_growth", &F::settled_growth, "",
            "how much that settle grew each cube to hold its clump (fluid.settle_engine bullet for a "
            "liggghts run), written beside settled_by: run with exact hulls (bullet), a warning (they "
            "start up to that growth apart and drop into the gaps before any wave)")
            .in(Range::at_least(1))
            .defaults("1 (not grown)")
            .written_if([](const F &f) { return f.settled_growth != 1.0; }),
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
        key("extra_gauges", &W::extra_gauges, "m",
            "x of up to 8 more free-surface gauges anywhere inside the flume (on a toe berm, at a "
            "structure's toe): each one's total waves (incident and reflected, not separated) over the "
            "array's analysis window, in summary.json's waves.extra_gauges")
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

} // namespace armour
