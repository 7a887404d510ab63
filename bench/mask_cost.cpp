// The wall time of one mask update (Coupler::update_mask), for the cases the
// tests check by counts (tests/test_solid_fraction.cpp HundredCubesMaskCost,
// tests/test_coupler.cpp Mask.FastForManyCellsAndUnits):
//   tank:  the mesh and units of scenes/bench_tank_cubes.toml (25^3 cells of
//          4 cm, 100 cubes a = 0.1 m 0.2 m apart at random orientations),
//          the former ramp and the exact fractions, at rest and moving
//          (every unit falls freely for 1 ms between updates);
//   many:  100 tilted cubes a = 1 m on a 10 x 10 grid in 1e5 cells, ramp.
// Each row: the mean over REPEATS updates after a first one (bins built).
// Usage: bench_mask_cost OUT_DIR [REPEATS]   writes OUT_DIR/mask_cost.json
#include "coupler.h"
#include "free_body_engine.h"
#include "shapes.h"

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

using namespace armour;

namespace {

UnitTemplate cube_unit(double a) {
    const Shape shape = make_cube_shape(a, 0.0, 2400.0);
    UnitTemplate unit;
    unit.name = "cube";
    unit.mesh = shape.mesh;
    unit.props = shape.props;
    return unit;
}

CellSet uniform_cells(const Eigen::Vector3d &lo, const std::array<int, 3> &n, double h) {
    CellSet cells;
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i) {
                cells.centres.push_back(lo + h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5));
                cells.volumes.push_back(h * h * h);
            }
    return cells;
}

// Mean seconds of one update over `repeats` (the engine advanced 1 ms
// before each when `moving`), and the work of the last.
nlohmann::json time_updates(RigidBodyEngine &engine, const UnitTemplate &unit, const CellSet &cells,
                            SolidFraction fraction, bool moving, int repeats) {
    CouplerSettings settings;
    settings.fraction = fraction;
    Coupler coupler(engine, {unit}, std::vector<int>(static_cast<std::size_t>(engine.body_count()), 0),
                    settings);
    coupler.update_mask(cells); // bins built once
    double seconds = 0.0;
    for (int n = 0; n < repeats; ++n) {
        if (moving)
            engine.advance(1e-3);
        const auto t0 = std::chrono::steady_clock::now();
        coupler.update_mask(cells);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    const Coupler::MaskWork &w = coupler.last_mask_work();
    return {{"fraction", fraction == SolidFraction::exact ? "exact" : "ramp"},
            {"moving", moving},
            {"cells", cells.volumes.size()},
            {"bodies", engine.body_count()},
            {"seconds_per_update", seconds / repeats},
            {"last_bodies_recomputed", w.bodies_recomputed},
            {"last_cells_visited", w.cells_visited},
            {"last_cells_resolved", w.cells_resolved}};
}

} // namespace

int main(int argc, char **argv) {
    if (argc < 2 || argc > 3) {
        std::fprintf(stderr, "usage: bench_mask_cost OUT_DIR [REPEATS]\n");
        return 2;
    }
    const std::string out = argv[1];
    const int repeats = argc == 3 ? std::stoi(argv[2]) : 20;
    nlohmann::json rows = nlohmann::json::array();

    const UnitTemplate small = cube_unit(0.1);
    const CellSet tank = uniform_cells(Eigen::Vector3d::Zero(), {25, 25, 25}, 0.04);
    for (const bool moving : {false, true})
        for (const SolidFraction fraction : {SolidFraction::sampled_ramp, SolidFraction::exact}) {
            // The same poses for every row (seeded), as in the test.
            auto engine = make_free_body_engine(EngineSettings{});
            engine->add_template(small);
            std::mt19937 rng(7);
            std::uniform_real_distribution<double> shift(-0.01, 0.01);
            std::normal_distribution<double> normal;
            for (int i = 0; i < 100; ++i) {
                BodyInit b;
                b.pose.position =
                    Eigen::Vector3d(0.1 + 0.2 * (i % 5) + shift(rng), 0.1 + 0.2 * (i / 5 % 5) + shift(rng),
                                    0.1 + 0.2 * (i / 25) + shift(rng));
                b.pose.orientation =
                    Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
                engine->add_body(b);
            }
            nlohmann::json row = time_updates(*engine, small, tank, fraction, moving, repeats);
            row["case"] = "tank";
            rows.push_back(row);
        }

    const UnitTemplate large = cube_unit(1.0);
    auto engine = make_free_body_engine(EngineSettings{});
    engine->add_template(large);
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) {
            BodyInit b;
            b.pose.position = Eigen::Vector3d(2.0 * i + 1.0, 2.0 * j + 1.0, 0.0);
            b.pose.orientation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
            engine->add_body(b);
        }
    const double h = std::cbrt(20.0 * 20.0 * 3.0 / 1e5);
    const std::array<int, 3> n = {static_cast<int>(std::ceil(20.0 / h)),
                                  static_cast<int>(std::ceil(20.0 / h)),
                                  static_cast<int>(std::ceil(3.0 / h))};
    nlohmann::json row = time_updates(*engine, large, uniform_cells(Eigen::Vector3d(0, 0, -1.5), n, h),
                                      SolidFraction::sampled_ramp, false, repeats);
    row["case"] = "many";
    rows.push_back(row);

    std::printf("%-5s %-5s %-7s %7s %7s %14s\n", "case", "mask", "units", "cells", "bodies", "ms per update");
    for (const auto &r : rows)
        std::printf("%-5s %-5s %-7s %7zu %7d %14.3f\n", r["case"].get<std::string>().c_str(),
                    r["fraction"].get<std::string>().c_str(), r["moving"].get<bool>() ? "moving" : "at rest",
                    r["cells"].get<std::size_t>(), r["bodies"].get<int>(),
                    1e3 * r["seconds_per_update"].get<double>());
    std::ofstream(out + "/mask_cost.json")
        << nlohmann::json{{"repeats", repeats}, {"rows", rows}}.dump(2) << "\n";
    return 0;
}
