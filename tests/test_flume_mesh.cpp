// The wave flume's graded mesh lines (fluid_case/flume_mesh.h): fine cells inside
// the refined box, growth of at most kMaxCellGrowth per cell outside it, up
// to coarse_cell_size, on the shipped stability scene with the box's
// edges off the fine grid's nodes. blockMesh's own points are checked
// against these lines in test_wave_flume (GradedMesh...).
#include "flume_mesh.h"
#include "wave_case.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace {

std::string scene_path(const std::string &name) {
    return std::string(ARMOUR_SOURCE_DIR) + "/scenes/" + name;
}

void expect_graded(const armour::MeshAxis &axis, double lo, double hi, double h, double a, double b,
                   double coarsen, const std::string &name) {
    ASSERT_EQ(axis.nodes.size(), static_cast<std::size_t>(axis.cells) + 1) << name;
    EXPECT_DOUBLE_EQ(axis.nodes.front(), lo) << name;
    EXPECT_DOUBLE_EQ(axis.nodes.back(), hi) << name;
    // The box holds whole cells no larger than h: at least h (1 - h / box).
    const double shrink = 1.0 - h / (b - a);
    for (std::size_t i = 1; i < axis.nodes.size(); ++i) {
        const double size = axis.nodes[i] - axis.nodes[i - 1],
                     centre = 0.5 * (axis.nodes[i] + axis.nodes[i - 1]);
        if (centre > a && centre < b) {
            EXPECT_LE(size, h * (1.0 + 1e-9)) << name << " cell " << i << " at " << centre;
        }
        // Never below the fine cell (a short stretch joins the box), never above the coarse one.
        EXPECT_GE(size, h * shrink * (1.0 - 1e-9)) << name << " cell " << i << " at " << centre;
        EXPECT_LE(size, coarsen * h * (1.0 + 1e-9)) << name << " cell " << i << " at " << centre;
        if (i > 1) {
            const double previous = axis.nodes[i - 1] - axis.nodes[i - 2];
            const double growth = std::max(size / previous, previous / size);
            EXPECT_LE(growth, armour::kMaxCellGrowth / shrink * (1.0 + 1e-9))
                << name << " cells " << i - 1 << ", " << i;
        }
    }
}

} // namespace

TEST(FlumeMesh, UniformWithoutARefinedBox) {
    const armour::Scene scene = armour::load_scene(scene_path("wave_flume.toml"));
    const armour::FlumeMesh mesh = armour::flume_mesh(scene);
    EXPECT_FALSE(mesh.graded);
    for (int i = 0; i < 3; ++i) {
        const armour::MeshAxis &axis = mesh.axes[i];
        ASSERT_EQ(axis.cells, scene.fluid->cells[i]);
        EXPECT_EQ(axis.grading, "1");
        const double h = (scene.domain_max[i] - scene.domain_min[i]) / axis.cells;
        for (int k = 0; k <= axis.cells; ++k)
            EXPECT_NEAR(axis.nodes[k], scene.domain_min[i] + k * h, 1e-12);
    }
}

// waves.extra_gauges follow the Mansard-Funke array, each moved to the
// centre of the block's cell column it lies in (as the array's are).
TEST(FlumeMesh, ExtraGaugesFollowTheArrayAtTheirColumnsCentres) {
    const armour::Scene plain = armour::load_scene(scene_path("stability_cubes.toml"));
    const armour::Scene scene =
        armour::load_scene(scene_path("stability_cubes.toml"), {"waves.extra_gauges=[1.22, 1.30, 1.38]"});
    const std::vector<double> array = armour::wave_gauge_positions(plain);
    const std::vector<double> x = armour::wave_gauge_positions(scene);
    ASSERT_EQ(array.size(), 3u);
    ASSERT_EQ(x.size(), 6u);
    EXPECT_EQ(std::vector<double>(x.begin(), x.begin() + 3), array);
    const armour::MeshAxis along = armour::flume_mesh(scene).axes[0];
    for (std::size_t i = 0; i < 3; ++i) {
        const double at = scene.waves->extra_gauges[i];
        const auto upper = std::upper_bound(along.nodes.begin(), along.nodes.end(), at);
        ASSERT_NE(upper, along.nodes.end());
        EXPECT_DOUBLE_EQ(x[3 + i], 0.5 * (*(upper - 1) + *upper)) << at;
    }
}

// The stability scene's graded mesh (the bench's reference row), with box
// edges that fall between fine nodes (x 1.153, z 0.183, just under the largest wave's trough bound 0.184) and
// a box that touches the flume's end and top (nothing to grade there).
TEST(FlumeMesh, GradedStabilityFlumeKeepsTheFineCellsInTheBoxAndGrowsSlowlyOutside) {
    const armour::Scene scene = armour::load_scene(
        scene_path("stability_cubes.toml"),
        {"fluid.mesh=graded", "fluid.cells=[200,25,62]", "fluid.refine_min=[1.153, -0.124, 0.183]",
         "fluid.refine_max=[2.0, 0.124, 0.62]", "fluid.coarse_cell_size=[0.05, 0.0, 0.03]"});
    const armour::FlumeMesh mesh = armour::flume_mesh(scene);
    ASSERT_TRUE(mesh.graded);
    const double h = 0.01; // m, the scene's fluid.cells
    expect_graded(mesh.axes[0], 0.0, 2.0, h, 1.153, 2.0, 5.0, "x");
    expect_graded(mesh.axes[1], -0.124, 0.124, 0.248 / 25, -0.124, 0.124, 1.0, "y");
    expect_graded(mesh.axes[2], 0.0, 0.62, h, 0.183, 0.62, 3.0, "z");
    EXPECT_EQ(mesh.axes[1].cells, 25);
    // Along x the 1.15 m in front of the box is long enough to reach 5 h.
    EXPECT_NEAR(mesh.axes[0].largest_cell() / (5.0 * h), 1.0, 0.05);
    // Fewer cells than the uniform mesh's 200 x 25 x 62.
    EXPECT_LT(mesh.cells(), 200L * 25 * 62 * 6 / 10);
    // Gauges sit mid-column, never on a face.
    for (const double at : {0.3, 0.6301, 1.1, 1.153, 1.9999}) {
        const double c = mesh.axes[0].column_centre(at);
        const auto upper = std::upper_bound(mesh.axes[0].nodes.begin(), mesh.axes[0].nodes.end(), c);
        EXPECT_NEAR(c, 0.5 * (*(upper - 1) + *upper), 1e-12) << at;
        EXPECT_LE(*(upper - 1), at + 1e-12);
        EXPECT_GE(*upper, at - 1e-12);
    }
}

TEST(FlumeMesh, BadGradingKeysAreRefusedNamingTheKey) {
    const std::string file = scene_path("wave_flume.toml"); // 10 x 0.05 x 0.6 m, cells 0.05 x 0.05 x 0.01 m
    const auto error_of = [&](const std::vector<std::string> &sets) -> std::string {
        try {
            armour::load_scene(file, sets);
        } catch (const std::exception &e) {
            return e.what();
        }
        return "";
    };
    const std::string box_min = "fluid.refine_min=[5.0, 0.0, 0.25]",
                      box_max = "fluid.refine_max=[10.0, 0.05, 0.6]";
    EXPECT_EQ(error_of({box_min, box_max, "fluid.coarse_cell_size=[0.1, 0.0, 0.03]"}), "");
    EXPECT_NE(error_of({box_min, "fluid.coarse_cell_size=[0.1, 0.0, 0.03]"}).find("fluid.refine_max"),
              std::string::npos);
    EXPECT_NE(error_of({"fluid.coarse_cell_size=[0.1, 0.0, 0.03]"}).find("fluid.refine_min"),
              std::string::npos);
    EXPECT_NE(error_of({box_min, box_max}).find("fluid.coarse_cell_size"), std::string::npos);
    EXPECT_NE(
        error_of({box_min, "fluid.refine_max=[10.5, 0.05, 0.6]", "fluid.coarse_cell_size=[0.1, 0.0, 0.03]"})
            .find("fluid.refine_max"),
        std::string::npos);
    EXPECT_NE(
        error_of({"fluid.refine_min=[5.0, 0.0, 0.7]", box_max, "fluid.coarse_cell_size=[0.1, 0.0, 0.03]"})
            .find("fluid.refine_max"),
        std::string::npos);
    // Thinner than one fine cell (0.01 m in z).
    EXPECT_NE(error_of({"fluid.refine_min=[5.0, 0.0, 0.3]", "fluid.refine_max=[10.0, 0.05, 0.305]",
                        "fluid.coarse_cell_size=[0.1, 0.0, 0.03]"})
                  .find("fluid.refine_max"),
              std::string::npos);
    // The fine cells themselves: nothing to grade.
    EXPECT_NE(error_of({box_min, box_max, "fluid.coarse_cell_size=[0.05, 0.05, 0.01]"})
                  .find("fluid.coarse_cell_size"),
              std::string::npos);
    EXPECT_NE(error_of({box_min, box_max, "fluid.coarse_cell_size=[-0.1, 0.0, 0.03]"})
                  .find("fluid.coarse_cell_size"),
              std::string::npos);
}

// Box edges 1.1 to 10 fine cells from the flume's ends: too short a stretch
// to grow in joins the box (no cells below h, no jumps above 10 %); longer
// ones grow. The wave_flume scene: 10 x 0.05 x 0.6 m, h = 0.05, 0.05, 0.01 m.
TEST(FlumeMesh, ShortStretchesOutsideTheBoxNeverMakeSmallCellsOrJumps) {
    for (const double edge : {1.1, 1.5, 2.5, 4.0, 7.0, 10.0, 25.0}) {
        const double x0 = edge * 0.05, z0 = edge * 0.01;
        const std::string at = std::to_string(edge) + " cells";
        const armour::Scene scene = armour::load_scene(
            scene_path("wave_flume.toml"),
            {"fluid.refine_min=[" + std::to_string(x0) + ", 0.0, " + std::to_string(z0) + "]",
             "fluid.refine_max=[" + std::to_string(10.0 - x0) + ", 0.05, 0.6]",
             "fluid.coarse_cell_size=[0.1, 0.0, 0.03]"});
        const armour::FlumeMesh mesh = armour::flume_mesh(scene);
        expect_graded(mesh.axes[0], 0.0, 10.0, 0.05, x0, 10.0 - x0, 2.0, "x, edge " + at);
        expect_graded(mesh.axes[2], 0.0, 0.6, 0.01, z0, 0.6, 3.0, "z, edge " + at);
        EXPECT_EQ(mesh.axes[1].cells, 1);
    }
}

// An axis whose coarse size is not above its fine cell stays exactly the
// uniform fluid.cells, wherever the box's faces fall on it.
TEST(FlumeMesh, AnAxisNotCoarsenedKeepsItsUniformCells) {
    const armour::Scene scene = armour::load_scene(
        scene_path("stability_cubes.toml"),
        {"fluid.mesh=graded", "fluid.cells=[200,25,62]", "fluid.refine_min=[1.153, -0.1, 0.18]",
         "fluid.refine_max=[2.0, 0.1, 0.62]", "fluid.coarse_cell_size=[0.05, 0.0, 0.03]"});
    const armour::MeshAxis y = armour::flume_mesh(scene).axes[1];
    ASSERT_EQ(y.cells, 25);
    EXPECT_EQ(y.grading, "1");
    for (int k = 0; k <= 25; ++k)
        EXPECT_NEAR(y.nodes[k], -0.124 + k * 0.248 / 25, 1e-12);
}
