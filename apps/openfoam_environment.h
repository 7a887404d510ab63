// Is OpenFOAM where its tools will look for it?
//
// Description
//     OpenFOAM's tools (blockMesh first) find their etc/ files through
//     WM_PROJECT_DIR (Debian's OpenFOAM v1912: /usr/share/openfoam, which a
//     coupled run sets when it is unset). A wrong one is found here, before
//     the output folder is touched, as one InputError naming the variable;
//     found later, it would stop blockMesh with OpenFOAM's own message (which
//     does not name it) and leave a half-written folder.
//
// Usage
//     check_openfoam_project_dir(); // throws InputError
#pragma once

#include <filesystem>

namespace armour {

// The folder OpenFOAM's tools will use as WM_PROJECT_DIR.
std::filesystem::path openfoam_project_dir();

// Throws InputError when that folder is not an OpenFOAM installation.
void check_openfoam_project_dir();

} // namespace armour
