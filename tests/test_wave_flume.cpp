// scenes/wave_flume.toml end to end through `armour run`: OpenFOAM's stock
// wave maker and absorbing outlet in an empty 2D flume, the gauges'
// incident/reflected analysis in summary.json's `waves` object
// (docs/waves.md). Needs Debian's openfoam (built only with armourWaves).
// Each test is one flume run, ~1-2 min on an idle 2-core machine.
#include "flume_mesh.h"
#include "scene_run.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <sys/wait.h>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using armour_test::SceneRun;

SceneRun run_flume(const std::string &name, const std::string &sets) {
    return armour_test::run_scene(ARMOUR_EXE, std::string(ARMOUR_SOURCE_DIR) + "/scenes/wave_flume.toml",
                                  "wave_flume_" + name, sets);
}

// Regular: H = 0.06 m, T = 1.6 s, h = 0.4 m (StokesII), 10 periods after the
// ramp and after the outlet's reflection is back at the gauges.
TEST(WaveFlume, RegularWaveHeightPeriodAndReflection) {
    const SceneRun run = run_flume("regular", "");
    ASSERT_EQ(run.status, 0) << run.output;
    ASSERT_TRUE(run.summary.contains("waves")) << run.output;
    const json &w = run.summary["waves"];
    EXPECT_EQ(w["theory"], "StokesII");
    const double H = w["target_height"], T = w["target_period"];
    ASSERT_DOUBLE_EQ(H, 0.06);
    const double window = w["window"][1].get<double>() - w["window"][0].get<double>();
    EXPECT_GE(window, 10 * T - 1e-9);
    // Height at each of the three gauges (mean zero-crossing height over the
    // window): within 5 % of H (the brief's bound). The gauges see the
    // incident wave and the outlet's reflection together, so each may differ
    // from H by up to the reflection coefficient. Measured +3.9, +3.0, +0.2 %
    // (incident first harmonic +0.8 %, Kr 2.0 %; with p_rgh solved to 1e-9,
    // the converged wave: +1.4, +1.8, -0.9 %, incident -1.5 %, Kr 2.8 %,
    // docs/validation/waves.md).
    for (const double h : w["gauge_heights"])
        EXPECT_NEAR(h / H, 1.0, 0.05) << "gauge height " << h << " m";
    for (const double t : w["gauge_periods"])
        EXPECT_NEAR(t / T, 1.0, 0.01) << "gauge period " << t << " s";
    EXPECT_NEAR(w["incident_period"].get<double>() / T, 1.0, 0.01);
    // The outlet tuned to c = L/T: measured 2.0 % (OpenFOAM's
    // shallowWaterAbsorption: 6.8 %, theory (a - 1)/(a + 1) = 5.6 % with
    // a = sqrt(g h)/c = 1.12 at kh = 0.89; docs/waves.md). 10 % is the brief's bound.
    EXPECT_LT(w["reflection_coefficient"].get<double>(), 0.10);
    EXPECT_GT(w["waves"].get<int>(), 10);
    EXPECT_TRUE(fs::is_regular_file(run.out / "waves_spectrum.csv"));
    EXPECT_TRUE(fs::is_regular_file(run.out / "waves_spectrum.png"));
    if (!HasFailure())
        fs::remove_all(run.dir);
}

// Irregular: JONSWAP Hs = 0.05 m, Tp = 1.6 s, gamma 3.3, 24 components with
// deterministic amplitudes and random phases. Record: one repeat period,
// 19.2 s = 12 Tp (~14 waves of Tm0,2 = 1.34 s), 15.8-35 s. Over exactly one
// repeat period the components are orthogonal, so the record holds the
// target m0 exactly: its own sampling error is nil in linear theory, and
// Tp falls on the component at fp (resolution fp/12). The
// same 19.2 s of a random sea (random amplitudes, or any record of a real
// one) would give Hm0 to +-18 % (1 sigma = 1 / sqrt(2 nu), nu = 2 D B =
// 15 degrees of freedom, B = m0^2 / int S^2 df = 0.39 Hz): the 5 % bound
// needs the deterministic train (a random one would need ~1000 s, 750
// waves, for sigma = 2.5 %). What is left is the flume's: measured Hm0
// 0.0492 m (-1.5 %), Tp 1.600 s, Kr 6.8 % (docs/waves.md; with Euler in
// time it was -11.4 %). 5 % on Hm0 and Tp is the brief's bound.
TEST(WaveFlume, IrregularHm0AndTp) {
    const SceneRun run = run_flume("irregular", "--set waves.type='\"irregular\"' --set run.duration=35");
    ASSERT_EQ(run.status, 0) << run.output;
    ASSERT_TRUE(run.summary.contains("waves")) << run.output;
    const json &w = run.summary["waves"];
    const double window = w["window"][1].get<double>() - w["window"][0].get<double>();
    EXPECT_NEAR(window, 19.2, 1e-6);
    EXPECT_NEAR(w["incident_height"].get<double>() / 0.05, 1.0, 0.05);
    EXPECT_NEAR(w["incident_period"].get<double>() / 1.6, 1.0, 0.05);
    EXPECT_GT(w["incident_Tm10"].get<double>(), 0.0);
    EXPECT_GT(w["s_om"].get<double>(), 0.0);
    EXPECT_LT(w["reflection_coefficient"].get<double>(), 0.10);
    if (!HasFailure())
        fs::remove_all(run.dir);
}

// The regular wave on a graded mesh (fluid_case/flume_mesh.h) laid out as the
// stability scene's: fine cells (dx 0.025 m) from x = 5 m to the outlet, where
// the structure would be, growing by <= 10 % a cell to 2 dx = 0.05 m towards
// the wave maker, and dz 0.01 m above z = 0.25 m growing to 3 dz towards the
// bed; and the scene's Courant limits (1 for every cell, 0.5 for the free
// surface's). The gauges (2.8-3.5 m) read the waves in the coarse cells; what
// the refinement reflects back shows in Kr. The same bounds as the uniform
// flume's; and blockMesh's points are the node lines the gauges were centred
// with. Measured: heights +2.9, +2.5, +0.4 %, periods within 0.2 %, Kr 1.9 %,
// incident H +0.3 % (with 0.5 for every cell: +1.6, +2.8, +1.8 %, Kr 1.7 %,
// +0.5 %); 302 x 1 x 48 = 14 496 cells (the uniform 2.5 cm mesh: 24 000).
TEST(WaveFlume, GradedMeshKeepsTheRegularWaveAndIsTheMeshTheGaugesAssume) {
    const std::vector<std::string> grading = {"fluid.cells=[400, 1, 60]",
                                              "fluid.refine_min=[5.0, 0.0, 0.25]",
                                              "fluid.refine_max=[10.0, 0.05, 0.6]",
                                              "fluid.coarse_cell_size=[0.05, 0.0, 0.03]",
                                              "fluid.max_courant=1.0",
                                              "fluid.max_interface_courant=0.5"};
    std::string sets;
    for (const std::string &g : grading)
        sets += " --set '" + g + "'";
    const SceneRun run = run_flume("graded", sets);
    ASSERT_EQ(run.status, 0) << run.output;
    ASSERT_TRUE(run.summary.contains("waves")) << run.output;
    const json &w = run.summary["waves"];
    const double H = w["target_height"], T = w["target_period"];
    for (const double h : w["gauge_heights"])
        EXPECT_NEAR(h / H, 1.0, 0.05) << "gauge height " << h << " m";
    for (const double t : w["gauge_periods"])
        EXPECT_NEAR(t / T, 1.0, 0.01) << "gauge period " << t << " s";
    EXPECT_LT(w["reflection_coefficient"].get<double>(), 0.10);

    const armour::FlumeMesh mesh = armour::flume_mesh(
        armour::load_scene(std::string(ARMOUR_SOURCE_DIR) + "/scenes/wave_flume.toml", grading));
    EXPECT_EQ(run.summary["fluid"]["cells_total"].get<long>(), mesh.cells());
    std::ifstream in(run.out / "case" / "constant" / "polyMesh" / "points");
    std::stringstream text;
    text << in.rdbuf();
    const std::string points = text.str();
    const std::regex point(R"(\(([-0-9.eE+]+) ([-0-9.eE+]+) ([-0-9.eE+]+)\))");
    std::set<double> xs, zs;
    for (auto it = std::sregex_iterator(points.begin(), points.end(), point); it != std::sregex_iterator();
         ++it) {
        xs.insert(std::round(std::stod((*it)[1]) * 1e7) / 1e7);
        zs.insert(std::round(std::stod((*it)[3]) * 1e7) / 1e7);
    }
    ASSERT_EQ(xs.size(), mesh.axes[0].nodes.size());
    ASSERT_EQ(zs.size(), mesh.axes[2].nodes.size());
    std::size_t k = 0;
    for (const double x : xs)
        EXPECT_NEAR(x, mesh.axes[0].nodes[k++], 1e-6);
    k = 0;
    for (const double z : zs)
        EXPECT_NEAR(z, mesh.axes[2].nodes[k++], 1e-6);
    if (!HasFailure())
        fs::remove_all(run.dir);
}

} // namespace
