#include "wave_case.h"

#include "flume_mesh.h"
#include "gauge_rows.h"
#include "jonswap.h"
#include "scene_keys.h"
#include "wave_separation.h"
#include "wave_theory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace armour {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string num(double v) {
    return number_text(v);
}

// How much of the run the gauges saw waves in (a short run ends before the front comes).
std::string after_front(double end, double front) {
    if (end <= front)
        return "waves: the record ends at " + figure_text(end) +
               " s, before the wave front reaches the gauges (" + figure_text(front) + " s)";
    return "waves: the record leaves " + figure_text(end - front) +
           " s after the wave front reaches the gauges (" + figure_text(front) + " s)";
}

// The Mansard-Funke array (x, x + L/10, x + L/4), each moved to the centre
// of its column of cells (a point on a face would sit in two columns).
std::vector<double> gauge_positions(const Scene &scene) {
    const SceneWaves &w = *scene.waves;
    const double L = wavelength(w.target_period(), scene.still_water_depth(), scene.gravity.norm());
    const MeshAxis along = flume_mesh(scene).axes[0];
    std::vector<double> x;
    for (const double at : {*w.gauge_x, *w.gauge_x + 0.1 * L, *w.gauge_x + 0.25 * L})
        x.push_back(along.column_centre(at));
    return x;
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

std::string wave_properties(const SceneWaves &w) {
    std::ostringstream o;
    o << "inlet\n{\n    alpha           alpha.water;\n    nPaddle         1;\n"
      << "    rampTime        " << num(w.ramp_time) << ";\n"
      << "    activeAbsorption " << (w.active_absorption ? "yes" : "no") << ";\n";
    if (w.type == "regular") {
        o << "    waveModel       " << w.theory << ";\n    waveHeight      " << num(w.height)
          << ";\n    wavePeriod      " << num(w.period) << ";\n    waveAngle       0;\n";
    } else {
        // One direction (0 deg) per frequency: irregularMultiDirectional sums
        // H/2 cos(k x - w t + phase) over the lists.
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
    o << "}\n";
    if (w.outlet == "shallow_water")
        o << "\noutlet\n{\n    alpha           alpha.water;\n    waveModel       shallowWaterAbsorption;\n"
          << "    nPaddle         1;\n}\n";
    return o.str();
}

struct GaugeRecord {
    std::vector<double> t;
    std::vector<std::vector<double>> eta; // per gauge
};

GaugeRecord read_gauges(const fs::path &case_dir, double level, std::size_t count) {
    GaugeRecord r;
    r.eta.resize(count);
    for (const std::vector<double> &row : gauge_rows(case_dir)) {
        if (row.size() < count + 1)
            continue;
        r.t.push_back(row[0]);
        for (std::size_t i = 0; i < count; ++i)
            r.eta[i].push_back(row[i + 1] - level);
    }
    return r;
}

} // namespace

bool makes_wave_train(const Scene &scene) {
    return scene.fluid && scene.waves && scene.waves->type != "solitary";
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
    const SceneWaves &w = *scene.waves;
    tokens["@WAVE_PROPERTIES@"] = wave_properties(w);
    tokens["@OUTLET_U@"] = outlet_velocity(scene);
    const double y = 0.5 * (scene.domain_min.y() + scene.domain_max.y());
    std::string gauges = "(";
    for (const double x : gauge_positions(scene))
        gauges += "(" + num(x) + " " + num(y) + " " + num(scene.domain_min.z()) + ") ";
    tokens["@WAVE_GAUGES@"] = gauges.substr(0, gauges.size() - 1) + ")";
}

void add_wave_summary(const Scene &scene, const fs::path &case_dir, OutputFolder &folder, json &summary,
                      double until) {
    const SceneWaves &w = *scene.waves;
    const double depth = scene.still_water_depth(), g = scene.gravity.norm();
    const double period = w.target_period(), H = w.target_height();
    const bool regular = w.type == "regular";
    const std::vector<double> x = gauge_positions(scene);
    GaugeRecord rec = read_gauges(case_dir, scene.fluid->water_level, 3);
    while (!rec.t.empty() && rec.t.back() > until) {
        rec.t.pop_back();
        for (auto &eta : rec.eta)
            eta.pop_back();
    }
    json out = {
        {"type", w.type}, {"target_height", H}, {"target_period", period}, {"gauge_x", x}, {"depth", depth}};
    if (regular)
        out["theory"] = w.theory;
    auto warn = [&](const std::string &text) {
        summary["warnings"].push_back(text);
        std::fprintf(stderr, "armour: warning: %s\n", text.c_str());
    };
    if (rec.t.size() < 8) {
        warn("waves: the gauges recorded nothing (" + (case_dir / "postProcessing/gauges").string() + ")");
        summary["waves"] = out;
        return;
    }
    // Analysis window: the waves are steady at the gauges once the ramp is
    // over and the front (group velocity at T or Tp) has been to the outlet
    // and back past the first gauge, so the reflection is in the record.
    const double x_in = scene.domain_min.x(), x_out = scene.domain_max.x(), end = rec.t.back();
    const double cg = group_velocity(period, depth, g);
    const double front = w.ramp_time + (x[2] - x_in) / cg;
    const double steady = w.ramp_time + (2.0 * (x_out - x_in) - (x[0] - x_in)) / cg;
    IrregularWaves comps;
    double span = 0.0; // s, the window's length
    if (regular) {
        const double from = end - steady >= 3.0 * period ? steady : front;
        span = std::floor((end - from) / period) * period;
        if (span < 3.0 * period) {
            warn(after_front(end, front) + ": fewer than 3 periods, no analysis");
            summary["waves"] = out;
            return;
        }
    } else {
        comps = jonswap_components(w.jonswap_sea());
        const double repeat = 1.0 / comps.frequency_step;
        out["repeat_period"] = repeat;
        if (end > 2.0 * repeat)
            warn("waves: the irregular train repeats every " + figure_text(repeat) +
                 " s (waves.components x Tp / 2): this " + figure_text(end) + " s run met the same waves " +
                 figure_text(std::floor(end / repeat)) +
                 " times, so its wave count N counts repeats; more waves.components (up to 200) lengthen the "
                 "train");
        span = end - steady >= repeat ? repeat : end - std::max(front, std::min(steady, end - repeat));
        if (span < 4.0 * period) {
            warn(after_front(end, front) + ": shorter than 4 Tp, no analysis");
            summary["waves"] = out;
            return;
        }
    }
    if (end - span < steady)
        warn("waves: the analysis window starts at " + figure_text(end - span) +
             " s, before the outlet's reflection is back at the gauges (" + figure_text(steady) +
             " s): the reflection coefficient is underestimated; a longer record (run.duration) moves the "
             "window past it");
    // Uniform samples, a whole number per window: 64 per period.
    const auto n = static_cast<std::size_t>(std::lround(span / period * 64.0));
    const double dt = span / static_cast<double>(n), t0 = end - span;
    GaugeArray array{x, dt, {}};
    for (const auto &eta : rec.eta)
        array.eta.push_back(resample(rec.t, eta, t0, dt, n));
    const double f_min = regular ? 0.5 / period : comps.frequency.front() - 0.5 * comps.frequency_step;
    const double f_max = regular ? 1.5 / period : comps.frequency.back() + 0.5 * comps.frequency_step;
    const SeparatedWaves spectra = separate_waves(array, depth, g, f_min, f_max);
    const SpectralParameters inc = spectral_parameters(spectra.frequency, spectra.incident, f_min, f_max);
    const SpectralParameters ref = spectral_parameters(spectra.frequency, spectra.reflected, f_min, f_max);
    std::vector<double> heights, periods;
    for (const auto &eta : array.eta) {
        const ZeroCrossing z = zero_down_crossing(eta, dt, 0.05 * H);
        heights.push_back(z.mean_height);
        periods.push_back(z.mean_period);
    }
    double incident_height = inc.hm0, incident_period = inc.tp, reflection = std::sqrt(ref.m0 / inc.m0);
    if (regular) {
        const RegularSeparation r = separate_regular(array, period, depth, g);
        incident_height = r.incident_height;
        reflection = r.reflection;
        incident_period = (periods[0] + periods[1] + periods[2]) / 3.0;
    }
    // Every wave that passed the first gauge (ripples below 5 % of H left out).
    const double dt_all = period / 64.0;
    const auto n_all = static_cast<std::size_t>(rec.t.back() / dt_all);
    const ZeroCrossing all =
        zero_down_crossing(resample(rec.t, rec.eta[0], 0.0, dt_all, n_all), dt_all, 0.05 * H);
    out["incident_height"] = incident_height;
    out["incident_period"] = incident_period;
    out["incident_Tm10"] = inc.tm10;
    // Van der Meer's wave steepness with the mean period Tm ~ Tm0,2 (regular: T).
    const double tm = regular ? incident_period : inc.tm02;
    out["s_om"] = 2.0 * M_PI * incident_height / (g * tm * tm);
    out["reflection_coefficient"] = reflection;
    out["waves"] = all.waves;
    out["gauge_heights"] = heights;
    out["gauge_periods"] = periods;
    out["window"] = {t0, end};
    out["incident_Tm02"] = inc.tm02;
    // Target spectrum on the record's frequencies (regular: the line's bin).
    std::ostringstream csv;
    csv << "# incident/reflected separation (Mansard-Funke), gauges at x = " << num(x[0]) << ", " << num(x[1])
        << ", " << num(x[2]) << " m, window " << num(t0) << " .. " << num(end) << " s\n"
        << "frequency_Hz,target_m2_per_Hz,incident_m2_per_Hz,reflected_m2_per_Hz,gauges_m2_per_Hz,resolved\n";
    const double df = spectra.frequency.size() > 1 ? spectra.frequency[1] - spectra.frequency[0] : 1.0;
    for (std::size_t j = 0; j < spectra.frequency.size(); ++j) {
        const double f = spectra.frequency[j];
        const double target = regular
                                  ? (std::abs(f * period - 1.0) < 0.5 * df * period ? H * H / 8.0 / df : 0.0)
                                  : comps.shape_scale * jonswap_shape(f, 1.0 / w.tp, w.gamma);
        csv << num(f) << "," << num(target) << "," << num(spectra.incident[j]) << ","
            << num(spectra.reflected[j]) << "," << num(spectra.measured[j]) << ","
            << (spectra.resolved[j] ? 1 : 0) << "\n";
    }
    const fs::path csv_path = folder.claim("waves_spectrum.csv");
    write_text_file(csv_path, csv.str());
    const fs::path png = folder.claim("waves_spectrum.png");
    const std::string plot = std::string("/usr/bin/python3 '") + ARMOUR_SOURCE_DIR +
                             "/analysis/wave_spectrum_chart.py' '" + csv_path.string() + "' '" +
                             png.string() + "' > /dev/null 2>&1";
    if (std::system(plot.c_str()) != 0)
        warn("waves: the spectrum chart failed (needs python3-matplotlib): " + plot);
    out["files"] = {{"spectrum", "waves_spectrum.csv"}, {"chart", "waves_spectrum.png"}};
    out["si_units"] = {{"heights", "m"}, {"periods", "s"}, {"spectra", "m^2/Hz"}};
    summary["waves"] = out;
}

} // namespace armour
