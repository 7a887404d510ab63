// Every `armour` command line in README.md and docs/**/*.md runs as a user
// would paste it, so a broken example fails CI; so does every `python3
// SCRIPT.py` and `bash bench/SCRIPT.sh` line (below). One test case per document.
//
// What counts as an example
//   - In a fenced code block (``` or ```sh, bash, shell, console; a block
//     tagged text, toml, cpp, ... is not shell), every line whose first word
//     is `armour` or a path ending in /armour (build/apps/armour), after an
//     optional `$ ` or `time`/`/usr/bin/time`; `\` continuations are joined
//     and a comment (`#` starting a word, outside quotes) is dropped.
//   - In prose, every inline code span (it may run over a line break) whose
//     first word is armour as above and that has a second word.
//   The line reported is the first line of the command in the document.
//
// How each one is checked (one of four modes; kRules below picks it)
//   full     run as written; exit 0 and, with --out, DIR/summary.json.
//   shorten  run with `--set run.duration=D` appended (the last --set of a
//            key wins): the example's scene, options and every --set are
//            read, checked and run through the same code, only for less
//            simulated time; exit 0 and DIR/summary.json.
//   dry      run with `--dry-run` appended (armour run, compare, sweep): every
//            check the real command makes before its work (scene keys and
//            ranges, files, engine, fluid case and OpenFOAM's tools, --out);
//            exit 0 and DIR not created.
//   syntax   a synopsis or a mention in prose: the subcommand and every
//            --option it names exist (`armour SUB --help`).
//   A command the table does not know gets dry for run, compare and sweep
//   and full for the rest, so a new example is tested without touching
//   this file; a slow or special one gets a row in kRules.
//
// Scripts (`python3 studies/x.py ...` or `/usr/bin/python3 bench/y.py ...`,
// fenced or inline as above; the interpreter is the system's, /usr/bin/python3,
// which has matplotlib and h5py; and `bash bench/run_x.sh ...`, the benchmarks)
//   full     a script kScriptRules names, with an --out and no placeholder
//            in any other word: run, its --out sent to a file of the test's
//            working folder (an example that writes into docs/ writes nothing
//            there); exit 0 and that file or folder written.
//   syntax   the rest (they read run folders outside the repository, or are
//            benchmarks of minutes to hours, several of them run by their
//            capability's tests with small options): the
//            script exists (under the source tree, or the document's folder)
//            and `SCRIPT --help` exits 0 and lists every --option named.
//
// Placeholders (the rule)
//   - An all-capitals word, alone or leading a path (OUT, DIR, RUN, REPORT,
//     SCENE.toml, OUT/settle/x.toml, KEY=VALUE, material.0.friction=MU):
//       as the value of --out it is an output folder: a new folder in the
//       command's fresh working folder;
//       as the run folder of `armour report` it is a run made for the
//       test (a short coupled run, made once and kept in the build folder),
//       and so is a relative path there (`armour report out/stability ...`
//       after the run that wrote it: the report is the example, not the run);
//       anywhere else (a scene, --np N, --until T, --collect DIR) it makes
//       the command a synopsis: syntax.
//   - `[`, `]`, `<`, `>`, `|` or `...` outside quotes make it a synopsis.
//   - An inline span naming no file and no --out (`armour run --resume`,
//     `armour demo`, `armour clump --spheres 100`; not engines or --help) is
//     a mention of a command and its options in prose: syntax. A span that
//     names a file or --out is a command a reader may paste: it runs.
//   - An option left out of --help on purpose (kHidden) exists for syntax.
//   - An absolute path is a failure: documents name no machine's folders.
// Each command runs in a fresh working folder where every top-level entry of
// the source tree (scenes/, studies/, ...) is a link and build/ links the
// build folder, so relative paths work and outputs land in the temporary
// folder. Clumps are cached in BUILD/doc_examples/cache.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kSource = ARMOUR_SOURCE_DIR;
const fs::path kBuild = ARMOUR_BUILD_DIR;
const fs::path kArmour = ARMOUR_EXE;

enum class Mode { full, shorten, dry, syntax };

const char *mode_name(Mode m) {
    switch (m) {
    case Mode::full:
        return "full";
    case Mode::shorten:
        return "shorten";
    case Mode::dry:
        return "dry";
    case Mode::syntax:
        return "syntax";
    }
    return "?";
}

// The per-command choice, first match wins, matched against the command with
// its binary written `armour`. Every document together: ~2.2 min of CPU on 2
// cores (most of it the stability scene's random placement in its dry runs).
struct Rule {
    const char *pattern;
    Mode mode;
    double duration; // s of simulated time, shorten only
    const char *why;
};
const Rule kRules[] = {
    {R"(^armour run .*--resume)", Mode::dry, 0,
     "a resume needs a killed run's checkpoints: the run it continues is dry-run without --resume "
     "(tests/test_checkpoint.cpp resumes real ones)"},
    {R"(^armour sweep .*--executor slurm)", Mode::syntax, 0,
     "needs a Slurm controller (tests/test_sweep.cpp starts one)"},
    {R"(^armour sweep --collect)", Mode::syntax, 0, "needs a Slurm sweep's folder"},
    {R"(^armour report .*--from )", Mode::syntax, 0,
     "a reference before the waves reach the toe needs a wave run's record, not the short dam-break run "
     "(tests/test_stability.cpp reports from one)"},
    {R"(^armour clump --out \.$)", Mode::syntax, 0, "the prose's example of a refused folder"},
    {R"(^armour run scenes/(tilt_cube|drop_bounce)\.toml )", Mode::shorten, 0.3,
     "a dry scene: its first 0.3 s (the whole tilt is ~10 s)"},
    {R"(^armour run scenes/(slope_cubes|slope_dolosse)\.toml )", Mode::shorten, 0.05,
     "a dry scene: its units placed and dropped for 0.05 s (settling takes minutes)"},
    {R"(^armour compare scenes/drop_bounce\.toml --spheres 4,8,20 --set run\.duration=0\.6)", Mode::full, 0,
     "the quick start's compare: ~7 s of CPU"},
    {R"(^armour sweep studies/tilt_friction\.toml --out \S+$)", Mode::dry, 0,
     "four full tilt runs (a minute or two); tests/test_sweep.cpp runs this sweep"},
};

// The scripts whose examples run in full (matched against the script's path as written).
const char *const kScriptRules[] = {
    R"(^studies/compare_curves\.py$)", // reads kept results in docs/results/: ~2 s a chart
    R"(^studies/seats\.py$)",          // reads kept results and layers in docs/results/: ~1 s
    R"(^studies/damage_timing\.py$)",  // reads kept results in docs/results/: ~2 s
};

// Internal options the documents name but --help leaves out on purpose.
const char *const kHidden[] = {"sweep --run-case"};

// ------------------------------------------------------------- extraction

struct Example {
    std::string file; // relative to the source tree
    int line = 0;
    std::string text; // the command line as written, continuations joined, comment dropped
    bool fenced = false;
    bool script = false; // a `python3 SCRIPT.py` or `bash bench/SCRIPT.sh` line, not an armour command
};

std::string trimmed(const std::string &s) {
    const auto b = s.find_first_not_of(" \t");
    return b == std::string::npos ? "" : s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// The line without a leading prompt (`$ `) or `time`.
std::string without_prefix(std::string text) {
    text = trimmed(text);
    for (const char *prefix : {"$ ", "time ", "/usr/bin/time "})
        if (text.rfind(prefix, 0) == 0)
            text = trimmed(text.substr(std::string(prefix).size()));
    return text;
}

// The text from the interpreter on when the line runs a script ("" otherwise).
std::string script_command(std::string text) {
    text = without_prefix(text);
    static const std::regex script(R"(^((python3|/usr/bin/python3)\s+\S+\.py|bash\s+bench/\S+\.sh)(\s.*)?$)");
    return std::regex_match(text, script) ? text : "";
}

bool is_armour_word(const std::string &w) {
    return w == "armour" || (w.size() > 7 && w.compare(w.size() - 7, 7, "/armour") == 0);
}

// The text from the armour word on ("" when the line does not invoke armour).
std::string armour_command(std::string text) {
    text = without_prefix(text);
    const std::string first = text.substr(0, text.find_first_of(" \t"));
    return is_armour_word(first) ? text : "";
}

// A comment starts at a `#` beginning a word, outside quotes.
std::string without_comment(const std::string &line) {
    char quote = 0;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quote) {
            if (c == quote)
                quote = 0;
        } else if (c == '\'' || c == '"') {
            quote = c;
        } else if (c == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) {
            return line.substr(0, i);
        }
    }
    return line;
}

bool shell_fence(const std::string &info) {
    return info.empty() || info == "sh" || info == "bash" || info == "shell" || info == "console";
}

// Inline code spans of one paragraph (lines without a blank one between).
void inline_examples(const std::vector<std::pair<int, std::string>> &paragraph, const std::string &file,
                     std::vector<Example> &out) {
    std::string text;
    std::vector<std::pair<std::size_t, int>> starts; // offset in text, document line
    for (const auto &[number, line] : paragraph) {
        starts.emplace_back(text.size(), number);
        text += line + "\n";
    }
    auto line_at = [&](std::size_t offset) {
        int line = starts.front().second;
        for (const auto &[at, number] : starts)
            if (at <= offset)
                line = number;
        return line;
    };
    for (std::size_t k = 0; k < text.size();) {
        if (text[k] != '`') {
            ++k;
            continue;
        }
        std::size_t run = k;
        while (run < text.size() && text[run] == '`')
            ++run;
        const std::string ticks = text.substr(k, run - k);
        // The span ends at the next run of exactly as many backticks.
        std::size_t end = text.find(ticks, run);
        while (end != std::string::npos && end + ticks.size() < text.size() &&
               text[end + ticks.size()] == '`')
            end = text.find(ticks, text.find_first_not_of('`', end));
        if (end == std::string::npos) {
            k = run;
            continue;
        }
        std::istringstream words(text.substr(run, end - run));
        std::string span, word;
        while (words >> word)
            span += (span.empty() ? "" : " ") + word;
        const std::string command = armour_command(span);
        if (!command.empty() && command.find(' ') != std::string::npos)
            out.push_back({file, line_at(k), command, false});
        else if (const std::string script = script_command(span); !script.empty())
            out.push_back({file, line_at(k), script, false, true});
        k = end + ticks.size();
    }
}

std::vector<Example> extract_examples(const std::string &document, const std::string &file) {
    std::vector<std::string> lines;
    std::istringstream in(document);
    for (std::string line; std::getline(in, line);)
        lines.push_back(line);
    std::vector<Example> out;
    std::vector<std::pair<int, std::string>> paragraph;
    const std::regex fence_open(R"(^ {0,3}(`{3,}|~{3,})\s*([^\s`]*).*$)");
    std::string fence; // the open fence's marker, "" outside one
    bool shell = false;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        std::smatch m;
        if (fence.empty() && std::regex_match(lines[i], m, fence_open)) {
            inline_examples(paragraph, file, out);
            paragraph.clear();
            fence = m[1];
            shell = shell_fence(m[2]);
            continue;
        }
        if (!fence.empty()) {
            const std::string t = trimmed(lines[i]);
            if (t.size() >= fence.size() && t.find_first_not_of(fence[0]) == std::string::npos) {
                fence.clear();
                continue;
            }
            if (!shell)
                continue;
            const int first = static_cast<int>(i) + 1;
            std::string joined = lines[i];
            while (!trimmed(joined).empty() && trimmed(joined).back() == '\\' && i + 1 < lines.size()) {
                joined = trimmed(joined);
                joined.pop_back();
                joined = trimmed(joined) + " " + trimmed(lines[++i]);
            }
            const std::string command = armour_command(without_comment(joined));
            if (!command.empty())
                out.push_back({file, first, command, true});
            else if (const std::string script = script_command(without_comment(joined)); !script.empty())
                out.push_back({file, first, script, true, true});
            continue;
        }
        if (trimmed(lines[i]).empty()) {
            inline_examples(paragraph, file, out);
            paragraph.clear();
        } else {
            paragraph.emplace_back(static_cast<int>(i) + 1, lines[i]);
        }
    }
    inline_examples(paragraph, file, out);
    std::stable_sort(out.begin(), out.end(),
                     [](const Example &a, const Example &b) { return a.line < b.line; });
    return out;
}

// ------------------------------------------------------------- planning

struct Word {
    std::string text; // quotes removed
    bool quoted = false;
};

// Shell words: whitespace splits, '...' and "..." group, a backslash escapes.
std::vector<Word> shell_words(const std::string &line) {
    std::vector<Word> words;
    Word w;
    bool in_word = false;
    char quote = 0;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quote) {
            if (c == quote)
                quote = 0;
            else
                w.text += c;
        } else if (c == '\'' || c == '"') {
            quote = c;
            w.quoted = in_word = true;
        } else if (c == '\\' && i + 1 < line.size()) {
            w.text += line[++i];
            in_word = true;
        } else if (c == ' ' || c == '\t') {
            if (in_word)
                words.push_back(w);
            w = Word();
            in_word = false;
        } else {
            w.text += c;
            in_word = true;
        }
    }
    if (in_word)
        words.push_back(w);
    return words;
}

// An all-capitals word alone or leading a path or a KEY=VALUE's part.
bool has_placeholder(const std::string &text) {
    static const std::regex capitals(R"((^|[=/])[A-Z][A-Z0-9_]*($|[./=]))");
    return std::regex_search(text, capitals);
}

bool synopsis_marks(const Word &w) {
    if (w.quoted)
        return false;
    return w.text.find_first_of("[]<>|") != std::string::npos || w.text.find("...") != std::string::npos ||
           w.text.find("\u2026") != std::string::npos;
}

// `armour SUB --help` (SUB "" for the top level), cached.
struct Help {
    int status = -1;
    std::string text;
};

std::string run_capture(const std::string &command, int &status) {
    std::string output;
    std::FILE *pipe = ::popen((command + " 2>&1").c_str(), "r");
    if (!pipe) {
        status = -1;
        return "popen failed";
    }
    char buffer[4096];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0)
        output.append(buffer, n);
    const int raw = ::pclose(pipe);
    status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + (WIFSIGNALED(raw) ? WTERMSIG(raw) : 0);
    return output;
}

const Help &help_of(const std::string &sub) {
    static std::map<std::string, Help> cache;
    auto found = cache.find(sub);
    if (found == cache.end()) {
        Help h;
        h.text = run_capture("'" + kArmour.string() + "' " + (sub.empty() ? "" : "'" + sub + "' ") + "--help",
                             h.status);
        found = cache.emplace(sub, h).first;
    }
    return found->second;
}

// The option `name` as the help lists it: "--out TEXT ..." takes a value,
// "--resume   Continue ..." is a flag. Returns false when it is not listed.
bool listed_option(const std::string &sub, const std::string &name, bool &takes_value) {
    std::istringstream lines(help_of(sub).text);
    for (std::string text; std::getline(lines, text);) {
        // The option column: "  -h,--help", "  --out TEXT REQUIRED" (before the description).
        const std::string line = trimmed(text).substr(0, trimmed(text).find("  "));
        if (line.empty() || line[0] != '-')
            continue;
        for (std::size_t at = line.find(name); at != std::string::npos; at = line.find(name, at + 1)) {
            const std::size_t end = at + name.size();
            const bool starts = at == 0 || line[at - 1] == ' ' || line[at - 1] == ',';
            const bool ends = end == line.size() || line[end] == ' ' || line[end] == ',';
            if (!starts || !ends)
                continue;
            // One space, then a type in capitals (TEXT, INT:POSITIVE, FLOAT:S>0).
            takes_value = end + 1 < line.size() && line[end] == ' ' &&
                          std::isupper(static_cast<unsigned char>(line[end + 1]));
            return true;
        }
    }
    return false;
}

struct Plan {
    Mode mode = Mode::full;
    std::string why;
    std::string command;              // what runs (shell text)
    std::string sub;                  // the subcommand ("" for `armour --help`)
    std::string out;                  // --out's value, "" if none
    std::string run_folder;           // the placeholder of `armour report RUN`, linked to the test's run
    std::string problem;              // not runnable as written (the failure), or ""
    std::vector<std::string> options; // --names it uses
};

Plan plan_example(const Example &e) {
    Plan p;
    const std::vector<Word> words = shell_words(e.text);
    if (words.front().text.front() == '/')
        p.problem =
            "names an absolute path (" + words.front().text + "): documents name no machine's folders";
    std::size_t i = 1;
    if (i < words.size() && !words[i].text.empty() && words[i].text.front() != '-')
        p.sub = words[i++].text;
    bool synopsis = synopsis_marks(Word{p.sub, false});
    std::vector<std::string> positional;
    for (; i < words.size(); ++i) {
        const Word &w = words[i];
        if (w.text.empty())
            continue; // '' (an empty argument)
        if (w.text.front() == '/' && p.problem.empty())
            p.problem = "names an absolute path (" + w.text +
                        "): documents name no machine's folders; write "
                        "OUT, RUN or a relative path";
        synopsis = synopsis || synopsis_marks(w);
        if (w.text.rfind("--", 0) != 0 || w.quoted) {
            positional.push_back(w.text);
            continue;
        }
        const std::string name = w.text.substr(0, w.text.find('='));
        p.options.push_back(name);
        bool takes_value = false;
        if (synopsis_marks(Word{p.sub, false}) || !listed_option(p.sub, name, takes_value))
            continue; // judged in syntax mode, or refused by the run itself
        std::string value;
        if (w.text.find('=') != std::string::npos)
            value = w.text.substr(w.text.find('=') + 1);
        else if (takes_value && i + 1 < words.size())
            value = words[++i].text;
        if (name == "--out")
            p.out = value;
        else if (has_placeholder(value))
            synopsis = true;
    }
    for (std::size_t k = 0; k < positional.size(); ++k)
        if (has_placeholder(positional[k])) {
            const bool run_folder =
                p.sub == "report" && k == 0 && std::regex_match(positional[k], std::regex("[A-Z][A-Z0-9_]*"));
            if (run_folder)
                p.run_folder = positional[k];
            else
                synopsis = true;
        }
    // A report's run folder named as a path (`armour report out/stability ...` after the run that
    // wrote it) is the test's run too: the example checks the report, not a days-long run.
    if (p.sub == "report" && p.run_folder.empty() && !positional.empty() && !has_placeholder(positional[0]) &&
        !fs::path(positional[0]).is_absolute())
        p.run_folder = positional[0];
    const bool mention = !e.fenced && p.out.empty() && positional.empty() && p.sub != "engines" &&
                         std::find(p.options.begin(), p.options.end(), "--help") == p.options.end();
    const std::size_t space = e.text.find_first_of(" \t");
    const std::string normal = "armour" + (space == std::string::npos ? "" : e.text.substr(space));
    const Rule *rule = nullptr;
    for (const Rule &r : kRules)
        if (!rule && std::regex_search(normal, std::regex(r.pattern)))
            rule = &r;
    if (synopsis || mention) {
        p.mode = Mode::syntax;
        p.why = synopsis ? "a synopsis (placeholders)" : "a mention in prose (no file, no --out)";
    } else if (rule) {
        p.mode = rule->mode;
        p.why = rule->why;
    } else {
        const bool long_kind = p.sub == "run" || p.sub == "compare" || p.sub == "sweep";
        p.mode = long_kind ? Mode::dry : Mode::full;
        p.why = long_kind ? "the default for run, compare and sweep" : "the default";
    }
    p.command = e.text;
    if (p.mode == Mode::dry) {
        p.command = std::regex_replace(p.command, std::regex(R"(\s--resume(?=\s|$))"), "");
        if (!std::regex_search(p.command, std::regex(R"(\s--dry-run(\s|$))")))
            p.command += " --dry-run";
    }
    if (p.mode == Mode::shorten) {
        char set[64];
        std::snprintf(set, sizeof set, " --set run.duration=%g", rule->duration);
        p.command += set;
    }
    return p;
}

// ------------------------------------------------------------- running

std::string read_text(const fs::path &path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string last_lines(const std::string &text, int n) {
    std::size_t at = text.size();
    for (int k = 0; k <= n && at != std::string::npos && at > 0; ++k)
        at = text.rfind('\n', at - 1);
    return at == std::string::npos || at == 0 ? text : text.substr(at + 1);
}

// A short coupled run for `armour report RUN`: made once per build of the
// binary (a stamp of its time and size) under a lock, so test processes
// running side by side share it.
fs::path report_run() {
    const fs::path dir = kBuild / "doc_examples";
    const fs::path run = dir / "report_run";
    fs::create_directories(dir);
    const int lock = ::open((dir / "report_run.lock").c_str(), O_RDWR | O_CREAT, 0644);
    ::flock(lock, LOCK_EX);
    const std::string stamp = std::to_string(fs::last_write_time(kArmour).time_since_epoch().count()) + " " +
                              std::to_string(fs::file_size(kArmour));
    if (read_text(dir / "report_run.stamp") != stamp || !fs::is_regular_file(run / "summary.json")) {
        int status = 0;
        const std::string output = run_capture(
            "'" + kArmour.string() + "' run '" + (kSource / "scenes" / "dambreak_two_cubes.toml").string() +
                "' --out '" + run.string() + "' --cache '" + (dir / "cache").string() +
                "' --set run.duration=0.05 --restart",
            status);
        EXPECT_EQ(status, 0) << "the run for `armour report RUN` failed:\n" << last_lines(output, 30);
        std::ofstream(dir / "report_run.stamp") << stamp;
    }
    ::close(lock); // drops the lock
    return run;
}

// A working folder where the source tree's entries and build/ resolve.
fs::path working_folder(const fs::path &parent, int index) {
    const fs::path cwd = parent / ("example" + std::to_string(index));
    fs::create_directories(cwd);
    for (const auto &entry : fs::directory_iterator(kSource)) {
        const std::string name = entry.path().filename().string();
        if (name == "build" || name == ".git" || name == "out")
            continue;
        fs::create_directory_symlink(entry.path(), cwd / name);
    }
    fs::create_directory_symlink(kBuild, cwd / "build");
    return cwd;
}

std::string where(const Example &e) {
    return e.file + ":" + std::to_string(e.line) + ": `" + e.text + "`";
}

// Syntax mode: the subcommand and every option it names exist.
void check_syntax(const Example &e, const Plan &p) {
    const bool sub_named = !p.sub.empty() && !synopsis_marks(Word{p.sub, false});
    const Help &help = help_of(sub_named ? p.sub : "");
    if (help.status != 0) {
        ADD_FAILURE() << where(e) << "\n  no such subcommand '" << p.sub << "' (`armour " << p.sub
                      << " --help` exits " << help.status << "):\n"
                      << last_lines(help.text, 10);
        return;
    }
    for (const std::string &name : p.options) {
        bool takes_value = false;
        const std::string hidden = p.sub + " " + name;
        if (std::find(std::begin(kHidden), std::end(kHidden), hidden) != std::end(kHidden))
            continue;
        if (!listed_option(sub_named ? p.sub : "", name, takes_value))
            ADD_FAILURE() << where(e) << "\n  `armour " << p.sub << " --help` lists no option " << name;
    }
}

std::string single_quoted(const std::string &text) {
    return "'" + std::regex_replace(text, std::regex("'"), "'\\''") + "'";
}

// A script example: full for the scripts kScriptRules names (an --out, no
// other placeholder), syntax for the rest (see the top of this file).
void check_script(const Example &e, const fs::path &scratch, int index) {
    const std::vector<Word> words = shell_words(e.text);
    const std::string written = words[1].text;
    fs::path script = kSource / written;
    if (!fs::is_regular_file(script)) // a results folder's own command, run from that folder
        script = (kSource / e.file).parent_path() / written;
    if (!fs::is_regular_file(script)) {
        ADD_FAILURE() << where(e) << "\n  no such script " << written;
        return;
    }
    std::vector<std::string> options, args;
    std::string out;
    bool synopsis = false;
    for (std::size_t i = 2; i < words.size(); ++i) {
        const Word &w = words[i];
        if (!w.quoted && !w.text.empty() && w.text.front() == '/') {
            ADD_FAILURE() << where(e) << "\n  names an absolute path (" << w.text
                          << "): documents name no machine's folders";
            return;
        }
        synopsis = synopsis || synopsis_marks(w) || (!w.quoted && has_placeholder(w.text));
        args.push_back(w.text);
        if (w.quoted || w.text.rfind("--", 0) != 0)
            continue;
        options.push_back(w.text.substr(0, w.text.find('=')));
        if (w.text == "--out" && i + 1 < words.size()) {
            out = words[++i].text;
            args.push_back("\x01"); // --out's value, replaced below
        }
    }
    const bool listed = std::any_of(std::begin(kScriptRules), std::end(kScriptRules),
                                    [&](const char *r) { return std::regex_match(written, std::regex(r)); });
    const bool shell_script = script.extension() == ".sh";
    const std::string invoke =
        (shell_script ? "bash " : "/usr/bin/python3 ") + single_quoted(script.string());
    if (!listed || shell_script || out.empty() || synopsis) {
        int status = 0;
        const std::string help = run_capture(invoke + " --help", status);
        if (status != 0) {
            ADD_FAILURE() << where(e) << "\n  `" << written << " --help` exits " << status << ":\n"
                          << last_lines(help, 10);
            return;
        }
        for (const std::string &name : options)
            if (!std::regex_search(help, std::regex("(^|[\\s\\[,])" + name + "($|[\\s\\],=])")))
                ADD_FAILURE() << where(e) << "\n  `" << written << " --help` lists no option " << name;
        return;
    }
    const fs::path cwd = working_folder(scratch, index);
    const fs::path written_out = cwd / "script_out" / fs::path(out).filename();
    fs::create_directories(written_out.parent_path());
    std::string command = "cd " + single_quoted(cwd.string()) + " || exit 99\n" + invoke;
    for (const std::string &a : args)
        command += " " + single_quoted(a == "\x01" ? written_out.string() : a);
    const fs::path shell = scratch / ("example" + std::to_string(index) + ".sh");
    std::ofstream(shell) << command << "\n";
    int status = 0;
    const std::string output = run_capture("timeout 300 bash " + single_quoted(shell.string()), status);
    std::printf("[script] %s:%d %s\n", e.file.c_str(), e.line, e.text.c_str());
    EXPECT_EQ(status, 0) << where(e) << "\n  ran: " << command << "\n  its output ends:\n"
                         << last_lines(output, 25);
    EXPECT_TRUE(fs::exists(written_out)) << where(e) << "\n  wrote no " << written_out;
}

void check_example(const Example &e, const fs::path &scratch, int index) {
    if (e.script) {
        check_script(e, scratch, index);
        return;
    }
    const Plan p = plan_example(e);
    if (!p.problem.empty()) {
        ADD_FAILURE() << where(e) << "\n  " << p.problem;
        return;
    }
    if (p.mode == Mode::syntax) {
        check_syntax(e, p);
        return;
    }
    const fs::path cwd = working_folder(scratch, index);
    if (!p.run_folder.empty()) {
        fs::create_directories((cwd / p.run_folder).parent_path());
        fs::create_directory_symlink(report_run(), cwd / p.run_folder);
    }
    const fs::path script = scratch / ("example" + std::to_string(index) + ".sh");
    std::ofstream(script) << "cd '" << cwd.string() << "' || exit 99\n" << p.command << "\n";
    const auto start = std::chrono::steady_clock::now();
    int status = 0;
    const std::string output = run_capture("timeout 900 bash '" + script.string() + "'", status);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("[%s %5.1f s] %s:%d %s\n", mode_name(p.mode), seconds, e.file.c_str(), e.line,
                p.command.c_str());
    const std::string what = where(e) + "\n  ran (" + mode_name(p.mode) + ": " + p.why + "): " + p.command +
                             "\n  in " + cwd.string() + "\n";
    if (status != 0) {
        ADD_FAILURE() << what << "  exit status " << status << (status == 124 ? " (over 900 s)" : "")
                      << "; its output ends:\n"
                      << last_lines(output, 25);
        return;
    }
    if (p.out.empty())
        return;
    const fs::path out = cwd / p.out; // an absolute --out is refused above
    if (p.mode == Mode::dry)
        EXPECT_FALSE(fs::exists(out)) << what << "  a dry run created " << out;
    else
        EXPECT_TRUE(fs::is_regular_file(out / "summary.json")) << what << "  wrote no summary.json; output:\n"
                                                               << last_lines(output, 25);
}

std::vector<std::string> doc_files() {
    std::vector<std::string> files;
    for (const auto &entry : fs::recursive_directory_iterator(kSource / "docs"))
        if (entry.is_regular_file() && entry.path().extension() == ".md")
            files.push_back(fs::relative(entry.path(), kSource).string());
    std::sort(files.begin(), files.end());
    files.insert(files.begin(), "README.md");
    return files;
}

std::string test_name(const ::testing::TestParamInfo<std::string> &info) {
    std::string name = info.param;
    for (char &c : name)
        if (!std::isalnum(static_cast<unsigned char>(c)))
            c = '_';
    return name;
}

class DocExamples : public ::testing::TestWithParam<std::string> {};

TEST_P(DocExamples, EveryArmourCommandRuns) {
    const std::string file = GetParam();
    ASSERT_TRUE(fs::is_regular_file(kSource / file)) << file;
    // The binary the examples name, from any working folder.
    static const bool environment = [] {
        const std::string path = (kBuild / "apps").string() + ":" + std::getenv("PATH");
        return ::setenv("PATH", path.c_str(), 1) == 0 &&
               ::setenv("ARMOUR_CACHE", (kBuild / "doc_examples" / "cache").c_str(), 1) == 0;
    }();
    ASSERT_TRUE(environment);
    const fs::path scratch = fs::temp_directory_path() / ("armour-doc-examples-" + test_name({file, 0}) +
                                                          "-" + std::to_string(::getpid()));
    fs::remove_all(scratch);
    fs::create_directories(scratch);
    const std::vector<Example> examples = extract_examples(read_text(kSource / file), file);
    int index = 0;
    for (const Example &e : examples)
        check_example(e, scratch, index++);
    if (!HasFailure())
        fs::remove_all(scratch);
}

INSTANTIATE_TEST_SUITE_P(Docs, DocExamples, ::testing::ValuesIn(doc_files()), test_name);

// The extraction and planning rules above, on a document made for them.
TEST(DocExampleRules, FindsFencedAndInlineCommandsAndPlansEach) {
    const std::string doc = "# Title with `armour run --resume`\n"
                            "\n"
                            "```sh\n"
                            "build/apps/armour run scenes/wave_flume.toml --out OUT \\\n"
                            "    --set 'name=\"x # y\"'   # a comment\n"
                            "ls out\n"
                            "```\n"
                            "```text\n"
                            "armour run\n"
                            "```\n"
                            "Prose `armour report RUN --out\n"
                            "REPORT --until 5` and `armour run SCENE --out DIR [--np N]`, `--set x=1`.\n";
    const std::vector<Example> found = extract_examples(doc, "x.md");
    ASSERT_EQ(found.size(), 4u);
    EXPECT_EQ(found[0].line, 1);
    EXPECT_EQ(found[1].line, 4);
    EXPECT_EQ(found[1].text, "build/apps/armour run scenes/wave_flume.toml --out OUT --set 'name=\"x # y\"'");
    EXPECT_TRUE(found[1].fenced);
    EXPECT_EQ(found[2].line, 11);
    EXPECT_EQ(found[2].text, "armour report RUN --out REPORT --until 5");

    EXPECT_EQ(plan_example(found[0]).mode, Mode::syntax); // a mention
    const Plan run = plan_example(found[1]);
    EXPECT_EQ(run.mode, Mode::dry);
    EXPECT_EQ(run.out, "OUT");
    EXPECT_NE(run.command.find("--dry-run"), std::string::npos);
    const Plan report = plan_example(found[2]);
    EXPECT_EQ(report.mode, Mode::full);
    EXPECT_EQ(report.run_folder, "RUN");
    EXPECT_EQ(report.out, "REPORT");
    EXPECT_EQ(plan_example(found[3]).mode, Mode::syntax); // SCENE, [--np N]

    EXPECT_FALSE(plan_example({"x.md", 1, "armour report /work/runs/a --out OUT", true}).problem.empty());
    const Plan resume =
        plan_example({"x.md", 1, "armour run scenes/slope_cubes.toml --out o --resume", true});
    EXPECT_EQ(resume.mode, Mode::dry);
    EXPECT_EQ(resume.command, "armour run scenes/slope_cubes.toml --out o --dry-run");
    const Plan shortened = plan_example({"x.md", 1, "armour run scenes/tilt_cube.toml --out o", true});
    EXPECT_EQ(shortened.mode, Mode::shorten);
    EXPECT_EQ(shortened.command, "armour run scenes/tilt_cube.toml --out o --set run.duration=0.3");
    EXPECT_EQ(
        plan_example({"x.md", 1, "armour run scenes/x.toml --set material.0.friction=MU --out o", true}).mode,
        Mode::syntax);
}

// Script lines are examples too: fenced or inline, `python3` or the system's path to it, and
// the benchmarks' `bash bench/...sh`.
TEST(DocExampleRules, FindsScriptCommands) {
    const std::string doc =
        "```sh\n"
        "python3 studies/compare_curves.py docs/results/a --out OUT/c.png  # a chart\n"
        "/usr/bin/python3 bench/compare_damage.py RUN_A RUN_B --out OUT\n"
        "python3 -c 'print(1)'\n"
        "bash scripts/test.sh\n"
        "```\n"
        "Prose `python3 studies/keep_results.py RUN DEST`, `bash bench/run_x.sh --out OUT`.\n";
    const std::vector<Example> found = extract_examples(doc, "x.md");
    ASSERT_EQ(found.size(), 4u); // not `python3 -c`, nor the install-and-build scripts
    EXPECT_TRUE(found[0].script && found[1].script && found[2].script && found[3].script);
    EXPECT_EQ(found[3].text, "bash bench/run_x.sh --out OUT");
    EXPECT_EQ(found[0].text, "python3 studies/compare_curves.py docs/results/a --out OUT/c.png");
    EXPECT_EQ(found[1].line, 3);
    EXPECT_EQ(found[2].text, "python3 studies/keep_results.py RUN DEST");
}

} // namespace
