// The scene reader's parts (scene_read.cpp, scene_read_flume.cpp): the
// readers of the wave-flume sections and the checks both files use. Internal
// to the scene library: the scene's interface is scene.h.
#pragma once

#include "scene.h"
#include "scene_keys.h"
#include "toml_table.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace armour::scene_read {

using scene_detail::Table;

// The keys min and max of table t: a box inside the run's domain.
void check_box(const Table &t, const Eigen::Vector3d &min, const Eigen::Vector3d &max, const Scene &s);

// Keys that belong to another shape or wall type are mistakes, not noise.
template <class S>
void forbid_other_variants(const Table &t, const std::vector<Key<S>> &keys, const std::string &variant,
                           const std::string &what) {
    std::vector<std::string> own;
    for (const auto &k : keys)
        if (variant == k.when)
            own.push_back(k.name);
    t.forbid_others(scene_detail::names_of(keys, variant.c_str()),
                    what + " " + toml_string(variant) + " (its keys: " + scene_detail::join(own, ", ") + ")");
}

// The wave-flume sections, each after what it depends on (load_scene's order).
void read_fluid(const Table &root, Scene &s);
void read_waves(const Table &root, Scene &s);
void read_porous(const Table &root, Scene &s);
void read_refine(const Table &root, Scene &s);
void read_series(const Table &root, Scene &s);
void check_surface_band(const Table &root, const Scene &s);

} // namespace armour::scene_read
