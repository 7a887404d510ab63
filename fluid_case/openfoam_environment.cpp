#include "openfoam_environment.h"

#include "input_error.h"

#include <cstdlib>
#include <string>

namespace armour {

namespace fs = std::filesystem;

namespace {
const char *const kDebianProjectDir = "/usr/share/openfoam";
} // namespace

fs::path openfoam_project_dir() {
    const char *set = std::getenv("WM_PROJECT_DIR");
    return set && *set ? fs::path(set) : fs::path(kDebianProjectDir);
}

void check_openfoam_project_dir() {
    const char *set = std::getenv("WM_PROJECT_DIR");
    const fs::path dir = openfoam_project_dir();
    // Every OpenFOAM tool reads WM_PROJECT_DIR/etc/controlDict first.
    if (fs::is_regular_file(dir / "etc" / "controlDict"))
        return;
    if (set && *set)
        throw InputError("WM_PROJECT_DIR: " + dir.string() +
                         ": not an OpenFOAM installation (no etc/controlDict); unset it to use " +
                         kDebianProjectDir + " (Debian's OpenFOAM v1912) or point it at OpenFOAM v1912");
    throw InputError(std::string("WM_PROJECT_DIR: unset, and ") + kDebianProjectDir +
                     "/etc/controlDict is missing: install OpenFOAM v1912 (Debian: openfoam) or set "
                     "WM_PROJECT_DIR to its folder");
}

void use_debian_openfoam() {
    ::setenv("WM_PROJECT_DIR", kDebianProjectDir, 0);
}

std::vector<std::string> keep_solver_memory() {
    const char *choice = std::getenv("ARMOUR_SOLVER_MALLOC");
    if (choice && std::string(choice) == "glibc")
        return {};
    const char *threshold = std::getenv("MALLOC_MMAP_THRESHOLD_"),
               *trim = std::getenv("MALLOC_TRIM_THRESHOLD_");
    if (!threshold && !trim) {
        ::setenv("MALLOC_MMAP_THRESHOLD_", "4294967296", 0); // bytes
        ::setenv("MALLOC_TRIM_THRESHOLD_", "4294967296", 0);
    }
    std::vector<std::string> names;
    for (const char *name : {"MALLOC_MMAP_THRESHOLD_", "MALLOC_TRIM_THRESHOLD_"})
        if (std::getenv(name))
            names.emplace_back(name);
    return names;
}

} // namespace armour
