// Plain geometry types shared by every part of armour-fsi.
//
// Description
//     A closed triangle mesh in SI units (metres). Triangles are vertex index
//     triples ordered counter-clockwise when seen from outside, so every face
//     normal points out of the solid. No CGAL type appears here: CGAL stays
//     inside a few .cpp files to keep the build short.
#pragma once

#include "input_error.h" // what its readers throw

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace armour {

struct TriangleMesh {
    std::vector<Eigen::Vector3d> vertices;     // m
    std::vector<std::array<int, 3>> triangles; // outward (counter-clockwise)
};

// Signed volume enclosed by the mesh (m^3); positive for an outward mesh.
double signed_volume(const TriangleMesh &mesh);

// Total surface area (m^2).
double surface_area(const TriangleMesh &mesh);

// Area-weighted uniform random points on the surface, deterministic for a seed.
// Outward unit normals are returned when `normals` is not null.
std::vector<Eigen::Vector3d> sample_surface(const TriangleMesh &mesh, int count, std::uint64_t seed,
                                            std::vector<Eigen::Vector3d> *normals = nullptr);

// The point of triangle abc nearest to p (m).
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d &p, const Eigen::Vector3d &a,
                                          const Eigen::Vector3d &b, const Eigen::Vector3d &c);

// The mesh moved by `offset` (m).
TriangleMesh translated(const TriangleMesh &mesh, const Eigen::Vector3d &offset);

// The half extents (m) when the mesh is a box centred at the origin with its
// faces normal to the axes (cubes and boxes in their unit frame), otherwise
// empty. Such a box has an exact closed-form signed distance, much cheaper
// than a query against its triangles.
std::optional<Eigen::Vector3d> axis_aligned_box_half_extents(const TriangleMesh &mesh);

// Exact signed distance (m, negative inside) from p to the box [-half, half].
double box_signed_distance(const Eigen::Vector3d &p, const Eigen::Vector3d &half);

// The part of a closed outward mesh on the side of a plane opposite its
// normal `up` (below a water surface): volume (m^3) and centroid (m). Exact
// for a closed mesh: the cut face lies in the plane, so about a point of the
// plane it adds no volume. An empty part has volume 0 and centroid `point`.
struct PartBelowPlane {
    double volume = 0.0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
};
PartBelowPlane part_below_plane(const TriangleMesh &mesh, const Eigen::Vector3d &point,
                                const Eigen::Vector3d &up);

// The part of a surface inside the box [lo, hi] (m): each triangle clipped to
// the box and fanned, orientation kept; triangles outside dropped. Vertices
// are not shared between triangles.
TriangleMesh clipped_to_box(const TriangleMesh &mesh, const Eigen::Vector3d &lo, const Eigen::Vector3d &hi);

} // namespace armour
