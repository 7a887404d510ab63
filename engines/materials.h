// Contact materials: the checks and the pair rule every engine shares.
#pragma once

#include "rigid_body_engine.h"

namespace armour {

// Throws InputError "material 'NAME': key rule" (or "material pair 'A'/'B': ...").
void check_materials(const EngineSettings &settings);

// The value of a contact property between materials a and b (indices into
// settings.materials): a MaterialPair override if one sets it, else the
// smaller of the two materials' values, so a slippery or dead material
// dominates the pair, as a coastal engineer expects.
double pair_value(const EngineSettings &settings, int a, int b, double Material::*field,
                  double MaterialPair::*override_field);

} // namespace armour
