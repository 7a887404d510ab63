// A resolved scene's text as keys only.
//
// Description
//     resolved_scene_toml (scene.h) heads its text with a comment naming the
//     file the scene was read from. What a run is compared by (a resume's
//     check, a sweep case's hash) must not depend on where that file lay, so
//     both take the text without its comment lines.
//
// Usage
//     const std::string keys = scene_keys_text(resolved_scene_toml(scene));
#pragma once

#include <string>

namespace armour {

std::string scene_keys_text(const std::string &resolved_toml);

} // namespace armour
