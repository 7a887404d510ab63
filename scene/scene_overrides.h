// The --set overrides of a scene file: one KEY=VALUE applied to the parsed
// TOML before the scene is read, the key found in the key table
// (scene_keys.h) and its value read as that key's type. Internal to scene/
// (scene_read.cpp); users write them as docs/scenes.md, "Overrides: --set", says.
#pragma once

#include <toml++/toml.h>

#include <string>
#include <vector>

namespace armour::scene_detail {

// The names the top level of a scene may hold: its own keys and the sections.
std::vector<std::string> top_level_names();

// Applies one --set KEY=VALUE to the parsed file; throws InputError naming
// the override and what is wrong with it.
void apply_override(toml::table &root, const std::string &text);

} // namespace armour::scene_detail
