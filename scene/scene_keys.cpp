#include "scene_keys.h"

#include "engine_registry.h"
#include "input_error.h"
#include "shapes.h"

#include <cmath>
#include <type_traits>

namespace armour {

namespace {

const std::vector<std::string> kAnalyses = {"none",     "tilt",        "slope",  "bounce",
                                            "buoyancy", "float",       "still",  "dambreak",
                                            "platform", "slope_waves", "damage", "pull"};

} // namespace

// ---------------------------------------------------------------- the table
// (the wave flume's sections, [fluid], [waves], [[series]], [[porous]] and
// [[refine]]: scene_keys_flume.cpp)

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
            .one_of(engine_style_names())
            .defaults("`\"liggghts\"`; `\"bullet\"` with `[fluid]`"),
        key("duration", &Scene::duration, "s", "simulated time").in(Range::above(0)),
        key("output_interval", &Scene::output_interval, "s", "time between saved frames; <= duration")
            .in(Range::above(0)),
        key("time_step", &Scene::time_step, "s",
            "engine step; <= output_interval; 0 = the engine's own: LIGGGHTS from the contact "
            "stiffness, Bullet min(1 ms, sqrt(Dn / g) / 256) for the smallest unit")
            .in(Range::at_least(0)),
        key("force_time_step", &Scene::force_time_step, "", "true: use time_step even above the stable step"),
        key("contact_iterations", &Scene::contact_iterations, "",
            "sequential-impulse iterations per step of an engine with rigid contacts (bullet): more hold a "
            "tall stack's lower units out of each other and a settled layer at rest, at more cost "
            "(docs/bullet.md); 0 = the engine's own (bullet: the adapter's 50); refused where run.engine or "
            "fluid.settle_engine has spring-dashpot contacts or none")
            .in(Range::at_least(0))
            .written_if([](const Scene &s) { return s.contact_iterations != 0; }),
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
        key("edge_spheres", &U::edge_spheres, "",
            "support spheres along every edge of the faces the unit rests on, besides the corner ones, out "
            "of `spheres` (needs it; optimised and inscribed): a unit resting on this one pivots at its "
            "edge, not on the last sphere cap short of it (clump_builder.md)")
            .in(Range::at_least(0))
            .written_if([](const U &u) { return u.edge_spheres > 0; }),
        key("tol_volume", &U::tol_volume, "", "tolerance mode: allowed relative volume error")
            .in(Range::open(0, 1)),
        key("tol_surface", &U::tol_surface, "", "tolerance mode: allowed surface RMS distance / Dn")
            .in(Range::open(0, 1)),
        key("method", &U::method, "", "clump method (clump_builder.md)")
            .one_of({"greedy", "optimised", "inscribed"}),
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
            "loose until a settle (docs/stability.md); seated: as random, but from the toe up, row by row, "
            "and each unit then slid down the face a tenth of Dn at a time while its centre goes lower, "
            "into the first trough (at most 5 Dn)")
            .one_of({"grid", "random", "seated"}),
        key("seed", &P::seed, "", "placement \"random\" or \"seated\": the same seed gives the same poses")
            .in(Range::at_least(0)),
        key("clear_of_toe", &P::clear_of_toe, "",
            "placement \"random\" or \"seated\": true sets every unit with its centre landward of the slope "
            "wall's foot (toe_x), none over the toe in front of it, as a placer starts the layer on the toe; "
            "unset or false, the pile's lowest units may stand out over it (docs/stability.md)"),
        key("first_row", &P::first_row, "",
            "the first row placed (0: the toe's); the rows below stay empty for units already there "
            "([[body]]), which random and seated placement set the pattern's units clear of (a settle in "
            "stages, fluid.settle_stages, writes such scenes)")
            .in(Range::at_least(0))
            .written_if([](const P &p) { return p.first_row != 0; }),
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
                   [&](std::vector<double> S::*) {
                       info.type = "array of numbers";
                       value = "[]";
                   },
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
