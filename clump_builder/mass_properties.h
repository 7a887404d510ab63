// Exact mass properties of a closed triangle mesh.
//
// Description
//     Volume, centroid and inertia tensor of a homogeneous solid bounded by a
//     closed, outward-oriented triangle mesh, integrated exactly (divergence
//     theorem over the mesh's tetrahedra; no sampling). SI units throughout.
#pragma once

#include "mesh.h"

#include <Eigen/Core>

namespace armour {

struct MassProperties {
    double density = 0.0;                                         // kg/m^3
    double volume = 0.0;                                          // m^3
    double mass = 0.0;                                            // kg
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();           // m, mesh frame
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();            // kg m^2, about the centroid, mesh axes
    Eigen::Vector3d principal_moments = Eigen::Vector3d::Zero();  // kg m^2, ascending
    Eigen::Matrix3d principal_axes = Eigen::Matrix3d::Identity(); // columns, right-handed
};

// Mass properties of the solid bounded by `mesh` at `density` (kg/m^3).
MassProperties mass_properties(const TriangleMesh &mesh, double density);

// Fills principal_moments and principal_axes from `inertia`.
void set_principal(MassProperties &props);

} // namespace armour
