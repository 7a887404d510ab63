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
//     keep_solver_memory(): interFoam's step allocates and frees face fields
//     of tens of MB; glibc hands blocks above its mmap threshold (adapted up
//     to 32 MB) to the kernel when freed, and mapping them again page by page
//     took ~13 % of a serial step of the stability scene at Dn/4
//     (docs/openfoam.md, "The solver's memory"). The solvers armour starts
//     keep them in the heap: glibc's own MALLOC_MMAP_THRESHOLD_ and
//     MALLOC_TRIM_THRESHOLD_ set to 4 GiB, unless the user set either;
//     ARMOUR_SOLVER_MALLOC=glibc leaves glibc's defaults (to compare).
//
// Usage
//     check_openfoam_project_dir(); // throws InputError
//     for (const auto &name : keep_solver_memory()) { /* mpirun -x name */ }
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace armour {

// The folder OpenFOAM's tools will use as WM_PROJECT_DIR.
std::filesystem::path openfoam_project_dir();

// Throws InputError when that folder is not an OpenFOAM installation.
void check_openfoam_project_dir();

// Sets WM_PROJECT_DIR to Debian's OpenFOAM when unset: Debian's tools find
// their etc/ files only through it.
void use_debian_openfoam();

// Sets the allocator's variables in this process's environment (children
// inherit them); returns the names set there, for mpirun's -x.
std::vector<std::string> keep_solver_memory();

} // namespace armour
