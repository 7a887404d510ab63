#include "compare_stats.h"

#include "input_error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace armour {

using nlohmann::json;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

json number(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}

double as_number(const json &v) {
    return v.is_number() ? v.get<double>() : kNaN;
}

std::string fmt(double v, const char *format = "%.3g") {
    char text[64];
    std::snprintf(text, sizeof text, format, v);
    return text;
}

std::string group_label(const json &g) {
    const int spheres = g["spheres"].get<int>();
    return spheres == 0 ? "exact hulls" : std::to_string(spheres) + " spheres";
}

} // namespace

double student_t95(double dof) {
    // Two-sided 95 % quantiles for 1..30 degrees of freedom.
    static const double table[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                                   2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                                   2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
    if (!(dof >= 1.0))
        return kNaN;
    const double k = std::floor(dof);
    if (k <= 30.0)
        return table[static_cast<int>(k) - 1];
    // Beyond the table: the Cornish-Fisher expansion about the normal quantile
    // (error < 1e-4 from 30 degrees of freedom on).
    const double z = 1.959964, z3 = z * z * z, z5 = z3 * z * z;
    return z + (z3 + z) / (4.0 * k) + (5.0 * z5 + 16.0 * z3 + 3.0 * z) / (96.0 * k * k);
}

Spread spread_of(const std::vector<double> &values) {
    Spread s{static_cast<int>(values.size()), kNaN, kNaN, kNaN};
    if (values.empty())
        return s;
    double sum = 0.0;
    for (double v : values)
        sum += v;
    s.mean = sum / s.n;
    if (s.n < 2)
        return s;
    double squares = 0.0;
    for (double v : values)
        squares += (v - s.mean) * (v - s.mean);
    s.std = std::sqrt(squares / (s.n - 1));
    s.ci95 = student_t95(s.n - 1) * s.std / std::sqrt(static_cast<double>(s.n));
    return s;
}

Spread difference_of(const std::vector<double> &a, const std::vector<double> &b) {
    const Spread x = spread_of(a), y = spread_of(b);
    Spread d{std::min(x.n, y.n), x.mean - y.mean, kNaN, kNaN};
    if (x.n == 0 || y.n == 0)
        return d;
    // Welch: variances of the two means, and the Welch-Satterthwaite dof.
    const double vx = x.n > 1 ? x.std * x.std / x.n : 0.0, vy = y.n > 1 ? y.std * y.std / y.n : 0.0;
    if (x.n < 2 && y.n < 2)
        return d;
    const double v = vx + vy;
    if (v == 0.0) {
        d.ci95 = 0.0; // every run of both sides gave the same value
        return d;
    }
    const double dof =
        v * v / ((x.n > 1 ? vx * vx / (x.n - 1) : 0.0) + (y.n > 1 ? vy * vy / (y.n - 1) : 0.0));
    d.std = std::sqrt(v);
    d.ci95 = student_t95(dof) * d.std;
    return d;
}

std::map<std::string, double> parse_tolerances(const std::string &text) {
    std::map<std::string, double> tolerances;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        const auto eq = item.find('=');
        if (eq == std::string::npos || eq == 0)
            throw InputError("--tolerance: '" + item + "': expected KEY=VALUE, e.g. slide_angle_deg=0.5");
        const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
        std::size_t used = 0;
        double v = kNaN;
        try {
            v = std::stod(value, &used);
        } catch (const std::exception &) {
            used = 0;
        }
        if (used != value.size() || value.empty() || !(v > 0.0) || !std::isfinite(v))
            throw InputError("--tolerance: " + key + ": '" + value +
                             "' is not a positive number (the figure's own unit)");
        tolerances[key] = v;
    }
    return tolerances;
}

double default_tolerance(const std::string &key, double reference) {
    // What an engineer would call "the same" for each figure (docs/comparison.md).
    static const std::map<std::string, double> table = {
        {"slide_angle_deg", 0.5},    {"topple_angle_deg", 1.0},     {"packing_density", 0.05},
        {"porosity", 0.02},          {"bounce_height_ratio", 0.05}, {"layer_thickness", 0.01},
        {"layer_coefficient", 0.05}, {"leave_angle_deg", 1.0}};
    const auto it = table.find(key);
    if (it != table.end())
        return it->second;
    return std::isfinite(reference) && reference != 0.0 ? 0.05 * std::abs(reference) : kNaN;
}

json compare_groups(const json &runs, const std::vector<std::string> &keys, const std::string &exact_engine) {
    struct Members {
        std::string engine;
        int spheres;
        std::vector<const json *> runs;
    };
    std::vector<Members> members;
    for (const json &run : runs) {
        const std::string engine = run.at("engine").get<std::string>();
        const int spheres = run.at("spheres").get<int>();
        auto it = std::find_if(members.begin(), members.end(),
                               [&](const Members &m) { return m.engine == engine && m.spheres == spheres; });
        if (it == members.end())
            it = members.insert(members.end(), {engine, spheres, {}});
        it->runs.push_back(&run);
    }
    auto ok = [](const json *run) { return run->value("status", "") == "ok"; };
    auto values = [&](const Members &m, const char *field, const std::string &key) {
        std::vector<double> v;
        for (const json *run : m.runs)
            if (ok(run) && run->contains(field))
                if (const double x = as_number((*run)[field].value(key, json(nullptr))); std::isfinite(x))
                    v.push_back(x);
        return v;
    };
    const Members *exact = nullptr;
    for (const Members &m : members)
        if (m.engine == exact_engine && m.spheres == 0)
            exact = &m;

    json groups = json::array();
    for (const Members &m : members) {
        json g = {{"engine", m.engine}, {"spheres", m.spheres}, {"n_runs", m.runs.size()}};
        g["label"] = group_label(g);
        int failed = 0;
        std::vector<double> cost;
        for (const json *run : m.runs) {
            if (!ok(run))
                ++failed;
            else if (const double c =
                         as_number(run->value("wall_seconds_per_simulated_second", json(nullptr)));
                     std::isfinite(c))
                cost.push_back(c);
        }
        g["n_failed"] = failed;
        const Spread c = spread_of(cost);
        g["cost"] = {{"mean", number(c.mean)}, {"ci95", number(c.ci95)}};
        json figures = json::object();
        for (const std::string &key : keys) {
            const std::vector<double> v = values(m, "figures", key);
            const Spread s = spread_of(v);
            json f = {{"n", s.n}, {"mean", number(s.mean)}, {"std", number(s.std)}, {"ci95", number(s.ci95)}};
            if (exact && &m == exact) {
                // The reference against itself: no error; its interval is the reference's own.
                f["error_vs_exact_mean"] = s.n > 0 ? json(0.0) : json(nullptr);
                f["error_vs_exact_ci95"] = number(s.ci95);
            } else {
                const Spread e =
                    exact ? difference_of(v, values(*exact, "figures", key)) : Spread{0, kNaN, kNaN, kNaN};
                f["error_vs_exact_mean"] = number(e.mean);
                f["error_vs_exact_ci95"] = number(e.ci95);
            }
            const std::vector<double> a = values(m, "error_vs_analytic", key);
            if (!a.empty()) {
                const Spread e = spread_of(a);
                f["error_vs_analytic_mean"] = number(e.mean);
                f["error_vs_analytic_ci95"] = number(e.ci95);
            }
            figures[key] = f;
        }
        g["figures"] = figures;
        groups.push_back(g);
    }
    return groups;
}

json compare_advice(const json &groups, const std::vector<std::string> &keys,
                    const std::map<std::string, double> &tolerances, const std::string &exact_engine) {
    json advice = json::object();
    for (const std::string &key : keys) {
        bool analytic = false;
        double reference = kNaN;
        for (const json &g : groups) {
            const json &f = g["figures"][key];
            analytic = analytic || f.contains("error_vs_analytic_mean");
            if (g["engine"] == exact_engine && g["spheres"] == 0)
                reference = as_number(f["mean"]);
        }
        const auto user = tolerances.find(key);
        const double tolerance = user != tolerances.end() ? user->second : default_tolerance(key, reference);
        json a = {{"tolerance", number(tolerance)},
                  {"tolerance_source", user != tolerances.end() ? "--tolerance" : "default"},
                  {"reference", analytic ? "analytic" : "exact hulls"},
                  {"choice", nullptr},
                  {"engine", nullptr},
                  {"spheres", nullptr}};
        const std::string field = analytic ? "error_vs_analytic" : "error_vs_exact";
        json verdicts = json::array();
        const json *best = nullptr;
        for (const json &g : groups) {
            const json &f = g["figures"][key];
            const double e = as_number(f.value(field + "_mean", json(nullptr)));
            const double ci = as_number(f.value(field + "_ci95", json(nullptr)));
            const bool is_reference =
                !analytic && g["engine"] == exact_engine && g["spheres"] == 0 && f["n"].get<int>() > 0;
            std::string verdict;
            if (is_reference)
                verdict = "reference";
            else if (!std::isfinite(e) || !std::isfinite(tolerance))
                verdict = "no value";
            else {
                const double half = std::isfinite(ci) ? ci : 0.0; // one run: the point decides
                verdict = std::abs(e) + half <= tolerance  ? "meets"
                          : std::abs(e) - half > tolerance ? "fails"
                                                           : "undecided";
            }
            json v = {{"label", g["label"]},      {"verdict", verdict}, {"error_mean", number(e)},
                      {"error_ci95", number(ci)}, {"n", f["n"]},        {"cost", g["cost"]["mean"]}};
            verdicts.push_back(v);
            if ((verdict == "meets" || verdict == "reference") && g["cost"]["mean"].is_number() &&
                (!best || g["cost"]["mean"].get<double>() < (*best)["cost"]["mean"].get<double>()))
                best = &g;
        }
        a["groups"] = verdicts;
        std::ostringstream reason;
        const std::string tol = "|error| <= " + fmt(tolerance) + " (the figure's unit) against the " +
                                (analytic ? "analytic value" : "exact hulls");
        if (!std::isfinite(tolerance)) {
            reason << "no tolerance: give --tolerance " << key << "=VALUE";
        } else if (best) {
            a["choice"] = (*best)["label"];
            a["engine"] = (*best)["engine"];
            a["spheres"] = (*best)["spheres"];
            reason << (*best)["label"].get<std::string>() << ": the cheapest group that meets " << tol;
            for (const json &v : verdicts)
                if (v["label"] == (*best)["label"]) {
                    if (v["verdict"] == "reference")
                        reason << " by definition (the reference)";
                    else if (v["error_ci95"].is_number())
                        reason << " over its whole 95 % interval (error "
                               << fmt(v["error_mean"].get<double>(), "%+.3g") << " +- "
                               << fmt(v["error_ci95"].get<double>()) << ")";
                    else
                        reason << " (error " << fmt(v["error_mean"].get<double>(), "%+.3g")
                               << "; one run: a point value, no interval)";
                }
            reason << ", at " << fmt((*best)["cost"]["mean"].get<double>()) << " wall s per simulated s";
        } else {
            reason << "no group meets " << tol << " with 95 % confidence";
        }
        for (const json &v : verdicts)
            if (v["verdict"] == "undecided" && v["cost"].is_number() &&
                (!best || v["cost"].get<double>() < (*best)["cost"]["mean"].get<double>()))
                reason << "; " << v["label"].get<std::string>() << " is cheaper but undecided (error "
                       << fmt(v["error_mean"].get<double>(), "%+.3g") << " +- "
                       << fmt(v["error_ci95"].get<double>()) << "): more seeds would tell";
        a["reason"] = reason.str();
        advice[key] = a;
    }
    return advice;
}

} // namespace armour
