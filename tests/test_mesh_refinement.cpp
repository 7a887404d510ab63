// A refined wave flume (fluid.mesh = "refined", [[refine]] regions;
// fluid_case/mesh_refinement.h): the regions' geometry, the keys' one-line errors,
// and, with Debian's openfoam, the mesh `armour run` makes for the stability
// scene (read back from constant/polyMesh: fine cells about the units, the
// base cells elsewhere, z never split) and a short coupled window on it.
#include "flume_mesh.h"
#include "mesh_refinement.h"
#include "scene_setup.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/wait.h>

namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path &file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The shipped stability scene with its own [[refine]] tables (if any) left
// out and `refine` appended, written to `dir`.
fs::path stability_scene(const fs::path &dir, const std::string &refine) {
    std::istringstream in(read_text(fs::path(ARMOUR_SOURCE_DIR) / "scenes" / "stability_cubes.toml"));
    std::string text, line;
    bool skipping = false;
    while (std::getline(in, line)) {
        if (!line.empty() && line[0] == '[')
            skipping = line.rfind("[[refine]]", 0) == 0;
        if (!skipping)
            text += line + "\n";
    }
    fs::create_directories(dir);
    const fs::path file = dir / "stability_refined.toml";
    std::ofstream(file) << text << "\n" << refine;
    return file;
}

// A band from 1.5 Dn under the slope's face to 4 Dn over it (Dn = 0.04 m).
const std::string kBand = "[[refine]]\nname = \"armour\"\ntype = \"slope_band\"\nwall = \"slope\"\n"
                          "below = 0.06\nabove = 0.16\n";

fs::path temp_dir(const std::string &name) {
    std::string tmpl = (fs::temp_directory_path() / ("armour_test_" + name + "_XXXXXX")).string();
    return mkdtemp(tmpl.data()) ? fs::path(tmpl) : fs::path();
}

std::string error_of(const fs::path &scene, const std::vector<std::string> &sets) {
    try {
        armour::load_scene(scene.string(), sets);
    } catch (const std::exception &e) {
        return e.what();
    }
    return "";
}

} // namespace

// The band follows the slope wall's face and crest (1:1.5 from x = 1.40 m,
// z = 0.20 m to the crest at z = 0.54 m): heights over them along their
// normals, as topoSet selects the cells.
TEST(MeshRefinement, TheSlopeBandHoldsWhatLiesBetweenItsDistancesUnderAndOverTheFaceAndCrest) {
    const fs::path dir = temp_dir("refine_band");
    const armour::Scene scene =
        armour::load_scene(stability_scene(dir, kBand).string(), {"fluid.cells=[200,26,62]"});
    ASSERT_EQ(scene.refine.size(), 1u);
    const armour::SceneRefine &band = scene.refine[0];
    const double s = 1.0 / std::sqrt(1.0 + 1.5 * 1.5), c = 1.5 * s; // the face's normal: (-s, 0, c)
    const Eigen::Vector3d mid(1.40 + 1.5 * 0.17, 0.05, 0.37);       // on the face, half way up
    const Eigen::Vector3d n(-s, 0.0, c);
    for (const double h : {-0.059, -0.03, 0.0, 0.08, 0.159})
        EXPECT_TRUE(armour::in_refine_region(scene, band, mid + h * n, 0.0)) << h;
    for (const double h : {-0.061, -0.2, 0.161, 0.3})
        EXPECT_FALSE(armour::in_refine_region(scene, band, mid + h * n, 0.0)) << h;
    // Over the crest: heights along z; under it, the core keeps coarse cells.
    EXPECT_TRUE(armour::in_refine_region(scene, band, Eigen::Vector3d(1.97, 0.0, 0.60), 0.0));
    EXPECT_FALSE(armour::in_refine_region(scene, band, Eigen::Vector3d(1.97, 0.0, 0.45), 0.0));
    // No lower than `below` under the floor (z = 0.20 m): not the flume's bed in front.
    EXPECT_TRUE(armour::in_refine_region(scene, band, Eigen::Vector3d(1.30, 0.0, 0.21), 0.0));
    EXPECT_FALSE(armour::in_refine_region(scene, band, Eigen::Vector3d(1.30, 0.0, 0.13), 0.0));
    // The base block: the fine cells' x and y doubled (level 1), z as they are.
    const armour::FlumeMesh graded = armour::flume_mesh(armour::load_scene(
        stability_scene(dir, kBand).string(), {"fluid.cells=[200,26,62]", "fluid.mesh=\"graded\""}));
    const armour::FlumeMesh base = armour::flume_mesh(
        armour::load_scene(stability_scene(dir, kBand).string(), {"fluid.cells=[200,26,62]"}));
    EXPECT_EQ(base.axes[1].cells, 13);
    // Whole base cells in the graded box: no larger than twice the fine cell.
    EXPECT_LE(base.axes[0].smallest_cell(), 2.0 * graded.axes[0].smallest_cell() * (1.0 + 1e-9));
    EXPECT_GT(base.axes[0].smallest_cell(), 0.95 * 2.0 * graded.axes[0].smallest_cell());
    EXPECT_EQ(base.axes[2].nodes, graded.axes[2].nodes);
    fs::remove_all(dir);
}

// The shipped scene's regions hold the units its settle piles in front of the
// toe (the settled poses of seeds 2 and 3 of the severe sea at 1540 kg/m^3,
// clumps of 118 spheres: 0.173 and 0.183 m out from the face): the toe box
// holds them where the band alone (4 Dn over the face) would not.
TEST(MeshRefinement, TheShippedRegionsHoldTheUnitsTheSettlePilesInFrontOfTheToe) {
    const armour::Scene scene =
        armour::load_scene((fs::path(ARMOUR_SOURCE_DIR) / "scenes" / "stability_cubes.toml").string(), {});
    ASSERT_EQ(scene.refine.size(), 2u);
    const std::vector<std::pair<Eigen::Vector3d, Eigen::Quaterniond>> piled = {
        {{1.3694419529270465, 0.04964362411495217, 0.34587645466605305},
         {-0.2692252674716125, -0.6904992182713099, -0.3060525178207971, -0.5975453466115348}},
        {{1.2230230025173605, -0.01965991022967483, 0.2627272650723094},
         {0.683129474171701, -0.6088803531878099, -0.26860323323500296, 0.300750960290214}}};
    const double half = 0.02; // m: the 4 cm cube
    for (const auto &[position, orientation] : piled) {
        bool band_alone_holds = true;
        for (int corner = 0; corner < 8; ++corner) {
            const Eigen::Vector3d local((corner & 1 ? half : -half), (corner & 2 ? half : -half),
                                        (corner & 4 ? half : -half));
            const Eigen::Vector3d p = position + orientation.normalized() * local;
            EXPECT_TRUE(armour::in_refine_region(scene, scene.refine[0], p, 0.0) ||
                        armour::in_refine_region(scene, scene.refine[1], p, 0.0))
                << p.transpose();
            band_alone_holds = band_alone_holds && armour::in_refine_region(scene, scene.refine[0], p, 0.0);
        }
        EXPECT_FALSE(band_alone_holds) << position.transpose();
    }
}

// Bad [[refine]] and fluid.mesh keys: one line naming the key, before anything runs.
TEST(MeshRefinement, BadRefineKeysAreRefusedInOneLineNamingTheKey) {
    const fs::path dir = temp_dir("refine_keys");
    const fs::path scene = stability_scene(dir, kBand);
    const std::vector<std::string> cells = {"fluid.cells=[200,26,62]"};
    EXPECT_EQ(error_of(scene, cells), "");
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"refine.0.wall=\"inlet_end\""}, "key 'refine.0.wall'"},
        {{"refine.0.above=0"}, "key 'refine.0.above'"},
        {{"refine.0.below=-0.01"}, "key 'refine.0.below'"},
        {{"refine.0.level=4"}, "key 'refine.0.level'"},
        {{"refine.0.type=\"sphere\""}, "key 'refine.0.type'"},
        {{"refine.0.min=[1.0,-0.1,0.0]"}, "refine.0.min"}, // a box key on a band
        {{"fluid.mesh=\"fine\""}, "key 'fluid.mesh'"},
        // 25 cells across cannot be halved into whole base cells.
        {{"fluid.cells=[200,25,62]"}, "key 'fluid.cells'"},
        {{"fluid.cells=[200,26,62]", "refine.0.level=2"}, "key 'fluid.cells'"},
    };
    for (const auto &[given, key] : cases) {
        std::vector<std::string> sets = cells;
        sets.insert(sets.end(), given.begin(), given.end()); // a later --set wins
        const std::string e = error_of(scene, sets);
        EXPECT_NE(e.find(key), std::string::npos) << given[0] << ": " << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
    // A box must lie in the flume; a refined mesh needs regions.
    const fs::path box =
        stability_scene(dir / "box", "[[refine]]\nname = \"front\"\nmin = [1.0, -0.124, 0.0]\n"
                                     "max = [2.5, 0.124, 0.62]\n");
    EXPECT_NE(error_of(box, cells).find("key 'refine.0.max'"), std::string::npos) << error_of(box, cells);
    const fs::path none = stability_scene(dir / "none", "");
    EXPECT_NE(error_of(none, {"fluid.mesh=\"refined\""}).find("key 'fluid.mesh'"), std::string::npos);
    EXPECT_EQ(error_of(none, {"fluid.mesh=\"graded\""}), "");
    // The graded reference ignores the regions: any cells go.
    EXPECT_EQ(error_of(scene, {"fluid.cells=[200,25,62]", "fluid.mesh=\"graded\""}), "");
    fs::remove_all(dir);
}

#ifdef ARMOUR_EXE
namespace {

// An OpenFOAM ascii list file of constant/polyMesh: its entries' texts.
std::vector<std::string> foam_list(const fs::path &file) {
    const std::string text = read_text(file);
    const std::smatch m = [&] {
        std::smatch found;
        std::regex_search(text, found, std::regex(R"(\n(\d+)\s*\n\()"));
        return found;
    }();
    const std::size_t n = std::stoul(m[1]);
    std::vector<std::string> items;
    std::size_t at = m.position(0) + m.length(0);
    while (items.size() < n) {
        while (std::isspace(static_cast<unsigned char>(text[at])))
            ++at;
        std::size_t end = at;
        if (text[at] == '(' || std::isdigit(static_cast<unsigned char>(text[at]))) {
            const std::size_t open = text.find_first_of("(\n ", at);
            end = text[open] == '(' ? text.find(')', open) + 1 : open;
        }
        items.push_back(text.substr(at, end - at));
        at = end;
    }
    return items;
}

// Each cell's bounding box, from the mesh's points and faces.
struct CellBox {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -Eigen::Vector3d::Constant(HUGE_VAL);
};

std::vector<CellBox> cell_boxes(const fs::path &mesh) {
    std::vector<Eigen::Vector3d> points;
    for (const std::string &p : foam_list(mesh / "points")) {
        std::istringstream s(p.substr(1));
        Eigen::Vector3d x;
        s >> x.x() >> x.y() >> x.z();
        points.push_back(x);
    }
    std::vector<std::vector<int>> faces;
    for (const std::string &f : foam_list(mesh / "faces")) {
        std::istringstream s(f.substr(f.find('(') + 1));
        faces.emplace_back();
        for (int i; s >> i;)
            faces.back().push_back(i);
    }
    std::vector<int> owner, neighbour;
    for (const std::string &o : foam_list(mesh / "owner"))
        owner.push_back(std::stoi(o));
    for (const std::string &o : foam_list(mesh / "neighbour"))
        neighbour.push_back(std::stoi(o));
    std::vector<CellBox> boxes(*std::max_element(owner.begin(), owner.end()) + 1);
    auto grow = [&](int cell, int face) {
        for (int p : faces[face]) {
            boxes[cell].lo = boxes[cell].lo.cwiseMin(points[p]);
            boxes[cell].hi = boxes[cell].hi.cwiseMax(points[p]);
        }
    };
    for (std::size_t f = 0; f < owner.size(); ++f)
        grow(owner[f], static_cast<int>(f));
    for (std::size_t f = 0; f < neighbour.size(); ++f)
        grow(neighbour[f], static_cast<int>(f));
    return boxes;
}

} // namespace

// The stability scene CI-sized (45 cubes on the grid, no settle) at Dn/2 in
// the band (fluid.cells [100, 12, 31]: base cells of one Dn in x and y):
// through `armour run`, a 0.1 s coupled window; then its mesh read back.
TEST(MeshRefinement, StabilitySceneRefinedAboutItsUnitsOnlyAndCoupledRunsOnIt) {
    const fs::path dir = temp_dir("refine_run");
    const fs::path scene = stability_scene(dir, kBand), out = dir / "out";
    const std::string sets =
        "--set pattern.0.rows=5 --set pattern.0.placement='\"grid\"' --set fluid.settle_time=0 "
        "--set fluid.settle_stages=1 "
        "--set 'fluid.cells=[100,12,31]' --set fluid.penalty=200 --set run.duration=0.1 "
        "--set run.output_interval=0.05 --set run.checkpoint_interval=0 "
        "--set fluid.write_interval=0.1";
    const std::string cmd = "'" + std::string(ARMOUR_EXE) + "' run '" + scene.string() + "' --out '" +
                            out.string() + "' " + sets + " > '" + (dir / "run.log").string() + "' 2>&1";
    const int rc = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 0) << read_text(dir / "run.log");
    std::ifstream summary_file(out / "summary.json");
    const nlohmann::json summary = nlohmann::json::parse(summary_file);
    EXPECT_EQ(summary["units"], 45);
    EXPECT_GE(summary["simulated_seconds"].get<double>(), 0.1 - 1e-9);
    EXPECT_EQ(summary["fluid"]["mesh"], "refined");
    EXPECT_EQ(summary["fluid"]["refine_levels"], 1);

    const armour::Scene s = armour::load_scene((out / "scene.resolved.toml").string());
    const armour::SceneSetup setup = armour::build_scene(s, (dir / "cache").string(), false);
    const armour::FlumeMesh base = armour::flume_mesh(s);
    const Eigen::Vector3d fine = armour::fine_cell_size(s); // 0.02 x 0.0207 x 0.02 m
    const std::vector<CellBox> boxes = cell_boxes(out / "case" / "constant" / "polyMesh");
    EXPECT_EQ(static_cast<long>(boxes.size()), summary["fluid"]["cells_total"].get<long>());
    // Fewer cells than the block at the fine cells would hold, more than the base block.
    EXPECT_GT(static_cast<long>(boxes.size()), base.cells());
    EXPECT_LT(static_cast<long>(boxes.size()), base.cells() * 4 * 6 / 10);
    const std::vector<double> &z_nodes = base.axes[2].nodes;
    int fine_cells = 0, coarse_cells = 0, unit_cells = 0;
    for (const CellBox &b : boxes) {
        const Eigen::Vector3d size = b.hi - b.lo, centre = 0.5 * (b.lo + b.hi);
        // z never split: every cell spans one of the block's z layers.
        const auto z0 = std::lower_bound(z_nodes.begin(), z_nodes.end(), b.lo.z() - 1e-6);
        ASSERT_TRUE(z0 + 1 != z_nodes.end());
        EXPECT_NEAR(*z0, b.lo.z(), 1e-6); // ascii points: 8 digits
        EXPECT_NEAR(*(z0 + 1), b.hi.z(), 1e-6);
        const bool is_fine = size.y() < 0.75 * 2.0 * fine.y();
        fine_cells += is_fine;
        // Every cell a unit reaches at its start (its bounding sphere) is fine in x and y.
        bool touches_unit = false;
        for (const armour::BodyInit &body : setup.bodies) {
            const Eigen::Vector3d nearest = body.pose.position.cwiseMax(b.lo).cwiseMin(b.hi);
            touches_unit =
                touches_unit || (nearest - body.pose.position).norm() < 0.5 * std::sqrt(3.0) * 0.04;
        }
        if (touches_unit) {
            ++unit_cells;
            // x: whole base cells fill the graded box, each at most twice the fine cell.
            EXPECT_LE(size.x(), fine.x() + 1e-6) << centre.transpose();
            EXPECT_GT(size.x(), 0.9 * fine.x()) << centre.transpose();
            EXPECT_NEAR(size.y(), fine.y(), 1e-6) << centre.transpose();
        }
        // In front of the band (x < 1.0 m) and deep in the core, the base cells.
        const bool core = std::none_of(s.refine.begin(), s.refine.end(), [&](const armour::SceneRefine &r) {
            return armour::in_refine_region(s, r, centre, 2.0 * fine.maxCoeff());
        });
        if (centre.x() < 1.0 || core) {
            ++coarse_cells;
            EXPECT_GT(size.x(), 1.8 * fine.x()) << centre.transpose();
            EXPECT_NEAR(size.y(), 2.0 * fine.y(), 1e-6) << centre.transpose();
        }
    }
    EXPECT_GT(unit_cells, 45 * 8);
    EXPECT_GT(fine_cells, 4 * unit_cells / 2);
    EXPECT_GT(coarse_cells, static_cast<int>(boxes.size()) / 4);
    if (!HasFailure())
        fs::remove_all(dir);
}

// A band too thin for the units: refused before anything runs, one line that
// names every region of the finest level (here a box in front of the toe too).
TEST(MeshRefinement, UnitsOutsideTheFinestRegionsAreRefusedBeforeAnythingRuns) {
    const fs::path dir = temp_dir("refine_outside");
    const std::string toe = "[[refine]]\nname = \"toe\"\ntype = \"box\"\nmin = [1.15, -0.124, 0.18]\n"
                            "max = [1.25, 0.124, 0.40]\n"; // in front of every unit
    const fs::path scene = stability_scene(dir, kBand + toe), out = dir / "out";
    const std::string cmd =
        "'" + std::string(ARMOUR_EXE) + "' run '" + scene.string() + "' --out '" + out.string() +
        "' --set pattern.0.rows=5 --set pattern.0.placement='\"grid\"' "
        "--set fluid.settle_time=0 --set fluid.settle_stages=1 --set 'fluid.cells=[100,12,31]' "
        "--set refine.0.above=0.02 "
        "> '" +
        (dir / "run.log").string() + "' 2>&1";
    const int rc = std::system(cmd.c_str());
    const std::string log = read_text(dir / "run.log");
    EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 2) << log;
    EXPECT_NE(log.find("armour: error: "), std::string::npos) << log;
    EXPECT_NE(log.find("key 'refine.0.above': body 0 (unit 'cube') starts outside every region of level 1 "
                       "(refine.0 'armour', refine.1 'toe') with its vertex ["),
              std::string::npos)
        << log;
    // One error line (a warning on the unused settle friction may precede it).
    std::size_t errors = 0;
    for (std::size_t at = log.find("armour: error: "); at != std::string::npos;
         at = log.find("armour: error: ", at + 1))
        ++errors;
    EXPECT_EQ(errors, 1u) << log;
    EXPECT_EQ(log.find('\n', log.find("armour: error: ")), log.size() - 1) << log;
    EXPECT_FALSE(fs::exists(out));
    if (!HasFailure())
        fs::remove_all(dir);
}
#endif
