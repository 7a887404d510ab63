// The analysis room: read_bodies_file returns exactly what BodyRecorder
// wrote, and names the file and the reason when it cannot; the registry of
// analyses holds exactly the kinds a scene may name.
#include "analysis.h"
#include "bodies_file.h"
#include "body_recorder.h"
#include "scene_keys.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using armour::BodiesFile;
using armour::BodyRecorder;
using armour::BodyState;
using armour::InputError;
using armour::read_bodies_file;
using armour::RecorderUnit;
using armour::TriangleMesh;

namespace {

TriangleMesh tetrahedron() {
    TriangleMesh m;
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.triangles = {{{0, 2, 1}}, {{0, 1, 3}}, {{0, 3, 2}}, {{1, 2, 3}}};
    return m;
}

const std::vector<int> kBodyUnit = {0, 1, 0};

// Distinct values per step, body and field, so a transposed or shifted read cannot pass.
BodyState state_of(int step, int body) {
    BodyState s;
    const double t = 0.25 * step + 0.1;
    s.pose.position = Eigen::Vector3d(body + t, -2.0 * body + 0.5 * t, 3.0 + t * t);
    s.pose.orientation =
        Eigen::Quaterniond(Eigen::AngleAxisd(0.7 * t + body, Eigen::Vector3d(1, 2, 3).normalized()));
    s.velocity = Eigen::Vector3d(10 + body, 20 + step, 30);
    s.angular_velocity = Eigen::Vector3d(-1.0 * body, 0.5 * step, 0.25);
    s.external_force = Eigen::Vector3d(100.0 * body, 7, -step);
    s.external_torque = Eigen::Vector3d(1, 2, 3) * (step + 1);
    s.contact_force = Eigen::Vector3d(0, 0, 9.81 * (body + 1) * step);
    return s;
}

class Analysis : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / (std::string("armour_analysis_") +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
};

TEST_F(Analysis, BodiesFileReadsBackEveryRecordedValue) {
    const std::string h5 = (dir_ / "bodies.h5").string();
    constexpr int kSteps = 4;
    {
        BodyRecorder recorder(h5, (dir_ / "bodies.xdmf").string(),
                              {{"tetra", tetrahedron()}, {"other", tetrahedron()}}, kBodyUnit,
                              {{"scene", "three bodies"}, {"engine", "free"}, {"dt", "1e-4"}});
        for (int step = 0; step < kSteps; ++step) {
            std::vector<BodyState> states;
            for (int body = 0; body < 3; ++body)
                states.push_back(state_of(step, body));
            recorder.append(0.25 * step + 0.1, states);
        }
    }
    const BodiesFile rec = read_bodies_file(h5);
    ASSERT_EQ(rec.steps(), static_cast<std::size_t>(kSteps));
    ASSERT_EQ(rec.bodies(), 3u);
    EXPECT_EQ(rec.unit, kBodyUnit);
    EXPECT_EQ(rec.attribute("scene"), "three bodies");
    EXPECT_EQ(rec.attribute("engine"), "free");
    EXPECT_EQ(rec.attribute("dt"), "1e-4");
    EXPECT_EQ(rec.attribute("units_system"), "SI");
    EXPECT_EQ(rec.attribute("no such attribute"), "");
    for (int step = 0; step < kSteps; ++step) {
        const auto s = static_cast<std::size_t>(step);
        EXPECT_EQ(rec.time[s], 0.25 * step + 0.1); // doubles are stored as doubles: exact
        for (int body = 0; body < 3; ++body) {
            const auto b = static_cast<std::size_t>(body);
            const BodyState expected = state_of(step, body);
            EXPECT_EQ(rec.position[s][b], expected.pose.position);
            EXPECT_EQ(rec.orientation[s][b].coeffs(), expected.pose.orientation.coeffs());
            EXPECT_EQ(rec.velocity[s][b], expected.velocity);
            EXPECT_EQ(rec.angular_velocity[s][b], expected.angular_velocity);
            EXPECT_EQ(rec.external_force[s][b], expected.external_force);
            EXPECT_EQ(rec.external_torque[s][b], expected.external_torque);
            EXPECT_EQ(rec.contact_force[s][b], expected.contact_force);
        }
    }
}

TEST_F(Analysis, BodiesFileReadsARecordWithoutSteps) {
    const std::string h5 = (dir_ / "bodies.h5").string();
    BodyRecorder(h5, (dir_ / "bodies.xdmf").string(), {{"tetra", tetrahedron()}}, {0}, {}).close();
    const BodiesFile rec = read_bodies_file(h5);
    EXPECT_EQ(rec.steps(), 0u);
    EXPECT_EQ(rec.bodies(), 1u);
    EXPECT_TRUE(rec.position.empty());
}

TEST_F(Analysis, BodiesFileNamesTheFileWhenItIsNoRecord) {
    const std::string missing = (dir_ / "missing.h5").string();
    try {
        read_bodies_file(missing);
        FAIL() << "a missing file was read";
    } catch (const InputError &e) {
        EXPECT_EQ(std::string(e.what()).rfind(missing + ": ", 0), 0u) << e.what();
    }
    const std::string text = (dir_ / "text.h5").string();
    std::ofstream(text) << "not HDF5\n";
    EXPECT_THROW(read_bodies_file(text), InputError);
}

TEST(AnalysisRegistry, HoldsExactlyTheKindsASceneMayName) {
    std::vector<std::string> scene_kinds;
    for (const auto &key : armour::analysis_keys())
        if (std::string(key.name) == "kind")
            scene_kinds = key.choices;
    ASSERT_FALSE(scene_kinds.empty());
    std::vector<std::string> registered;
    for (const auto &style : armour::analysis_styles())
        registered.push_back(style.name);
    EXPECT_EQ(registered, scene_kinds);
}

TEST(AnalysisRegistry, EveryStyleDescribesItselfAndItsAnalyticKeysAreHeadlines) {
    for (const auto &style : armour::analysis_styles()) {
        EXPECT_FALSE(style.summary.empty()) << style.name;
        EXPECT_TRUE(style.make) << style.name;
        for (const auto &[key, analytic] : style.analytic_keys) {
            EXPECT_NE(std::find(style.headline_keys.begin(), style.headline_keys.end(), key),
                      style.headline_keys.end())
                << style.name << ": " << key;
            EXPECT_NE(key, analytic) << style.name;
        }
    }
    EXPECT_TRUE(armour::analysis_style("tilt").turns_gravity);
    EXPECT_FALSE(armour::analysis_style("slope").turns_gravity);
}

TEST(AnalysisRegistry, RefusesAnUnknownKindNamingTheKey) {
    try {
        armour::analysis_style("damage");
        FAIL() << "an unknown kind was found";
    } catch (const InputError &e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind("analysis.kind: 'damage'", 0), 0u) << what;
        EXPECT_NE(what.find("slope_waves"), std::string::npos) << what;
    }
}

} // namespace
