// A test series' damage prediction (analysis/series_damage.h): Van der
// Meer's equivalent number of waves applied to his cube formula, against a
// hand computation and at its edges. The series run itself is
// test_stability_series.cpp.
#include "damage_analysis.h"
#include "jonswap.h"
#include "scene.h"
#include "series_damage.h"
#include "wave_theory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>

namespace {

using armour::SeaStateFigures;
using armour::van_der_meer_cubes_n_od;
using armour::van_der_meer_cubes_sequence;

// N_od = ((Ns s_om^0.1 - 1) N^0.3 / 6.7)^2.5 (Van der Meer 1988, double-layer cubes).
double formula(double Ns, double N, double s_om) {
    return std::pow((Ns * std::pow(s_om, 0.1) - 1.0) * std::pow(N, 0.3) / 6.7, 2.5);
}

// The waves at (Ns, s_om) that make damage D: the formula solved for N.
double waves_for(double D, double Ns, double s_om) {
    return std::pow(6.7 * std::pow(D, 0.4) / (Ns * std::pow(s_om, 0.1) - 1.0), 1.0 / 0.3);
}

// Three rising steps, by hand: step 1 from an undamaged layer; step 2 at its
// own sea state needs N_eq waves to reach step 1's damage, then adds its
// own; step 3 likewise from step 2's.
TEST(SeriesPrediction, ThreeStepsMatchTheEquivalentWavesByHand) {
    const std::vector<SeaStateFigures> steps = {
        {2.2, 0.030, 1000.0}, {2.6, 0.035, 1000.0}, {3.0, 0.040, 500.0}};
    const auto p = van_der_meer_cubes_sequence(steps);
    ASSERT_EQ(p.size(), 3u);
    const double d1 = formula(2.2, 1000.0, 0.030);
    const double n2 = waves_for(d1, 2.6, 0.035), d2 = formula(2.6, n2 + 1000.0, 0.035);
    const double n3 = waves_for(d2, 3.0, 0.040), d3 = formula(3.0, n3 + 500.0, 0.040);
    std::printf("N_od after each step %.4f %.4f %.4f; N_eq %.1f %.1f\n", d1, d2, d3, n2, n3);
    ASSERT_TRUE(p[0].N_od && p[1].N_od && p[2].N_od);
    EXPECT_NEAR(*p[0].N_od, d1, 1e-12 * d1);
    EXPECT_NEAR(*p[1].N_od, d2, 1e-12 * d2);
    EXPECT_NEAR(*p[2].N_od, d3, 1e-12 * d3);
    EXPECT_DOUBLE_EQ(*p[0].equivalent_waves, 0.0);
    EXPECT_NEAR(*p[1].equivalent_waves, n2, 1e-9 * n2);
    EXPECT_NEAR(*p[2].equivalent_waves, n3, 1e-9 * n3);
    // Step 2's N_eq waves at its own sea state make step 1's damage again.
    EXPECT_NEAR(formula(2.6, n2, 0.035), d1, 1e-9 * d1);
    // The first step is the formula itself (damage.h's inverse).
    EXPECT_NEAR(*p[0].N_od, van_der_meer_cubes_n_od(2.2, 1000.0, 0.030), 1e-12);
}

// Two steps of one sea state are one test of their summed waves.
TEST(SeriesPrediction, TwoStepsOfOneSeaStateAreTheFormulaAtTheirSummedWaves) {
    const auto p = van_der_meer_cubes_sequence({{2.5, 0.03, 300.0}, {2.5, 0.03, 700.0}});
    ASSERT_TRUE(p[1].N_od);
    EXPECT_NEAR(*p[1].N_od, formula(2.5, 1000.0, 0.03), 1e-9);
    EXPECT_NEAR(*p[1].equivalent_waves, 300.0, 1e-9);
}

// Below the formula's floor (Ns s_om^0.1 <= 1) a step does no damage; a
// lower step after a higher one adds damage (more waves) but never takes
// any away, and one below the floor keeps it as it was.
TEST(SeriesPrediction, DamageIsZeroBelowTheFloorAndNeverShrinks) {
    const double floor = std::pow(0.03, -0.1); // Ns at which N_od = 0 for any N (1.42)
    const auto below = van_der_meer_cubes_sequence({{0.99 * floor, 0.03, 5000.0}});
    ASSERT_TRUE(below[0].N_od);
    EXPECT_EQ(*below[0].N_od, 0.0);

    const auto falling = van_der_meer_cubes_sequence(
        {{3.0, 0.03, 1000.0}, {2.0, 0.03, 1000.0}, {0.9 * floor, 0.03, 1000.0}, {2.0, 0.03, 1.0}});
    const double after_high = formula(3.0, 1000.0, 0.03);
    EXPECT_NEAR(*falling[0].N_od, after_high, 1e-12);
    EXPECT_GE(*falling[1].N_od, after_high);
    EXPECT_NEAR(*falling[1].N_od, formula(2.0, waves_for(after_high, 2.0, 0.03) + 1000.0, 0.03), 1e-9);
    EXPECT_EQ(*falling[2].N_od, *falling[1].N_od); // below the floor: nothing added, nothing lost
    EXPECT_FALSE(falling[2].equivalent_waves);     // no number of such waves makes that damage
    EXPECT_GE(*falling[3].N_od, *falling[2].N_od);
}

// A step whose figures are unknown (no waves reached the gauges, no Ns)
// leaves the prediction unknown from there on.
TEST(SeriesPrediction, AnUnknownStepLeavesThePredictionUnknownAfterIt) {
    const auto p =
        van_der_meer_cubes_sequence({{2.5, 0.03, 500.0}, {std::nullopt, 0.03, 500.0}, {2.5, 0.03, 500.0}});
    EXPECT_TRUE(p[0].N_od);
    EXPECT_FALSE(p[1].N_od);
    EXPECT_FALSE(p[2].N_od);
}

// The shipped stability scene with `steps` appended, in a temporary file.
std::string series_scene(const std::string &steps) {
    namespace fs = std::filesystem;
    std::ifstream in(fs::path(ARMOUR_SOURCE_DIR) / "scenes" / "stability_cubes.toml");
    const std::string base{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    static int count = 0;
    const fs::path file = fs::temp_directory_path() / ("armour_series_scene_" + std::to_string(::getpid()) +
                                                       "_" + std::to_string(++count) + ".toml");
    std::ofstream(file) << base << steps;
    return file.string();
}

std::string error_of(const std::string &file, const std::vector<std::string> &sets = {}) {
    try {
        armour::load_scene(file, sets);
    } catch (const armour::InputError &e) {
        return e.what();
    }
    return "";
}

// A step's length in waves: the front's travel from the maker (x = 0) to the
// toe (x = 1.40 m) at the group velocity of Tp in h = 0.40 m, then that many
// of the train's Tm0,2; a step without a length runs run.duration; gamma,
// seed and the ramp default to [waves]'s. The resolved scene reads back the same.
TEST(SeriesScene, AStepsLengthInWavesIsTheFrontsTravelAndThatManyTm02) {
    const std::string file =
        series_scene("\n[[series]]\nHs = 0.1\nTp = 1.6\nwaves = 100\n\n[[series]]\nHs = 0.12\nTp = 1.8\n");
    const armour::Scene s = armour::load_scene(file, {"run.duration=50"});
    ASSERT_EQ(s.series.size(), 2u);
    const auto &a = s.series[0], &b = s.series[1];
    const double tm02 = armour::target_tm02(armour::jonswap_components(0.1, 1.6, 3.3, 200, 1));
    EXPECT_GT(tm02, 0.75 * 1.6); // JONSWAP at gamma 3.3: Tm0,2 ~ Tp / 1.28
    EXPECT_LT(tm02, 0.85 * 1.6);
    EXPECT_NEAR(a.duration, 1.40 / armour::group_velocity(1.6, 0.40, 9.81) + 100.0 * tm02, 1e-9);
    EXPECT_DOUBLE_EQ(b.duration, 50.0);
    EXPECT_DOUBLE_EQ(a.gamma, 3.3);
    EXPECT_EQ(b.seed, 1u);
    EXPECT_DOUBLE_EQ(a.ramp_time, 3.6); // the scene gives waves.ramp_time
    const std::string resolved = armour::resolved_scene_toml(s);
    const std::string again = series_scene("");
    std::ofstream(again) << resolved;
    EXPECT_EQ(armour::resolved_scene_toml(armour::load_scene(again)).substr(resolved.find('\n')),
              resolved.substr(resolved.find('\n'))); // but the comment naming the file
    std::filesystem::remove(file);
    std::filesystem::remove(again);
}

// What a series cannot be: one line naming the key.
TEST(SeriesScene, AStepWithoutIrregularWavesOrWithTwoLengthsIsRefused) {
    const std::string file = series_scene("\n[[series]]\nHs = 0.1\nTp = 1.6\nwaves = 100\nduration = 20\n");
    EXPECT_NE(error_of(file).find("key 'series.0.duration': give the step's length as waves or as duration"),
              std::string::npos)
        << error_of(file);
    const std::string one = series_scene("\n[[series]]\nHs = 0.1\nTp = 1.6\n");
    EXPECT_NE(error_of(one, {"waves.type=regular", "waves.height=0.1", "waves.period=1.6"})
                  .find("key 'series.0.Hs': a test series runs irregular sea states"),
              std::string::npos)
        << error_of(one, {"waves.type=regular", "waves.height=0.1", "waves.period=1.6"});
    EXPECT_NE(
        error_of(one, {"analysis.kind=none"}).find("key 'analysis.kind': a [[series]] measures the damage"),
        std::string::npos)
        << error_of(one, {"analysis.kind=none"});
    EXPECT_NE(error_of(one, {"series.0.duration=0.01"})
                  .find("key 'series.0.duration': step 1: the step's 0.01 s must be >= run.output_interval"),
              std::string::npos)
        << error_of(one, {"series.0.duration=0.01"});
    std::filesystem::remove(file);
    std::filesystem::remove(one);
}

} // namespace
