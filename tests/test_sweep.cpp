// `armour sweep`: the tilt scene over friction x spheres per clump through the
// local executor and a real single-node Slurm (scripts/slurm-local.sh),
// resume after kill -9, bad input, --set, the shipped studies (every case
// checked, one tiny case of each run), and the report's stability chart on
// synthetic damage summaries. The armour binary runs as a separate process,
// as users run it.
#include "process_wait.h"
#include "scene_smoke.h"
#include "scratch_folder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <sys/file.h>
#include <sys/wait.h>
#include <thread>
#include <toml++/toml.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::string kArmour = ARMOUR_EXE;
const std::string kSource = ARMOUR_SOURCE_DIR;
constexpr double kPi = 3.14159265358979323846;

struct Result {
    int status = -1;
    std::string output; // stdout and stderr
};

Result run(const std::string &command) {
    Result r;
    std::FILE *pipe = ::popen((command + " 2>&1").c_str(), "r");
    char buffer[4096];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0)
        r.output.append(buffer, n);
    const int status = ::pclose(pipe);
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

std::string read_text(const fs::path &path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void write(const fs::path &path, const std::string &text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
}

using Row = std::map<std::string, std::string>;

std::vector<Row> read_csv(const fs::path &path) {
    std::ifstream in(path);
    std::vector<std::string> header;
    std::vector<Row> rows;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("#", 0) == 0) // a comment line (damage.csv's units)
            continue;
        std::vector<std::string> cells;
        std::stringstream s(line);
        for (std::string cell; std::getline(s, cell, ',');)
            cells.push_back(cell);
        if (!line.empty() && line.back() == ',')
            cells.emplace_back();
        if (header.empty()) {
            header = cells;
            continue;
        }
        Row row;
        for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i)
            row[header[i]] = cells[i];
        rows.push_back(row);
    }
    return rows;
}

// The scene hash a `--dry-run` listing gives case `id` ("ID  scene HASH  ..."),
// or "" where the listing has no such case.
std::string listed_hash(const std::string &listing, const std::string &id) {
    const std::size_t at = listing.find(id + "  scene ");
    return at == std::string::npos ? std::string() : listing.substr(at + id.size() + 8, 16);
}

class SweepTest : public ::testing::Test {
  protected:
    void SetUp() override { dir_ = armour_test::fresh_test_folder("sweep"); }
    void TearDown() override { fs::remove_all(dir_); }

    // The tilt scene over friction 0.3/0.5 x 20/50 spheres per clump (the
    // clump's resolution: the scene has no other size of clump to vary).
    fs::path tilt_sweep(const std::string &extra = "") {
        const fs::path file = dir_ / "tilt.toml";
        write(file, "scene = \"" + kSource + "/scenes/tilt_cube.toml\"\n" + extra +
                        "[vary]\n\"material.0.friction\" = [0.3, 0.5]\n\"unit.0.spheres\" = [20, 50]\n");
        return file;
    }

    // The tilt scene run `duration` s at each friction in `frictions` (a TOML
    // list's items): a sweep of short cases, in DIR/`name`.
    fs::path friction_sweep(const std::string &name, const std::string &duration,
                            const std::string &frictions) {
        const fs::path file = dir_ / name;
        write(file, "scene = \"" + kSource + "/scenes/tilt_cube.toml\"\n[set]\n\"run.duration\" = " +
                        duration + "\n[vary]\n\"material.0.friction\" = [" + frictions + "]\n");
        return file;
    }

    // friction_sweep's cases run into `out`; the sweep's output where one failed.
    std::string friction_sweep_error(const std::string &name, const std::string &duration,
                                     const std::string &frictions, const fs::path &out) {
        const Result r = run(kArmour + " sweep " + friction_sweep(name, duration, frictions).string() +
                             " --out " + out.string());
        return r.status == 0 ? std::string() : r.output;
    }

    // The shipped stability scene CI-sized (5 rows), its settle cut to 1 s, at
    // three densities of one seed: three layers for `--settle-only`.
    fs::path layers_sweep() {
        const fs::path file = dir_ / "layers.toml";
        write(
            file,
            "scene = \"" + kSource +
                "/scenes/stability_cubes.toml\"\nseeds = [2]\nseed_key = [\"pattern.0.seed\"]\n"
                "[vary]\n\"unit.0.density\" = [1845, 2050, 2475]\n"
                "[set]\n\"pattern.0.rows\" = 5\n\"fluid.settle_stages\" = 5\n\"fluid.settle_time\" = 1.0\n");
        return file;
    }

    // Every case done once, slide angle atan(mu) within 0.5 degree.
    void expect_tilt_results(const fs::path &out) {
        const std::vector<Row> rows = read_csv(out / "results.csv");
        ASSERT_EQ(rows.size(), 4u) << read_text(out / "results.csv");
        std::map<std::string, int> seen;
        for (const Row &row : rows) {
            EXPECT_EQ(row.at("status"), "done") << row.at("case");
            EXPECT_EQ(row.at("attempts"), "1") << row.at("case");
            const double mu = std::stod(row.at("material.0.friction"));
            ++seen[row.at("material.0.friction") + "/" + row.at("unit.0.spheres")];
            ASSERT_FALSE(row.at("slide_angle_deg").empty()) << row.at("case") << ": the cube never slid";
            EXPECT_NEAR(std::stod(row.at("slide_angle_deg")), std::atan(mu) * 180.0 / kPi, 0.5)
                << row.at("case");
            EXPECT_GT(std::stod(row.at("wall_seconds")), 0.0);
            // Which machine and which maths made the realisation, as its own summary says.
            const json own = json::parse(read_text(out / "cases" / row.at("case") / "run" / "summary.json"));
            EXPECT_EQ(row.at("arithmetic"), own.at("arithmetic").get<std::string>()) << row.at("case");
            EXPECT_EQ(row.at("arithmetic").size(), 16u) << row.at("case");
            EXPECT_FALSE(row.at("host").empty()) << row.at("case");
        }
        EXPECT_EQ(seen.size(), 4u);
        EXPECT_TRUE(fs::exists(out / "cases" / "friction-0.3_spheres-20" / "run" / "summary.json"));
        const json summary = json::parse(read_text(out / "summary.json"));
        EXPECT_EQ(summary["done"], 4);
        EXPECT_EQ(summary["failed"], 0);
        const std::string report = read_text(out / "report.md");
        EXPECT_NE(report.find("figures/slide_angle_deg_vs_material.0.friction.png"), std::string::npos)
            << report;
        EXPECT_TRUE(fs::exists(out / "figures" / "slide_angle_deg_vs_material.0.friction.png"));
    }

    fs::path dir_;
};

TEST_F(SweepTest, LocalTiltSweepFollowsAtanMuAndResumesWithoutRerunning) {
    const fs::path sweep = tilt_sweep(), out = dir_ / "out";
    const std::string command = kArmour + " sweep " + sweep.string() + " --out " + out.string() + " --jobs 2";
    const Result first = run(command);
    ASSERT_EQ(first.status, 0) << first.output;
    expect_tilt_results(out);
    EXPECT_NE(first.output.find("sweep: 4/4 done, 0 running, 0 failed, 0 pending"), std::string::npos)
        << first.output;

    // The same command again: every case is done with the same scene, none runs.
    const Result again = run(command);
    ASSERT_EQ(again.status, 0) << again.output;
    EXPECT_NE(again.output.find("4 cases, 0 to run, 4 done before"), std::string::npos) << again.output;
    expect_tilt_results(out); // attempts still 1
}

TEST_F(SweepTest, DryRunChecksEveryCaseAndWritesNothing) {
    const Result r =
        run(kArmour + " sweep " + tilt_sweep().string() + " --out " + (dir_ / "out").string() + " --dry-run");
    ASSERT_EQ(r.status, 0) << r.output;
    for (const char *id : {"friction-0.3_spheres-20", "friction-0.3_spheres-50", "friction-0.5_spheres-20",
                           "friction-0.5_spheres-50"})
        EXPECT_NE(r.output.find(id), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "out"));
}

// --set reaches every case after the sweep file's [set]: the cases' scenes
// (their hashes) change, and a longer duration in [set] is overridden.
TEST_F(SweepTest, SetOverridesEveryCaseAfterTheFilesSet) {
    const fs::path sweep = tilt_sweep("[set]\n\"run.duration\" = 8.0\n");
    const std::string dry =
        kArmour + " sweep " + sweep.string() + " --out " + (dir_ / "out").string() + " --dry-run";
    const Result plain = run(dry), shorter = run(dry + " --set run.duration=6");
    ASSERT_EQ(plain.status, 0) << plain.output;
    ASSERT_EQ(shorter.status, 0) << shorter.output;
    for (const char *id : {"friction-0.3_spheres-20", "friction-0.5_spheres-50"}) {
        ASSERT_FALSE(listed_hash(plain.output, id).empty()) << plain.output;
        EXPECT_NE(listed_hash(plain.output, id), listed_hash(shorter.output, id)) << id;
    }
    // A real case runs the duration --set gives, not [set]'s.
    const fs::path one = dir_ / "one.toml", out = dir_ / "one";
    write(one, "scene = \"" + kSource + "/scenes/tilt_cube.toml\"\n[set]\n\"run.duration\" = 8.0\n" +
                   "[vary]\n\"material.0.friction\" = [0.5]\n");
    const Result r =
        run(kArmour + " sweep " + one.string() + " --out " + out.string() + " --set run.duration=6");
    ASSERT_EQ(r.status, 0) << r.output;
    const json summary = json::parse(read_text(out / "cases" / "friction-0.5" / "run" / "summary.json"));
    EXPECT_NEAR(summary["simulated_seconds"].get<double>(), 6.0, 0.01);
    const json plan = json::parse(read_text(out / "sweep.json"));
    EXPECT_EQ(plan["set"], json({"run.duration=8.0", "run.duration=6"}));
    // The copy of the sweep file is the file as written, then a comment naming the --set:
    // a kept copy says how its cases were made, and still reads as the same sweep.
    const std::string copy = read_text(out / "sweep.toml"), file = read_text(one);
    EXPECT_EQ(copy.substr(0, file.size()), file);
    EXPECT_NE(copy.find("\n# armour sweep ran this file with --set 'run.duration=6'\n", file.size()),
              std::string::npos)
        << copy;
    const std::string listing = " --out " + (dir_ / "listed").string() + " --dry-run";
    const Result of_file = run(kArmour + " sweep " + one.string() + listing),
                 of_copy = run(kArmour + " sweep " + (out / "sweep.toml").string() + listing);
    ASSERT_EQ(of_copy.status, 0) << of_copy.output;
    EXPECT_EQ(listed_hash(of_copy.output, "friction-0.5"), listed_hash(of_file.output, "friction-0.5"));
    EXPECT_FALSE(listed_hash(of_file.output, "friction-0.5").empty()) << of_file.output;
}

// --seeds replaces the sweep file's seeds: --seeds 1,2,3 on a file of [1, 2]
// lists the same two realisations under the same scene hashes (so a folder's
// done cases stay done) and a third; a seed given twice, a negative one, or
// --seeds with --collect is one error line, nothing written.
TEST_F(SweepTest, SeedsOnTheCommandLineAddRealisationsAndKeepTheOthers) {
    const fs::path sweep = dir_ / "seeded.toml";
    write(sweep, "scene = \"" + kSource +
                     "/scenes/slope_cubes.toml\"\nseeds = [1, 2]\nseed_key = \"drop.0.seed\"\n" +
                     "[vary]\n\"material.0.friction\" = [0.3]\n");
    const std::string dry =
        kArmour + " sweep " + sweep.string() + " --out " + (dir_ / "out").string() + " --dry-run";
    const Result file = run(dry), more = run(dry + " --seeds 1,2,3");
    ASSERT_EQ(file.status, 0) << file.output;
    ASSERT_EQ(more.status, 0) << more.output;
    for (const char *id : {"friction-0.3_seed-1", "friction-0.3_seed-2"}) {
        ASSERT_FALSE(listed_hash(file.output, id).empty()) << file.output;
        EXPECT_EQ(listed_hash(file.output, id), listed_hash(more.output, id)) << id;
    }
    EXPECT_TRUE(listed_hash(file.output, "friction-0.3_seed-3").empty()) << file.output;
    EXPECT_FALSE(listed_hash(more.output, "friction-0.3_seed-3").empty()) << more.output;
    EXPECT_NE(listed_hash(more.output, "friction-0.3_seed-3"),
              listed_hash(more.output, "friction-0.3_seed-1"));
    EXPECT_NE(more.output.find("3 cases of"), std::string::npos) << more.output;

    // The sweep file may follow the option: one comma-separated word is all --seeds takes.
    const Result before_file = run(kArmour + " sweep --seeds 1,2,3 " + sweep.string() + " --out " +
                                   (dir_ / "out").string() + " --dry-run");
    EXPECT_EQ(before_file.status, 0) << before_file.output;
    EXPECT_EQ(listed_hash(before_file.output, "friction-0.3_seed-3"),
              listed_hash(more.output, "friction-0.3_seed-3"));
    const Result twice = run(dry + " --seeds 1,2,1");
    EXPECT_EQ(twice.status, 2);
    EXPECT_NE(twice.output.find("armour: error: --seeds: seed 1 given twice"), std::string::npos)
        << twice.output;
    const Result negative = run(dry + " --seeds=-1");
    EXPECT_EQ(negative.status, 2) << negative.output;
    EXPECT_NE(negative.output.find("armour: error: --seeds: must be >= 0 (got -1)"), std::string::npos)
        << negative.output;
    const Result collect = run(kArmour + " sweep --collect " + (dir_ / "out").string() + " --seeds 4");
    EXPECT_EQ(collect.status, 2);
    EXPECT_NE(collect.output.find("no --seeds"), std::string::npos) << collect.output;
    EXPECT_FALSE(fs::exists(dir_ / "out"));
}

// --np sets every case's MPI ranks in place of the file's [run] np: the case
// runs on them (the coupled run's summary says so) and the sweep file's copy
// names them; what counts as done does not change (the same scene hashes, and
// the finished case is not run again by the sweep without --np). The case is
// the Slurm test's: a concrete cube sinking in still water, 0.4 s, ~3 s a run.
TEST_F(SweepTest, NpSetsTheRanksOfEveryCaseAndNotWhatCountsAsDone) {
#ifndef ARMOUR_HAS_OPENFOAM
    GTEST_SKIP() << "needs the OpenFOAM coupling (Debian's openfoam)";
#endif
    const fs::path sweep = dir_ / "ranks.toml", out = dir_ / "out";
    write(sweep, "scene = \"" + kSource +
                     "/scenes/still_water_cube.toml\"\n[vary]\n\"fluid.penalty\" = [1e4]\n" +
                     "[set]\n\"run.engine\" = \"liggghts\"\n\"body.0.position\" = [0.0, 0.0, 0.17]\n" +
                     "\"run.duration\" = 0.4\n");
    const std::string command = kArmour + " sweep " + sweep.string() + " --out " + out.string();
    const Result as_file = run(command + " --dry-run"), two = run(command + " --dry-run --np 2");
    ASSERT_EQ(two.status, 0) << two.output;
    ASSERT_FALSE(listed_hash(as_file.output, "penalty-10000.0").empty()) << as_file.output;
    EXPECT_EQ(listed_hash(two.output, "penalty-10000.0"), listed_hash(as_file.output, "penalty-10000.0"));

    const Result r = run(command + " --np 2");
    ASSERT_EQ(r.status, 0) << r.output;
    const fs::path case_dir = out / "cases" / "penalty-10000.0";
    EXPECT_EQ(json::parse(read_text(case_dir / "plan.json"))["np"], 2);
    EXPECT_EQ(json::parse(read_text(case_dir / "run" / "summary.json"))["fluid"]["np"], 2);
    EXPECT_NE(read_text(out / "sweep.toml").find("\n# armour sweep ran this file with --np 2\n"),
              std::string::npos)
        << read_text(out / "sweep.toml");
    const std::string record = read_text(case_dir / "case.json");
    const Result again = run(command);
    ASSERT_EQ(again.status, 0) << again.output;
    EXPECT_EQ(read_text(case_dir / "case.json"), record) << "the finished case ran again";

    // Refused in one line before anything is written: a scene without [fluid], 0 ranks,
    // with --settle-only (a settle runs on one rank), with --collect.
    const fs::path none = dir_ / "none";
    for (const auto &[options, expected] : std::vector<std::pair<std::string, std::string>>{
             {tilt_sweep().string() + " --np 2", "armour: error: --np: case "},
             {sweep.string() + " --np 0", "armour: error: --np: must be >= 1 (got 0)"},
             {sweep.string() + " --np 2 --settle-only", "armour: error: --np: not with --settle-only"}}) {
        const Result refused = run(kArmour + " sweep " + options + " --out " + none.string());
        EXPECT_EQ(refused.status, 2) << refused.output;
        EXPECT_EQ(refused.output.rfind(expected, 0), 0u) << refused.output;
        EXPECT_EQ(std::count(refused.output.begin(), refused.output.end(), '\n'), 1) << refused.output;
    }
    const Result collect = run(kArmour + " sweep --collect " + out.string() + " --np 2");
    EXPECT_EQ(collect.status, 2);
    EXPECT_NE(collect.output.find("no --np"), std::string::npos) << collect.output;
    EXPECT_FALSE(fs::exists(none));
}

// A stability curve's sweep over a test series (docs/stability.md, "Test
// series"): seeds reach each step's train and the layer (seed_key as a list),
// [vary] a step's height; every case is a different scene, and a seed key
// naming a step the series does not have is refused before anything runs.
TEST_F(SweepTest, ASeriesSweepVariesTheStepsSeedsAndTheLayersSeed) {
    const fs::path scene = dir_ / "series.toml", sweep = dir_ / "series_sweep.toml";
    write(
        scene,
        read_text(fs::path(kSource) / "scenes" / "stability_cubes.toml") +
            "\n[[series]]\nHs = 0.10\nTp = 1.8\nwaves = 50\n\n[[series]]\nHs = 0.12\nTp = 1.8\nwaves = 50\n");
    const auto sweep_file = [&](const std::string &keys) {
        write(sweep, "scene = \"" + scene.string() + "\"\nseeds = [1, 2]\nseed_key = [" + keys +
                         "]\n[vary]\n\"series.1.Hs\" = [0.11, 0.12]\n");
        return kArmour + " sweep " + sweep.string() + " --out " + (dir_ / "out").string() + " --dry-run";
    };
    // The steps' seeds alone: the cases differ only if they reach the steps.
    const Result r = run(sweep_file(R"("series.0.seed", "series.1.seed")"));
    ASSERT_EQ(r.status, 0) << r.output;
    std::set<std::string> hashes;
    for (const char *id : {"Hs-0.11_seed-1", "Hs-0.11_seed-2", "Hs-0.12_seed-1", "Hs-0.12_seed-2"}) {
        ASSERT_FALSE(listed_hash(r.output, id).empty()) << r.output;
        hashes.insert(listed_hash(r.output, id));
    }
    EXPECT_EQ(hashes.size(), 4u) << r.output;
    // Realisation-major: every height's first realisation before any second,
    // so a sweep stopped part-way already spans the curve.
    EXPECT_LT(r.output.find("Hs-0.12_seed-1  scene "), r.output.find("Hs-0.11_seed-2  scene ")) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "out"));
    const Result with_layer = run(sweep_file(R"("series.0.seed", "series.1.seed", "pattern.0.seed")"));
    EXPECT_EQ(with_layer.status, 0) << with_layer.output;
    const Result bad = run(sweep_file(R"("series.2.seed")"));
    EXPECT_EQ(bad.status, 2) << bad.output;
    EXPECT_NE(bad.output.find("series.2.seed"), std::string::npos) << bad.output;
    EXPECT_FALSE(fs::exists(dir_ / "out"));
}

// `--settle-only`: each case is `armour run --settle-only` of its scene (the
// layer its waves would meet, pose for pose), results.csv holds the layers'
// figures, the same command again skips the settled cases, and a sweep with
// waves into the same folder is refused (a settled case is no run with waves).
TEST_F(SweepTest, SettleOnlySweepSettlesEachCasesLayerAlone) {
    const fs::path sweep = layers_sweep(), out = dir_ / "out";
    const std::string command = kArmour + " sweep " + sweep.string() + " --out " + out.string();
    const Result r = run(command + " --settle-only --jobs 2");
    ASSERT_EQ(r.status, 0) << r.output;
    const std::vector<Row> rows = read_csv(out / "results.csv");
    ASSERT_EQ(rows.size(), 3u) << read_text(out / "results.csv");
    for (const Row &row : rows) {
        EXPECT_EQ(row.at("status"), "done");
        // A settled double layer of cubes (the Rock Manual's band: 0.35-0.55).
        const double porosity = std::stod(row.at("settled_layer.porosity"));
        EXPECT_GT(porosity, 0.35) << row.at("case");
        EXPECT_LT(porosity, 0.55) << row.at("case");
        EXPECT_GT(std::stod(row.at("settled_layer.packing_density")), 0.9) << row.at("case");
        EXPECT_GE(std::stoi(row.at("settled_layer.units_at_foot")), 0) << row.at("case");
        const fs::path run_dir = out / "cases" / row.at("case") / "run";
        EXPECT_FALSE(fs::exists(run_dir / "case")) << "a settle alone builds no fluid case";
        EXPECT_FALSE(fs::exists(run_dir / "bodies.h5"));
    }
    // The report's table heads with the layers' figures (no damage analysis ran).
    EXPECT_NE(read_text(out / "report.md").find("| settled_layer.porosity | settled_layer.packing_density |"),
              std::string::npos)
        << read_text(out / "report.md");
    // The case is the command a user runs on its scene: the same layer to the last digit.
    const fs::path case_dir = out / "cases" / "density-1845_seed-2";
    const Result alone = run(kArmour + " run " + (case_dir / "scene.toml").string() + " --out " +
                             (dir_ / "alone").string() + " --settle-only");
    ASSERT_EQ(alone.status, 0) << alone.output;
    const auto bodies = [](const fs::path &run_dir) {
        const std::string text = read_text(run_dir / "settle" / "scene.settled.toml");
        const auto from = text.find("[[body]]");
        return from == std::string::npos ? std::string() : text.substr(from, text.find("[[porous]]") - from);
    };
    EXPECT_FALSE(bodies(dir_ / "alone").empty());
    EXPECT_EQ(bodies(case_dir / "run"), bodies(dir_ / "alone"));
    EXPECT_NE(bodies(case_dir / "run"), bodies(out / "cases" / "density-2050_seed-2" / "run"))
        << "each density settles its own layer";
    const Result again = run(command + " --settle-only");
    EXPECT_EQ(again.status, 0) << again.output;
    EXPECT_NE(again.output.find("0 to run, 3 done before"), std::string::npos) << again.output;
    // Waves into the settles' folder, or settles beside kept wave runs: refused, nothing touched.
    const std::string before = read_text(out / "results.csv");
    for (const std::string &bad : {command, command + " --settle-only --kept " + out.string()}) {
        const Result refused = run(bad);
        EXPECT_EQ(refused.status, 2) << refused.output;
        EXPECT_EQ(refused.output.rfind("armour: error: ", 0), 0u) << refused.output;
        EXPECT_EQ(std::count(refused.output.begin(), refused.output.end(), '\n'), 1) << refused.output;
        EXPECT_NE(refused.output.find("--settle-only"), std::string::npos) << refused.output;
    }
    EXPECT_EQ(read_text(out / "results.csv"), before);
    EXPECT_TRUE(fs::exists(case_dir / "run" / "settle" / "scene.settled.toml"));
    // A scene that does not settle: refused before anything runs, naming the case and key.
    const Result no_settle = run(kArmour + " sweep " + tilt_sweep().string() + " --out " +
                                 (dir_ / "tilt").string() + " --settle-only");
    EXPECT_EQ(no_settle.status, 2) << no_settle.output;
    EXPECT_EQ(std::count(no_settle.output.begin(), no_settle.output.end(), '\n'), 1) << no_settle.output;
    EXPECT_NE(no_settle.output.find("fluid.settle_time"), std::string::npos) << no_settle.output;
    EXPECT_FALSE(fs::exists(dir_ / "tilt"));
}

// studies/settled_layers.py on a settle-only sweep: each layer's proud units
// are seats.py's, the densities paired seed by seed against --against's, and
// with --curve a kept curve's cases joined to the layers they ran on: with
// each case's displaced units set to its layer's proud units (expected 1
// each), the rank correlation of the two is 1; a case whose body sits 5 mm
// from the layer's seat is refused.
TEST_F(SweepTest, SettledLayersCountEachLayersWeakSeatsAndJoinACurve) {
    const fs::path sweep = layers_sweep(), out = dir_ / "out";
    const Result r = run(kArmour + " sweep " + sweep.string() + " --out " + out.string() + " --settle-only");
    ASSERT_EQ(r.status, 0) << r.output;
    const std::string python = "/usr/bin/python3 " + kSource + "/studies/";
    // Each layer's seats as seats.py measures them, and a kept curve made of them.
    std::map<std::string, int> proud;
    std::string results =
        "case,unit.0.density,seed,status,Ns,N_od,units_displaced,units_displaced_van_der_meer,"
        "waves.waves,s_om\n";
    for (const std::string density : {"1845", "2050", "2475"}) {
        const std::string id = "density-" + density + "_seed-2";
        const fs::path seats = dir_ / ("seats-" + density);
        const Result s = run(python + "seats.py --layer 2=" +
                             (out / "cases" / id / "run" / "settle" / "scene.settled.toml").string() +
                             " --out " + seats.string());
        ASSERT_EQ(s.status, 0) << s.output;
        std::string damage = "# damage per unit\nbody,unit,s_m,y_m,final_displacement_over_Dn,displaced\n";
        const std::vector<Row> seat_rows = read_csv(seats / "seats.csv");
        ASSERT_EQ(seat_rows.size(), 45u);
        for (const Row &seat : seat_rows) {
            proud[density] += std::stod(seat.at("above_neighbours_Dn")) > 0.0;
            damage += seat.at("body") + ",cube," + seat.at("s_m") + "," + seat.at("y_m") + ",0.01,0\n";
        }
        write(dir_ / "curve" / "cases" / id / "run" / "damage.csv", damage);
        results +=
            id + "," + density + ".0,2,done,3.0,0.5," + std::to_string(proud[density]) + ",1.0,26,0.03\n";
    }
    write(dir_ / "curve" / "results.csv", results);
    const std::string script = python + "settled_layers.py " + out.string() + " --against 2050 --curve " +
                               (dir_ / "curve").string() + " --out " + (dir_ / "sl").string();
    const Result sl = run(script);
    ASSERT_EQ(sl.status, 0) << sl.output;
    const std::vector<Row> sweep_rows = read_csv(out / "results.csv");
    std::map<std::string, double> porosity;
    for (const Row &row : sweep_rows)
        porosity[row.at("unit.0.density").substr(0, 4)] = std::stod(row.at("settled_layer.porosity"));
    const std::vector<Row> layers = read_csv(dir_ / "sl" / "layers.csv");
    ASSERT_EQ(layers.size(), 3u) << sl.output;
    for (const Row &layer : layers) {
        const std::string density = layer.at("case").substr(8, 4);
        EXPECT_EQ(std::stoi(layer.at("proud_units")), proud[density]) << layer.at("case");
        EXPECT_NEAR(std::stod(layer.at("porosity")), porosity[density], 1e-5) << layer.at("case");
    }
    const json summary = json::parse(read_text(dir_ / "sl" / "summary.json"));
    EXPECT_NEAR(summary["paired"]["1845"]["porosity"]["mean_difference"].get<double>(),
                porosity["1845"] - porosity["2050"], 1e-5);
    ASSERT_FALSE(proud["1845"] == proud["2050"] && proud["2050"] == proud["2475"])
        << "three layers as proud as each other: no rank to correlate";
    EXPECT_NEAR(summary["curve"]["correlations"]["proud_units"]["spearman"].get<double>(), 1.0, 1e-12);
    // A case that did not run on the layer settled again.
    {
        const fs::path damage = dir_ / "curve" / "cases" / "density-2475_seed-2" / "run" / "damage.csv";
        std::string text = read_text(damage);
        const std::size_t row = text.find("\n0,cube,") + 8;
        const std::size_t comma = text.find(',', row);
        text.replace(row, comma - row, std::to_string(std::stod(text.substr(row, comma - row)) + 0.005));
        write(damage, text);
    }
    const Result moved = run(script);
    EXPECT_EQ(moved.status, 2) << moved.output;
    EXPECT_NE(moved.output.find("armour: error: "), std::string::npos) << moved.output;
    EXPECT_NE(moved.output.find("density-2475_seed-2"), std::string::npos) << moved.output;
}

// A case's scene hash is of the resolved scene's keys, not of where the scene
// file lies: the same sweep from another checkout (or a cluster's copy) skips
// the cases done. A case recorded under the hash earlier versions took (over
// the text with its header, which names the scene's path) is still done.
TEST_F(SweepTest, DoneCasesStayDoneFromAnotherFolderAndUnderTheEarlierHash) {
    const auto sweep_in = [&](const std::string &folder) {
        const fs::path scene = dir_ / folder / "tilt_cube.toml", sweep = dir_ / folder / "tilt.toml";
        fs::create_directories(scene.parent_path());
        fs::copy_file(fs::path(kSource) / "scenes" / "tilt_cube.toml", scene,
                      fs::copy_options::overwrite_existing);
        write(sweep, "scene = \"" + scene.string() + "\"\n[set]\n\"run.duration\" = 3.0\n" +
                         "[vary]\n\"material.0.friction\" = [0.5]\n");
        return kArmour + " sweep " + sweep.string() + " --out " + (dir_ / "out").string();
    };
    // The listing's action for the one case: "run" or "skip: done".
    const auto action = [&](const std::string &folder) {
        const Result r = run(sweep_in(folder) + " --dry-run");
        const std::size_t at = r.output.find("friction-0.5  scene ");
        EXPECT_EQ(r.status, 0) << r.output;
        if (at == std::string::npos)
            return "no listing: " + r.output;
        const std::size_t from = at + std::string("friction-0.5  scene ").size() + 18;
        return r.output.substr(from, r.output.find('\n', from) - from);
    };
    const Result first = run(sweep_in("a"));
    ASSERT_EQ(first.status, 0) << first.output;
    EXPECT_EQ(action("b"), "skip: done");

    const fs::path record = dir_ / "out" / "cases" / "friction-0.5" / "case.json";
    const json plan = json::parse(read_text(record.parent_path() / "plan.json"));
    ASSERT_TRUE(plan.contains("earlier_scene_hash")) << plan.dump();
    ASSERT_NE(plan["earlier_scene_hash"], plan["scene_hash"]);
    json r = json::parse(read_text(record));
    r["scene_hash"] = plan["earlier_scene_hash"]; // as an earlier version recorded it, from folder a
    write(record, r.dump(2));
    EXPECT_EQ(action("a"), "skip: done");
    r["scene_hash"] = "0123456789abcdef"; // another scene
    write(record, r.dump(2));
    EXPECT_EQ(action("a"), "run");
}

// More waves for a finished sweep: a longer run.duration (a key a resume may
// change) takes each case on from its run's last checkpoint instead of from
// t = 0; another scene key still runs it from the start.
TEST_F(SweepTest, ALongerRunGoesOnFromEachCasesLastCheckpoint) {
    const fs::path sweep = dir_ / "tilt.toml", out = dir_ / "out";
    const auto run_with = [&](const std::string &set) {
        write(sweep, "scene = \"" + kSource +
                         "/scenes/tilt_cube.toml\"\n[set]\n\"run.checkpoint_interval\" = 1.0\n" + set +
                         "[vary]\n\"material.0.friction\" = [0.5]\n");
        return run(kArmour + " sweep " + sweep.string() + " --out " + out.string());
    };
    const fs::path record = out / "cases" / "friction-0.5" / "case.json";
    const auto simulated = [&] {
        return json::parse(read_text(out / "cases" / "friction-0.5" / "run" / "summary.json"))
            .at("simulated_seconds")
            .get<double>();
    };
    const Result first = run_with("\"run.duration\" = 3.0\n");
    ASSERT_EQ(first.status, 0) << first.output;
    EXPECT_EQ(json::parse(read_text(record)).at("resumed_from"), 0.0);

    const Result longer = run_with("\"run.duration\" = 4.0\n");
    ASSERT_EQ(longer.status, 0) << longer.output;
    json r = json::parse(read_text(record));
    EXPECT_EQ(r.at("status"), "done");
    EXPECT_EQ(r.at("attempts"), 2);
    EXPECT_NEAR(r.at("resumed_from").get<double>(), 2.0, 1e-3) << "the 3 s run's last checkpoint";
    EXPECT_NEAR(simulated(), 4.0, 1e-3);

    const Result other = run_with("\"run.duration\" = 4.0\n\"material.0.restitution\" = 0.4\n");
    ASSERT_EQ(other.status, 0) << other.output;
    r = json::parse(read_text(record));
    EXPECT_EQ(r.at("attempts"), 3);
    EXPECT_EQ(r.at("resumed_from"), 0.0) << "another material: not the run that checkpointed";
    EXPECT_NEAR(simulated(), 4.0, 1e-3);
}

// A curve's cases outlive the machine they ran on: the small results that
// studies/keep_results.py keeps in the repository let a sweep in a new folder
// (another machine, the run folder lost) take those cases as done and run
// only the others; a kept case of another scene runs again.
TEST_F(SweepTest, KeptResultsLetASweepElsewhereRunOnlyTheOtherCases) {
    const Result first = run(kArmour + " sweep " + friction_sweep("one.toml", "3.0", "0.5").string() +
                             " --out " + (dir_ / "first").string());
    ASSERT_EQ(first.status, 0) << first.output;
    const fs::path kept = dir_ / "kept";
    const Result keep = run("/usr/bin/python3 " + kSource + "/studies/keep_results.py " +
                            (dir_ / "first").string() + " " + kept.string());
    ASSERT_EQ(keep.status, 0) << keep.output;
    ASSERT_TRUE(fs::exists(kept / "cases" / "friction-0.5" / "case.json"));

    const std::string two = friction_sweep("two.toml", "3.0", "0.3, 0.5").string();
    const fs::path out = dir_ / "elsewhere";
    const Result resumed =
        run(kArmour + " sweep " + two + " --out " + out.string() + " --kept " + kept.string());
    ASSERT_EQ(resumed.status, 0) << resumed.output;
    EXPECT_NE(resumed.output.find("2 cases, 1 to run, 1 done before"), std::string::npos) << resumed.output;
    std::map<std::string, Row> rows;
    for (const Row &row : read_csv(out / "results.csv"))
        rows[row.at("case")] = row;
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows["friction-0.3"].at("status"), "done");
    EXPECT_EQ(rows["friction-0.5"].at("status"), "done");
    EXPECT_EQ(rows["friction-0.5"].at("attempts"), "1"); // the kept run's record, not a rerun
    EXPECT_EQ(read_text(out / "cases" / "friction-0.5" / "run" / "summary.json"),
              read_text(kept / "cases" / "friction-0.5" / "run" / "summary.json"));
    EXPECT_EQ(rows["friction-0.5"].at("steps"), read_csv(dir_ / "first" / "results.csv").at(0).at("steps"));
    EXPECT_FALSE(rows["friction-0.3"].at("steps").empty()); // the case the kept folder lacked ran here

    // Another scene (a shorter run): the kept case is not this sweep's.
    const Result other =
        run(kArmour + " sweep " + friction_sweep("short.toml", "2.0", "0.5").string() + " --out " +
            (dir_ / "other").string() + " --kept " + kept.string() + " --dry-run");
    ASSERT_EQ(other.status, 0) << other.output;
    EXPECT_NE(other.output.find("1 would run"), std::string::npos) << other.output;

    // A folder that keep_results.py did not write: one error line, nothing made.
    const Result bad = run(kArmour + " sweep " + two + " --out " + (dir_ / "bad").string() + " --kept " +
                           (dir_ / "nowhere").string());
    EXPECT_EQ(bad.status, 2) << bad.output;
    EXPECT_NE(bad.output.find("armour: error: --kept"), std::string::npos) << bad.output;
    EXPECT_FALSE(fs::exists(dir_ / "bad"));
}

// A sweep still running rewrites its tables, report.md and figures as its
// cases end (the charts in place): while an armour command holds the folder's
// lock, keep_results.py keeps nothing (one error line naming the holder, exit
// 2, DEST not made); once the lock is free the same command keeps the folder.
TEST_F(SweepTest, KeepResultsRefusesASweepStillRunning) {
    const fs::path file = friction_sweep("one.toml", "0.5", "0.5");
    const fs::path out = dir_ / "running";
    const Result sweep = run(kArmour + " sweep " + file.string() + " --out " + out.string());
    ASSERT_EQ(sweep.status, 0) << sweep.output;
    const std::string keep = "/usr/bin/python3 " + kSource + "/studies/keep_results.py " + out.string() +
                             " " + (dir_ / "kept").string();
    // The lock as a running sweep holds it (results/output_folder.cpp): its
    // pid in DIR/.armour-lock, the file flock()ed, removed when it ends.
    const fs::path lock = out / ".armour-lock";
    const int fd = ::open(lock.c_str(), O_CREAT | O_RDWR, 0644);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
    const std::string pid = std::to_string(::getpid());
    ASSERT_EQ(::write(fd, pid.data(), pid.size()), static_cast<ssize_t>(pid.size()));
    const Result refused = run(keep);
    ::close(fd);
    fs::remove(lock);
    EXPECT_EQ(refused.status, 2) << refused.output;
    const std::string why =
        "armour: error: " + out.string() + ": in use by another armour command (pid " + pid + ")";
    EXPECT_EQ(refused.output.rfind(why, 0), 0u) << refused.output;
    EXPECT_EQ(std::count(refused.output.begin(), refused.output.end(), '\n'), 1) << refused.output;
    EXPECT_FALSE(fs::exists(dir_ / "kept"));
    const Result kept = run(keep);
    EXPECT_EQ(kept.status, 0) << kept.output;
    EXPECT_TRUE(fs::exists(dir_ / "kept" / "cases" / "friction-0.5" / "case.json"));
}

// Kept again from a sweep with fewer cases, DEST loses the files of the case
// the sweep no longer has, and nothing keep_results.py did not write: a
// chart and a note of one's own in DEST's figures/ and cases/ stay. A DEST
// kept before kept_files.txt existed: the files of the names a keep writes,
// and the charts its report.md shows, count as its own.
TEST_F(SweepTest, KeepingAgainRemovesOnlyWhatAKeepWrote) {
    const fs::path two = dir_ / "two", one = dir_ / "one", dest = dir_ / "kept";
    ASSERT_EQ(friction_sweep_error("two.toml", "0.5", "0.3, 0.5", two), "");
    ASSERT_EQ(friction_sweep_error("one.toml", "0.5", "0.5", one), "");
    const std::string keep = "/usr/bin/python3 " + kSource + "/studies/keep_results.py ";
    for (const bool listed : {true, false}) {
        SCOPED_TRACE(listed ? "with kept_files.txt" : "kept before kept_files.txt");
        const Result first = run(keep + two.string() + " " + dest.string());
        ASSERT_EQ(first.status, 0) << first.output;
        ASSERT_TRUE(fs::exists(dest / "cases" / "friction-0.3" / "run" / "summary.json"));
        if (!listed)
            fs::remove(dest / "kept_files.txt");
        write(dest / "figures" / "mine.png", "a chart of one's own");
        write(dest / "cases" / "notes.txt", "a note of one's own");
        const Result again = run(keep + one.string() + " " + dest.string());
        ASSERT_EQ(again.status, 0) << again.output;
        EXPECT_FALSE(fs::exists(dest / "cases" / "friction-0.3")) << "the case the sweep no longer has";
        EXPECT_TRUE(fs::exists(dest / "cases" / "friction-0.5" / "run" / "summary.json"));
        EXPECT_EQ(read_text(dest / "figures" / "mine.png"), "a chart of one's own");
        EXPECT_EQ(read_text(dest / "cases" / "notes.txt"), "a note of one's own");
        const std::string listed_files = read_text(dest / "kept_files.txt");
        EXPECT_NE(listed_files.find("cases/friction-0.5/case.json\n"), std::string::npos) << listed_files;
        EXPECT_EQ(listed_files.find("friction-0.3"), std::string::npos) << listed_files;
        EXPECT_EQ(listed_files.find("mine.png"), std::string::npos) << listed_files;
        EXPECT_EQ(read_csv(dest / "results.csv").size(), 1u);
    }
}

// A keep cut short leaves DEST as it was: here a case's file it cannot read
// (a folder where summary.json should be) stops it after it has written the
// tables and the other files; one error line naming the file, exit 2, every
// file of the earlier keep as it was, no temporary file, no new folder. So
// does a folder in DEST where the keep writes a file.
TEST_F(SweepTest, KeepCutShortLeavesTheKeptFolderAsItWas) {
    const fs::path two = dir_ / "two", three = dir_ / "three", dest = dir_ / "kept";
    ASSERT_EQ(friction_sweep_error("two.toml", "0.5", "0.3, 0.5", two), "");
    ASSERT_EQ(friction_sweep_error("three.toml", "0.5", "0.3, 0.5, 0.7", three), "");
    const std::string keep = "/usr/bin/python3 " + kSource + "/studies/keep_results.py ";
    ASSERT_EQ(run(keep + two.string() + " " + dest.string()).status, 0);
    std::map<std::string, std::string> before;
    for (const auto &entry : fs::recursive_directory_iterator(dest))
        if (entry.is_regular_file())
            before[fs::relative(entry.path(), dest).string()] = read_text(entry.path());

    const fs::path unreadable = three / "cases" / "friction-0.7" / "run" / "summary.json";
    fs::remove(unreadable);
    fs::create_directory(unreadable);
    const Result cut = run(keep + three.string() + " " + dest.string());
    EXPECT_EQ(cut.status, 2) << cut.output;
    EXPECT_NE(cut.output.find("armour: error: " + unreadable.string() + ": "), std::string::npos)
        << cut.output;
    EXPECT_NE(cut.output.find(dest.string() + " left as it was"), std::string::npos) << cut.output;
    EXPECT_EQ(cut.output.find("Traceback"), std::string::npos) << cut.output;
    std::map<std::string, std::string> after;
    for (const auto &entry : fs::recursive_directory_iterator(dest)) {
        EXPECT_FALSE(entry.is_directory() && entry.path().filename() == "friction-0.7") << entry.path();
        if (entry.is_regular_file())
            after[fs::relative(entry.path(), dest).string()] = read_text(entry.path());
    }
    EXPECT_EQ(after, before) << "every file as the first keep wrote it, no .keeping file left";
    EXPECT_EQ(read_csv(dest / "results.csv").size(), 2u);

    // A folder where the keep writes a file: refused before any file is renamed over DEST's.
    fs::remove(unreadable);
    ASSERT_EQ(friction_sweep_error("three.toml", "0.5", "0.3, 0.5, 0.7", three), "");
    fs::remove(dest / "report.md");
    fs::create_directory(dest / "report.md");
    before.erase("report.md");
    const Result blocked = run(keep + three.string() + " " + dest.string());
    EXPECT_EQ(blocked.status, 2) << blocked.output;
    EXPECT_NE(blocked.output.find("armour: error: " + (dest / "report.md").string() + ": "),
              std::string::npos)
        << blocked.output;
    after.clear();
    for (const auto &entry : fs::recursive_directory_iterator(dest))
        if (entry.is_regular_file())
            after[fs::relative(entry.path(), dest).string()] = read_text(entry.path());
    EXPECT_EQ(after, before) << "summary.json and the rest untouched";
}

// Realisations run one by one as plain `armour run`s (a validation's check)
// are kept as a sweep's cases: `keep_results.py --runs DEST RUN...` writes a
// results.csv row per run (its seed from the run's scene, its figures from
// its summary.json, `waves` as waves.<name>) and each run's damage.csv under
// cases/<run>/run/, so compare_curves.py counts them against Van der Meer as
// one curve. A folder that is not a finished damage run is refused first:
// one error line, DEST not made.
TEST_F(SweepTest, KeptRunsAreReadAsOneCurveOfRealisations) {
    const auto damage_run = [&](const std::string &name, int seed, int displaced, double expected,
                                double ns) {
        const fs::path folder = dir_ / "runs" / name;
        write(folder / "scene.resolved.toml",
              "[waves]\nseed = " + std::to_string(seed) + "\n[[unit]]\nname = \"cube\"\ndensity = 1540.0\n");
        write(folder / "summary.json", "{\"units_displaced\": " + std::to_string(displaced) +
                                           ", \"N_od\": " + std::to_string(displaced / 6.0) +
                                           ", \"units_displaced_van_der_meer\": " + std::to_string(expected) +
                                           ", \"Ns\": " + std::to_string(ns) +
                                           ", \"s_om\": 0.034, \"coupled\": true, \"waves\": {\"waves\": 9, "
                                           "\"incident_height\": 0.115, \"type\": \"irregular\"}}\n");
        write(folder / "damage.csv", "# damage per unit\nbody,unit,s_m,y_m,at_foot,displaced\n"
                                     "0,cube,-0.02,0,1," +
                                         std::string(displaced > 0 ? "1" : "0") + "\n1,cube,0.1,0,0,0\n");
        return folder.string();
    };
    const std::string one = damage_run("seed-1", 1, 2, 3.0, 5.0);
    const std::string two = damage_run("seed-2", 2, 1, 1.0, 6.1);
    const fs::path dest = dir_ / "kept";
    const std::string keep = "/usr/bin/python3 " + kSource + "/studies/keep_results.py --runs ";
    const Result kept = run(keep + dest.string() + " " + one + " " + two);
    ASSERT_EQ(kept.status, 0) << kept.output;
    const std::vector<Row> rows = read_csv(dest / "results.csv");
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0].at("case"), "seed-1");
    EXPECT_EQ(rows[1].at("seed"), "2");
    EXPECT_EQ(rows[1].at("unit.0.density"), "1540");
    EXPECT_EQ(rows[1].at("waves.waves"), "9");
    EXPECT_EQ(rows[0].at("units_displaced"), "2");
    EXPECT_EQ(rows[0].count("coupled"), 0u) << "a flag is not a figure";
    EXPECT_EQ(read_text(dest / "cases" / "seed-2" / "run" / "summary.json"),
              read_text(fs::path(two) / "summary.json"));

    // 3 displaced of 4.0 expected: P(X <= 3 | 4) = 71 e^-4 / 3 = 0.43; the toe row holds both runs'
    // displaced.
    const Result curve = run("/usr/bin/python3 " + kSource + "/studies/compare_curves.py " + dest.string() +
                             " --out " + (dir_ / "curve.png").string());
    ASSERT_EQ(curve.status, 0) << curve.output;
    EXPECT_NE(curve.output.find("all: 3 / 4.0 (P 0.43)"), std::string::npos) << curve.output;
    EXPECT_NE(curve.output.find("from the toe row (seated below the face's foot): 2 of 3"), std::string::npos)
        << curve.output;

    // A run folder without a damage run's summary: refused, nothing made.
    fs::create_directories(dir_ / "runs" / "empty");
    const fs::path other = dir_ / "other";
    const Result bad = run(keep + other.string() + " " + one + " " + (dir_ / "runs" / "empty").string());
    EXPECT_EQ(bad.status, 2) << bad.output;
    EXPECT_EQ(
        bad.output.rfind("armour: error: " + (dir_ / "runs" / "empty" / "summary.json").string() + ": ", 0),
        0u)
        << bad.output;
    EXPECT_FALSE(fs::exists(other));

    // A run whose analysis gave no Van der Meer count (null: no wave train), kept over DEST: refused,
    // DEST's results as they were.
    const std::string kept_table = read_text(dest / "results.csv");
    write(dir_ / "runs" / "dry" / "scene.resolved.toml", "[[unit]]\nname = \"cube\"\n");
    write(dir_ / "runs" / "dry" / "summary.json",
          "{\"units_displaced\": 0, \"units_displaced_van_der_meer\": null}\n");
    const Result dry = run(keep + dest.string() + " " + one + " " + (dir_ / "runs" / "dry").string());
    EXPECT_EQ(dry.status, 2) << dry.output;
    EXPECT_NE(dry.output.find("key 'units_displaced_van_der_meer': not a number"), std::string::npos)
        << dry.output;
    EXPECT_EQ(std::count(dry.output.begin(), dry.output.end(), '\n'), 1) << dry.output;
    EXPECT_EQ(read_text(dest / "results.csv"), kept_table);
}

// A sweep rewrites report.md as each case ends, not only at its own end: a
// study of days is read as it goes. With one job, the second case (a long
// one) starts only after the first's row is in the report; the sweep is then
// stopped (SIGTERM), the long case left pending.
TEST_F(SweepTest, ReportFollowsTheCasesAsTheyEnd) {
    const fs::path file = dir_ / "durations.toml";
    write(file,
          "scene = \"" + kSource + "/scenes/tilt_cube.toml\"\n[vary]\n\"run.duration\" = [0.5, 600.0]\n");
    const fs::path out = dir_ / "following";
    const pid_t sweep = armour_test::start_quietly(
        {ARMOUR_EXE, "sweep", file.string(), "--out", out.string(), "--jobs", "1"});
    const fs::path second = out / "cases" / "duration-600.0" / "log.txt";
    const bool started = armour_test::wait_until(sweep, [&] { return fs::exists(second); });
    const std::string report = read_text(out / "report.md");
    if (started)
        ::kill(sweep, SIGTERM);
    ASSERT_TRUE(started) << "the sweep ended before its second case started";
    EXPECT_EQ(armour_test::wait_for(sweep), 1); // stopped: a case did not finish
    EXPECT_NE(report.find("1 of 2 cases done, 0 failed, 1 not finished"), std::string::npos) << report;
    EXPECT_NE(report.find("| duration-0.5 | 0.5 |  | done |"), std::string::npos) << report;
    EXPECT_NE(report.find("| duration-600.0 | 600.0 |  | pending |"), std::string::npos) << report;
}

// A long study is taken a few cases a sitting, in the order its user needs
// them (the realisations of one point first): --cases runs only those, the
// others stay pending in the same folder for the next sweep, which runs only
// them. An id that is not a case: one error line, nothing made.
TEST_F(SweepTest, CasesRunsOnlyTheNamedCasesAndTheRestLater) {
    const fs::path file = friction_sweep("three.toml", "2.0", "0.3, 0.5, 0.7");
    const fs::path out = dir_ / "some";
    const std::string sweep = kArmour + " sweep " + file.string() + " --out " + out.string();
    const Result some = run(sweep + " --cases friction-0.7,friction-0.3");
    ASSERT_EQ(some.status, 0) << "every named case done: " << some.output;
    EXPECT_NE(some.output.find("3 cases, 2 to run"), std::string::npos) << some.output;
    EXPECT_NE(some.output.find("2 of the 2 cases of --cases done"), std::string::npos) << some.output;
    std::map<std::string, std::string> status;
    for (const Row &row : read_csv(out / "results.csv"))
        status[row.at("case")] = row.at("status");
    EXPECT_EQ(status, (std::map<std::string, std::string>{
                          {"friction-0.3", "done"}, {"friction-0.5", "pending"}, {"friction-0.7", "done"}}));
    // Kept part-way, the repository's results.csv holds the finished realisations alone (one row each).
    const Result keep = run("/usr/bin/python3 " + kSource + "/studies/keep_results.py " + out.string() + " " +
                            (dir_ / "kept").string());
    ASSERT_EQ(keep.status, 0) << keep.output;
    std::set<std::string> kept;
    for (const Row &row : read_csv(dir_ / "kept" / "results.csv")) {
        EXPECT_EQ(row.at("status"), "done") << row.at("case");
        kept.insert(row.at("case"));
    }
    EXPECT_EQ(kept, (std::set<std::string>{"friction-0.3", "friction-0.7"}));

    const Result rest = run(sweep);
    ASSERT_EQ(rest.status, 0) << rest.output;
    EXPECT_NE(rest.output.find("3 cases, 1 to run, 2 done before"), std::string::npos) << rest.output;
    for (const Row &row : read_csv(out / "results.csv"))
        EXPECT_EQ(row.at("status"), "done") << row.at("case");

    const Result bad = run(kArmour + " sweep " + file.string() + " --out " + (dir_ / "bad").string() +
                           " --cases friction-0.3,friction-0.9");
    EXPECT_EQ(bad.status, 2) << bad.output;
    EXPECT_NE(bad.output.find("armour: error: --cases: 'friction-0.9' is not a case of"), std::string::npos)
        << bad.output;
    EXPECT_NE(bad.output.find("friction-0.5"), std::string::npos)
        << "names the sweep's cases: " << bad.output;
    EXPECT_FALSE(fs::exists(dir_ / "bad"));
}

// The shipped studies as a user starts them: every case passes what
// `armour run` checks before it writes (the scene reader, the placement, the
// engine's step, the fluid case): a case refused at its start on a cluster
// costs a queue.
TEST_F(SweepTest, ShippedStudiesCheckEveryCase) {
    int studies = 0;
    for (const auto &entry : fs::directory_iterator(kSource + "/studies")) {
        if (entry.path().extension() != ".toml")
            continue;
#ifndef ARMOUR_HAS_OPENFOAM
        // Its cases need the OpenFOAM plugin, which this build lacks: `armour sweep` refuses them.
        if (read_text(entry.path()).find("stability_cubes") != std::string::npos) {
            ++studies;
            continue;
        }
#endif
        ++studies;
        const Result r = run(kArmour + " sweep " + entry.path().string() + " --out " +
                             (dir_ / entry.path().stem()).string() + " --dry-run");
        EXPECT_EQ(r.status, 0) << entry.path() << ": " << r.output;
        EXPECT_NE(r.output.find("all checked"), std::string::npos) << r.output;
    }
    EXPECT_GE(studies, 2);
}

// One tiny real case of each shipped study, as a user would try one before
// a cluster: a copy of the study cut to the first value of every [vary] list
// (or its first [[case]]) and its first seed, on one MPI rank, its case's
// scene shortened as the smoke shortens that scene (scene_smoke.h) through
// `armour sweep --set`. The case ends done and every headline figure of the
// sweep is a finite number.
TEST_F(SweepTest, ShippedStudiesRunOneTinyCaseEach) {
    int studies = 0;
    for (const auto &entry : fs::directory_iterator(kSource + "/studies")) {
        if (entry.path().extension() != ".toml")
            continue;
        ++studies;
        const std::string name = entry.path().filename().string();
        toml::table study = toml::parse_file(entry.path().string());
        fs::path scene(study["scene"].value_or(std::string()));
        if (scene.is_relative())
            scene = entry.path().parent_path() / scene;
        scene = scene.lexically_normal();
#ifndef ARMOUR_HAS_OPENFOAM
        if (toml::parse_file(scene.string()).contains("fluid"))
            continue; // its cases need the OpenFOAM plugin, which this build lacks
#endif
        const auto smoke = armour_test::kSmoke.find(scene.filename().string());
        ASSERT_NE(smoke, armour_test::kSmoke.end()) << name << ": its scene has no row in scene_smoke.h";

        study.insert_or_assign("scene", scene.string());
        const auto first_only = [](toml::array *list) {
            if (list && list->size() > 1)
                list->erase(list->cbegin() + 1, list->cend());
        };
        if (toml::table *vary = study["vary"].as_table()) {
            for (auto &&[key, values] : *vary)
                first_only(values.as_array());
            study.erase("case");
        } else {
            first_only(study["case"].as_array());
        }
        first_only(study["seeds"].as_array());
        if (toml::table *run_table = study["run"].as_table())
            run_table->erase("np"); // one rank on a 2-core machine
        const fs::path copy = dir_ / "studies" / name, out = dir_ / ("tiny-" + entry.path().stem().string());
        fs::create_directories(copy.parent_path());
        std::ofstream(copy) << study << "\n";

        const Result r = run(kArmour + " sweep " + copy.string() + " --out " + out.string() + " " +
                             armour_test::shell_sets(smoke->second));
        ASSERT_EQ(r.status, 0) << name << ": " << r.output << "\n" << read_text(copy);
        const json summary = json::parse(read_text(out / "summary.json"));
        ASSERT_EQ(summary["total"], 1) << name;
        ASSERT_EQ(summary["done"], 1) << name;
        const json &figures = summary["cases"][0]["figures"];
        const std::vector<std::string> &may_be_null = smoke->second.null_figures;
        ASSERT_FALSE(summary["headline"].empty()) << name;
        for (const std::string key : summary["headline"]) {
            if (std::find(may_be_null.begin(), may_be_null.end(), key) != may_be_null.end() &&
                (!figures.contains(key) || figures[key].is_null()))
                continue; // the smoke row says why
            ASSERT_TRUE(figures.contains(key) && figures[key].is_number()) << name << ": " << key;
            EXPECT_TRUE(std::isfinite(figures[key].get<double>())) << name << ": " << key;
        }
    }
    EXPECT_GE(studies, 2);
}

TEST_F(SweepTest, KilledSweepLosesOnlyTheRunningCase) {
    const fs::path sweep = tilt_sweep(), out = dir_ / "out";
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::freopen("/dev/null", "w", stderr);
        ::execl(kArmour.c_str(), kArmour.c_str(), "sweep", sweep.c_str(), "--out", out.c_str(), "--jobs", "1",
                static_cast<char *>(nullptr));
        ::_exit(127);
    }
    // Kill -9 the sweep once its first case is done (the second is then
    // running), however long that takes; a sweep that ended first failed.
    std::string first_done;
    int status = 0;
    pid_t ended = 0;
    while (first_done.empty() && (ended = ::waitpid(pid, &status, WNOHANG)) == 0) {
        for (const Row &row : read_csv(out / "results.csv"))
            if (row.at("status") == "done")
                first_done = row.at("case");
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ASSERT_EQ(ended, 0) << "the sweep ended before a case was seen done";
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    ASSERT_FALSE(first_done.empty());
    // The running case's processes die with the sweep (PR_SET_PDEATHSIG) and free its lock.
    auto any_locked = [&] {
        for (const auto &entry : fs::directory_iterator(out / "cases")) {
            const int fd = ::open((entry.path() / "lock").c_str(), O_RDWR);
            if (fd < 0)
                continue;
            const bool held = ::flock(fd, LOCK_EX | LOCK_NB) != 0;
            ::close(fd);
            if (held)
                return true;
        }
        return false;
    };
    const auto killed = std::chrono::steady_clock::now();
    while (any_locked() && std::chrono::steady_clock::now() - killed < std::chrono::seconds(10))
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_FALSE(any_locked()) << "a case process outlived its killed sweep by 10 s";
    int started = 0;
    for (const auto &entry : fs::directory_iterator(out / "cases"))
        started += fs::exists(entry.path() / "case.json");
    EXPECT_LT(started, 4) << "the sweep ran every case before it was killed; the test proves nothing";

    const Result resumed = run(kArmour + " sweep " + sweep.string() + " --out " + out.string() + " --jobs 1");
    ASSERT_EQ(resumed.status, 0) << resumed.output;
    const std::vector<Row> rows = read_csv(out / "results.csv");
    ASSERT_EQ(rows.size(), 4u);
    int rerun = 0;
    for (const Row &row : rows) {
        EXPECT_EQ(row.at("status"), "done") << row.at("case");
        EXPECT_FALSE(row.at("slide_angle_deg").empty()) << row.at("case");
        if (row.at("case") == first_done) {
            EXPECT_EQ(row.at("attempts"), "1") << "the finished case ran again";
        }
        rerun += row.at("attempts") == "2";
    }
    EXPECT_LE(rerun, 1) << "only the case running at the kill may run twice";
}

TEST_F(SweepTest, StoppedSweepLeavesItsRunningCasesPending) {
    const fs::path sweep = tilt_sweep(), out = dir_ / "out";
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::freopen("/dev/null", "w", stderr);
        ::execl(kArmour.c_str(), kArmour.c_str(), "sweep", sweep.c_str(), "--out", out.c_str(), "--jobs", "2",
                static_cast<char *>(nullptr));
        ::_exit(127);
    }
    // SIGTERM once a case is running, however long that takes; a sweep that
    // ended first failed.
    bool running = false;
    int status = 0;
    pid_t ended = 0;
    while (!running && (ended = ::waitpid(pid, &status, WNOHANG)) == 0) {
        std::error_code ec;
        for (const auto &entry : fs::directory_iterator(out / "cases", ec))
            running =
                running || read_text(entry.path() / "case.json").find("\"running\"") != std::string::npos;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ASSERT_EQ(ended, 0) << "the sweep ended before a case was seen running";
    ASSERT_TRUE(running);
    ::kill(pid, SIGTERM);
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 1);
    const json summary = json::parse(read_text(out / "summary.json"));
    EXPECT_EQ(summary["failed"], 0);
    EXPECT_EQ(summary["running"], 0);
    EXPECT_GT(summary["pending"], 0);
    for (const auto &c : summary["cases"])
        EXPECT_TRUE(c["status"] == "done" || c["status"] == "pending") << c.dump();
}

// A series case checkpoints in its steps' folders, not in its run's: a sweep
// stopped in its second step goes on from there when run again (its first
// step and its settle kept, not run again), as `armour run --resume` would.
// The shipped stability scene made CI-sized as test_stability_series.cpp
// makes it (45 cubes, 4 cm cells), two steps of 2 s. ~2-3 min.
TEST_F(SweepTest, AStoppedSeriesCaseGoesOnFromItsSteps) {
#ifndef ARMOUR_HAS_OPENFOAM
    GTEST_SKIP() << "needs the OpenFOAM coupling (Debian's openfoam)";
#endif
    const fs::path scene = dir_ / "series.toml", sweep = dir_ / "series_sweep.toml", out = dir_ / "out";
    write(scene, read_text(fs::path(kSource) / "scenes" / "stability_cubes.toml") +
                     "\n[[series]]\nHs = 0.10\nTp = 1.8\nramp_time = 0.9\nduration = 2.0\n"
                     "\n[[series]]\nHs = 0.12\nTp = 1.6\nseed = 2\nramp_time = 0.8\nduration = 2.0\n");
    write(
        sweep,
        "scene = \"" + scene.string() +
            "\"\n[set]\n\"pattern.0.rows\" = 5\n\"fluid.settle_stages\" = 5\n\"fluid.cells\" = [50, 6, 16]\n"
            "\"fluid.penalty\" = 200.0\n\"run.checkpoint_interval\" = 1.0\n"
            "[[case]]\n\"series.1.Hs\" = 0.12\n");
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::freopen("/dev/null", "w", stderr);
        ::execl(kArmour.c_str(), kArmour.c_str(), "sweep", sweep.c_str(), "--out", out.c_str(),
                static_cast<char *>(nullptr));
        ::_exit(127);
    }
    // SIGTERM once the first step is done (the second then runs), however
    // long that takes; a sweep that ended first failed.
    fs::path run_dir;
    bool first_done = false;
    int status = 0;
    pid_t ended = 0;
    while (!first_done && (ended = ::waitpid(pid, &status, WNOHANG)) == 0) {
        std::error_code ec;
        for (const auto &entry : fs::directory_iterator(out / "cases", ec)) {
            run_dir = entry.path() / "run";
            first_done = fs::exists(run_dir / "series" / "1" / "summary.json");
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ASSERT_EQ(ended, 0) << "the sweep ended before its first step was seen done";
    ::kill(pid, SIGTERM);
    ::waitpid(pid, &status, 0);
    ASSERT_FALSE(fs::exists(run_dir / "summary.json")) << "the series ended before it was stopped";
    const std::string step1 = read_text(run_dir / "series" / "1" / "summary.json");
    const double step1_seconds = json::parse(step1).at("simulated_seconds").get<double>();

    const Result resumed = run(kArmour + " sweep " + sweep.string() + " --out " + out.string());
    ASSERT_EQ(resumed.status, 0) << resumed.output;
    const fs::path case_dir = run_dir.parent_path();
    const std::string log = read_text(case_dir / "log.txt");
    EXPECT_NE(log.find("attempt 2"), std::string::npos) << log;
    EXPECT_NE(log.find("its series resumed at t = "), std::string::npos) << log;
    EXPECT_NE(log.find("series step 1 of 2: done in"), std::string::npos) << "step 1 kept: " << log;
    EXPECT_EQ(read_text(run_dir / "series" / "1" / "summary.json"), step1) << "step 1 ran again";
    const json record = json::parse(read_text(case_dir / "case.json"));
    EXPECT_EQ(record.at("status"), "done");
    EXPECT_GE(record.at("resumed_from").get<double>(), step1_seconds) << "from step 2, not the start";
    const json summary = json::parse(read_text(run_dir / "summary.json"));
    ASSERT_EQ(summary.at("series").size(), 2u);
    EXPECT_NEAR(summary.at("simulated_seconds").get<double>(), 4.0, 0.05);
}

TEST_F(SweepTest, ACaseLockedByAnotherProcessIsNotRunTwice) {
    const fs::path out = dir_ / "out", sweep = dir_ / "two.toml";
    auto write_sweep = [&](double tilt_max) {
        write(sweep, "scene = \"" + kSource + "/scenes/tilt_cube.toml\"\n[set]\n\"analysis.tilt_max\" = " +
                         std::to_string(tilt_max) + "\n[vary]\n\"material.0.friction\" = [0.3, 0.5]\n");
    };
    write_sweep(60.0);
    const std::string command = kArmour + " sweep " + sweep.string() + " --out " + out.string() + " --jobs 2";
    ASSERT_EQ(run(command).status, 0);
    // Another scene (tilt_max) makes both cases due again; one is held by another process.
    write_sweep(59.0);
    const int fd = ::open((out / "cases" / "friction-0.3" / "lock").c_str(), O_RDWR);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
    const Result r = run(command);
    ::close(fd);
    EXPECT_EQ(r.status, 1) << r.output; // not every case is done
    EXPECT_NE(r.output.find("case friction-0.3 is running in another sweep"), std::string::npos) << r.output;
    const json summary = json::parse(read_text(out / "summary.json"));
    for (const auto &c : summary["cases"]) {
        const bool held = c["case"] == "friction-0.3";
        EXPECT_EQ(c["status"], held ? "pending" : "done") << c.dump();
        EXPECT_EQ(c["attempts"], held ? 1 : 2) << c.dump();
    }
}

TEST_F(SweepTest, BadInputIsOneErrorLineBeforeAnythingRuns) {
    const std::string scene = "scene = \"" + kSource + "/scenes/tilt_cube.toml\"\n";
    write(dir_ / "dead-slurm.conf", "ClusterName=none\nSlurmctldHost=localhost(127.0.0.1)\nSlurmctldPort=9\n"
                                    "NodeName=localhost CPUs=1\nPartitionName=p Nodes=localhost\n");
    const struct {
        std::string sweep, options, expected;
    } cases[] = {
        {scene + "[vary]\n\"material.0.frction\" = [0.3]\n", "",
         "case frction-0.3: --set 'material.0.frction=0.3': unknown key"},
        {scene + "[vary]\n\"material.0.friction\" = []\n", "",
         "key 'vary.\"material.0.friction\"': empty list"},
        {scene + "[vary]\n\"material.0.friction\" = [0.3, -1.0]\n", "",
         "case friction--1.0: --set: key 'material.0.friction': must be >= 0"},
        {"scene = \"no-such-scene.toml\"\n[vary]\n\"material.0.friction\" = [0.3]\n", "",
         "key 'scene': no such file"},
        {scene + "[vary]\n\"material.0.friction\" = [0.3]\n", "--executor slurm", "--executor: slurm:"},
        {scene + "[vary]\n\"material.0.friction\" = [0.3]\n", "--executor pbs",
         "--executor: must be local or slurm"},
        {scene + "[vary]\n\"material.0.friction\" = [0.3]\n[run]\nnp = 2\n", "",
         "key 'run.np': case friction-0.3: only for scenes with [fluid]"},
        // Past the reader: the engine refuses the step when `armour run` builds it.
        {scene + "[vary]\n\"run.time_step\" = [1e-5, 0.01]\n", "",
         "case time_step-0.01: run.time_step: 0.01 s exceeds the stability limit"},
        {scene + "[vary]\n\"body.0.position\" = [[0.0, 0.0, 0.05]]\n", "", "cuts into wall 'plate' by"},
        // --set: what every case shares, never what the sweep varies.
        {scene + "[vary]\n\"material.0.friction\" = [0.3]\n", "--set material.0.friction=0.4",
         "--set: key 'material.0.friction': the sweep file"},
        {scene + "[vary]\n\"material.0.friction\" = [0.3]\n", "--set run.duration",
         "--set: 'run.duration': expected KEY=VALUE"},
        {scene + "[vary]\n\"material.0.friction\" = [0.3]\n", "--set run.durration=1",
         "case friction-0.3: --set 'run.durration=1': unknown key"},
    };
    for (const auto &c : cases) {
        write(dir_ / "bad.toml", c.sweep);
        const Result r =
            run("SLURM_CONF=" + (dir_ / "dead-slurm.conf").string() + " " + kArmour + " sweep " +
                (dir_ / "bad.toml").string() + " --out " + (dir_ / "out").string() + " " + c.options);
        EXPECT_EQ(r.status, 2) << r.output;
        EXPECT_EQ(r.output.rfind("armour: error: ", 0), 0u) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_NE(r.output.find(c.expected), std::string::npos)
            << "expected '" << c.expected << "' in " << r.output;
        EXPECT_FALSE(fs::exists(dir_ / "out")) << c.sweep;
    }
    const Result missing =
        run(kArmour + " sweep " + (dir_ / "none.toml").string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(missing.status, 2);
    EXPECT_NE(missing.output.find("none.toml: cannot read the sweep file"), std::string::npos)
        << missing.output;
}

// The report's damage chart on summaries as the damage analysis writes them.
TEST_F(SweepTest, ReportDrawsDamageAgainstVanDerMeerAndHudson) {
    const fs::path out = dir_ / "out";
    json cases = json::array();
    const double hs[] = {1.6, 1.9, 2.2, 2.5};
    for (int k = 0; k < 4; ++k)
        for (int seed = 1; seed <= 2; ++seed) {
            const std::string id = "Hs-" + std::to_string(k) + "_seed-" + std::to_string(seed);
            const double Ns = hs[k];
            if (k == 3) // a history as the damage analysis writes it, for two realisations
                write(out / "cases" / id / "run" / "damage_history.csv",
                      "# units displaced (>= displaced_threshold Dn) against time\n"
                      "time_s,units_displaced,N_od,max_displacement_over_Dn\n0,0,0,0\n10,2,0.4,1.5\n");
            cases.push_back({{"case", id},
                             {"folder", "cases/" + id},
                             {"values", {{"fluid.wave_height", hs[k]}}},
                             {"seed", seed},
                             {"status", "done"},
                             {"figures",
                              {{"Ns", Ns},
                               {"N_od", 0.1 * std::pow(Ns, 3) * (0.9 + 0.1 * seed)},
                               {"waves", 1000},
                               {"s_om", 0.03},
                               {"N_od_van_der_meer", 0.05 * Ns},
                               {"units_displaced_van_der_meer", 0.5 * Ns}, // a 10 Dn wide section
                               // Hudson's Ns on a 1:2 slope, as the damage analysis writes them
                               {"Ns_hudson_breaking", std::cbrt(6.5 * 2.0)},
                               {"Ns_hudson_nonbreaking", std::cbrt(7.5 * 2.0)},
                               {"damage_S", 0.5 * Ns}}}});
        }
    write(out / "summary.json", json{{"sweep_file", "stability.toml"},
                                     {"scene", "stability_cubes.toml"},
                                     {"analysis", "damage"},
                                     {"executor", "local"},
                                     {"varied", {"fluid.wave_height"}},
                                     {"headline", {"N_od", "Ns"}},
                                     {"total", 8},
                                     {"done", 8},
                                     {"failed", 0},
                                     {"pending", 0},
                                     {"running", 0},
                                     {"cases", cases}}
                                    .dump());
    const Result r = run("/usr/bin/python3 " + kSource + "/apps/sweep/sweep_report.py " + out.string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_GT(fs::file_size(out / "figures" / "stability_Nod_vs_Ns.png"), 10000u);
    EXPECT_TRUE(fs::exists(out / "figures" / "N_od_vs_fluid.wave_height.png"));
    const std::string report = read_text(out / "report.md");
    EXPECT_NE(report.find("Van der Meer curve for N = 1000 waves, s_om = 0.03"), std::string::npos) << report;
    EXPECT_NE(report.find("Hudson lines for cot α = 2"), std::string::npos) << report;
    EXPECT_GT(fs::file_size(out / "figures" / "stability_Nod_vs_time.png"), 10000u);
    EXPECT_NE(report.find("2 realisations' damage histories"), std::string::npos) << report;
    EXPECT_NE(report.find("band: 90 % of the displaced-unit counts a 10 Dn wide section"), std::string::npos)
        << report;
    // A point per height: the mean of its two realisations (seeds), with intervals.
    EXPECT_NE(report.find("4 points, each the mean of 2 realisation(s) with its 95 % interval"),
              std::string::npos)
        << report;

    // The formulas the chart draws (stability.md): Van der Meer for cubes and Hudson.
    const Result f = run("cd " + kSource +
                         "/apps/sweep && /usr/bin/python3 -c 'import sweep_report as s; "
                         "print(\"%.12f %d %d\" % (s.van_der_meer_ns(0.5, 1000, 0.03), "
                         "s.poisson_quantile(3, 0.05), s.poisson_quantile(3, 0.95)))'");
    ASSERT_EQ(f.status, 0) << f.output;
    double vdm = 0.0;
    int low = -1, high = -1;
    ASSERT_EQ(std::sscanf(f.output.c_str(), "%lf %d %d", &vdm, &low, &high), 3) << f.output;
    // Poisson(3): P(X <= 0) = 0.0498 < 0.05 <= P(X <= 1) = 0.199; P(X <= 5) = 0.916 < 0.95 <= P(X <= 6) =
    // 0.966.
    EXPECT_EQ(low, 1);
    EXPECT_EQ(high, 6);
    EXPECT_NEAR(vdm, (6.7 * std::pow(0.5, 0.4) / std::pow(1000.0, 0.3) + 1.0) * std::pow(0.03, -0.1), 1e-9);
    EXPECT_NEAR(vdm, 2.3277, 1e-3);

    // Hudson's lines from the runs' own figures (the damage analysis's Ns for
    // its slope, test_slope): a case gathered from --kept holds its summary but
    // not its scene.
    const Result h = run("cd " + kSource +
                         "/apps/sweep && /usr/bin/python3 -c 'import sweep_report as s; "
                         "own = [{\"figures\": {\"Ns_hudson_breaking\": 9.75 ** (1 / 3), "
                         "\"Ns_hudson_nonbreaking\": 11.25 ** (1 / 3)}}]; "
                         "a, lines = s.hudson_lines(own); "
                         "print(\"%.12f %.12f %.12f\" % (a, lines[0][1], lines[1][1])); "
                         "print(s.hudson_lines([{\"figures\": {}}]))'");
    ASSERT_EQ(h.status, 0) << h.output;
    double own_cot = 0.0, breaking = 0.0, nonbreaking = 0.0;
    ASSERT_EQ(std::sscanf(h.output.c_str(), "%lf %lf %lf", &own_cot, &breaking, &nonbreaking), 3) << h.output;
    EXPECT_NEAR(own_cot, 1.5, 1e-9); // (K_D cot α)^(1/3) = Ns, K_D 7.5 non-breaking
    EXPECT_NEAR(breaking, std::cbrt(6.5 * 1.5), 1e-9);
    EXPECT_NEAR(nonbreaking, std::cbrt(7.5 * 1.5), 1e-9);
    EXPECT_NE(h.output.find("None"), std::string::npos) << h.output; // without them: no lines
}

// When the units left and from which seats (studies/damage_timing.py): each
// displaced unit at the time its case's count first reached its number, as a
// share of the case's wave train at the toe, pooled against Van der Meer's
// u^0.75 with an interval from resampling the cases; each unit's seat on top
// of the layer (settled centre farther out of the face than the layer is
// thick) or in it, at the foot or on the face; bad input is one error line.
TEST_F(SweepTest, DamageTimingPutsEachDepartureInTheTrainAndOnItsSeat) {
    const auto summary = [](int displaced) {
        return "{\"waves\": {\"window\": [4.0, 14.0]}, \"units_displaced\": " + std::to_string(displaced) +
               ", \"damage\": {\"settled_layer\": {\"layer_thickness\": 0.08}}}\n";
    };
    const std::string history = "# units displaced against time\ntime_s,units_displaced,N_od,max\n";
    const fs::path a = dir_ / "k" / "cases" / "a" / "run", b = dir_ / "k" / "cases" / "b" / "run";
    // a: one unit gone at 4.5 s (u 0.05), one at 6 s (0.2); a third moved 1 Dn at 9 s and came back
    // (its final displacement is under 1 Dn), so it is not one of the case's two displaced.
    write(a / "summary.json", summary(2));
    write(a / "damage_history.csv", history + "0,0,0,0\n4.5,1,0,1\n6,2,0,1\n9,3,0,1\n10,2,0,1\n");
    write(a / "damage.csv", "# per unit\nbody,unit,s_m,y_m,n_m,at_foot,displaced\n"
                            "0,cube,0.1,0,0.10,0,1\n1,cube,0.1,0,0.05,0,1\n2,cube,-0.02,0,0.03,1,0\n"
                            "3,cube,0.2,0,0.05,0,0\n");
    // b: one gone before the window (3 s: at u 0, counted apart), one at 12 s (u 0.8); its damage.csv
    // predates n_m, so it counts in the timing only.
    write(b / "summary.json", summary(2));
    write(b / "damage_history.csv", history + "0,0,0,0\n3,1,0,1\n12,2,0,1\n");
    write(b / "damage.csv", "# per unit\nbody,unit,s_m,y_m,displaced\n0,cube,0.1,0,1\n1,cube,0.2,0,1\n");
    write(dir_ / "k" / "cases" / "c" / "run" / "summary.json", summary(0)); // no history: not a case here
    // d: its damage.csv says when its one unit left for good (left_at_s 13 s: u 0.9), which the
    // count's first rise (5 s: it had left and come back before) would not.
    const fs::path d = dir_ / "k" / "cases" / "d" / "run";
    write(d / "summary.json", summary(1));
    write(d / "damage_history.csv", history + "0,0,0,0\n5,1,0,1\n6,0,0,0.5\n13,1,0,1\n");
    write(d / "damage.csv", "# per unit\nbody,unit,s_m,y_m,n_m,at_foot,on_top,displaced,left_at_s\n"
                            "0,cube,0.1,0,0.02,0,0,1,13\n");

    const std::string script = "/usr/bin/python3 " + kSource + "/studies/damage_timing.py ";
    const Result r = run(script + (dir_ / "k").string() + " --label K --out " + (dir_ / "t").string());
    ASSERT_EQ(r.status, 0) << r.output;
    // Pooled shares 0.05, 0.2, 0, 0.8, 0.9: 3 of 5 gone by a quarter and by half of the waves.
    // Resampled, three draws of d alone (0 of 3, chance 1/27 = 3.7 %) and of a alone (6 of 6, 3.7 %)
    // lie beyond the 2.5 % tails: the interval 0-100 %.
    EXPECT_NE(r.output.find("K: 3 cases, 5 displaced (1 before the first wave)"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("gone by 25% of the waves: 60% (95 % 0%-100%); Van der Meer 35%"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("gone by 50% of the waves: 60% (95 % 0%-100%); Van der Meer 59%"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("seats (2 cases with n_m)"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("face, on top                 1 / 1"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("face, in the layer           3 / 2"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("foot, in the layer           1 / 0"), std::string::npos) << r.output;
    // Per point (the case's folder less its seed; these summaries give no Ns or expected count).
    EXPECT_NE(
        r.output.find("a (1 cases, Ns -, Van der Meer -): face, in the layer 1 of 2, face, on top 1 of 1, "
                      "foot, in the layer 0 of 1"),
        std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("d (1 cases, Ns -, Van der Meer -): face, in the layer 1 of 1\n"),
              std::string::npos)
        << r.output;
    EXPECT_GT(fs::file_size(dir_ / "t" / "timing.png"), 10000u);
    const auto out = nlohmann::json::parse(read_text(dir_ / "t" / "summary.json"));
    const auto &curve = out["curves"][0];
    EXPECT_EQ(curve["displaced"].get<int>(), 5);
    EXPECT_NEAR(curve["by_share_of_waves"]["0.25"]["van_der_meer"].get<double>(), std::pow(0.25, 0.75),
                1e-12);
    EXPECT_NEAR(curve["by_share_of_waves"]["0.5"]["share_displaced"].get<double>(), 0.6, 1e-12);

    // Bad input, one line each: a folder with no case; labels that do not pair with the folders;
    // a history whose count never reaches the summary's; a wave window of no length.
    write(dir_ / "short" / "cases" / "a" / "run" / "summary.json", summary(3));
    write(dir_ / "short" / "cases" / "a" / "run" / "damage_history.csv", history + "0,0,0,0\n5,1,0,1\n");
    write(dir_ / "short" / "cases" / "a" / "run" / "damage.csv",
          "# per unit\nbody,unit,s_m,y_m,displaced\n0,cube,0,0,1\n1,cube,0,0,1\n2,cube,0,0,1\n");
    write(dir_ / "flat" / "cases" / "a" / "run" / "summary.json",
          "{\"waves\": {\"window\": [4.0, 4.0]}, \"units_displaced\": 0}\n");
    write(dir_ / "flat" / "cases" / "a" / "run" / "damage_history.csv", history);
    write(dir_ / "flat" / "cases" / "a" / "run" / "damage.csv", "# per unit\nbody,unit,s_m,y_m,displaced\n");
    const std::vector<std::pair<std::string, std::string>> bad_inputs = {
        {(dir_ / "none").string(), "no case with summary.json"},
        {(dir_ / "k").string() + " --label A --label B", "--label: 2 given for 1 curves"},
        {(dir_ / "short").string(),
         "damage_history.csv: the count reaches 1, summary.json's units_displaced is 3"},
        {(dir_ / "flat").string(), "key 'waves.window' [4, 4] s holds no waves"}};
    for (const auto &[args, reason] : bad_inputs) {
        const Result bad = run(script + args);
        EXPECT_EQ(bad.status, 2) << args << "\n" << bad.output;
        EXPECT_EQ(bad.output.rfind("armour: error: ", 0), 0u) << bad.output;
        EXPECT_NE(bad.output.find(reason), std::string::npos) << bad.output;
        EXPECT_EQ(std::count(bad.output.begin(), bad.output.end(), '\n'), 1) << bad.output;
    }
}

// Does the damage go on growing with the waves (studies/damage_growth.py): a
// run's figures at a series of times, from `armour report --until` (here a
// stand-in program with a known history), and, conditioned on each run's
// final count, the binomial chance that so few left after the first N0 waves
// if they left as Van der Meer's expected count grows; pooled, the exact
// distribution of the sum; bad input is one error line.
TEST_F(SweepTest, DamageGrowthHoldsEachRunsLateDeparturesAgainstTheFormulasGrowth) {
    // The stand-in: a run that has come to 100 s, a record every 0.05 s; N = t / 2 waves; the formula's
    // count 0.1 N^0.75.
    // Run a: units displaced 1 from 10 s, 2 from 20 s, 3 from 80 s; run b: 1 from 10 s; run c: refused;
    // run f: as b, but the formula's count falls with the waves (as where a run's measured Ns falls).
    const fs::path fake = dir_ / "fake_armour";
    write(fake,
          "#!/usr/bin/python3\n"
          "import json, os, sys\n"
          "a = sys.argv[1:]\n"
          "run, out = os.path.basename(a[1]), a[a.index('--out') + 1]\n"
          "if run == 'c':\n"
          "    sys.exit(print('armour: error: c: not a coupled run', file=sys.stderr) or 2)\n"
          "t = min(float(a[a.index('--until') + 1]) if '--until' in a else 100.0, 100.0)\n"
          "steps = {'a': (10, 20, 80), 'b': (10,), 'f': (10,)}[run]\n"
          "n, d = t / 2, sum(t >= s for s in steps)\n"
          "vdm = 2.0 - 0.01 * n if run == 'f' else 0.1 * n ** 0.75\n"
          "os.makedirs(out)\n"
          "json.dump({'simulated_seconds': t, 'records': round(t / 0.05) + 1,\n"
          "           'damage': {'waves': n, 'wave_source': 'measured'},\n"
          "           'Ns': 4.2, 's_om': 0.03, 'units_displaced': d, 'N_od': d / 6.2, 'damage_S': 0.5,\n"
          "           'rocking_units': 3, 'units_displaced_van_der_meer': vdm,\n"
          "           'N_od_van_der_meer': vdm / 6.2}, open(out + '/summary.json', 'w'))\n");
    fs::permissions(fake, fs::perms::owner_all);
    for (const char *r : {"a", "b", "c", "f"})
        fs::create_directories(dir_ / "runs" / r);
    const std::string script = "/usr/bin/python3 " + kSource + "/studies/damage_growth.py ";
    const std::string runs = (dir_ / "runs" / "a").string() + " " + (dir_ / "runs" / "b").string();
    const std::string tail = " --armour " + fake.string() + " --out " + (dir_ / "g").string();
    const Result r = run(script + runs + " --every 20 --after 27" + tail);
    ASSERT_EQ(r.status, 0) << r.output;
    // Reports at 20, 40, 60, 80 s and the end (100 s); the first at or past 27 waves is 60 s (30
    // waves), the end 50 waves: the formula's growth puts q = 1 - (30/50)^0.75 of the units after.
    const double q = 1.0 - std::pow(0.6, 0.75);
    const auto out = nlohmann::json::parse(read_text(dir_ / "g" / "summary.json"));
    const auto &a = out["runs"][(dir_ / "runs" / "a").string()];
    EXPECT_EQ(a["waves_at"].get<double>(), 30.0);
    EXPECT_EQ(a["displaced_at"].get<int>(), 2);
    EXPECT_EQ(a["displaced_after"].get<int>(), 1);
    EXPECT_NEAR(a["share_after_van_der_meer"].get<double>(), q, 1e-12);
    EXPECT_NEAR(a["chance_of_so_few"].get<double>(), std::pow(1 - q, 3) + 3 * q * std::pow(1 - q, 2), 1e-12);
    const auto &b = out["runs"][(dir_ / "runs" / "b").string()];
    EXPECT_EQ(b["displaced_after"].get<int>(), 0);
    EXPECT_NEAR(b["chance_of_so_few"].get<double>(), 1 - q, 1e-12);
    // Pooled: 1 of 4 after; both runs share q, so the sum is binomial (4, q).
    EXPECT_EQ(out["pooled"]["displaced_after"].get<int>(), 1);
    EXPECT_NEAR(out["pooled"]["expected_after"].get<double>(), 4 * q, 1e-12);
    EXPECT_NEAR(out["pooled"]["chance_of_so_few"].get<double>(),
                std::pow(1 - q, 4) + 4 * q * std::pow(1 - q, 3), 1e-12);
    const std::string csv = read_text(dir_ / "g" / "growth.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 1 + 2 * 5)
        << csv; // comment, header, 5 rows a run
    EXPECT_NE(csv.find((dir_ / "runs" / "a").string() + ",80.0,measured,40.0,4.2,0.03,3,"), std::string::npos)
        << csv;
    EXPECT_GT(fs::file_size(dir_ / "g" / "growth.png"), 10000u);
    // --times asks at the times given (those before the run's end) and the end; 99.99 s lies within
    // one record (0.05 s) of the end and would repeat it.
    const Result at = run(script + (dir_ / "runs" / "a").string() + " --times 70,10,99.99,250" + tail + "t");
    ASSERT_EQ(at.status, 0) << at.output;
    const std::string at_csv = read_text(dir_ / "gt" / "growth.csv");
    EXPECT_EQ(std::count(at_csv.begin(), at_csv.end(), '\n'), 2 + 3) << at_csv;

    // Where the formula's count does not grow after N0, there is nothing to hold the late departures
    // against: the run is not tested (nor pooled), and says why.
    const Result falling =
        run(script + (dir_ / "runs" / "f").string() + " --every 20 --after 27" + tail + "f");
    ASSERT_EQ(falling.status, 0) << falling.output;
    const auto f = nlohmann::json::parse(read_text(dir_ / "gf" / "summary.json"));
    EXPECT_FALSE(f["runs"][(dir_ / "runs" / "f").string()]["tested"].get<bool>());
    EXPECT_TRUE(f["pooled"].is_null());
    EXPECT_NE(
        falling.output.find("not tested: Van der Meer's expected count does not grow after 27 waves (1.70 at "
                            "30 waves, 1.50 at 50: the Ns measured so far falls)"),
        std::string::npos)
        << falling.output;

    // Bad input, one line each, nothing written: a run the report refuses; both or neither of
    // --every and --times; a time or an --after that is no number > 0; a folder that is not there.
    const std::vector<std::pair<std::string, std::string>> bad_inputs = {
        {(dir_ / "runs" / "c").string() + " --every 20", "runs/c: `armour report` found no damage figures "
                                                         "(armour: error: c: not a coupled run)"},
        {runs + " --every 20 --times 10", "give one of --every or --times"},
        {runs, "give one of --every or --times"},
        {runs + " --times 10,x", "--times: '10,x' is not a comma-separated list of times in s"},
        {runs + " --every 0", "--every: must be a finite number > 0 s (got 0)"},
        {runs + " --every 10 --after -1", "--after: must be a finite number of waves > 0 (got -1)"},
        {(dir_ / "runs" / "none").string() + " --every 10", "runs/none: not a folder"}};
    for (const auto &[args, reason] : bad_inputs) {
        const Result bad =
            run(script + args + " --armour " + fake.string() + " --out " + (dir_ / "bad").string());
        EXPECT_EQ(bad.status, 2) << args << "\n" << bad.output;
        EXPECT_EQ(bad.output.rfind("armour: error: ", 0), 0u) << bad.output;
        EXPECT_NE(bad.output.find(reason), std::string::npos) << bad.output;
        EXPECT_EQ(std::count(bad.output.begin(), bad.output.end(), '\n'), 1) << bad.output;
        EXPECT_FALSE(fs::exists(dir_ / "bad" / "summary.json")) << args;
    }
}
// Two kept curves side by side (studies/compare_curves.py): each curve's
// units displaced per point and in all against Van der Meer's expected count,
// with the Poisson chance of so few, and their spread about it and within the
// points; where the cases' damage.csv are kept, how many of the displaced sat in
// the toe row (s_m < 0) and at the foot (at_foot) and the counts without them; a chart; one curve joined
// from two studies' points; bad input is one error line.
TEST_F(SweepTest, ComparedCurvesCountEachCurvesUnitsAgainstVanDerMeer) {
    const std::string header = "case,unit.0.density,seed,status,Ns,N_od,units_displaced,"
                               "units_displaced_van_der_meer,waves.waves,s_om\n";
    write(dir_ / "a" / "results.csv",
          "case,unit.0.density,seed,status,Ns,N_od,units_displaced,units_displaced_van_der_meer,waves.waves,"
          "s_om,units\n"
          "d-2000_seed-1,2000.0,1,done,2.5,0,0,0.5,27,0.03,3\n"
          "d-2000_seed-2,2000.0,2,done,2.7,0.16,1,0.5,27,0.03,3\n"
          "d-1700_seed-1,1700.0,1,done,4.0,0.16,1,4.0,27,0.03,3\n"
          "d-1700_seed-2,1700.0,2,failed,,,,,,,\n");
    // Three units a case, one of them in the toe row (below the face's foot): the toe unit left
    // in d-2000_seed-2, a face unit in d-1700_seed-1. Both sat at the foot (seaward of the face's
    // foot, damage.csv's at_foot), the third not.
    const std::string units = "# damage per unit\nbody,unit,s_m,y_m,at_foot,displaced\n";
    write(dir_ / "a" / "cases" / "d-2000_seed-1" / "run" / "damage.csv",
          units + "0,cube,-0.02,0,1,0\n1,cube,0.1,0,1,0\n2,cube,0.2,0,0,0\n");
    write(dir_ / "a" / "cases" / "d-2000_seed-2" / "run" / "damage.csv",
          units + "0,cube,-0.02,0,1,1\n1,cube,0.1,0,1,0\n2,cube,0.2,0,0,0\n");
    write(dir_ / "a" / "cases" / "d-1700_seed-1" / "run" / "damage.csv",
          units + "0,cube,-0.02,0,1,0\n1,cube,0.1,0,1,1\n2,cube,0.2,0,0,0\n");
    write(dir_ / "b" / "results.csv", header + "d-2000_seed-1,2000.0,1,done,2.5,0,0,0.5,27,0.03\n"
                                               "d-1700_seed-1,1700.0,1,done,4.0,0.64,4,4.0,27,0.03\n");
    const std::string script = "/usr/bin/python3 " + kSource + "/studies/compare_curves.py ";
    const Result r = run(script + (dir_ / "a").string() + " " + (dir_ / "b").string() +
                         " --label A --label B --out " + (dir_ / "c.png").string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_GT(fs::file_size(dir_ / "c.png"), 10000u);
    // A: 1 of 0.5 + 0.5 expected at 2000 kg/m^3, 1 of 4 at 1700 (P(X <= 1 | 4) = 5 e^-4 = 0.092),
    // 2 of 5 in all (P = 18.5 e^-5 = 0.12); the failed case counts for nothing.
    EXPECT_NE(r.output.find("unit.0.density 2000.0: Ns 2.60  1 / 1.0 (P 0.74)  over 2 realisations"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("unit.0.density 1700.0: Ns 4.00  1 / 4.0 (P 0.092)  over 1 realisations"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("all: 2 / 5.0 (P 0.12)"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("all: 4 / 4.5 (P 0.53)"), std::string::npos) << r.output;
    // The spread about the formula, Pearson's chi-square: A (0 - 0.5)^2 / 0.5 + (1 - 0.5)^2 / 0.5 +
    // (1 - 4)^2 / 4 = 3.25 over 3 realisations, P(chi2_3 >= 3.25) = erfc(sqrt(1.625)) +
    // sqrt(6.5 / pi) e^-1.625 = 0.355; B 0.5 over 2, P(chi2_2 >= 0.5) = e^-0.25 = 0.78.
    EXPECT_NE(r.output.find("spread about the formula: chi2 3.25 over 3 realisations, 1.08 x independent "
                            "units' (P 0.35 of one this wide)"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("spread about the formula: chi2 0.50 over 2 realisations, 0.25 x independent "
                            "units' (P 0.78 of one this wide)"),
              std::string::npos)
        << r.output;
    // The spread within the points, each point's counts about its own mean: A at 2000 kg/m^3 counts
    // 0 and 1 about 0.5 and 0.5 (its factor 1 / 1), chi2 1.0 over 1 degree of freedom, P(chi2_1 >= 1)
    // = erfc(1 / sqrt 2) = 0.317; its one realisation at 1700 has no freedom left. B has no point with
    // two realisations and a unit displaced.
    EXPECT_NE(
        r.output.find("spread within the points (about each point's own mean): chi2 1.00 over 1 degrees of "
                      "freedom, 1.00 x independent units' (P 0.32 of one this wide)"),
        std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("spread within the points: no point has two realisations and a unit displaced"),
              std::string::npos)
        << r.output;
    // The shape: A's counts about each point's own mean lose 2 (0 ln 0 - (0 - 0.5)) + 2 (1 ln 2 - (1 -
    // 0.5)) + 0 = 2 ln 2 = 1.39 in deviance, weighed on (2 - 1, 1) degrees of freedom; B's two points
    // have one realisation each.
    EXPECT_NE(r.output.find(" against 1.39, F "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(" on (1, 1) over the points' own scatter: P "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(
                  "the shape: too few points or realisations to weigh it against the points' own scatter"),
              std::string::npos)
        << r.output;
    // Fisher's F tail against closed forms: on (2, d) (1 + 2x/d)^(-d/2), on (1, 1) 1 - (2/pi) atan(sqrt x).
    const Result tail =
        run("cd " + kSource +
            "/studies && /usr/bin/python3 -c 'import compare_curves as c; "
            "print(c.f_tail(0.5, 2, 5), c.f_tail(3.0, 2, 8), c.f_tail(3.0, 1, 1), c.f_tail(0, 3, 4))'");
    ASSERT_EQ(tail.status, 0) << tail.output;
    std::istringstream tails(tail.output);
    double t1 = 0, t2 = 0, t3 = 0, t4 = 0;
    tails >> t1 >> t2 >> t3 >> t4;
    EXPECT_NEAR(t1, std::pow(1.0 + 2.0 * 0.5 / 5.0, -2.5), 1e-12);
    EXPECT_NEAR(t2, std::pow(1.0 + 2.0 * 3.0 / 8.0, -4.0), 1e-12);
    EXPECT_NEAR(t3, 1.0 - 2.0 / M_PI * std::atan(std::sqrt(3.0)), 1e-12);
    EXPECT_EQ(t4, 1.0);
    // A's toe row: 1 of its 2 displaced (the point at 2000 kg/m^3); without it 1 of 5.0 expected,
    // P(X <= 1 | 5) = 6 e^-5 = 0.040; per unit 1 of the 3 toe units, 1 of the 6 on the face. B kept
    // no damage.csv.
    EXPECT_NE(r.output.find("from the toe row (seated below the face's foot): 1 of 2 (by point in rising Ns: "
                            "1 of 1, 0 of 1); without them 1 / 5.0 (P 0.04)"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("displaced per unit: the toe row 1 of 3 (33.3 %), the face 1 of 6 (16.7 %)"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("without the toe row: the counts are Van der Meer's at Ns / f, f = "),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("toe row: not known (the cases' damage.csv are not kept beside results.csv)"),
              std::string::npos)
        << r.output;
    // A's foot (at_foot): both its displaced units; without them 0 of 5.0, P(X = 0 | 5) = e^-5 = 0.0067;
    // per unit 2 of the 6 at the foot, 0 of the 3 on the face; with none left, no factor.
    EXPECT_NE(
        r.output.find("from the foot (seated seaward of the face's foot, damage.csv's at_foot): 2 of 2 (by "
                      "point in rising Ns: 1 of 1, 1 of 1); without them 0 / 5.0 (P 0.0067)"),
        std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("displaced per unit: the foot 2 of 6 (33.3 %), the face 0 of 3 (0.0 %)"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("without the foot: no unit displaced: the factor on Ns is not bounded"),
              std::string::npos)
        << r.output;

    // One curve of two studies' points (FOLDER+FOLDER:VALUE): B's two points with A's 1700 kg/m^3
    // realisation, so at 1700 kg/m^3 4 + 1 units of 4.0 + 4.0 (P(X <= 5 | 8) = 0.19) over 2
    // realisations, 5 of 8.5 in all (P 0.15); A's 2000 kg/m^3 point stays out.
    const std::string joined = (dir_ / "b").string() + "+" + (dir_ / "a").string() + ":1700";
    const Result j = run(script + joined + " --out " + (dir_ / "j.png").string());
    ASSERT_EQ(j.status, 0) << j.output;
    EXPECT_NE(j.output.find("unit.0.density 1700.0: Ns 4.00  5 / 8.0 (P 0.19)  over 2 realisations"),
              std::string::npos)
        << j.output;
    EXPECT_NE(j.output.find("unit.0.density 2000.0: Ns 2.50  0 / 0.5 (P 0.61)  over 1 realisations"),
              std::string::npos)
        << j.output;
    EXPECT_NE(j.output.find("all: 5 / 8.5 (P 0.15)"), std::string::npos) << j.output;
    EXPECT_NE(j.output.find("b + a:1700: units displaced"), std::string::npos) << j.output; // its label
    // One curve is drawn as a sweep draws its own cases (sweep_report.stability_chart): the joined
    // realisations as its cases, a point per density, A's 1700 kg/m^3 case beside B's.
    EXPECT_GT(fs::file_size(dir_ / "j.png"), 10000u);
    const Result cases =
        run("cd " + kSource + "/studies && /usr/bin/python3 -c 'import compare_curves as c; " +
            "print(sorted((x[\"values\"][\"unit.0.density\"], x[\"figures\"][\"N_od\"]) for x in " +
            "c.as_sweep_cases(*c.read_curve(\"" + joined + "\"))))'");
    ASSERT_EQ(cases.status, 0) << cases.output;
    EXPECT_EQ(cases.output, "[(1700.0, 0.16), (1700.0, 0.64), (2000.0, 0.0)]\n");

    // --seeds keeps only those seeds' realisations in every curve: A's seed 1 at 2000 kg/m^3 (0 of
    // 0.5) and 1700 kg/m^3 (1 of 4.0), 1 of 4.5 in all (P(X <= 1 | 4.5) = 5.5 e^-4.5 = 0.061), beside
    // B's own seed 1 (4 of 4.5). A seed a curve has not run is refused, naming the curve.
    const Result seeded = run(script + (dir_ / "a").string() + " " + (dir_ / "b").string() +
                              " --seeds 1 --out " + (dir_ / "s.png").string());
    ASSERT_EQ(seeded.status, 0) << seeded.output;
    EXPECT_NE(seeded.output.find("unit.0.density 2000.0: Ns 2.50  0 / 0.5 (P 0.61)  over 1 realisations"),
              std::string::npos)
        << seeded.output;
    EXPECT_NE(seeded.output.find("all: 1 / 4.5 (P 0.061)"), std::string::npos) << seeded.output;
    EXPECT_NE(seeded.output.find("all: 4 / 4.5 (P 0.53)"), std::string::npos) << seeded.output;
    const Result unseeded = run(script + (dir_ / "a").string() + " " + (dir_ / "b").string() +
                                " --seeds 1,2 --out " + (dir_ / "d.png").string());
    EXPECT_EQ(unseeded.status, 2) << unseeded.output;
    EXPECT_EQ(unseeded.output,
              "armour: error: " + (dir_ / "b").string() + ": --seeds: no done case with seed 2\n");
    EXPECT_FALSE(fs::exists(dir_ / "d.png"));

    const Result bad = run(script + (dir_ / "missing").string() + " --out " + (dir_ / "d.png").string());
    EXPECT_EQ(bad.status, 2) << bad.output;
    EXPECT_EQ(bad.output, "armour: error: " + (dir_ / "missing" / "results.csv").string() +
                              ": not found (not a kept stability curve)\n");
    EXPECT_FALSE(fs::exists(dir_ / "d.png"));
    // Folders that vary different keys do not make one curve.
    write(dir_ / "h" / "results.csv", "case,waves.Hs,seed,status,Ns,N_od,units_displaced,"
                                      "units_displaced_van_der_meer,waves.waves,s_om\n"
                                      "Hs-0.15_seed-1,0.15,1,done,3.3,0,0,1.4,27,0.04\n");
    const Result mixed = run(script + (dir_ / "b").string() + "+" + (dir_ / "h").string() + " --out " +
                             (dir_ / "d.png").string());
    EXPECT_EQ(mixed.status, 2) << mixed.output;
    EXPECT_NE(mixed.output.find("varies 'waves.Hs', the curve's first folder 'unit.0.density'"),
              std::string::npos)
        << mixed.output;
    EXPECT_FALSE(fs::exists(dir_ / "d.png"));
    // A value the folder's varied key never takes is refused, naming the folder, key and value.
    const Result none = run(script + (dir_ / "b").string() + "+" + (dir_ / "a").string() + ":2100 --out " +
                            (dir_ / "d.png").string());
    EXPECT_EQ(none.status, 2) << none.output;
    EXPECT_EQ(none.output, "armour: error: " + (dir_ / "b").string() + "+" + (dir_ / "a").string() +
                               ":2100: " + (dir_ / "a").string() +
                               " has no done case with unit.0.density = 2100\n");
    EXPECT_FALSE(fs::exists(dir_ / "d.png"));
}

// The gap as a factor on Ns (studies/compare_curves.py): with one realisation
// the likelihood peaks where Van der Meer's expected count at Ns / f equals the
// count seen, so f = Ns / Ns_VdM(N_od seen) on the formula itself; the same
// curve given twice and pooled peaks at the same f; a curve that displaced
// nothing bounds no factor and says so.
TEST_F(SweepTest, ComparedCurvesGiveTheGapAsAFactorOnNs) {
    const std::string header = "case,unit.0.density,seed,status,Ns,N_od,units_displaced,"
                               "units_displaced_van_der_meer,waves.waves,s_om\n";
    write(dir_ / "one" / "results.csv", header + "d-1700_seed-1,1700.0,1,done,4.0,0.11,1,4.0,27,0.03\n");
    write(dir_ / "none" / "results.csv", header + "d-1700_seed-1,1700.0,1,done,4.0,0,0,4.0,27,0.03\n");
    // Van der Meer for cubes: N_od = ((Ns s_om^0.1 - 1) N^0.3 / 6.7)^2.5 and its inverse.
    const double n = 27.0, s_om = 0.03;
    const double n_od_at_4 = std::pow((4.0 * std::pow(s_om, 0.1) - 1.0) * std::pow(n, 0.3) / 6.7, 2.5);
    const double width = 4.0 / n_od_at_4; // units per N_od: 4.0 expected at Ns 4.0
    const double ns_of_one =
        (6.7 * std::pow(1.0 / width, 0.4) / std::pow(n, 0.3) + 1.0) * std::pow(s_om, -0.1);
    char expected[64];
    std::snprintf(expected, sizeof expected, "f = %.2f (95 %%", 4.0 / ns_of_one);

    const std::string script = "/usr/bin/python3 " + kSource + "/studies/compare_curves.py ";
    const Result r = run(script + (dir_ / "one").string() + " " + (dir_ / "none").string() + " --out " +
                         (dir_ / "c.png").string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find(std::string("all: the counts are Van der Meer's at Ns / f, ") + expected),
              std::string::npos)
        << expected << "\n"
        << r.output;
    EXPECT_NE(r.output.find("all: no unit displaced: the factor on Ns is not bounded"), std::string::npos)
        << r.output;

    const Result pooled = run(script + (dir_ / "one").string() + " " + (dir_ / "one").string() +
                              " --pool --out " + (dir_ / "d.png").string());
    ASSERT_EQ(pooled.status, 0) << pooled.output;
    const auto at = pooled.output.find("pooled:");
    ASSERT_NE(at, std::string::npos) << pooled.output;
    EXPECT_NE(pooled.output.find(expected, at), std::string::npos) << expected << "\n" << pooled.output;
}

// What a point would take (studies/compare_curves.py): a realisation whose
// count is the formula's (4 of 4.0, so f = 1) and no second realisation to
// widen the scatter: n realisations hold 4 n units on average, and f within a
// factor 1.1 at 95 % asks 1.96 sqrt(1 / (4 n)) / slope = ln 1.1, with the
// slope of ln N_od against ln Ns the formula's, 2.5 x / (x - 1) at x = Ns
// s_om^0.1: 7.04 realisations at 10 %, 1.92 at 20 %; a precision of 0 is
// refused before anything is written.
TEST_F(SweepTest, ComparedCurvesSayHowManyRealisationsAPointNeeds) {
    write(dir_ / "one" / "results.csv", "case,unit.0.density,seed,status,Ns,N_od,units_displaced,"
                                        "units_displaced_van_der_meer,waves.waves,s_om\n"
                                        "d-1700_seed-1,1700.0,1,done,4.0,0.11,4,4.0,27,0.03\n");
    const double x = 4.0 * std::pow(0.03, 0.1), slope = 2.5 * x / (x - 1.0);
    const auto needed = [&](double precision) {
        return std::pow(1.96 / (std::log(1.0 + precision) * slope), 2) / 4.0;
    };
    ASSERT_NEAR(needed(0.1), 7.04, 0.01); // far enough from 7 and 8 for the likelihood's grid
    const std::string script = "/usr/bin/python3 " + kSource + "/studies/compare_curves.py " +
                               (dir_ / "one").string() + " --out " + (dir_ / "c.png").string();
    for (const double precision : {0.1, 0.2}) {
        const Result r = run(script + " --precision " + std::to_string(precision));
        ASSERT_EQ(r.status, 0) << r.output;
        char line[160];
        std::snprintf(line, sizeof line, "at f 1.00 and independent units' scatter: Ns 4.00: %d\n",
                      static_cast<int>(std::ceil(needed(precision))));
        EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
    }
    fs::remove(dir_ / "c.png");
    const Result bad = run(script + " --precision 0");
    EXPECT_EQ(bad.status, 2) << bad.output;
    EXPECT_EQ(bad.output, "armour: error: --precision: 0 is not a relative half-width in (0, 1]\n");
    EXPECT_FALSE(fs::exists(dir_ / "c.png"));
}

// The same seats at rising Ns (studies/compare_curves.py): per seed, the units
// that ended 0.25 Dn or more from their settled pose at one point and again at
// the next point up, against the count if the next point's were drawn at
// random from its units. Seed 1 runs at three points, {0, 1} -> {0, 1, 2} ->
// {2, 5}: 2 of 2 and 1 of 3 again; seed 2 at two, {3} -> {4}: none. 3 of 6,
// where random draws give 2·3/10 + 3·2/10 + 1·1/10 = 1.3, P(X >= 3 | 1.3) =
// 1 - e^-1.3 (1 + 1.3 + 1.3²/2) = 0.14. Unit 2 ends at exactly 0.25 Dn (it
// counts), unit 7 at 0.2499 (it does not). Without damage.csv it is not known.
TEST_F(SweepTest, ComparedCurvesSayWhetherTheSameSeatsLeaveAtRisingNs) {
    write(dir_ / "held" / "results.csv", "case,unit.0.density,seed,status,Ns,N_od,units_displaced,"
                                         "units_displaced_van_der_meer,waves.waves,s_om\n"
                                         "d-2400_seed-1,2400.0,1,done,2.0,0,0,0.1,27,0.03\n"
                                         "d-2400_seed-2,2400.0,2,done,2.1,0,0,0.1,27,0.03\n"
                                         "d-2000_seed-1,2000.0,1,done,3.0,0,0,1.0,27,0.03\n"
                                         "d-2000_seed-2,2000.0,2,done,3.1,0,0,1.0,27,0.03\n"
                                         "d-1700_seed-1,1700.0,1,done,4.0,0,0,4.0,27,0.03\n");
    const auto damage = [&](const std::string &c, const std::map<int, double> &moved) {
        std::string text = "# damage per unit\nbody,unit,s_m,y_m,final_displacement_over_Dn,displaced\n";
        for (int body = 0; body < 10; ++body) {
            const auto it = moved.find(body);
            text += std::to_string(body) + ",cube,0.1,0," +
                    std::to_string(it == moved.end() ? 0.01 : it->second) + ",0\n";
        }
        write(dir_ / "held" / "cases" / c / "run" / "damage.csv", text);
    };
    damage("d-2400_seed-1", {{0, 0.3}, {1, 0.6}});
    damage("d-2000_seed-1", {{0, 0.5}, {1, 0.9}, {2, 0.25}, {7, 0.2499}});
    damage("d-1700_seed-1", {{2, 1.2}, {5, 0.4}});
    damage("d-2400_seed-2", {{3, 0.3}});
    damage("d-2000_seed-2", {{4, 0.7}});
    const std::string script = "/usr/bin/python3 " + kSource + "/studies/compare_curves.py ";
    const Result r = run(script + (dir_ / "held").string() + " --out " + (dir_ / "c.png").string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(
        r.output.find("the same seats at rising Ns (per seed, units ending >= 0.25 Dn from their settled "
                      "pose at one point that do again at the next point up): 3 of 6 (50 %), 1.3 at "
                      "random (P 0.14 of so many)"),
        std::string::npos)
        << r.output;

    fs::remove_all(dir_ / "held" / "cases");
    const Result bare = run(script + (dir_ / "held").string() + " --out " + (dir_ / "c.png").string());
    ASSERT_EQ(bare.status, 0) << bare.output;
    EXPECT_NE(bare.output.find("the same seats at rising Ns: not known"), std::string::npos) << bare.output;
}

// Seats on a settled layer (studies/seats.py): how far each cube's outermost
// corner stands above its highest neighbour's, in closed form on four
// unturned cubes beside a 1:1.5 face, and the displaced among the proud
// against a random draw (hypergeometric); a case whose bodies do not sit where
// the layer has them is refused.
TEST_F(SweepTest, SeatsTellHowFarEachUnitStandsAboveItsNeighbours) {
    const double cot = 1.5, root = std::sqrt(1.0 + cot * cot);
    // Unit s up the face from its foot (0, 0), y across, its centre c out of the face (m).
    const auto body = [&](double s, double y, double c) {
        const double x = s * cot / root - c / root, z = s / root + c * cot / root;
        return "[[body]]\nunit = \"cube\"\nposition = [" + std::to_string(x) + ", " + std::to_string(y) +
               ", " + std::to_string(z) + "]\norientation = [1.0, 0.0, 0.0, 0.0]\n\n";
    };
    // Body 0 stands 1 Dn above 1 and 2 (0.04 m higher, 1 Dn = 0.04 m along the face from each); body 3,
    // within 1.5 Dn of all three (0.057 m from 1 and 2), stands 0.25 Dn above 1 and 2 but 0.75 Dn below 0:
    // only 0 is above its highest neighbour, so only 0 is proud. Body 0's centre, 0.02 m up the face and
    // 0.06 m out of it, lies 0.017 m seaward of the face's foot; 1 and 2 (0.02 m out) 0.006 m landward.
    const std::string unit_and_slope =
        "[[unit]]\nname = \"cube\"\nshape = \"cube\"\nsize = 0.04\n\n[[wall]]\n"
        "name = \"slope\"\ntype = \"slope\"\ncot = 1.5\nheight = 1.0\nwidth = 1.0\n\n";
    write(dir_ / "layer.toml", unit_and_slope + body(0.02, 0.0, 0.06) + body(0.02, 0.04, 0.02) +
                                   body(0.02, -0.04, 0.02) + body(0.06, 0.0, 0.03));
    write(dir_ / "held" / "results.csv", "case,unit.0.density,seed,status,Ns,N_od,units_displaced,"
                                         "units_displaced_van_der_meer,waves.waves,s_om\n"
                                         "d-2000_seed-1,2000.0,1,done,3.0,0.4,2,1.0,27,0.03\n"
                                         "d-1700_seed-1,1700.0,1,done,4.0,0.2,1,4.0,27,0.03\n");
    const auto damage = [&](const std::string &c, const std::set<int> &displaced, double shift) {
        const double s[] = {0.02, 0.02, 0.02, 0.06}, y[] = {0.0, 0.04, -0.04, 0.0};
        std::string text = "# damage per unit\nbody,unit,s_m,y_m,final_displacement_over_Dn,displaced\n";
        for (int b = 0; b < 4; ++b)
            text += std::to_string(b) + ",cube," + std::to_string(s[b] + shift) + "," + std::to_string(y[b]) +
                    (displaced.count(b) ? ",1.5,1\n" : ",0.01,0\n");
        write(dir_ / "held" / "cases" / c / "run" / "damage.csv", text);
    };
    damage("d-2000_seed-1", {0, 1}, 0.0);
    damage("d-1700_seed-1", {0}, 0.0);
    const std::string command = "/usr/bin/python3 " + kSource + "/studies/seats.py " +
                                (dir_ / "held").string() + " --layer 1=" + (dir_ / "layer.toml").string() +
                                " --out " + (dir_ / "out").string();
    const Result r = run(command);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(
        r.output.find("proud units (above every neighbour within 1.5 Dn): 1 of 4; of the 2 units that were "
                      "displaced at a point, 1 were proud (2 of 3 unit-points), 0.5 at random (P 0.5 of so "
                      "many)"),
        std::string::npos)
        << r.output;
    EXPECT_NE(
        r.output.find("+0.5 Dn or more:    1 units; left their seat at a point   1 (100.0 %), displaced at "
                      "a point   1 (100.0 %), unit-points displaced 2"),
        std::string::npos)
        << r.output;
    const json summary = json::parse(read_text(dir_ / "out" / "summary.json"));
    EXPECT_EQ(summary["proud_units"], 1);
    EXPECT_EQ(summary["displaced_unit_points_proud"], 2);
    EXPECT_NEAR(summary["displaced_p_value"].get<double>(), 0.5, 1e-12); // 1 - C(3,2) / C(4,2)
    // Where they sat: body 0 alone at the foot (seaward of it), displaced at both points; body 1 on the face
    // at one.
    EXPECT_NE(r.output.find("  at the foot,     proud:    1 units, displaced at a point   1 (100.0 %), "
                            "unit-points 2"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("over the face, not proud:    3 units, displaced at a point   1 (33.3 %), "
                            "unit-points 1"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(summary["units_at_foot"], 1);
    EXPECT_EQ(summary["displaced_unit_points_at_foot"], 2);
    // Without body 0 the curve has one displaced unit of the three: it needs a higher Ns for the same
    // count, so its factor on Ns is larger.
    EXPECT_GT(summary["ns_factor_without_units_at_foot"][0].get<double>(),
              summary["ns_factor"][0].get<double>());

    // With a pull test's resistances and the waves' load swings (bench/pull_vs_loads.py's table): body 0,
    // proud, held 0.5 weights; the rest 2.0, 2.5 and the whole pull (ranked above every other). Rank sum:
    // U 0 against 1.5, variance 1 x 3 / 12 x 5, |U - 1.5| - 0.5 = 1: P = erfc(1 / sqrt(1.25) / sqrt(2)) =
    // 0.37.
    write(dir_ / "loads" / "pull_vs_loads.csv", "# forces in unit weights\nbody,s_over_Dn,resistance_weights,"
                                                "stayed_in_pull,seat_weight_N,peak_swing_out_weights\n"
                                                "0,2.5,0.5,False,1.0,0.3\n1,2.5,2.0,False,1.0,0.3\n"
                                                "2,2.5,,True,1.0,0.4\n3,3.5,2.5,False,1.0,0.2\n");
    const Result pulled = run(command + " --pulled 1=" + (dir_ / "loads").string());
    ASSERT_EQ(pulled.status, 0) << pulled.output;
    EXPECT_NE(
        pulled.output.find("held in the pull (unit weights): proud 0.50 (quartiles 0.50-0.50, 1 units), the "
                           "rest 2.50 (2.00-2.50, 3); P 0.37 of a split as wide"),
        std::string::npos)
        << pulled.output;
    // Displaced at a point: bodies 0 and 1 (0.5, 2.0) against 2 and 3 (the whole pull, 2.5): U 0 against 2,
    // variance 2 x 2 / 12 x 5, P = erfc(1.5 / sqrt(5 / 3) / sqrt(2)) = 0.25; quartiles as sample values
    // (lower).
    EXPECT_NE(
        pulled.output.find("held in the pull by the units displaced at a point: 0.50 (quartiles 0.50-0.50, 2 "
                           "units), by the rest 2.50 (2.50-2.50, 2); P 0.25 of a split as wide"),
        std::string::npos)
        << pulled.output;

    // The layer as placed, before the settle: body 0 placed 0.1 m (2.5 Dn) further up the face, on it
    // (x 0.067 m), the others where they settled. So the one unit that slid 2 Dn or more is the proud
    // one (P 1 / 4 at random) and slid to the foot.
    write(dir_ / "placed.toml", unit_and_slope + body(0.12, 0.0, 0.06) + body(0.02, 0.04, 0.02) +
                                    body(0.02, -0.04, 0.02) + body(0.06, 0.0, 0.03));
    const Result placed = run(command + " --placed 1=" + (dir_ / "placed.toml").string());
    ASSERT_EQ(placed.status, 0) << placed.output;
    EXPECT_NE(placed.output.find("below +1.0 Dn:    3 units, proud   0 (0.0 %), displaced at a point   1 "
                                 "(33.3 %), unit-points 1"),
              std::string::npos)
        << placed.output;
    EXPECT_NE(placed.output.find("+2.0 Dn or more:    1 units, proud   1 (100.0 %), displaced at a point   1 "
                                 "(100.0 %), unit-points 2"),
              std::string::npos)
        << placed.output;
    EXPECT_NE(placed.output.find("slid 2 Dn or more: 1 of the 1 proud, 0.2 at random (P 0.25 of so many)"),
              std::string::npos)
        << placed.output;
    EXPECT_NE(
        placed.output.find("at the foot, slid there in the settle: 1 units, proud 1, displaced at a point 1"),
        std::string::npos)
        << placed.output;
    // The layer alone, before any waves (no curve): its proud units and its slide, no damage.
    const Result alone =
        run("/usr/bin/python3 " + kSource + "/studies/seats.py --layer 1=" + (dir_ / "layer.toml").string() +
            " --placed 1=" + (dir_ / "placed.toml").string() + " --out " + (dir_ / "alone").string());
    ASSERT_EQ(alone.status, 0) << alone.output;
    EXPECT_NE(
        alone.output.find("seed 1: 1 of 4 units proud (above every neighbour within 1.5 Dn, 25.0 %), 1 at "
                          "the foot"),
        std::string::npos)
        << alone.output;
    EXPECT_NE(alone.output.find("+2.0 Dn or more:    1 units, proud   1 (100.0 %)\n"), std::string::npos)
        << alone.output;
    EXPECT_EQ(alone.output.find("displaced"), std::string::npos) << alone.output;
    write(dir_ / "three.toml",
          unit_and_slope + body(0.12, 0.0, 0.06) + body(0.02, 0.04, 0.02) + body(0.02, -0.04, 0.02));
    const Result short_layer = run(command + " --placed 1=" + (dir_ / "three.toml").string());
    EXPECT_EQ(short_layer.status, 2);
    EXPECT_NE(short_layer.output.find("armour: error: --placed 1=" + (dir_ / "three.toml").string() +
                                      ": 3 bodies, the seed's settled layer 4"),
              std::string::npos)
        << short_layer.output;

    damage("d-1700_seed-1", {0}, 0.002); // 2 mm up the face: another layer
    const Result other = run(command);
    EXPECT_EQ(other.status, 2);
    EXPECT_NE(other.output.find("armour: error: case d-1700_seed-1: body 0 sits at s_m 0.0220"),
              std::string::npos)
        << other.output;
    EXPECT_NE(other.output.find("the case did not run on this layer"), std::string::npos) << other.output;
}

// A dry scene of a layer (studies/dry_scene.py): the scene's tables less the
// fluid's (their sub-tables too), the bodies as the scene holds them or, with
// --run and --time, each at the record nearest the time asked, at rest; a
// scene whose bodies are not the record's is one error line and nothing
// written.
TEST_F(SweepTest, DrySceneTakesEachBodyFromTheRecordWithoutTheFluid) {
    const std::string body = "[[body]]\nunit = \"cube\"\nposition = [0.0, 0.0, 0.0] # m\n"
                             "orientation = [1.0, 0.0, 0.0, 0.0]\nvelocity = [0.5, 0.0, 0.0] # m/s\n"
                             "angular_velocity = [0.0, 0.0, 0.0] # rad/s\n\n";
    write(dir_ / "scene.toml",
          "[run]\nduration = 1.0\n\n[fluid]\nwater_level = 0.4\n\n[fluid.turbulence]\nmodel = "
          "\"laminar\"\n\n[waves]\ntype = \"irregular\"\n\n[[refine]]\nlevels = 1\nbox = [\n[0.0, "
          "0.0],\n[1.0, 1.0]]\n\n" +
              body + body);
    fs::create_directories(dir_ / "run");
    write(dir_ / "make.py", R"(
import sys, h5py, numpy as np
with h5py.File(sys.argv[1], "w") as f:
    f["time"] = np.array([0.0, 0.5, 1.0])
    x = np.zeros((3, 2, 3)); x[:, 1, 0] = [0.0, 0.25, 0.5]; f["bodies/position"] = x
    q = np.zeros((3, 2, 4)); q[:, :, 3] = 1.0; f["bodies/orientation"] = q
)");
    ASSERT_EQ(
        run("/usr/bin/python3 " + (dir_ / "make.py").string() + " " + (dir_ / "run" / "bodies.h5").string())
            .status,
        0);
    const std::string script = "/usr/bin/python3 " + kSource + "/studies/dry_scene.py ";
    const std::string at = " --run " + (dir_ / "run").string() + " --time 0.6";
    const Result as_settled =
        run(script + (dir_ / "scene.toml").string() + " " + (dir_ / "settled.toml").string());
    ASSERT_EQ(as_settled.status, 0) << as_settled.output;
    const toml::table settled = toml::parse_file((dir_ / "settled.toml").string());
    EXPECT_FALSE(settled.contains("fluid"));                         // with its sub-table
    EXPECT_FALSE(settled.contains("refine"));                        // with its array's rows
    EXPECT_EQ(settled["body"][0]["velocity"][0].value_or(0.0), 0.5); // as the scene holds it

    const Result r = run(script + (dir_ / "scene.toml").string() + " " + (dir_ / "dry.toml").string() + at);
    ASSERT_EQ(r.status, 0) << r.output;
    const toml::table dry = toml::parse_file((dir_ / "dry.toml").string());
    EXPECT_FALSE(dry.contains("fluid"));
    EXPECT_FALSE(dry.contains("waves"));
    EXPECT_FALSE(dry.contains("refine"));
    EXPECT_EQ(dry["run"]["duration"].value_or(0.0), 1.0);
    const auto *bodies = dry["body"].as_array();
    ASSERT_NE(bodies, nullptr);
    ASSERT_EQ(bodies->size(), 2u);
    // The record nearest 0.6 s is 0.5 s: body 1 at x = 0.25 m, both turned by the record's quaternion, at
    // rest.
    const toml::table &second = *bodies->at(1).as_table();
    EXPECT_EQ(second["position"][0].value_or(-1.0), 0.25);
    EXPECT_EQ(second["orientation"][3].value_or(0.0), 1.0);
    EXPECT_EQ(second["velocity"][0].value_or(-1.0), 0.0);

    write(dir_ / "three.toml", body + body + body);
    const Result bad = run(script + (dir_ / "three.toml").string() + " " + (dir_ / "bad.toml").string() + at);
    EXPECT_EQ(bad.status, 2) << bad.output;
    EXPECT_EQ(bad.output, "armour: error: " + (dir_ / "three.toml").string() +
                              ": more [[body]] tables than the 2 "
                              "bodies of " +
                              (dir_ / "run" / "bodies.h5").string() + "\n");
    EXPECT_FALSE(fs::exists(dir_ / "bad.toml"));
}

// Who left, when and with whom (studies/departures.py), on a run made up so
// that each figure is known: Dn 0.1 m, Delta 1, water 1000 kg/m^3, g 10 m/s^2
// (W' = 10 N); three units move seaward at 3 Dn/s from 1.0, 1.5 and 3.0 s, so
// each starts its move one record later (its first record over 0.2 Dn) and
// passes 1 Dn at 1.35, 1.85 and 3.35 s; the first two are neighbours (1.5 Dn
// apart), the third far. Their seaward loads: 5 N long before and 10 N in the
// move (2 x), 8 N before and 4 N in the move (0.5 x), and 6 N with none before.
// Their ways out, over their last move (from the record at 0.15 Dn to the pass:
// 0.9 Dn in 0.3 s): the first, at the foot, does not turn (slid); the second,
// in the layer (1.5 Dn under its 2 Dn thickness), turns at 90 deg/s, 30 deg per
// Dn (slid and turned), touching nothing; the third, on top of the layer, at
// 270 deg/s, 90 deg per Dn (rolled: a cube's roll over an edge), its upward
// load 5 N (half its buoyancy) below the still water's at its pass.
TEST_F(SweepTest, DeparturesTellTheLoadEachUnitLeftUnderAndWhoLeftTogether) {
    const fs::path run_dir = dir_ / "run";
    fs::create_directories(run_dir);
    write(run_dir / "summary.json", R"({"damage": {"Dn": 0.1, "delta": 1.0, "displaced_threshold": 1.0,
                                        "settled_layer": {"layer_thickness": 0.2}}})");
    const std::string scene =
        "[run]\ngravity = [0.0, 0.0, -10.0]\n[fluid]\nfluid_density = 1000.0\n"
        "[[material]]\nname = \"rough\"\nfriction = 0.9\n[[unit]]\nname = \"cube\"\nmaterial = \"rough\"\n"
        "[[wall]]\nname = \"slope\"\ntype = \"slope\"\ncot = 1.5\nmaterial = \"rough\"\ntoe_x = 0.0\n"
        "floor_z = -0.05\n";
    write(run_dir / "scene.resolved.toml", scene);
    write(run_dir / "damage.csv",
          "# damage per unit\nbody,unit,s_m,y_m,n_m,at_foot,displaced\n0,cube,0.0,0,0.05,1,1\n"
          "1,cube,0.15,0,0.05,0,1\n2,cube,1.0,0,0.25,0,1\n3,cube,0.5,0,0.05,0,0\n");
    const std::string make = R"(
import sys, h5py, numpy as np
t = np.arange(81) * 0.05
x = np.zeros((81, 4, 3)); F = np.zeros((81, 4, 3)); F[1:, :, 2] = 10.0  # buoyancy; none at 0 s, as in a run
q = np.zeros((81, 4, 4)); C = np.zeros((81, 4, 3)); C[:, :, 2] = 10.0  # resting on the layer
for b, seat, start, deg_per_s in ((0, 0.0, 1.0, 0), (1, 0.15, 1.5, 90), (2, 1.0, 3.0, 270), (3, 0.5, 99.0, 0)):
    moving = np.clip(t - start, 0.0, None)
    x[:, b, 0] = seat - 0.3 * moving
    half = np.radians(deg_per_s * moving) / 2  # turning about y
    q[:, b, 0] = np.cos(half); q[:, b, 2] = np.sin(half)
def push(b, at, newtons): F[int(round(at / 0.05)), b, 0] = -newtons
push(0, 0.5, 5.0); push(0, 1.2, 10.0); push(1, 0.5, 8.0); push(1, 1.7, 4.0); push(2, 3.2, 6.0)
C[30:, 1] = 0.0; F[67, 2, 2] = 5.0
with h5py.File(sys.argv[1], "w") as f:
    f["time"] = t; f["bodies/position"] = x; f["bodies/external_force"] = F
    f["bodies/orientation"] = q; f["bodies/contact_force"] = C
)";
    write(dir_ / "make.py", make);
    ASSERT_EQ(run("/usr/bin/python3 " + (dir_ / "make.py").string() + " " + (run_dir / "bodies.h5").string())
                  .status,
              0);

    const std::string script = "/usr/bin/python3 " + kSource + "/studies/departures.py ";
    const Result r = run(script + run_dir.string() + " --out " + (dir_ / "out").string() + " --still 0.25");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(
        r.output.find("unit 0 (seat 0.000 m up the slope) moved from 1.05 s, passed the threshold at 1.35 s "
                      "under 1.00 W', 2.00 x the largest load before, needing 79 deg of friction to stay"),
        std::string::npos)
        << r.output;
    EXPECT_NE(
        r.output.find("unit 1 (seat 0.150 m up the slope) moved from 1.55 s, passed the threshold at 1.85 s "
                      "under 0.40 W', 0.50 x the largest load before, needing 55 deg of friction to stay"),
        std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find(
                  "passed the threshold at 3.35 s under 0.60 W', the first load that way, needing 65 deg"),
              std::string::npos)
        << r.output;
    // Each moved 1.05 Dn seaward (-x) by its pass: on the 1:1.5 face that is 1.05 x 1.5 / sqrt(3.25) =
    // 0.87 Dn down it and 1.05 / sqrt(3.25) = 0.58 Dn out of it, so none slid in the face's plane.
    EXPECT_NE(r.output.find(
                  "2.00 x the largest load before, needing 79 deg of friction to stay; moved -0.87 Dn up the "
                  "face, +0.58 Dn out of it"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find(
                  "moved down the face in its plane (down it >= 3/4 of the threshold, out of it < 1/4; slid "
                  "or rolled): 0 of 3; of the 0 with load figures, 0 met no load along their move beyond "
                  "the still water's"),
              std::string::npos)
        << r.output;
    EXPECT_NE(
        r.output.find("+0.58 Dn out of it; seat at the foot; slid: turned 0 deg over its last 0.90 Dn (0 "
                      "deg per Dn), touching nothing in 0 % of its records, the upward load 0.00 of its "
                      "buoyancy below the still water's"),
        std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("seat in the layer; slid and turned: turned 27 deg over its last 0.90 Dn (30 deg "
                            "per Dn), touching nothing in 100 % of its records"),
              std::string::npos)
        << r.output;
    EXPECT_NE(
        r.output.find("seat on top of the layer; rolled: turned 81 deg over its last 0.90 Dn (90 deg per "
                      "Dn), touching nothing in 0 % of its records, the upward load 0.50 of its buoyancy"),
        std::string::npos)
        << r.output;
    const json summary = json::parse(read_text(dir_ / "out" / "summary.json"));
    EXPECT_EQ(summary["units_displaced"], 3);
    EXPECT_EQ(summary["left_under_a_smaller_load_than_before"], 1);
    EXPECT_EQ(summary["left_under_the_first_load_that_way"], 1);
    EXPECT_NEAR(summary["load_ratio_median"].get<double>(), 1.25, 1e-9);
    // A free block face down on the 1:1.5 face, weight 20 N and buoyancy 10 N, needs atan(1 / 1.5) = 34 deg
    // of friction at rest; pushed seaward by 10 N, atan2(13.87, 2.77) = 79 deg (unit 0), and past the
    // wall's atan(0.9) = 42 deg under every push here.
    EXPECT_NEAR(summary["wall_friction_angle_deg"].get<double>(), 41.99, 0.01);
    EXPECT_EQ(summary["hold_angle_others_past_the_wall"], 3);
    // Together: units 0 and 1. Shuffled, the pair of times 0.5 s apart falls to them 1 time in 3
    // (then 2 together, else 0): a mean of 2/3 and P(>= 2) 1/3, to the shuffles' sampling.
    EXPECT_EQ(summary["left_with_a_neighbour"], 2);
    EXPECT_NEAR(summary["left_with_a_neighbour_shuffled"].get<double>(), 2.0 / 3.0, 0.05);
    EXPECT_NEAR(summary["chance_of_as_many"].get<double>(), 1.0 / 3.0, 0.025);
    const std::string table = read_text(dir_ / "out" / "departures.csv");
    EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 5) << table; // a comment, the header, 3 units
    const json &seats = summary["by_seat"];
    EXPECT_EQ(seats.size(), 3U) << seats.dump();
    EXPECT_EQ(seats["at the foot"]["slid"], 1);
    EXPECT_EQ(seats["in the layer"]["slid_and_turned"], 1);
    EXPECT_NEAR(seats["in the layer"]["turn_per_Dn_median_deg"].get<double>(), 30.0, 1e-6);
    EXPECT_EQ(seats["in the layer"]["off_contact_share_median"], 1.0);
    EXPECT_EQ(seats["on top of the layer"]["rolled"], 1);
    EXPECT_NEAR(seats["on top of the layer"]["turn_per_Dn_median_deg"].get<double>(), 90.0, 1e-6);
    EXPECT_NEAR(seats["on top of the layer"]["upward_load_drop_median"].get<double>(), 0.5, 1e-9);
    EXPECT_EQ(seats["on top of the layer"]["moved_down_the_face"], 1);

    // A unit that slides down the face in its plane (along (-1.5, 0, -1) / sqrt(3.25), 0.3 m/s from 1 s)
    // with no water load on it: 1.05 Dn down the face, none out of it, by its pass at 1.35 s, needing
    // the face's own 34 deg of friction to stay; beside it on the wall a unit that stays under a steady
    // seaward 10 N and buoyancy 10 N, which asks 79 deg of a free block.
    const fs::path slide_dir = dir_ / "slide";
    fs::create_directories(slide_dir);
    write(slide_dir / "summary.json", R"({"damage": {"Dn": 0.1, "delta": 1.0, "displaced_threshold": 1.0}})");
    write(slide_dir / "scene.resolved.toml", scene);
    write(slide_dir / "damage.csv",
          "# damage per unit\nbody,unit,s_m,y_m,displaced\n0,cube,0.3,0,1\n1,cube,0.5,0,0\n");
    write(dir_ / "slide.py", R"(
import sys, h5py, numpy as np
t = np.arange(81) * 0.05
x = np.zeros((81, 2, 3)); F = np.zeros((81, 2, 3)); F[1:, 1] = [-10.0, 0.0, 10.0]
x[:, 0, :] = np.outer(0.3 * np.clip(t - 1.0, 0.0, None), np.array([-1.5, 0.0, -1.0]) / np.sqrt(3.25))
q = np.zeros((81, 2, 4)); q[:, :, 0] = 1.0; C = np.zeros((81, 2, 3)); C[:, :, 2] = 10.0
with h5py.File(sys.argv[1], "w") as f:
    f["time"] = t; f["bodies/position"] = x; f["bodies/external_force"] = F
    f["bodies/orientation"] = q; f["bodies/contact_force"] = C
)");
    ASSERT_EQ(
        run("/usr/bin/python3 " + (dir_ / "slide.py").string() + " " + (slide_dir / "bodies.h5").string())
            .status,
        0);
    const Result slide = run(script + slide_dir.string() + " --out " + (dir_ / "slide_out").string());
    ASSERT_EQ(slide.status, 0) << slide.output;
    EXPECT_NE(
        slide.output.find("under no push along its move (+0.00 W'), needing 34 deg of friction to stay; "
                          "moved -1.05 Dn up the face, +0.00 Dn out of it"),
        std::string::npos)
        << slide.output;
    EXPECT_NE(slide.output.find(
                  "in its plane (down it >= 3/4 of the threshold, out of it < 1/4; slid or rolled): 1 of "
                  "1; of the 1 with load figures, 1 met no load along their move beyond the still water's"),
              std::string::npos)
        << slide.output;
    const json slid = json::parse(read_text(dir_ / "slide_out" / "summary.json"));
    EXPECT_EQ(slid["in_plane_down_the_face"], 1);
    EXPECT_EQ(slid["in_plane_down_the_face_unpushed"], 1);
    EXPECT_EQ(slid["hold_angle_in_plane_past_the_wall"], 0);
    EXPECT_EQ(slid["in_plane_inner_layer"], 1);
    EXPECT_NEAR(slid["hold_angle_in_plane_inner_median_deg"].get<double>(), 33.69, 0.01);
    EXPECT_NEAR(slid["hold_angle_stayed_inner_same_stretches_median_deg"].get<double>(), 78.69, 0.01);
    EXPECT_EQ(slid["stayed_inner_past_the_wall_share"], 1.0);
    // Read against still water at 2 s, it passed while the layer settled: no load figures, still counted.
    const Result settling =
        run(script + slide_dir.string() + " --out " + (dir_ / "settling").string() + " --still 2");
    ASSERT_EQ(settling.status, 0) << settling.output;
    EXPECT_NE(settling.output.find("passed the threshold at 1.35 s before the still water's record (no load "
                                   "figures); moved -1.05 Dn up the face"),
              std::string::npos)
        << settling.output;
    const json settled = json::parse(read_text(dir_ / "settling" / "summary.json"));
    EXPECT_EQ(settled["passed_before_the_still_record"], 1);
    EXPECT_EQ(settled["in_plane_down_the_face"], 1);
    EXPECT_EQ(settled["by_seat"]["unknown"]["slid"], 1); // damage.csv without at_foot: no seat

    const Result bad = run(script + (dir_ / "missing").string() + " --out " + (dir_ / "bad").string());
    EXPECT_EQ(bad.status, 2) << bad.output;
    EXPECT_EQ(bad.output, "armour: error: " + (dir_ / "missing" / "bodies.h5").string() +
                              ": not found (not the folder of a coupled damage run)\n");
    EXPECT_FALSE(fs::exists(dir_ / "bad"));
}

// A real single-node Slurm (scripts/slurm-local.sh), started for these tests.
class SlurmSweepTest : public SweepTest {
  protected:
    static void SetUpTestSuite() {
        if (run("command -v slurmctld || test -x /usr/sbin/slurmctld").status != 0 ||
            run("test -x /usr/sbin/munged").status != 0) {
            skip_ = "slurmctld or munged is not installed (apt-get install slurm-wlm munge; "
                    "scripts/debian-packages.txt lists them)";
            return;
        }
        if (::geteuid() != 0) {
            skip_ = "scripts/slurm-local.sh needs root (slurmd runs jobs as their user)";
            return;
        }
        slurm_dir_ = fs::temp_directory_path() / ("armour-slurm-test-" + std::to_string(::getpid()));
        started_ = true; // stopped in any case: a failed start may leave a daemon running
        const Result r = run(env() + kSource + "/scripts/slurm-local.sh start");
        if (r.status != 0)
            start_error_ = "scripts/slurm-local.sh start failed:\n" + r.output;
    }
    static void TearDownTestSuite() {
        if (started_)
            run(env() + kSource + "/scripts/slurm-local.sh stop");
    }
    void SetUp() override {
        if (!skip_.empty())
            GTEST_SKIP() << skip_;
        if (!start_error_.empty())
            FAIL() << start_error_; // a Slurm that will not start is a failure, not a skip
        SweepTest::SetUp();
    }
    // Its own folder and ports (ctest -j runs each test in its own process,
    // each starting its own Slurm), so a Slurm started by hand keeps running.
    static std::string env() {
        const int port = 20000 + 2 * static_cast<int>(::getpid() % 5000);
        return "ARMOUR_SLURM_DIR=" + slurm_dir_.string() + " ARMOUR_SLURM_PORT=" + std::to_string(port) +
               " SLURM_CONF=" + (slurm_dir_ / "slurm.conf").string() + " ";
    }
    static inline std::string skip_, start_error_;
    static inline fs::path slurm_dir_;
    static inline bool started_ = false;
};

TEST_F(SlurmSweepTest, TiltSweepRunsAsOneJobArray) {
    const fs::path out = dir_ / "out";
    // Submitted without waiting, gathered with --collect.
    const Result submitted = run(env() + kArmour + " sweep " + tilt_sweep().string() + " --out " +
                                 out.string() + " --executor slurm --no-wait");
    ASSERT_EQ(submitted.status, 0) << submitted.output;
    EXPECT_NE(submitted.output.find("submitted Slurm job array"), std::string::npos) << submitted.output;
    const Result r = run(env() + kArmour + " sweep --collect " + out.string());
    ASSERT_EQ(r.status, 0) << r.output << read_text(slurm_dir_ / "slurmctld.log");
    expect_tilt_results(out);
    // Slurm's own record: one array, one completed task per case.
    const std::string job = json::parse(read_text(out / "slurm" / "job.json"))["job_id"];
    std::ifstream log(slurm_dir_ / "jobcomp.txt");
    std::multiset<int> tasks;
    for (std::string line; std::getline(log, line);)
        if (line.find(" ArrayJobId=" + job + " ") != std::string::npos) {
            EXPECT_NE(line.find("JobState=COMPLETED"), std::string::npos) << line;
            tasks.insert(std::atoi(line.c_str() + line.find("ArrayTaskId=") + 12));
        }
    EXPECT_EQ(tasks, (std::multiset<int>{0, 1, 2, 3})) << read_text(slurm_dir_ / "jobcomp.txt");
    EXPECT_NE(read_text(out / "slurm" / "array.sbatch").find("#SBATCH --array=0-3"), std::string::npos);
}

// One coupled case on two MPI ranks inside its Slurm task (the way a case
// spans a cluster's cores: the array task holds run.np tasks and the run's
// mpirun starts interFoam's ranks in that allocation). The case is
// CoupledRun.LiggghtsSerialAndTwoRanksAgree's: a concrete cube sinking 6 cm
// in still water, ~3 s a run. Checked: the case ran on 2 ranks (both
// LIGGGHTS replicas wrote their logs and agreed to the bit), and it follows
// the serial run outside Slurm to that test's tolerance, 1e-4 of the edge
// (20 um; measured 1.3e-7 m).
TEST_F(SlurmSweepTest, ACoupledCaseRunsOnTwoRanksInsideItsSlurmTask) {
    const std::string scene = kSource + "/scenes/still_water_cube.toml";
    const std::vector<std::pair<std::string, std::string>> sets = {
        {"run.engine", "\"liggghts\""}, {"body.0.position", "[0.0, 0.0, 0.17]"}, {"run.duration", "0.4"}};
    // A sweep varies something: the penalty, over its one value.
    std::string sweep_text = "scene = \"" + scene + "\"\n[vary]\n\"fluid.penalty\" = [1e4]\n[set]\n";
    std::string flags = " --set fluid.penalty=1e4";
    for (const auto &[key, value] : sets) {
        sweep_text += "\"" + key + "\" = " + value + "\n";
        flags += " --set '" + key + "=" + value + "'";
    }
    const fs::path sweep = dir_ / "two-ranks.toml", out = dir_ / "out", serial = dir_ / "serial";
    write(sweep, sweep_text + "[run]\nnp = 2\n");
    const Result r =
        run(env() + kArmour + " sweep " + sweep.string() + " --out " + out.string() + " --executor slurm");
    ASSERT_EQ(r.status, 0) << r.output << read_text(slurm_dir_ / "slurmctld.log");
    EXPECT_NE(read_text(out / "slurm" / "array.sbatch").find("#SBATCH --ntasks=2"), std::string::npos);
    const fs::path run_dir = out / "cases" / "penalty-10000.0" / "run";
    const json parallel = json::parse(read_text(run_dir / "summary.json"));
    EXPECT_EQ(parallel["fluid"]["np"], 2);
    const json times = json::parse(read_text(run_dir / "coupling_times.json"));
    EXPECT_EQ(times.value("replicas_identical", false), true) << times.dump();
    EXPECT_TRUE(fs::is_regular_file(run_dir / "case" / "armourEngine" / "processor1" / "log.liggghts"));

    const Result alone = run(kArmour + " run " + scene + " --out " + serial.string() + flags);
    ASSERT_EQ(alone.status, 0) << alone.output;
    const json one = json::parse(read_text(serial / "summary.json"));
    const double sinks = one["max_displacement"].get<double>();
    EXPECT_GT(sinks, 0.02); // a moving cube is compared
    EXPECT_NEAR(parallel["max_displacement"].get<double>(), sinks, 1e-4 * 0.2);
}

TEST_F(SlurmSweepTest, FailedTaskIsReportedWithSlurmStateAndLogTail) {
    // A cube thrown up at 30 m/s: every check before the run passes, the run
    // stops when it leaves the domain (a cube placed into the plate, the case
    // here before, is now refused before the sweep submits anything).
    const fs::path sweep = dir_ / "thrown-out.toml", out = dir_ / "out";
    write(sweep, "scene = \"" + kSource +
                     "/scenes/tilt_cube.toml\"\n[vary]\n\"body.0.velocity\" = [[0.0, 0.0, 30.0]]\n");
    const Result r =
        run(env() + kArmour + " sweep " + sweep.string() + " --out " + out.string() + " --executor slurm");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find("Slurm task"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("FAILED"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("left the domain"), std::string::npos) << "no log tail in: " << r.output;
    const json summary = json::parse(read_text(out / "summary.json"));
    ASSERT_EQ(summary["cases"].size(), 1u);
    EXPECT_EQ(summary["cases"][0]["status"], "failed");
    EXPECT_EQ(summary["failed"], 1);
    EXPECT_EQ(summary["cases"][0]["slurm_state"], "FAILED");
}

// Under Slurm the sweep that follows the job array rewrites report.md as each
// task ends, as the local one does. Two tilt tests side by side: at 20 deg/s
// the cube slides at 1.3 s, at 0.01 deg/s it would at 2 660 s (minutes of
// wall time). Once the first has ended and the second still runs, report.md
// says so. The job is then cancelled: the long case ends as a failed case
// with Slurm's state, and the sweep exits 1.
TEST_F(SlurmSweepTest, ReportFollowsTheTasksAsTheyEnd) {
    const fs::path file = dir_ / "tilt_rates.toml", out = dir_ / "following";
    write(file, "scene = \"" + kSource +
                    "/scenes/tilt_cube.toml\"\n[vary]\n\"analysis.tilt_rate\" = [20.0, 0.01]\n"
                    "[set]\n\"run.duration\" = 6000.0\n");
    // The sweep itself, not a shell: `env` hands it Slurm's settings and execs it under the same pid.
    const pid_t sweep =
        armour_test::start_quietly({"/bin/sh", "-c",
                                    "exec env " + env() + kArmour + " sweep " + file.string() + " --out " +
                                        out.string() + " --executor slurm"});
    std::string report;
    const bool followed = armour_test::wait_until(sweep, [&] {
        report = read_text(out / "report.md");
        return report.find("1 of 2 cases done") != std::string::npos;
    });
    const std::string long_case = read_text(out / "cases" / "tilt_rate-0.01" / "case.json");
    std::string job;
    if (fs::exists(out / "slurm" / "job.json"))
        job = json::parse(read_text(out / "slurm" / "job.json"))["job_id"];
    if (!job.empty())
        run(env() + "scancel " + job);
    ASSERT_TRUE(followed) << "the sweep ended before report.md counted the short case";
    EXPECT_NE(report.find("1 of 2 cases done, 0 failed, 1 not finished"), std::string::npos) << report;
    EXPECT_NE(report.find("| tilt_rate-20.0 | 20.0 |  | done |"), std::string::npos) << report;
    EXPECT_EQ(long_case.find("\"status\": \"done\""), std::string::npos) << "it ended first: " << long_case;

    EXPECT_EQ(armour_test::wait_for(sweep), 1); // cancelled: a case did not finish
    const json summary = json::parse(read_text(out / "summary.json"));
    EXPECT_EQ(summary["done"], 1);
    EXPECT_EQ(summary["failed"], 1);
    std::string cancelled; // the long case's Slurm state
    for (const json &c : summary["cases"])
        if (c["case"] == "tilt_rate-0.01") {
            EXPECT_EQ(c["status"], "failed");
            cancelled = c.value("slurm_state", "");
        }
    EXPECT_EQ(cancelled.rfind("CANCELLED", 0), 0u) << summary.dump();
}

} // namespace
