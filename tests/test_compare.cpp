// `armour compare` on a tiny scene: every file, consistent entries.
#include "cli.h"
#include "engine_registry.h"
#include "output_folder_rule.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

TEST(Compare, TinySceneProducesAllFilesWithConsistentEntries) {
    const fs::path dir = fs::temp_directory_path() / "armour_compare_test";
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "scene.toml")
        << "name = \"tiny\"\n[run]\nduration = 0.8\noutput_interval = 0.005\ndomain_min = [-1, -1, -0.5]\n"
           "domain_max = [1, 1, 1.5]\n[analysis]\nkind = \"bounce\"\n[[material]]\nname = \"concrete\"\n"
           "[[unit]]\nname = \"cube\"\nshape = \"cube\"\nsize = 0.2\nspheres = 8\n"
           "[[wall]]\nname = \"floor\"\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nsize = 2\n"
           "[[body]]\nunit = \"cube\"\nposition = [0, 0, 0.4]\n";
    const std::string scene = (dir / "scene.toml").string(), out = (dir / "out").string(),
                      cache = (dir / "cache").string();
    const std::vector<const char *> argv = {"armour",    "compare",      scene.c_str(), "--spheres",
                                            "4,8",       "--dt-factors", "1,2",         "--out",
                                            out.c_str(), "--cache",      cache.c_str()};
    ::testing::internal::CaptureStderr();
    const int code = armour::armour_main(static_cast<int>(argv.size()), argv.data());
    const std::string err = ::testing::internal::GetCapturedStderr();
    ASSERT_EQ(code, 0) << err;
    for (const char *name :
         {"summary.json", "pareto.png", "stability_dt.png", "bumpiness.png", "report.md"}) {
        ASSERT_TRUE(fs::exists(fs::path(out) / name)) << name;
        EXPECT_GT(fs::file_size(fs::path(out) / name), 100u) << name;
    }
    std::ifstream in(fs::path(out) / "summary.json");
    const auto s = nlohmann::json::parse(in);
    const bool exact = armour::find_engine_style([](const armour::EngineCapabilities &c) {
                           return c.shape == armour::ShapeModel::convex_hulls;
                       }) != nullptr;
    const std::size_t engines = exact ? 2u : 1u;
    // One run per sphere count (one seed: no random drop), plus the exact hulls.
    ASSERT_EQ(s["runs"].size(), 2u + (exact ? 1u : 0u));
    EXPECT_EQ(s["dt_sweep"].size(), 2u * engines);
    std::ifstream report_in(fs::path(out) / "report.md");
    std::stringstream report;
    report << report_in.rdbuf();
    for (const auto &run : s["runs"]) {
        ASSERT_EQ(run["status"], "ok") << run.dump();
        EXPECT_GT(run["wall_seconds"].get<double>(), 0.0);
        EXPECT_GT(run["seconds_per_unit_step"].get<double>(), 0.0);
        const double ratio = run["figures"]["bounce_height_ratio"].get<double>();
        EXPECT_GE(ratio, 0.0); // a rebound no higher than the drop: restitution < 1
        EXPECT_LE(ratio, 1.0);
        if (exact) { // error = figure - mean of the exact runs, by definition
            EXPECT_NEAR(run["error_vs_exact"]["bounce_height_ratio"].get<double>(),
                        ratio - s["exact_mean"]["bounce_height_ratio"].get<double>(), 1e-12);
        }
        EXPECT_NE(report.str().find(run["label"].get<std::string>()), std::string::npos);
    }
    for (const auto &run : s["dt_sweep"])
        EXPECT_TRUE(run["status"] == "ok" || run.contains("failure")) << run.dump();
    fs::remove_all(dir);
}

TEST(Compare, KeepsTheUsersFiles) {
    const fs::path dir = fs::temp_directory_path() / "armour_compare_output_rule";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string scene = (dir / "scene.toml").string(), cache = (dir / "cache").string();
    std::ofstream(scene)
        << "name = \"tiny\"\n[run]\nduration = 0.05\noutput_interval = 0.01\ndomain_min = [-1, -1, -0.5]\n"
           "domain_max = [1, 1, 1.5]\n[analysis]\nkind = \"bounce\"\n[[material]]\nname = \"concrete\"\n"
           "[[unit]]\nname = \"cube\"\nshape = \"cube\"\nsize = 0.2\nspheres = 8\n"
           "[[wall]]\nname = \"floor\"\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nsize = 2\n"
           "[[body]]\nunit = \"cube\"\nposition = [0, 0, 0.4]\n";
    output_rule::check(
        dir, "armour compare",
        [&](const std::string &out, int variant) {
            return output_rule::armour({"compare", scene, "--spheres", variant == 0 ? "4" : "6",
                                        "--dt-factors", "1", "--out", out, "--cache", cache});
        },
        [](const nlohmann::json &s) {
            for (const auto &run : s["runs"])
                if (run["spheres"] == 6)
                    return 1;
            return 0;
        });
    if (!::testing::Test::HasFailure())
        fs::remove_all(dir);
}
