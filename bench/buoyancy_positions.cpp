// Buoyancy of a submerged cube against where it sits in the grid: the mask's
// volume sum chi V over the cube's volume, for the former sampled ramp and
// the exact fractions, at 3, 4, 6 and 12 cells across, over random positions
// (axis-aligned) and random positions and orientations. In still water the
// force density is uniform (f = rho |g| z), so the load is rho |g| sum chi V
// and buoyancy_error = sum chi V / a^3 - 1 exactly (the coupled runs check the
// same through interFoam: tests/test_coupled.cpp).
// Usage: bench_buoyancy_positions OUT_DIR [POSES]   writes OUT_DIR/buoyancy_positions.json
#include "coupler.h"
#include "free_body_engine.h"
#include "shapes.h"

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>

using namespace armour;

int main(int argc, char **argv) {
    if (argc < 2 || argc > 3) {
        std::fprintf(stderr, "usage: bench_buoyancy_positions OUT_DIR [POSES]\n");
        return 2;
    }
    const std::string out = argv[1];
    const int poses = argc == 3 ? std::stoi(argv[2]) : 200;
    const double a = 1.0;
    const Shape shape = make_cube_shape(a, 0.0, 2400.0);
    UnitTemplate cube;
    cube.name = "cube";
    cube.mesh = shape.mesh;
    cube.props = shape.props;

    nlohmann::json rows = nlohmann::json::array();
    for (const char *fraction : {"ramp", "exact"})
        for (const bool turned : {false, true})
            for (const double across : {3.0, 4.0, 6.0, 12.0}) {
                const double h = a / across;
                std::mt19937 rng(15);
                std::uniform_real_distribution<double> offset(0.0, 1.0);
                std::normal_distribution<double> normal;
                CellSet cells;
                const int reach = static_cast<int>(std::ceil(across)) + 2;
                for (int i = -reach; i < reach; ++i)
                    for (int j = -reach; j < reach; ++j)
                        for (int k = -reach; k < reach; ++k) {
                            cells.centres.push_back(h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5));
                            cells.volumes.push_back(h * h * h);
                        }
                double sum = 0.0, lo = HUGE_VAL, hi = -HUGE_VAL, seconds = 0.0;
                for (int n = 0; n < poses; ++n) {
                    auto engine = make_free_body_engine(EngineSettings{});
                    engine->add_template(cube);
                    BodyInit body;
                    body.pose.position = Eigen::Vector3d(offset(rng), offset(rng), offset(rng)) * h;
                    if (turned)
                        body.pose.orientation =
                            Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng))
                                .normalized();
                    engine->add_body(body);
                    CouplerSettings settings;
                    settings.fraction =
                        std::string(fraction) == "ramp" ? SolidFraction::sampled_ramp : SolidFraction::exact;
                    Coupler coupler(*engine, {cube}, {0}, settings);
                    coupler.update_mask(cells); // bins
                    const auto t0 = std::chrono::steady_clock::now();
                    const CellMask &mask = coupler.update_mask(cells);
                    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                    double volume = 0.0;
                    for (std::size_t i = 0; i < cells.volumes.size(); ++i)
                        volume += mask.chi[i] * cells.volumes[i];
                    const double error = volume / (a * a * a) - 1.0;
                    sum += error;
                    lo = std::min(lo, error);
                    hi = std::max(hi, error);
                }
                rows.push_back({{"fraction", fraction},
                                {"orientation", turned ? "random" : "aligned"},
                                {"cells_across", across},
                                {"poses", poses},
                                {"mean", sum / poses},
                                {"min", lo},
                                {"max", hi},
                                {"mask_seconds_per_pose", seconds / poses}});
                std::printf("%-5s %-7s %4.0f cells across: buoyancy error mean %+.4f %%, min %+.4f %%, max "
                            "%+.4f %%\n",
                            fraction, turned ? "random" : "aligned", across, 100 * sum / poses, 100 * lo,
                            100 * hi);
            }
    const nlohmann::json result = {{"what", "buoyancy_error = sum chi V / a^3 - 1 of a submerged cube"},
                                   {"rows", rows}};
    std::ofstream(out + "/buoyancy_positions.json") << result.dump(2) << "\n";
    std::ofstream(out + "/summary.json")
        << nlohmann::json{{"bench", "buoyancy_positions"}, {"poses", poses}, {"rows", rows}}.dump(2) << "\n";
    return 0;
}
