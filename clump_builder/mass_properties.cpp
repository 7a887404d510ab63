#include "mass_properties.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace armour {

// Each outward triangle (a, b, c) and the origin span a signed tetrahedron;
// summed, the signed tetrahedra cover the solid exactly once (divergence
// theorem). For the tetrahedron x = A u with A = [a b c] and u in the canonical
// tetrahedron {u >= 0, u1 + u2 + u3 <= 1} (volume 1/6):
//     int u_i du        = 1/24
//     int u_i u_j du    = (1 + delta_ij) / 120
// so, with V = det(A) / 6 and s = a + b + c,
//     int x dV     = V s / 4
//     int x x^T dV = A (int u u^T du) A^T * 6V = V / 20 (a a^T + b b^T + c c^T + s s^T).
MassProperties mass_properties(const TriangleMesh &mesh, double density) {
    MassProperties props;
    props.density = density;
    if (mesh.vertices.empty())
        return props;

    // Integrating about a point near the solid, not the world origin, keeps the
    // large terms of far-away meshes from cancelling in the parallel-axis shift.
    Eigen::Vector3d ref = Eigen::Vector3d::Zero();
    for (const auto &v : mesh.vertices)
        ref += v;
    ref /= static_cast<double>(mesh.vertices.size());

    double six_volume = 0.0;
    Eigen::Vector3d first = Eigen::Vector3d::Zero();  // 24 * int x dV
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero(); // 120 * int x x^T dV
    for (const auto &t : mesh.triangles) {
        const Eigen::Vector3d a = mesh.vertices[t[0]] - ref;
        const Eigen::Vector3d b = mesh.vertices[t[1]] - ref;
        const Eigen::Vector3d c = mesh.vertices[t[2]] - ref;
        const double det = a.dot(b.cross(c));
        const Eigen::Vector3d s = a + b + c;
        six_volume += det;
        first += det * s;
        second += det * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
    }
    const double volume = six_volume / 6.0;
    props.volume = volume;
    props.mass = density * volume;
    if (volume == 0.0)
        return props;

    const Eigen::Vector3d offset = first / (24.0 * volume);
    props.centroid = ref + offset;
    // Covariance about the centroid, then I = tr(C) 1 - C.
    Eigen::Matrix3d cov = second / 120.0 - volume * offset * offset.transpose();
    cov = 0.5 * (cov + cov.transpose());
    props.inertia = density * (cov.trace() * Eigen::Matrix3d::Identity() - cov);
    set_principal(props);
    return props;
}

void set_principal(MassProperties &props) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(props.inertia);
    props.principal_moments = solver.eigenvalues(); // Eigen sorts them ascending
    props.principal_axes = solver.eigenvectors();
    if (props.principal_axes.determinant() < 0.0)
        props.principal_axes.col(2) = -props.principal_axes.col(2);
}

} // namespace armour
