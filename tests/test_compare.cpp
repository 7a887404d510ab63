// `armour compare` on a tiny scene: every file, consistent entries.
#include "cli.h"
#include "engine_registry.h"
#include "output_folder_rule.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace {

// A 0.2 m cube of 8 spheres dropped 0.4 m onto a floor (analysis "bounce");
// duration and output_interval in s, as TOML numbers.
void write_tiny_scene(const fs::path &file, const std::string &duration, const std::string &output_interval) {
    std::ofstream(file)
        << "name = \"tiny\"\n[run]\nduration = " << duration << "\noutput_interval = " << output_interval
        << "\ndomain_min = [-1, -1, -0.5]\ndomain_max = [1, 1, 1.5]\n[analysis]\nkind = \"bounce\"\n"
           "[[material]]\nname = \"concrete\"\n[[unit]]\nname = \"cube\"\nshape = \"cube\"\nsize = 0.2\n"
           "spheres = 8\n[[wall]]\nname = \"floor\"\ntype = \"plane\"\npoint = [0, 0, 0]\n"
           "normal = [0, 0, 1]\nsize = 2\n[[body]]\nunit = \"cube\"\nposition = [0, 0, 0.4]\n";
}

} // namespace

TEST(Compare, TinySceneProducesAllFilesWithConsistentEntries) {
    const fs::path dir = fs::temp_directory_path() / ("armour_compare_test_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    write_tiny_scene(dir / "scene.toml", "0.8", "0.005");
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
    for (const auto &run : s["dt_sweep"]) {
        EXPECT_TRUE(run["status"] == "ok" || run.contains("failure")) << run.dump();
        if (!run.contains("dt_limit"))
            continue; // crashed: no summary of its own
        // Every point on its own run's limit: the factor asked for is the one run.
        EXPECT_NEAR(run["dt"].get<double>() / run["dt_limit"].get<double>(),
                    run["dt_factor_requested"].get<double>(), 1e-9 * run["dt_factor_requested"].get<double>())
            << run.dump();
        EXPECT_NEAR(run["energy_gain"].get<double>(),
                    (run["energy_max"].get<double>() - run["energy_initial"].get<double>()) /
                        run["energy_scale"].get<double>(),
                    1e-12);
        if (run["energy_gain"].get<double>() > s["blow_up_gain"].get<double>()) {
            EXPECT_EQ(run["status"], "failed") << "a blow-up is a failure";
        }
    }
    for (const auto &run : s["runs"]) {
        EXPECT_GT(run["dt"].get<double>(), 0.0);
        EXPECT_GT(run["dt_limit"].get<double>(), 0.0);
    }
    // One group per engine and sphere count, and advice for the headline figure.
    ASSERT_EQ(s["groups"].size(), 2u + (exact ? 1u : 0u));
    for (const auto &g : s["groups"]) {
        EXPECT_EQ(g["n_runs"], 1);
        for (const char *k : {"mean", "std", "ci95", "error_vs_exact_mean", "error_vs_exact_ci95"})
            EXPECT_TRUE(g["figures"]["bounce_height_ratio"].contains(k)) << k;
    }
    const auto &advice = s["advice"]["bounce_height_ratio"];
    EXPECT_DOUBLE_EQ(advice["tolerance"].get<double>(), 0.05);
    EXPECT_TRUE(advice.contains("choice"));
    EXPECT_FALSE(advice["reason"].get<std::string>().empty());
    fs::remove_all(dir);
}

TEST(Compare, KeepsTheUsersFiles) {
    const fs::path dir =
        fs::temp_directory_path() / ("armour_compare_output_rule_" + std::to_string(::getpid()));
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

// ---- Statistics and advice on synthetic run sets (no engine runs) ----

#include "compare_stats.h"
#include "input_error.h"

#include <cmath>
#include <unistd.h>

namespace {

using nlohmann::json;

json run(const std::string &engine, int spheres, double value, double cost, const char *status = "ok") {
    json r = {{"engine", engine},
              {"spheres", spheres},
              {"status", status},
              {"wall_seconds_per_simulated_second", cost},
              {"figures", {{"packing_density", value}}},
              {"error_vs_analytic", json::object()}};
    return r;
}

const json &group(const json &groups, const std::string &engine, int spheres) {
    for (const json &g : groups)
        if (g["engine"] == engine && g["spheres"] == spheres)
            return g;
    throw std::runtime_error("no group " + engine + " " + std::to_string(spheres));
}

const json &verdict(const json &advice, const std::string &key, const std::string &label) {
    for (const json &v : advice[key]["groups"])
        if (v["label"] == label)
            return v;
    throw std::runtime_error("no verdict for " + label);
}

} // namespace

TEST(CompareStats, StudentT95IsTheTabulatedQuantile) {
    EXPECT_DOUBLE_EQ(armour::student_t95(1), 12.706);
    EXPECT_DOUBLE_EQ(armour::student_t95(2), 4.303);
    EXPECT_DOUBLE_EQ(armour::student_t95(4), 2.776);
    EXPECT_DOUBLE_EQ(armour::student_t95(4.9), 2.776); // Welch's fractional dof: rounded down
    EXPECT_DOUBLE_EQ(armour::student_t95(30), 2.042);
    EXPECT_NEAR(armour::student_t95(40), 2.021, 1e-3); // Cornish-Fisher beyond the table
    EXPECT_NEAR(armour::student_t95(120), 1.980, 1e-3);
    EXPECT_NEAR(armour::student_t95(1e6), 1.95996, 1e-4);
    EXPECT_TRUE(std::isnan(armour::student_t95(0.5)));
}

TEST(CompareStats, SpreadIsMeanSampleStdAndStudentInterval) {
    const armour::Spread s = armour::spread_of({1, 2, 3, 4, 5});
    EXPECT_EQ(s.n, 5);
    EXPECT_DOUBLE_EQ(s.mean, 3.0);
    EXPECT_NEAR(s.std, std::sqrt(2.5), 1e-12);                           // n - 1 in the denominator
    EXPECT_NEAR(s.ci95, 2.776 * std::sqrt(2.5) / std::sqrt(5.0), 1e-12); // t(4) s / sqrt(n)
    const armour::Spread one = armour::spread_of({7.0});
    EXPECT_EQ(one.n, 1);
    EXPECT_DOUBLE_EQ(one.mean, 7.0);
    EXPECT_TRUE(std::isnan(one.std));
    EXPECT_TRUE(std::isnan(one.ci95));
    EXPECT_TRUE(std::isnan(armour::spread_of({}).mean));
}

TEST(CompareStats, DifferenceIsWelchsInterval) {
    // var(a) = 1 (n 3), var(b) = 20/3 (n 4): v = 1/3 + 5/3 = 2, Welch dof 4.08 -> t(4).
    const armour::Spread d = armour::difference_of({1, 2, 3}, {10, 12, 14, 16});
    EXPECT_DOUBLE_EQ(d.mean, -11.0); // signed: a minus b
    EXPECT_NEAR(d.ci95, 2.776 * std::sqrt(2.0), 1e-9);
    // One reference run: only the other side's spread, n - 1 dof.
    const armour::Spread e = armour::difference_of({1, 2, 3}, {5});
    EXPECT_DOUBLE_EQ(e.mean, -3.0);
    EXPECT_NEAR(e.ci95, 4.303 / std::sqrt(3.0), 1e-9);
    EXPECT_TRUE(std::isnan(armour::difference_of({1}, {5}).ci95)); // no spread known at all
    EXPECT_DOUBLE_EQ(armour::difference_of({2, 2}, {1, 1}).ci95, 0.0);
}

TEST(CompareStats, TolerancesParseAndBadTextIsOneClearError) {
    const auto t = armour::parse_tolerances("slide_angle_deg=0.5,packing_density=0.05");
    EXPECT_DOUBLE_EQ(t.at("slide_angle_deg"), 0.5);
    EXPECT_DOUBLE_EQ(t.at("packing_density"), 0.05);
    EXPECT_TRUE(armour::parse_tolerances("").empty());
    for (const char *bad : {"slide_angle_deg", "slide_angle_deg=", "slide_angle_deg=-1", "=0.5",
                            "slide_angle_deg=0.5x", "porosity=nan"}) {
        try {
            armour::parse_tolerances(bad);
            ADD_FAILURE() << bad << " accepted";
        } catch (const armour::InputError &e) {
            EXPECT_EQ(std::string(e.what()).rfind("--tolerance: ", 0), 0u) << e.what();
        }
    }
    EXPECT_DOUBLE_EQ(armour::default_tolerance("slide_angle_deg", 26.6), 0.5);
    EXPECT_DOUBLE_EQ(armour::default_tolerance("topple_angle_deg", 45.0), 1.0);
    EXPECT_DOUBLE_EQ(armour::default_tolerance("leave_angle_deg", 31.0), 1.0);
    EXPECT_DOUBLE_EQ(armour::default_tolerance("draft", 0.2), 0.01); // 5 % of the reference
}

// The case: one seed of the 5-sphere clump was off by 0.001, another
// by 0.164. The group's interval spans both, so the clump is not advised for
// a tolerance of 0.01; the steadier 20-sphere clump is, and failures and
// signs are kept.
TEST(CompareStats, GroupsAndAdviceFollowTheIntervalsNotTheLuckiestSeed) {
    const json runs = json::array({run("bullet", 0, 0.600, 3.0), run("bullet", 0, 0.602, 3.0),
                                   run("bullet", 0, 0.598, 3.0), run("liggghts", 5, 0.601, 0.5),
                                   run("liggghts", 5, 0.764, 0.5), run("liggghts", 5, 0.690, 0.5),
                                   run("liggghts", 20, 0.605, 2.0), run("liggghts", 20, 0.607, 2.0),
                                   run("liggghts", 20, 0.606, 2.0), run("liggghts", 20, 9.9, 2.0, "failed")});
    const json groups = armour::compare_groups(runs, {"packing_density"}, "bullet");
    ASSERT_EQ(groups.size(), 3u);
    const json &exact = group(groups, "bullet", 0), &five = group(groups, "liggghts", 5),
               &twenty = group(groups, "liggghts", 20);
    EXPECT_EQ(twenty["n_runs"], 4);
    EXPECT_EQ(twenty["n_failed"], 1);
    const json &f20 = twenty["figures"]["packing_density"];
    EXPECT_EQ(f20["n"], 3); // the failed run is not a value
    EXPECT_NEAR(f20["mean"].get<double>(), 0.606, 1e-12);
    EXPECT_NEAR(f20["std"].get<double>(), 0.001, 1e-12);
    EXPECT_NEAR(f20["ci95"].get<double>(), 4.303 * 0.001 / std::sqrt(3.0), 1e-12);
    EXPECT_NEAR(f20["error_vs_exact_mean"].get<double>(), +0.006, 1e-12); // signed
    // Welch: both sides' spread, sqrt(0.001^2/3 + 0.002^2/3), dof 2.9 -> t(2).
    EXPECT_NEAR(f20["error_vs_exact_ci95"].get<double>(), 4.303 * std::sqrt(5e-6 / 3.0), 1e-9);
    EXPECT_DOUBLE_EQ(exact["figures"]["packing_density"]["error_vs_exact_mean"].get<double>(), 0.0);
    EXPECT_NEAR(five["figures"]["packing_density"]["error_vs_exact_mean"].get<double>(), 0.085, 1e-12);

    // Tolerance 0.02: the 20-sphere interval (+0.006 +- 0.0056) lies inside
    // it; the 5-sphere one (+0.085 +- 0.20) straddles it; hulls are the reference.
    json advice = armour::compare_advice(groups, {"packing_density"}, {{"packing_density", 0.02}}, "bullet");
    EXPECT_EQ(advice["packing_density"]["tolerance"], 0.02);
    EXPECT_EQ(advice["packing_density"]["reference"], "exact hulls");
    EXPECT_EQ(verdict(advice, "packing_density", "20 spheres")["verdict"], "meets");
    EXPECT_EQ(verdict(advice, "packing_density", "5 spheres")["verdict"], "undecided");
    EXPECT_EQ(verdict(advice, "packing_density", "exact hulls")["verdict"], "reference");
    EXPECT_EQ(advice["packing_density"]["choice"], "20 spheres"); // cheaper than the hulls (2 < 3)
    EXPECT_NE(
        advice["packing_density"]["reason"].get<std::string>().find("5 spheres is cheaper but undecided"),
        std::string::npos)
        << advice.dump(2);

    // Tighter than the 20-sphere interval: nothing meets it but the
    // reference itself, so the hulls are the advice.
    advice = armour::compare_advice(groups, {"packing_density"}, {{"packing_density", 0.005}}, "bullet");
    EXPECT_EQ(verdict(advice, "packing_density", "20 spheres")["verdict"], "undecided");
    EXPECT_EQ(verdict(advice, "packing_density", "5 spheres")["verdict"], "undecided");
    EXPECT_EQ(advice["packing_density"]["choice"], "exact hulls");
}

TEST(CompareStats, HullsAreAdvisedWhereTheyMeetTheAnalyticValueAtLowerCost) {
    auto with_analytic = [](json r, double error) {
        r["figures"]["slide_angle_deg"] = 26.565 + error;
        r["error_vs_analytic"]["slide_angle_deg"] = error;
        return r;
    };
    json runs = json::array();
    for (double e : {0.10, 0.12, 0.11})
        runs.push_back(with_analytic(run("bullet", 0, 0, 0.4), e));
    for (double e : {-0.20, -0.22, -0.21}) // cheaper still, but off by more than the tolerance
        runs.push_back(with_analytic(run("liggghts", 8, 0, 0.3), e - 0.5));
    for (double e : {0.05, 0.04, 0.06})
        runs.push_back(with_analytic(run("liggghts", 40, 0, 1.5), e));
    const json groups = armour::compare_groups(runs, {"slide_angle_deg"}, "bullet");
    const json advice = armour::compare_advice(groups, {"slide_angle_deg"}, {}, "bullet");
    const json &a = advice["slide_angle_deg"];
    EXPECT_EQ(a["tolerance"], 0.5); // the default for slide angles
    EXPECT_EQ(a["tolerance_source"], "default");
    EXPECT_EQ(a["reference"], "analytic");
    EXPECT_EQ(verdict(advice, "slide_angle_deg", "8 spheres")["verdict"], "fails");
    EXPECT_LT(verdict(advice, "slide_angle_deg", "8 spheres")["error_mean"].get<double>(), 0.0); // signed
    EXPECT_EQ(verdict(advice, "slide_angle_deg", "40 spheres")["verdict"], "meets");
    EXPECT_EQ(verdict(advice, "slide_angle_deg", "exact hulls")["verdict"], "meets");
    EXPECT_EQ(a["choice"], "exact hulls");
    EXPECT_EQ(a["engine"], "bullet");
    EXPECT_EQ(a["spheres"], 0);
}

TEST(CompareStats, OneRunPerGroupHasNoIntervalAndSaysSo) {
    const json runs = json::array({run("bullet", 0, 0.60, 3.0), run("liggghts", 10, 0.61, 1.0)});
    const json groups = armour::compare_groups(runs, {"packing_density"}, "bullet");
    const json &f = group(groups, "liggghts", 10)["figures"]["packing_density"];
    EXPECT_TRUE(f["std"].is_null());
    EXPECT_TRUE(f["ci95"].is_null());
    EXPECT_TRUE(f["error_vs_exact_ci95"].is_null());
    const json advice =
        armour::compare_advice(groups, {"packing_density"}, {{"packing_density", 0.05}}, "bullet");
    EXPECT_EQ(advice["packing_density"]["choice"], "10 spheres");
    EXPECT_NE(
        advice["packing_density"]["reason"].get<std::string>().find("one run: a point value, no interval"),
        std::string::npos);
}

TEST(CompareStats, NoAdviceWhereNoRunHasTheFigure) {
    // A tilt at low friction: nothing topples, so nothing meets a topple tolerance.
    json runs = json::array({run("bullet", 0, 0.0, 1.0), run("liggghts", 20, 0.0, 0.5)});
    for (json &r : runs)
        r["figures"] = {{"topple_angle_deg", nullptr}};
    const json groups = armour::compare_groups(runs, {"topple_angle_deg"}, "bullet");
    EXPECT_EQ(group(groups, "bullet", 0)["figures"]["topple_angle_deg"]["n"], 0);
    const json advice = armour::compare_advice(groups, {"topple_angle_deg"}, {}, "bullet");
    EXPECT_TRUE(advice["topple_angle_deg"]["choice"].is_null()) << advice.dump(2);
    EXPECT_EQ(verdict(advice, "topple_angle_deg", "exact hulls")["verdict"], "no value");
}

TEST(Compare, RefusesAToleranceForAFigureTheAnalysisHasNot) {
    const fs::path dir =
        fs::temp_directory_path() / ("armour_compare_tolerance_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    write_tiny_scene(dir / "scene.toml", "0.05", "0.01");
    const std::string scene = (dir / "scene.toml").string(), out = (dir / "out").string();
    const std::vector<const char *> argv = {"armour",       "compare", scene.c_str(), "--tolerance",
                                            "porosity=0.1", "--out",   out.c_str()};
    ::testing::internal::CaptureStderr();
    const int code = armour::armour_main(static_cast<int>(argv.size()), argv.data());
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(code, 0);
    EXPECT_NE(err.find("armour: error: --tolerance: porosity: not a headline figure of analysis 'bounce'"),
              std::string::npos)
        << err;
    EXPECT_FALSE(fs::exists(out)); // nothing written
    fs::remove_all(dir);
}

// `--dry-run` makes compare's own checks (the scene, the options, --out),
// lists the runs the real command makes (one seed, each sphere count, the
// exact hulls where the build has them; the time-step sweep) and writes nothing.
TEST(Compare, DryRunListsTheRunsAndWritesNothing) {
    const fs::path dir = fs::temp_directory_path() / ("armour_compare_dry_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    write_tiny_scene(dir / "scene.toml", "0.05", "0.01");
    const std::string scene = (dir / "scene.toml").string(), out = (dir / "out").string();
    const auto compare = [&](std::vector<const char *> extra, std::string &printed) {
        std::vector<const char *> argv = {"armour", "compare",   scene.c_str(),  "--spheres", "4,8,20",
                                          "--out",  out.c_str(), "--dt-factors", "1,2",       "--dry-run"};
        argv.insert(argv.end(), extra.begin(), extra.end());
        ::testing::internal::CaptureStdout();
        ::testing::internal::CaptureStderr();
        const int code = armour::armour_main(static_cast<int>(argv.size()), argv.data());
        printed = ::testing::internal::GetCapturedStdout() + ::testing::internal::GetCapturedStderr();
        return code;
    };
    std::string printed;
    ASSERT_EQ(compare({}, printed), 0) << printed;
    const bool exact = armour::find_engine_style([](const armour::EngineCapabilities &c) {
                           return c.shape == armour::ShapeModel::convex_hulls;
                       }) != nullptr;
    EXPECT_NE(printed.find(std::to_string(3 + (exact ? 1 : 0)) + " runs of 0.05 s"), std::string::npos)
        << printed;
    EXPECT_NE(printed.find("2 factors"), std::string::npos) << printed;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_EQ(compare({"--tolerance", "porosity=0.1"}, printed), 2);
    EXPECT_NE(printed.find("armour: error: --tolerance: porosity: not a headline figure"), std::string::npos)
        << printed;
    fs::create_directories(out);
    std::ofstream(fs::path(out) / "notes.txt") << "a user's notes\n";
    EXPECT_EQ(compare({}, printed), 2);
    EXPECT_NE(printed.find("holds 'notes.txt'"), std::string::npos) << printed;
    EXPECT_EQ(output_rule::names(out), std::set<std::string>{"notes.txt"});
    fs::remove_all(dir);
}

TEST(Compare, CountsABlowUpAsAFailureOutOfTheStatistics) {
    // A threshold far below any real gain: every run that gained energy blew up.
    const fs::path dir = fs::temp_directory_path() / ("armour_compare_blow_up_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    write_tiny_scene(dir / "scene.toml", "0.3", "0.005");
    const std::string scene = (dir / "scene.toml").string(), out = (dir / "out").string(),
                      cache = (dir / "cache").string();
    const std::vector<const char *> argv = {"armour",      "compare",      scene.c_str(), "--spheres",
                                            "4",           "--out",        out.c_str(),   "--cache",
                                            cache.c_str(), "--dt-factors", "2",           "--blow-up-gain",
                                            "1e-12"};
    ::testing::internal::CaptureStderr();
    const int code = armour::armour_main(static_cast<int>(argv.size()), argv.data());
    const std::string err = ::testing::internal::GetCapturedStderr();
    ASSERT_EQ(code, 0) << err;
    std::ifstream in(fs::path(out) / "summary.json");
    const auto s = nlohmann::json::parse(in);
    int blown = 0;
    for (const auto *set : {&s["runs"], &s["dt_sweep"]})
        for (const auto &run : *set)
            if (run.contains("energy_gain") && run["energy_gain"].is_number() &&
                run["energy_gain"].get<double>() > 1e-12) {
                ++blown;
                EXPECT_EQ(run["status"], "failed") << run.dump();
                EXPECT_EQ(run["blow_up"], true);
                EXPECT_NE(run["failure"].get<std::string>().find("blow-up"), std::string::npos);
            }
    ASSERT_GT(blown, 0) << "the clumps' soft contacts always gain a little";
    for (const auto &g : s["groups"])
        if (g["spheres"].get<int>() > 0) {
            EXPECT_EQ(g["n_failed"], g["n_runs"]); // the clump run gained energy: out of the figures
            EXPECT_EQ(g["figures"]["bounce_height_ratio"]["n"], 0);
        }
    fs::remove_all(dir);
}
