// STL files (ASCII and binary) <-> TriangleMesh.
//
// Description
//     STL stores loose triangles; read_stl merges vertices with identical
//     coordinates so that topology checks (closed, manifold) can be made.
//     Coordinates are taken as metres. Errors throw InputError naming the file.
#pragma once

#include "mesh.h"

#include <string>

namespace armour {

TriangleMesh read_stl(const std::string &path);

// Writes through a temporary file and a rename, so no half-written file remains.
void write_stl(const TriangleMesh &mesh, const std::string &path, bool binary = true,
               const std::string &solid_name = "armour");

} // namespace armour
