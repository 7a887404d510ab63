// The fluid's turbulence closure and its porous regions, written into a case
// copied from a template (docs/turbulence.md, docs/porous.md).
//
// Description
//     fluid.turbulence = "kOmegaSST" replaces the template's laminar
//     constant/turbulenceProperties with OpenFOAM's RAS kOmegaSST and writes
//     0/k.orig, 0/omega.orig and 0/nut.orig (wall functions on every patch of
//     type wall, inletOutlet elsewhere, the constraint types of
//     caseDicts/setConstraintTypes), with the schemes and solvers they need
//     appended to system/fvSchemes and system/fvSolution (OpenFOAM merges a
//     repeated dictionary). k and omega start from the scene's intensity and
//     length scale (turbulence_start).
//
//     Each [[porous]] region becomes the cellZone porous_NAME (the cells whose
//     centre lies in its box, or in its layer under a slope wall's face and
//     crest: system/topoSetDict.porous) and an explicitPorositySource with
//     OpenFOAM's DarcyForchheimer model appended to constant/fvOptions, its d
//     and f from van Gent (1995) (darcy_forchheimer). When the template cuts
//     cells out of the mesh (its system/topoSetDict makes the cellSet "fluid"
//     for subsetMesh), the porous cells join "fluid": the rock under a slope
//     stays in the mesh, permeable, and the rest stays cut out.
//
// Usage
//     write_fluid_models(scene, case_dir);   // after the template's tokens are filled
//     blockMesh; topoSet (the template's, if any);
//     if (needs_porous_zones(scene)) topoSet -dict system/topoSetDict.porous
//     subsetMesh -overwrite fluid -patch walls (if the template cuts cells)
//     add_fluid_models_summary(scene, summary);
#pragma once

#include "scene.h"

#include <filesystem>
#include <nlohmann/json.hpp>

namespace armour {

// van Gent (1995), steady flow (KC -> infinity): the hydraulic gradient
// i = a u + b u|u| of the filter (Darcy) velocity u, and OpenFOAM's
// DarcyForchheimer source -(mu d + rho |u| f / 2) u that gives the same
// pressure gradient rho g i: d = g a / nu, f = 2 g b.
struct DarcyForchheimer {
    double a = 0.0; // s/m, at the water's viscosity
    double b = 0.0; // s^2/m^2
    double d = 0.0; // 1/m^2 = alpha (1 - n)^2 / (n^3 Dn50^2)
    double f = 0.0; // 1/m = 2 beta (1 - n) / (n^3 Dn50)
};
DarcyForchheimer darcy_forchheimer(const ScenePorous &p, double viscosity, double gravity);

// kOmegaSST's k [m^2/s^2], omega [1/s] and nut = k / omega [m^2/s] at the start.
struct TurbulenceStart {
    double k = 0.0, omega = 0.0, nut = 0.0;
};
TurbulenceStart turbulence_start(const Scene &scene);

void write_fluid_models(const Scene &scene, const std::filesystem::path &case_dir);
bool needs_porous_zones(const Scene &scene);
void add_fluid_models_summary(const Scene &scene, nlohmann::json &summary);

} // namespace armour
