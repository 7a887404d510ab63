// Clump error, build cost and the DEM time step each clump allows, against
// sphere count, for both methods.
//
// The time step is the multisphere limit (engines/time_step.h) of one unit
// against a wall of the scenes' softened concrete (E = 5e7 Pa, nu = 0.25,
// e = 0.5) at 1 m/s, next to the smallest-sphere Rayleigh time it replaced.
//
// Usage
//     bench_clump_convergence [--out] OUT_DIR [N,N,...]
// Run by bench/run_clump_bench.sh. Prints a table and writes OUT_DIR/clump_convergence.json (and
// summary.json); bench/plot_clump_convergence.py turns it into OUT_DIR/clump_convergence.png.
#include "clump_evaluator.h"
#include "time_step.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

using namespace armour;

namespace {

TimeStepReport allowed_step(const Shape &shape, const Clump &clump) {
    EngineSettings settings;
    Material concrete;
    concrete.name = "concrete";
    concrete.youngs_modulus = 5e7;
    concrete.poisson_ratio = 0.25;
    concrete.restitution = 0.5;
    settings.materials = {concrete};
    UnitTemplate unit;
    unit.clump = clump;
    unit.props = shape.props;
    return compute_time_step(settings, {unit}, {0});
}

} // namespace

int main(int argc, char **argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (!args.empty() && args[0] == "--out")
        args.erase(args.begin());
    if (args.empty() || args[0].rfind("-", 0) == 0) {
        std::fprintf(stderr, "usage: %s [--out] OUT_DIR [N,N,...]\n", argv[0]);
        return 1;
    }
    const std::filesystem::path out = args[0];
    std::vector<int> counts = {5, 10, 15, 20, 30, 40, 50, 60, 80, 100, 150, 200};
    if (args.size() > 1) {
        counts.clear();
        std::stringstream list(args[1]);
        for (std::string item; std::getline(list, item, ',');)
            counts.push_back(std::stoi(item));
    }
    std::filesystem::create_directories(out);
    const Shape shapes[] = {make_cube_shape(1.0, 0.0, 2400.0),
                            make_dolos_shape(2.0, kDolosWaistDefault, 2400.0)};
    nlohmann::json rows = nlohmann::json::array();
    std::printf("%-6s %-10s %5s %10s %10s %10s %10s %10s %10s %10s %9s\n", "shape", "method", "N", "vol.err%",
                "surfRMS%", "surfMax%", "inertia%", "topple°", "dt[ms]", "rayl.[ms]", "build[s]");
    for (const Shape &shape : shapes)
        for (ClumpMethod method : {ClumpMethod::greedy, ClumpMethod::optimised})
            for (int n : counts) {
                const auto start = std::chrono::steady_clock::now();
                const Clump clump = build_clump(shape, method, n, 1);
                const double seconds =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                const ClumpQuality q = evaluate_clump(shape, clump);
                const TimeStepReport dt = allowed_step(shape, clump);
                std::printf("%-6s %-10s %5d %+10.3f %10.3f %10.3f %10.3f %10.2f %10.3f %10.3f %9.3f\n",
                            shape.kind.c_str(), method_name(method).c_str(), n, 100 * q.volume_error,
                            100 * q.surface_rms, 100 * q.surface_max, 100 * q.inertia_error, q.topple_error_deg,
                            1e3 * dt.limit, 1e3 * dt.rayleigh, seconds);
                std::fflush(stdout);
                rows.push_back({{"shape", shape.kind},
                                {"method", method_name(method)},
                                {"spheres", n},
                                {"volume_error", q.volume_error},
                                {"surface_rms", q.surface_rms},
                                {"surface_max", q.surface_max},
                                {"inertia_error", q.inertia_error},
                                {"topple_error_deg", q.topple_error_deg},
                                {"dt_limit", dt.limit},
                                {"rayleigh_time", dt.rayleigh},
                                {"centroid_offset", q.centroid_offset},
                                {"build_seconds", seconds},
                                {"Dn", q.Dn}});
            }
    const nlohmann::json doc = {
        {"units", "errors as fractions (surface as fraction of Dn), topple_error_deg in degrees, dt_limit "
                  "(multisphere DEM limit, E = 5e7 Pa, 1 m/s) and rayleigh_time (smallest sphere) in s, "
                  "build_seconds in s"},
        {"rows", rows}};
    std::ofstream(out / "clump_convergence.json") << doc.dump(2) << "\n";
    std::ofstream(out / "summary.json") << doc.dump(2) << "\n";
    return 0;
}
