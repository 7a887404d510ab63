// The interFoam plugin end to end: foam_cases/buoyancy_cube through
// foam_cases/run_case.sh, checked against Archimedes and the plugin's own
// force balance. Needs Debian's openfoam (the target exists only then).
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

namespace fs = std::filesystem;

namespace {

// The cube of scenes/buoyancy_cube.toml, which run_case.sh --scene puts in foam_cases/buoyancy_cube.
constexpr double kEdge = 0.3;        // m
constexpr double kRhoWater = 1000.0; // kg/m^3
constexpr double kG = 9.81;          // m/s^2
const double kPosition[3] = {0.512, 0.493, 0.415};

struct CaseRun {
    int status = -1;
    std::string output; // run_case.sh's stdout and stderr
    fs::path dir;
};

std::string slurp(const fs::path &path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Replaces the first `from` in the file by `to`; false if it is not there.
bool replace_in_file(const fs::path &path, const std::string &from, const std::string &to) {
    std::string text = slurp(path);
    const auto at = text.find(from);
    if (at == std::string::npos)
        return false;
    text.replace(at, from.size(), to);
    std::ofstream(path) << text;
    return true;
}

const fs::path kBuoyancyScene = fs::path(ARMOUR_SOURCE_DIR) / "scenes/buoyancy_cube.toml";

CaseRun run_case(const std::string &name, int np,
                 const fs::path &case_template = fs::path(ARMOUR_SOURCE_DIR) / "foam_cases/buoyancy_cube",
                 const fs::path &scene = kBuoyancyScene) {
    CaseRun r;
    std::string tmpl = (fs::temp_directory_path() / ("armour_test_foam_" + name + "_XXXXXX")).string();
    if (!mkdtemp(tmpl.data()))
        return r;
    r.dir = tmpl;
    const fs::path log = r.dir / "run_case.log";
    const std::string cmd = std::string("bash '") + ARMOUR_SOURCE_DIR + "/foam_cases/run_case.sh' --np " +
                            std::to_string(np) + " --plugin '" + ARMOUR_FOAM_PLUGIN + "' --scene '" +
                            scene.string() + "' '" + case_template.string() + "' '" +
                            (r.dir / "case").string() + "' > '" + log.string() + "' 2>&1";
    const int rc = std::system(cmd.c_str());
    r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    r.output = slurp(log);
    return r;
}

// The last CSV row of `body`, by column name.
std::map<std::string, std::string> last_row(const fs::path &csv, const std::string &body) {
    std::ifstream in(csv);
    std::string line;
    std::vector<std::string> header;
    std::map<std::string, std::string> row;
    auto split = [](const std::string &s) {
        std::vector<std::string> out;
        std::stringstream ss(s);
        std::string cell;
        while (std::getline(ss, cell, ','))
            out.push_back(cell);
        return out;
    };
    if (std::getline(in, line))
        header = split(line);
    while (std::getline(in, line)) {
        const auto cells = split(line);
        if (cells.size() != header.size() || cells[1] != body)
            continue;
        row.clear();
        for (std::size_t i = 0; i < cells.size(); ++i)
            row[header[i]] = cells[i];
    }
    return row;
}

double num(const std::map<std::string, std::string> &row, const std::string &key) {
    const auto it = row.find(key);
    if (it == row.end())
        ADD_FAILURE() << "CSV has no column " << key;
    return it == row.end() ? NAN : std::stod(it->second);
}

class FoamBuoyancy : public ::testing::Test {
  protected:
    static void SetUpTestSuite() { serial_ = new CaseRun(run_case("serial", 1)); }
    static void TearDownTestSuite() {
        // Kept on failure for the logs and fields.
        if (serial_ && !::testing::UnitTest::GetInstance()->Failed())
            fs::remove_all(serial_->dir);
        delete serial_;
        serial_ = nullptr;
    }
    static CaseRun *serial_;
};
CaseRun *FoamBuoyancy::serial_ = nullptr;

TEST_F(FoamBuoyancy, CaseRuns) {
    ASSERT_EQ(serial_->status, 0) << serial_->output;
    EXPECT_TRUE(fs::exists(serial_->dir / "case/0.2/armourChi"));
    EXPECT_TRUE(fs::exists(serial_->dir / "case/0.2/armourUBody"));
    // On this orthogonal mesh the loads take the fast path, which agreed
    // with fvc on smooth test fields (armourForceDensity.C).
    EXPECT_NE(slurp(serial_->dir / "case/log.interFoam").find("force density face by face"),
              std::string::npos);
}

// A sheared mesh (2.9 deg non-orthogonal): the face-by-face force density
// leaves out the non-orthogonal correction, the check sees the difference and
// the plugin computes the loads with fvc instead, within Archimedes.
TEST(FoamForceDensity, NonOrthogonalMeshFallsBackToFvc) {
    std::string tmpl = (fs::temp_directory_path() / "armour_test_foam_sheared_XXXXXX").string();
    ASSERT_NE(mkdtemp(tmpl.data()), nullptr);
    const fs::path sheared = fs::path(tmpl) / "template";
    fs::copy(fs::path(ARMOUR_SOURCE_DIR) / "foam_cases/buoyancy_cube", sheared, fs::copy_options::recursive);
    ASSERT_TRUE(replace_in_file(sheared / "system/blockMeshDict", "(0 0 1) (1 0 1) (1 1 1) (0 1 1)",
                                "(0.05 0 1) (1.05 0 1) (1.05 1 1) (0.05 1 1)"))
        << "blockMeshDict vertices changed";
    // Four steps: the sheared tank itself (without the plugin too) blows up
    // in interFoam after ~0.1 s with this template's solver settings.
    ASSERT_TRUE(
        replace_in_file(sheared / "system/controlDict", "endTime         0.2;", "endTime         0.02;"))
        << "controlDict endTime changed";

    const CaseRun run = run_case("sheared", 1, sheared);
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(slurp(run.dir / "case/log.interFoam").find("force density by fvc on the whole mesh"),
              std::string::npos);
    const auto row = last_row(run.dir / "case/armourBodies.csv", "cube_0");
    ASSERT_FALSE(row.empty());
    const double buoyancy = kRhoWater * kG * kEdge * kEdge * kEdge;
    EXPECT_NEAR(num(row, "Fz") / buoyancy, 1.0, 0.02);
    if (!::testing::Test::HasFailure()) {
        fs::remove_all(run.dir);
        fs::remove_all(tmpl);
    }
}

// A scene's pivot: the template's cube hinged about a
// y-parallel axis through a point 0.1 m off its centre in +x (translations
// held at the pivot, rotation free about y only). Weight less buoyancy,
// (rho_c - rho_w) g V = 371 N down at the centre, turns it about -y, the
// centre swinging down. Facts: the pivot stays where it was (the free
// body's constraint projection, to rounding); the rotation is about y
// only and negative; and in 0.2 s it is at most what the same torque
// gives without the fluid's inertia, 1/2 (T / I_p) t^2 = 0.458 rad
// (I_p = m a^2/6 + m d^2 = 1.62 kg m^2): added mass and drag only slow it.
TEST(FoamPivot, ScenePivotHingesTheCube) {
    std::string tmpl = (fs::temp_directory_path() / "armour_test_foam_pivot_XXXXXX").string();
    ASSERT_NE(mkdtemp(tmpl.data()), nullptr);
    const fs::path hinged = fs::path(tmpl) / "template";
    fs::copy(fs::path(ARMOUR_SOURCE_DIR) / "foam_cases/buoyancy_cube", hinged, fs::copy_options::recursive);
    const double pivot[3] = {kPosition[0] + 0.1, kPosition[1], kPosition[2]};
    const fs::path scene = fs::path(tmpl) / "hinged.toml";
    fs::copy_file(kBuoyancyScene, scene);
    ASSERT_TRUE(replace_in_file(scene, "fixed_rotation = [true, true, true]",
                                "fixed_rotation = [true, false, true]\npivot = [" + std::to_string(pivot[0]) +
                                    ", " + std::to_string(pivot[1]) + ", " + std::to_string(pivot[2]) + "]"))
        << "scenes/buoyancy_cube.toml changed";
    const CaseRun run = run_case("pivot", 1, hinged, scene);
    ASSERT_EQ(run.status, 0) << run.output;
    const auto row = last_row(run.dir / "case/armourBodies.csv", "cube_0");
    ASSERT_FALSE(row.empty());
    const Eigen::Quaterniond q(num(row, "qw"), num(row, "qx"), num(row, "qy"), num(row, "qz"));
    const Eigen::Vector3d centre(num(row, "x"), num(row, "y"), num(row, "z"));
    const Eigen::Vector3d start(kPosition[0], kPosition[1], kPosition[2]),
        hinge(pivot[0], pivot[1], pivot[2]);
    const Eigen::Vector3d hinge_now = centre + q * (hinge - start);
    const Eigen::AngleAxisd turn(q);
    const double about_y = turn.angle() * turn.axis().y();
    std::printf(
        "[ pivot    ] hinge moved %.3g m, turned %.4f rad about y (bound -0.458), centre moved %.4f m\n",
        (hinge_now - hinge).norm(), about_y, (centre - start).norm());
    EXPECT_LT((hinge_now - hinge).norm(), 1e-9);
    EXPECT_NEAR(std::abs(turn.axis().y()), 1.0, 1e-9);
    EXPECT_LT(about_y, -0.05);
    EXPECT_GT(about_y, -0.458 * 1.01);
    if (!::testing::Test::HasFailure()) {
        fs::remove_all(run.dir);
        fs::remove_all(tmpl);
    }
}

// A fixed, fully submerged cube in still water: the fluid load is the weight
// of the displaced water, upwards, and nothing sideways.
TEST_F(FoamBuoyancy, Archimedes) {
    ASSERT_EQ(serial_->status, 0) << serial_->output;
    const auto row = last_row(serial_->dir / "case/armourBodies.csv", "cube_0");
    ASSERT_FALSE(row.empty());
    EXPECT_NEAR(num(row, "time"), 0.2, 1e-9);

    const double buoyancy = kRhoWater * kG * kEdge * kEdge * kEdge; // 264.87 N
    const double fz = num(row, "Fz");
    EXPECT_NEAR(fz / buoyancy, 1.0, 0.02) << "Fz = " << fz << " N, rho g V = " << buoyancy << " N";
    EXPECT_LT(std::hypot(num(row, "Fx"), num(row, "Fy")), 1e-3 * buoyancy);

    // Held: the engine kept it where it was put.
    EXPECT_DOUBLE_EQ(num(row, "x"), kPosition[0]);
    EXPECT_DOUBLE_EQ(num(row, "y"), kPosition[1]);
    EXPECT_DOUBLE_EQ(num(row, "z"), kPosition[2]);
    EXPECT_EQ(num(row, "vz"), 0.0);
}

// The load is -grad p + div tau over the mask, the source is the penalty
// force on the fluid. Momentum of the masked fluid, at rest here, gives
//     F + S = -sum(chi V rho g) = rho_w |g| chiVolume (upwards):
// the load is not minus the source alone, because the masked fluid's weight
// is carried by the pressure, not by the penalty.
TEST_F(FoamBuoyancy, LoadBalancesSourceAndMaskedWeight) {
    ASSERT_EQ(serial_->status, 0) << serial_->output;
    const auto row = last_row(serial_->dir / "case/armourBodies.csv", "cube_0");
    ASSERT_FALSE(row.empty());
    const double weight = kRhoWater * kG * num(row, "chiVolume");
    EXPECT_NEAR(num(row, "Fz") + num(row, "Sz"), weight, 1e-3 * weight);
    EXPECT_NEAR(num(row, "Fx") + num(row, "Sx"), 0.0, 1e-3 * weight);
    EXPECT_NEAR(num(row, "Fy") + num(row, "Sy"), 0.0, 1e-3 * weight);
    // Fluid and body at rest: the penalty hardly acts.
    EXPECT_LT(std::abs(num(row, "Sz")), 1e-4 * weight);
}

// Loads are summed over MPI ranks: two ranks must give the serial answer.
TEST_F(FoamBuoyancy, TwoRanksMatchSerial) {
    ASSERT_EQ(serial_->status, 0) << serial_->output;
    const CaseRun parallel = run_case("np2", 2);
    ASSERT_EQ(parallel.status, 0) << parallel.output;
    const auto s = last_row(serial_->dir / "case/armourBodies.csv", "cube_0");
    const auto p = last_row(parallel.dir / "case/armourBodies.csv", "cube_0");
    ASSERT_FALSE(p.empty());
    EXPECT_NEAR(num(p, "Fz"), num(s, "Fz"), 1e-5 * num(s, "Fz"));
    EXPECT_NEAR(num(p, "chiVolume"), num(s, "chiVolume"), 1e-12);
    // The check passed across the processor patches too.
    EXPECT_NE(slurp(parallel.dir / "case/log.interFoam").find("force density face by face"),
              std::string::npos);
    if (!HasFailure())
        fs::remove_all(parallel.dir);
}

} // namespace

// A wrong WM_PROJECT_DIR stops run_case.sh before OUTDIR is made, naming the
// variable (blockMesh's own message does not).
TEST(RunCase, WrongProjectDirIsRefusedBeforeTheCaseIsMade) {
    ::setenv("WM_PROJECT_DIR", "/no/such/openfoam", 1);
    const CaseRun r = run_case("wrong_project_dir", 1);
    ::unsetenv("WM_PROJECT_DIR");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_EQ(r.output, "run_case: WM_PROJECT_DIR: /no/such/openfoam: not an OpenFOAM installation (no "
                        "etc/controlDict); unset it to use /usr/share/openfoam\n");
    EXPECT_FALSE(fs::exists(r.dir / "case"));
    fs::remove_all(r.dir);
}
