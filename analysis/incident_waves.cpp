#include "incident_waves.h"

#include "gauge_rows.h"
#include "jonswap.h"
#include "output_folder.h"
#include "scene_keys.h"
#include "wave_separation.h"
#include "wave_theory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

struct GaugeRecord {
    std::vector<double> t;
    std::vector<std::vector<double>> eta; // per gauge
};

// The gauges' rows up to `until` (s), eta from the still water level: the
// first `count` gauges, or as many as every row of three or more holds (a
// case written without the scene's extra gauges keeps its array).
GaugeRecord read_gauges(const fs::path &case_dir, double level, std::size_t count, double until) {
    std::vector<std::vector<double>> rows;
    for (std::vector<double> &row : gauge_rows(case_dir))
        if (row.size() >= 4 && row[0] <= until) {
            count = std::min(count, row.size() - 1);
            rows.push_back(std::move(row));
        }
    GaugeRecord r;
    r.eta.resize(count);
    for (const std::vector<double> &row : rows) {
        r.t.push_back(row[0]);
        for (std::size_t i = 0; i < count; ++i)
            r.eta[i].push_back(row[i + 1] - level);
    }
    return r;
}

// The analysis window: its length (s; 0 when the record holds too little,
// with the warning why) and the time the waves are steady at the gauges.
struct Window {
    double span = 0.0;
    double steady = 0.0;
};

// The waves are steady at the gauges once the ramp is over and the front
// (group velocity at T or Tp) has been to the outlet and back past the
// first gauge, so the reflection is in the record.
Window analysis_window(const Scene &scene, const std::vector<double> &x, double end,
                       const IrregularWaves &comps, IncidentWaves &r) {
    const SceneWaves &w = *scene.waves;
    const double period = w.target_period();
    const double x_in = scene.domain_min.x(), x_out = scene.domain_max.x();
    const double cg = group_velocity(period, scene.still_water_depth(), scene.gravity.norm());
    const double front = w.ramp_time + (x[2] - x_in) / cg;
    Window win;
    win.steady = w.ramp_time + (2.0 * (x_out - x_in) - (x[0] - x_in)) / cg;
    if (w.type == "regular") {
        const double from = end - win.steady >= 3.0 * period ? win.steady : front;
        win.span = std::floor((end - from) / period) * period;
        if (win.span < 3.0 * period) {
            r.warnings.push_back(after_front(end, front) + ": fewer than 3 periods, no analysis");
            win.span = 0.0;
        }
        return win;
    }
    const double repeat = 1.0 / comps.frequency_step;
    r.figures["repeat_period"] = repeat;
    if (end > 2.0 * repeat)
        r.warnings.push_back("waves: the irregular train repeats every " + figure_text(repeat) +
                             " s (waves.components x Tp / 2): this " + figure_text(end) +
                             " s run met the same waves " + figure_text(std::floor(end / repeat)) +
                             " times, so its wave count N counts repeats; more waves.components (up to 200) "
                             "lengthen the train");
    win.span =
        end - win.steady >= repeat ? repeat : end - std::max(front, std::min(win.steady, end - repeat));
    if (win.span < 4.0 * period) {
        r.warnings.push_back(after_front(end, front) + ": shorter than 4 Tp, no analysis");
        win.span = 0.0;
    }
    return win;
}

// waves_spectrum.csv: the separated spectra beside the target on the
// record's frequencies (regular: the line's bin).
std::string spectrum_csv(const SceneWaves &w, const std::vector<double> &x, double t0, double end,
                         const SeparatedWaves &spectra, const IrregularWaves &comps) {
    const bool regular = w.type == "regular";
    const double period = w.target_period(), H = w.target_height();
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
    return csv.str();
}

// One gauge's total waves (null where too few waves give a figure none).
json total_waves(double x, const WaveStatistics &w) {
    const auto figure = [](double v) { return std::isnan(v) ? json(nullptr) : json(v); };
    return {{"x", x},
            {"Hm0", w.hm0},
            {"H_max", figure(w.h_max)},
            {"H_one_third", figure(w.h_one_third)},
            {"H_2_percent", figure(w.h_2_percent)},
            {"waves", w.waves},
            {"mean_level", w.mean_level}};
}

// The separation over the window's last `span` s: the figures into r.figures.
void separate(const Scene &scene, const std::vector<double> &x, const GaugeRecord &rec, double span,
              const IrregularWaves &comps, IncidentWaves &r) {
    const SceneWaves &w = *scene.waves;
    const double depth = scene.still_water_depth(), g = scene.gravity.norm();
    const double period = w.target_period(), H = w.target_height(), end = rec.t.back();
    const bool regular = w.type == "regular";
    // Uniform samples, a whole number per window: 64 per period.
    const auto n = static_cast<std::size_t>(std::lround(span / period * 64.0));
    const double dt = span / static_cast<double>(n), t0 = end - span;
    GaugeArray array{{x.begin(), x.begin() + 3}, dt, {}};
    for (std::size_t i = 0; i < 3; ++i)
        array.eta.push_back(resample(rec.t, rec.eta[i], t0, dt, n));
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
        const RegularSeparation s = separate_regular(array, period, depth, g);
        incident_height = s.incident_height;
        reflection = s.reflection;
        incident_period = (periods[0] + periods[1] + periods[2]) / 3.0;
    }
    // Every wave that passed the first gauge (ripples below 5 % of H left out).
    const double dt_all = period / 64.0;
    const auto n_all = static_cast<std::size_t>(rec.t.back() / dt_all);
    const ZeroCrossing all =
        zero_down_crossing(resample(rec.t, rec.eta[0], 0.0, dt_all, n_all), dt_all, 0.05 * H);
    json &out = r.figures;
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
    // Each gauge's total waves, the array's beside the extra ones' (a berm's against the toe's).
    out["array_gauges"] = json::array();
    out["extra_gauges"] = json::array();
    for (std::size_t i = 0; i < rec.eta.size(); ++i) {
        // The array's records are resampled already, for the separation.
        std::vector<double> eta = i < 3 ? array.eta[i] : resample(rec.t, rec.eta[i], t0, dt, n);
        out[i < 3 ? "array_gauges" : "extra_gauges"].push_back(
            total_waves(x[i], wave_statistics(std::move(eta), dt, 0.05 * H)));
    }
    r.spectrum_csv = spectrum_csv(w, array.x, t0, end, spectra, comps);
}

} // namespace

IncidentWaves measure_incident_waves(const Scene &scene, const std::vector<double> &x,
                                     const fs::path &case_dir, double until) {
    const SceneWaves &w = *scene.waves;
    IncidentWaves r;
    r.figures = {{"type", w.type},
                 {"target_height", w.target_height()},
                 {"target_period", w.target_period()},
                 {"gauge_x", std::vector<double>(x.begin(), x.begin() + 3)},
                 {"depth", scene.still_water_depth()}};
    if (w.type == "regular")
        r.figures["theory"] = w.theory;
    const GaugeRecord rec = read_gauges(case_dir, scene.fluid->water_level, x.size(), until);
    if (rec.t.size() < 8) {
        r.warnings.push_back("waves: the gauges recorded nothing (" +
                             (case_dir / "postProcessing/gauges").string() + ")");
        return r;
    }
    if (rec.eta.size() < x.size())
        r.warnings.push_back("waves: the gauges' record holds " + std::to_string(rec.eta.size()) +
                             " gauges where the scene names " + std::to_string(x.size()) +
                             ": waves.extra_gauges from x = " + figure_text(x[rec.eta.size()]) +
                             " m have no record and are left out");
    const IrregularWaves comps = w.type == "regular" ? IrregularWaves{} : jonswap_components(w.jonswap_sea());
    const double end = rec.t.back();
    const Window win = analysis_window(scene, x, end, comps, r);
    if (win.span <= 0.0)
        return r;
    if (end - win.span < win.steady)
        r.warnings.push_back(
            "waves: the analysis window starts at " + figure_text(end - win.span) +
            " s, before the outlet's reflection is back at the gauges (" + figure_text(win.steady) +
            " s): the reflection coefficient is underestimated; a longer record (run.duration) "
            "moves the window past it");
    separate(scene, x, rec, win.span, comps, r);
    return r;
}

void add_incident_waves(const IncidentWaves &waves,
                        const std::function<std::string(const std::string &)> &claim, json &summary) {
    auto warn = [&](const std::string &text) {
        summary["warnings"].push_back(text);
        std::fprintf(stderr, "armour: warning: %s\n", text.c_str());
    };
    for (const std::string &text : waves.warnings)
        warn(text);
    json out = waves.figures;
    if (!waves.spectrum_csv.empty()) {
        const fs::path csv_path = claim("waves_spectrum.csv");
        write_text_file(csv_path, waves.spectrum_csv);
        const fs::path png = claim("waves_spectrum.png");
        const std::string plot = std::string("/usr/bin/python3 '") + ARMOUR_SOURCE_DIR +
                                 "/analysis/wave_spectrum_chart.py' '" + csv_path.string() + "' '" +
                                 png.string() + "' > /dev/null 2>&1";
        if (std::system(plot.c_str()) != 0)
            warn("waves: the spectrum chart failed (needs python3-matplotlib): " + plot);
        out["files"] = {{"spectrum", "waves_spectrum.csv"}, {"chart", "waves_spectrum.png"}};
        out["si_units"] = {
            {"heights", "m"}, {"periods", "s"}, {"spectra", "m^2/Hz"}, {"x", "m"}, {"mean_level", "m"}};
    }
    summary["waves"] = out;
}

} // namespace armour
