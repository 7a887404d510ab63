// Smoke: every shipped scene (scenes/*.toml, as the folder holds them) runs
// as shipped through the armour binary, shortened only by run.duration (and
// for one scene its settle: scene_smoke.h): exit 0, summary.json written, every
// headline figure of its analysis a finite number, the run at its shortened
// end, and a coupled run through several interFoam steps. A scene without a
// row in kSmoke (scene_smoke.h) fails: a new scene gets its smoke run with it.
#include "analysis.h"
#include "scene.h"
#include "scene_run.h"
#include "scene_smoke.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using armour_test::kSmoke;
using armour_test::Smoke;
using nlohmann::json;

namespace {

std::vector<std::string> shipped_scenes() {
    std::vector<std::string> names;
    for (const auto &entry : fs::directory_iterator(fs::path(ARMOUR_SOURCE_DIR) / "scenes"))
        if (entry.path().extension() == ".toml")
            names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// "slope_cubes.toml" -> "slope_cubes" (gtest names take letters, digits and '_').
std::string test_name(const ::testing::TestParamInfo<std::string> &info) {
    std::string name = fs::path(info.param).stem().string();
    for (char &c : name)
        if (!std::isalnum(static_cast<unsigned char>(c)))
            c = '_';
    return name;
}

class SceneSmoke : public ::testing::TestWithParam<std::string> {};

TEST_P(SceneSmoke, RunsAsShipped) {
    const std::string name = GetParam();
    const auto row = kSmoke.find(name);
    ASSERT_NE(row, kSmoke.end()) << "scenes/" << name
                                 << " has no smoke run: add it to kSmoke in tests/scene_smoke.h "
                                    "with the shortest run.duration that gives its figures";
    const Smoke &smoke = row->second;
    const double duration = armour_test::smoke_duration(smoke);
    ASSERT_TRUE(std::isfinite(duration)) << name << ": the smoke must shorten run.duration";
    const fs::path path = fs::path(ARMOUR_SOURCE_DIR) / "scenes" / name;

    // What this build can run: a scene with [fluid] needs the OpenFOAM
    // plugin, one naming Bullet the Bullet engine.
    const toml::table raw = toml::parse_file(path.string());
    const bool coupled = raw.contains("fluid");
#ifndef ARMOUR_HAS_OPENFOAM
    if (coupled)
        GTEST_SKIP() << name << " is coupled: this build has no OpenFOAM plugin";
#endif
#ifndef ARMOUR_HAS_BULLET
    if (raw["run"]["engine"].value_or(std::string()) == "bullet")
        GTEST_SKIP() << name << " runs Bullet: this build has none";
#endif
    const armour::Scene scene = armour::load_scene(path.string(), smoke.sets);

    const armour_test::SceneRun run = armour_test::run_scene(
        ARMOUR_EXE, path, "smoke_" + fs::path(name).stem().string(),
        armour_test::shell_sets(smoke) + "--cache '" + std::string(ARMOUR_TEST_CACHE) + "'");
    const std::string log =
        run.output.size() > 4000 ? run.output.substr(run.output.size() - 4000) : run.output;
    ASSERT_EQ(run.status, 0) << log;
    ASSERT_TRUE(run.summary.is_object()) << "no readable summary.json\n" << log;

    // The run reached its shortened end (the slope analysis may stop it
    // once the pile has settled, which it has not by then).
    ASSERT_TRUE(run.summary["simulated_seconds"].is_number()) << run.summary.dump();
    EXPECT_NEAR(run.summary["simulated_seconds"].get<double>(), duration, 0.01 * duration);
    for (const std::string &key : armour::analysis_style(scene.analysis).headline_keys) {
        const bool may_be_null =
            std::find(smoke.null_figures.begin(), smoke.null_figures.end(), key) != smoke.null_figures.end();
        ASSERT_TRUE(run.summary.contains(key)) << key << " missing from summary.json\n" << log;
        if (may_be_null && run.summary[key].is_null())
            continue; // smoke.why_null
        ASSERT_TRUE(run.summary[key].is_number()) << key << " = " << run.summary[key].dump() << "\n" << log;
        EXPECT_TRUE(std::isfinite(run.summary[key].get<double>())) << key << " = " << run.summary[key].dump();
    }
    if (coupled) {
        // interFoam took several steps with the bodies in it.
        ASSERT_TRUE(run.summary.contains("fluid") && run.summary["fluid"]["steps"].is_number()) << log;
        EXPECT_GE(run.summary["fluid"]["steps"].get<int>(), 3);
    }
    if (!HasFailure())
        fs::remove_all(run.dir);
}

INSTANTIATE_TEST_SUITE_P(Shipped, SceneSmoke, ::testing::ValuesIn(shipped_scenes()), test_name);

// The table has a row for every scene in the folder now (also where the
// tests were listed before a scene was added) and none for a scene that is gone.
TEST(SceneSmokeTable, MatchesTheScenesFolder) {
    const std::vector<std::string> shipped = shipped_scenes();
    for (const auto &name : shipped)
        EXPECT_EQ(kSmoke.count(name), 1u) << "scenes/" << name << " has no row in kSmoke";
    for (const auto &[name, smoke] : kSmoke) {
        EXPECT_TRUE(std::find(shipped.begin(), shipped.end(), name) != shipped.end())
            << name << " is in kSmoke but not in scenes/";
        EXPECT_EQ(smoke.null_figures.empty(), smoke.why_null.empty()) << name << ": say why a figure is null";
    }
}

} // namespace
