#include "shapes.h"

#include "mesh_check.h"
#include "stl_io.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace armour {

namespace {

std::string number(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

std::string fixed2(double value) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", value);
    return buf;
}

// `ok` is written so that NaN fails it; infinities are rejected separately.
void require(bool ok, double value, const std::string &option, const std::string &rule) {
    if (!ok || !std::isfinite(value))
        throw InputError(option + ": " + rule + " (got " + number(value) + ")");
}

void require_density(double density) {
    require(density > 0.0, density, "--density", "density must be > 0 kg/m^3");
}

// The unit frame has its origin at the exact centroid; the reference axes are
// kept so that the user's orientation of the unit survives.
Shape finish(std::string kind, std::string description, const TriangleMesh &mesh, double density,
             const std::vector<TriangleMesh> &parts = {}) {
    Shape shape;
    shape.kind = std::move(kind);
    shape.description = std::move(description);
    const MassProperties raw = mass_properties(mesh, density);
    shape.mesh = translated(mesh, -raw.centroid);
    for (const auto &part : parts) // moved with the union, so they stay its exact pieces
        shape.convex_parts.push_back(translated(part, -raw.centroid));
    shape.props = mass_properties(shape.mesh, density);
    return shape;
}

} // namespace

double Shape::Dn() const {
    return std::cbrt(props.volume);
}

Shape make_cube_shape(double edge, double chamfer, double density) {
    require(edge > 0.0, edge, "--size", "cube edge must be > 0 m");
    require(chamfer >= 0.0 && chamfer < 0.5 * edge, chamfer, "--chamfer",
            "chamfer must be in [0, edge/2) = [0, " + number(0.5 * edge) + ") m");
    require_density(density);
    const TriangleMesh mesh = make_cube_mesh(edge, chamfer);
    return finish("cube", "cube a=" + number(edge) + " m chamfer=" + number(chamfer) + " m", mesh, density,
                  {mesh});
}

Shape make_dolos_shape(double height, double waist_ratio, double density) {
    require(height > 0.0, height, "--height", "dolos height must be > 0 m");
    require(waist_ratio >= kDolosWaistMin && waist_ratio <= kDolosWaistMax, waist_ratio, "--waist",
            "dolos waist ratio must be in [" + fixed2(kDolosWaistMin) + ", " + fixed2(kDolosWaistMax) + "]");
    require_density(density);
    return finish("dolos", "dolos H=" + number(height) + " m r=" + number(waist_ratio),
                  make_dolos_mesh(height, waist_ratio), density, make_dolos_parts(height, waist_ratio));
}

Shape make_stl_shape(const std::string &path, double density) {
    require_density(density);
    const TriangleMesh mesh = read_stl(path);
    validate_mesh(mesh, path);
    return finish("stl", "stl " + path, mesh, density);
}

} // namespace armour
