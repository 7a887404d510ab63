// Reading a scene's wave-flume sections: [fluid], [waves], [[series]],
// [[porous]] and [[refine]] (their keys: scene_keys_flume.cpp; the rest of
// the scene, and the order the sections are read in: scene_read.cpp).
#include "scene_read_parts.h"

#include "jonswap.h"
#include "wave_theory.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace armour {

using namespace scene_detail;

namespace {

// waves.extra_gauges: a few where the array leaves off (a berm, a toe), not a
// gauge per cell; each adds a column sum to every fluid step.
constexpr std::size_t kMaxExtraGauges = 8;

// The still water: its level, or a water column (dam break), and a solitary
// wave's height below the depth.
void read_fluid_water(const Table &t, const std::vector<Key<SceneFluid>> &keys, const Scene &s,
                      SceneFluid &f) {
    // A water column (water_box_min/max) may replace the level: the level
    // then defaults to the mesh's bottom (no water outside the column).
    if (t.has("water_box_min") != t.has("water_box_max"))
        t.fail(t.has("water_box_min") ? "water_box_max" : "water_box_min",
               "missing: give both water_box_min and water_box_max (m)");
    f.has_water_box = t.has("water_box_min");
    if (f.has_water_box) {
        read_value(t, key_named(keys, "water_box_min"), f);
        read_value(t, key_named(keys, "water_box_max"), f);
        if (!(f.water_box_max.array() > f.water_box_min.array()).all())
            t.fail("water_box_max", "must exceed fluid.water_box_min " + vector_text(f.water_box_min) +
                                        " m in every component (got " + vector_text(f.water_box_max) + ")");
    } else {
        t.require("water_level", " (z of the still-water surface, m)");
    }
    f.water_level = s.domain_min.z();
    read_value(t, key_named(keys, "water_level"), f);
    t.check((f.water_level > s.domain_min.z() || (f.has_water_box && f.water_level == s.domain_min.z())) &&
                f.water_level < s.domain_max.z(),
            "water_level",
            "must lie inside run.domain_min.z .. run.domain_max.z = (" + number_text(s.domain_min.z()) +
                ", " + number_text(s.domain_max.z()) + ") m",
            f.water_level);
    t.check(f.wave_height == 0 || f.wave_height < f.water_level - s.domain_min.z(), "wave_height",
            "must be in [0, the still-water depth water_level - run.domain_min.z) m", f.wave_height);
}

// The mesh: cells or cell_size, and a graded mesh's refined box and coarse size.
void read_fluid_cells(const Table &t, const std::vector<Key<SceneFluid>> &keys, const Scene &s,
                      SceneFluid &f) {
    const Eigen::Vector3d extent = s.domain_max - s.domain_min;
    if (t.has("cells") == t.has("cell_size"))
        t.fail(t.has("cells") ? "cell_size" : "cells",
               t.has("cells") ? "give either cells or cell_size, not both"
                              : "missing required key: give cells = [nx, ny, nz] or cell_size (m)");
    if (t.has("cells")) {
        read_value(t, key_named(keys, "cells"), f);
    } else {
        read_value(t, key_named(keys, "cell_size"), f);
        t.check(f.cell_size > 0 && f.cell_size <= extent.minCoeff(), "cell_size",
                "must be in (0, " + number_text(extent.minCoeff()) + "] m (the run domain's smallest extent)",
                f.cell_size);
        for (int i = 0; i < 3; ++i)
            f.cells[i] = std::max(1, static_cast<int>(std::lround(extent[i] / f.cell_size)));
    }
    if (t.has("refine_min") != t.has("refine_max"))
        t.fail(t.has("refine_min") ? "refine_max" : "refine_min",
               "missing: give both refine_min and refine_max (m), or neither (a uniform mesh)");
    if (t.has("coarse_cell_size") != t.has("refine_min"))
        t.fail(t.has("refine_min") ? "coarse_cell_size" : "refine_min",
               t.has("refine_min")
                   ? "missing: a graded mesh needs the size its cells grow to (m)"
                   : "missing: coarse_cell_size grades the mesh outside refine_min .. refine_max");
    if (t.has("refine_min")) {
        read_value(t, key_named(keys, "refine_min"), f);
        read_value(t, key_named(keys, "refine_max"), f);
        read_value(t, key_named(keys, "coarse_cell_size"), f);
        const Eigen::Vector3d &lo = *f.refine_min, &hi = *f.refine_max;
        if (!(hi.array() > lo.array()).all())
            t.fail("refine_max", "must exceed fluid.refine_min " + vector_text(lo) +
                                     " m in every component (got " + vector_text(hi) + ")");
        if ((lo.array() < s.domain_min.array()).any() || (hi.array() > s.domain_max.array()).any())
            t.fail((lo.array() < s.domain_min.array()).any() ? "refine_min" : "refine_max",
                   "the refined box " + vector_text(lo) + " .. " + vector_text(hi) +
                       " m must lie inside run.domain_min .. run.domain_max " + vector_text(s.domain_min) +
                       " .. " + vector_text(s.domain_max) + " m");
        const Eigen::Vector3d fine = f.fine_cell(extent);
        if (((hi - lo).array() < fine.array() * (1.0 - 1e-9)).any())
            t.fail("refine_max", "the refined box " + vector_text(lo) + " .. " + vector_text(hi) +
                                     " m must be at least one fine cell " + vector_text(fine) +
                                     " m across along each axis");
        const Eigen::Vector3d &coarse = f.coarse_cell_size;
        if (!coarse.allFinite() || (coarse.array() < 0.0).any() || (coarse.array() > extent.array()).any() ||
            (coarse.array() <= fine.array()).all())
            t.fail("coarse_cell_size", "must be in [0, the run domain's extent] m along each axis and exceed "
                                       "the fine cell " +
                                           vector_text(fine) + " m along one (got " + vector_text(coarse) +
                                           ")");
    }
}

// The fluid step's limits, the air, and the writes, against each other and [run].
void check_fluid_steps(const Table &t, const Scene &s, SceneFluid &f) {
    const Eigen::Vector3d extent = s.domain_max - s.domain_min;
    // 1 km/s, three times the speed of sound in air, is no flow a flume
    // holds: an incompressible solver that steps for it has diverged.
    if (!f.min_time_step_given)
        f.min_time_step = std::min(std::min(f.max_courant, f.max_interface_courant) *
                                       f.fine_cell(extent).minCoeff() / 1000.0,
                                   f.max_time_step / 100.0);
    t.check(f.min_time_step < f.max_time_step, "min_time_step",
            "must be in (0, max_time_step = " + number_text(f.max_time_step) + ") s", f.min_time_step);
    t.check(f.air_density < f.fluid_density, "air_density",
            "must be in (0, fluid_density = " + number_text(f.fluid_density) + ") kg/m^3", f.air_density);
    t.check(f.max_time_step <= s.output_interval, "max_time_step",
            "must be in (0, run.output_interval = " + number_text(s.output_interval) + "] s",
            f.max_time_step);
    // Interface cells are cells: a larger limit there could never bind.
    t.check(f.max_interface_courant <= f.max_courant, "max_interface_courant",
            "must be in (0, max_courant = " + number_text(f.max_courant) + "]", f.max_interface_courant);
    t.check(f.write_interval <= s.duration, "write_interval",
            "must be in (0, run.duration = " + number_text(s.duration) + "] s", f.write_interval);
}

// Why an irregular train of `hs` (m) and `tp` (s) cannot run at `depth`:
// the key ("Tp" or "Hs") and the reason; an empty key when it can.
struct KeyRefusal {
    std::string key, reason;
};
KeyRefusal irregular_refusal(double hs, double tp, double depth, double g) {
    const double longest = 2.0 * tp; // the lowest component, 0.5 fp
    const double kh = wave_number(longest, depth, g) * depth;
    if (kh < kStockWavelengthMinKh)
        return {"Tp", "the longest component (2 Tp = " + number_text(longest) +
                          " s) has kh = " + number_text(kh) + " < " + number_text(kStockWavelengthMinKh) +
                          ": OpenFOAM v1912's irregularMultiDirectional finds wavelengths by a fixed-point "
                          "iteration that has not converged there (docs/waves.md)"};
    const double largest = kLargestWaveOverHs * hs, miche = miche_height(tp, depth, g);
    if (largest > kDepthBreakingRatio * depth || largest > miche)
        return {"Hs",
                number_text(kLargestWaveOverHs) + " Hs = " + figure_text(largest) +
                    " m (the largest of ~1000 waves) breaks at the inlet: it must stay below 0.78 h = " +
                    figure_text(kDepthBreakingRatio * depth) +
                    " m and 0.142 L tanh(kh) = " + figure_text(miche) + " m at Tp"};
    return {};
}

// Why the gauge array from x (m) at the wavelength of `period` (s) does not
// fit the flume; "" when it does.
std::string gauge_refusal(const Scene &s, double x, double period) {
    const double L = wavelength(period, s.still_water_depth(), s.gravity.norm());
    if (x > s.domain_min.x() && x + 0.25 * L < s.domain_max.x())
        return "";
    return "the gauge array x .. x + L/4 (L = " + number_text(L) +
           " m) must lie inside the flume run.domain_min.x .. run.domain_max.x = (" +
           number_text(s.domain_min.x()) + ", " + number_text(s.domain_max.x()) + ") m (got " +
           number_text(x) + ")";
}

// s: the front of a train of peak period `tp` travels from the maker to the
// first slope wall's toe at the group velocity at Tp (0 without a slope).
double front_travel(const Scene &s, double tp) {
    for (const SceneWall &w : s.walls)
        if (w.type == "slope")
            return std::max(0.0, w.toe_x - s.domain_min.x()) /
                   group_velocity(tp, s.still_water_depth(), s.gravity.norm());
    return 0.0;
}

// A region's name (key `name` of t) becomes an OpenFOAM cellZone or cell
// set: a word, unique among the regions of its kind (`kind`, as the file
// names it).
template <class Region>
void check_region_name(const Table &t, const std::string &name, const std::vector<Region> &others,
                       const char *kind) {
    if (name.empty() || name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                               "0123456789_") != std::string::npos)
        t.fail("name", "letters, digits and _ only (got " + toml_string(name) + ")");
    for (const Region &other : others)
        if (other.name == name)
            t.fail("name", std::string("a second ") + kind + " named " + toml_string(name));
}

// The slope wall that key `wall` of t names.
const SceneWall &slope_wall_named(const Table &t, const Scene &s, const std::string &name) {
    const auto wall =
        std::find_if(s.walls.begin(), s.walls.end(), [&](const SceneWall &w) { return w.name == name; });
    if (wall == s.walls.end() || wall->type != "slope")
        t.fail("wall", "no [[wall]] of type \"slope\" named " + toml_string(name));
    return *wall;
}

} // namespace

namespace scene_read {

void read_fluid(const Table &root, Scene &s) {
    if (!root.has("fluid"))
        return;
    const Table t = root.section("fluid");
    const auto &keys = fluid_keys();
    t.only(names_of(keys));
    SceneFluid f;
    // Defaults that follow [run].
    f.max_time_step = std::min(f.max_time_step, s.output_interval);
    f.write_interval = s.duration;
    f.write_interval_given = t.has("write_interval");
    f.max_interface_courant_given = t.has("max_interface_courant");
    f.min_time_step_given = t.has("min_time_step");
    read_keys(t, keys, f);
    if (!f.max_interface_courant_given)
        f.max_interface_courant = f.max_courant;
    // Both take their scale from gravity (without it, NaN in the case): the
    // height at which the interior mirrors the outside, and k's start from
    // the celerity sqrt(g depth).
    if (s.gravity.norm() == 0 && f.mirror_interior)
        t.fail("mirror_interior", "needs gravity: the interior takes the outside's phase at its height "
                                  "along gravity, and gravity is [0, 0, 0]");
    if (s.gravity.norm() == 0 && f.turbulence != "laminar")
        t.fail("turbulence",
               "needs gravity: k starts from the celerity sqrt(g depth), and gravity is [0, 0, 0]");
    if (f.case_name.find('/') != std::string::npos || f.case_name[0] == '.')
        t.fail("case", "must name a template folder in foam_cases/, e.g. \"tank\" (got " +
                           toml_string(f.case_name) + ")");
    read_fluid_water(t, keys, s, f);
    read_fluid_cells(t, keys, s, f);
    check_fluid_steps(t, s, f);
    s.fluid = f;
}

// [waves] after [fluid] (the depth is fluid.water_level - run.domain_min.z):
// the wave must be one the chosen theory describes and must not break at
// the inlet, and the gauge array must lie in the flume.
void read_waves(const Table &root, Scene &s) {
    if (!root.has("waves"))
        return;
    const Table t = root.section("waves");
    const auto &keys = wave_keys();
    t.only(names_of(keys));
    SceneWaves w;
    t.require("type");
    read_value(t, key_named(keys, "type"), w);
    if (!s.fluid)
        t.fail("type", "[waves] makes waves in a coupled run: the scene needs a [fluid] table");
    // The other type's keys may stay (checked, unused): one file then holds
    // a regular and an irregular train, picked with --set waves.type=...
    read_keys(t, keys, w, w.type);
    for (const auto &k : keys)
        if (*k.when && w.type != k.when)
            read_value(t, k, w);
    if (w.type == "solitary") {
        for (const char *name : {"ramp_time", "active_absorption", "outlet", "gauge_x", "extra_gauges"})
            if (t.has(name))
                t.fail(name, "not used by type \"solitary\" (the template's solitary wave of "
                             "fluid.wave_height; docs/waves.md)");
        s.waves = w;
        return;
    }
    const double depth = s.still_water_depth(), g = s.gravity.norm();
    const bool regular = w.type == "regular";
    const double period = w.target_period();
    if (regular) {
        w.theory = regular_theory(w.theory, w.height, w.period, depth, g);
        const std::string why = regular_wave_refusal(w.theory, w.height, w.period, depth, g);
        if (!why.empty())
            t.fail(why.find("breaks") != std::string::npos ? "height" : "theory", why);
    } else {
        // (Integer keys get only their lower bound from the table.)
        if (w.components > kMaxWaveComponents)
            t.fail("components",
                   "must be in [4, " + std::to_string(kMaxWaveComponents) + "] (got " +
                       std::to_string(w.components) +
                       "): each component costs a cosine per inlet face and step; a longer "
                       "non-repeating train needs no more than 200 (repeat: components Tp / 2)");
        if (w.components % 2 != 0)
            t.fail("components", "must be even (got " + std::to_string(w.components) + ")");
        if (const KeyRefusal no = irregular_refusal(w.hs, w.tp, depth, g); !no.key.empty())
            t.fail(no.key, no.reason);
    }
    if (!t.has("ramp_time"))
        w.ramp_time = 2.0 * period;
    const double L = wavelength(period, depth, g);
    if (!w.gauge_x)
        w.gauge_x = s.domain_min.x() + L;
    if (const std::string why = gauge_refusal(s, *w.gauge_x, period); !why.empty())
        t.fail("gauge_x", why);
    if (w.extra_gauges.size() > kMaxExtraGauges)
        t.fail("extra_gauges", "at most " + std::to_string(kMaxExtraGauges) + " gauges (got " +
                                   std::to_string(w.extra_gauges.size()) + ")");
    for (const double x : w.extra_gauges)
        if (!(x > s.domain_min.x() && x < s.domain_max.x()))
            t.fail("extra_gauges",
                   "each gauge must lie inside the flume run.domain_min.x .. run.domain_max.x = (" +
                       number_text(s.domain_min.x()) + ", " + number_text(s.domain_max.x()) + ") m (got " +
                       number_text(x) + ")");
    s.waves = w;
}

// [[series]] after [waves] and the walls: each step is the [waves] train
// with its own height, period, peak enhancement and seed, checked as
// [waves] is (the stock model, breaking at the inlet, the gauge array at
// its L), and its length resolved to seconds (from `waves`: the front's
// travel to the toe and that many of its Tm0,2).
void read_series(const Table &root, Scene &s) {
    const auto &keys = series_keys();
    const auto entries = root.entries("series");
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const Table &t = entries[i];
        t.only(names_of(keys));
        if (!s.waves || s.waves->type != "irregular")
            t.fail("Hs", "a test series runs irregular sea states: the scene needs [waves] with type = "
                         "\"irregular\" (its other keys are the steps' own)");
        if (s.analysis != "damage")
            root.section("analysis")
                .fail("kind", "a [[series]] measures the damage of each step: kind must be "
                              "\"damage\" (got " +
                                  toml_string(s.analysis) + ")");
        const SceneWaves &w = *s.waves;
        SceneSeriesStep step;
        step.gamma = w.gamma;
        step.seed = w.seed;
        read_keys(t, keys, step);
        if (t.has("waves") && t.has("duration"))
            t.fail("duration", "give the step's length as waves or as duration, not both");
        const std::string label = "step " + std::to_string(i + 1) + ": ";
        const double depth = s.still_water_depth(), g = s.gravity.norm();
        if (const KeyRefusal no = irregular_refusal(step.hs, step.tp, depth, g); !no.key.empty())
            t.fail(no.key, label + no.reason);
        if (const std::string why = gauge_refusal(s, *w.gauge_x, step.tp); !why.empty())
            t.fail("Tp", label + "waves.gauge_x: " + why);
        if (!t.has("ramp_time"))
            step.ramp_time = root.section("waves").has("ramp_time") ? w.ramp_time : 2.0 * step.tp;
        if (step.waves > 0.0) {
            const IrregularWaves c =
                jonswap_components(JonswapSea{step.hs, step.tp, step.gamma, w.components, step.seed});
            step.duration = front_travel(s, step.tp) + step.waves * target_tm02(c);
        } else if (!t.has("duration")) {
            step.duration = s.duration;
        }
        t.check(step.duration >= s.output_interval, t.has("waves") ? "waves" : "duration",
                label + "the step's " + number_text(step.duration) +
                    " s must be >= run.output_interval = " + number_text(s.output_interval) + " s",
                t.has("waves") ? step.waves : step.duration);
        s.series.push_back(step);
    }
}

// A graded z axis holds all along the flume: the refined box's z range is the
// free surface's band everywhere, so it must hold the largest wave's crest
// and trough (+- its height: a bound, not a profile), except where it reaches
// the domain's top or floor and there are no coarse cells beyond it. Here,
// not when the mesh is made, so that a sweep's cases are refused in its plan.
void check_surface_band(const Table &root, const Scene &s) {
    if (!s.fluid || !s.fluid->refine_min)
        return;
    const SceneFluid &f = *s.fluid;
    const double fine_z = f.fine_cell(s.domain_max - s.domain_min).z();
    if (f.coarse_cell_size.z() <= fine_z)
        return; // z not graded
    double height = f.wave_height;
    if (s.waves && s.waves->type == "regular")
        height = s.waves->height;
    if (s.waves && s.waves->type == "irregular")
        height = kLargestWaveOverHs * s.waves->hs;
    for (const SceneSeriesStep &step : s.series) // a series runs each of its sea states
        height = std::max(height, kLargestWaveOverHs * step.hs);
    const double tolerance = 1e-9 * (s.domain_max.z() - s.domain_min.z());
    const bool coarse_below = f.refine_min->z() > s.domain_min.z() + tolerance,
               coarse_above = f.refine_max->z() < s.domain_max.z() - tolerance;
    const bool misses_trough = coarse_below && f.refine_min->z() > f.water_level - height,
               misses_crest = coarse_above && f.refine_max->z() < f.water_level + height;
    if (misses_trough || misses_crest)
        root.section("fluid").fail(
            misses_trough ? "refine_min" : "refine_max",
            "the refined box's z range " + number_text(f.refine_min->z()) + " .. " +
                number_text(f.refine_max->z()) + " m must hold the free surface " +
                number_text(f.water_level) + " m +- the wave height " + figure_text(height) + " m" +
                (s.waves && s.waves->type == "irregular"
                     ? " (" + number_text(kLargestWaveOverHs) + " Hs" +
                           (s.series.empty() ? std::string(")") : " of the highest [[series]] step)")
                     : "") +
                ": the z grading holds all along the flume, and coarse cells there damp the waves");
}

// [[porous]] after [fluid] and the walls: boxes inside the fluid mesh, or
// layers under a slope wall; unique names (each is the cellZone porous_NAME).
void read_porous(const Table &root, Scene &s) {
    const auto &keys = porous_keys();
    for (const Table &t : root.entries("porous")) {
        t.only(names_of(keys));
        ScenePorous p;
        read_value(t, key_named(keys, "type"), p);
        forbid_other_variants(t, keys, p.type, "porous type");
        read_keys(t, keys, p, p.type);
        if (!s.fluid)
            t.fail("name", "a porous region is in the fluid: the scene needs a [fluid] table");
        check_region_name(t, p.name, s.porous, "[[porous]]");
        if (p.type == "slope_layer") {
            const SceneWall &wall = slope_wall_named(t, s, p.wall);
            // Deeper than the slope is high, the layer holds no cell.
            if (wall.height <= p.depth)
                t.fail("depth", "must be less than wall " + toml_string(p.wall) + "'s height " +
                                    number_text(wall.height) + " m (got " + number_text(p.depth) + ")");
        } else {
            check_box(t, p.min, p.max, s);
        }
        s.porous.push_back(p);
    }
    // A slope_layer below the surface must lie under other layers of its wall
    // that reach down to it: the slope between would be cut out of the mesh
    // (slope_waves), closing the layer off from the water, and interFoam
    // cannot solve a closed region (its pressure has no level).
    const auto tables = root.entries("porous");
    for (std::size_t k = 0; k < s.porous.size(); ++k) {
        const ScenePorous &p = s.porous[k];
        if (p.type != "slope_layer")
            continue;
        double reached = 0.0;
        for (bool grew = true; grew && reached < p.depth;) {
            grew = false;
            for (const ScenePorous &o : s.porous)
                if (o.type == "slope_layer" && o.wall == p.wall && o.depth <= reached + 1e-9 && o.thickness &&
                    o.depth + *o.thickness > reached + 1e-9) {
                    reached = o.depth + *o.thickness;
                    grew = true;
                }
        }
        if (reached < p.depth - 1e-9)
            tables[k].fail("depth", "the slope_layers of wall " + toml_string(p.wall) + " reach down to " +
                                        number_text(reached) + " m only: the slope between that and " +
                                        number_text(p.depth) +
                                        " m is impermeable and closes this layer off from the water; "
                                        "start it at " +
                                        number_text(reached) + " m or add a layer between");
    }
}

// [[refine]] after [fluid] and the walls: boxes inside the fluid mesh, or
// bands about a slope wall; unique names. fluid.mesh defaults to "refined"
// with regions; a refined mesh halves its base cells L times in x and y (L
// the deepest level), so fluid.cells must hold 2^L whole base cells there.
void read_refine(const Table &root, Scene &s) {
    const auto &keys = refine_keys();
    for (const Table &t : root.entries("refine")) {
        t.only(names_of(keys));
        SceneRefine r;
        read_value(t, key_named(keys, "type"), r);
        forbid_other_variants(t, keys, r.type, "refine type");
        read_keys(t, keys, r, r.type);
        // read_value checks an integer's lower bound only.
        t.check(r.level <= 3, "level", "must be in [1, 3]", r.level);
        if (!s.fluid)
            t.fail("name", "a refined region is in the fluid mesh: the scene needs a [fluid] table");
        check_region_name(t, r.name, s.refine, "[[refine]]");
        if (r.type == "slope_band") {
            slope_wall_named(t, s, r.wall); // refuses any other wall
        } else {
            check_box(t, r.min, r.max, s);
        }
        s.refine.push_back(r);
    }
    if (!s.fluid)
        return;
    SceneFluid &f = *s.fluid;
    const Table fluid = root.section("fluid");
    if (!fluid.has("mesh"))
        f.mesh = s.refine.empty() ? "graded" : "refined";
    if (f.mesh != "refined")
        return;
    if (s.refine.empty())
        fluid.fail("mesh", "\"refined\" splits the cells of [[refine]] regions: the scene has none (add "
                           "[[refine]] tables, or mesh = \"graded\")");
    int levels = 0;
    for (const SceneRefine &r : s.refine)
        levels = std::max(levels, r.level);
    const int split = 1 << levels;
    if (f.cells[0] % split != 0 || f.cells[1] % split != 0)
        fluid.fail(fluid.has("cells") ? "cells" : "cell_size",
                   "a refined mesh of [[refine]] level " + std::to_string(levels) +
                       " splits its base cells " + std::to_string(split) +
                       " times along x and y: the fine cells along x and y must be "
                       "multiples of " +
                       std::to_string(split) + " (got [" + std::to_string(f.cells[0]) + ", " +
                       std::to_string(f.cells[1]) + ", " + std::to_string(f.cells[2]) +
                       "]); or fluid.mesh = \"graded\"");
}

} // namespace scene_read

} // namespace armour
