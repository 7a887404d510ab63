#include "wave_case.h"

#include "flume_mesh.h"
#include "input_error.h"
#include "jonswap.h"
#include "scene_keys.h"
#include "wave_theory.h"

#include <sstream>

namespace armour {

namespace {

std::string num(double v) {
    return number_text(v);
}

std::string list_of(const std::vector<double> &v, bool one_per_row) {
    std::string s = std::to_string(v.size()) + "(";
    for (std::size_t i = 0; i < v.size(); ++i)
        s += (i ? " " : "") + (one_per_row ? "(" + num(v[i]) + ")" : num(v[i]));
    return s + ")";
}

// The outlet's velocity condition (alpha zeroGradient, p_rgh fixedFluxPressure).
std::string outlet_velocity(const Scene &scene) {
    const SceneWaves &w = *scene.waves;
    if (w.outlet == "wall")
        return "type            noSlip;";
    if (w.outlet == "shallow_water")
        return "type            waveVelocity;\n        value           uniform (0 0 0);";
    // Linear celerity at T (Tp): the depth-mean velocity of a wave leaving is c eta / h.
    const double depth = scene.still_water_depth(), period = w.target_period();
    const double c = wavelength(period, depth, scene.gravity.norm()) / period;
    return "type            armourShallowWaterAbsorption;\n        waterDepth      " + num(depth) +
           ";\n        celerity        " + num(c) + ";\n        value           uniform (0 0 0);";
}

// One direction (0 deg) per frequency: irregularMultiDirectional sums
// H/2 cos(k x - w t + phase) over the lists.
void irregular_properties(const SceneWaves &w, std::ostringstream &o) {
    const IrregularWaves c = jonswap_components(w.jonswap_sea());
    std::vector<double> periods, heights, zeros(c.frequency.size(), 0.0);
    for (std::size_t j = 0; j < c.frequency.size(); ++j) {
        periods.push_back(1.0 / c.frequency[j]);
        heights.push_back(2.0 * c.amplitude[j]);
    }
    o << "    waveModel       irregularMultiDirectional;\n"
      << "    wavePeriods     " << list_of(periods, true) << ";\n"
      << "    waveHeights     " << list_of(heights, true) << ";\n"
      << "    wavePhases      " << list_of(c.phase, true) << ";\n"
      << "    waveDirs        " << list_of(zeros, true) << ";\n";
}

std::string wave_properties(const SceneWaves &w) {
    std::ostringstream o;
    o << "inlet\n{\n    alpha           alpha.water;\n    nPaddle         1;\n"
      << "    rampTime        " << num(w.ramp_time) << ";\n"
      << "    activeAbsorption " << (w.active_absorption ? "yes" : "no") << ";\n";
    if (w.type == "regular")
        o << "    waveModel       " << w.theory << ";\n    waveHeight      " << num(w.height)
          << ";\n    wavePeriod      " << num(w.period) << ";\n    waveAngle       0;\n";
    else
        irregular_properties(w, o);
    o << "}\n";
    if (w.outlet == "shallow_water")
        o << "\noutlet\n{\n    alpha           alpha.water;\n    waveModel       shallowWaterAbsorption;\n"
          << "    nPaddle         1;\n}\n";
    return o.str();
}

} // namespace

bool makes_wave_train(const Scene &scene) {
    return scene.fluid && scene.waves && scene.waves->type != "solitary";
}

// The Mansard-Funke array, then waves.extra_gauges, each gauge moved to the
// centre of its column of the block's cells (a point on a face would sit in
// two columns; in a [[refine]] region that centre is the face between the
// halves, where the gauges' function object reads the cell on its +x side).
std::vector<double> wave_gauge_positions(const Scene &scene) {
    if (!makes_wave_train(scene))
        return {};
    const SceneWaves &w = *scene.waves;
    const double L = wavelength(w.target_period(), scene.still_water_depth(), scene.gravity.norm());
    const MeshAxis along = flume_mesh(scene).axes[0];
    std::vector<double> at = {*w.gauge_x, *w.gauge_x + 0.1 * L, *w.gauge_x + 0.25 * L};
    at.insert(at.end(), w.extra_gauges.begin(), w.extra_gauges.end());
    std::vector<double> x;
    for (const double a : at)
        x.push_back(along.column_centre(a));
    return x;
}

void wave_tokens(const Scene &scene, const std::string &template_text,
                 std::map<std::string, std::string> &tokens) {
    const bool maker = template_text.find("@WAVE_PROPERTIES@") != std::string::npos;
    const std::string &case_name = scene.fluid->case_name;
    if (maker && !makes_wave_train(scene))
        throw InputError(scene.file + ": key 'waves.type': fluid.case \"" + case_name +
                         "\" is a wave maker: add [waves] with type \"regular\" or \"irregular\"");
    if (!maker && makes_wave_train(scene))
        throw InputError(scene.file + ": key 'fluid.case': [waves] type \"" + scene.waves->type +
                         "\" needs a wave-maker template (\"wave_flume\"); \"" + case_name + "\" has none");
    const bool flat = scene.fluid->cells[1] == 1;
    tokens["@SIDES_PATCH@"] = flat ? "empty" : "wall";
    tokens["@SIDES_U@"] = flat ? "empty" : "slip";
    tokens["@SIDES_SCALAR@"] = flat ? "empty" : "zeroGradient";
    tokens["@SIDES_P@"] = flat ? "empty" : "fixedFluxPressure";
    if (!maker)
        return;
    tokens["@WAVE_PROPERTIES@"] = wave_properties(*scene.waves);
    tokens["@OUTLET_U@"] = outlet_velocity(scene);
    const double y = 0.5 * (scene.domain_min.y() + scene.domain_max.y());
    std::string gauges = "(";
    for (const double x : wave_gauge_positions(scene))
        gauges += "(" + num(x) + " " + num(y) + " " + num(scene.domain_min.z()) + ") ";
    tokens["@WAVE_GAUGES@"] = gauges.substr(0, gauges.size() - 1) + ")";
}

} // namespace armour
