// Statistics and advice of `armour compare`, apart from running engines.
//
// Description
//     Runs are grouped by engine and sphere count (exact hulls: 0 spheres).
//     For every headline figure a group gets the mean, the sample standard
//     deviation and the half-width of the 95 % interval of the mean (Student
//     t, n - 1 degrees of freedom) over its seeds, and the signed error of its
//     mean against the exact hulls' mean with the 95 % interval of that
//     difference (Welch: each side's spread counts, a side with one run adds
//     none). Failed runs count in n_runs and n_failed, never in the figures.
//
//     Advice, per figure, against a tolerance: a group meets it when its whole
//     95 % interval of the signed error lies within +-tolerance, fails when the
//     whole interval lies outside, and is undecided otherwise; the advice is
//     the cheapest group (wall seconds per simulated second) that meets it.
//     The error is taken against the analytic value where the analysis gives
//     one (so exact hulls are judged too), else against the exact hulls (which
//     then meet it by definition). A group of one run has no interval: its
//     point value decides, and the reason says so.
//
// Usage
//     json groups = compare_groups(runs, {"slide_angle_deg"}, "bullet");
//     json advice = compare_advice(groups, {"slide_angle_deg"},
//                                  parse_tolerances("slide_angle_deg=0.5"), "bullet");
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace armour {

// Two-sided 95 % quantile of Student's t with `dof` (> 0) degrees of
// freedom; fractional dof (Welch) are rounded down (wider, conservative).
double student_t95(double dof);

// n, mean, sample std and 95 % half-width of the mean; NaN where undefined
// (n = 0: all; n = 1: std and ci95).
struct Spread {
    int n = 0;
    double mean, std, ci95;
};
Spread spread_of(const std::vector<double> &values);

// mean(a) - mean(b) with the Welch 95 % half-width; NaN half-width when
// neither side has two values.
Spread difference_of(const std::vector<double> &a, const std::vector<double> &b);

// "key=value,key=value" (values > 0, in the figure's own unit). Throws
// InputError("--tolerance: ...") on bad text.
std::map<std::string, double> parse_tolerances(const std::string &text);

// The documented default tolerance of a headline figure; for a figure not
// in the table, 5 % of |reference| (NaN if the reference is unknown).
double default_tolerance(const std::string &key, double reference);

// `runs`: compare's run entries (engine, spheres, status, figures,
// error_vs_analytic, wall_seconds_per_simulated_second). One group per
// engine and sphere count, in the order first seen.
nlohmann::json compare_groups(const nlohmann::json &runs, const std::vector<std::string> &keys,
                              const std::string &exact_engine);

// Per headline figure: tolerance, reference, choice (a group's label or
// null), engine, spheres, reason, and every group's verdict.
nlohmann::json compare_advice(const nlohmann::json &groups, const std::vector<std::string> &keys,
                              const std::map<std::string, double> &tolerances,
                              const std::string &exact_engine);

} // namespace armour
