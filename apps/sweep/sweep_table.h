// The sweep's tables: DIR/results.csv and DIR/summary.json, rebuilt from the
// case folders and written atomically whenever a case finishes.
//
// Description
//     results.csv has one row per case: case, the varied keys as named in
//     [vary] (their values in the case's resolved scene), seed, status
//     (done/failed/running/pending), attempts, wall_seconds (s, the case's
//     process), host (where it last ran), arithmetic (its summary's fingerprint
//     of the C library's maths: two realisations whose fingerprints differ were
//     rounded otherwise, docs/checkpoints.md), then every number of the case's
//     summary.json, the analysis's headline figures first. summary.json has
//     the same per case (plus the scene hash and why a case failed) and the
//     counts. A case counts as done only when its run/summary.json exists and
//     its scene hash is the plan's; one recorded as running whose lock is free
//     was lost (its sweep was killed) and counts as pending.
//
// Usage
//     SweepTable table = read_sweep_table(out, plan);
//     write_sweep_tables(out, plan, table, "local");
//     std::fprintf(stderr, "%s\n", progress_line(table, eta).c_str());
#pragma once

#include "case_runner.h"
#include "sweep_cases.h"

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

namespace armour {

struct CaseRow {
    CaseRecord record;
    std::string status;     // as the table shows it
    nlohmann::json figures; // the numbers of run/summary.json (object)
    std::string arithmetic; // run/summary.json's "arithmetic" ("" before it was recorded)
};

struct SweepTable {
    std::vector<CaseRow> rows;     // in plan order
    std::set<std::string> skipped; // done before this invocation, not run again
    int count(const std::string &status) const;
};

std::filesystem::path case_dir(const std::filesystem::path &out, const SweepCase &c);

SweepTable read_sweep_table(const std::filesystem::path &out, const SweepPlan &plan);

void write_sweep_tables(const std::filesystem::path &out, const SweepPlan &plan, const SweepTable &table,
                        const std::string &executor);

// "sweep: 3/8 done, 2 running, 1 failed, 2 pending, ETA 45 s"; eta < 0: unknown.
std::string progress_line(const SweepTable &table, double eta);

} // namespace armour
