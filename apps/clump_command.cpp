#include "clump_command.h"

#include "clump_evaluator.h"
#include "clump_io.h"
#include "output_folder.h"
#include "stl_io.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace armour {

namespace {

using nlohmann::json;

std::string number(double value) {
    std::ostringstream s;
    s << value;
    return s.str();
}

Shape make_requested_shape(const ClumpRequest &r) {
    if (!r.stl.empty())
        return make_stl_shape(r.stl, r.density);
    if (r.shape == "cube") {
        if (r.height != 0.0)
            throw InputError("--height: applies to --shape dolos, not cube (use --size)");
        if (r.waist_given)
            throw InputError("--waist: applies to --shape dolos, not cube");
        return make_cube_shape(r.size, r.chamfer, r.density);
    }
    if (r.shape == "dolos") {
        if (r.size != 0.0 || r.chamfer != 0.0)
            throw InputError("--size/--chamfer: apply to --shape cube, not dolos (use --height)");
        return make_dolos_shape(r.height, r.waist, r.density);
    }
    if (r.shape.empty())
        throw InputError("--shape: give --shape cube|dolos or --stl FILE");
    throw InputError("--shape: unknown shape '" + r.shape + "' (known: cube, dolos; or use --stl FILE)");
}

json deviation_json(const SurfaceDeviation &d) {
    return {{"mean", d.mean}, {"rms", d.rms}, {"max", d.max}};
}

json quality_json(const ClumpQuality &q) {
    return {
        {"spheres", q.spheres},
        {"volume_error", q.volume_error},
        {"surface_rms", q.surface_rms},
        {"surface_max", q.surface_max},
        {"inertia_error", q.inertia_error},
        {"centroid_offset", q.centroid_offset},
        {"rest_gap", std::isfinite(q.rest_gap) ? json(q.rest_gap) : json(nullptr)}, // null: stands on no face
        {"rest_faces", q.rest_faces},
        {"tipping_faces", q.tipping_faces},
        {"topple_error_deg", q.topple_error_deg},
        {"build_seconds", q.build_seconds}};
}

json matrix_json(const Eigen::Matrix3d &m) {
    return json::array(
        {{m(0, 0), m(0, 1), m(0, 2)}, {m(1, 0), m(1, 1), m(1, 2)}, {m(2, 0), m(2, 1), m(2, 2)}});
}

// Where a file of the result is written, by its name.
using FilePlace = std::function<std::filesystem::path(const std::string &)>;

// Writes the clump's files (at `place(name)`, to end up in `final_dir`) and returns its summary.
json write_clump_files(const FilePlace &place, const std::filesystem::path &final_dir, const Shape &shape,
                       const Clump &clump, const ClumpQuality &q, const std::string &method,
                       std::uint64_t seed) {
    write_sphere_file(clump, place("clump.spheres").string(),
                      shape.description + ", " + std::to_string(clump.size()) + " spheres, method " + method);
    write_text_file(place("template.liggghts"),
                    liggghts_template_snippet(shape, clump, (final_dir / "clump.spheres").string()));
    write_stl(shape.mesh, place("shape.stl").string(), true, "exact " + shape.description);
    write_stl(clump_surface_mesh(clump), place("clump.stl").string(), true, "clump " + shape.description);
    const MassProperties &p = shape.props;
    json s = quality_json(q);
    s["method"] = method;
    s["seed"] = seed;
    s["shape"] = shape.kind;
    s["description"] = shape.description;
    s["Dn"] = q.Dn;
    s["volume_exact"] = q.volume_exact;
    s["volume_clump"] = q.volume_clump;
    s["surface_exact_to_clump"] = deviation_json(q.exact_to_clump);
    s["surface_clump_to_exact"] = deviation_json(q.clump_to_exact);
    s["density"] = p.density;
    s["mass"] = p.mass;
    s["inertia_tensor"] = matrix_json(p.inertia);
    s["principal_moments"] = {p.principal_moments[0], p.principal_moments[1], p.principal_moments[2]};
    s["principal_axes"] = matrix_json(p.principal_axes);
    s["units"] = {{"length", "m"},
                  {"volume", "m^3"},
                  {"mass", "kg"},
                  {"density", "kg/m^3"},
                  {"inertia", "kg m^2 (about the centroid, unit frame)"},
                  {"time", "s"},
                  {"volume_error", "fraction, signed (clump - exact) / exact"},
                  {"inertia_error", "fraction, max over exact principal axes"},
                  {"surface_and_centroid", "fractions of Dn"},
                  {"rest_gap", "fraction of Dn (null: the clump stands on none of the faces)"},
                  {"topple_error_deg", "degrees, largest |clump - exact| topple angle over resting faces and "
                                       "their edges"}};
    s["files"] = {{"spheres", "clump.spheres"},
                  {"liggghts_template", "template.liggghts"},
                  {"exact_shape", "shape.stl"},
                  {"clump_surface", "clump.stl"}};
    return s;
}

void print_progress(const std::string &label, const ClumpQuality &q) {
    std::fprintf(
        stderr,
        "  %s N=%-4d volume error %+7.3f %%  surface RMS %6.3f %% Dn  topple error %5.2f deg  (%.2f s)\n",
        label.c_str(), q.spheres, 100.0 * q.volume_error, 100.0 * q.surface_rms, q.topple_error_deg,
        q.build_seconds);
}

struct Built {
    Clump clump;
    ClumpQuality quality;
    json tolerance; // null for a fixed sphere count
};

// A fixed sphere count when `spheres` > 0, else the tolerance search.
Built build_requested(const Shape &shape, ClumpMethod method, int spheres, const ClumpTolerances &tol,
                      int max_spheres, std::uint64_t seed, const std::string &label, int edge_spheres = 0) {
    Built b;
    if (spheres > 0) {
        const auto start = std::chrono::steady_clock::now();
        b.clump = build_clump(shape, method, spheres, seed, edge_spheres);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        b.quality = evaluate_clump(shape, b.clump);
        b.quality.build_seconds = seconds;
        return b;
    }
    std::fprintf(stderr,
                 "%s: fewest spheres with |volume error| <= %g, surface RMS <= %g Dn and topple error <= %g "
                 "deg (%s)\n",
                 label.c_str(), tol.volume, tol.surface_rms, tol.topple_deg, method_name(method).c_str());
    ToleranceSearch search = fewest_spheres(shape, method, tol, max_spheres, seed,
                                            [&](const ClumpQuality &q) { print_progress(label, q); });
    if (!search.met)
        throw InputError("--tol-volume/--tol-surface/--tol-topple: " + number(tol.volume) + " / " +
                         number(tol.surface_rms) + " / " + number(tol.topple_deg) +
                         " deg cannot be met with at most " + std::to_string(max_spheres) +
                         " spheres (best: volume " + "error " + number(search.quality.volume_error) +
                         ", surface RMS " + number(search.quality.surface_rms) + " Dn, topple error " +
                         number(search.quality.topple_error_deg) + " deg at N=" +
                         std::to_string(search.quality.spheres) + "); raise --max-spheres or the tolerances");
    b.clump = std::move(search.clump);
    b.quality = search.quality;
    json tried = json::array();
    for (const auto &q : search.tried)
        tried.push_back(quality_json(q));
    b.tolerance = {{"volume", tol.volume},
                   {"surface_rms", tol.surface_rms},
                   {"topple_deg", tol.topple_deg},
                   {"max_spheres", max_spheres},
                   {"met", true},
                   {"tried", tried}};
    return b;
}

} // namespace

int run_clump(const ClumpRequest &r) {
    // Everything the user typed is checked before any work or any file.
    const ClumpMethod method = parse_method(r.method);
    if (r.fixed_count && r.spheres < 1)
        throw InputError("--spheres: the number of spheres must be >= 1 (got " + std::to_string(r.spheres) +
                         ")");
    if (!r.fixed_count)
        check_tolerances({r.tol_volume, r.tol_surface, r.tol_topple});
    if (r.max_spheres < 1)
        throw InputError("--max-spheres: must be >= 1 (got " + std::to_string(r.max_spheres) + ")");
    const Shape shape = make_requested_shape(r);
    OutputFolder out(r.out, "armour clump", OutputFolder::Mode::staged);
    const Built b = build_requested(shape, method, r.fixed_count ? r.spheres : 0,
                                    {r.tol_volume, r.tol_surface, r.tol_topple}, r.max_spheres, r.seed,
                                    shape.kind, r.edge_spheres);
    out.open();
    json summary = write_clump_files([&](const std::string &name) { return out.claim(name); }, out.target(),
                                     shape, b.clump, b.quality, r.method, r.seed);
    summary["command"] = "clump";
    summary["edge_spheres"] = r.edge_spheres;
    summary["tolerance"] = b.tolerance;
    write_text_file(out.claim("summary.json"), summary.dump(2) + "\n");
    out.commit();
    std::printf(
        "%s: %d spheres (%s), volume error %+.3f %%, surface RMS %.3f %% Dn, max %.3f %% Dn, "
        "inertia error %.3f %%, rest gap %.3f %% Dn (tips off %d of %d faces), topple error %.2f deg, "
        "built in %.2f s -> %s\n",
        shape.description.c_str(), b.quality.spheres, r.method.c_str(), 100.0 * b.quality.volume_error,
        100.0 * b.quality.surface_rms, 100.0 * b.quality.surface_max, 100.0 * b.quality.inertia_error,
        100.0 * b.quality.rest_gap, b.quality.tipping_faces, b.quality.rest_faces, b.quality.topple_error_deg,
        b.quality.build_seconds, out.target().c_str());
    return 0;
}

int run_demo(const DemoRequest &r) {
    check_tolerances({r.tol_volume, r.tol_surface, r.tol_topple});
    const double density = 2400.0;
    const Shape shapes[] = {make_cube_shape(1.0, 0.0, density),
                            make_dolos_shape(2.0, kDolosWaistDefault, density)};
    OutputFolder out(r.out, "armour demo", OutputFolder::Mode::staged);
    out.open();
    json rows = json::array();
    struct Row {
        std::string unit, method;
        ClumpQuality quality;
    };
    std::vector<Row> table;
    for (const Shape &shape : shapes) {
        // The optimised method picks N; the baseline is measured at the same N.
        const Built best = build_requested(shape, ClumpMethod::optimised, 0,
                                           {r.tol_volume, r.tol_surface, r.tol_topple}, 200, 1, shape.kind);
        const Built base = build_requested(shape, ClumpMethod::greedy, best.quality.spheres, {}, 0, 1, "");
        const std::filesystem::path dir = out.claim(shape.kind);
        std::filesystem::create_directory(dir);
        json s =
            write_clump_files([&](const std::string &name) { return dir / name; }, out.target() / shape.kind,
                              shape, best.clump, best.quality, "optimised", 1);
        s["tolerance"] = best.tolerance;
        write_text_file(dir / "summary.json", s.dump(2) + "\n");
        for (const auto &[method, built] : {std::pair<std::string, const Built &>{"optimised", best},
                                            std::pair<std::string, const Built &>{"greedy", base}}) {
            json row = quality_json(built.quality);
            row["shape"] = shape.kind;
            row["description"] = shape.description;
            row["method"] = method;
            row["Dn"] = built.quality.Dn;
            row["volume_exact"] = built.quality.volume_exact;
            rows.push_back(row);
            table.push_back({shape.kind, method, built.quality});
        }
    }
    json summary = {
        {"command", "demo"},
        {"tolerance",
         {{"volume", r.tol_volume}, {"surface_rms", r.tol_surface}, {"topple_deg", r.tol_topple}}},
        {"units",
         {{"errors", "fractions; surface and centroid as fractions of Dn"},
          {"build_seconds", "s"},
          {"Dn", "m"},
          {"volume_exact", "m^3"}}},
        {"rows", rows}};
    write_text_file(out.claim("summary.json"), summary.dump(2) + "\n");
    out.commit();

    std::printf("\nClump error table (errors in %%; surface, centroid and rest gap in %% of Dn)\n");
    std::printf("%-6s %-10s %5s %10s %10s %10s %10s %10s %10s %9s\n", "unit", "method", "N", "volume",
                "surf.RMS", "surf.max", "inertia", "centroid", "rest gap", "build[s]");
    for (const Row &row : table) {
        const ClumpQuality &q = row.quality;
        std::printf("%-6s %-10s %5d %+10.3f %10.3f %10.3f %10.3f %10.4f %10.3f %9.2f\n", row.unit.c_str(),
                    row.method.c_str(), q.spheres, 100.0 * q.volume_error, 100.0 * q.surface_rms,
                    100.0 * q.surface_max, 100.0 * q.inertia_error, 100.0 * q.centroid_offset,
                    100.0 * q.rest_gap, q.build_seconds);
    }
    std::printf(
        "\nFiles: %s (per unit: clump.spheres, template.liggghts, shape.stl, clump.stl, summary.json)\n",
        out.target().c_str());
    return 0;
}

} // namespace armour
