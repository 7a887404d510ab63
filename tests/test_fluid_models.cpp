// Porous regions ([[porous]], docs/porous.md) and the turbulence option
// (fluid.turbulence, docs/turbulence.md): van Gent's coefficients, the
// scene's checks, the cells of a breakwater's underlayer and core, steady
// flow through a porous plug and a falling head draining through a porous
// layer in interFoam against the Darcy-Forchheimer law, and the empty wave
// flume with kOmegaSST through `armour run`. Needs Debian's openfoam (built
// only with armourWaves); the slope layers take < 1 s, the plug ~5 s, the
// column ~20 s, the flume ~1.5 min on an idle 2-core machine.
#include "fluid_models.h"
#include "output_folder.h"
#include "scene.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using nlohmann::json;
using namespace armour;

namespace {

fs::path temp_dir(const std::string &name) {
    std::string tmpl = (fs::temp_directory_path() / ("armour_test_" + name + "_XXXXXX")).string();
    if (!mkdtemp(tmpl.data()))
        return {};
    return tmpl;
}

// A copy of tests/foam_cases/NAME with each token in `files` replaced by its value.
fs::path filled_case(const std::string &name, const std::vector<std::string> &files,
                     const std::vector<std::pair<std::string, std::string>> &tokens) {
    const fs::path dir = temp_dir(name);
    fs::copy(fs::path(ARMOUR_SOURCE_DIR) / "tests/foam_cases" / name, dir, fs::copy_options::recursive);
    for (const std::string &f : files) {
        std::string text = read_text_file(dir / f);
        for (const auto &[token, value] : tokens)
            text = std::regex_replace(text, std::regex(token), value);
        write_text_file(dir / f, text);
    }
    return dir;
}

// Runs the shell command line `tools` in the case with Debian's OpenFOAM: its exit status.
int run_foam(const fs::path &dir, const std::string &tools) {
    const std::string cmd = "cd '" + dir.string() +
                            "' && export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam} && " + tools;
    return std::system(cmd.c_str());
}

ScenePorous rock(double stone_size, double porosity) {
    ScenePorous p;
    p.name = "plug";
    p.stone_size = stone_size;
    p.porosity = porosity;
    return p;
}

// A scene of water (nu = 1e-6 m^2/s) under g = 9.81 m/s^2 with these regions.
Scene water_with(const std::vector<ScenePorous> &regions) {
    Scene scene;
    scene.gravity = {0, 0, -9.81};
    scene.fluid = SceneFluid();
    scene.porous = regions;
    return scene;
}

// The empty flume with one [[porous]] block appended (TOML text).
std::string flume_with(const std::string &porous_block) {
    return read_text_file(fs::path(ARMOUR_SOURCE_DIR) / "scenes/wave_flume.toml") + "\n" + porous_block;
}

// load_scene's error line for a scene text ("" when it loads).
std::string load_error(const fs::path &dir, const std::string &text) {
    const fs::path file = dir / "scene.toml";
    write_text_file(file, text);
    try {
        load_scene(file.string());
    } catch (const std::exception &e) {
        return e.what();
    }
    return "";
}

} // namespace

// van Gent (1995), steady flow: a = alpha (1-n)^2/n^3 nu/(g D^2), b = beta
// (1-n)/n^3/(g D); OpenFOAM's d = g a / nu, f = 2 g b (hand values for
// Dn50 = 0.01 m, n = 0.4: (1-n)^2/n^3 = 5.625, (1-n)/n^3 = 9.375).
TEST(VanGent, CoefficientsFromStoneSizeAndPorosity) {
    const DarcyForchheimer c = darcy_forchheimer(rock(0.01, 0.4), 1e-6, 9.81);
    EXPECT_NEAR(c.d, 1000 * 5.625 / 1e-4, 1e-9 * c.d);    // 5.625e7 1/m^2
    EXPECT_NEAR(c.f, 2 * 1.1 * 9.375 / 0.01, 1e-9 * c.f); // 2062.5 1/m
    EXPECT_NEAR(c.a, 1000 * 5.625 * 1e-6 / (9.81 * 1e-4), 1e-12);
    EXPECT_NEAR(c.b, 1.1 * 9.375 / (9.81 * 0.01), 1e-9);
    // Coarser, more open rock resists less, the laminar part with D^2.
    const DarcyForchheimer coarse = darcy_forchheimer(rock(0.02, 0.4), 1e-6, 9.81);
    EXPECT_NEAR(coarse.d, c.d / 4, 1e-9 * c.d);
    EXPECT_NEAR(coarse.f, c.f / 2, 1e-9 * c.f);
    EXPECT_LT(darcy_forchheimer(rock(0.01, 0.5), 1e-6, 9.81).d, c.d);
}

TEST(PorousScene, ReadsChecksAndWritesRegions) {
    const fs::path dir = temp_dir("porous_scene");
    const std::string block = "[[porous]]\nname = \"core\"\nmin = [6.0, 0.0, 0.0]\nmax = [8.0, 0.05, 0.3]\n"
                              "stone_size = 0.02\n";
    const fs::path file = dir / "scene.toml";
    write_text_file(file, flume_with(block));
    const Scene s = load_scene(file.string());
    ASSERT_EQ(s.porous.size(), 1u);
    EXPECT_EQ(s.porous[0].name, "core");
    EXPECT_DOUBLE_EQ(s.porous[0].porosity, 0.4);
    EXPECT_DOUBLE_EQ(s.porous[0].alpha, 1000);
    EXPECT_DOUBLE_EQ(s.porous[0].beta, 1.1);
    EXPECT_EQ(s.fluid->turbulence, "laminar");
    // The resolved scene reads back the same region.
    write_text_file(file, resolved_scene_toml(s));
    const Scene again = load_scene(file.string());
    ASSERT_EQ(again.porous.size(), 1u);
    EXPECT_EQ(again.porous[0].max, s.porous[0].max);
    EXPECT_DOUBLE_EQ(again.porous[0].stone_size, 0.02);

    EXPECT_NE(load_error(dir, flume_with(std::regex_replace(block, std::regex("max = \\[8.0"), "max = [5.0")))
                  .find("porous.0.max"),
              std::string::npos);
    EXPECT_NE(
        load_error(dir, flume_with(std::regex_replace(block, std::regex("max = \\[8.0"), "max = [11.0")))
            .find("must lie inside"),
        std::string::npos);
    EXPECT_NE(load_error(dir, flume_with(block + "\n" + block)).find("a second [[porous]]"),
              std::string::npos);
    EXPECT_NE(load_error(dir, flume_with(std::regex_replace(block, std::regex("\"core\""), "\"a b\"")))
                  .find("porous.0.name"),
              std::string::npos);
    EXPECT_NE(load_error(dir, flume_with(block + "porosity = 1.0\n")).find("porous.0.porosity"),
              std::string::npos);
    const std::string k_epsilon = std::regex_replace(flume_with(""), std::regex("\\[fluid\\]\n"),
                                                     "[fluid]\nturbulence = \"kEpsilon\"\n");
    EXPECT_NE(load_error(dir, k_epsilon).find("fluid.turbulence"), std::string::npos);
    // Without gravity k's start and the mirror's heights are undefined (NaN in the case).
    write_text_file(file, flume_with(""));
    for (const char *option : {"fluid.turbulence=\"kOmegaSST\"", "fluid.mirror_interior=true"}) {
        try {
            load_scene(file.string(), {"run.gravity=[0, 0, 0]", option});
            ADD_FAILURE() << option;
        } catch (const std::exception &e) {
            EXPECT_NE(std::string(e.what()).find("needs gravity"), std::string::npos) << e.what();
        }
    }
    fs::remove_all(dir);
}

// Steady flow through a porous plug under a head difference: a 1 m duct of
// water (1D), a plug of L = 0.2 m (Dn50 = 0.01 m, n = 0.4), p_rgh = rho g dH
// at the inlet and 0 at the outlet. Darcy-Forchheimer: dH / L = a u + b u^2,
// here i = 0.5, a u = 0.27 and b u^2 = 0.23 (both terms count):
// u = 0.046890 m/s. Measured (flux): 0.047692 m/s with 20 cells across the
// plug (+1.7 %), 0.047255 (+0.78 %) with 40, 0.047051 (+0.34 %) with 80:
// first order, the plug's two edge cells resist less (the momentum
// interpolation across the jump of the implicit coefficient; docs/porous.md).
TEST(PorousPlug, SteadyFlowFollowsVanGentsLaw) {
    const double g = 9.81, rho = 1000, nu = 1e-6, head = 0.1, length = 0.2;
    ScenePorous plug = rock(0.01, 0.4);
    plug.min = {0.4, 0.0, 0.0};
    plug.max = {0.6, 0.01, 0.01};
    const Scene scene = water_with({plug});
    const DarcyForchheimer c = darcy_forchheimer(plug, nu, g);
    const double i = head / length;
    const double u = (-c.a + std::sqrt(c.a * c.a + 4 * c.b * i)) / (2 * c.b);
    ASSERT_NEAR(u, 0.046890, 1e-6);

    auto flux_velocity = [&](int cells) {
        const fs::path dir = filled_case(
            "porous_plug", {"system/blockMeshDict", "0/p_rgh"},
            {{"@NX@", std::to_string(cells)}, {"@HEAD_PRESSURE@", std::to_string(rho * g * head)}});
        write_fluid_models(scene, dir);
        EXPECT_EQ(run_foam(dir, "blockMesh > log.blockMesh 2>&1 && "
                                "topoSet -dict system/topoSetDict.porous > log.topoSet 2>&1 && "
                                "interFoam > log.interFoam 2>&1"),
                  0)
            << "see " << dir;
        EXPECT_NE(read_text_file(dir / "log.topoSet")
                      .find("cellZoneSet porous_plug now size " + std::to_string(cells / 5)),
                  std::string::npos);
        // Face fluxes (m^3/s) through the 0.01 x 0.01 m duct: all equal.
        const std::string phi = read_text_file(dir / "0.5" / "phi");
        std::smatch m;
        const bool found = std::regex_search(phi, m, std::regex("internalField[^(]*\\(\\s*([-0-9.eE+]+)"));
        EXPECT_TRUE(found) << dir;
        if (!HasFailure())
            fs::remove_all(dir);
        return found ? std::stod(m[1]) / 1e-4 : 0.0;
    };
    const double coarse = flux_velocity(100), fine = flux_velocity(200);
    EXPECT_NEAR(coarse / u, 1.0, 0.025) << coarse;
    EXPECT_NEAR(fine / u, 1.0, 0.012) << fine;
    EXPECT_GT(coarse, fine); // from above, first order
    // Richardson extrapolation of the first-order error: 0.15 %.
    EXPECT_NEAR((2 * fine - coarse) / u, 1.0, 0.003) << coarse << " " << fine;
}

// A breakwater's underlayer and core as slope_layer regions of the slope
// wall of scenes/armour_slope_waves.toml: read, written back, and the bad
// inputs each named by their key.
TEST(PorousScene, SlopeLayersOfABreakwater) {
    const fs::path dir = temp_dir("porous_slope_scene");
    const std::string slope = read_text_file(fs::path(ARMOUR_SOURCE_DIR) / "scenes/armour_slope_waves.toml");
    const std::string layers = "[[porous]]\nname = \"underlayer\"\ntype = \"slope_layer\"\nwall = \"slope\"\n"
                               "thickness = 0.03\nstone_size = 0.02\nporosity = 0.4\n\n"
                               "[[porous]]\nname = \"core\"\ntype = \"slope_layer\"\nwall = \"slope\"\n"
                               "depth = 0.03\nstone_size = 0.01\nporosity = 0.35\n";
    const fs::path file = dir / "scene.toml";
    write_text_file(file, slope + "\n" + layers);
    const Scene s = load_scene(file.string());
    ASSERT_EQ(s.porous.size(), 2u);
    EXPECT_EQ(s.porous[0].type, "slope_layer");
    EXPECT_DOUBLE_EQ(s.porous[0].depth, 0.0);
    EXPECT_DOUBLE_EQ(s.porous[0].thickness.value_or(0), 0.03);
    EXPECT_DOUBLE_EQ(s.porous[1].depth, 0.03);
    EXPECT_FALSE(s.porous[1].thickness.has_value());
    write_text_file(file, resolved_scene_toml(s));
    const Scene again = load_scene(file.string());
    ASSERT_EQ(again.porous.size(), 2u);
    EXPECT_EQ(again.porous[1].wall, "slope");
    EXPECT_DOUBLE_EQ(again.porous[1].porosity, 0.35);
    EXPECT_FALSE(again.porous[1].thickness.has_value());

    auto error = [&](const std::string &from, const std::string &to) {
        return load_error(dir, slope + "\n" + std::regex_replace(layers, std::regex(from), to));
    };
    EXPECT_NE(error("wall = \"slope\"\nthickness", "wall = \"inlet_end\"\nthickness").find("porous.0.wall"),
              std::string::npos);
    EXPECT_NE(error("thickness = 0.03", "thickness = 0.0").find("porous.0.thickness"), std::string::npos);
    EXPECT_NE(error("depth = 0.03", "depth = -0.01").find("porous.1.depth"), std::string::npos);
    EXPECT_NE(error("depth = 0.03", "depth = 0.4")
                  .find("porous.1.depth': must be less than wall \"slope\"'s height"),
              std::string::npos);
    // A gap under the underlayer would cut the core off from the water.
    EXPECT_NE(error("depth = 0.03", "depth = 0.05")
                  .find("porous.1.depth': the slope_layers of wall \"slope\" "
                        "reach down to 0.03 m only"),
              std::string::npos)
        << error("depth = 0.03", "depth = 0.05");
    EXPECT_NE(error("porosity = 0.35", "porosity = -0.35").find("porous.1.porosity"), std::string::npos);
    EXPECT_NE(error("stone_size = 0.01", "stone_size = 0.0").find("porous.1.stone_size"), std::string::npos);
    EXPECT_NE(error("depth = 0.03", "depth = 0.03\nmin = [0.0, 0.0, 0.0]").find("porous.1"),
              std::string::npos);
    EXPECT_NE(error("type = \"slope_layer\"\nwall = \"slope\"\nthickness", "thickness")
                  .find("porous.0.thickness': not used by porous type \"box\""),
              std::string::npos);
    EXPECT_NE(error("type = \"slope_layer\"\nwall = \"slope\"\nthickness = 0.03", "")
                  .find("porous.0.min': missing required key"),
              std::string::npos)
        << error("type = \"slope_layer\"\nwall = \"slope\"\nthickness = 0.03", "");
    fs::remove_all(dir);
}

// The cells the slope_layer regions select, and that the mesh keeps: a 2D
// mesh of 50 x 25 square cells (0.02 m), a 1:1.5 slope from the toe at x =
// 0.303 m to the crest at z = 0.317 m cut out by the slope_waves template's
// topoSetDict, an underlayer 0.045 m thick and a core from 0.09 m down. A
// cell whose centre lies under the face and the crest at a distance d below
// the nearer of the two is in the underlayer (d < 0.045 m) or the core (d >=
// 0.09 m) and stays in the mesh; the band between stays cut out (solid):
// counted exactly from the cell centres. (A scene may not leave such a gap:
// the reader refuses it, since it closes the core off from the water; the
// gap here tests the depths and the cut.)
TEST(PorousSlope, LayersFollowTheFaceAndStayInTheMesh) {
    const fs::path dir = temp_dir("porous_slope");
    fs::create_directories(dir / "system");
    fs::create_directories(dir / "constant");
    fs::create_directories(dir / "0");
    for (const char *f : {"controlDict", "fvSchemes", "fvSolution"})
        fs::copy_file(fs::path(ARMOUR_SOURCE_DIR) / "tests/foam_cases/porous_plug/system" / f,
                      dir / "system" / f);
    write_text_file(
        dir / "system/blockMeshDict",
        "FoamFile { version 2.0; format ascii; class dictionary; object blockMeshDict; }\n"
        "vertices ((0 0 0) (1 0 0) (1 0.02 0) (0 0.02 0) (0 0 0.5) (1 0 0.5) (1 0.02 0.5) (0 0.02 0.5));\n"
        "blocks (hex (0 1 2 3 4 5 6 7) (50 1 25) simpleGrading (1 1 1));\n"
        "boundary ( walls { type wall; faces ((0 4 7 3) (1 2 6 5) (0 1 2 3) (4 5 6 7)); }\n"
        "  sides { type empty; faces ((0 1 5 4) (3 7 6 2)); } );\n");
    const double toe = 0.303, cot = 1.5, height = 0.317, thickness = 0.045;
    std::string cut =
        read_text_file(fs::path(ARMOUR_SOURCE_DIR) / "foam_cases/slope_waves/system/topoSetDict");
    cut = std::regex_replace(cut, std::regex("@SLOPE_TOE_X@"), std::to_string(toe));
    cut = std::regex_replace(cut, std::regex("@SLOPE_CREST_X@"), std::to_string(toe + cot * height));
    cut = std::regex_replace(cut, std::regex("@SLOPE_CREST_Z@"), std::to_string(height));
    cut = std::regex_replace(cut, std::regex("@Z0@"), "0");
    write_text_file(dir / "system/topoSetDict", cut);

    SceneWall wall;
    wall.name = "slope";
    wall.type = "slope";
    wall.toe_x = toe;
    wall.cot = cot;
    wall.height = height;
    ScenePorous under = rock(0.02, 0.4), core = rock(0.01, 0.35);
    under.name = "underlayer";
    under.type = core.type = "slope_layer";
    under.wall = core.wall = "slope";
    under.thickness = thickness;
    core.name = "core";
    core.depth = 2 * thickness;
    Scene scene = water_with({under, core});
    scene.domain_max = {1.0, 0.02, 0.5};
    scene.walls.push_back(wall);
    write_fluid_models(scene, dir);
    ASSERT_EQ(run_foam(dir, "blockMesh > log.blockMesh 2>&1 && topoSet > log.topoSet 2>&1 && "
                            "topoSet -dict system/topoSetDict.porous > log.topoSet.porous 2>&1 && "
                            "subsetMesh -overwrite fluid -patch walls > log.subsetMesh 2>&1"),
              0)
        << "see " << dir;

    const double sin_t = 1 / std::sqrt(1 + cot * cot), cos_t = cot * sin_t;
    int above = 0, in_under = 0, in_core = 0, solid = 0;
    for (int i = 0; i < 50; ++i)
        for (int k = 0; k < 25; ++k) {
            const double x = 0.02 * (i + 0.5), z = 0.02 * (k + 0.5);
            const double below = std::min((x - toe) * sin_t - z * cos_t, height - z);
            if (below < 0)
                ++above;
            else if (below < thickness)
                ++in_under;
            else if (below < 2 * thickness)
                ++solid;
            else
                ++in_core;
        }
    ASSERT_GT(in_under, 20);
    ASSERT_GT(solid, 20);
    ASSERT_GT(in_core, 20);
    const std::string log = read_text_file(dir / "log.topoSet.porous");
    EXPECT_NE(log.find("cellZoneSet porous_underlayer now size " + std::to_string(in_under)),
              std::string::npos)
        << in_under << "\n"
        << log;
    EXPECT_NE(log.find("cellZoneSet porous_core now size " + std::to_string(in_core)), std::string::npos)
        << in_core;
    // The mesh keeps the water's cells and the two layers', not the solid band between.
    EXPECT_NE(read_text_file(dir / "log.subsetMesh")
                  .find("Subset " + std::to_string(above + in_under + in_core) + " of 1250 cells"),
              std::string::npos);
    const std::string zones = read_text_file(dir / "constant/polyMesh/cellZones");
    std::smatch m;
    ASSERT_TRUE(
        std::regex_search(zones, m, std::regex("porous_underlayer\\s*\\{[^}]*List<label>\\s*(\\d+)")));
    EXPECT_EQ(std::stoi(m[1]), in_under);
    if (!HasFailure())
        fs::remove_all(dir);
}

// The same through `armour run` on the slope_waves template (one cube held
// in the air above the crest, 0.02 s): an underlayer 0.04 m thick and a
// berm box in the water before the toe. The case keeps the template's fluid
// cells and the underlayer's (the slope below stays cut out), and interFoam
// builds both porous zones and runs.
TEST(PorousSlope, ArmourRunKeepsTheLayersInTheSlopesMesh) {
    const fs::path dir = temp_dir("porous_slope_run");
    std::string scene = read_text_file(fs::path(ARMOUR_SOURCE_DIR) / "scenes/armour_slope_waves.toml");
    scene = scene.substr(0, scene.find("\n[[pattern]]")) +
            "\n[[body]]\nunit = \"cube\"\nposition = [0.6, 0.0, 0.45]\n\n"
            "[[porous]]\nname = \"underlayer\"\ntype = \"slope_layer\"\nwall = \"slope\"\nthickness = 0.04\n"
            "stone_size = 0.02\n\n[[porous]]\nname = \"berm\"\nmin = [-0.2, -0.14, 0.0]\n"
            "max = [0.0, 0.14, 0.04]\nstone_size = 0.04\n";
    write_text_file(dir / "scene.toml", scene);
    const std::string cmd =
        std::string("'") + ARMOUR_EXE + "' run '" + (dir / "scene.toml").string() + "' --out '" +
        (dir / "out").string() +
        "' --set run.duration=0.02 --set fluid.settle_time=0 --set 'run.engine=\"free_body\"' > '" +
        (dir / "run.log").string() + "' 2>&1";
    const int rc = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 0) << read_text_file(dir / "run.log");
    const fs::path case_dir = dir / "out/case";
    auto last_size = [](const std::string &log, const std::string &what) {
        int size = -1;
        std::smatch m;
        const std::regex pattern(what + " now size (\\d+)");
        for (auto it = std::sregex_iterator(log.begin(), log.end(), pattern); it != std::sregex_iterator();
             ++it)
            size = std::stoi((*it)[1]);
        return size;
    };
    const int fluid = last_size(read_text_file(case_dir / "log.topoSet"), "cellSet fluid");
    const std::string porous = read_text_file(case_dir / "log.topoSet.porous");
    const int under = last_size(porous, "cellZoneSet porous_underlayer"),
              berm = last_size(porous, "cellZoneSet porous_berm");
    // 0.04 m under the face and crest of 0.02 m cells: ~2 cells deep, across 14.
    EXPECT_GT(under, 14 * 2 * 30);
    EXPECT_EQ(berm, 10 * 14 * 2); // 0.2 x 0.28 x 0.04 m
    // 95 x 14 x 26 cells; the slope below the underlayer stays cut out, the berm was water.
    const int kept = fluid + under;
    EXPECT_LT(kept, 95 * 14 * 26);
    EXPECT_NE(read_text_file(case_dir / "log.subsetMesh").find("Subset " + std::to_string(kept) + " of "),
              std::string::npos)
        << fluid << " + " << under;
    const std::string solver = read_text_file(case_dir / "log.interFoam");
    EXPECT_NE(solver.find("creating porous zone: porous_underlayer"), std::string::npos);
    EXPECT_NE(solver.find("creating porous zone: porous_berm"), std::string::npos);
    const json summary = json::parse(read_text_file(dir / "out/summary.json"));
    EXPECT_EQ(summary["fluid"]["cells_total"].get<int>(), kept);
    EXPECT_EQ(summary["fluid"]["porous"].size(), 2u);
    if (!HasFailure())
        fs::remove_all(dir);
}

// A falling head through a porous layer: a vertical column (1D) with a
// layer of rock at its foot (L = 0.2 m, Dn50 = 0.01 m, n = 0.4), open to the
// atmosphere below it and above, water from the bottom up to h0 = 0.6 m.
// While the surface is above the layer, the layer stays full and the water
// above it moves down at the filter velocity u: dh/dt = -u with
// a u + b u|u| = i = (1 - rho_air / rho) h / L (the air column's weight
// against the water's). The column's inertia settles in ~h / (g L (a + 2 b
// u)) = 0.02 s, so after 0.2 s the quasi-steady law holds.
struct ColumnRun {
    std::vector<double> t, h, u; // s, m (water volume / area), m/s (outflow / area)
};

ColumnRun drain_column(const Scene &scene, int cells, double dt, double h0, double end) {
    const int every = static_cast<int>(std::lround(0.05 / dt));
    const fs::path dir =
        filled_case("porous_column", {"system/blockMeshDict", "system/controlDict", "system/setFieldsDict"},
                    {{"@NZ@", std::to_string(cells)},
                     {"@DT@", std::to_string(dt)},
                     {"@END@", std::to_string(end)},
                     {"@EVERY@", std::to_string(every)},
                     {"@H0@", std::to_string(h0)}});
    write_fluid_models(scene, dir);
    EXPECT_EQ(run_foam(dir, "blockMesh > log.blockMesh 2>&1 && "
                            "topoSet -dict system/topoSetDict.porous > log.topoSet 2>&1 && "
                            "setFields > log.setFields 2>&1 && interFoam > log.interFoam 2>&1"),
              0)
        << "see " << dir;
    ColumnRun run;
    auto series = [&](const std::string &file) {
        std::ifstream in(dir / file);
        std::vector<std::pair<double, double>> rows;
        std::string line;
        while (std::getline(in, line))
            if (!line.empty() && line[0] != '#') {
                std::istringstream s(line);
                double time = 0, value = 0;
                if (s >> time >> value)
                    rows.emplace_back(time, value);
            }
        return rows;
    };
    const auto water = series("postProcessing/water/0/volFieldValue.dat");
    const auto outflow = series("postProcessing/outflow/0/surfaceFieldValue.dat");
    EXPECT_EQ(water.size(), outflow.size()) << dir;
    for (std::size_t k = 0; k < std::min(water.size(), outflow.size()); ++k) {
        run.t.push_back(water[k].first);
        run.h.push_back(water[k].second / 1e-4);
        run.u.push_back(outflow[k].second / 1e-4);
    }
    if (!::testing::Test::HasFailure())
        fs::remove_all(dir);
    return run;
}

TEST(PorousColumn, DrainsAtTheDarcyForchheimerRate) {
    const double g = 9.81, nu = 1e-6, length = 0.2, h0 = 0.6, end = 2.5, air = 1.0 / 1000;
    ScenePorous layer = rock(0.01, 0.4);
    layer.min = {-1, -1, -1};
    layer.max = {1, 1, length};
    const Scene scene = water_with({layer});
    const DarcyForchheimer c = darcy_forchheimer(layer, nu, g);
    auto rate = [&](double h) { // the filter velocity at head h
        const double i = (1 - air) * h / length;
        return (-c.a + std::sqrt(c.a * c.a + 4 * c.b * i)) / (2 * c.b);
    };
    // The column's own inertia as interFoam has it (rho du/dt over the whole
    // column, the filter velocity in the layer): h du/dt = g ((1 - rho_air /
    // rho) h - L i(u)), dh/dt = -u, from rest; RK4 in 1e-4 s steps.
    auto head_at = [&](double time) {
        auto slope = [&](double h, double u) {
            const double i = c.a * u + c.b * u * std::abs(u);
            return std::make_pair(-u, g * ((1 - air) * h - length * i) / h);
        };
        double h = h0, u = 0;
        const double step = 1e-4;
        for (int k = 0; k < static_cast<int>(std::lround(time / step)); ++k) {
            const auto k1 = slope(h, u);
            const auto k2 = slope(h + 0.5 * step * k1.first, u + 0.5 * step * k1.second);
            const auto k3 = slope(h + 0.5 * step * k2.first, u + 0.5 * step * k2.second);
            const auto k4 = slope(h + step * k3.first, u + step * k3.second);
            h += step / 6 * (k1.first + 2 * k2.first + 2 * k3.first + k4.first);
            u += step / 6 * (k1.second + 2 * k2.second + 2 * k3.second + k4.second);
        }
        return h;
    };
    const double h_end = head_at(end);
    ASSERT_GT(h_end, length + 0.02); // the surface stays above the layer
    struct Errors {
        double rate_mean = 0, rate_worst = 0, drained = 0;
    };
    // While the surface is above the layer (t <= end).
    auto errors = [&](const char *name, const ColumnRun &r) {
        Errors e;
        int n = 0;
        double h_at_end = r.h.front();
        for (std::size_t k = 0; k < r.t.size() && r.t[k] < end + 1e-9; ++k) {
            h_at_end = r.h[k];
            if (r.t[k] >= 0.2) {
                const double error = r.u[k] / rate(r.h[k]) - 1;
                e.rate_mean += error;
                e.rate_worst = std::max(e.rate_worst, std::abs(error));
                ++n;
            }
        }
        e.rate_mean /= std::max(n, 1);
        e.drained = (h0 - h_at_end) / (h0 - h_end) - 1;
        std::printf("%s: outflow against the law at the run's own head: mean %+.3f %%, worst %.3f %% (%d "
                    "samples); drained at %.1f s: %.5f m against %.5f m (%+.3f %%)\n",
                    name, 100 * e.rate_mean, 100 * e.rate_worst, n, end, h0 - h_at_end, h0 - h_end,
                    100 * e.drained);
        return e;
    };
    // Measured: the rate +0.504 % (dz 5 mm, dt 1 ms), +0.468 % (dt 0.5 ms),
    // +0.272 % (dz 2.5 mm, dt 0.5 ms): first order in dz, the layer's top
    // cells resisting less (as the plug's edges), dt's share 0.04 %;
    // Richardson +0.04 %. Drained depth +0.266 % and +0.102 %. The bounds:
    // twice the measured errors, and convergence.
    const ColumnRun coarse_run = drain_column(scene, 160, 1e-3, h0, 5.0);
    ASSERT_GT(coarse_run.t.size(), 90u);
    const Errors coarse = errors("dz 5 mm, dt 1 ms", coarse_run);
    const ColumnRun fine_run = drain_column(scene, 320, 5e-4, h0, end);
    ASSERT_GT(fine_run.t.size(), 40u);
    const Errors fine = errors("dz 2.5 mm, dt 0.5 ms", fine_run);
    EXPECT_NEAR(coarse.rate_mean, 0, 0.01);
    EXPECT_LT(coarse.rate_worst, 0.011);
    EXPECT_NEAR(fine.rate_mean, 0, 0.0055);
    EXPECT_LT(fine.rate_worst, 0.006);
    EXPECT_LT(std::abs(fine.rate_mean), std::abs(coarse.rate_mean));
    EXPECT_NEAR(2 * fine.rate_mean - coarse.rate_mean, 0, 0.002);
    EXPECT_NEAR(coarse.drained, 0, 0.006);
    EXPECT_NEAR(fine.drained, 0, 0.003);

    // Once the surface is inside the layer (h < L), the head over the wet
    // part is its own height: i = 1 - rho_air / rho, u = 0.0740 m/s. The
    // level falls at u, not at the pore velocity u / n: interFoam's VOF fills
    // the whole cell (no porosity in the storage, docs/porous.md), so the
    // layer drains n = 0.4 times as fast as real rock would.
    int inside = 0;
    for (std::size_t k = 1; k < coarse_run.t.size(); ++k)
        if (coarse_run.h[k] < length - 0.02 && coarse_run.h[k - 1] < length - 0.02) {
            const double fall =
                (coarse_run.h[k - 1] - coarse_run.h[k]) / (coarse_run.t[k] - coarse_run.t[k - 1]);
            const double u = 0.5 * (coarse_run.u[k] + coarse_run.u[k - 1]);
            EXPECT_NEAR(u / rate(length), 1, 0.005) << coarse_run.t[k];
            EXPECT_NEAR(fall / u, 1, 0.01) << coarse_run.t[k];
            ++inside;
        }
    EXPECT_GT(inside, 15);
}

// The empty wave flume (scenes/wave_flume.toml: H = 0.06 m, T = 1.6 s, h =
// 0.4 m) with kOmegaSST: the case gets the RAS model and its fields, and the
// incident wave at the far array (waves.gauge_x = 6.5 m) is reported. The
// inflow intensity is 0.01, not the default 1e-4: k-omega SST over-produces
// k under the wave whatever its seed (docs/turbulence.md), and from 0.01 the
// wave at 6.5 m has reached its over-damped, quasi-steady height by the
// analysis window (the last 9 periods of 32 s: 33.0 mm falling to 32.1 mm
// per period, 2.6 %), where from 1e-4 the window catches the collapse
// itself (59.2 to 54.0 mm), which a period's shift of its onset changes by
// ~10 %. Measured (bench/run_turbulence_flume.sh, the flume's Crank-Nicolson
// 0.3): 0.03235 m, laminar 0.05969 m. The bounds: within 5 % of the measured
// height (twice the drift over the window; runs repeat bit for bit here),
// and below 0.6 of the laminar height (the over-damping itself; measured 0.54).
TEST(Turbulence, KOmegaSSTFlumeRunsAndReportsItsHeight) {
    const fs::path dir = temp_dir("turbulence_flume");
    const std::string cmd = std::string("'") + ARMOUR_EXE + "' run '" + ARMOUR_SOURCE_DIR +
                            "/scenes/wave_flume.toml' --out '" + (dir / "out").string() +
                            "' --set 'fluid.turbulence=\"kOmegaSST\"' --set fluid.turbulence_intensity=0.01 "
                            "--set waves.gauge_x=6.5 > '" +
                            (dir / "run.log").string() + "' 2>&1";
    const int rc = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 0) << read_text_file(dir / "run.log");
    EXPECT_NE(read_text_file(dir / "out/case/constant/turbulenceProperties").find("kOmegaSST"),
              std::string::npos);
    EXPECT_NE(read_text_file(dir / "out/case/log.interFoam").find("Selecting RAS turbulence model kOmegaSST"),
              std::string::npos);
    const json summary = json::parse(read_text_file(dir / "out/summary.json"));
    const json &t = summary["fluid"]["turbulence"];
    EXPECT_EQ(t["model"], "kOmegaSST");
    // k0 = 1.5 (0.01 sqrt(9.81 x 0.4))^2, omega0 = sqrt(k0) / (0.09^0.25 x 0.01 m).
    const double k0 = 1.5 * 1e-4 * 9.81 * 0.4;
    EXPECT_NEAR(t["k0"].get<double>(), k0, 1e-6 * k0);
    EXPECT_NEAR(t["omega0"].get<double>(), std::sqrt(k0) / (std::pow(0.09, 0.25) * 0.01), 1e-9);
    const double height = summary["waves"]["incident_height"].get<double>();
    const double loss = 1.0 - height / 0.06;
    RecordProperty("incident_height_loss_percent", std::to_string(100 * loss));
    std::printf("kOmegaSST: incident height %.5f m at x = 6.5 m, %.1f %% below H = 0.06 m\n", height,
                100 * loss);
    EXPECT_NEAR(height / 0.03235, 1.0, 0.05);
    EXPECT_LT(height, 0.6 * 0.05969);
    if (!HasFailure())
        fs::remove_all(dir);
}

// Past the edge of the pressure solve: the turbulent flume above with p_rgh
// solved to 1e-6 and 5 % (the laminar stability scene's setting) loses its
// step at t = 7.27 s (measured: 5 ms to 2e-6 s and below, where it went on
// at 1e-25 s until killed before the step floor existed). The run stops
// there with one line naming fluid.min_time_step (the default floor: 0.5 x
// 1 cm / 1000 m/s = 5e-6 s), instead of running for ever; ~40 s.
TEST(Turbulence, LooserPressureSolveStallsAndTheRunStopsWithOneLine) {
    const fs::path dir = temp_dir("turbulence_stall");
    const std::string cmd =
        std::string("'") + ARMOUR_EXE + "' run '" + ARMOUR_SOURCE_DIR + "/scenes/wave_flume.toml' --out '" +
        (dir / "out").string() +
        "' --set 'fluid.turbulence=\"kOmegaSST\"' --set fluid.turbulence_intensity=0.01 "
        "--set fluid.pressure_tolerance=1e-6 --set fluid.pressure_relative_tolerance=0.05 > '" +
        (dir / "run.log").string() + "' 2>&1";
    const int rc = std::system(cmd.c_str());
    const std::string out = read_text_file(dir / "run.log");
    ASSERT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 2) << out;
    const std::string error = out.substr(std::min(out.find("armour: error: "), out.size()));
    EXPECT_EQ(error.find('\n'), error.size() - 1) << out;
    EXPECT_NE(error.find("wave_flume.toml: key 'fluid.min_time_step': interFoam's step fell to "),
              std::string::npos)
        << out;
    EXPECT_NE(error.find("below 5e-06 s"), std::string::npos) << out;
    const std::smatch at = [&] {
        std::smatch m;
        std::regex_search(error, m, std::regex(R"(at t = ([0-9.]+) s)"));
        return m;
    }();
    ASSERT_EQ(at.size(), 2u) << error;
    EXPECT_GT(std::stod(at[1]), 3.0) << "the pressure solve held through the ramp";
    EXPECT_LT(std::stod(at[1]), 32.0);
    EXPECT_FALSE(fs::exists(dir / "out/summary.json"));
    if (!HasFailure())
        fs::remove_all(dir);
}

// fluid.pressure_tolerance and pressure_relative_tolerance reach p_rgh's
// solve in every corrector (the last solves p_rghFinal, relTol 0), and
// fluid.momentum_predictor = false PIMPLE's momentumPredictor: OpenFOAM reads
// them from the case (foamDictionary merges the appended entries); every
// p_rgh solve of the shipped empty flume's first 0.3 s stops where they say,
// the last of each step at the absolute tolerance, which the template's 1e-7
// would not let pass (some final residuals lie above it); and no step solves
// the momentum equation (no "Solving for Ux"), which the template's does.
TEST(SolverSettings, PressureToleranceAndMomentumPredictorReachTheSolve) {
    const fs::path dir = temp_dir("pressure_solve");
    const std::string cmd =
        std::string("'") + ARMOUR_EXE + "' run '" + ARMOUR_SOURCE_DIR + "/scenes/wave_flume.toml' --out '" +
        (dir / "out").string() +
        "' --set run.duration=0.3 --set fluid.pressure_tolerance=2e-6 --set "
        "fluid.pressure_relative_tolerance=0.03 --set fluid.momentum_predictor=false > '" +
        (dir / "run.log").string() + "' 2>&1";
    const int rc = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 0) << read_text_file(dir / "run.log");
    const fs::path case_dir = dir / "out/case";
    for (const auto &[entry, value] :
         std::vector<std::pair<std::string, double>>{{"p_rgh/tolerance", 2e-6},
                                                     {"p_rgh/relTol", 0.03},
                                                     {"p_rghFinal/tolerance", 2e-6},
                                                     {"p_rghFinal/relTol", 0.0},
                                                     {"\"U.*\"/tolerance", 1e-8}}) {
        const fs::path read = dir / "entry.txt";
        ASSERT_EQ(run_foam(case_dir, "foamDictionary -entry 'solvers/" + entry +
                                         "' -value system/fvSolution > '" + read.string() + "' 2>&1"),
                  0)
            << entry << ": " << read_text_file(read);
        EXPECT_DOUBLE_EQ(std::stod(read_text_file(read)), value) << entry;
    }
    // "GAMG:  Solving for p_rgh, Initial residual = a, Final residual = b, No Iterations n"
    const std::string log = read_text_file(case_dir / "log.interFoam");
    const std::regex solve(R"(Solving for p_rgh, Initial residual = ([^,]+), Final residual = ([^,]+),)");
    std::vector<std::pair<double, double>> step; // one step's solves
    int steps = 0, above_template = 0;
    const auto close_step = [&] {
        for (std::size_t i = 0; i < step.size(); ++i) {
            const auto [initial, final] = step[i];
            if (i + 1 == step.size()) {
                EXPECT_LE(final, 2e-6) << "step " << steps;
                above_template += final > 1e-7;
            } else {
                EXPECT_LE(final, std::max(2e-6, 0.03 * initial) * (1 + 1e-9)) << "step " << steps;
            }
        }
        steps += !step.empty();
        step.clear();
    };
    std::istringstream lines(log);
    for (std::string line; std::getline(lines, line);) {
        std::smatch m;
        if (line.rfind("Time = ", 0) == 0)
            close_step();
        else if (std::regex_search(line, m, solve))
            step.emplace_back(std::stod(m[1]), std::stod(m[2]));
    }
    close_step();
    EXPECT_GT(steps, 10);
    EXPECT_GT(above_template, 0) << "every last solve met the template's 1e-7 anyway";
    const fs::path predictor = dir / "predictor.txt";
    ASSERT_EQ(
        run_foam(case_dir, "foamDictionary -entry PIMPLE/momentumPredictor -value system/fvSolution > '" +
                               predictor.string() + "' 2>&1"),
        0)
        << read_text_file(predictor);
    EXPECT_EQ(read_text_file(predictor).substr(0, 2), "no") << read_text_file(predictor);
    EXPECT_EQ(log.find("Solving for Ux"), std::string::npos);
    const json summary = json::parse(read_text_file(dir / "out/summary.json"));
    EXPECT_DOUBLE_EQ(summary["fluid"]["pressure_tolerance"].get<double>(), 2e-6);
    EXPECT_DOUBLE_EQ(summary["fluid"]["pressure_relative_tolerance"].get<double>(), 0.03);
    EXPECT_EQ(summary["fluid"]["momentum_predictor"], false);
    if (!HasFailure())
        fs::remove_all(dir);
}
