// The Slurm executor: one job array, followed with squeue, ended with sacct or scontrol.
#include "executors.h"

#include "input_error.h"
#include "output_folder.h"

#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace armour {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string quoted(const std::string &s) {
    std::string out = "'";
    for (const char ch : s)
        out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return out + "'";
}

// Runs a shell command; returns its exit status and fills `output` (stdout and stderr).
int shell(const std::string &command, std::string &output) {
    output.clear();
    std::FILE *pipe = ::popen((command + " 2>&1").c_str(), "r");
    if (!pipe)
        return -1;
    std::array<char, 4096> buffer{};
    std::size_t n = 0;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
        output.append(buffer.data(), n);
    const int status = ::pclose(pipe);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string first_line(const std::string &text) {
    const std::string line = text.substr(0, text.find('\n'));
    return line.empty() ? "(no output)" : line;
}

json read_job(const fs::path &out) {
    std::ifstream in(out / "slurm" / "job.json");
    return in ? json::parse(in, nullptr, false) : json();
}

// The final state of each array task: "TASK" -> "STATE" (COMPLETED, FAILED, TIMEOUT...).
std::map<std::string, std::string> task_states(const std::string &job) {
    std::map<std::string, std::string> states;
    std::string text;
    if (shell("sacct -n -P -X -j " + job + " -o JobID,State", text) == 0) {
        std::istringstream in(text);
        for (std::string line; std::getline(in, line);) {
            const auto bar = line.find('|'), under = line.find('_');
            if (bar != std::string::npos && under != std::string::npos && under < bar)
                states[line.substr(under + 1, bar - under - 1)] =
                    line.substr(bar + 1, line.find(' ', bar) - bar - 1);
        }
        if (!states.empty())
            return states;
    }
    // No accounting (slurmdbd) here: the controller still knows recently ended jobs.
    if (shell("scontrol -o show job " + job, text) == 0) {
        std::istringstream in(text);
        for (std::string line; std::getline(in, line);) {
            auto field = [&](const std::string &name) {
                const auto at = line.find(" " + name + "=");
                if (at == std::string::npos)
                    return std::string();
                const auto begin = at + name.size() + 2;
                return line.substr(begin, line.find(' ', begin) - begin);
            };
            if (!field("ArrayTaskId").empty())
                states[field("ArrayTaskId")] = field("JobState");
        }
    }
    return states;
}

} // namespace

void check_slurm_reachable() {
    std::string text;
    if (shell("command -v sbatch", text) != 0)
        throw InputError("--executor: slurm: sbatch not found; run on a cluster's login node (or start "
                         "scripts/slurm-local.sh)");
    // A missing configuration makes scontrol retry for a minute: 15 s is enough to answer.
    if (shell("timeout 15 scontrol ping", text) != 0 || text.find("UP") == std::string::npos)
        throw InputError(
            "--executor: slurm: no Slurm controller reachable (scontrol ping: " + first_line(text) + ")");
}

std::string slurm_script(const SweepContext &ctx, std::size_t tasks) {
    const SweepSlurm &s = ctx.plan.spec.slurm;
    const fs::path slurm = ctx.out / "slurm";
    std::ostringstream o;
    o << "#!/bin/bash\n"
      << "# armour sweep " << ctx.plan.spec.file << ": one array task per case.\n"
      << "#SBATCH --job-name=armour-sweep\n"
      << "#SBATCH --array=0-" << tasks - 1;
    if (s.max_concurrent > 0)
        o << "%" << s.max_concurrent;
    o << "\n#SBATCH --output=" << (slurm / "task-%a.out").string() << "\n"
      << "#SBATCH --ntasks=" << ranks_per_case(ctx) << "\n"
      << "#SBATCH --cpus-per-task=" << std::max(1, s.cpus_per_case) << "\n";
    if (!s.partition.empty())
        o << "#SBATCH --partition=" << s.partition << "\n";
    if (!s.time.empty())
        o << "#SBATCH --time=" << s.time << "\n";
    if (!s.memory.empty())
        o << "#SBATCH --mem=" << s.memory << "\n";
    for (const auto &line : s.extra)
        o << "#SBATCH " << line << "\n";
    o << "# Task i runs the case on line i+1 of cases.txt in its own folder (log: cases/<id>/log.txt).\n"
      << "case_id=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" " << quoted((slurm / "cases.txt").string())
      << ")\n"
      << "exec " << quoted(ctx.armour_exe) << " sweep --run-case " << quoted((ctx.out / "cases").string())
      << "/\"$case_id\"\n";
    return o.str();
}

std::string submit_slurm(const SweepContext &ctx, const std::vector<std::size_t> &to_run) {
    const fs::path slurm = ctx.out / "slurm";
    fs::create_directories(slurm);
    std::string cases;
    json ids = json::array();
    for (const std::size_t i : to_run) {
        cases += ctx.plan.cases[i].id + "\n";
        ids.push_back(ctx.plan.cases[i].id);
    }
    write_text_file(slurm / "cases.txt", cases);
    write_text_file(slurm / "array.sbatch", slurm_script(ctx, to_run.size()));
    std::string text;
    if (shell("sbatch --parsable " + quoted((slurm / "array.sbatch").string()), text) != 0)
        throw InputError("--executor: slurm: sbatch refused the job array: " + first_line(text));
    const std::string job = first_line(text).substr(0, first_line(text).find(';'));
    write_text_file(slurm / "job.json",
                    json{{"job_id", job}, {"tasks", to_run.size()}, {"cases", ids}}.dump(2) + "\n");
    std::fprintf(stderr, "sweep: submitted Slurm job array %s (%zu tasks): %s\n", job.c_str(), to_run.size(),
                 (slurm / "array.sbatch").c_str());
    return job;
}

std::string slurm_job_in_queue(const fs::path &out) {
    const json job = read_job(out);
    if (!job.is_object() || !job.contains("job_id"))
        return "";
    const std::string id = job["job_id"].get<std::string>();
    std::string text;
    if (shell("squeue -h -j " + id + " -o %i", text) != 0)
        // An id Slurm has forgotten has ended; any other failure (the
        // controller busy or restarting) is no news: ask again later.
        return text.find("Invalid job id") != std::string::npos ? "" : id;
    return text.find_first_not_of(" \n") == std::string::npos ? "" : id;
}

void follow_slurm(const SweepContext &ctx, const std::set<std::string> &skipped) {
    const json job = read_job(ctx.out);
    if (!job.is_object() || !job.contains("job_id"))
        throw InputError("--collect " + ctx.out.string() + ": no Slurm job recorded (slurm/job.json)");
    const std::string id = job["job_id"].get<std::string>();
    const std::vector<std::string> ids = job["cases"].get<std::vector<std::string>>();
    const bool terminal = ::isatty(STDERR_FILENO) != 0;
    std::string last_line;
    std::set<std::string> finished;
    std::vector<CaseRecord> finished_records;
    int reported = 0; // the job's cases done or failed when report.md was last written
    for (;;) {
        const bool queued = !slurm_job_in_queue(ctx.out).empty();
        const SweepTable table = refresh_tables(ctx, skipped);
        int left = 0, ended = 0;
        for (const auto &row : table.rows)
            if (std::find(ids.begin(), ids.end(), row.record.id) != ids.end()) {
                if (row.status == "done" && finished.insert(row.record.id).second)
                    finished_records.push_back(row.record);
                left += row.status == "pending" || row.status == "running";
                ended += row.status == "done" || row.status == "failed";
            }
        if (queued && ended > reported) { // report.md follows the cases (the sweep writes it at its end)
            write_report(ctx.out);
            reported = ended;
        }
        const int parallel = std::max(1, table.count("running"));
        const std::string line =
            progress_line(table, estimate_eta(finished_records, left, parallel)) + " (Slurm job " + id + ")";
        if (terminal)
            std::fprintf(stderr, "\r%-90s", line.c_str());
        else if (line != last_line)
            std::fprintf(stderr, "%s\n", line.c_str());
        last_line = line;
        if (!queued)
            break;
        std::this_thread::sleep_for(std::chrono::seconds(2));
    }
    if (terminal)
        std::fputc('\n', stderr);

    // Tasks Slurm ended before the case could record it (time limit, node
    // failure, cancelled while queued) are failed cases with Slurm's state.
    const std::map<std::string, std::string> states = task_states(id);
    for (std::size_t task = 0; task < ids.size(); ++task) {
        const auto c = std::find_if(ctx.plan.cases.begin(), ctx.plan.cases.end(),
                                    [&](const SweepCase &x) { return x.id == ids[task]; });
        if (c == ctx.plan.cases.end())
            continue;
        const fs::path dir = case_dir(ctx.out, *c);
        CaseRecord r = read_case_record(dir);
        const auto state = states.find(std::to_string(task));
        if (r.status == "done")
            continue;
        // A later --collect, when Slurm has forgotten the job, keeps the state seen first.
        if (state != states.end() || r.slurm_state.empty())
            r.slurm_state = state == states.end() ? "UNKNOWN" : state->second;
        const std::string &slurm_state = r.slurm_state;
        if (r.status != "failed") {
            r.status = "failed";
            r.reason = "the Slurm task ended as " + slurm_state + " before the case finished";
        }
        if (r.slurm_job.empty())
            r.slurm_job = id + "_" + std::to_string(task);
        write_case_record(dir, r);
        // The case's log, or Slurm's own for a task that never started the case.
        const fs::path task_log = ctx.out / "slurm" / ("task-" + std::to_string(task) + ".out");
        const bool case_log = fs::exists(dir / "log.txt");
        std::fprintf(stderr, "sweep: case %s failed: Slurm task %s_%zu %s (%s); log %s:\n%s", c->id.c_str(),
                     id.c_str(), task, slurm_state.c_str(), r.reason.c_str(),
                     (case_log ? dir / "log.txt" : task_log).c_str(),
                     log_tail_of(case_log ? dir / "log.txt" : task_log, 5).c_str());
    }
    refresh_tables(ctx, skipped);
}

} // namespace armour
