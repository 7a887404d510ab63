#include "flume_mesh.h"

#include "scene_keys.h"
#include "scene_setup.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace armour {

namespace {

// One blockMesh grading section: `cells` cells over `length` m, the last
// cell `ratio` times the first (blockMesh's expansion ratio).
struct Section {
    double length;
    int cells;
    double ratio;
};

// Length of n cells outward from the box: h min(r^k, coarsen), k = 1..n.
double outward_length(int n, double r, double h, double coarsen) {
    double length = 0.0, size = h;
    for (int k = 1; k <= n; ++k)
        length += std::min(size *= r, coarsen * h);
    return length;
}

// The fewest cells that fill `length` growing outward from h at a rate r in
// [1, kMaxCellGrowth], capped at coarsen x h; 0 when the stretch is too short
// for that (filling it would need cells smaller than h: the box takes it).
int outward_cells(double length, double h, double coarsen) {
    int n = 1;
    while (outward_length(n, kMaxCellGrowth, h, coarsen) < length)
        ++n;
    return outward_length(n, 1.0, h, coarsen) <= length ? n : 0;
}

// The sections from the box's edge outward over `length`, in n cells: the
// cells grow from h at the rate r that fills it exactly, to coarsen x h,
// then stay there.
std::vector<Section> outward(double length, double h, double coarsen, int n) {
    double slow = 1.0, fast = kMaxCellGrowth; // outward_length grows with r
    for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (slow + fast);
        (outward_length(n, mid, h, coarsen) < length ? slow : fast) = mid;
    }
    const double r = 0.5 * (slow + fast);
    int growing = 0; // cells below coarsen x h
    for (double size = h * r; growing < n && size < coarsen * h; size *= r)
        ++growing;
    std::vector<Section> sections;
    if (growing > 0)
        sections.push_back({outward_length(growing, r, h, coarsen), growing, std::pow(r, growing - 1)});
    if (growing < n)
        sections.push_back({(n - growing) * coarsen * h, n - growing, 1.0});
    // The bisection leaves ~1e-16 of the length: the last section takes it.
    double sum = 0.0;
    for (const Section &s : sections)
        sum += s.length;
    sections.back().length += length - sum;
    return sections;
}

std::string fraction_text(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.12g", v);
    return buf;
}

MeshAxis axis_of(double lo, double hi, int fine_cells, double a, double b, double coarsen) {
    const double h = (hi - lo) / fine_cells;
    // An axis not coarsened is uniform, exactly `fine_cells`; a stretch too
    // short to grow in (or under a cell) goes to the box: no cells below h.
    const int below = coarsen > 1.0 && a - lo >= h ? outward_cells(a - lo, h, coarsen) : 0;
    const int above = coarsen > 1.0 && hi - b >= h ? outward_cells(hi - b, h, coarsen) : 0;
    if (below == 0)
        a = lo;
    if (above == 0)
        b = hi;
    std::vector<Section> sections;
    if (below > 0) // toward lo: reversed, the cells shrinking to the box
        for (const Section &s : outward(a - lo, h, coarsen, below))
            sections.insert(sections.begin(), {s.length, s.cells, 1.0 / s.ratio});
    // Whole cells no larger than h (a box of exactly `fine_cells` x h: those).
    sections.push_back({b - a, std::max(1, static_cast<int>(std::ceil((b - a) / h * (1.0 - 1e-12)))), 1.0});
    if (above > 0)
        for (const Section &s : outward(hi - b, h, coarsen, above))
            sections.push_back(s);

    MeshAxis axis;
    for (const Section &s : sections)
        axis.cells += s.cells;
    axis.nodes.push_back(lo);
    double at = lo;
    for (const Section &s : sections) {
        // blockMesh's spacing: sizes in geometric progression r = ratio^(1/(n-1)).
        const double r = s.cells > 1 ? std::pow(s.ratio, 1.0 / (s.cells - 1)) : 1.0;
        const double first = std::abs(r - 1.0) < 1e-12 ? s.length / s.cells
                                                       : s.length * (r - 1.0) / (std::pow(r, s.cells) - 1.0);
        for (int k = 0; k < s.cells; ++k)
            axis.nodes.push_back(at += first * std::pow(r, k));
        at = axis.nodes.back();
    }
    axis.nodes.back() = hi;
    if (sections.size() > 1) {
        axis.grading = "(";
        for (const Section &s : sections)
            axis.grading += "(" + fraction_text(s.length / (hi - lo)) + " " +
                            fraction_text(static_cast<double>(s.cells) / axis.cells) + " " +
                            fraction_text(s.ratio) + ")";
        axis.grading += ")";
    }
    return axis;
}

} // namespace

double MeshAxis::smallest_cell() const {
    double d = nodes.back() - nodes.front();
    for (std::size_t i = 1; i < nodes.size(); ++i)
        d = std::min(d, nodes[i] - nodes[i - 1]);
    return d;
}

double MeshAxis::largest_cell() const {
    double d = 0.0;
    for (std::size_t i = 1; i < nodes.size(); ++i)
        d = std::max(d, nodes[i] - nodes[i - 1]);
    return d;
}

double MeshAxis::column_centre(double at) const {
    const auto upper = std::upper_bound(nodes.begin() + 1, nodes.end() - 1, at);
    return 0.5 * (*(upper - 1) + *upper);
}

int refine_levels(const Scene &scene) {
    if (!scene.fluid || scene.fluid->mesh != "refined")
        return 0;
    int levels = 0;
    for (const SceneRefine &r : scene.refine)
        levels = std::max(levels, r.level);
    return levels;
}

std::string mesh_layout(const Scene &scene) {
    const FlumeMesh mesh = flume_mesh(scene);
    std::string text = std::to_string(mesh.axes[0].cells) + " x " + std::to_string(mesh.axes[1].cells) +
                       " x " + std::to_string(mesh.axes[2].cells) +
                       (mesh.graded ? " graded block" : " block");
    const int levels = refine_levels(scene);
    if (levels == 0)
        return text;
    const std::size_t regions = scene.refine.size();
    return text + ", cells halved in x and y " +
           (levels > 1 ? "up to " + std::to_string(levels) + " times " : "") + "in " +
           std::to_string(regions) + " [[refine]] region" + (regions > 1 ? "s" : "");
}

Eigen::Vector3d fine_cell_size(const Scene &scene) {
    return scene.fluid->fine_cell(scene.domain_max - scene.domain_min);
}

FlumeMesh flume_mesh(const Scene &scene) {
    const SceneFluid &f = *scene.fluid;
    FlumeMesh mesh;
    const bool box = f.refine_min.has_value();
    const int levels = refine_levels(scene);
    for (int i = 0; i < 3; ++i) {
        const double lo = scene.domain_min[i], hi = scene.domain_max[i];
        const double a = box ? (*f.refine_min)[i] : lo, b = box ? (*f.refine_max)[i] : hi;
        // A refined mesh's block: 2^L times the fine cells in x and y (mesh_refinement.h).
        const int cells = i < 2 ? f.cells[i] >> levels : f.cells[i];
        const double h = (hi - lo) / cells;
        const double coarsen = box ? std::max(1.0, f.coarse_cell_size[i] / h) : 1.0;
        mesh.axes[i] = axis_of(lo, hi, cells, a, b, coarsen);
        mesh.graded = mesh.graded || mesh.axes[i].grading != "1";
    }
    return mesh;
}

void check_flume_grading(const Scene &scene, const SceneSetup &setup, const std::string &template_text) {
    const SceneFluid &f = *scene.fluid;
    const bool fixed = template_text.find("@GRADING@") == std::string::npos;
    if (refine_levels(scene) > 0 && fixed)
        throw InputError(scene.file + ": key 'fluid.mesh': fluid.case \"" + f.case_name +
                         "\" has a fixed block structure; a refined mesh needs fluid.case \"wave_flume\"");
    if (!f.refine_min)
        return;
    if (fixed)
        throw InputError(scene.file + ": key 'fluid.refine_min': fluid.case \"" + f.case_name +
                         "\" has a fixed block structure; a graded mesh needs fluid.case \"wave_flume\"");
    // A unit resting on a side wall or the slope reaches into it by its contact
    // overlap: up to half a fine cell, as the mesh box's own check allows.
    const Eigen::Vector3d fine = fine_cell_size(scene);
    // Units placed for a settle may stand above it (scene_setup.h).
    const Eigen::Vector3d lo = *f.refine_min - 0.5 * fine,
                          hi = *f.refine_max + 0.5 * fine +
                               Eigen::Vector3d(0.0, 0.0, settle_headroom(scene, setup));
    for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
        const BodyInit &b = setup.bodies[i];
        for (const auto &v : setup.units[b.unit].mesh.vertices) {
            const Eigen::Vector3d p = b.pose.position + b.pose.orientation * v;
            if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any())
                throw InputError(scene.file + ": key '" +
                                 ((p.array() < lo.array()).any() ? "fluid.refine_min" : "fluid.refine_max") +
                                 "': body " + std::to_string(i) + " (unit '" + setup.units[b.unit].name +
                                 "') starts outside the refined box " + vector_text(*f.refine_min) + " .. " +
                                 vector_text(*f.refine_max) + " m (vertex " + vector_text(p) +
                                 " m): the loads need the fine cells; widen the box");
        }
    }
}

} // namespace armour
