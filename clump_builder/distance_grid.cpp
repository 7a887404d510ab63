#include "distance_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace armour {

namespace {
double distance_to(const Eigen::Vector3d &p, const std::array<Eigen::Vector3d, 3> &t) {
    return (p - closest_point_on_triangle(p, t[0], t[1], t[2])).norm();
}
} // namespace

DistanceGrid::DistanceGrid(const TriangleMesh &mesh, double pad, int cells_per_axis) {
    if (mesh.triangles.empty())
        throw std::invalid_argument("DistanceGrid: empty mesh");
    if (!(pad >= 0.0) || cells_per_axis < 1)
        throw std::invalid_argument("DistanceGrid: pad must be >= 0 and cells_per_axis >= 1");
    lower_ = Eigen::Vector3d::Constant(HUGE_VAL);
    upper_ = Eigen::Vector3d::Constant(-HUGE_VAL);
    for (const Eigen::Vector3d &v : mesh.vertices) {
        lower_ = lower_.cwiseMin(v);
        upper_ = upper_.cwiseMax(v);
    }
    lower_.array() -= pad;
    upper_.array() += pad;
    const Eigen::Vector3d extent = upper_ - lower_;
    // Near-cubic grid cells: the longest axis gets cells_per_axis of them.
    const double h = extent.maxCoeff() / cells_per_axis;
    for (int a = 0; a < 3; ++a) {
        n_[a] = std::max(1, static_cast<int>(std::ceil(extent[a] / h - 1e-9)));
        cell_[a] = extent[a] / n_[a];
    }
    for (const auto &t : mesh.triangles)
        triangles_.push_back({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});

    const double r = 0.5 * cell_.norm();
    const int cells = n_[0] * n_[1] * n_[2];
    first_.reserve(cells + 1);
    first_.push_back(0);
    std::vector<double> d(triangles_.size());
    for (int k = 0; k < n_[2]; ++k)
        for (int j = 0; j < n_[1]; ++j)
            for (int i = 0; i < n_[0]; ++i) {
                const Eigen::Vector3d c =
                    lower_ + cell_.cwiseProduct(Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5));
                double nearest = HUGE_VAL;
                for (std::size_t t = 0; t < triangles_.size(); ++t) {
                    d[t] = distance_to(c, triangles_[t]);
                    nearest = std::min(nearest, d[t]);
                }
                for (std::size_t t = 0; t < triangles_.size(); ++t)
                    if (d[t] <= nearest + 2.0 * r)
                        candidates_.push_back(static_cast<int>(t));
                first_.push_back(static_cast<int>(candidates_.size()));
            }
}

bool DistanceGrid::covers(const Eigen::Vector3d &p) const {
    return (p.array() >= lower_.array()).all() && (p.array() <= upper_.array()).all();
}

double DistanceGrid::distance(const Eigen::Vector3d &p) const {
    std::array<int, 3> ijk{};
    for (int a = 0; a < 3; ++a)
        ijk[a] = std::clamp(static_cast<int>((p[a] - lower_[a]) / cell_[a]), 0, n_[a] - 1);
    const int c = ijk[0] + n_[0] * (ijk[1] + n_[1] * ijk[2]);
    double best = HUGE_VAL;
    for (int m = first_[c]; m < first_[c + 1]; ++m)
        best = std::min(best, distance_to(p, triangles_[candidates_[m]]));
    return best;
}

double DistanceGrid::mean_candidates() const {
    return static_cast<double>(candidates_.size()) / static_cast<double>(first_.size() - 1);
}

} // namespace armour
