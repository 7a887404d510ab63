// Our LIGGGHTS driver against a bare LIGGGHTS script of the same scene.
//
// Usage
//     bench_dem_overhead [--out] OUT_DIR [seconds]   (run by bench/run_dem_bench.sh)
// For 50, 100 and 200 cubes (20-sphere clumps) falling into a box and
// settling, runs (a) the armour engine, advancing in 0.01 s chunks and
// reading every body's state after each, as `armour run` does, and (b) the
// `liggghts` executable on a plain script made from the same templates in
// liggghts_inputs/ with one `run N`. Both do the same steps with the same
// spheres and contact law. Set-up is excluded from both: the driver's time
// is its time loop, the bare time is LIGGGHTS' "Loop time" of its run.
// Prints both, their ratio, sphere-steps per second, and writes
// OUT_DIR/summary.json.
#include "clump.h"
#include "liggghts_engine.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

using namespace armour;
namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Wall box_floor(double half, double height) {
    Wall w;
    w.name = "box";
    auto quad = [&](Eigen::Vector3d a, Eigen::Vector3d b, Eigen::Vector3d c, Eigen::Vector3d d) {
        const int k = static_cast<int>(w.surface.vertices.size());
        w.surface.vertices.insert(w.surface.vertices.end(), {a, b, c, d});
        w.surface.triangles.push_back({k, k + 1, k + 2});
        w.surface.triangles.push_back({k, k + 2, k + 3});
    };
    const double h = half;
    quad({-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0});
    quad({-h, -h, 0}, {-h, h, 0}, {-h, h, height}, {-h, -h, height});
    quad({h, -h, 0}, {h, -h, height}, {h, h, height}, {h, h, 0});
    quad({-h, -h, 0}, {-h, -h, height}, {h, -h, height}, {h, -h, 0});
    quad({-h, h, 0}, {h, h, 0}, {h, h, height}, {-h, h, height});
    return w;
}

} // namespace

int main(int argc, char **argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (!args.empty() && args[0] == "--out")
        args.erase(args.begin());
    if (args.empty() || args[0].rfind("-", 0) == 0) {
        std::fprintf(stderr, "usage: %s [--out] OUT_DIR [simulated seconds, default 0.5]\n", argv[0]);
        return 1;
    }
    const fs::path out = fs::absolute(args[0]);
    const double duration = args.size() > 1 ? std::atof(args[1].c_str()) : 0.5;
    fs::create_directories(out);
    const Shape cube = make_cube_shape(0.2, 0.0, 2400.0);
    UnitTemplate unit;
    unit.name = "cube";
    unit.mesh = cube.mesh;
    unit.props = cube.props;
    unit.clump = build_clump(cube, ClumpMethod::optimised, 20);

    nlohmann::json rows = nlohmann::json::array();
    std::printf("%6s %8s %12s %12s %8s %16s\n", "units", "steps", "driver[s]", "bare[s]", "ratio",
                "sphere-steps/s");
    for (int units : {50, 100, 200}) {
        const fs::path dir = out / ("units" + std::to_string(units));
        fs::create_directories(dir);
        EngineSettings settings;
        settings.materials = {{"concrete", 5e7, 0.25, 0.5, 0.5, 0.0}};
        // Four layers of cubes on a 0.45 m grid, dropped into a box that fits one layer.
        const int per_side = static_cast<int>(std::ceil(std::sqrt(units / 4.0)));
        const double half = 0.225 * per_side + 0.2;
        settings.domain_min = Eigen::Vector3d(-half - 0.1, -half - 0.1, -0.1);
        settings.domain_max = Eigen::Vector3d(half + 0.1, half + 0.1, 0.4 * units / 16.0 + 1.5);
        settings.work_dir = (dir / "driver").string();
        auto engine = make_liggghts_engine(settings);
        engine->add_template(unit);
        engine->add_wall(box_floor(half, settings.domain_max.z() - 0.05));
        for (int i = 0; i < units; ++i) {
            BodyInit b;
            const int layer = i / (per_side * per_side), in_layer = i % (per_side * per_side);
            b.pose.position =
                Eigen::Vector3d(-half + 0.425 + 0.45 * (in_layer % per_side),
                                -half + 0.425 + 0.45 * (in_layer / per_side), 0.3 + 0.4 * layer);
            engine->add_body(b);
        }
        const double dt = engine->time_step();
        const long steps = std::lround(duration / dt);
        engine->state(0); // set-up (insertion, exact placement) is not timed, as for the bare script
        const auto start = std::chrono::steady_clock::now();
        const double chunk = 0.01;
        double checksum = 0.0;
        while (engine->steps() < steps) {
            engine->advance(std::min(chunk, static_cast<double>(steps - engine->steps()) * dt));
            for (int i = 0; i < engine->body_count(); ++i)
                checksum += engine->state(i).pose.position.z();
        }
        const double driver = seconds_since(start);

        // The bare script: the driver's own set-up script (input.liggghts),
        // gravity as a fix, and one run of the same number of steps.
        std::ifstream setup(fs::path(settings.work_dir) / "input.liggghts");
        std::ostringstream script;
        script << setup.rdbuf() << "fix gravity all gravity 9.81 vector 0 0 -1\n"
               << "run " << steps << "\n";
        std::ofstream(dir / "bare.in") << script.str();
        const std::string command =
            "cd '" + dir.string() + "' && liggghts -in bare.in -screen /dev/null -log bare.log";
        if (std::system(command.c_str()) != 0) {
            std::fprintf(stderr, "bare LIGGGHTS failed (see %s/bare.log)\n", dir.c_str());
            return 2;
        }
        // LIGGGHTS' own loop time of the long run (the last "Loop time" line).
        double bare = 0.0;
        std::ifstream bare_log(dir / "bare.log");
        for (std::string line; std::getline(bare_log, line);)
            if (line.rfind("Loop time of ", 0) == 0)
                bare = std::atof(line.c_str() + 13);
        const double sphere_steps =
            static_cast<double>(units) * static_cast<double>(unit.clump.size()) * static_cast<double>(steps);
        std::printf("%6d %8ld %12.3f %12.3f %8.3f %16.3g\n", units, steps, driver, bare, driver / bare,
                    sphere_steps / driver);
        std::fflush(stdout);
        rows.push_back({{"units", units},
                        {"steps", steps},
                        {"dt", dt},
                        {"driver_seconds", driver},
                        {"bare_seconds", bare},
                        {"ratio", driver / bare},
                        {"sphere_steps_per_second", sphere_steps / driver},
                        {"seconds_per_unit_step", driver / (units * static_cast<double>(steps))},
                        {"checksum_z", checksum}});
    }
    std::ofstream(out / "summary.json")
        << nlohmann::json({{"units", "s, dimensionless ratio"}, {"rows", rows}}).dump(2) << "\n";
    return 0;
}
