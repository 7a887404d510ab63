#include "sweep_command.h"

#include "cli_checks.h"
#include "executors.h"
#include "input_error.h"
#include "output_folder.h"
#include "run_command.h"
#include "scene.h"
#include "scene_setup.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>
#include <unistd.h>

namespace armour {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Everything a sweep writes at the top of DIR (the output-folder marker lists
// them, temporary copies included, so a sweep killed mid-write can resume).
const std::vector<std::string> kEntries = {
    "sweep.json",   "sweep.toml",       "cases",     "slurm",         "results.csv", "results.csv.tmp",
    "summary.json", "summary.json.tmp", "report.md", "report.md.tmp", "figures"};

std::string self_exe() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec)
        throw InputError("armour sweep: cannot find its own executable (/proc/self/exe)");
    return exe.string();
}

// The cases of this plan that a folder written by studies/keep_results.py
// holds done, with the same scene: a sweep resumed on another machine, whose
// own folder lost them. Only cases not done in DIR already.
std::set<std::size_t> kept_cases(const fs::path &kept, const SweepPlan &plan, const SweepTable &before) {
    if (!fs::is_directory(kept / "cases"))
        throw InputError("--kept " + kept.string() +
                         ": holds no cases/ (not a folder written by studies/keep_results.py)");
    // A kept folder reads as a sweep's: done means the same scene and a summary.
    const SweepTable kept_table = read_sweep_table(kept, plan);
    std::set<std::size_t> found;
    for (std::size_t i = 0; i < plan.cases.size(); ++i)
        if (before.rows[i].status != "done" && kept_table.rows[i].status == "done")
            found.insert(i);
    return found;
}

// The plan indices of the case ids --cases names; an id that is not a case
// of this sweep is refused, with the sweep's ids (or the first of them).
std::set<std::size_t> selected_cases(const SweepPlan &plan, const std::vector<std::string> &ids) {
    std::set<std::size_t> selected;
    for (const std::string &id : ids) {
        std::size_t i = 0;
        while (i < plan.cases.size() && plan.cases[i].id != id)
            ++i;
        if (i == plan.cases.size()) {
            std::string known;
            for (std::size_t k = 0; k < plan.cases.size() && k < 8; ++k)
                known += (k ? ", " : "") + plan.cases[k].id;
            if (plan.cases.size() > 8)
                known += ", ... (" + std::to_string(plan.cases.size()) + " in all; --dry-run lists them)";
            throw InputError("--cases: '" + id + "' is not a case of " + plan.spec.file +
                             " (its cases: " + known + ")");
        }
        selected.insert(i);
    }
    return selected;
}

// Copies a kept case (its run's small results, then its record) into DIR.
void copy_kept_case(const fs::path &from, const fs::path &to) {
    fs::create_directories(to / "run");
    for (const auto &entry : fs::directory_iterator(from / "run"))
        if (entry.is_regular_file())
            fs::copy_file(entry.path(), to / "run" / entry.path().filename(),
                          fs::copy_options::overwrite_existing);
    fs::copy_file(from / "case.json", to / "case.json", fs::copy_options::overwrite_existing);
}

// [set] and --set, as KEY=VALUE: what every case shares (sweep.json's `set`).
std::vector<std::string> set_overrides(const SweepSpec &spec) {
    std::vector<std::string> out;
    for (const auto &[key, value] : spec.fixed)
        out.push_back(key + "=" + value);
    return out;
}

json plan_json(const SweepContext &ctx) {
    json cases = json::array();
    for (const SweepCase &c : ctx.plan.cases)
        cases.push_back({{"case", c.id},
                         {"values", c.column_values},
                         {"seed", c.seed ? json(*c.seed) : json(nullptr)},
                         {"scene_hash", c.scene_hash}});
    return {{"sweep_file", fs::absolute(ctx.plan.spec.file).lexically_normal().string()},
            {"scene", ctx.plan.spec.scene},
            {"analysis", ctx.plan.analysis},
            {"executor", ctx.executor},
            {"varied", ctx.plan.columns},
            {"set", set_overrides(ctx.plan.spec)},
            {"seeds", ctx.plan.spec.seeds},
            {"np", ctx.plan.spec.np},
            {"timeout", ctx.plan.spec.timeout},
            {"armour", ctx.armour_exe},
            {"settle_only", ctx.settle_only},
            {"cases", cases}};
}

// The plan as an earlier sweep wrote it into DIR/sweep.json (for --collect).
SweepContext read_context(const fs::path &out) {
    std::ifstream in(out / "sweep.json");
    const json j = in ? json::parse(in, nullptr, false) : json();
    if (!j.is_object() || !j.contains("cases"))
        throw InputError("--collect " + out.string() + ": not a sweep's folder (no readable sweep.json)");
    SweepContext ctx;
    ctx.out = out;
    ctx.executor = j.value("executor", "local");
    ctx.armour_exe = self_exe();
    ctx.plan.spec.file = j.value("sweep_file", "");
    ctx.plan.spec.scene = j.value("scene", "");
    ctx.plan.spec.seeds = j.value("seeds", std::vector<std::int64_t>{});
    ctx.plan.analysis = j.value("analysis", "");
    ctx.plan.columns = j.value("varied", std::vector<std::string>{});
    ctx.settle_only = j.value("settle_only", false);
    for (const auto &c : j["cases"]) {
        SweepCase sc;
        sc.id = c.value("case", "");
        sc.column_values = c.value("values", std::vector<std::string>{});
        if (c.contains("seed") && c["seed"].is_number_integer())
            sc.seed = c["seed"].get<std::int64_t>();
        sc.scene_hash = c.value("scene_hash", "");
        ctx.plan.cases.push_back(sc);
    }
    return ctx;
}

// The --set overrides appended to the sweep file's [set]: they apply to
// every case. A key the sweep varies is refused: each case sets it again
// after [set], so --set would change nothing while seeming to.
void add_command_line_sets(SweepSpec &spec, const std::vector<std::string> &overrides) {
    std::set<std::string> varied(spec.seed_keys.begin(), spec.seed_keys.end());
    for (const auto &[key, values] : spec.vary)
        varied.insert(key);
    for (const auto &c : spec.cases)
        for (const auto &kv : c)
            varied.insert(kv.first);
    const bool drop_seeds = !spec.seeds.empty() && spec.seed_keys.empty(); // every [[drop]]'s seed
    for (const std::string &o : overrides) {
        const std::size_t eq = o.find('=');
        if (eq == std::string::npos || eq == 0)
            throw InputError("--set: '" + o + "': expected KEY=VALUE, e.g. --set run.duration=0.5");
        const std::string key = o.substr(0, eq);
        const bool seed = drop_seeds && key.rfind("drop.", 0) == 0 && key.size() > 5 &&
                          key.compare(key.size() - 5, 5, ".seed") == 0;
        if (varied.count(key) || seed)
            throw InputError("--set: key '" + key + "': the sweep file " + spec.file +
                             " varies it ([vary], [[case]] or seeds); --set sets what every case shares");
        spec.fixed.emplace_back(key, o.substr(eq + 1));
    }
}

// `selected`: the cases --cases names (plan indices), whose completion decides
// the exit status; empty: every case.
int finish(const SweepContext &ctx, const std::set<std::string> &skipped,
           const std::set<std::size_t> &selected = {}) {
    const SweepTable table = refresh_tables(ctx, skipped);
    write_report(ctx.out);
    const int failed = table.count("failed");
    int selected_done = 0, others_left = 0;
    for (std::size_t i = 0; i < table.rows.size(); ++i) {
        const bool done = table.rows[i].status == "done";
        if (selected.count(i))
            selected_done += done;
        else
            others_left += !done;
    }
    std::printf(
        "sweep: %d of %zu cases done (%zu skipped as done before), %d failed, %d not finished -> %s\n",
        table.count("done"), table.rows.size(), skipped.size(), failed,
        table.count("pending") + table.count("running"), ctx.out.c_str());
    if (failed > 0)
        std::fprintf(stderr,
                     "sweep: %d case(s) failed (results.csv says which, cases/<id>/log.txt why); run the "
                     "same command with --retry-failed to run them again\n",
                     failed);
    if (!selected.empty()) {
        std::printf("sweep: %d of the %zu cases of --cases done", selected_done, selected.size());
        if (others_left > 0)
            std::printf("; %d other case(s) left: the same command without --cases runs them", others_left);
        std::printf("\n");
        return selected_done == static_cast<int>(selected.size()) ? 0 : 1;
    }
    return failed > 0 || table.count("done") != static_cast<int>(table.rows.size()) ? 1 : 0;
}

int collect(const SweepRequest &r) {
    SweepContext ctx = read_context(fs::absolute(r.collect).lexically_normal());
    if (ctx.executor == "slurm" && fs::exists(ctx.out / "slurm" / "job.json"))
        follow_slurm(ctx, {});
    return finish(ctx, {});
}

// What a sweep does with each case of its plan: run it, or skip it and why.
struct SweepActions {
    std::vector<std::size_t> to_run;
    std::set<std::string> skipped; // done before (here or in --kept)
    std::string listing;           // a line per case, for --dry-run
};

// `selected`: the cases --cases names (plan indices); empty: every case.
SweepActions decide_actions(const SweepPlan &plan, const SweepTable &before,
                            const std::set<std::size_t> &from_kept, const std::set<std::size_t> &selected,
                            bool retry_failed) {
    SweepActions a;
    std::ostringstream listing;
    for (std::size_t i = 0; i < plan.cases.size(); ++i) {
        const SweepCase &c = plan.cases[i];
        const std::string &status = before.rows[i].status;
        std::string action = "run";
        if (status == "done") {
            action = "skip: done";
            a.skipped.insert(c.id);
        } else if (from_kept.count(i)) {
            action = "skip: done in --kept";
            a.skipped.insert(c.id);
        } else if (status == "running") {
            action = "skip: running in another sweep";
        } else if (status == "failed" && !retry_failed) {
            action = "skip: failed before (--retry-failed runs it)";
        } else if (!selected.empty() && !selected.count(i)) {
            action = "skip: not in --cases";
        }
        if (action == "run")
            a.to_run.push_back(i);
        listing << "  " << c.id << "  scene " << c.scene_hash << "  " << action << "\n";
    }
    a.listing = listing.str();
    return a;
}

// Each case to run as `armour run` checks it before it writes (placement,
// engine step, fluid case, waves): beyond the scene reader, a case refused
// at its start on a cluster costs a queue, and a local sweep's hours.
void check_cases_run(const SweepPlan &plan, const std::vector<std::size_t> &to_run, bool settle_only) {
    const bool terminal = ::isatty(STDERR_FILENO) != 0;
    for (std::size_t k = 0; k < to_run.size(); ++k) {
        const SweepCase &c = plan.cases[to_run[k]];
        if (terminal)
            std::fprintf(stderr, "\rsweep: checking case %zu / %zu (%s)\033[K", k + 1, to_run.size(),
                         c.id.c_str());
        try {
            const Scene scene = load_scene(plan.spec.scene, c.overrides);
            if (const std::string why = settle_only ? settle_only_refusal(scene) : ""; !why.empty())
                throw InputError(why);
            check_scene_runs(scene, default_cache_dir(), plan.spec.np);
        } catch (const InputError &e) {
            if (terminal)
                std::fprintf(stderr, "\r\033[K");
            throw InputError(plan.spec.file + ": case " + c.id + ": " + e.what());
        }
    }
    if (terminal && !to_run.empty())
        std::fprintf(stderr, "\r\033[K");
}

// What the command line added to the sweep file (--seeds, --set), as TOML
// comments for its copy in DIR/sweep.toml: a kept copy then says by itself
// how its cases were made (empty when the file was run as written).
std::string command_line_note(const SweepRequest &r) {
    if (r.seeds.empty() && r.overrides.empty() && !r.settle_only && r.np == 0)
        return "";
    std::string line = "# armour sweep ran this file with";
    if (r.settle_only)
        line += " --settle-only";
    if (!r.seeds.empty()) {
        line += " --seeds ";
        for (std::size_t i = 0; i < r.seeds.size(); ++i)
            line += (i ? "," : "") + std::to_string(r.seeds[i]);
    }
    if (r.np > 0)
        line += " --np " + std::to_string(r.np);
    for (const std::string &kv : r.overrides)
        line += " --set '" + kv + "'";
    return "\n" + line + "\n# (" + (r.settle_only ? "--settle-only: each case's settle alone; " : "") +
           "--seeds in place of the file's seeds; --np in place of its [run] np; --set after its [set], in "
           "every case)\n";
}

// The sweep's own files in DIR (its marker first), the sweep file as run
// (with `note`, command_line_note) and each case to run's scene and plan.
void write_sweep_folder(const SweepContext &ctx, const std::string &sweep_file, const std::string &note,
                        const std::vector<std::size_t> &to_run) {
    fs::create_directories(ctx.out / "cases");
    std::string marker = "armour sweep\n";
    for (const auto &e : kEntries)
        marker += e + "\n";
    write_text_file(ctx.out / ".armour-output", marker);
    write_text_file(ctx.out / "sweep.json", plan_json(ctx).dump(2) + "\n");
    {
        std::ifstream in(sweep_file);
        std::stringstream text;
        text << in.rdbuf();
        std::string copy = text.str();
        if (!note.empty() && !copy.empty() && copy.back() != '\n')
            copy += '\n';
        write_text_file(ctx.out / "sweep.toml", copy + note);
    }
    for (const std::size_t i : to_run) {
        const SweepCase &c = ctx.plan.cases[i];
        const fs::path dir = case_dir(ctx.out, c);
        fs::create_directories(dir);
        write_text_file(dir / "scene.toml", c.scene_text);
        json values = json::object();
        for (std::size_t k = 0; k < ctx.plan.columns.size(); ++k)
            values[ctx.plan.columns[k]] = c.column_values[k];
        write_text_file(dir / "plan.json", json{{"case", c.id},
                                                {"values", values},
                                                {"seed", c.seed ? json(*c.seed) : json(nullptr)},
                                                {"overrides", c.overrides},
                                                {"scene_hash", c.scene_hash},
                                                {"earlier_scene_hash", c.earlier_scene_hash},
                                                {"resume_hash", c.resume_hash},
                                                {"duration", c.duration},
                                                {"np", ctx.plan.spec.np},
                                                {"settle_only", ctx.settle_only},
                                                {"timeout", ctx.plan.spec.timeout},
                                                {"si_units", {{"timeout", "s"}, {"duration", "s"}}}}
                                                   .dump(2) +
                                               "\n");
    }
}

} // namespace

CLI::App *add_sweep_command(CLI::App &app, SweepRequest &r) {
    CLI::App *cmd = app.add_subcommand(
        "sweep",
        "Run a scene over a grid of key values and seeds (sweep file: TOML, SI units, docs/sweeps.md), each "
        "case its "
        "own "
        "`armour run` in DIR/cases/<id>, locally or as a Slurm job array; writes results.csv, summary.json "
        "and report.md to --out. The same command again resumes.");
    cmd->add_option("sweep", r.sweep_file, "Sweep file (.toml)");
    cmd->add_option("--out", r.out,
                    "Output folder: new, empty, or an earlier result of this sweep (resumed)");
    cmd->add_option("--set", r.overrides,
                    "Override a scene key for every case, after the sweep file's [set], TOML syntax: "
                    "--set run.duration=0.5 (not a key the sweep varies)");
    cmd->add_option("--executor", r.executor, "local (processes on this machine) or slurm (one job array)")
        ->capture_default_str();
    cmd->add_option("--jobs", r.jobs,
                    "local: cases run at once, >= 1 (default: cores / run.np); Slurm: [slurm] max_concurrent")
        ->check(integer_at_least(1));
    cmd->add_flag("--dry-run", r.dry_run, "Check every case and list what would run; write nothing");
    cmd->add_flag("--retry-failed", r.retry_failed, "Run failed cases again (finished ones are always kept)");
    cmd->add_flag("--no-wait", r.no_wait,
                  "slurm: submit and return; `armour sweep --collect DIR` gathers later");
    cmd->add_option("--kept", r.kept,
                    "Folder of results kept by studies/keep_results.py: its finished cases with the "
                    "same scene are copied into --out and count as done (resume on another machine)");
    cmd->add_option("--cases", r.cases,
                    "Run only these cases now (ids as in DIR/cases, comma-separated: "
                    "--cases density-1685_seed-1,density-1685_seed-3); the others stay for a later sweep "
                    "into the same --out")
        ->delimiter(',')
        ->allow_extra_args(false);
    cmd->add_option("--seeds", r.seeds,
                    "Realisations in place of the sweep file's seeds (integers >= 0, comma-separated: "
                    "--seeds 1,2,3,4 adds a fourth to seeds = [1, 2, 3]; the cases of 1-3 stay done)")
        ->delimiter(',')
        ->allow_extra_args(false) // one comma-separated word: the sweep file after it stays the sweep file
        ->check(integer_at_least(0));
    cmd->add_option("--np", r.np,
                    "MPI ranks of each case in place of the sweep file's [run] np (coupled scenes; "
                    ">= 1); what counts as done does not change with it")
        ->check(integer_at_least(1));
    cmd->add_flag("--settle-only", r.settle_only,
                  "Run each case's settle alone (`armour run --settle-only`: the layer its waves would "
                  "meet, no fluid case; scenes with fluid.settle_time > 0 s): results.csv gains the "
                  "layers' figures (settled_layer.porosity, .packing_density in units per Dn^2, "
                  ".units_at_foot, ...); --out then holds settles only");
    cmd->add_option("--collect", r.collect,
                    "Gather the results of a sweep submitted earlier into DIR (waits for "
                    "its Slurm job to end)");
    cmd->add_option("--run-case", r.run_case, "Internal: run one case folder")->group("");
    return cmd;
}

namespace {

// The options of a sweep (not --collect, not --run-case) against each other.
void check_sweep_options(const SweepRequest &r) {
    if (r.sweep_file.empty())
        throw InputError("sweep: a sweep file is required (or --collect DIR)");
    if (r.out.empty())
        throw InputError("--out: an output folder is required");
    if (r.executor != "local" && r.executor != "slurm")
        throw InputError("--executor: must be local or slurm (got '" + r.executor + "')");
    if (r.jobs < 0) // 0: not given (the command line refuses --jobs 0 itself)
        throw InputError("--jobs: must be >= 1 (got " + std::to_string(r.jobs) + ")");
    for (std::size_t i = 0; i < r.seeds.size(); ++i)
        if (std::count(r.seeds.begin(), r.seeds.begin() + i, r.seeds[i]))
            throw InputError("--seeds: seed " + std::to_string(r.seeds[i]) + " given twice");
    if (r.no_wait && r.executor != "slurm")
        throw InputError("--no-wait: only with --executor slurm");
    if (r.settle_only && !r.kept.empty())
        throw InputError("--kept: not with --settle-only (a kept folder holds runs with waves; a settle "
                         "takes a minute: run it again)");
    if (r.settle_only && r.np > 0)
        throw InputError("--np: not with --settle-only (a settle runs on one rank)");
    if (r.jobs > 0 && r.executor == "slurm") // else it would be ignored without a word
        throw InputError(
            "--jobs: only with --executor local (a Slurm array runs [slurm] max_concurrent cases "
            "at once)");
}

// A Slurm sweep needs Slurm, and an --out whose array is not still queued
// or running (a second array would run the same cases).
void check_slurm_out(const fs::path &out, bool dry_run) {
    check_slurm_reachable();
    if (dry_run || !fs::exists(out / "sweep.json"))
        return;
    const std::string job = slurm_job_in_queue(out);
    if (!job.empty())
        throw InputError("--out " + out.string() + ": its Slurm job " + job +
                         " is still queued or running; wait for it or `armour sweep --collect " +
                         out.string() + "`");
}

// A sweep's --out holds settles alone or runs with waves, never both: a
// settled case would otherwise count as done for a sweep with waves (the
// same scene), and the reverse.
void check_same_kind(const fs::path &out, bool settle_only) {
    std::ifstream in(out / "sweep.json");
    const json j = in ? json::parse(in, nullptr, false) : json();
    if (!j.is_object() || j.value("settle_only", false) == settle_only)
        return;
    throw InputError("--out " + out.string() +
                     (settle_only ? ": holds a sweep with waves; --settle-only needs a folder of its own"
                                  : ": holds a sweep's settles alone (--settle-only); a sweep with waves "
                                    "needs a folder of its own (or add --settle-only to go on with it)"));
}

} // namespace

int run_sweep(const SweepRequest &r) {
    if (!r.run_case.empty()) {
        const int status = run_case(fs::absolute(r.run_case).lexically_normal(), self_exe());
        if (status == kCaseLocked)
            std::fprintf(stderr, "armour: %s: the case is running in another process\n", r.run_case.c_str());
        return status;
    }
    if (!r.collect.empty()) {
        if (!r.sweep_file.empty() || !r.out.empty() || !r.overrides.empty() || !r.kept.empty() ||
            !r.cases.empty() || !r.seeds.empty() || r.np != 0 || r.settle_only)
            throw InputError("--collect: takes the sweep's folder alone (no SWEEP.toml, no --out, no --set, "
                             "no --kept, no --cases, no --seeds, no --np, no --settle-only)");
        return collect(r);
    }
    check_sweep_options(r);

    SweepContext ctx;
    SweepSpec spec = read_sweep_file(r.sweep_file);
    if (!r.seeds.empty()) // before --set: a seed key the seeds vary is refused there
        spec.seeds = r.seeds;
    if (r.np > 0) {
        spec.np = r.np;
        spec.np_option = "--np";
    }
    add_command_line_sets(spec, r.overrides);
    ctx.plan = plan_sweep(spec); // every case checked before anything runs
    const std::set<std::size_t> selected = selected_cases(ctx.plan, r.cases);
    ctx.out = fs::absolute(r.out).lexically_normal();
    ctx.executor = r.executor;
    ctx.armour_exe = self_exe();
    ctx.settle_only = r.settle_only;
    if (r.settle_only) // a settle runs no analysis: the tables head with its layer's figures
        ctx.plan.analysis = kSettleOnly;
    const OutputFolder folder(ctx.out, "armour sweep",
                              OutputFolder::Mode::streaming); // refuses foreign folders
    if (r.executor == "slurm")
        check_slurm_out(ctx.out, r.dry_run);
    check_same_kind(ctx.out, r.settle_only);

    const SweepTable before = read_sweep_table(ctx.out, ctx.plan);
    const std::set<std::size_t> from_kept =
        r.kept.empty() ? std::set<std::size_t>{} : kept_cases(fs::path(r.kept), ctx.plan, before);
    const SweepActions actions = decide_actions(ctx.plan, before, from_kept, selected, r.retry_failed);
    const std::vector<std::size_t> &to_run = actions.to_run;
    const std::set<std::string> &skipped = actions.skipped;
    check_cases_run(ctx.plan, to_run, r.settle_only);
    if (r.dry_run) {
        std::printf("sweep: %zu cases of %s, all checked; %zu would run:\n%s", ctx.plan.cases.size(),
                    ctx.plan.spec.scene.c_str(), to_run.size(), actions.listing.c_str());
        if (r.executor == "slurm" && !to_run.empty())
            std::printf("--- %s ---\n%s", (ctx.out / "slurm" / "array.sbatch").c_str(),
                        slurm_script(ctx, to_run.size()).c_str());
        return 0;
    }

    write_sweep_folder(ctx, r.sweep_file, command_line_note(r), to_run);
    for (const std::size_t i : from_kept) // the record last: a copy cut short stays pending
        copy_kept_case(fs::path(r.kept) / "cases" / ctx.plan.cases[i].id,
                       case_dir(ctx.out, ctx.plan.cases[i]));
    if (!r.kept.empty())
        std::fprintf(stderr, "sweep: %zu finished cases taken from --kept %s\n", from_kept.size(),
                     r.kept.c_str());
    std::fprintf(stderr, "sweep: %zu cases, %zu to run, %zu done before -> %s\n", ctx.plan.cases.size(),
                 to_run.size(), skipped.size(), ctx.out.c_str());
    refresh_tables(ctx, skipped);
    if (to_run.empty())
        return finish(ctx, skipped, selected);

    if (r.executor == "local") {
        const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
        const int jobs = r.jobs > 0 ? r.jobs : std::max(1, cores / ranks_per_case(ctx));
        run_local(ctx, to_run, jobs, skipped);
        return finish(ctx, skipped, selected);
    }
    submit_slurm(ctx, to_run);
    if (r.no_wait) {
        std::printf(
            "sweep: submitted; `armour sweep --collect %s` gathers the results when the job has ended\n",
            ctx.out.c_str());
        return 0;
    }
    follow_slurm(ctx, skipped);
    return finish(ctx, skipped, selected);
}

} // namespace armour
