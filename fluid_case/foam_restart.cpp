#include "foam_restart.h"

#include "input_error.h"
#include "output_folder.h"
#include "scene_keys.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>

namespace armour {

namespace fs = std::filesystem;

namespace {

std::string text_of(const fs::path &file) {
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Through a temporary file and a rename: a resume killed while it sets the
// case's dictionaries leaves each whole (the old text or the new), and the
// next resume sets them again. Truncated in place, a kill there left a
// controlDict without the entries a resume sets.
void write_text(const fs::path &file, const std::string &text) {
    write_text_file(file, text);
}

// Sets `key value;` in an OpenFOAM dictionary file (the case's controlDict).
void set_entry(const fs::path &dict, const std::string &key, const std::string &value) {
    const std::string text = text_of(dict);
    const std::regex entry("(^|\\n)(" + key + ")[ \\t]+[^;\\n]*;");
    if (!std::regex_search(text, entry))
        throw InputError(dict.string() + ": no '" + key + "' entry to set");
    write_text(dict, std::regex_replace(text, entry, "$1$2 " + value + ";"));
}

// Removes the time folders of `dir` later than t (a killed run's writes
// after its checkpoint), and the one of t itself with `and_at`.
void remove_later(const fs::path &dir, double t, bool and_at = false) {
    std::error_code ec;
    for (const auto &e : fs::directory_iterator(dir, ec)) {
        const std::optional<double> time = time_of_name(e.path().filename().string());
        if (e.is_directory() && time && (and_at ? *time >= t * (1 - 1e-12) : *time > t * (1 + 1e-12)))
            fs::remove_all(e.path(), ec);
    }
}

// interFoam projects the flux phi whenever it starts (initCorrectPhi.H: a
// pcorr solve, phi -= its flux). The checkpoint's phi is the flux the live
// run went on with, conservative to the pressure solver's tolerance; the
// projection moved it in the 7th digit, and a surge on the units amplified
// that (0.07-0.6 Dn at the end of the dam break test). A pcorr solver whose
// tolerance, 2, lies above the largest normalised residual a zero guess can
// start from (1) takes no iteration: pcorr stays 0 and phi is the one read,
// to the bit. pcorr serves only that start-up projection on a static mesh.
void keep_checkpoint_flux(const fs::path &case_dir) {
    const fs::path dict = case_dir / "system" / "fvSolution";
    const std::string text = text_of(dict);
    const std::string mark = "// armour --resume: the checkpoint's flux phi is kept";
    if (text.find(mark) != std::string::npos)
        return;
    const std::regex solvers("(^|\\n)solvers[ \\t]*\\n?[ \\t]*\\{");
    std::smatch m;
    if (!std::regex_search(text, m, solvers))
        throw InputError(dict.string() + ": no 'solvers' dictionary to set pcorr in");
    const std::string entries = "\n    " + mark + " (docs/checkpoints.md)\n" +
                                "    pcorr { solver PCG; preconditioner DIC; tolerance 2; relTol 0; }\n" +
                                "    pcorrFinal { $pcorr; }\n";
    const auto at = static_cast<std::size_t>(m.position(0) + m.length(0));
    write_text(dict, text.substr(0, at) + entries + text.substr(at));
}

} // namespace

void write_fields_exactly(const fs::path &case_dir) {
    const fs::path control = case_dir / "system" / "controlDict";
    set_entry(control, "writeFormat", "binary");
    set_entry(control, "writePrecision", "17");
    // OpenFOAM restarts at the time its folder's NAME reads as (uniform/time's
    // exact value only warns): names with all 17 digits restart exactly.
    set_entry(control, "timePrecision", "17");
    // An adjustable write control stretches the step to land on the write
    // times, counted from the START time, which a restart moves: the steps
    // after a restart would differ. Plain runTime writes at the first step
    // past each write time and leaves the step to the Courant limit alone.
    set_entry(control, "writeControl", "runTime");
}

int checkpoint_ranks(const Checkpoint &checkpoint) {
    int ranks = 1;
    std::error_code ec;
    for (const auto &e : fs::directory_iterator(checkpoint.dir / "fluid", ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind("processor", 0) == 0 && name.size() > 9 &&
            name.find_first_not_of("0123456789", 9) == std::string::npos)
            ranks = std::max(ranks, std::stoi(name.substr(9)) + 1);
    }
    return ranks;
}

RestoredCase restore_case(const fs::path &case_dir, const Checkpoint &checkpoint, double end_time) {
    const fs::path fluid = checkpoint.dir / "fluid";
    if (!fs::is_directory(fluid))
        throw InputError(fluid.string() + ": missing (a checkpoint of a run without [fluid]?)");
    RestoredCase restored;
    restored.ranks = checkpoint_ranks(checkpoint);
    std::error_code ec;
    for (const auto &e : fs::directory_iterator(fluid)) {
        const std::string name = e.path().filename().string();
        if (name.rfind("processor", 0) == 0) { // a parallel run: processor<N>/<time>
            remove_later(case_dir / name, checkpoint.time);
            for (const auto &t : fs::directory_iterator(e.path())) {
                restored.time_name = t.path().filename().string();
                fs::copy(t.path(), case_dir / name / restored.time_name,
                         fs::copy_options::recursive | fs::copy_options::overwrite_existing);
            }
        } else {
            restored.time_name = name;
            remove_later(case_dir, checkpoint.time);
            fs::copy(e.path(), case_dir / name,
                     fs::copy_options::recursive | fs::copy_options::overwrite_existing);
        }
    }
    // Function objects (the wave gauges) write postProcessing/<name>/<start
    // time>/: a part a killed resume started at t or later goes, so that the
    // resume writes its own from t (gauge_rows.h stitches the parts).
    std::error_code none;
    for (const auto &e : fs::directory_iterator(case_dir / "postProcessing", none))
        if (e.is_directory())
            remove_later(e.path(), checkpoint.time, true);
    keep_checkpoint_flux(case_dir);
    const fs::path control = case_dir / "system" / "controlDict";
    set_entry(control, "startFrom", "latestTime");
    set_entry(control, "endTime", number_text(end_time));
    // The killed run's solver log stays beside the new one.
    for (int n = 1;; ++n) {
        const fs::path kept = case_dir / ("log.interFoam." + std::to_string(n));
        if (!fs::exists(kept)) {
            fs::rename(case_dir / "log.interFoam", kept, ec);
            break;
        }
    }
    return restored;
}

void set_ranks(const fs::path &case_dir, int ranks) {
    const fs::path dict = case_dir / "system" / "decomposeParDict";
    set_entry(dict, "numberOfSubdomains", std::to_string(ranks));
    // The templates split the flume along x (method simple, coeffs n (N 1 1)).
    const std::string text = text_of(dict);
    const std::regex split("(\\n[ \\t]+n[ \\t]+)\\([^)]*\\)");
    if (!std::regex_search(text, split))
        throw InputError(dict.string() + ": no 'n (nx ny nz)' entry to set");
    write_text(dict, std::regex_replace(text, split, "$1(" + std::to_string(ranks) + " 1 1)"));
}

std::string filled(std::string text, const std::map<std::string, std::string> &tokens) {
    for (const auto &[token, value] : tokens)
        for (auto at = text.find(token); at != std::string::npos; at = text.find(token, at + value.size()))
            text.replace(at, token.size(), value);
    return text;
}

void refill_paths(const fs::path &case_dir, const fs::path &template_dir,
                  const std::map<std::string, std::string> &tokens) {
    const std::regex entry("^[ \\t]*([A-Za-z_]+)[ \\t]+([^;]*);[ \\t]*$");
    for (const char *folder : {"system", "constant"}) {
        std::error_code ec;
        for (const auto &e : fs::directory_iterator(template_dir / folder, ec)) {
            if (!e.is_regular_file())
                continue;
            std::map<std::string, std::string> values; // key -> filled value
            std::set<std::string> other_keys;          // keys of entries without a path
            std::istringstream lines(text_of(e.path()));
            for (std::string line; std::getline(lines, line);) {
                const bool names_path = std::any_of(tokens.begin(), tokens.end(), [&](const auto &t) {
                    return line.find(t.first) != std::string::npos;
                });
                const auto code = line.find_first_not_of(" \t");
                const bool comment = code != std::string::npos && line.compare(code, 2, "//") == 0;
                std::smatch m;
                if (!std::regex_match(line, m, entry)) {
                    if (names_path && !comment)
                        throw InputError(
                            e.path().string() + ": '" + line +
                            "': a path a resume sets anew must be a `key value;` line of its own");
                    continue;
                }
                if (!names_path) {
                    other_keys.insert(m.str(1));
                    continue;
                }
                const std::string value = filled(m.str(2), tokens); // holds the token: a key is letters only
                if (const auto known = values.find(m.str(1)); known != values.end() && known->second != value)
                    throw InputError(e.path().string() + ": '" + m.str(1) +
                                     "' holds two different paths: a resume cannot set them anew");
                values[m.str(1)] = value;
            }
            for (const auto &[key, value] : values)
                if (other_keys.count(key) != 0)
                    throw InputError(e.path().string() + ": '" + key +
                                     "' holds a path in one entry and not in another: a resume cannot tell "
                                     "them apart");
            const fs::path target = case_dir / folder / e.path().filename();
            if (values.empty() || !fs::is_regular_file(target))
                continue;
            std::string text = text_of(target);
            for (const auto &[key, value] : values) {
                const std::regex line("(^|\\n)([ \\t]*" + key + "[ \\t]+)[^;\\n]*;");
                if (!std::regex_search(text, line))
                    throw InputError(target.string() + ": no '" + key + "' entry to set");
                std::string format = "$1$2"; // a '$' of the value stays itself
                format += std::regex_replace(value, std::regex("\\$"), "$$$$");
                format += ';';
                text = std::regex_replace(text, line, format);
            }
            write_text(target, text);
        }
    }
}

void set_resumable_controls(const fs::path &case_dir, double every_cell, double free_surface,
                            double write_interval) {
    const fs::path control = case_dir / "system" / "controlDict";
    set_entry(control, "maxCo", number_text(every_cell));
    set_entry(control, "maxAlphaCo", number_text(free_surface));
    set_entry(control, "writeInterval", number_text(write_interval));
}

} // namespace armour
