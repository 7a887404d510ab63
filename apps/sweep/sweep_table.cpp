#include "sweep_table.h"

#include "analysis.h"
#include "output_folder.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace armour {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A case's run/summary.json (an object; empty where it cannot be read).
json summary_of(const fs::path &summary_file) {
    std::ifstream in(summary_file);
    const json summary = json::parse(in, nullptr, false);
    return summary.is_object() ? summary : json::object();
}

// The numbers of a summary (top level only: the headline figures live there).
json numbers_of(const json &summary) {
    json figures = json::object();
    for (const auto &[key, value] : summary.items())
        if ((value.is_number() || value.is_null()) && key != "wall_seconds")
            figures[key] = value;
        else if (key == "wall_seconds")
            figures["run_wall_seconds"] = value;
    // A run that measures its waves keeps them in an object (N, s_om, the
    // incident height): the stability chart needs them as numbers.
    // and a settle's layer (armour run --settle-only) its packing, porosity, k_t.
    for (const char *object : {"waves", "settled_layer"})
        if (summary.contains(object) && summary[object].is_object())
            for (const auto &[key, value] : summary[object].items())
                if (value.is_number())
                    figures[std::string(object) + "." + key] = value;
    return figures;
}

// Which maths the case's process rounded with (checkpoints.h): a sweep run on
// two machines holds realisations of two arithmetics.
std::string arithmetic_of(const json &summary) {
    return summary.contains("arithmetic") && summary["arithmetic"].is_string()
               ? summary["arithmetic"].get<std::string>()
               : std::string();
}

std::string csv_cell(const std::string &text) {
    if (text.find_first_of(",\"\n") == std::string::npos)
        return text;
    std::string out = "\"";
    for (const char ch : text)
        out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return out + "\"";
}

std::string number_cell(const json &v) {
    if (v.is_null())
        return "";
    if (v.is_number_integer())
        return std::to_string(v.get<long long>());
    std::ostringstream s;
    s.precision(10);
    s << v.get<double>();
    return s.str();
}

// A value as JSON: numbers and booleans as such, anything else as text.
json typed(const std::string &text) {
    const json v = json::parse(text, nullptr, false);
    return v.is_number() || v.is_boolean() ? v : json(text);
}

// Headline figures (and what physics predicts for them) first, then every
// other number, in the order the cases' summaries name them.
std::vector<std::string> figure_columns(const SweepPlan &plan, const SweepTable &table,
                                        std::vector<std::string> &headline, json &predicted) {
    std::vector<std::string> columns;
    auto add = [&](const std::string &k) {
        if (std::find(columns.begin(), columns.end(), k) == columns.end())
            columns.push_back(k);
    };
    try {
        const AnalysisStyle &style = analysis_style(plan.analysis);
        headline = style.headline_keys;
        for (const auto &k : style.headline_keys)
            add(k);
        for (const auto &[measured, expected] : style.analytic_keys) {
            add(expected);
            predicted[measured] = expected;
        }
    } catch (const InputError &) {
    }
    // Damage sweeps: the stability number and damage are headline figures
    // whichever analysis reports them.
    for (const char *k : {"Ns", "N_od", "damage_S"})
        for (const auto &row : table.rows)
            if (row.figures.contains(k) && std::find(headline.begin(), headline.end(), k) == headline.end()) {
                headline.push_back(k);
                add(k);
                break;
            }
    // Settle-only sweeps (armour sweep --settle-only): the layers' figures.
    if (plan.analysis == kSettleOnly)
        for (const char *k : {"settled_layer.porosity", "settled_layer.packing_density",
                              "settled_layer.layer_coefficient", "settled_layer.units_at_foot"}) {
            headline.push_back(k);
            add(k);
        }
    for (const auto &row : table.rows)
        for (const auto &[k, v] : row.figures.items())
            add(k);
    return columns;
}

} // namespace

int SweepTable::count(const std::string &status) const {
    int n = 0;
    for (const auto &r : rows)
        n += r.status == status;
    return n;
}

fs::path case_dir(const fs::path &out, const SweepCase &c) {
    return out / "cases" / c.id;
}

SweepTable read_sweep_table(const fs::path &out, const SweepPlan &plan) {
    SweepTable table;
    for (const SweepCase &c : plan.cases) {
        const fs::path dir = case_dir(out, c);
        CaseRow row;
        row.record = read_case_record(dir);
        row.record.id = c.id;
        row.status = row.record.status;
        const fs::path summary = dir / "run" / "summary.json";
        if (row.status == "done" && (!same_scene(row.record.scene_hash, c) || !fs::is_regular_file(summary)))
            row.status = "pending"; // another scene now, or its result was removed
        if (row.status == "running" && !case_is_locked(dir))
            row.status = "pending"; // its sweep was killed
        if (row.status == "done") {
            const json own = summary_of(summary);
            row.figures = numbers_of(own);
            row.arithmetic = arithmetic_of(own);
        } else {
            row.figures = json::object();
        }
        table.rows.push_back(std::move(row));
    }
    return table;
}

void write_sweep_tables(const fs::path &out, const SweepPlan &plan, const SweepTable &table,
                        const std::string &executor) {
    std::vector<std::string> headline;
    json predicted = json::object();
    const std::vector<std::string> figures = figure_columns(plan, table, headline, predicted);

    std::ostringstream csv;
    csv << "case";
    for (const auto &k : plan.columns)
        csv << ',' << csv_cell(k);
    csv << ",seed,status,attempts,wall_seconds,host,arithmetic";
    for (const auto &k : figures)
        csv << ',' << csv_cell(k);
    csv << '\n';
    json cases = json::array();
    for (std::size_t i = 0; i < plan.cases.size(); ++i) {
        const SweepCase &c = plan.cases[i];
        const CaseRow &row = table.rows[i];
        csv << csv_cell(c.id);
        json values = json::object();
        for (std::size_t k = 0; k < plan.columns.size(); ++k) {
            csv << ',' << csv_cell(c.column_values[k]);
            values[plan.columns[k]] = typed(c.column_values[k]);
        }
        csv << ',' << (c.seed ? std::to_string(*c.seed) : "") << ',' << row.status << ','
            << row.record.attempts << ',' << number_cell(row.record.wall_seconds) << ','
            << csv_cell(row.record.host) << ',' << row.arithmetic;
        for (const auto &k : figures)
            csv << ',' << (row.figures.contains(k) ? number_cell(row.figures[k]) : "");
        csv << '\n';
        json entry = {{"case", c.id},
                      {"folder", "cases/" + c.id},
                      {"values", values},
                      {"seed", c.seed ? json(*c.seed) : json(nullptr)},
                      {"status", row.status},
                      {"attempts", row.record.attempts},
                      {"wall_seconds", row.record.wall_seconds},
                      {"scene_hash", c.scene_hash},
                      {"host", row.record.host},
                      {"arithmetic", row.arithmetic},
                      {"figures", row.figures}};
        if (row.status == "failed") {
            entry["reason"] = row.record.reason;
            if (!row.record.slurm_state.empty())
                entry["slurm_state"] = row.record.slurm_state;
        }
        if (!row.record.slurm_job.empty())
            entry["slurm_job"] = row.record.slurm_job;
        cases.push_back(entry);
    }
    const json summary = {
        {"command", "sweep"},
        {"sweep_file", fs::absolute(plan.spec.file).lexically_normal().string()},
        {"scene", plan.spec.scene},
        {"analysis", plan.analysis},
        {"executor", executor},
        {"varied", plan.columns},
        {"seeds", plan.spec.seeds},
        {"headline", headline},
        {"predicted", predicted},
        {"figures", figures},
        {"total", plan.cases.size()},
        {"done", table.count("done")},
        {"failed", table.count("failed")},
        {"running", table.count("running")},
        {"pending", table.count("pending")},
        {"skipped", table.skipped.size()},
        {"cases", cases},
        {"files",
         {{"table", "results.csv"}, {"report", "report.md"}, {"cases", "cases/<case>/run/summary.json"}}},
        {"si_units",
         {{"wall_seconds", "s"}, {"figures", "as in each case's summary.json (docs/analysis.md)"}}}};
    write_text_file(out / "results.csv", csv.str());
    write_text_file(out / "summary.json", summary.dump(2) + "\n");
}

std::string progress_line(const SweepTable &table, double eta) {
    std::ostringstream s;
    s << "sweep: " << table.count("done") << "/" << table.rows.size() << " done, " << table.count("running")
      << " running, " << table.count("failed") << " failed, " << table.count("pending") << " pending";
    if (eta >= 0.0)
        s << ", ETA " << std::lround(eta) << " s";
    return s.str();
}

} // namespace armour
