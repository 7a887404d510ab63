// Porous regions ([[porous]], docs/porous.md) and the turbulence option
// (fluid.turbulence, docs/turbulence.md): van Gent's coefficients, the
// scene's checks, steady flow through a porous plug in interFoam against the
// Darcy-Forchheimer law, and the empty wave flume with kOmegaSST through
// `armour run`. Needs Debian's openfoam (built only with armourWaves); the
// plug runs ~5 s, the flume ~1-2 min on an idle 2-core machine.
#include "fluid_models.h"
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

#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using nlohmann::json;
using namespace armour;

namespace {

std::string read_text(const fs::path &path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void write_text(const fs::path &path, const std::string &text) {
    std::ofstream(path) << text;
}

fs::path temp_dir(const std::string &name) {
    std::string tmpl = (fs::temp_directory_path() / ("armour_test_" + name + "_XXXXXX")).string();
    if (!mkdtemp(tmpl.data()))
        return {};
    return tmpl;
}

ScenePorous rock(double stone_size, double porosity) {
    ScenePorous p;
    p.name = "plug";
    p.stone_size = stone_size;
    p.porosity = porosity;
    return p;
}

// The empty flume with one [[porous]] block appended (TOML text).
std::string flume_with(const std::string &porous_block) {
    return read_text(fs::path(ARMOUR_SOURCE_DIR) / "scenes/wave_flume.toml") + "\n" + porous_block;
}

// load_scene's error line for a scene text ("" when it loads).
std::string load_error(const fs::path &dir, const std::string &text) {
    const fs::path file = dir / "scene.toml";
    write_text(file, text);
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
    write_text(file, flume_with(block));
    const Scene s = load_scene(file.string());
    ASSERT_EQ(s.porous.size(), 1u);
    EXPECT_EQ(s.porous[0].name, "core");
    EXPECT_DOUBLE_EQ(s.porous[0].porosity, 0.4);
    EXPECT_DOUBLE_EQ(s.porous[0].alpha, 1000);
    EXPECT_DOUBLE_EQ(s.porous[0].beta, 1.1);
    EXPECT_EQ(s.fluid->turbulence, "laminar");
    // The resolved scene reads back the same region.
    write_text(file, resolved_scene_toml(s));
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
    Scene scene;
    scene.gravity = {0, 0, -g};
    scene.fluid.emplace();
    scene.fluid->viscosity = nu;
    ScenePorous plug = rock(0.01, 0.4);
    plug.min = {0.4, 0.0, 0.0};
    plug.max = {0.6, 0.01, 0.01};
    scene.porous.push_back(plug);
    const DarcyForchheimer c = darcy_forchheimer(plug, nu, g);
    const double i = head / length;
    const double u = (-c.a + std::sqrt(c.a * c.a + 4 * c.b * i)) / (2 * c.b);
    ASSERT_NEAR(u, 0.046890, 1e-6);

    auto flux_velocity = [&](int cells) {
        const fs::path dir = temp_dir("porous_plug");
        fs::copy(fs::path(ARMOUR_SOURCE_DIR) / "tests/foam_cases/porous_plug", dir,
                 fs::copy_options::recursive);
        for (const char *f : {"system/blockMeshDict", "0/p_rgh"}) {
            std::string text = read_text(dir / f);
            text = std::regex_replace(text, std::regex("@NX@"), std::to_string(cells));
            text = std::regex_replace(text, std::regex("@HEAD_PRESSURE@"), std::to_string(rho * g * head));
            write_text(dir / f, text);
        }
        write_fluid_models(scene, dir);
        const std::string cmd = "cd '" + dir.string() +
                                "' && export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam} && "
                                "blockMesh > log.blockMesh 2>&1 && "
                                "topoSet -dict system/topoSetDict.porous > log.topoSet 2>&1 && "
                                "interFoam > log.interFoam 2>&1";
        const int rc = std::system(cmd.c_str());
        EXPECT_EQ(rc, 0) << "see " << dir;
        EXPECT_NE(read_text(dir / "log.topoSet")
                      .find("cellZoneSet porous_plug now size " + std::to_string(cells / 5)),
                  std::string::npos);
        // Face fluxes (m^3/s) through the 0.01 x 0.01 m duct: all equal.
        const std::string phi = read_text(dir / "0.5" / "phi");
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
