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

// The sections from the box's edge outward over `length`: the cells grow
// from h at a rate r <= kMaxCellGrowth to coarsen x h, then stay there; n
// is the fewest cells that can fill the length that way, r fills it exactly.
std::vector<Section> outward(double length, double h, double coarsen) {
    if (length <= 0.0)
        return {};
    if (coarsen <= 1.0)
        return {{length, std::max(1, static_cast<int>(std::lround(length / h))), 1.0}};
    int n = 1;
    while (outward_length(n, kMaxCellGrowth, h, coarsen) < length)
        ++n;
    double slow = 0.5, fast = kMaxCellGrowth; // outward_length grows with r
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

std::string vec_text(const Eigen::Vector3d &v) {
    return "[" + number_text(v.x()) + ", " + number_text(v.y()) + ", " + number_text(v.z()) + "]";
}

MeshAxis axis_of(double lo, double hi, int fine_cells, double a, double b, double coarsen) {
    const double h = (hi - lo) / fine_cells;
    // Less than a cell outside the box: the box takes it (no sliver cells).
    if (a - lo < h)
        a = lo;
    if (hi - b < h)
        b = hi;
    std::vector<Section> sections;
    for (const Section &s : outward(a - lo, h, coarsen)) // toward lo: reversed, shrinking to the box
        sections.insert(sections.begin(), {s.length, s.cells, 1.0 / s.ratio});
    sections.push_back({b - a, std::max(1, static_cast<int>(std::lround((b - a) / h))), 1.0});
    for (const Section &s : outward(hi - b, h, coarsen))
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

FlumeMesh flume_mesh(const Scene &scene) {
    const SceneFluid &f = *scene.fluid;
    FlumeMesh mesh;
    mesh.graded = f.refine_min.has_value();
    for (int i = 0; i < 3; ++i) {
        const double lo = scene.domain_min[i], hi = scene.domain_max[i];
        const double a = mesh.graded ? (*f.refine_min)[i] : lo, b = mesh.graded ? (*f.refine_max)[i] : hi;
        const double h = (hi - lo) / f.cells[i];
        mesh.axes[i] =
            axis_of(lo, hi, f.cells[i], a, b, mesh.graded ? std::max(1.0, f.coarse_cell_size[i] / h) : 1.0);
    }
    return mesh;
}

void check_flume_grading(const Scene &scene, const SceneSetup &setup, const std::string &template_text) {
    const SceneFluid &f = *scene.fluid;
    if (!f.refine_min)
        return;
    if (template_text.find("@GRADING@") == std::string::npos)
        throw InputError(scene.file + ": key 'fluid.refine_min': fluid.case \"" + f.case_name +
                         "\" has a fixed block structure; a graded mesh needs fluid.case \"wave_flume\"");
    // A unit resting on a side wall or the slope reaches into it by its contact
    // overlap: up to half a fine cell, as the mesh box's own check allows.
    const Eigen::Vector3d fine = (scene.domain_max - scene.domain_min)
                                     .cwiseQuotient(Eigen::Vector3d(f.cells[0], f.cells[1], f.cells[2]));
    const Eigen::Vector3d lo = *f.refine_min - 0.5 * fine, hi = *f.refine_max + 0.5 * fine;
    for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
        const BodyInit &b = setup.bodies[i];
        for (const auto &v : setup.units[b.unit].mesh.vertices) {
            const Eigen::Vector3d p = b.pose.position + b.pose.orientation * v;
            if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any())
                throw InputError(scene.file + ": key 'fluid.refine_min': body " + std::to_string(i) +
                                 " (unit '" + setup.units[b.unit].name +
                                 "') starts outside the refined box " + vec_text(*f.refine_min) + " .. " +
                                 vec_text(*f.refine_max) + " m (vertex " + vec_text(p) +
                                 " m): the loads need the fine cells; widen the box");
        }
    }
}

} // namespace armour
