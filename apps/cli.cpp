#include "cli.h"

#include "cli_checks.h"
#include "clump_command.h"
#include "compare_command.h"
#include "engine_registry.h"
#include "input_error.h"
#include "report_command.h"
#include "run_command.h"
#include "scene_keys.h"
#include "sweep_command.h"

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <exception>
#include <iostream>

namespace armour {

// The output-folder rule (output_folder.h, docs/outputs.md), the same for every command.
const char *const kOutHelp = "Output folder: new, empty, or an earlier result of the same command (whose "
                             "files alone are replaced); any other folder is refused";
const char *const kCacheHelp = "Clump cache folder (default $ARMOUR_CACHE or ~/.cache/armour-fsi)";

namespace {

// --tol-volume, --tol-surface, --tol-topple of `clump` and `demo`: the same
// words and ranges, checked by check_tolerances (clump_evaluator.h).
std::vector<CLI::Option *> add_tolerance_options(CLI::App &cmd, const std::string &prefix, double &volume,
                                                 double &surface, double &topple) {
    return {cmd.add_option("--tol-volume", volume, prefix + "max |volume error| as a fraction, in (0, 1) [-]")
                ->capture_default_str(),
            cmd.add_option("--tol-surface", surface,
                           prefix + "max surface RMS deviation as a fraction of Dn, in (0, 1) [-]")
                ->capture_default_str(),
            cmd.add_option("--tol-topple", topple,
                           prefix + "max error of the topple angle about any edge of any face the unit rests "
                                    "on, in (0, 90) [deg]")
                ->capture_default_str()};
}

CLI::App *add_clump_command(CLI::App &app, ClumpRequest &clump) {
    CLI::App *clump_cmd = app.add_subcommand(
        "clump",
        "Build a sphere clump of a cube, a dolos or a closed STL, measure its error against the exact "
        "shape and write LIGGGHTS files. Without --spheres, picks the fewest spheres meeting "
        "--tol-volume, --tol-surface and --tol-topple.");
    auto *shape_opt = clump_cmd->add_option("--shape", clump.shape, "Built-in unit: cube or dolos");
    auto *stl_opt =
        clump_cmd->add_option("--stl", clump.stl, "Closed triangle mesh (ASCII or binary STL, m)");
    shape_opt->excludes(stl_opt);
    auto *size_opt = clump_cmd->add_option("--size", clump.size, "Cube edge length [m]");
    auto *chamfer_opt = clump_cmd->add_option("--chamfer", clump.chamfer,
                                              "Cube edge chamfer, cut into each face [m] (default 0)");
    auto *height_opt = clump_cmd->add_option("--height", clump.height, "Dolos overall height H [m]");
    auto *waist_opt =
        clump_cmd->add_option("--waist", clump.waist, "Dolos waist ratio: shank thickness / H [-], 0.25-0.50")
            ->capture_default_str();
    for (CLI::Option *dimension : {size_opt, chamfer_opt, height_opt, waist_opt})
        stl_opt->excludes(dimension); // a mesh brings its own size
    auto *spheres_opt = clump_cmd->add_option("--spheres", clump.spheres,
                                              "Number of spheres N (>= 1); omit for tolerance mode");
    const std::vector<CLI::Option *> tolerances = add_tolerance_options(
        *clump_cmd, "Tolerance mode: ", clump.tol_volume, clump.tol_surface, clump.tol_topple);
    for (CLI::Option *tolerance : tolerances)
        spheres_opt->excludes(tolerance);
    clump_cmd
        ->add_option("--edge-spheres", clump.edge_spheres,
                     "Support spheres along every edge of the faces the unit rests on, besides the corner "
                     "ones, out of --spheres (optimised and inscribed): a unit resting on this one pivots at "
                     "its edge (default 0)")
        ->needs(spheres_opt);
    clump_cmd->add_option("--max-spheres", clump.max_spheres, "Tolerance mode: largest N to try")
        ->capture_default_str();
    clump_cmd
        ->add_option("--method", clump.method,
                     "Clump method: greedy (baseline), optimised, or inscribed (optimised, every sphere "
                     "inside the exact shape)")
        ->capture_default_str();
    clump_cmd->add_option("--density", clump.density, "Unit density [kg/m^3]")->capture_default_str();
    clump_cmd->add_option("--seed", clump.seed, "Random seed (results are deterministic per seed)")
        ->capture_default_str();
    clump_cmd->add_option("--out", clump.out, kOutHelp)->required();
    return clump_cmd;
}

CLI::App *add_demo_command(CLI::App &app, DemoRequest &demo) {
    CLI::App *demo_cmd = app.add_subcommand(
        "demo",
        "Default job: clumps of a 1 m cube and a 2 m dolos (2400 kg/m^3) with the fewest spheres meeting "
        "the tolerances, both methods, and their error table.");
    demo_cmd->add_option("--out", demo.out, kOutHelp)->capture_default_str();
    add_tolerance_options(*demo_cmd, "", demo.tol_volume, demo.tol_surface, demo.tol_topple);
    return demo_cmd;
}

// `run_engine`: --engine, the same as --set run.engine=NAME.
CLI::App *add_run_command(CLI::App &app, RunRequest &run, std::string &run_engine) {
    CLI::App *run_cmd = app.add_subcommand(
        "run",
        "Run a scene file (TOML, SI units; see docs/scenes.md) with the DEM engine, or coupled with "
        "interFoam "
        "when it has [fluid]: writes summary.json, bodies.h5 (+ bodies.xdmf for ParaView) and the resolved "
        "scene to --out (and the OpenFOAM case to --out/case).");
    run_cmd->add_option("scene", run.scene, "Scene file (.toml)")->required();
    run_cmd->add_option("--out", run.out, kOutHelp)->required();
    run_cmd->add_option(
        "--set", run.overrides,
        "Override a scene key: KEY=VALUE, the value in TOML syntax, a string key's also as a bare word "
        "(docs/scenes.md): --set run.duration=0.5 --set unit.0.spheres=20 --set waves.type=irregular");
    run_cmd->add_option("--cache", run.cache, kCacheHelp);
    run_cmd
        ->add_option("--np", run.np,
                     "Scenes with [fluid]: MPI ranks of interFoam (overrides fluid.np; every rank runs "
                     "the engine)")
        ->check(integer_at_least(1));
    run_cmd->add_option("--engine", run_engine,
                        "Engine, same as --set run.engine=NAME (`armour engines` lists them)");
    run_cmd->add_flag("--resume", run.resume,
                      "Continue the run in --out from its last checkpoint (run.checkpoint_interval, s of "
                      "simulated time); only run.duration, run.checkpoint_interval, fluid.write_interval and "
                      "the Courant limits may differ; on the run's ranks unless --np gives others (the "
                      "fields are split anew); a run that settled first is not settled again "
                      "(docs/checkpoints.md)");
    run_cmd->add_flag("--restart", run.restart,
                      "Start again in an --out that holds a run stopped before its end (its checkpoints "
                      "are replaced); without --resume or --restart such a folder is refused");
    run_cmd->add_flag("--dry-run", run.dry_run,
                      "Check everything the run checks before it starts (scene, --set, units, engine, fluid "
                      "case and tools, --out, --resume) and print its plan; write nothing to --out");
    run_cmd->add_flag(
        "--settle-only", run.settle_only,
        "Scenes that settle their units first (fluid.settle_time > 0 s): settle them and stop, "
        "without the fluid case: --out/settle/scene.settled.toml (the layer; `armour run` runs "
        "the waves on it) and summary.json with the layer's packing (units per Dn^2), porosity, "
        "thickness (m) and k_t against the Rock Manual's band, and the units seaward of the "
        "face's foot (docs/stability.md)");
    return run_cmd;
}

CLI::App *add_report_command(CLI::App &app, ReportRequest &report) {
    CLI::App *report_cmd = app.add_subcommand(
        "report",
        "Analyse an `armour run` folder of a scene with [fluid] as it stands (ended, stopped, killed or "
        "still running), up to its last recorded step or --until: the scene's analysis (damage: N_od "
        "against Van der Meer at the waves so far) and the incident-wave figures, as the run writes them "
        "at its end (SI units); writes summary.json and the analysis' files to --out and only reads the "
        "run (docs/analysis.md).");
    report_cmd->add_option("run", report.run, "The run's folder (its --out)")->required();
    report_cmd->add_option("--out", report.out, kOutHelp)->required();
    report_cmd->add_option("--until", report.until, "Use the record up to this simulated time [s]")
        ->check(number_above(0.0, "s"));
    report_cmd->add_option(
        "--from", report.from,
        "Measure the damage from the units' poses at this simulated time [s] (the layer as "
        "the waves find it; at most when the wave train's front reaches the toe)");
    report_cmd->add_option("--cache", report.cache, kCacheHelp);
    return report_cmd;
}

CLI::App *add_compare_command(CLI::App &app, CompareRequest &compare) {
    CLI::App *compare_cmd = app.add_subcommand(
        "compare",
        "Run a scene with sphere clumps of several sizes and with exact convex hulls (Bullet), sweep "
        "the time step past the stability limit, and write summary.json, pareto.png, stability_dt.png, "
        "bumpiness.png and report.md to --out.");
    compare_cmd->add_option("scene", compare.scene, "Scene file (.toml)")->required();
    compare_cmd->add_option("--out", compare.out, kOutHelp)->required();
    compare_cmd
        ->add_option("--spheres", compare.spheres,
                     "Sphere counts per unit, each >= 2 (LIGGGHTS multisphere), e.g. 5,10,20,50,100")
        ->delimiter(',')
        ->capture_default_str();
    compare_cmd
        ->add_option("--seeds", compare.seeds,
                     "Seeds of the random placement (default 1,2,3 for scenes with [[drop]], else 1)")
        ->delimiter(',');
    compare_cmd
        ->add_option("--dt-factors", compare.dt_factors,
                     "Time steps to sweep, as multiples of each engine's stability limit, each > 0 [-]")
        ->delimiter(',')
        ->capture_default_str();
    compare_cmd
        ->add_option("--dt-sweep-spheres", compare.dt_sweep_spheres,
                     "Spheres per unit in the dt sweep, >= 2 (0: the --spheres count nearest 20)")
        ->capture_default_str();
    compare_cmd->add_option(
        "--tolerance", compare.tolerance,
        "Advice tolerances per headline figure, KEY=VALUE,... in the figure's own unit, e.g. "
        "slide_angle_deg=0.5,packing_density=0.05 (defaults: docs/comparison.md)");
    compare_cmd
        ->add_option("--blow-up-gain", compare.blow_up_gain,
                     "Energy gain (E_max - E_0) / sum(m g Dn) above which a run counts as blown up, > 0 [-]")
        ->capture_default_str();
    compare_cmd->add_option("--set", compare.overrides,
                            "Override a scene key for every run, as `armour run --set`");
    compare_cmd->add_option("--cache", compare.cache, kCacheHelp);
    compare_cmd->add_flag(
        "--dry-run", compare.dry_run,
        "Check the scene, the options and --out, list the runs; run nothing, write nothing");
    return compare_cmd;
}

} // namespace

int armour_main(int argc, const char *const *argv) {
    CLI::App app{"armour-fsi: breakwater armour units as sphere clumps, DEM and coupled with waves.\n"
                 "All quantities are SI: m, kg, s, N; densities in kg/m^3."};
    app.require_subcommand(1);

    ClumpRequest clump;
    CLI::App *clump_cmd = add_clump_command(app, clump);
    DemoRequest demo;
    CLI::App *demo_cmd = add_demo_command(app, demo);
    RunRequest run;
    std::string run_engine;
    CLI::App *run_cmd = add_run_command(app, run, run_engine);
    ReportRequest report;
    CLI::App *report_cmd = add_report_command(app, report);
    CLI::App *engines_cmd = app.add_subcommand(
        "engines", "List the rigid-body engines of this build, one per line, with their capabilities.");
    CompareRequest compare;
    CLI::App *compare_cmd = add_compare_command(app, compare);
    SweepRequest sweep;
    CLI::App *sweep_cmd = add_sweep_command(app, sweep);

    add_type_checks(app); // after the options' own checks, which check the type too
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        return parse_error_exit(app, e);
    }
    try {
        if (clump_cmd->parsed()) {
            clump.fixed_count = clump_cmd->get_option("--spheres")->count() > 0;
            clump.waist_given = clump_cmd->get_option("--waist")->count() > 0;
            return run_clump(clump);
        }
        if (demo_cmd->parsed())
            return run_demo(demo);
        if (run_cmd->parsed()) {
            if (!run_engine.empty())
                run.overrides.push_back("run.engine=" + toml_string(run_engine));
            return run_scene(run);
        }
        if (report_cmd->parsed())
            return run_report(report);
        if (compare_cmd->parsed())
            return run_compare(compare);
        if (sweep_cmd->parsed())
            return run_sweep(sweep);
        if (engines_cmd->parsed()) {
            std::cout << describe_engine_styles();
            return 0;
        }
    } catch (const InputError &e) {
        std::cerr << "armour: error: " << e.what() << '\n';
        return 2;
    } catch (const std::exception &e) {
        std::cerr << "armour: internal error: " << e.what() << '\n';
        return 4;
    }
    return 1;
}

} // namespace armour
