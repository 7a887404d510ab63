// Validation of user meshes before anything is built on them.
//
// Description
//     Checks that a mesh bounds a solid: closed, edge- and vertex-manifold,
//     consistently and outwardly oriented, free of self-intersections and of
//     non-zero volume. The first failed check throws InputError with one line
//     "<name>: <what is wrong>".
#pragma once

#include "mesh.h"

#include <string>

namespace armour {

void validate_mesh(const TriangleMesh &mesh, const std::string &name);

} // namespace armour
