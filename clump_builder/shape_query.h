// Fast point queries against an exact closed mesh (CGAL AABB tree inside).
#pragma once

#include "mesh.h"

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace armour {

class ShapeQuery {
  public:
    explicit ShapeQuery(const TriangleMesh &mesh);
    ~ShapeQuery();
    ShapeQuery(const ShapeQuery &) = delete;
    ShapeQuery &operator=(const ShapeQuery &) = delete;

    bool inside(const Eigen::Vector3d &p) const;
    double distance(const Eigen::Vector3d &p) const;        // unsigned, m
    double signed_distance(const Eigen::Vector3d &p) const; // negative inside, m
    Eigen::Vector3d lower() const;                          // bounding box, m
    Eigen::Vector3d upper() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace armour
