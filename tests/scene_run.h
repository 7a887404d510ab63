// One `armour run` of a shipped scene in a fresh temporary folder, for the
// tests that drive the whole program through its command line
// (test_wave_flume, test_stability).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>

namespace armour_test {

struct SceneRun {
    int status = -1;           // armour's exit status; -1 when it did not exit
    std::string output;        // its stdout and stderr
    std::filesystem::path dir; // the temporary folder: run.log and out/
    std::filesystem::path out; // dir/out, the run's --out
    nlohmann::json summary;    // out/summary.json; discarded when absent or unreadable
};

// The whole of a text file ("" when it cannot be read).
inline std::string read_text(const std::filesystem::path &path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// `armour run SCENE --out DIR/out SETS`, SETS being further options as the
// shell reads them (e.g. "--set run.duration=10").
inline SceneRun run_scene(const std::string &armour, const std::filesystem::path &scene,
                          const std::string &name, const std::string &sets) {
    SceneRun r;
    std::string tmpl =
        (std::filesystem::temp_directory_path() / ("armour_test_" + name + "_XXXXXX")).string();
    if (!mkdtemp(tmpl.data()))
        return r;
    r.dir = tmpl;
    r.out = r.dir / "out";
    const std::filesystem::path log = r.dir / "run.log";
    const std::string cmd = "'" + armour + "' run '" + scene.string() + "' --out '" + r.out.string() + "' " +
                            sets + " > '" + log.string() + "' 2>&1";
    const int rc = std::system(cmd.c_str());
    r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    r.output = read_text(log);
    std::ifstream summary(r.out / "summary.json");
    if (summary)
        r.summary = nlohmann::json::parse(summary, nullptr, false);
    return r;
}

} // namespace armour_test
